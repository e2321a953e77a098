//! Every figure of the paper computes from the library in quick mode, and its data reads back
//! from JSON to the same value; a computation stops when its monitor asks.

use std::sync::atomic::{AtomicU64, Ordering};
use trirhythm::monitor::{CancelFlag, Monitor, Silent};
use trirhythm::theory::averaging::Variant;
use trirhythm::Error;
use trirhythm_paper::*;

const QUICK: FigureOptions = FigureOptions {
    quick: true,
    variant: Variant::Paper,
};

/// Compute `F` in quick mode; its tables are rectangular and not empty, and its JSON text
/// reads back to a value that writes the same JSON.
fn round_trip<F: Figure>() {
    let data = F::compute(&QUICK, &Silent)
        .unwrap_or_else(|e| panic!("figure {} does not compute: {e}", F::NUMBER));
    let tables = data.tables();
    assert!(!tables.is_empty(), "figure {}: no table", F::NUMBER);
    for t in &tables {
        assert!(
            !t.rows.is_empty(),
            "figure {}{}: no rows",
            F::NUMBER,
            t.suffix
        );
        assert!(
            t.rows.iter().all(|r| r.len() == t.columns.len()),
            "figure {}{}: a row with the wrong number of cells",
            F::NUMBER,
            t.suffix
        );
    }
    let value = to_json(&data).unwrap();
    let text = serde_json::to_string(&data).unwrap();
    let back: F = serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("figure {}: its JSON does not read back: {e}", F::NUMBER));
    assert_eq!(
        to_json(&back).unwrap(),
        value,
        "figure {}: the data read back differs",
        F::NUMBER
    );
}

#[test]
fn every_figure_computes_in_quick_mode_and_round_trips_through_json() {
    round_trip::<fig01_phase_recurrence::Fig01>();
    round_trip::<fig02_rhythmicity_planes::Fig02>();
    round_trip::<fig03_restitution_planes::Fig03>();
    round_trip::<fig04_drift::Fig04>();
    round_trip::<fig05_branches::Fig05>();
    round_trip::<fig06_fractional_planes::Fig06>();
    round_trip::<fig07_pseudo_potential::Fig07>();
    round_trip::<fig08_barriers::Fig08>();
    round_trip::<fig09_barrier_surfaces::Fig09>();
    round_trip::<fig10_pbif_lambda_tau::Fig10>();
    round_trip::<fig11_amplitude_lambda::Fig11>();
    round_trip::<fig12_pbif_maps::Fig12>();
    round_trip::<fig13_pdf_restitution::Fig13>();
    round_trip::<fig14_joint_pdf::Fig14>();
    round_trip::<fig15_oscillation_boundaries::Fig15>();
    round_trip::<fig16_oscillation_regions::Fig16>();
    round_trip::<fig17_lle_noise::Fig17>();
    round_trip::<fig18_lle_noise_fractional::Fig18>();
    round_trip::<fig19_critical_noise::Fig19>();
}

#[test]
fn the_registry_holds_the_nineteen_figures_in_order() {
    let numbers: Vec<u32> = registry().iter().map(|e| e.number).collect();
    assert_eq!(numbers, (1..=19).collect::<Vec<_>>());
    assert!(registry().iter().all(|e| !e.title.is_empty()));
    // an entry computes the same value as the typed function
    let typed = fig07_pseudo_potential::Fig07::compute(&QUICK, &Silent).unwrap();
    assert_eq!(
        compute_json(7, &QUICK, &Silent).unwrap(),
        to_json(&typed).unwrap()
    );
    assert!(matches!(
        compute_json(20, &QUICK, &Silent),
        Err(Error::Unknown { .. })
    ));
}

#[test]
fn a_cancelled_monitor_stops_a_monte_carlo_figure() {
    let flag = CancelFlag::default();
    flag.cancel();
    assert!(matches!(
        fig13_pdf_restitution::Fig13::compute(&QUICK, &flag),
        Err(Error::Cancelled)
    ));
    assert!(matches!(
        fig17_lle_noise::Fig17::compute(&QUICK, &flag),
        Err(Error::Cancelled)
    ));
    assert!(matches!(
        compute_json(11, &QUICK, &flag),
        Err(Error::Cancelled)
    ));
}

/// Counts progress reports; cancels after `after` of them.
struct CancelAfter {
    reports: AtomicU64,
    after: u64,
}

impl Monitor for CancelAfter {
    fn progress(&self, _done: u64, _total: u64) {
        self.reports.fetch_add(1, Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.reports.load(Ordering::Relaxed) >= self.after
    }
}

#[test]
fn a_figure_reports_progress_and_stops_midway_when_asked() {
    let monitor = CancelAfter {
        reports: AtomicU64::new(0),
        after: 2,
    };
    assert!(matches!(
        fig05_branches::Fig05::compute(&QUICK, &monitor),
        Err(Error::Cancelled)
    ));
    assert_eq!(monitor.reports.load(Ordering::Relaxed), 2);
}

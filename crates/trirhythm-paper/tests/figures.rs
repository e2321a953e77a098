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
    data.validate()
        .unwrap_or_else(|e| panic!("figure {}: computed data fails its check: {e}", F::NUMBER));
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

#[test]
fn the_lyapunov_step_resolves_the_correlation_time() {
    use trirhythm_paper::lle::dt_for;
    assert_eq!(dt_for(0.025), 0.0025);
    assert_eq!(dt_for(0.06), 0.005);
    assert_eq!(dt_for(0.1), 0.01);
    assert_eq!(dt_for(1.0), 0.01);
    assert_eq!(dt_for(0.0), 0.01);
    assert_eq!(dt_for(1e-6), 0.0001);
    for tau in [0.001, 0.004, 0.025, 0.06, 0.3] {
        assert!(dt_for(tau) <= tau / 10.0 * (1.0 + 1e-9), "τ = {tau}");
    }
}

#[test]
fn the_outer_start_is_the_averaged_outer_cycle_or_none() {
    use trirhythm::model::preset;
    use trirhythm_paper::lle::outer_amplitude;
    // Fig. 18's set at r = 0.998: a large outer cycle (≈ 12.9 at λ = 1)
    let p = preset("fig18a")
        .unwrap()
        .params
        .with("lambda", 1.0)
        .unwrap();
    let a = outer_amplitude(&p, Variant::Paper).unwrap().unwrap();
    assert!((10.0..16.0).contains(&a), "{a}");
    // strong impact loss: no stable cycle, no outer start
    let p = preset("fig18b").unwrap().params.with("r", 0.8).unwrap();
    assert_eq!(outer_amplitude(&p, Variant::Paper).unwrap(), None);
}

#[test]
fn lyapunov_figures_run_one_curve_per_attractor_and_keep_every_point() {
    use trirhythm_paper::lle::{panels_table, Curve, Flag, Panel, Point, StartKind};
    use trirhythm_paper::notes::variant_line;
    use trirhythm_paper::verdict::rules::{Bracket, PointSign};
    let f = fig18_lle_noise_fractional::Fig18::compute(&QUICK, &Silent).unwrap();
    for p in &f.0.panels {
        // every value has at least one curve, no two curves of a value on the same attractor
        for v in p.curves.iter().map(|c| c.value) {
            let of: Vec<&Curve> = p.curves.iter().filter(|c| c.value == v).collect();
            assert!(!of.is_empty());
            for (i, a) in of.iter().enumerate() {
                assert!(of[i + 1..].iter().all(|b| b.attractor != a.attractor));
            }
        }
        assert!(
            p.curves.iter().all(|c| c.dt == 0.0025),
            "τ = 0.025 runs at Δt = 0.0025"
        );
        for c in &p.curves {
            assert_eq!(c.attractor == "rest", c.start == StartKind::Rest);
            let r = c
                .regime
                .as_ref()
                .expect("every curve decided by its regime");
            assert_eq!(r.calls.len(), c.points.len());
            assert_eq!(r.rest.is_some(), c.start == StartKind::Rest);
            assert!(r.margin > 0.0);
            if let Bracket::Located { lo, hi } = r.bracket {
                assert!(lo < hi);
            }
            for q in &c.points {
                assert_ne!(q.sign, PointSign::Undefined, "every point has its call");
            }
        }
    }
    assert!(!f.0.caption.lines.contains(&variant_line(Variant::Paper)));
    let dts: Vec<f64> = f.0.dt_check.points.iter().map(|q| q.x).collect();
    assert_eq!(dts, vec![0.01, 0.005, 0.0025, 0.00125]);
    // a merged point is a row with its flag and no value
    let q = |x: f64, y: f64, flag| Point {
        x,
        y,
        lo: y - 0.01,
        hi: y + 0.01,
        se: 0.01,
        n: 8,
        flag,
        sign: PointSign::NotSignificant,
        merged: 0,
        unmerged: y,
        unmerged_se: 0.01,
    };
    let panel = Panel {
        caption: "(b) λ = 0.998".into(),
        x_key: "D".into(),
        x_desc: String::new(),
        y_desc: String::new(),
        y_key: "lle".into(),
        curves: vec![Curve {
            label: "r = 0.8, rest".into(),
            value: 0.8,
            start: StartKind::Rest,
            u0: 1.0,
            dt: 0.0025,
            attractor: "rest".into(),
            points: vec![
                q(0.1, 0.12, Flag::Value),
                q(0.3, f64::NEG_INFINITY, Flag::Merged),
            ],
            regime: None,
        }],
        verdicts: vec![],
    };
    let t = panels_table(&[], &[panel]);
    assert_eq!(t.rows.len(), 2);
    let col = |name: &str| t.columns.iter().position(|c| c == name).unwrap();
    assert_eq!(t.rows[1][col("flag")], "merged");
    assert_eq!(t.rows[1][col("y")], "");
    assert_eq!(t.rows[0][col("y")], "0.12");
    assert_eq!(t.rows[0][col("flag")], "");
    assert_eq!(t.rows[0][col("merged")], "0");
}

/// A point is merged (−∞, not drawn) only when at least half its realisations merged, as a
/// point's call reads it; a minority leaves the others' mean, tested on their own degrees of
/// freedom.
#[test]
fn a_point_is_merged_when_half_its_realisations_merged() {
    use trirhythm_paper::lle::{lle_curve, Curve, Flag, Point, StartKind};
    use trirhythm_paper::verdict::rules::PointSign;
    assert_eq!(Flag::of(0, 16, 0.1, 0.01), Flag::Value);
    assert_eq!(Flag::of(1, 16, 0.1, 0.01), Flag::Value);
    assert_eq!(Flag::of(7, 16, 0.1, 0.01), Flag::Value);
    assert_eq!(Flag::of(8, 16, 0.1, 0.01), Flag::Merged);
    assert_eq!(Flag::of(16, 16, f64::NAN, f64::NAN), Flag::Merged);
    assert_eq!(Flag::of(0, 1, 0.1, f64::NAN), Flag::Undefined);
    let point = |merged: usize| Point {
        x: 0.1,
        y: 0.1,
        lo: 0.09,
        hi: 0.11,
        se: 0.01,
        n: 16,
        flag: Flag::Value,
        sign: PointSign::NotSignificant,
        merged,
        unmerged: 0.1,
        unmerged_se: 0.01,
    };
    let curve = Curve {
        label: "r = 0.8, rest".into(),
        value: 0.8,
        start: StartKind::Rest,
        u0: 1.0,
        dt: 0.0025,
        attractor: "rest".into(),
        points: vec![point(0), point(3)],
        regime: None,
    };
    let dof: Vec<Option<f64>> = lle_curve(&curve).points.iter().map(|q| q.dof).collect();
    assert_eq!(dof, vec![Some(15.0), Some(12.0)]);
}

#[test]
fn fig19_has_every_value_with_a_curve_per_attractor() {
    let f = fig19_critical_noise::Fig19::compute(&QUICK, &Silent).unwrap();
    assert_eq!(f.panels.len(), 4);
    for m in &f.panels {
        for v in &m.values {
            assert!(
                m.panel.curves.iter().any(|c| c.value == *v),
                "{} = {v} has a curve",
                m.key
            );
        }
        assert_eq!(m.located.len(), m.panel.curves.len());
        for (c, l) in m.panel.curves.iter().zip(&m.located) {
            assert!(l.is_some() && c.regime.is_some());
            assert!(c.points.iter().all(|q| q.x > 0.0));
        }
    }
    let rows = f.tables()[0].rows.len();
    let points: usize = f
        .panels
        .iter()
        .flat_map(|m| m.panel.curves.iter().map(|c| c.points.len()))
        .sum();
    assert_eq!(rows, points, "every cell is a row");
}

/// A cycle's well lies between the averaged theory's unstable cycles next to it: Fig. 19's base
/// point is trirhythmic (stable 1.74, 8.17, 12.93; unstable 4.27, 10.57 at D = 0), and the
/// simulated cycles (inner 1.23, middle 8.04, outer 12.91) each get their own well.
#[test]
fn each_cycle_gets_the_well_between_its_unstable_neighbours() {
    use trirhythm::theory::averaging::Theory;
    let base = trirhythm::model::preset("fig19").unwrap().params;
    let cycles = Theory::new(&base.with("D", 0.0).unwrap(), Variant::Paper)
        .unwrap()
        .limit_cycles();
    let unstable: Vec<f64> = cycles
        .iter()
        .filter(|c| !c.stable)
        .map(|c| c.amplitude)
        .collect();
    assert_eq!(unstable.len(), 2, "{cycles:?}");
    let well = |a: f64| lle::cycle_well(&base, Variant::Paper, a).unwrap().unwrap();
    assert_eq!(well(1.23), (0.0, unstable[0]));
    assert_eq!(well(8.04), (unstable[0], unstable[1]));
    assert_eq!(well(12.91), (unstable[1], f64::INFINITY));
    // no stable cycle in the theory: no well
    let rest = base.with("r", 0.8).unwrap();
    let none = Theory::new(&rest.with("D", 0.0).unwrap(), Variant::Paper)
        .unwrap()
        .limit_cycles()
        .iter()
        .all(|c| !c.stable);
    assert_eq!(
        lle::cycle_well(&rest, Variant::Paper, 5.0)
            .unwrap()
            .is_none(),
        none
    );
}

/// Every preset passes the step guard at the step its figure simulates with: Δt = 0.01, or
/// for the Lyapunov figures the step that resolves τ ([`trirhythm_paper::lle::dt_for`]), with
/// no warning.
#[test]
fn every_preset_passes_the_step_guard_at_its_figure_step() {
    use trirhythm::analysis::check_step;
    use trirhythm::engine::{PredictorCorrector, Problem};
    for preset in trirhythm::model::presets() {
        let p = &preset.params;
        let lyapunov = ["fig17", "fig18", "fig19"]
            .iter()
            .any(|f| preset.name.starts_with(f));
        let dt = if lyapunov {
            trirhythm_paper::lle::dt_for(p.correlation_time)
        } else {
            0.01
        };
        let method = PredictorCorrector {
            dt,
            ..Default::default()
        };
        let r = check_step(&Problem::from_params(p).unwrap(), &method).unwrap();
        assert!(r.refusal().is_none(), "{}: {r:?}", preset.name);
        assert!(
            r.warnings().is_empty(),
            "{}: {:?}",
            preset.name,
            r.warnings()
        );
    }
}

/// Fig. 14's plotted window holds the Monte Carlo density (at most `WINDOW_MASS_TOL` of the
/// samples outside, the share stored per panel and printed in the caption), its cells carry
/// standard errors, and ⟨U̇²⟩ is stored for both models; the caption says whether the maps
/// decide anything.
#[test]
fn fig14_window_holds_the_monte_carlo_mass() {
    use trirhythm_paper::verdict::rules::WINDOW_MASS_TOL;
    let f = fig14_joint_pdf::Fig14::compute(&QUICK, &Silent).unwrap();
    for p in &f.panels {
        assert!(
            p.mc_outside <= WINDOW_MASS_TOL,
            "r = {}: {} of the samples outside the window",
            p.r,
            p.mc_outside
        );
        let v_max = p.v_edges.last().copied().unwrap();
        let u_max = p.u_edges.last().copied().unwrap();
        // the U̇ axis reaches twice the harmonic cycle's ±ω1·A_max (ω1 ≈ 1 here)
        assert!(v_max > 1.9 * u_max, "U̇ axis ±{v_max} for A_max = {u_max}");
        assert_eq!(p.mc_stderr.len(), p.mc.len());
        assert_eq!(p.mc_velocity_variance.len(), 2);
        assert!(p.theory_velocity_variance > 0.0);
    }
    let lines = f.caption.lines.join("\n");
    assert!(lines.contains("mass outside the window"), "{lines}");
    assert!(
        lines.contains("DECIDE NOTHING") || lines.contains("every Monte Carlo map is stationary"),
        "{lines}"
    );
}

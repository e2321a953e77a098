//! Parameter planes and lines: oscillation boundaries, branch diagrams and classified maps.

use crate::notes::num;
use crate::table::Table;
use serde::Serialize;
use trirhythm::analysis::oscillation::{Boundary, Classifier, Side};
use trirhythm::engine::ImpactMemory;
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;
use trirhythm::theory::bifurcation::{BranchDiagram, Folds, Map, What};

/// Oscillation boundaries along `x_key`: `method,x,y,y_lo,y_hi`, the abscissae without a
/// boundary in the interval named in the notes.
pub fn boundaries_table(notes: &[String], x_key: &str, results: &[Boundary]) -> Table {
    let mut notes = notes.to_vec();
    for b in results {
        for q in b.points.iter().filter(|q| q.side != Side::Boundary) {
            let why = match q.side {
                Side::Oscillates => "no boundary in the interval: oscillates throughout",
                Side::Rests => "no boundary in the interval: rests throughout",
                _ => "not available (exact linearisation with the wall at λ < 1)",
            };
            notes.push(format!("{}: at {x_key} = {} {why}", b.method, num(q.x)));
        }
    }
    let mut t = Table::new(&notes, &["method", "x", "y", "y_lo", "y_hi"]);
    for b in results {
        for q in b.points.iter().filter(|q| q.side == Side::Boundary) {
            let cells = [q.x, q.y, q.y_lo, q.y_hi].map(num);
            t.row(std::iter::once(b.method.to_string()).chain(cells));
        }
    }
    t
}

/// A branch diagram `branch,param,amplitude,stable`, its folds and Hopf points in the notes.
pub fn branches_table(notes: &[String], bd: &BranchDiagram) -> Table {
    let mut notes = notes.to_vec();
    let key = &bd.key;
    for f in &bd.folds {
        notes.push(format!("fold: {key} = {}, A = {}", num(f.0), num(f.1)));
    }
    for h in &bd.hopf {
        notes.push(format!("branch reaches A = 0 at {key} = {}", num(*h)));
    }
    let mut t = Table::new(&notes, &["branch", "param", "amplitude", "stable"]);
    for (i, b) in bd.branches.iter().enumerate() {
        for p in &b.points {
            let stable = u8::from(p.stable).to_string();
            t.row([i.to_string(), num(p.param), num(p.amplitude), stable]);
        }
    }
    t
}

/// The notes of a map's CSV files: parameters, variant, what is counted, the axes, the count
/// histogram and the fold curves traced.
pub fn map_notes(
    params: &Params,
    variant: Variant,
    what: What,
    (kx, ky): (&str, &str),
    m: &Map,
    sets: &[Folds],
) -> Vec<String> {
    let hist = m.histogram();
    let counted = if what == What::Rhythmicity {
        "limit cycles"
    } else {
        "maxima of P(A)"
    };
    let mut notes = vec![
        format!("params: {}", params.describe()),
        format!("variant: {}", variant.name()),
        format!("what: {} (count of stable {counted})", what.name()),
        format!("x: {kx}, y: {ky}"),
        format!(
            "points with count 0, 1, 2, 3, >=4: {}, {}, {}, {}, {}",
            hist[0], hist[1], hist[2], hist[3], hist[4]
        ),
    ];
    for f in sets {
        notes.push(format!(
            "fold curves ({}): {} traced from {} seeds, {} cusps",
            f.curves.first().map(|c| c.system.name()).unwrap_or("-"),
            f.curves.len(),
            f.seeds,
            f.cusps.len()
        ));
    }
    notes
}

/// An axis of a [`MapView`]: the key and its values.
#[derive(Serialize)]
pub struct AxisValues {
    /// The parameter.
    pub key: String,
    /// Its values on the grid.
    pub values: Vec<f64>,
}

/// A classified plane in JSON: the axes, the counts (one row per y), the count histogram and
/// the fold curves traced (the exact ones, then Eq. 37 as printed).
#[derive(Serialize)]
pub struct MapView<'a> {
    /// The parameters (a JSON object, key by key).
    pub params: serde_json::Value,
    /// The formula variant.
    pub variant: &'static str,
    /// What is counted.
    pub what: What,
    /// The horizontal axis.
    pub x: AxisValues,
    /// The vertical axis.
    pub y: AxisValues,
    /// `counts[iy][ix]`.
    pub counts: Vec<Vec<u8>>,
    /// Points with count 0, 1, 2, 3, ≥ 4.
    pub histogram: [usize; 5],
    /// The fold curves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub folds: Option<&'a Folds>,
    /// The fold curves of Eq. 37 as printed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub printed_eq37: Option<&'a Folds>,
}

impl<'a> MapView<'a> {
    /// The view of `m` with the fold curves `sets` and the parameters as `params`.
    pub fn of(params: serde_json::Value, m: &Map, sets: &'a [Folds]) -> MapView<'a> {
        let p = &m.plane;
        let axis = |a: &trirhythm::theory::bifurcation::Axis| AxisValues {
            key: a.key.clone(),
            values: a.values(),
        };
        MapView {
            params,
            variant: p.variant.name(),
            what: m.what,
            x: axis(&p.x),
            y: axis(&p.y),
            counts: (0..p.y.count)
                .map(|iy| (0..p.x.count).map(|ix| m.count(ix, iy)).collect())
                .collect(),
            histogram: m.histogram(),
            folds: sets.first(),
            printed_eq37: sets.get(1),
        }
    }
}

/// How an oscillation boundary is found by simulation, in words (a note of its table).
pub fn classifier_note(c: &Classifier) -> String {
    let impact_memory = match c.method.impact_memory {
        ImpactMemory::Continuous => "continuous",
        ImpactMemory::Restart => "restart",
    };
    format!(
        "simulation: predictor–corrector from U(0) = {}, dt = {}, {impact_memory} impact memory; \
         growth rate of ln(amplitude) after {} periods 2π/ω0, early stop once its sign is clear \
         (at most {} periods)",
        num(c.amplitude),
        num(c.method.dt),
        num(c.settle_periods),
        num(c.max_periods)
    )
}

//! What the oscillation-boundary figures (Figs 15, 16) share: the Hopf boundary in μ0 along one
//! parameter, found three ways — by simulation (predictor–corrector from a small amplitude, the
//! growth rate of ln(amplitude) after the start-up transient, the boundary bracketed), by
//! averaging (f′(0) = 0 of Eq. 18) and by the exact linearisation at U = 0 where it is exact —
//! and the distances between them.
//!
//! A panel is either a comparison of the methods for one parameter set
//! ([`Boundaries::methods`]) or the effect of a parameter on the simulated and averaged
//! boundaries ([`Boundaries::family`]). Method: [`boundary`] on a [`Plane`]; checked by the
//! library's oscillation tests (the exact boundary μ0π/(2ω_d) + ln r = 0 at λ = 1) and
//! `tests/figures.rs`.

use crate::notes::num;
use crate::table::Table;
use crate::{FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::analysis::oscillation::{
    boundary, BoundaryPoint, Classifier, Method, Plane, Search, Side,
};
use trirhythm::engine::{Barrier, Problem};
use trirhythm::model::Params;
use trirhythm::monitor::OnlyCancel;
use trirhythm::Result;

/// One boundary curve of a panel.
#[derive(Serialize, Deserialize)]
pub struct Curve {
    /// What it is (empty: one of a family's methods other than its simulation).
    pub label: String,
    /// `simulation`, `averaging`, `exact`, `exact, no wall` or `exact, λ = 1`.
    pub method: String,
    /// The boundary at each abscissa.
    pub points: Vec<BoundaryPoint>,
    /// In a family panel, the index of the parameter value the curve belongs to; `None` in a
    /// panel of methods.
    pub member: Option<usize>,
    /// Whether the region below this curve is the panel's simulated rest region.
    pub rest_below: bool,
}

impl Curve {
    /// A curve of a panel of methods.
    pub fn new(method: &str, label: impl Into<String>, points: Vec<BoundaryPoint>) -> Curve {
        Curve {
            label: label.into(),
            method: method.into(),
            points,
            member: None,
            rest_below: method == "simulation",
        }
    }

    /// A curve of a family panel: member `i`'s `method`, labelled only for the simulation.
    fn member(i: usize, method: &str, label: String, points: Vec<BoundaryPoint>) -> Curve {
        Curve {
            label,
            method: method.into(),
            points,
            member: Some(i),
            rest_below: i == 0 && method == "simulation",
        }
    }
}

/// One panel: an abscissa, μ0 searched in an interval, curves.
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// "(a) ω0 = 0.9, r = 0.998".
    pub caption: String,
    /// Short label for the data table.
    pub label: String,
    /// The abscissa's symbol.
    pub x_desc: String,
    /// Abscissa range.
    pub x_range: (f64, f64),
    /// μ0 range searched.
    pub y_range: (f64, f64),
    /// The curves.
    pub curves: Vec<Curve>,
}

impl Panel {
    /// Its ranges finite and increasing, every boundary point at a finite abscissa with its
    /// bracket in order ([`crate::validate`]).
    pub fn validate(&self, field: &str) -> crate::validate::Valid {
        use crate::validate::{invalid, range};
        range(&format!("{field}.x_range"), self.x_range)?;
        range(&format!("{field}.y_range"), self.y_range)?;
        for (j, c) in self.curves.iter().enumerate() {
            for (k, p) in c.points.iter().enumerate() {
                if !p.x.is_finite() || p.y_lo > p.y_hi {
                    return invalid(
                        format!("{field}.curves[{j}].points[{k}]"),
                        format!(
                            "x = {}, bracket [{}, {}]: x must be finite and the bracket ordered",
                            p.x, p.y_lo, p.y_hi
                        ),
                    );
                }
            }
        }
        Ok(())
    }

    /// Whether the panel's curves are a family (one set of curves per parameter value).
    pub fn is_family(&self) -> bool {
        self.curves.iter().any(|c| c.member.is_some())
    }
}

/// Points of [a, b], `n` of them.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1).max(1) as f64)
        .collect()
}

/// One sweep: the parameters, the abscissa and its values, the μ0 interval searched.
#[derive(Clone, Copy)]
pub struct Sweep<'a> {
    /// Base parameters.
    pub base: &'a Params,
    /// The abscissa's key.
    pub x_key: &'a str,
    /// Its values.
    pub xs: &'a [f64],
    /// The μ0 interval searched.
    pub y_range: (f64, f64),
}

/// A figure's boundary searches: accuracy (quick or paper quality), the two approximate
/// methods, the monitor.
pub struct Boundaries<'a> {
    /// The simulation's classifier.
    pub classifier: Classifier,
    /// The bracketing search.
    pub search: Search,
    /// Abscissae per curve.
    pub points: usize,
    averaging: Method,
    monitor: &'a dyn Monitor,
}

/// A family panel: the effect of `key` (one member per value) on the boundary along a sweep.
pub struct Family<'a> {
    /// Caption.
    pub caption: &'a str,
    /// Short label.
    pub label: &'a str,
    /// The parameter set per member.
    pub key: &'a str,
    /// Its symbol.
    pub symbol: &'a str,
    /// Its values.
    pub values: &'a [f64],
    /// The abscissa range of the panel.
    pub x_range: (f64, f64),
    /// Where member `value` has an exact boundary (the abscissae), if anywhere.
    pub exact_at: fn(f64, &[f64]) -> Option<Vec<f64>>,
    /// Whether a member's exact curve comes before its simulation (the data table's order).
    pub exact_first: bool,
}

impl<'a> Boundaries<'a> {
    /// Quick (CI) or paper quality.
    pub fn of(options: &FigureOptions, monitor: &'a dyn Monitor) -> Boundaries<'a> {
        let mut classifier = Classifier::default();
        let mut search = Search::default();
        let points = if options.quick {
            classifier.max_periods = 40.0;
            search.tolerance = 1e-2;
            5
        } else {
            21
        };
        Boundaries {
            classifier,
            search,
            points,
            averaging: Method::Averaging(options.variant),
            monitor,
        }
    }

    /// The boundary along `sweep` by `method`, with or without the wall.
    pub fn curve(
        &self,
        sweep: Sweep,
        barrier: Barrier,
        method: &Method,
    ) -> Result<Vec<BoundaryPoint>> {
        self.monitor.check()?;
        let template = Problem::from_params(sweep.base)?.with_barrier(barrier)?;
        let plane = Plane::new(
            &template,
            (sweep.x_key, sweep.xs.to_vec()),
            ("mu0", sweep.y_range.0, sweep.y_range.1),
        )?;
        Ok(boundary(&plane, method, &self.search, &OnlyCancel(self.monitor))?.points)
    }

    /// The simulated and the averaged boundary along `sweep`, with the wall.
    pub fn methods(&self, sweep: Sweep) -> Result<(Vec<BoundaryPoint>, Vec<BoundaryPoint>)> {
        let simulation = Method::Simulation(self.classifier);
        Ok((
            self.curve(sweep, Barrier::On, &simulation)?,
            self.curve(sweep, Barrier::On, &self.averaging)?,
        ))
    }

    /// The exact boundary along `sweep`.
    pub fn exact(&self, sweep: Sweep, barrier: Barrier) -> Result<Vec<BoundaryPoint>> {
        self.curve(sweep, barrier, &Method::Exact)
    }

    /// A family panel along `sweep` and a note per member (the distance simulation–averaging,
    /// and simulation–exact where the exact curve spans the sweep).
    pub fn family(&self, family: &Family, sweep: Sweep) -> Result<(Panel, Vec<String>)> {
        let mut curves = Vec::new();
        let mut notes = Vec::new();
        let x_name = crate::notes::symbol(sweep.x_key);
        for (i, &v) in family.values.iter().enumerate() {
            let p = sweep.base.with(family.key, v)?;
            let member = Sweep { base: &p, ..sweep };
            let (s, a) = self.methods(member)?;
            let mut text = format!(
                "panel {}, {} = {v}: largest distance simulation–averaging {}",
                family.label,
                family.symbol,
                distance_text(&s, &a, x_name)
            );
            let exact = match (family.exact_at)(v, sweep.xs) {
                Some(xs) => {
                    let e = self.exact(Sweep { xs: &xs, ..member }, Barrier::On)?;
                    if xs.len() == sweep.xs.len() {
                        text.push_str(&format!(
                            "; simulation–exact {}",
                            distance_text(&s, &e, x_name)
                        ));
                    }
                    Some(Curve::member(i, "exact", String::new(), e))
                }
                None => None,
            };
            notes.push(text);
            let label = format!("{} = {v}", family.symbol);
            let sim = Curve::member(i, "simulation", label, s);
            let avg = Curve::member(i, "averaging", String::new(), a);
            match exact {
                Some(e) if family.exact_first => curves.extend([e, sim, avg]),
                Some(e) => curves.extend([sim, avg, e]),
                None => curves.extend([sim, avg]),
            }
        }
        let panel = Panel {
            caption: family.caption.into(),
            label: family.label.into(),
            x_desc: x_name.into(),
            x_range: family.x_range,
            y_range: sweep.y_range,
            curves,
        };
        Ok((panel, notes))
    }
}

/// The largest |Δμ0| (and relative to the simulated value) between the simulated curve and
/// another, over the abscissae where both have a boundary.
pub fn distances(sim: &[BoundaryPoint], other: &[BoundaryPoint]) -> Option<(f64, f64, f64)> {
    sim.iter()
        .zip(other)
        .filter(|(s, o)| s.side == Side::Boundary && o.side == Side::Boundary)
        .map(|(s, o)| ((s.y - o.y).abs(), (s.y - o.y).abs() / s.y, s.x))
        .fold(None, |acc: Option<(f64, f64, f64)>, d| match acc {
            Some(a) if a.0 >= d.0 => Some(a),
            _ => Some(d),
        })
}

/// "largest |Δμ0| = … (…%) at x = …" or "no common point".
pub fn distance_text(sim: &[BoundaryPoint], other: &[BoundaryPoint], x_name: &str) -> String {
    match distances(sim, other) {
        Some((d, rel, x)) => format!(
            "{:.3e} ({} of the simulated μ0) at {x_name} = {}",
            d,
            if rel >= 1e-3 {
                format!("{:.1} %", 100.0 * rel)
            } else {
                format!("{rel:.1e} relative")
            },
            num(x)
        ),
        None => "no abscissa where both have a boundary".into(),
    }
}

/// The table of boundary panels: `panel,curve,method,x,mu0,mu0_lo,mu0_hi`, boundary points
/// only (a bracket: mu0_lo ≤ mu0 ≤ mu0_hi).
pub fn table(notes: &[String], panels: &[Panel]) -> Table {
    let mut csv = Table::new(
        notes,
        &["panel", "curve", "method", "x", "mu0", "mu0_lo", "mu0_hi"],
    );
    for p in panels {
        rows(&mut csv, p);
    }
    csv
}

/// The rows of a panel; a curve without a label of its own (a family member's averaging or
/// exact boundary, drawn unlabelled) is named by its member's label, else by its method.
fn rows(csv: &mut Table, panel: &Panel) {
    for c in &panel.curves {
        let name = if !c.label.is_empty() {
            c.label.as_str()
        } else {
            panel
                .curves
                .iter()
                .find(|o| c.member.is_some() && o.member == c.member && !o.label.is_empty())
                .map_or(c.method.as_str(), |o| o.label.as_str())
        };
        for q in c.points.iter().filter(|q| q.side == Side::Boundary) {
            csv.row([
                panel.label.clone(),
                name.replace(',', ";"),
                c.method.clone(),
                num(q.x),
                num(q.y),
                num(q.y_lo),
                num(q.y_hi),
            ]);
        }
    }
}

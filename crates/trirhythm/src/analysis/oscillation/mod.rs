//! Oscillation boundaries (Hopf): where the rest state U = 0 of Eq. (1) at D = 0 loses its
//! stability, by simulation, by averaging and by the exact linearisation (Figs 15–16).
//!
//! # Equation
//! D^{1+λ}U − μ0 P(U) U̇ + ω0² U = 0 on U ≥ 0 with U̇₊ = −rU̇₋ at U = 0 (or on the whole line,
//! [`Barrier::Off`](crate::engine::Barrier::Off)). P(0) = c0 (= 1 for the paper's
//! polynomial), so at rest the term −μ0c0U̇ is a *negative* damping μ0c0 against the
//! fractional term's positive one. A small
//! oscillation grows (the system oscillates) or dies (it rests); the boundary in one parameter
//! y at fixed other parameters is where the growth rate of the amplitude changes sign.
//!
//! The search runs over a [`Plane`]: a [`Problem`] template (its parameters at D = 0, its wall
//! and blow-up bound; Eq. 1 only) with one parameter as abscissa and the interval of another in
//! which the boundary is sought.
//!
//! # Methods
//! - [`Method::Simulation`]: from U(0) = a0 tiny (10⁻⁹, so P(U) = c0 to 10⁻¹⁸ and the run
//!   is the linearisation's), the predictor–corrector of [`crate::engine`] with the wall; the
//!   amplitude is read at every turning point (the extremum of the quadratic through the two
//!   nodes around V = 0; without the wall half the difference of consecutive extrema, which
//!   removes the slowly decaying offset of the fractional memory). After a start-up transient of
//!   [`Classifier::settle_periods`] periods 2π/ω0 (the Caputo memory of the start), the growth
//!   rate σ is the least-squares slope of ln(amplitude) against time over the window; the path
//!   stops as soon as the sign is clear (|σ| above [`Classifier::clarity`] standard errors on
//!   the window and on its second half, same sign on both, window at least
//!   [`Classifier::min_periods`] long), when the amplitude has grown 10⁵-fold or shrunk
//!   10⁵-fold, or at [`Classifier::max_periods`]. σ is close to linear in the parameter, so
//!   the boundary is bracketed by regula falsi on σ: each secant estimate c is followed by
//!   the pair c ∓ ½·tolerance, which straddles the root once the secant is accurate
//!   ([`Refinement::Secant`]); a step that does not halve the bracket is followed by a
//!   bisection, and [`Refinement::Bisection`] uses bisection on the sign alone. The result is
//!   the bracket [y_lo, y_hi] (width ≤ tolerance·|y|) and the secant root inside it.
//! - [`Method::Averaging`]: f′(0) = μ1β1/2 − κ = 0 of Eq. (18) (the theory's
//!   [`crate::theory::averaging::Theory::rest_state_slope`]), i.e. for μ0 the closed form [`averaging_mu0`]:
//!   μ0c0 = ω0^λ cos(πλ/2) + 2κ sin(πλ/2)/ω0^{1−λ}, κ = (1−r)ω1/π (paper) or −ω1 ln r/π
//!   (consistent). Without the wall there are no impacts: r = 1.
//! - [`Method::Exact`]: the linearisation at U = 0. Without the wall
//!   D^{1+λ}U − μ0c0U̇ + ω0²U = 0 grows iff s^{1+λ} − μ0c0 s + ω0² = 0 has a root with
//!   Re s > 0 (principal branch); on the boundary s = iΩ, so Ω^{1+λ} = ω0²/sin(πλ/2) and
//!   μ0c0 = Ω^λ cos(πλ/2) ([`exact_mu0`]). With the wall at λ = 1 each half-oscillation
//!   multiplies the amplitude by e^{μ0c0π/(2ω_d)} and each impact by r
//!   (ω_d² = ω0² − μ0²c0²/4): the boundary is μ0c0π/(2ω_d) + ln r = 0, i.e.
//!   μ0c0 = kω0/√(1 + k²/4), k = −2 ln r/π. With the wall and λ < 1 there is no exact
//!   half-period map under the continuous memory convention: [`Side::Unavailable`].
//!
//! With the wall at λ < 1 the decaying side is not a clean exponential: the memory's algebraic
//! tail acts on an exponentially shrinking bounce and the fitted rate drifts slowly, so the
//! simulated boundary there is the one over the horizon [`Classifier::max_periods`] (at
//! ω0 = 0.5, λ = 0.95, r = 0.99: 0.0206 over 40 periods, 0.0210 over 120).
//!
//! The analytic boundaries along any parameter are found by bisection on the sign of their
//! margin to full precision. Abscissae run in parallel (rayon); every point is deterministic
//! (no noise), so the results do not depend on the number of threads. A [`Monitor`] hears the
//! points (or cells) done, receives each as it is finished, and may stop the search
//! ([`Error::Cancelled`]), also inside a simulation.
//!
//! # Reference
//! The paper's Section IV.B (Figs 15–16, predictor–corrector at D = 0); the averaged drift
//! Eq. (18); Matignon, "Stability results for fractional differential equations" (1996) for
//! the characteristic equation s^{1+λ} − μs + ω² = 0 of a Caputo equation and its roots on
//! the principal sheet.
//!
//! # Tests
//! `tests/oscillation.rs`: the simulated boundary against the exact one without the wall
//! (λ ∈ {0.7, 0.9, 0.998}, ω0 ∈ {0.3, 0.9}) and with the wall at λ = 1 (r ∈ {0.95, 0.9, 0.7})
//! within the bracket plus 2·10⁻⁴ relative; the averaging boundary against its closed form
//! (both variants, along μ0 and along r); thread-count independence; the unit tests below.

mod analytic;
mod growth;
mod search;

pub use analytic::{averaging_mu0, exact_mu0, margin};
pub use growth::{growth_rate, Classifier, Growth};

use crate::engine::Problem;
use crate::error::{Error, Exact, Result};
use crate::model::Params;
use crate::monitor::{Monitor, OnlyCancel};
use crate::theory::averaging::Variant;
use growth::Cache;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// How a boundary is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Predictor–corrector runs from a small amplitude, bracketed along y.
    Simulation(Classifier),
    /// f′(0) = 0 of the averaged drift (Eq. 18) in the given variant.
    Averaging(Variant),
    /// The exact linearisation at U = 0 (no wall: any λ; wall: λ = 1).
    Exact,
}

impl Method {
    /// `simulation`, `averaging` or `exact`.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Simulation(_) => "simulation",
            Method::Averaging(_) => "averaging",
            Method::Exact => "exact",
        }
    }
}

/// How the simulated bracket is narrowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Refinement {
    /// Regula falsi on the growth rate, each estimate followed by a pair straddling it.
    #[default]
    Secant,
    /// Bisection on the sign alone.
    Bisection,
}

/// Accuracy of the simulated boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Search {
    /// Bracket width relative to |y| at which the search stops, in (0, 0.1].
    pub tolerance: f64,
    /// How the bracket is narrowed.
    pub refinement: Refinement,
}

impl Search {
    /// Check the search: `tolerance` in (0, 0.1].
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(Error::invalid("tolerance", self.tolerance, "(0, 0.1]"));
        }
        Ok(())
    }
}

impl Method {
    /// Check the method: a simulation's [`Classifier`] ([`Classifier::validate`]).
    pub fn validate(&self) -> Result<()> {
        match self {
            Method::Simulation(c) => c.validate(),
            Method::Averaging(_) | Method::Exact => Ok(()),
        }
    }
}

/// Most abscissae of a [`Plane`].
pub const MAX_ABSCISSAE: usize = 100_000;
/// Most points (x, y) one [`classify_plane`] classifies.
pub const MAX_CELLS: usize = 1_000_000;

impl Default for Search {
    fn default() -> Self {
        Search {
            tolerance: 1e-3,
            refinement: Refinement::Secant,
        }
    }
}

/// The plane searched: a [`Problem`] template (D = 0, Eq. 1; its wall and blow-up bound are
/// the search's), abscissae of one parameter and the interval of another in which the boundary
/// is sought.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// Everything that does not vary: the parameters, the wall, the blow-up bound.
    pub template: Problem,
    /// The abscissa's key (as for [`Params::set`]).
    pub x_key: String,
    /// The abscissae.
    pub x: Vec<f64>,
    /// The searched parameter's key.
    pub y_key: String,
    /// The interval [lo, hi] searched.
    pub y_range: (f64, f64),
}

impl Plane {
    /// Validate: D = 0, Eq. (1), two different known keys, lo < hi, 1 to [`MAX_ABSCISSAE`]
    /// abscissae, and every abscissa valid with both ends of the interval.
    pub fn new(
        template: &Problem,
        (x_key, x): (&str, Vec<f64>),
        (y_key, lo, hi): (&str, f64, f64),
    ) -> Result<Plane> {
        let plane = Plane {
            template: template.clone(),
            x_key: x_key.to_string(),
            x,
            y_key: y_key.to_string(),
            y_range: (lo, hi),
        };
        plane.validate()?;
        Ok(plane)
    }

    /// Check the plane as [`Plane::new`] does (its fields are public): every driver taking a
    /// plane calls it before any work.
    pub fn validate(&self) -> Result<()> {
        let (x_key, y_key, (lo, hi)) = (self.x_key.as_str(), self.y_key.as_str(), self.y_range);
        growth::check_problem(&self.template)?;
        let base = self.template.params();
        base.get(x_key)?;
        base.get(y_key)?;
        if x_key == y_key {
            return Err(Error::invalid(
                x_key,
                f64::NAN,
                "a key different from the searched one",
            ));
        }
        if x_key == "D" || y_key == "D" {
            return Err(Error::invalid(
                "D",
                base.noise_intensity,
                "0, not an axis (the oscillation boundary is that of the noise-free system)",
            ));
        }
        if lo.is_nan() || hi.is_nan() || lo >= hi {
            return Err(Error::invalid(
                y_key,
                lo,
                format!("an interval start below its end {}", Exact(hi)),
            ));
        }
        if self.x.is_empty() || self.x.len() > MAX_ABSCISSAE {
            return Err(Error::invalid(
                x_key,
                self.x.len() as f64,
                format!("1 to {MAX_ABSCISSAE} abscissae"),
            ));
        }
        for &xv in &self.x {
            self.at(xv, lo)?;
            self.at(xv, hi)?;
        }
        Ok(())
    }

    /// The parameters at (x, y), validated.
    pub fn at(&self, x: f64, y: f64) -> Result<Params> {
        let mut p = self.template.params().clone();
        p.set(&self.x_key, x)?;
        p.set(&self.y_key, y)?;
        p.validate()?;
        Ok(p)
    }

    /// The template's problem at (x, y).
    pub fn problem_at(&self, x: f64, y: f64) -> Result<Problem> {
        self.template.with_params(&self.at(x, y)?)
    }
}

/// Where the boundary is at one abscissa.
/// Serialised by [`Side::name`]; the capitalised names of earlier data files are read too.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Inside the interval.
    #[serde(alias = "Boundary")]
    Boundary,
    /// The system oscillates over the whole interval.
    #[serde(alias = "Oscillates")]
    Oscillates,
    /// The system rests over the whole interval.
    #[serde(alias = "Rests")]
    Rests,
    /// The method does not apply here (exact linearisation with the wall at λ < 1).
    #[serde(alias = "Unavailable")]
    Unavailable,
}

impl Side {
    /// `boundary`, `oscillates`, `rests`, `unavailable`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Boundary => "boundary",
            Side::Oscillates => "oscillates",
            Side::Rests => "rests",
            Side::Unavailable => "unavailable",
        }
    }
}

/// The boundary at one abscissa.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BoundaryPoint {
    /// The abscissa.
    pub x: f64,
    /// Whether a boundary lies in the interval.
    pub side: Side,
    /// The boundary (simulation: the secant root of the growth rates at the bracket's ends;
    /// NaN unless [`Side::Boundary`]).
    #[serde(with = "crate::non_finite")]
    pub y: f64,
    /// Lower end of the bracket (= y for the analytic methods).
    #[serde(with = "crate::non_finite")]
    pub y_lo: f64,
    /// Upper end of the bracket (= y for the analytic methods).
    #[serde(with = "crate::non_finite")]
    pub y_hi: f64,
    /// Whether the system oscillates just above the boundary (y_hi side).
    pub oscillates_above: bool,
    /// Simulations run for this point (0 for the analytic methods).
    pub simulations: usize,
    /// Simulations whose sign was not clear when they reached their longest run.
    pub unclear: usize,
}

/// The boundary along the abscissae.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Boundary {
    /// `simulation`, `averaging` or `exact`.
    pub method: &'static str,
    /// One point per abscissa, in order.
    pub points: Vec<BoundaryPoint>,
}

impl Boundary {
    /// Simulations run in all.
    pub fn simulations(&self) -> usize {
        self.points.iter().map(|p| p.simulations).sum()
    }
}

/// The boundary of `plane` by `method` at every abscissa (in parallel; deterministic).
/// `monitor` hears the points done and receives each point as it is finished.
pub fn boundary(
    plane: &Plane,
    method: &Method,
    search: &Search,
    monitor: &dyn Monitor<BoundaryPoint>,
) -> Result<Boundary> {
    search.validate()?;
    method.validate()?;
    plane.validate()?;
    let done = AtomicU64::new(0);
    let total = plane.x.len() as u64;
    let report = |point: &BoundaryPoint| {
        let n = done.fetch_add(1, Ordering::Relaxed) + 1;
        monitor.progress(n, total);
        monitor.finished(point)
    };
    let points = match method {
        Method::Simulation(c) => {
            // the searches of lanes/2 abscissae advanced together (two runs each at a time),
            // fewer when the threads would otherwise lack abscissae
            let threads = rayon::current_num_threads().max(1);
            let per = (c.lanes.width()? / 2)
                .min(plane.x.len().div_ceil(threads))
                .max(1);
            let groups = plane
                .x
                .par_chunks(per)
                .map(|xs| {
                    monitor.check()?;
                    search::simulated(plane, xs, c, search, &OnlyCancel(monitor), &report)
                })
                .collect::<Result<Vec<_>>>()?;
            groups.into_iter().flatten().collect()
        }
        Method::Averaging(_) | Method::Exact => plane
            .x
            .par_iter()
            .map(|&x| {
                monitor.check()?;
                let point = analytic::analytic(plane, x, method)?;
                report(&point)?;
                Ok(point)
            })
            .collect::<Result<Vec<_>>>()?,
    };
    Ok(Boundary {
        method: method.name(),
        points,
    })
}

/// One classified point of a plane.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Cell {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
    /// Whether a small oscillation grows here.
    pub oscillates: bool,
    /// The growth rate (simulation) or the margin (analytic methods; NaN where unavailable).
    #[serde(with = "crate::non_finite")]
    pub rate: f64,
}

/// Classify every (x, y) of `plane.x` × `ys` by `method` (rows over x in parallel;
/// deterministic). The interval `plane.y_range` is not used. At most [`MAX_CELLS`] points,
/// each a valid parameter set (checked before any work). `monitor` hears the cells done and
/// receives each cell as it is finished.
pub fn classify_plane(
    plane: &Plane,
    ys: &[f64],
    method: &Method,
    monitor: &dyn Monitor<Cell>,
) -> Result<Vec<Cell>> {
    method.validate()?;
    plane.validate()?;
    let cells = plane.x.len() as f64 * ys.len() as f64;
    if cells > MAX_CELLS as f64 {
        return Err(Error::invalid(
            &plane.y_key,
            ys.len() as f64,
            format!(
                "at most {MAX_CELLS} points in all ({} abscissae here)",
                plane.x.len()
            ),
        ));
    }
    for &x in &plane.x {
        for &y in ys {
            plane.at(x, y)?;
        }
    }
    let done = AtomicU64::new(0);
    let total = (plane.x.len() * ys.len()) as u64;
    let barrier = plane.template.barrier();
    let rows = plane
        .x
        .par_iter()
        .map(|&x| {
            let mut cache = Cache::default();
            let mut row = Vec::with_capacity(ys.len());
            // a simulated row in groups of ys stepped together in lanes
            let width = match method {
                Method::Simulation(c) => c.lanes.width()?,
                _ => 1,
            };
            for chunk in ys.chunks(width) {
                monitor.check()?;
                let rates: Vec<Result<f64>> = match method {
                    Method::Simulation(c) => {
                        let only = OnlyCancel(monitor);
                        let runs = search::grow_at(plane, x, chunk, c, &mut cache, &only)?;
                        runs.into_iter().map(|g| g.map(|g| g.rate)).collect()
                    }
                    _ => chunk
                        .iter()
                        .map(
                            |&y| Ok(margin(&plane.at(x, y)?, barrier, method)?.unwrap_or(f64::NAN)),
                        )
                        .collect(),
                };
                for (&y, rate) in chunk.iter().zip(rates) {
                    let rate = rate?;
                    let cell = Cell {
                        x,
                        y,
                        oscillates: rate > 0.0,
                        rate,
                    };
                    let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                    monitor.progress(n, total);
                    monitor.finished(&cell)?;
                    row.push(cell);
                }
            }
            Ok(row)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(rows.into_iter().flatten().collect())
}

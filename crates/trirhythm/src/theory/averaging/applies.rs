//! Where the averaged theory applies to a model of the class, and how well.
//!
//! Equation: first-order stochastic averaging of Ü + ω1²U = β2[(h − c − Σc_j)U̇ − k_nl(U) +
//! η_a + Uη_m] (the equivalent linearisation of [`super::general`]) in the amplitude–phase
//! variables of Z = A cos φ, Ż = −Aω1 sin φ, with Zhuravlev's U = |Z| for the wall at 0.
//!
//! Method: structural conditions refuse ([`Error::NotApplicable`], naming the term, its value
//! and why): a wall off 0 or two walls (no Zhuravlev image: the motion between impacts is not
//! a half-oscillation of one linear oscillator), a speed-dependent restitution (the loss rate
//! would depend on A, so f/A is no longer a polynomial in A²: not implemented), forcing (the
//! phase to the forcing is a second slow variable), correlated noises with a wall (the cross
//! drift meets sgn Z's jump), [`Variant::Paper`] outside the paper's Eq. (1) with its wall
//! (the paper's κ and σ1 are printed, not derived), and a strong Duffing shift at a cycle
//! (checked once the cycles are known, [`DUFFING_LIMIT`]). The class's h is even in U and U̇
//! and its k odd by construction, so the wall at 0 always has Zhuravlev's image. The small
//! parameters of the method are reported, not refused, as [`Assumption`]s (like R̂ for an
//! ensemble): the memory 1 − λ, the balance frequency's distance |ω_b − ω1|/ω1, the damping
//! strength β2·max|h − c − Σc_j|/ω1 on the largest cycle, the Duffing shift there and the
//! frequency shift |Δω|/ω1 it causes (the response leaves the balance frequency).
//!
//! The routines built on the paper's closed forms rather than on the phase quadrature (the
//! critical noise, the oscillation boundaries, the phase response, the attractor's starts) ask
//! [`closed_forms`]: they take the paper's family only.
//!
//! Reference: Khasminskii's averaging theorem (first order in the small parameters reported
//! here); Zhuravlev's transformation; `model-class.md` §6 of the project's design notes.
//!
//! Tests: `tests/averaging.rs` (`the_theory_refuses_what_it_does_not_cover`, the assumptions
//! reported for the paper's presets) and `trirhythm-cli/tests/model.rs` (the refusal at the
//! command line).

use super::Variant;
use crate::error::{Error, Exact, Result};
use crate::model::{Keep, Model, PaperFamily, Restitution};
use serde::{Deserialize, Serialize};

/// The method's name in its refusals.
pub const METHOD: &str = "the averaged theory";

/// Largest Duffing shift (|k3|A² + |k5|A⁴)/ω0² at a cycle the theory accepts: beyond it the
/// restoring force's nonlinearity is not a small frequency correction.
pub const DUFFING_LIMIT: f64 = 0.2;
/// The memory 1 − λ beyond which the harmonic-balance equivalents are reported as a strained
/// assumption (the paper works at 1 − λ ≤ 0.005).
pub const MEMORY_LIMIT: f64 = 0.1;
/// |ω_b − ω1|/ω1 beyond which balancing at ω_b = ω0 is reported as strained.
pub const BALANCE_LIMIT: f64 = 0.1;
/// β2·max|h − c − Σc_j|/ω1 (the damping per radian) beyond which first-order averaging is
/// reported as strained.
pub const DAMPING_LIMIT: f64 = 1.0;

/// One assumption of the method, measured on the model: `holds` when `value` ≤ `limit`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Assumption {
    /// What is measured, with its formula (`1 − λ`).
    pub name: String,
    /// Its value for the model.
    pub value: f64,
    /// The largest value the method is trusted at.
    pub limit: f64,
    /// `value <= limit`.
    pub holds: bool,
}

impl Assumption {
    /// `name = value` measured against `limit`.
    pub fn new(name: impl Into<String>, value: f64, limit: f64) -> Self {
        Assumption {
            name: name.into(),
            value,
            limit,
            holds: value <= limit,
        }
    }
}

fn refuse(assumption: &str, reason: String) -> Error {
    Error::NotApplicable {
        method: METHOD.to_string(),
        assumption: assumption.to_string(),
        reason,
    }
}

/// Whether the model has the paper's wall at U = 0 with a constant r: `Some(r)`, `None` for no
/// wall. Refuses every other wall by name.
pub(super) fn wall_at_zero(model: &Model) -> Result<Option<f64>> {
    match model.walls.as_slice() {
        [] => Ok(None),
        [w] => {
            if w.position != 0.0 {
                return Err(refuse(
                    "a wall at U = 0 or none (Zhuravlev's U = |Z|)",
                    format!(
                        "wall.0.position = {}: a wall off 0 has no Zhuravlev image (the motion \
                         between impacts is no half-oscillation of one linear oscillator); \
                         allowed: 0",
                        Exact(w.position)
                    ),
                ));
            }
            match w.restitution {
                Restitution::Constant(r) => Ok(Some(r)),
                Restitution::Speed(_) => Err(refuse(
                    "a constant restitution coefficient",
                    "wall.0.restitution is speed-dependent: the averaged loss rate would \
                     depend on A (f/A no longer a polynomial in A²), not implemented; allowed: \
                     a number in [0, 1]"
                        .into(),
                )),
            }
        }
        _ => Err(refuse(
            "a wall at U = 0 or none (Zhuravlev's U = |Z|)",
            format!(
                "wall.1.position = {}: two walls have no Zhuravlev image (the motion between \
                 them is no half-oscillation of one linear oscillator); allowed: one wall, at 0",
                Exact(model.walls[1].position)
            ),
        )),
    }
}

/// Whether the averaged theory applies to `model` in `variant`: the structural refusals (see
/// the module docs), else the assumptions that can be measured before the cycles are known
/// (1 − λ, |ω_b − ω1|/ω1). [`super::Theory::from_model`] adds the damping strength and the
/// Duffing shift at the cycles it finds (and refuses a shift beyond [`DUFFING_LIMIT`]).
pub fn applies(model: &Model, variant: Variant) -> Result<Vec<Assumption>> {
    model.validate()?;
    let wall = wall_at_zero(model)?;
    if let Some(f) = model.forcing.filter(|f| f.amplitude != 0.0) {
        return Err(refuse(
            "no forcing (one slow phase)",
            format!(
                "forcing.amplitude = {}: the phase to the forcing F cos(Ωt + φ) is a second \
                 slow variable, outside one-dimensional amplitude averaging; allowed: 0",
                Exact(f.amplitude)
            ),
        ));
    }
    let both = model.noise.additive.is_some_and(|a| a.intensity != 0.0)
        && model
            .noise
            .multiplicative
            .is_some_and(|m| m.intensity != 0.0);
    if wall.is_some() && both && model.noise.correlation != 0.0 {
        return Err(refuse(
            "independent noises with a wall",
            format!(
                "noise.correlation = {} with wall.0: the cross drift of η_a and η_m meets \
                 sgn Z's jump at the impact, not derived; allowed: 0 with a wall",
                Exact(model.noise.correlation)
            ),
        ));
    }
    if variant == Variant::Paper {
        if let Err(e) = model.paper_family(METHOD) {
            let why = match e {
                Error::NotApplicable { reason, .. } => reason,
                other => other.to_string(),
            };
            return Err(refuse(
                "the paper's Eq. (1) for --variant paper",
                format!(
                    "{}; the paper variant's κ and σ1 are printed for Eq. (1), not derived: \
                     use the consistent variant",
                    why.split(':').next().unwrap_or(&why)
                ),
            ));
        }
        if wall.is_none() {
            return Err(refuse(
                "the paper's Eq. (1) for --variant paper",
                "wall: none; the paper variant's κ and σ1 are printed for Eq. (1) with its \
                 wall at 0, not derived: use the consistent variant"
                    .into(),
            ));
        }
        if matches!(model.walls.as_slice(), [w] if w.keep == Keep::Below) {
            return Err(refuse(
                "the paper's Eq. (1) for --variant paper",
                "wall.0.keep = \"below\": the paper's wall keeps U ≥ 0; use the consistent \
                 variant (the mirror image U → −U is the same theory)"
                    .into(),
            ));
        }
    }
    let eq = super::general::linearise(model);
    Ok(vec![
        Assumption::new("1 − λ", 1.0 - model.leading.lambda, MEMORY_LIMIT),
        Assumption::new(
            "|ω_b − ω1|/ω1",
            (eq.omega_b - eq.equivalents.omega1).abs() / eq.equivalents.omega1,
            BALANCE_LIMIT,
        ),
    ])
}

/// Whether the paper's closed forms apply to `model`: Eq. (5)'s equivalents, Zhuravlev's
/// transformation and P(A) of h = μ0P(U), k = ω0²U without forcing, with the wall at 0 or
/// none, on which the critical noise, the oscillation boundaries, the phase response and the
/// attractor's starts are built. Returns the model's paper family, or refuses any other model
/// with [`Error::NotApplicable`] naming the first term outside it, its value and why
/// ([`Model::paper_family`]).
pub fn closed_forms(model: &Model) -> Result<PaperFamily> {
    model.paper_family(METHOD).map_err(|e| match e {
        Error::NotApplicable {
            method,
            assumption,
            reason,
        } => Error::NotApplicable {
            method,
            assumption,
            reason: format!(
                "{reason}; the paper's closed forms (Eq. 5, Zhuravlev, P(A)) are those of \
                 h = μ0P(U), k = ω0²U without forcing, with the wall at 0 or none"
            ),
        },
        other => other,
    })
}

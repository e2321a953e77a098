//! The averaged (analytic) theory of the paper, in two variants.
//!
//! Equations (paper numbers; corrections from the project's `formulas.md`):
//! - harmonic balance (Eq. 4–5): μ1 = μ0ω0^{1−λ}/sin(πλ/2), β1 = c0 − ω0^λcos(πλ/2)/μ0,
//!   ω1² = ω0^{3−λ}/sin(πλ/2), β2 = ω0^{1−λ}/sin(πλ/2);
//! - averaged drift (Eq. 18) for a damping polynomial of any degree:
//!   f(A) = μ1 A Σ_k c̃_k w_k A^{2k} − κA, with c̃_0 = β1, c̃_k = c_k (k ≥ 1),
//!   w_k = ⟨cos^{2k}φ sin²φ⟩ = C(2k,k)/(4^k(2k+2)) (1/2, 1/8, 1/16, 5/128, 7/256, 21/1024, …),
//!   and the impact loss rate κ = (1−r)ω1/π ([`Variant::Paper`]) or −ω1 ln(r)/π
//!   ([`Variant::Consistent`]: each impact multiplies the amplitude by r, two per period);
//! - energy change per period (Eq. 20): πA²f(A) (paper, as printed) or 2πω1 A f(A) (consistent);
//! - FPK for the amplitude (Eq. 25–26): drift m1 = f + σ1/(2A), diffusion σ1, with
//!   σ1 = β2D/(ω1²(1+τ²)) (paper) or (β2²D/ω1²) Σ_{k≥1} b_k²/(1+4k²τ²ω1²),
//!   b_k = 8k(−1)^{k+1}/(π(4k²−1)) (consistent: the noise enters through sgn(Z));
//! - pseudo-potential (Eq. 23): U_eff = −∫₀^A f − (σ1/2) ln A, so dU_eff/dA = −m1;
//! - stationary PDFs (Eq. 27–31): P(A) ∝ (A/σ1) exp(S), S = (2/σ1)∫₀^A f (Eq. 27's typo, the
//!   missing (1+τ²) on the impact term, fixed); P(H) = P(A)/(ω1²A) at H = ω1²A²/2;
//!   P(U, U̇) = 2 P(A)/(2πω1A) on U ≥ 0 with A² = U² + U̇²/ω1².
//!
//! Method: f/A = g(x) and A·m1 = h(x) = x g(x) + σ1/2 are polynomials in x = A², so limit cycles
//! and PDF extrema are the positive real roots of g and h, isolated completely by
//! [`crate::theory::polynomial`] (derivative cascade, Sturm count); stability is the sign of g′ or h′.
//! PDFs are held in log space relative to their highest mode, the difference of the large terms
//! S(A) − S(A_p) formed in double-double, and normalised by globally adaptive Gauss–Kronrod
//! quadrature with breakpoints at the extrema and geometrically around each mode, so exponents
//! of thousands (D down to 1e-4) neither overflow, underflow, nor lose precision.
//!
//! Reference: the paper (Eq. 4–37); Zhuravlev's transformation; stochastic averaging
//! (Khasminskii). Tests: `tests/averaging.rs` (independent reference values, normalisation,
//! Eq. 29 relation, joint PDF mass, proptest invariants) and the unit tests below.
//!
//! Layout: `variant` (the two forms of the averaged coefficients: loss rate, diffusion, phase
//! weights), this module (the drift, the potential, cycles, extrema and barriers of [`Theory`]),
//! `pdf` (the stationary densities, [`AmplitudePdf`]).

mod pdf;
mod variant;

pub use pdf::{AmplitudePdf, MIN_RELATIVE_WIDTH};
pub use variant::{phase_average_weight, sgn_harmonic_sum, Variant};

use crate::error::{Error, Result};
use crate::model::{Equivalents, Params};
use crate::theory::polynomial::Polynomial;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A limit cycle (or an extremum of the stationary amplitude PDF when D > 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cycle {
    /// Amplitude A0 > 0.
    pub amplitude: f64,
    /// Stable: df/dA < 0 (D = 0) or dm1/dA < 0 (D > 0, a mode of P(A)).
    pub stable: bool,
    /// Two branches merge here (df/dA = 0 within rounding): a saddle-node point.
    pub fold: bool,
}

/// Number of coexisting stable cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rhythmicity {
    /// No stable cycle (the rest state attracts, or everything escapes).
    None,
    /// One stable cycle.
    Mono,
    /// Two.
    Bi,
    /// Three.
    Tri,
    /// More than three (possible for damping polynomials of higher degree).
    Multi(usize),
}

impl Rhythmicity {
    /// From a count of stable cycles.
    pub fn from_count(n: usize) -> Self {
        match n {
            0 => Rhythmicity::None,
            1 => Rhythmicity::Mono,
            2 => Rhythmicity::Bi,
            3 => Rhythmicity::Tri,
            n => Rhythmicity::Multi(n),
        }
    }

    /// The count of stable cycles.
    pub fn count(self) -> usize {
        match self {
            Rhythmicity::None => 0,
            Rhythmicity::Mono => 1,
            Rhythmicity::Bi => 2,
            Rhythmicity::Tri => 3,
            Rhythmicity::Multi(n) => n,
        }
    }

    /// `none`, `monorhythmic`, `birhythmic`, `trirhythmic`, `4-rhythmic`, …
    pub fn name(self) -> String {
        match self {
            Rhythmicity::None => "none".into(),
            Rhythmicity::Mono => "monorhythmic".into(),
            Rhythmicity::Bi => "birhythmic".into(),
            Rhythmicity::Tri => "trirhythmic".into(),
            Rhythmicity::Multi(n) => format!("{n}-rhythmic"),
        }
    }
}

/// An extremum of U_eff.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Extremum {
    /// Amplitude (A = 0 is the rest state when D = 0).
    pub amplitude: f64,
    /// U_eff there.
    pub potential: f64,
    /// A well (minimum) or a crest (maximum).
    pub minimum: bool,
}

/// Which way a barrier is crossed from its well.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Towards smaller amplitude.
    Left,
    /// Towards larger amplitude.
    Right,
}

impl Side {
    /// `left` or `right`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
        }
    }
}

/// An energy barrier ΔU = U_eff(crest) − U_eff(well) between neighbouring extrema.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Barrier {
    /// The well's amplitude.
    pub well: f64,
    /// The crest's amplitude.
    pub crest: f64,
    /// Direction of escape.
    pub side: Side,
    /// ΔU > 0.
    pub height: f64,
}

/// The averaged problem: parameters, variant and everything derived from them.
#[derive(Debug, Clone)]
pub struct Theory {
    params: Params,
    variant: Variant,
    eq: Equivalents,
    /// Impact loss rate κ: the drift's impact term is −κA.
    loss_rate: f64,
    /// σ1 (0 when D = 0).
    sigma1: f64,
    /// g(x) = f(A)/A at x = A².
    g: Polynomial,
    /// g′(x).
    g_derivative: Polynomial,
    /// ∫₀^x g: ∫₀^A f dA = G(A²)/2.
    g_integral: Polynomial,
    /// h(x) = A·m1 = x g(x) + σ1/2.
    h: Polynomial,
}

impl Theory {
    /// Validate `params` and build the averaged problem.
    pub fn new(params: &Params, variant: Variant) -> Result<Self> {
        params.validate()?;
        let eq = Equivalents::new(params);
        let r = params.restitution;
        if variant == Variant::Consistent && r == 0.0 {
            return Err(Error::invalid(
                "r",
                r,
                "(0, 1] for the consistent variant (r = 0 gives an infinite loss ω1 ln(r)/π)",
            ));
        }
        let loss_rate = eq.loss_rate(variant, r);
        let sigma1 = eq.diffusion(variant, params.noise_intensity, params.correlation_time);
        let mut gc: Vec<f64> = params
            .damping
            .coefficients
            .iter()
            .enumerate()
            .map(|(k, &c)| eq.mu1 * if k == 0 { eq.beta1 } else { c } * phase_average_weight(k))
            .collect();
        gc[0] -= loss_rate;
        let g = Polynomial::new(gc);
        let g_integral = g.integral();
        let g_derivative = g.derivative();
        let mut hc = vec![sigma1 / 2.0];
        hc.extend(g.coefficients.iter().copied());
        let h = Polynomial::new(hc);
        Ok(Theory {
            params: params.clone(),
            variant,
            eq,
            loss_rate,
            sigma1,
            g,
            g_derivative,
            g_integral,
            h,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The variant.
    pub fn variant(&self) -> Variant {
        self.variant
    }

    /// μ1, β1, ω1, β2.
    pub fn equivalents(&self) -> Equivalents {
        self.eq
    }

    /// κ, the impact loss rate of the drift (−κA).
    pub fn loss_rate(&self) -> f64 {
        self.loss_rate
    }

    /// σ1, the amplitude diffusion (Eq. 26).
    pub fn diffusion(&self) -> f64 {
        self.sigma1
    }

    /// f(A)/A as a polynomial in x = A².
    pub fn drift_polynomial(&self) -> &Polynomial {
        &self.g
    }

    /// A·m1(A) as a polynomial in x = A².
    pub fn fpk_polynomial(&self) -> &Polynomial {
        &self.h
    }

    /// f(A) (Eq. 18).
    pub fn drift(&self, a: f64) -> f64 {
        a * self.g.eval(a * a)
    }

    /// df/dA = g(x) + 2x g′(x).
    pub fn drift_slope(&self, a: f64) -> f64 {
        let x = a * a;
        self.g.eval(x) + 2.0 * x * self.g_derivative.eval(x)
    }

    /// f′(0) = μ1β1/2 − κ: the rest state U = 0 is stable when negative.
    pub fn rest_state_slope(&self) -> f64 {
        self.g.coefficients[0]
    }

    /// Energy change over one period (Eq. 19–20): πA²f (paper) or 2πω1Af (consistent).
    pub fn energy_change(&self, a: f64) -> f64 {
        match self.variant {
            Variant::Paper => PI * a * a * self.drift(a),
            Variant::Consistent => 2.0 * PI * self.eq.omega1 * a * self.drift(a),
        }
    }

    /// FPK drift m1(A) = f(A) + σ1/(2A) (Eq. 26); at A = 0 its limit: +∞ when σ1 > 0, else
    /// f(0) = 0.
    pub fn fpk_drift(&self, a: f64) -> f64 {
        if a == 0.0 {
            return if self.h.eval(0.0) > 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
        }
        self.h.eval(a * a) / a
    }

    /// U_eff(A) = −∫₀^A f − (σ1/2) ln A (Eq. 23).
    pub fn potential(&self, a: f64) -> f64 {
        let poly = -0.5 * self.g_integral.eval(a * a);
        if self.sigma1 > 0.0 {
            poly - 0.5 * self.sigma1 * a.ln()
        } else {
            poly
        }
    }

    /// Every positive root of f (D = 0) with its stability, ascending: the limit cycles of the
    /// noise-free averaged system.
    pub fn limit_cycles(&self) -> Vec<Cycle> {
        positive_roots(&self.g)
    }

    /// Every positive root of m1 (the extrema of P(A)) when D > 0, else the limit cycles.
    pub fn cycles(&self) -> Vec<Cycle> {
        if self.sigma1 > 0.0 {
            positive_roots(&self.h)
        } else {
            self.limit_cycles()
        }
    }

    /// Number of stable entries of [`Theory::cycles`].
    pub fn rhythmicity(&self) -> Rhythmicity {
        Rhythmicity::from_count(self.cycles().iter().filter(|c| c.stable).count())
    }

    /// Number of stable limit cycles from the Sturm count alone (no root isolation): the
    /// roots of g alternate in slope and g is negative at +∞ when the leading coefficient is.
    pub fn stable_count_fast(&self) -> usize {
        stable_count(if self.sigma1 > 0.0 { &self.h } else { &self.g })
    }

    /// Extrema of U_eff, ascending in A (with the rest state A = 0 when D = 0).
    pub fn extrema(&self) -> Vec<Extremum> {
        let mut out = Vec::new();
        if self.sigma1 == 0.0 {
            out.push(Extremum {
                amplitude: 0.0,
                potential: 0.0,
                minimum: self.rest_state_slope() < 0.0,
            });
        }
        for c in self.cycles() {
            if c.fold {
                continue;
            }
            out.push(Extremum {
                amplitude: c.amplitude,
                potential: self.potential(c.amplitude),
                minimum: c.stable,
            });
        }
        out
    }

    /// Energy barriers: for each well from the left, the climb to its left crest, then to its
    /// right crest (the paper's ΔU1…ΔU4 in a trirhythmic potential).
    pub fn barriers(&self) -> Vec<Barrier> {
        let ex = self.extrema();
        let mut out = Vec::new();
        for (i, e) in ex.iter().enumerate() {
            if !e.minimum {
                continue;
            }
            if i > 0 && !ex[i - 1].minimum {
                let c = ex[i - 1];
                out.push(Barrier {
                    well: e.amplitude,
                    crest: c.amplitude,
                    side: Side::Left,
                    height: c.potential - e.potential,
                });
            }
            if i + 1 < ex.len() && !ex[i + 1].minimum {
                let c = ex[i + 1];
                out.push(Barrier {
                    well: e.amplitude,
                    crest: c.amplitude,
                    side: Side::Right,
                    height: c.potential - e.potential,
                });
            }
        }
        out
    }

    /// The stationary amplitude PDF (Eq. 27–28), normalised.
    pub fn amplitude_pdf(&self) -> Result<AmplitudePdf> {
        AmplitudePdf::new(self)
    }
}

fn positive_roots(p: &Polynomial) -> Vec<Cycle> {
    p.real_roots(0.0, f64::INFINITY)
        .into_iter()
        .map(|r| Cycle {
            amplitude: r.x.sqrt(),
            stable: !r.double && r.slope < 0.0,
            fold: r.double,
        })
        .collect()
}

/// Stable roots (p going from + to −) of p on x > 0, from a Sturm count and the signs at 0 and ∞.
pub fn stable_count(p: &Polynomial) -> usize {
    let n = p.sturm_count(0.0, f64::INFINITY);
    let at_zero = p.coefficients[0];
    // Roots alternate in slope; the first one is a + → − crossing when p(0) > 0.
    if at_zero > 0.0 {
        n.div_ceil(2)
    } else {
        n / 2
    }
}

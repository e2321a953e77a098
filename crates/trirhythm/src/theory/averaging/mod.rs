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
//! The model class (`general`, [`Theory::from_model`]): the same [`Theory`] from a
//! [`Model`] — the fractional terms by the Eq. 4 rule, f by exact phase quadrature of h (still a
//! polynomial in A²), the noise's diffusion b(A) = σ1 + b_1A² and drift correction
//! m_c = σ1/(2A) + qA (additive and multiplicative, white or OU); the extrema of P(A) are then
//! the roots of x g(x) + σ1/2 + (q − b_1)x, U_eff = −∫(f + m_c − b′/2). Where the method does
//! not apply, [`applies`] refuses naming the term, and reports its small parameters
//! ([`Assumption`]).
//!
//! Layout: `variant` (the two forms of the averaged coefficients: loss rate, diffusion, phase
//! weights), this module (the drift, the potential, cycles, extrema and barriers of [`Theory`]),
//! `pdf` (the stationary densities, [`AmplitudePdf`]), `shape` (ln P(A) for a constant or an
//! A-dependent diffusion), `applies` (where the theory applies to a model), `general` (the
//! theory of a model of the class).

mod applies;
mod general;
mod pdf;
mod shape;
mod variant;

pub use applies::{
    applies, closed_forms, Assumption, BALANCE_LIMIT, DAMPING_LIMIT, DUFFING_LIMIT, MEMORY_LIMIT,
    METHOD,
};
pub use general::{
    linearise, linearise_at, linearise_with, phase_average, Balance, Linearised, PHASE_NODES,
};
pub use pdf::{AmplitudePdf, MIN_RELATIVE_WIDTH};
pub use variant::{phase_average_weight, sgn_harmonic_sum, Variant};

use crate::error::{Error, Result};
use crate::model::{Equivalents, Model, Params};
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

/// The averaged problem: parameters (or a model of the class), variant and everything derived
/// from them.
#[derive(Debug, Clone)]
pub struct Theory {
    /// The paper family's parameters; for a model outside it, its projection (μ0, ω0, λ, P,
    /// the additive D and τ, r or 1), the model itself in `model`.
    params: Params,
    /// The model, when it is not the paper's Eq. (1) with its wall ([`Theory::from_model`]).
    model: Option<Box<Model>>,
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
    /// The extrema of P(A) (2(f + m_c) = b′) as the roots of a polynomial in x:
    /// x g(x) + σ1/2 + (q − b_1)x (divided by x when σ1 = 0 < b_1); x g(x) + σ1/2 = A·m1 for
    /// additive noise.
    h: Polynomial,
    /// A·(f + m_c) = x g(x) + σ1/2 + q x, the FPK drift times A.
    fpk: Polynomial,
    /// b_1: the multiplicative noise's diffusion b_1A² (0 without it).
    multiplicative: f64,
    /// q: the multiplicative noise's drift correction qA (0 without it).
    correction: f64,
    /// The assumptions measured on the model ([`Theory::from_model`]; empty from
    /// [`Theory::new`]).
    assumptions: Vec<Assumption>,
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
        let gc: Vec<f64> = params
            .damping
            .coefficients
            .iter()
            .enumerate()
            .map(|(k, &c)| eq.mu1 * if k == 0 { eq.beta1 } else { c } * phase_average_weight(k))
            .collect();
        Ok(Theory::assemble(
            params.clone(),
            variant,
            eq,
            loss_rate,
            Polynomial::new(gc),
            sigma1,
            0.0,
            0.0,
        ))
    }

    /// The theory from its averaged coefficients: g without the loss, the loss rate κ, the
    /// additive diffusion σ1, the multiplicative b_1 and q.
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        params: Params,
        variant: Variant,
        eq: Equivalents,
        loss_rate: f64,
        mut g: Polynomial,
        sigma1: f64,
        multiplicative: f64,
        correction: f64,
    ) -> Theory {
        g.coefficients[0] -= loss_rate;
        let g_integral = g.integral();
        let g_derivative = g.derivative();
        let shifted = |shift: f64| {
            let mut c = vec![sigma1 / 2.0];
            c.extend(g.coefficients.iter().copied());
            if shift != 0.0 {
                c[1] += shift;
            }
            Polynomial::new(c)
        };
        let fpk = shifted(correction);
        let h = if sigma1 == 0.0 && multiplicative > 0.0 {
            // x g + (q − b_1)x over x: the extrema away from A = 0
            let mut c = g.coefficients.clone();
            c[0] += correction - multiplicative;
            Polynomial::new(c)
        } else {
            shifted(correction - multiplicative)
        };
        Theory {
            params,
            model: None,
            variant,
            eq,
            loss_rate,
            sigma1,
            g,
            g_derivative,
            g_integral,
            h,
            fpk,
            multiplicative,
            correction,
            assumptions: Vec::new(),
        }
    }

    /// The parameters: the paper family's, or for a model outside it ([`Theory::model`]) its
    /// projection μ0, ω0, λ, P(U), the additive D and τ and r (1 without a wall).
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The model of the class the theory was averaged from, when it is not the paper's Eq. (1)
    /// with its wall.
    pub fn model(&self) -> Option<&Model> {
        self.model.as_deref()
    }

    /// What the theory is of, in one line: `key=value` pairs for the paper family, else the
    /// model's fields.
    pub fn describe(&self) -> String {
        match &self.model {
            None => self.params.describe(),
            Some(m) => {
                let lines: Vec<String> = m
                    .to_toml()
                    .lines()
                    .map(str::trim)
                    .filter(|l| !l.is_empty() && !l.starts_with('#') && !l.starts_with("format"))
                    .map(String::from)
                    .collect();
                format!("model: {}", lines.join(" "))
            }
        }
    }

    /// The assumptions measured on the model (from [`Theory::from_model`]; empty from
    /// [`Theory::new`]).
    pub fn assumptions(&self) -> &[Assumption] {
        &self.assumptions
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

    /// σ1, the amplitude diffusion (Eq. 26) of the additive noise.
    pub fn diffusion(&self) -> f64 {
        self.sigma1
    }

    /// b(A) = σ1 + b_1A², the diffusion of the amplitude with multiplicative noise.
    pub fn diffusion_at(&self, a: f64) -> f64 {
        self.sigma1 + self.multiplicative * a * a
    }

    /// b_1 of the multiplicative noise's diffusion b_1A² (0 without it).
    pub fn multiplicative_diffusion(&self) -> f64 {
        self.multiplicative
    }

    /// q of the multiplicative noise's drift correction qA (0 without it).
    pub fn multiplicative_correction(&self) -> f64 {
        self.correction
    }

    /// m_c(A) = σ1/(2A) + qA, the drift correction of the noise (+∞ at A = 0 with σ1 > 0).
    pub fn drift_correction(&self, a: f64) -> f64 {
        let additive = if self.sigma1 > 0.0 {
            self.sigma1 / (2.0 * a)
        } else {
            0.0
        };
        additive + self.correction * a
    }

    /// Whether the amplitude diffuses (additive or multiplicative noise).
    pub fn noisy(&self) -> bool {
        self.sigma1 > 0.0 || self.multiplicative > 0.0
    }

    /// The phase velocity's shift at amplitude A from the restoring force's nonlinearity:
    /// β2⟨cos φ·k_nl(A cos φ)⟩/(ω1A) = β2(3k3A²/8 + 5k5A⁴/16)/ω1 (0 for the paper family).
    pub fn frequency_shift(&self, a: f64) -> f64 {
        let Some(m) = &self.model else { return 0.0 };
        let (k3, k5, x) = (m.restoring.cubic, m.restoring.quintic, a * a);
        self.eq.beta2 * (3.0 * k3 * x / 8.0 + 5.0 * k5 * x * x / 16.0) / self.eq.omega1
    }

    /// f(A)/A as a polynomial in x = A².
    pub fn drift_polynomial(&self) -> &Polynomial {
        &self.g
    }

    /// A·m1(A) as a polynomial in x = A² (additive noise; with multiplicative noise the
    /// polynomial whose positive roots are the extrema of P(A)).
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

    /// FPK drift m1(A) = f(A) + m_c(A), m_c = σ1/(2A) + qA (Eq. 26 for additive noise); at
    /// A = 0 its limit: +∞ when σ1 > 0, else f(0) = 0.
    pub fn fpk_drift(&self, a: f64) -> f64 {
        if a == 0.0 {
            return if self.fpk.eval(0.0) > 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
        }
        self.fpk.eval(a * a) / a
    }

    /// U_eff(A) = −∫₀^A f − (σ1/2) ln A (Eq. 23); with multiplicative noise
    /// −∫₀^A (f + m_c − b′/2), whose wells and crests are the modes and antimodes of P(A).
    pub fn potential(&self, a: f64) -> f64 {
        let x = a * a;
        let mut poly = -0.5 * self.g_integral.eval(x);
        let shift = self.correction - self.multiplicative;
        if shift != 0.0 {
            poly -= 0.5 * shift * x;
        }
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

    /// Every positive root of m1 (the extrema of P(A)) when the amplitude diffuses, else the
    /// limit cycles.
    pub fn cycles(&self) -> Vec<Cycle> {
        if self.noisy() {
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
        stable_count(if self.noisy() { &self.h } else { &self.g })
    }

    /// Extrema of U_eff, ascending in A (with the rest state A = 0 when D = 0).
    pub fn extrema(&self) -> Vec<Extremum> {
        let mut out = Vec::new();
        if !self.noisy() {
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

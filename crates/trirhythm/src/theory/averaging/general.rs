//! The averaged theory of a model of the class: equivalent linearisation, the drift by phase
//! quadrature, the diffusion and drift correction of additive and multiplicative noise.
//!
//! Equation (balance at ω_b = ω0, the paper's Eq. 4 rule applied to every fractional term, or
//! at the fixed point ω_b = ω1(ω_b), [`Balance::SelfConsistent`]):
//! D^{1+λ}U ≈ mÜ + cU̇, m = ω_b^{λ−1} sin(πλ/2), c = ω_b^λ cos(πλ/2);
//! K_j D^{α_j}U ≈ s_jU + c_jU̇, s_j = K_jω_b^{α_j} cos(πα_j/2), c_j = K_jω_b^{α_j−1} sin(πα_j/2);
//! so Ü + ω1²U = β2[(h − c − Σc_j)U̇ − k_nl(U) + η_a + Uη_m], β2 = 1/m, ω1² = β2(ω0² + Σs_j).
//! With Z = A cos φ, Ż = −Aω1 sin φ (U = |Z| for the wall at 0):
//! f(A) = β2A⟨(h(A cos φ, −Aω1 sin φ) − c − Σc_j) sin²φ⟩ − κA, κ = −ω1 ln r/π (wall) or 0;
//! k_nl drops out (⟨sin φ·k_nl(A cos φ)⟩ = 0) and shifts the frequency by
//! β2⟨cos φ·k_nl(A cos φ)⟩/(ω1A) = β2(3k3A²/8 + 5k5A⁴/16)/ω1.
//! Additive noise (Ȧ-coefficient G = −β2σ sin φ/ω1, σ = sgn cos φ with the wall, else 1):
//! b_a = (β2²/ω1²)·Σ_k b_k² S_a(2kω1)/2 with the wall (b_k of sgn(cos φ) sin φ = Σb_k sin 2kφ),
//! (β2²/ω1²)·S_a(ω1)/2 without, S(ν) = 2D/(1 + τ²ν²); drift correction m_c = b_a/(2A).
//! Multiplicative noise (G = −β2A cos φ sin φ/ω1, θ̇-coefficient H = −β2 cos²φ/ω1, as σ|Z| = Z):
//! b_m = β2²A²S_m(2ω1)/(8ω1²), m_c = 3β2²A·S_m(2ω1)/(16ω1²). Without a wall the cross terms of
//! correlated noises vanish at first order (G_a has harmonic 1, G_m and H_m harmonics 0 and 2).
//! FPK: dA = (f + m_c)dt + √b dW, P(A) ∝ b⁻¹exp∫2(f + m_c)/b, extrema where 2(f + m_c) = b′.
//!
//! Method: h is a polynomial in U² and U̇², so the phase averages are trigonometric
//! polynomials; [`phase_average`] integrates ⟨cos^{2i}φ sin^{2j}φ⟩ exactly by the periodic
//! trapezoidal rule on [`PHASE_NODES`] nodes (more than the degree 2(i + j) ≤ 44), carried in
//! double-double so that each average is the exact rational (2i − 1)!!(2j − 1)!!/(2(i + j))!!
//! rounded once (the closed form's weights bit for bit, so that for the paper's model the two
//! routes' g and P(A) are equal; the trapezoid in doubles, two ulps off in w_1 and w_3, moved
//! ln P(A) by up to 9e-11 relative at small σ1), and f/A = g(x), x = A², is assembled as a
//! polynomial: the certified roots of
//! [`crate::theory::polynomial`] give the cycles unchanged. The noise's phase correlations
//! C(ψ) = ⟨G(φ)G(φ + ψ)⟩ are sums of cos(nψ) (the harmonics of G are known), so the
//! integrals against the OU correlation are the spectrum at those harmonics, exactly;
//! ∫m_c and b are polynomials in x too: A·(f + m_c) = x g(x) + b_a/2 + q x with
//! q = 3β2²S_m(2ω1)/(16ω1²), b = b_a + b_1 x with b_1 = β2²S_m(2ω1)/(8ω1²), and the extrema of
//! P(A) are the positive roots of x g(x) + b_a/2 + (q − b_1)x; P(A) itself is
//! [`super::AmplitudePdf`] (the closed form of `shape.rs`). For the paper's model with its
//! wall the coefficients are those of [`Theory::new`], which [`Theory::from_model`] returns
//! (same bits); the route by quadrature is [`Theory::by_quadrature`].
//!
//! Reference: the paper (Eq. 4, 18, 26); Khasminskii's stochastic averaging; Zhuravlev's
//! transformation; for the multiplicative terms, the second-moment boundary D_c = 2ζω³ of
//! Ü + 2ζωU̇ + ω²U = Uη_m; `model-class.md` §6 of the project's design notes.
//!
//! Tests: `tests/averaging.rs`: `quadrature_is_the_closed_form` (the paper family both ways to
//! 1e-12, every phase average the exact rational rounded once), `multiplicative_noise_gives_the_exact_moment_boundary`,
//! `rayleigh_van_der_pol_cycle_is_its_closed_form`, `duffing_leaves_the_drift_and_shifts_the_frequency`,
//! `fractional_damping_enters_as_its_harmonic_balance`.

use super::applies::{
    applies, wall_at_zero, Assumption, BALANCE_LIMIT, DAMPING_LIMIT, DUFFING_LIMIT, METHOD,
};
use super::{Theory, Variant};
use crate::error::{Error, Exact, Result};
use crate::maths::{pow, sin};
use crate::model::{Equivalents, Model, Params};
use crate::theory::polynomial::Polynomial;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Nodes of the periodic trapezoidal rule of [`phase_average`]: exact for trigonometric
/// polynomials of degree below it; h of degree ≤ 40 in U and U̇ times sin²φ has degree ≤ 44.
pub const PHASE_NODES: usize = 128;

/// ⟨cos^{2i}φ sin^{2j}φ⟩ over a period, by the periodic trapezoidal rule on [`PHASE_NODES`]
/// nodes (exact for 2(i + j) < [`PHASE_NODES`]), in double-double: the nodes' cos²φ and sin²φ
/// from Taylor series on the first octant, the powers and the sum carried to ~1e-30, so that
/// the rule's value is the exact average rounded once (checked for i + j ≤ 22; the closed
/// form [`super::phase_average_weight`]'s bits where that is exact, as for every k ≤ 27 of
/// ⟨cos^{2k}φ sin²φ⟩).
pub fn phase_average(i: usize, j: usize) -> f64 {
    let nodes = phase_nodes();
    let quarter = PHASE_NODES / 4;
    // cos² and sin² have period π and are even about 0 and π/2: node m of the first quadrant
    // stands for 4 of the n nodes (2 for m = 0 and m = n/4)
    let mut sum = (0.0, 0.0);
    for (m, &(c2, s2)) in nodes.iter().enumerate() {
        let mut term = (1.0, 0.0);
        for _ in 0..i {
            term = dd_mul(term, c2);
        }
        for _ in 0..j {
            term = dd_mul(term, s2);
        }
        let copies = if m == 0 || m == quarter { 2.0 } else { 4.0 };
        sum = dd_add(sum, (copies * term.0, copies * term.1));
    }
    // n is a power of two: the division is exact
    (sum.0 + sum.1) / PHASE_NODES as f64
}

/// A double-double: the unevaluated sum hi + lo, |lo| ≤ ulp(hi)/2.
type DoubleDouble = (f64, f64);

/// cos²φ and sin²φ at the nodes φ = 2πm/n, m = 0..=n/4, as double-doubles.
fn phase_nodes() -> &'static [(DoubleDouble, DoubleDouble)] {
    static NODES: std::sync::OnceLock<Vec<(DoubleDouble, DoubleDouble)>> =
        std::sync::OnceLock::new();
    NODES.get_or_init(|| {
        const _: () = assert!(PHASE_NODES % 8 == 0);
        let (quarter, eighth) = (PHASE_NODES / 4, PHASE_NODES / 8);
        (0..=quarter)
            .map(|m| {
                // φ = 2πm/n, or its complement π/2 − φ on the second octant (cos ↔ sin)
                let (k, swap) = if m <= eighth {
                    (m, false)
                } else {
                    (quarter - m, true)
                };
                let (c, s) = cos_sin_octant(dd_mul(TWO_PI, (k as f64 / PHASE_NODES as f64, 0.0)));
                let (c2, s2) = (dd_mul(c, c), dd_mul(s, s));
                if swap {
                    (s2, c2)
                } else {
                    (c2, s2)
                }
            })
            .collect()
    })
}

/// 2π as a double-double.
const TWO_PI: DoubleDouble = (std::f64::consts::TAU, 2.4492935982947064e-16);

/// cos x and sin x for 0 ≤ x ≤ π/4 (a double-double) by their Taylor series in double-double:
/// the n-th terms are at most 0.62^n/(2n)!, below 1e-33 from n = 15 (16 are taken).
fn cos_sin_octant(x: DoubleDouble) -> (DoubleDouble, DoubleDouble) {
    let x2 = dd_mul(x, x);
    let (mut c, mut s) = ((1.0, 0.0), x);
    let (mut tc, mut ts) = ((1.0, 0.0), x);
    for n in 1..=16 {
        let k = (2 * n) as f64;
        // tc ← −tc·x²/((2n − 1)2n), ts ← −ts·x²/(2n(2n + 1))
        tc = dd_div(dd_mul(tc, x2), -(k - 1.0) * k);
        ts = dd_div(dd_mul(ts, x2), -k * (k + 1.0));
        c = dd_add(c, tc);
        s = dd_add(s, ts);
    }
    (c, s)
}

/// a + b exactly as (sum, error).
fn two_sum(a: f64, b: f64) -> DoubleDouble {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Double-double sum.
fn dd_add(a: DoubleDouble, b: DoubleDouble) -> DoubleDouble {
    let (s, e) = two_sum(a.0, b.0);
    let (hi, lo) = two_sum(s, e + a.1 + b.1);
    (hi, lo)
}

/// Double-double product.
fn dd_mul(a: DoubleDouble, b: DoubleDouble) -> DoubleDouble {
    let p = a.0 * b.0;
    let e = a.0.mul_add(b.0, -p) + a.0 * b.1 + a.1 * b.0;
    two_sum(p, e)
}

/// A double-double divided by a double (an integer here, exact in f64).
fn dd_div(a: DoubleDouble, d: f64) -> DoubleDouble {
    let q = a.0 / d;
    // the remainder a − q·d, exact up to a.1's rounding
    let p = q * d;
    let r = (a.0 - p) - q.mul_add(d, -p) + a.1;
    two_sum(q, r / d)
}

/// The equivalent linearisation of a model at ω_b = ω0: Eq. 5's μ1, β1, ω1, β2 generalised
/// (μ1 = β2μ0, β1 = c0 − (c + Σc_j)/μ0), with the equivalent damping c + Σc_j.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearised {
    /// μ1, β1, ω1, β2.
    pub equivalents: Equivalents,
    /// c + Σc_j, the damping of the leading and fractional terms at ω_b.
    pub damping: f64,
    /// The balance frequency ω_b (ω0).
    pub omega_b: f64,
}

/// Where the harmonic balance is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Balance {
    /// ω_b = ω0, the paper's Eq. 4.
    #[default]
    Natural,
    /// ω_b = ω1(ω_b): the balance at the linearised oscillator's own frequency (a fixed point,
    /// found by iteration from ω0).
    SelfConsistent,
}

impl Balance {
    /// `natural` or `self_consistent`.
    pub fn name(self) -> &'static str {
        match self {
            Balance::Natural => "natural",
            Balance::SelfConsistent => "self_consistent",
        }
    }
}

/// The equivalent linearisation of `model` (valid) at ω_b = ω0; with no fractional term
/// exactly [`Equivalents::from_scalars`] (the same bits as the paper's Eq. 5).
pub fn linearise(model: &Model) -> Linearised {
    let (l, w0, mu0) = (
        model.leading.lambda,
        model.restoring.omega0,
        model.damping.mu0,
    );
    if model.fractional.iter().all(|f| f.coefficient == 0.0) {
        let c0 = model.damping.coefficients.first().copied().unwrap_or(0.0);
        return Linearised {
            equivalents: Equivalents::from_scalars(mu0, w0, l, c0),
            damping: pow(w0, l) * sin(PI * (1.0 - l) / 2.0),
            omega_b: w0,
        };
    }
    linearise_at(model, w0)
}

/// The equivalent linearisation of `model` (valid) at the balance frequency `omega_b`.
pub fn linearise_at(model: &Model, omega_b: f64) -> Linearised {
    let (l, w0, mu0, wb) = (
        model.leading.lambda,
        model.restoring.omega0,
        model.damping.mu0,
        omega_b,
    );
    let c0 = model.damping.coefficients.first().copied().unwrap_or(0.0);
    // m = ω_b^{λ−1} sin(πλ/2), c = ω_b^λ cos(πλ/2) (cos(πλ/2) = sin(π(1 − λ)/2): exact 0 at 1)
    let beta2 = pow(wb, 1.0 - l) / sin(PI * l / 2.0);
    let leading = pow(wb, l) * sin(PI * (1.0 - l) / 2.0);
    let (mut stiff, mut damp) = (0.0, 0.0);
    for f in model.fractional.iter().filter(|f| f.coefficient != 0.0) {
        let a = f.order;
        stiff += f.coefficient * pow(wb, a) * sin(PI * (1.0 - a) / 2.0);
        damp += f.coefficient * pow(wb, a - 1.0) * sin(PI * a / 2.0);
    }
    let damping = leading + damp;
    Linearised {
        equivalents: Equivalents {
            mu1: beta2 * mu0,
            beta1: c0 - damping / mu0,
            omega1: (beta2 * (w0 * w0 + stiff)).sqrt(),
            beta2,
        },
        damping,
        omega_b: wb,
    }
}

/// The linearisation at the balance `balance` asks for: ω0, or the fixed point ω_b = ω1(ω_b)
/// (iterated from ω0 to 4ε relative; the map is a contraction for the class's ranges, its slope
/// (1 − λ)/2 + Σ O(K_j) near 1 − λ ≪ 1).
pub fn linearise_with(model: &Model, balance: Balance) -> Result<Linearised> {
    if balance == Balance::Natural {
        return Ok(linearise(model));
    }
    let mut wb = model.restoring.omega0;
    for _ in 0..200 {
        let lin = linearise_at(model, wb);
        let next = lin.equivalents.omega1;
        if (next - wb).abs() <= 4.0 * f64::EPSILON * wb {
            return Ok(linearise_at(model, next));
        }
        wb = next;
    }
    Err(Error::NoConvergence {
        what: "the self-consistent balance frequency ω_b = ω1(ω_b)",
        detail: format!(
            "200 iterations from ω0 = {} end at ω_b = {}",
            Exact(model.restoring.omega0),
            Exact(wb)
        ),
    })
}

/// S(ν) = 2D/(1 + τ²ν²), the spectrum of ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ} (2Dδ at τ = 0).
fn spectrum(d: f64, tau: f64, nu: f64) -> f64 {
    2.0 * d / (1.0 + tau * tau * nu * nu)
}

/// The coefficients of the averaged amplitude equation, before they are put into a [`Theory`].
pub(super) struct Averaged {
    pub eq: Equivalents,
    pub loss_rate: f64,
    /// g(x) = f/A without the loss.
    pub g: Polynomial,
    /// b_a, the additive diffusion.
    pub additive: f64,
    /// b_1: the multiplicative diffusion is b_1 A².
    pub multiplicative: f64,
    /// q: the multiplicative drift correction is q A.
    pub correction: f64,
}

/// The averaged coefficients of `model` by quadrature; `wall` is the restitution of the wall
/// at 0 (none: no wall). The paper variant takes the printed κ and σ1 (paper family only).
pub(super) fn average(
    model: &Model,
    variant: Variant,
    wall: Option<f64>,
    lin: &Linearised,
) -> Result<Averaged> {
    let eq = lin.equivalents;
    let (b2, w1) = (eq.beta2, eq.omega1);
    let loss_rate = match wall {
        Some(r) => {
            if variant == Variant::Consistent && r == 0.0 {
                return Err(Error::invalid(
                    "wall.0.restitution",
                    r,
                    "(0, 1] for the consistent variant (r = 0 gives an infinite loss ω1 ln(r)/π)",
                ));
            }
            eq.loss_rate(variant, r)
        }
        None => 0.0,
    };
    // g = β2⟨(μ0P(A cos φ) + Σd_k(Aω1 sin φ)^{2k} − c − Σc_j) sin²φ⟩, in the paper's grouping
    // μ1(β1 − c0 + P): μ1 = β2μ0, β1 = c0 − (c + Σc_j)/μ0
    let p = &model.damping.coefficients;
    let n = p.len().max(model.damping.rayleigh.len() + 1);
    let mut gc = vec![0.0; n];
    for (k, &c) in p.iter().enumerate() {
        gc[k] = eq.mu1 * if k == 0 { eq.beta1 } else { c } * phase_average(k, 1);
    }
    let mut w1k = 1.0;
    for (k, &d) in model.damping.rayleigh.iter().enumerate() {
        w1k *= w1 * w1;
        gc[k + 1] += b2 * d * w1k * phase_average(0, k + 2);
    }
    let additive = match model.noise.additive {
        None => 0.0,
        Some(a) => match wall {
            Some(_) => eq.diffusion(variant, a.intensity, a.correlation_time),
            None => b2 * b2 / (w1 * w1) * spectrum(a.intensity, a.correlation_time, w1) / 2.0,
        },
    };
    let (multiplicative, correction) = match model.noise.multiplicative {
        None => (0.0, 0.0),
        Some(m) => {
            let s = spectrum(m.intensity, m.correlation_time, 2.0 * w1);
            let unit = b2 * b2 * s / (w1 * w1);
            (unit / 8.0, 3.0 * unit / 16.0)
        }
    };
    Ok(Averaged {
        eq,
        loss_rate,
        g: Polynomial::new(gc),
        additive,
        multiplicative,
        correction,
    })
}

/// The paper family's [`Params`] a general theory reports (headers, the PDF's messages): μ0,
/// ω0, λ, P(U), the additive (D, τ) and the wall's r (1 without a wall); the model itself is
/// [`Theory::model`].
fn projection(model: &Model, wall: Option<f64>) -> Params {
    let (d, tau) = model
        .noise
        .additive
        .map_or((0.0, 0.0), |a| (a.intensity, a.correlation_time));
    Params {
        mu0: model.damping.mu0,
        omega0: model.restoring.omega0,
        lambda: model.leading.lambda,
        restitution: wall.unwrap_or(1.0),
        damping: model.polynomial(),
        noise_intensity: d,
        correlation_time: tau,
    }
}

impl Theory {
    /// The averaged theory of `model` in `variant`, or the refusal naming the term it does not
    /// cover ([`super::applies`]). The paper's Eq. (1) with its wall at 0 returns
    /// [`Theory::new`] (the closed forms, same bits); every other model is averaged by
    /// quadrature ([`Theory::by_quadrature`]). The assumptions measured are
    /// [`Theory::assumptions`]; a Duffing shift beyond [`DUFFING_LIMIT`] at a cycle is refused.
    pub fn from_model(model: &Model, variant: Variant) -> Result<Theory> {
        Theory::from_model_with(model, variant, Balance::Natural)
    }

    /// [`Theory::from_model`] with the harmonic balance at `balance`; the self-consistent
    /// balance takes the quadrature route also for the paper's model, and refuses
    /// [`Variant::Paper`] (whose formulas balance at ω0).
    pub fn from_model_with(model: &Model, variant: Variant, balance: Balance) -> Result<Theory> {
        let mut assumptions = applies(model, variant)?;
        let wall = wall_at_zero(model)?;
        if balance == Balance::SelfConsistent && variant == Variant::Paper {
            return Err(Error::NotApplicable {
                method: METHOD.to_string(),
                assumption: "the balance at ω0 for --variant paper".into(),
                reason: "the paper variant's formulas balance at ω0 (Eq. 4): use the \
                         consistent variant for the self-consistent balance"
                    .into(),
            });
        }
        let lin = linearise_with(model, balance)?;
        let mut th = match (model.paper_family(METHOD), wall, balance) {
            (Ok(family), Some(_), Balance::Natural) => Theory::new(&family.params, variant)?,
            _ => Theory::quadrature(model, variant, wall, &lin)?,
        };
        if balance == Balance::SelfConsistent {
            th.model = Some(Box::new(model.clone()));
            let w1 = lin.equivalents.omega1;
            for a in assumptions.iter_mut().filter(|a| a.name == "|ω_b − ω1|/ω1") {
                *a = Assumption::new(a.name.clone(), (lin.omega_b - w1).abs() / w1, a.limit);
            }
        }
        assumptions.extend(th.measured_assumptions(model, &lin)?);
        th.assumptions = assumptions;
        Ok(th)
    }

    /// The averaged theory of `model` by phase quadrature, also for the paper family (the route
    /// `quadrature_is_the_closed_form` checks against [`Theory::new`]); the same refusals as
    /// [`Theory::from_model`].
    pub fn by_quadrature(model: &Model, variant: Variant) -> Result<Theory> {
        let mut assumptions = applies(model, variant)?;
        let wall = wall_at_zero(model)?;
        let lin = linearise(model);
        let mut th = Theory::quadrature(model, variant, wall, &lin)?;
        assumptions.extend(th.measured_assumptions(model, &lin)?);
        th.assumptions = assumptions;
        Ok(th)
    }

    fn quadrature(
        model: &Model,
        variant: Variant,
        wall: Option<f64>,
        lin: &Linearised,
    ) -> Result<Theory> {
        let av = average(model, variant, wall, lin)?;
        let paper = model.paper_family(METHOD).is_ok() && wall.is_some();
        let mut th = Theory::assemble(
            projection(model, wall),
            variant,
            av.eq,
            av.loss_rate,
            av.g,
            av.additive,
            av.multiplicative,
            av.correction,
        );
        if !paper {
            th.model = Some(Box::new(model.clone()));
        }
        Ok(th)
    }

    /// The assumptions measured at the cycles found: the damping strength and the Duffing
    /// shift on the largest; a shift beyond [`DUFFING_LIMIT`] is refused.
    fn measured_assumptions(&self, model: &Model, lin: &Linearised) -> Result<Vec<Assumption>> {
        let largest = self
            .limit_cycles()
            .into_iter()
            .chain(self.cycles())
            .map(|c| c.amplitude)
            .fold(0.0, f64::max);
        let (b2, w1) = (lin.equivalents.beta2, lin.equivalents.omega1);
        let strength = (0..PHASE_NODES)
            .map(|k| {
                let p = 2.0 * PI * k as f64 / PHASE_NODES as f64;
                let (u, v) = (largest * p.cos(), -largest * w1 * p.sin());
                let rayleigh = model
                    .damping
                    .rayleigh
                    .iter()
                    .rev()
                    .fold(0.0, |acc, &d| (acc + d) * v * v);
                (model.damping.mu0 * model.polynomial().eval(u) + rayleigh - lin.damping).abs()
            })
            .fold(0.0, f64::max)
            * b2
            / w1;
        let k = &model.restoring;
        let a2 = largest * largest;
        let shift = (k.cubic.abs() * a2 + k.quintic.abs() * a2 * a2) / (k.omega0 * k.omega0);
        if shift > DUFFING_LIMIT {
            return Err(Error::NotApplicable {
                method: METHOD.to_string(),
                assumption: format!(
                    "a weak Duffing shift (|k3|A² + |k5|A⁴)/ω0² ≤ {DUFFING_LIMIT} at every cycle"
                ),
                reason: format!(
                    "restoring.cubic = {}, restoring.quintic = {} give {} at the cycle A = {}: \
                     the restoring force is no small correction to the oscillation there",
                    Exact(k.cubic),
                    Exact(k.quintic),
                    crate::error::Readable(shift),
                    crate::error::Readable(largest)
                ),
            });
        }
        // the response frequency ω1 + Δω moves away from the balance frequency ω_b
        let x = a2;
        let dw = b2 * (3.0 * k.cubic * x / 8.0 + 5.0 * k.quintic * x * x / 16.0) / w1;
        Ok(vec![
            Assumption::new("β2·max|h − c − Σc_j|/ω1", strength, DAMPING_LIMIT),
            Assumption::new("(|k3|A² + |k5|A⁴)/ω0²", shift, DUFFING_LIMIT),
            Assumption::new(
                "|Δω|/ω1 (Duffing frequency shift)",
                dw.abs() / w1,
                BALANCE_LIMIT,
            ),
        ])
    }
}

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

use crate::error::{Error, Exact, Readable, Result};
use crate::model::{Equivalents, Params};
use crate::theory::polynomial::Polynomial;
use crate::theory::quadrature::integrate_with_breakpoints;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which form of the averaged formulas to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// The paper's formulas as printed (Eq. 27's typo fixed).
    #[default]
    Paper,
    /// The corrected, self-consistent formulas: exact impact loss ω1A ln(r)/π, the coloured
    /// noise averaged through sgn(Z), ΔE = 2πω1Af.
    Consistent,
}

impl Variant {
    /// `paper` or `consistent`.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Paper => "paper",
            Variant::Consistent => "consistent",
        }
    }
}

impl Equivalents {
    /// The impact loss rate κ of the averaged drift (−κA): (1−r)ω1/π (paper) or −ω1 ln(r)/π
    /// (consistent; +∞ at r = 0, which [`Theory::new`] rejects).
    #[inline]
    pub fn loss_rate(&self, variant: Variant, r: f64) -> f64 {
        match variant {
            Variant::Paper => (1.0 - r) * self.omega1 / PI,
            Variant::Consistent => -r.ln() * self.omega1 / PI,
        }
    }

    /// The amplitude diffusion σ1 (Eq. 26) for noise intensity D and correlation time τ:
    /// β2D/(ω1²(1+τ²)) (paper) or (β2²D/ω1²) Σ_k b_k²/(1+4k²τ²ω1²) (consistent).
    #[inline]
    pub fn diffusion(&self, variant: Variant, d: f64, tau: f64) -> f64 {
        let w1 = self.omega1;
        match variant {
            Variant::Paper => self.beta2 * d / (w1 * w1 * (1.0 + tau * tau)),
            Variant::Consistent => {
                self.beta2 * self.beta2 * d / (w1 * w1)
                    * sgn_harmonic_sum(4.0 * tau * tau * w1 * w1)
            }
        }
    }
}

/// w_k = ⟨cos^{2k}φ sin²φ⟩ over a period = C(2k, k) / (4^k (2k + 2)).
pub fn phase_average_weight(k: usize) -> f64 {
    // C(2k,k)/4^k = Π_{j=1..k} (2j−1)/(2j)
    let mut w = 1.0;
    for j in 1..=k {
        w *= (2 * j - 1) as f64 / (2 * j) as f64;
    }
    w / (2 * k + 2) as f64
}

/// Σ_{k≥1} b_k²/(1 + c k²), b_k = 8k(−1)^{k+1}/(π(4k²−1)), in closed form; 1 at c = 0.
///
/// With q = k², b_k²/(1+ck²) = (4/π²) q/((q−¼)²(1+cq)) = (4/π²)[A/(q−¼) + B/(q−¼)² + C/(1+cq)],
/// A = 16/(4+c)², B = 1/(4+c), C = −16c/(4+c)², and Σ1/(k²−¼) = 2, Σ1/(k²−¼)² = π² − 8,
/// Σ1/(1+ck²) = (πa coth(πa) − 1)/2 with a = 1/√c. The unit test checks it against the series.
pub fn sgn_harmonic_sum(c: f64) -> f64 {
    if c == 0.0 {
        return 1.0;
    }
    let den = 4.0 + c;
    let a_ = 16.0 / (den * den);
    let b_ = 1.0 / den;
    let c_ = -16.0 * c / (den * den);
    let pa = PI / c.sqrt();
    // πa coth(πa) − 1, accurate for small πa too.
    let t = if pa < 1e-4 {
        pa * pa / 3.0
    } else {
        pa / pa.tanh() - 1.0
    };
    4.0 / (PI * PI) * (2.0 * a_ + b_ * (PI * PI - 8.0) + c_ * t / 2.0)
}

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

    /// The amplitude equation (Eq. 24) = −2 m1/(μ1 A).
    pub fn amplitude_equation(&self, a: f64) -> f64 {
        -2.0 * self.fpk_drift(a) / (self.eq.mu1 * a)
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

/// Narrowest peak, relative to its amplitude, that a PDF is computed for: a width of 1e-12·A
/// is still ~5000 ulps; at D → 0 the density becomes a delta function that doubles cannot hold.
pub const MIN_RELATIVE_WIDTH: f64 = 1e-12;

/// The stationary amplitude PDF P(A) = N0 (A/σ1) e^{S(A)}, held in log form.
#[derive(Debug, Clone)]
pub struct AmplitudePdf {
    sigma1: f64,
    omega1: f64,
    g_integral: Polynomial,
    /// The highest mode A_p, and G(A_p²) = ∫₀^{A_p²} g as a double-double (hi, lo).
    peak: f64,
    peak_g: (f64, f64),
    /// ln ∫ P̃ dA for P̃(A) = (A/A_p) e^{S(A) − S(A_p)}: ln P(A) = ln P̃(A) − log_mass.
    log_mass: f64,
    /// Amplitudes of the maxima of P(A) (ascending).
    pub modes: Vec<f64>,
    /// Amplitudes of the interior minima of P(A) (ascending).
    pub antimodes: Vec<f64>,
    /// ⟨A⟩ = ∫A P(A) dA.
    pub mean_amplitude: f64,
    /// Amplitude beyond which P(A) < e^{−46} P_max (the quadrature's upper limit).
    pub support_end: f64,
    /// Width |φ″(m)|^{−1/2} of each mode's peak (φ = ln P), in the order of `modes`: the
    /// Gaussian standard deviation of the peak (1e−3·m where the curvature vanishes).
    pub mode_widths: Vec<f64>,
}

impl AmplitudePdf {
    fn new(th: &Theory) -> Result<Self> {
        let s1 = th.sigma1;
        if s1 <= 0.0 {
            return Err(Error::Undefined {
                what: "stationary amplitude PDF",
                why: format!(
                    "needs noise: D = {} gives σ1 = 0",
                    th.params.noise_intensity
                ),
            });
        }
        if th.g.leading() >= 0.0 {
            let c = &th.params.damping.coefficients;
            let k = c.iter().rposition(|&x| x != 0.0).unwrap_or(0);
            let (name, value) = crate::model::coefficient_name(k, c[k]);
            return Err(Error::Undefined {
                what: "stationary amplitude PDF",
                why: format!(
                    "P(A) is not normalisable: f(A) must tend to −∞ for large A, which needs the \
                     highest non-zero damping coefficient c_k (of U^2k) to be negative; here it \
                     is c{k} ({name} = {})",
                    crate::error::Exact(value)
                ),
            });
        }
        let extrema = positive_roots(&th.h);
        let modes: Vec<f64> = extrema
            .iter()
            .filter(|c| c.stable)
            .map(|c| c.amplitude)
            .collect();
        let antimodes: Vec<f64> = extrema
            .iter()
            .filter(|c| !c.stable && !c.fold)
            .map(|c| c.amplitude)
            .collect();
        let gi = th.g_integral.clone();
        // φ(A) = ln A + S(A), S = G(A²)/σ1, is huge when σ1 is small: only differences from
        // the highest mode are ever formed, in double-double, so they keep full precision.
        let phi = |a: f64| a.ln() + gi.eval(a * a) / s1;
        let peak = modes
            .iter()
            .copied()
            .max_by(|a, b| phi(*a).total_cmp(&phi(*b)))
            .filter(|&m| phi(m).is_finite())
            .ok_or_else(|| Error::Overflow {
                what: "amplitude PDF",
                at: format!(
                    "its modes: none where ln P(A) is finite (maxima at A = {modes:?}); the \
                     damping polynomial's coefficients put them out of range"
                ),
                value: f64::NAN,
            })?;
        let peak_g = gi.eval_double_double(peak * peak);
        let rel = |a: f64| relative_log(&gi, s1, peak, peak_g, a);
        // Upper limit: beyond the last extremum φ decreases; find φ = φmax − 46.
        let last = extrema.last().map(|c| c.amplitude).unwrap_or(1.0);
        let mut hi = last.max(1e-300) * 1.5 + 1e-3;
        while rel(hi) > -46.0 {
            hi *= 1.5;
            if !hi.is_finite() {
                return Err(Error::Overflow {
                    what: "amplitude PDF support",
                    at: "A → ∞".into(),
                    value: hi,
                });
            }
        }
        // Cuts at the extrema and, around each mode, at m ± w·2^k with w = |φ″(m)|^{−1/2} the
        // peak's width, so that no Gauss–Kronrod panel is much wider than the peak it holds.
        let gd = &th.g_derivative;
        let mut cuts: Vec<f64> = vec![0.0, hi];
        // A peak of width w at amplitude m cannot be resolved better than ε·m/w relative: the
        // quadrature nodes themselves are rounded to ulp(m). The tolerance respects that floor.
        let width = |m: f64| {
            let x = m * m;
            let curvature = -1.0 / x + (2.0 * th.g.eval(x) + 4.0 * x * gd.eval(x)) / s1;
            if curvature < 0.0 {
                (-curvature).sqrt().recip()
            } else {
                1e-3 * m
            }
        };
        let mode_widths: Vec<f64> = modes.iter().map(|&m| width(m)).collect();
        // A peak a few ulps wide is a delta function to double precision: its normalisation is
        // rounding noise. Refuse instead of printing it.
        if let Some((&m, &w)) = modes
            .iter()
            .zip(&mode_widths)
            .find(|&(&m, &w)| w.is_nan() || w < MIN_RELATIVE_WIDTH * m)
        {
            return Err(Error::Undefined {
                what: "stationary amplitude PDF",
                why: format!(
                    "its peak at A = {} has width {}, below the {MIN_RELATIVE_WIDTH:e}·A that \
                     double precision resolves: the density is a delta function to this \
                     precision (σ1 = {} from D = {}; a larger D widens it)",
                    Readable(m),
                    Readable(w),
                    Readable(s1),
                    Exact(th.params.noise_intensity)
                ),
            });
        }
        let mut resolution: f64 = 0.0;
        for (i, c) in extrema.iter().enumerate() {
            if c.amplitude >= hi {
                continue;
            }
            cuts.push(c.amplitude);
            if !c.stable {
                continue;
            }
            let m = c.amplitude;
            let w = width(m);
            resolution = resolution.max(m / w);
            let left = if i > 0 { extrema[i - 1].amplitude } else { 0.0 };
            let right = extrema.get(i + 1).map_or(hi, |n| n.amplitude.min(hi));
            let mut step = w;
            while m - step > left || m + step < right {
                for cut in [m - step, m + step] {
                    if cut > left && cut < right {
                        cuts.push(cut);
                    }
                }
                step *= 2.0;
            }
        }
        cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        cuts.dedup();
        let scaled = |a: f64| rel(a).exp();
        let tolerance = (4.0 * f64::EPSILON * resolution).max(1e-13);
        let mass = integrate_with_breakpoints(&scaled, &cuts, tolerance);
        let first = integrate_with_breakpoints(&|a: f64| a * scaled(a), &cuts, tolerance);
        if !(mass.is_finite() && mass > 0.0) {
            return Err(Error::Overflow {
                what: "amplitude PDF normalisation",
                at: format!("modes {modes:?}"),
                value: mass,
            });
        }
        Ok(AmplitudePdf {
            sigma1: s1,
            omega1: th.eq.omega1,
            g_integral: gi,
            peak,
            peak_g,
            log_mass: mass.ln(),
            modes,
            antimodes,
            mean_amplitude: first / mass,
            support_end: hi,
            mode_widths,
        })
    }

    /// ln P(A) (−∞ for A ≤ 0).
    pub fn log_density(&self, a: f64) -> f64 {
        if a <= 0.0 {
            return f64::NEG_INFINITY;
        }
        relative_log(&self.g_integral, self.sigma1, self.peak, self.peak_g, a) - self.log_mass
    }

    /// P(A).
    pub fn density(&self, a: f64) -> f64 {
        self.log_density(a).exp()
    }

    /// ln P(H) at energy H = ω1²A²/2 (Eq. 29): P(H) = P(A)/(ω1²A).
    pub fn log_energy_density(&self, h: f64) -> f64 {
        if h <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let a = (2.0 * h).sqrt() / self.omega1;
        // ln P(A) − ln(ω1² A).
        self.log_density(a) - (self.omega1 * self.omega1 * a).ln()
    }

    /// P(H).
    pub fn energy_density(&self, h: f64) -> f64 {
        self.log_energy_density(h).exp()
    }

    /// ln P(U, U̇) on the physical half-plane U ≥ 0 (Eq. 30–31): 2 P(A)/(2πω1A),
    /// A² = U² + U̇²/ω1²; −∞ for U < 0.
    pub fn log_joint_density(&self, u: f64, v: f64) -> f64 {
        if u < 0.0 {
            return f64::NEG_INFINITY;
        }
        let x = u * u + v * v / (self.omega1 * self.omega1);
        // ln[P(A)/A] = S(A) − S(A_p) − ln A_p − log_mass, finite at A = 0.
        let dg = self.g_integral.eval_double_double(x);
        ((dg.0 - self.peak_g.0) + (dg.1 - self.peak_g.1)) / self.sigma1
            - self.peak.ln()
            - self.log_mass
            - (PI * self.omega1).ln()
    }

    /// P(U, U̇).
    pub fn joint_density(&self, u: f64, v: f64) -> f64 {
        self.log_joint_density(u, v).exp()
    }

    /// ∫ P(A) dA over [a, b], by the same quadrature as the normalisation.
    pub fn probability(&self, a: f64, b: f64) -> f64 {
        let a = a.max(0.0);
        let b = b.min(self.support_end);
        if a >= b {
            return 0.0;
        }
        let mut cuts = vec![a];
        cuts.extend(
            self.modes
                .iter()
                .chain(&self.antimodes)
                .copied()
                .filter(|&m| m > a && m < b),
        );
        // around each peak, cuts at m ± w·2^k (w its width), as in the normalisation: a peak
        // much narrower than the interval is otherwise missed by the first panels
        for (&m, &w) in self.modes.iter().zip(&self.mode_widths) {
            let mut step = w;
            while step < b - a && (m - step > a || m + step < b) {
                cuts.extend([m - step, m + step].into_iter().filter(|&c| c > a && c < b));
                step *= 2.0;
            }
        }
        cuts.sort_by(|x, y| x.partial_cmp(y).unwrap());
        cuts.dedup();
        cuts.push(b);
        integrate_with_breakpoints(&|x: f64| self.density(x), &cuts, 1e-12)
    }
}

/// ln[(A/A_p) e^{S(A) − S(A_p)}] with S(A) − S(A_p) = [G(A²) − G(A_p²)]/σ1 in double-double.
fn relative_log(gi: &Polynomial, s1: f64, peak: f64, peak_g: (f64, f64), a: f64) -> f64 {
    if a <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let g = gi.eval_double_double(a * a);
    (a / peak).ln() + ((g.0 - peak_g.0) + (g.1 - peak_g.1)) / s1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_match_the_paper() {
        let paper = [512.0, 128.0, 64.0, 40.0, 28.0, 21.0];
        for (k, &w) in paper.iter().enumerate() {
            assert!(
                (phase_average_weight(k) - w / 1024.0).abs() < 1e-16,
                "k = {k}"
            );
        }
    }

    #[test]
    fn weights_are_the_phase_averages() {
        // Independent check by trapezoidal quadrature over a period (exact for trig polynomials).
        for k in 0..9 {
            let n = 64;
            let avg: f64 = (0..n)
                .map(|i| {
                    let p = 2.0 * PI * i as f64 / n as f64;
                    p.cos().powi(2 * k as i32) * p.sin().powi(2)
                })
                .sum::<f64>()
                / n as f64;
            assert!((avg - phase_average_weight(k)).abs() < 1e-15, "k = {k}");
        }
    }

    /// The series summed directly to K = 10⁶ with the integral of its large-k form as tail
    /// (π/2 − atan(y) written as atan(1/y), which does not cancel for large y).
    fn harmonic_series(c: f64) -> f64 {
        const K: usize = 1_000_000;
        let term =
            |k: f64| 64.0 * k * k / (PI * PI * (4.0 * k * k - 1.0).powi(2)) / (1.0 + c * k * k);
        let head: f64 = (1..=K).rev().map(|k| term(k as f64)).sum();
        let (a, sc) = (K as f64 + 0.5, c.sqrt());
        head + 4.0 / (PI * PI) * (1.0 / a - sc * (1.0 / (sc * a)).atan())
    }

    #[test]
    fn closed_form_harmonic_sum_matches_the_series() {
        assert_eq!(sgn_harmonic_sum(0.0), 1.0);
        for c in [
            1e-9, 1e-4, 0.01, 0.3, 0.81, 1.0, 3.24, 10.0, 100.0, 1e4, 1e7,
        ] {
            let (closed, series) = (sgn_harmonic_sum(c), harmonic_series(c));
            assert!(
                (closed - series).abs() < 1e-11 * series.max(1e-3),
                "c = {c}: {closed} vs {series}"
            );
        }
        // c → 0⁺ is continuous; large c: only k = 1 matters, ≈ b1²/c.
        assert!((sgn_harmonic_sum(1e-12) - 1.0).abs() < 1e-5);
        let b1 = 64.0 / (9.0 * PI * PI);
        assert!((sgn_harmonic_sum(1e6) * 1e6 / b1 - 1.0).abs() < 0.2);
    }
}

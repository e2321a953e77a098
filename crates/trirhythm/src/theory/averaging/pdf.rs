//! The stationary densities of the averaged amplitude equation.
//!
//! Equation (Eq. 27–31): P(A) ∝ (A/σ1) exp(S), S = (2/σ1)∫₀^A f; P(H) = P(A)/(ω1²A) at
//! H = ω1²A²/2; P(U, U̇) = 2 P(A)/(2πω1A) on U ≥ 0 with A² = U² + U̇²/ω1².
//!
//! Method: the density in log space relative to its highest mode, S(A) − S(A_p) formed in
//! double-double, normalised by globally adaptive Gauss–Kronrod quadrature with breakpoints at
//! the extrema and geometrically around each mode.
//!
//! Reference: the paper (Eq. 27–31); stochastic averaging (Khasminskii).
//!
//! Tests: `tests/averaging.rs` (normalisation, Eq. 29 relation, joint PDF mass, reference
//! values).

use super::shape::Shape;
use super::{positive_roots, Cycle, Theory};
use crate::error::{Error, Exact, Readable, Result};
use crate::theory::quadrature::integrate_with_breakpoints;
use std::f64::consts::PI;

/// Narrowest peak, relative to its amplitude, that a PDF is computed for: a width of 1e-12·A
/// is still ~5000 ulps; at D → 0 the density becomes a delta function that doubles cannot hold.
pub const MIN_RELATIVE_WIDTH: f64 = 1e-12;

/// The stationary amplitude PDF P(A) = N0 (A/σ1) e^{S(A)}, held in log form.
#[derive(Debug, Clone)]
pub struct AmplitudePdf {
    omega1: f64,
    /// ln P(A) = ln A + w(A²)/divisor + const.
    shape: Shape,
    /// The highest mode A_p, and w(A_p²) (G(A_p²) = ∫₀^{A_p²} g for additive noise) as a
    /// double-double (hi, lo).
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
    pub(super) fn new(th: &Theory) -> Result<Self> {
        refuse_undefined(th)?;
        let shape = shape_of(th);
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
        let peak = highest_mode(&shape, &modes)?;
        let peak_g = shape.w(peak * peak);
        let rel = |a: f64| relative_log(&shape, peak, peak_g, a);
        // Upper limit: beyond the last extremum φ decreases; find φ = φmax − 46.
        let last = extrema.last().map(|c| c.amplitude).unwrap_or(1.0);
        let hi = support_end(&rel, last)?;
        let mode_widths: Vec<f64> = modes.iter().map(|&m| peak_width(&shape, m)).collect();
        refuse_delta(th, &modes, &mode_widths)?;
        let (cuts, resolution) = breakpoints(&shape, &extrema, hi);
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
            omega1: th.eq.omega1,
            shape,
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
        relative_log(&self.shape, self.peak, self.peak_g, a) - self.log_mass
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
        self.shape.difference(self.shape.w(x), self.peak_g)
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

/// ln[(A/A_p) e^{S(A) − S(A_p)}] with S(A) − S(A_p) = [G(A²) − G(A_p²)]/σ1 in double-double
/// (additive noise; [`Shape`] in general).
fn relative_log(shape: &Shape, peak: f64, peak_g: (f64, f64), a: f64) -> f64 {
    if a <= 0.0 {
        return f64::NEG_INFINITY;
    }
    (a / peak).ln() + shape.difference(shape.w(a * a), peak_g)
}

/// The density's shape: the paper's (constant σ1) or with the multiplicative noise's b(A).
fn shape_of(th: &Theory) -> Shape {
    if th.multiplicative == 0.0 && th.correction == 0.0 {
        return Shape::Additive {
            g_integral: th.g_integral.clone(),
            g: th.g.clone(),
            g_derivative: th.g_derivative.clone(),
            sigma1: th.sigma1,
        };
    }
    let mut p = th.g.clone();
    p.coefficients[0] += th.correction;
    Shape::General {
        p_derivative: p.derivative(),
        p,
        sigma1: th.sigma1,
        b1: th.multiplicative,
    }
}

/// Refuse a density that does not exist: no noise (σ1 = 0), or f(A) not tending to −∞.
fn refuse_undefined(th: &Theory) -> Result<()> {
    if th.multiplicative > 0.0 {
        // ln P ~ (2(g0 + q)/b_1 − 2) ln A at A → 0 without additive noise, and
        // (2(g0 + q)/b_1 − 2) ln A at A → ∞ when g is a constant
        let p0 = th.g.coefficients[0] + th.correction;
        let exponent = 2.0 * p0 / th.multiplicative - 2.0;
        let why = |at: &str| Error::Undefined {
            what: "stationary amplitude PDF",
            why: format!(
                "P(A) ~ A^{} at {at} (the multiplicative noise's b(A) = σ1 + b_1A² with \
                 σ1 = {}, b_1 = {}, and f(A) + m_c(A) ≈ {}·A there): no normalisable \
                 density with a peak at A > 0 (that needs an exponent > 0 at A → 0 and \
                 < −1 at A → ∞)",
                Readable(exponent),
                Readable(th.sigma1),
                Readable(th.multiplicative),
                Readable(p0)
            ),
        };
        if th.sigma1 == 0.0 && exponent <= 0.0 {
            return Err(why("A → 0 (no additive noise)"));
        }
        if th.g.degree() == 0 && exponent >= -1.0 {
            return Err(why("A → ∞"));
        }
        if th.g.degree() == 0 {
            return Ok(());
        }
    } else if th.sigma1 <= 0.0 {
        return Err(Error::Undefined {
            what: "stationary amplitude PDF",
            why: format!(
                "needs noise: D = {} gives σ1 = 0",
                th.params.noise_intensity
            ),
        });
    }
    if th.g.leading() >= 0.0 && th.model.is_some() {
        return Err(Error::Undefined {
            what: "stationary amplitude PDF",
            why: format!(
                "P(A) is not normalisable: f(A) must tend to −∞ for large A, which needs the \
                 highest power of A in f (from damping.coefficients and damping.rayleigh) to \
                 have a negative coefficient; here it is {} A^{}",
                crate::error::Readable(th.g.leading()),
                2 * th.g.degree() + 1
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
    Ok(())
}

/// The highest mode of P(A). φ(A) = ln A + S(A), S = G(A²)/σ1, is huge when σ1 is small: only
/// differences from the highest mode are ever formed, in double-double, so they keep full
/// precision.
fn highest_mode(shape: &Shape, modes: &[f64]) -> Result<f64> {
    let phi = |a: f64| shape.phi(a);
    modes
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
        })
}

/// The amplitude beyond the last extremum `last` where the relative log-density `rel` falls
/// below −46 (the quadrature's upper limit).
fn support_end(rel: &dyn Fn(f64) -> f64, last: f64) -> Result<f64> {
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
    Ok(hi)
}

/// Width |φ″(m)|^{−1/2} of the peak at the mode m (1e−3·m where the curvature vanishes). A
/// peak of width w at amplitude m cannot be resolved better than ε·m/w relative: the
/// quadrature nodes themselves are rounded to ulp(m).
fn peak_width(shape: &Shape, m: f64) -> f64 {
    let curvature = shape.curvature(m * m);
    if curvature < 0.0 {
        (-curvature).sqrt().recip()
    } else {
        1e-3 * m
    }
}

/// A peak a few ulps wide is a delta function to double precision: its normalisation is
/// rounding noise. Refuse instead of printing it.
fn refuse_delta(th: &Theory, modes: &[f64], mode_widths: &[f64]) -> Result<()> {
    if let Some((&m, &w)) = modes
        .iter()
        .zip(mode_widths)
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
                Readable(th.sigma1),
                Exact(th.params.noise_intensity)
            ),
        });
    }
    Ok(())
}

/// The quadrature's breakpoints on [0, hi]: the extrema and, around each mode, m ± w·2^k with
/// w the peak's width, so that no Gauss–Kronrod panel is much wider than the peak it holds;
/// with the largest m/w (the resolution the tolerance must respect).
fn breakpoints(shape: &Shape, extrema: &[Cycle], hi: f64) -> (Vec<f64>, f64) {
    let mut cuts: Vec<f64> = vec![0.0, hi];
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
        let w = peak_width(shape, m);
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
    (cuts, resolution)
}

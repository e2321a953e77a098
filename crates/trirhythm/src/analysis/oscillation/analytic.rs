//! The analytic boundaries: the averaged drift's slope at rest (Eq. 18) and the exact
//! linearisation at U = 0, as margins whose sign says whether a small oscillation grows, their
//! closed forms in μ0, and the bisection on their sign along a plane's ordinate.

use super::{BoundaryPoint, Method, Plane, Side};
use crate::engine::Barrier;
use crate::error::{Error, Result};
use crate::maths::{ln, pow, sin};
use crate::model::Params;
use crate::theory::averaging::{Theory, Variant};
use std::f64::consts::PI;

/// The analytic margin at `p` (validated): positive where the small oscillation grows; `None`
/// where the method does not apply.
pub fn margin(p: &Params, barrier: Barrier, method: &Method) -> Result<Option<f64>> {
    p.validate()?;
    match method {
        Method::Averaging(v) => {
            let q = match barrier {
                Barrier::On => p.clone(),
                Barrier::Off => p.with("r", 1.0)?,
            };
            Ok(Some(Theory::new(&q, *v)?.rest_state_slope()))
        }
        Method::Exact => Ok(exact_margin(p, barrier)),
        Method::Simulation(_) => Err(Error::invalid(
            "method",
            f64::NAN,
            "averaging or exact (a simulation has a growth rate, not a margin)",
        )),
    }
}

/// cos(πλ/2) without cancellation near λ = 1, and sin(πλ/2).
fn trig(lambda: f64) -> (f64, f64) {
    (sin(PI * (1.0 - lambda) / 2.0), sin(PI * lambda / 2.0))
}

/// The exact linearisation's margin: μ0c0 − Ω^λcos(πλ/2) without the wall;
/// μ0c0π/(2ω_d) + ln r with it at λ = 1 (+∞ when μ0c0 ≥ 2ω0: the motion leaves the wall
/// without returning); `None` with the wall at λ < 1.
fn exact_margin(p: &Params, barrier: Barrier) -> Option<f64> {
    let m = p.mu0 * p.damping.coefficient(0);
    match barrier {
        Barrier::Off => {
            let (c, s) = trig(p.lambda);
            let omega = pow(p.omega0 * p.omega0 / s, 1.0 / (1.0 + p.lambda));
            Some(m - pow(omega, p.lambda) * c)
        }
        Barrier::On if p.lambda == 1.0 => {
            let r = p.restitution;
            if r == 0.0 {
                return Some(f64::NEG_INFINITY);
            }
            if m >= 2.0 * p.omega0 {
                return Some(f64::INFINITY);
            }
            let wd = (p.omega0 * p.omega0 - m * m / 4.0).sqrt();
            Some(m * PI / (2.0 * wd) + ln(r))
        }
        Barrier::On => None,
    }
}

/// The averaging's boundary in μ0 (closed form of f′(0) = 0, Eq. 18):
/// μ0 = (ω0^λcos(πλ/2) + 2κ sin(πλ/2)/ω0^{1−λ})/c0 with κ the variant's impact loss rate
/// (r = 1 without the wall); `None` when c0 ≤ 0 (no boundary: the rest state is stable for
/// every μ0) or when κ is infinite (r = 0, consistent variant).
pub fn averaging_mu0(p: &Params, barrier: Barrier, variant: Variant) -> Option<f64> {
    let c0 = p.damping.coefficient(0);
    let r = match barrier {
        Barrier::On => p.restitution,
        Barrier::Off => 1.0,
    };
    let eq = crate::model::Equivalents::new(p);
    let kappa = eq.loss_rate(variant, r);
    let (c, s) = trig(p.lambda);
    let mu = (pow(p.omega0, p.lambda) * c + 2.0 * kappa * s / pow(p.omega0, 1.0 - p.lambda)) / c0;
    (c0 > 0.0 && mu.is_finite()).then_some(mu)
}

/// The exact linearisation's boundary in μ0: Ω^λcos(πλ/2)/c0 with
/// Ω^{1+λ} = ω0²/sin(πλ/2) (no wall); kω0/(c0√(1 + k²/4)), k = −2 ln r/π (wall, λ = 1);
/// `None` with the wall at λ < 1, for r = 0, or when c0 ≤ 0.
pub fn exact_mu0(p: &Params, barrier: Barrier) -> Option<f64> {
    let c0 = p.damping.coefficient(0);
    if c0 <= 0.0 {
        return None;
    }
    match barrier {
        Barrier::Off => {
            let (c, s) = trig(p.lambda);
            let omega = pow(p.omega0 * p.omega0 / s, 1.0 / (1.0 + p.lambda));
            Some(pow(omega, p.lambda) * c / c0)
        }
        Barrier::On if p.lambda == 1.0 && p.restitution > 0.0 => {
            let k = -2.0 * ln(p.restitution) / PI;
            Some(k * p.omega0 / (1.0 + k * k / 4.0).sqrt() / c0)
        }
        Barrier::On => None,
    }
}

/// The analytic boundary at abscissa `x` of `plane`: bisection on the sign of the margin.
pub(super) fn analytic(plane: &Plane, x: f64, method: &Method) -> Result<BoundaryPoint> {
    let (lo, hi) = plane.y_range;
    let barrier = plane.template.barrier();
    let eval = |y: f64| -> Result<Option<f64>> { margin(&plane.at(x, y)?, barrier, method) };
    let unavailable = BoundaryPoint {
        x,
        side: Side::Unavailable,
        y: f64::NAN,
        y_lo: f64::NAN,
        y_hi: f64::NAN,
        oscillates_above: false,
        simulations: 0,
        unclear: 0,
    };
    let (Some(fa), Some(fb)) = (eval(lo)?, eval(hi)?) else {
        return Ok(unavailable);
    };
    let (ga, gb) = (fa > 0.0, fb > 0.0);
    if ga == gb {
        return Ok(BoundaryPoint {
            side: if ga { Side::Oscillates } else { Side::Rests },
            oscillates_above: gb,
            ..unavailable
        });
    }
    let (mut a, mut b) = (lo, hi);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        match eval(m)? {
            Some(f) if (f > 0.0) == ga => a = m,
            Some(_) => b = m,
            None => return Ok(unavailable),
        }
    }
    let y = 0.5 * (a + b);
    Ok(BoundaryPoint {
        side: Side::Boundary,
        y,
        y_lo: y,
        y_hi: y,
        oscillates_above: gb,
        ..unavailable
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(mu0: f64, omega0: f64, lambda: f64, r: f64) -> Params {
        Params {
            mu0,
            omega0,
            lambda,
            restitution: r,
            ..Default::default()
        }
    }

    #[test]
    fn exact_boundary_solves_the_characteristic_equation_on_the_imaginary_axis() {
        for (w, l) in [(0.3, 0.9), (0.9, 0.7), (1.0, 0.5)] {
            let p = params(0.01, w, l, 1.0);
            let mu = exact_mu0(&p, Barrier::Off).unwrap();
            // s = iΩ: (iΩ)^{1+λ} − iμΩ + ω0² = 0 with the principal power
            let omega = (w * w / (PI * l / 2.0).sin()).powf(1.0 / (1.0 + l));
            let arg = PI / 2.0 * (1.0 + l);
            let mag = omega.powf(1.0 + l);
            let re = mag * arg.cos() + w * w;
            let im = mag * arg.sin() - mu * omega;
            assert!(re.abs() < 1e-14 && im.abs() < 1e-14, "{re} {im}");
        }
        // at λ = 1 the exact boundary without the wall is μ0 = 0, as the averaging's
        let p = params(0.01, 0.7, 1.0, 1.0);
        assert_eq!(exact_mu0(&p, Barrier::Off), Some(0.0));
        assert_eq!(averaging_mu0(&p, Barrier::Off, Variant::Paper), Some(0.0));
    }

    #[test]
    fn margins_vanish_on_their_closed_forms() {
        let p = params(0.01, 0.9, 1.0, 0.9);
        let mu = exact_mu0(&p, Barrier::On).unwrap();
        let m = exact_margin(&p.with("mu0", mu).unwrap(), Barrier::On).unwrap();
        assert!(m.abs() < 1e-14, "{m}");
        for v in [Variant::Paper, Variant::Consistent] {
            let p = params(0.01, 0.5, 0.95, 0.97);
            let mu = averaging_mu0(&p, Barrier::On, v).unwrap();
            let f = Theory::new(&p.with("mu0", mu).unwrap(), v)
                .unwrap()
                .rest_state_slope();
            assert!(f.abs() < 1e-15, "{f}");
        }
        assert_eq!(
            exact_margin(&params(0.01, 0.9, 0.99, 0.9), Barrier::On),
            None
        );
    }
}

//! The elementary functions of the simulation, the same bits on every platform.
//!
//! # Why
//! IEEE 754 fixes the result of +, −, ×, ÷ and √ to the last bit, but not that of `exp`, `ln`,
//! `pow`, `sin`, `cos`, `hypot`: Rust's `f64::exp` and its siblings call the platform's C library
//! (glibc, musl, Apple's libm, MSVC's CRT), whose results differ in the last bit from one library
//! to another and from one version to another. A last-bit difference in a kernel weight or a
//! noise coefficient is amplified along a chaotic, noisy path; so without this module a
//! simulated path would be the same bits on one machine but not on a cluster node with another
//! C library. Here every such function is the pure-Rust port of FreeBSD's / musl's msun in the
//! [`libm`] crate: plain IEEE double arithmetic in a fixed order (no fused multiply–add unless
//! it is written, and then correctly rounded either in hardware or in software), so the result
//! is the same on x86-64 and aarch64, on any operating system. (`libm`'s only architecture
//! specific routines are `sqrt`, `fma` and `rint`, which IEEE 754 rounds correctly: the same
//! bits as its software versions.)
//!
//! # What is covered
//! Everything from the parameters to a simulated path and the numbers computed from it:
//! - the Eq. 5 equivalents of [`crate::model`] (`sin`, `pow`);
//! - [`crate::special`] (Γ, ln Γ, Mittag-Leffler), hence the kernel's 1/Γ(λ);
//! - the engine: product-integration weights (`pow`), the sum-of-exponentials kernel fit and its
//!   verification (`exp`, `expm1`, `ln`, `log10`, `pow`, `sin`), the mode and split factors
//!   (`exp`), the Ornstein–Uhlenbeck coefficients (`exp`, `expm1`) and the **normal deviates**
//!   ([`standard_normal`]: the ziggurat of `rand_distr` with this module's `exp` and `ln`), the
//!   tangent's norm (`hypot`);
//! - the analyses of paths: Lyapunov renormalisation (`hypot`, `ln`), oscillation growth rates
//!   and analytic boundaries (`ln`, `pow`, `sin`, `cos`), the theory-against-simulation
//!   distances of [`crate::analysis::versus`].
//!
//! Squares are written as products (`x * x`), not `powi`, whose precision Rust leaves
//! unspecified. The test `tests/maths.rs` scans the library's sources and fails on a call of a
//! platform function outside the parts named below; it also pins the bits of a short noisy path
//! with impacts, a constant that is the same on every platform by construction.
//!
//! # What is not covered, and why
//! - The averaged theory ([`crate::theory`]: stationary PDFs, quadrature, polynomial roots,
//!   bifurcation maps, fold curves) keeps the platform's functions: its results are analytic
//!   approximations checked to tolerances of 10⁻⁸ and coarser, not paths, and the
//!   reproducibility claim is about simulation. Its numbers may differ in the last bits between
//!   platforms; no simulated path depends on them.
//! - [`crate::known_answers`] (exact solutions against which tests measure errors) and the
//!   digits chosen for an error message.
//! - Unit tests compare with tolerances and use the platform's functions freely.
//!
//! # Cost
//! `libm`'s `pow` takes about twice the instructions of glibc's, but a step without an impact
//! calls no elementary function (the exponentials of the memory modes are computed once per
//! path; an impact at λ < 1 calls about 40 powers and two exponentials per mode), and a normal
//! deviate calls `exp` in the ziggurat's wedges (1.5 % of draws) and `ln` in its tail (0.03 %).
//! Measured: a noisy λ = 0.998 path 4.7 % slower than with glibc's functions, λ = 1 the same
//! (`docs/numerics.md`, Speed). The cargo feature `std-maths` (off by default) routes this
//! module to the platform's functions again, to measure that cost; paths then depend on the
//! platform and the pinned-bits test is skipped.
//!
//! # Reference
//! Sun Microsystems' fdlibm / FreeBSD msun, as ported to Rust by the `libm` crate; Marsaglia &
//! Tsang, J. Stat. Softw. 5 (2000) 8 (the ziggurat method); the tables and the algorithm of
//! `rand_distr` 0.5 (Doornik's ZIGNOR variant, J. Stat. Softw. 2005).
//!
//! # Tests
//! Unit tests below (the functions against the platform's to a few ulp, the normal deviates
//! against `rand_distr::StandardNormal` bit for bit on the same stream, and their moments);
//! `tests/maths.rs` (the source scan and the pinned path).

mod ziggurat;

pub use ziggurat::{standard_normal, ziggurat_tables};

#[cfg(not(feature = "std-maths"))]
mod imp {
    pub use libm::{cos, exp, expm1, hypot, log as ln, log10, pow, sin};
}

#[cfg(feature = "std-maths")]
mod imp {
    pub fn cos(x: f64) -> f64 {
        x.cos()
    }
    pub fn exp(x: f64) -> f64 {
        x.exp()
    }
    pub fn expm1(x: f64) -> f64 {
        x.exp_m1()
    }
    pub fn hypot(x: f64, y: f64) -> f64 {
        x.hypot(y)
    }
    pub fn ln(x: f64) -> f64 {
        x.ln()
    }
    pub fn log10(x: f64) -> f64 {
        x.log10()
    }
    pub fn pow(x: f64, y: f64) -> f64 {
        x.powf(y)
    }
    pub fn sin(x: f64) -> f64 {
        x.sin()
    }
}

/// True when this build uses the platform's functions (cargo feature `std-maths`): paths are
/// then reproducible on one platform only.
pub const PLATFORM_MATHS: bool = cfg!(feature = "std-maths");

/// eˣ.
#[inline]
pub fn exp(x: f64) -> f64 {
    imp::exp(x)
}

/// eˣ − 1, accurate for small |x|.
#[inline]
pub fn expm1(x: f64) -> f64 {
    imp::expm1(x)
}

/// The natural logarithm ln x.
#[inline]
pub fn ln(x: f64) -> f64 {
    imp::ln(x)
}

/// log₁₀ x.
#[inline]
pub fn log10(x: f64) -> f64 {
    imp::log10(x)
}

/// xʸ (as `f64::powf`).
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    imp::pow(x, y)
}

/// sin x.
#[inline]
pub fn sin(x: f64) -> f64 {
    imp::sin(x)
}

/// cos x.
#[inline]
pub fn cos(x: f64) -> f64 {
    imp::cos(x)
}

/// √(x² + y²) without undue overflow or underflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    imp::hypot(x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite doubles of one sign.
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    #[test]
    fn functions_agree_with_the_platform_to_a_few_ulp() {
        // fdlibm's and glibc's functions are both within 1 ulp of the exact value
        let mut worst = [0u64; 8];
        for i in 1..20_000 {
            let x = -30.0 + 60.0 * i as f64 / 20_000.0 + 1e-7;
            let p = x.abs() + 1e-3;
            let pairs = [
                (exp(x), x.exp()),
                (expm1(x * 1e-3), (x * 1e-3).exp_m1()),
                (ln(p), p.ln()),
                (log10(p), p.log10()),
                (pow(p, 0.998 - x / 30.0), p.powf(0.998 - x / 30.0)),
                (sin(x), x.sin()),
                (cos(x), x.cos()),
                (hypot(x, 0.3 * x + 1.0), x.hypot(0.3 * x + 1.0)),
            ];
            for (k, (a, b)) in pairs.into_iter().enumerate() {
                if a == b {
                    continue;
                }
                assert!(a.signum() == b.signum(), "function {k} at {x}: {a} vs {b}");
                worst[k] = worst[k].max(ulps(a, b));
            }
        }
        assert!(worst.iter().all(|&w| w <= 2), "ulp differences {worst:?}");
    }

    #[test]
    fn special_values() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert_eq!(ln(1.0), 0.0);
        assert_eq!(ln(0.0), f64::NEG_INFINITY);
        assert!(ln(-1.0).is_nan());
        assert_eq!(expm1(0.0), 0.0);
        assert_eq!(pow(2.0, 10.0), 1024.0);
        assert_eq!(pow(0.0, 0.998), 0.0);
        assert_eq!(hypot(3.0, 4.0), 5.0);
        assert_eq!(sin(0.0), 0.0);
        assert_eq!(cos(0.0), 1.0);
        assert_eq!(log10(1000.0), 3.0);
    }
}

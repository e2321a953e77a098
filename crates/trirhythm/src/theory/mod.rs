//! The averaged theory (the paper's analytic side): harmonic balance and stochastic averaging
//! (Eq. 18–31), certified polynomial roots, quadrature, and the bifurcation structure
//! (Eq. 32–37).
//!
//! - [`averaging`]: limit cycles f(A) = 0 (Eq. 18), pseudo-potential U_eff (Eq. 23), stationary
//!   PDFs (Eq. 27–31), in the paper's and the consistent variant; for a model of the class by
//!   phase quadrature, or the refusal saying where it does not apply;
//! - [`polynomial`]: real polynomials, certified real-root isolation (Sturm sequences);
//! - [`quadrature`]: adaptive Gauss–Kronrod with breakpoints;
//! - [`bifurcation`]: rhythmicity and P-bifurcation maps, exact fold curves, branch diagrams,
//!   barrier surfaces.
//!
//! The theory depends on [`crate::model`] only; the simulation ([`crate::engine`]) does not
//! import it.

pub mod averaging;
pub mod bifurcation;
pub mod polynomial;
pub mod quadrature;

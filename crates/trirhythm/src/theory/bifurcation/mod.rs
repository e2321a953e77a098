//! Bifurcation structure of the averaged theory: rhythmicity and P-bifurcation maps, exact fold
//! curves, branch diagrams, barrier surfaces.
//!
//! Equations (paper numbers; corrections from the project's `formulas.md`): with x = A²,
//! g(x) = f(A)/A (Eq. 18) and h(x) = A·m1(A) = x g(x) + σ1/2 (Eq. 26) are polynomials in x.
//! - Limit cycles are the positive roots of g, stable where g′ < 0; the number of stable ones
//!   classifies a point as none / mono / bi / trirhythmic (Figs 2, 3, 6).
//! - Maxima of the stationary P(A) are the roots of d ln P/dA = 2m1/σ1 with m1′ < 0, i.e. the
//!   stable roots of h (Figs 10, 12).
//! - Saddle-node lines (the paper's L1, L2, L3) are folds of g: g = g′ = 0; P-bifurcation lines
//!   are folds of h: h = h′ = 0 (Eq. 35, with Eq. 37 corrected to d(xg)/dx = 0; the printed
//!   Eq. 37 is traced too for comparison). Cusps: g = g′ = g″ = 0.
//! - Energy barriers ΔU_i are differences of U_eff (Eq. 23) between neighbouring extrema
//!   (Fig. 9).
//!
//! Method: a `Copy` parameter point and the polynomials' coefficients on the stack (no
//! allocation per point), the certified Sturm count of [`crate::theory::polynomial`] replicated on
//! fixed-size arrays, rows classified in parallel with rayon (deterministic: cells are
//! independent). Fold curves by pseudo-arclength continuation in (x, p1, p2) with a 3 × 3 Newton
//! corrector, seeded from grid cells where the count changes; branches by the same continuation
//! in (x, p).
//!
//! Reference: the paper (Eq. 18, 23–26, 32–37); Kuznetsov, *Elements of Applied Bifurcation
//! Theory*, ch. 10 (continuation of equilibria and folds).
//!
//! Tests: `tests/bifurcation.rs` (every count change of a map lies within one cell of a traced
//! curve; curve points satisfy both equations to 1e-10; an analytic cusp; branches against
//! `Theory::limit_cycles` at sampled parameter values; the fast count against
//! `Theory::stable_count_fast` by proptest) and unit tests in `kernel.rs`.
//!
//! # Example
//! A map of stable-cycle counts on a 9 × 9 grid of Fig. 2(ii)'s (γ0, δ0) plane, checked point
//! by point against the averaged theory; the plane holds trirhythmic points:
//! ```
//! use trirhythm::model::preset;
//! use trirhythm::theory::averaging::{Theory, Variant};
//! use trirhythm::theory::bifurcation::{classify, Axis, Plane, What};
//!
//! let base = preset("fig2ii")?.params;
//! let plane = Plane::new(
//!     &base,
//!     Axis::new("gamma0", 2e-5, 1e-4, 9)?,
//!     Axis::new("delta0", 2e-8, 4e-7, 9)?,
//!     Variant::Paper,
//! )?;
//! let map = classify(&plane, What::Rhythmicity, &|_rows_done, _rows| {});
//! for iy in 0..9 {
//!     for ix in 0..9 {
//!         let p = plane.params(plane.x.value(ix), plane.y.value(iy))?;
//!         let theory = Theory::new(&p, Variant::Paper)?;
//!         assert_eq!(map.count(ix, iy) as usize, theory.rhythmicity().count());
//!     }
//! }
//! let [_none, _mono, _bi, tri, _more] = map.histogram();
//! assert!(tri > 0, "three coexisting stable cycles somewhere on the plane");
//! # Ok::<(), trirhythm::Error>(())
//! ```

mod barrier;
mod branch;
mod fold;
mod grid;
mod kernel;

pub use barrier::{barrier_surfaces, paper_barriers, BarrierSurfaces};
pub use branch::{branches, Branch, BranchDiagram, BranchPoint, MAX_STEP_RANGE};
pub use fold::{
    cusp_monitor, fold_residuals, trace_folds, trace_printed_eq37, CurveEnd, FoldCurve, FoldPoint,
    FoldSystem, Folds, TraceOptions,
};
pub use grid::{classify, Axis, Map, Plane, MAX_PLANE_POINTS};
pub use kernel::{Kernel, Key, Point, What, MAXC};

//! Fig. 10: stochastic P-bifurcation map in the (λ, τ) plane for four noise intensities D:
//! number of maxima of the stationary P(A) (Eq. 27), the exact transition curves
//! m1 = ∂m1/∂A = 0 (Eq. 35 with Eq. 37 corrected) and, for the paper variant, the paper's printed
//! Eq. 36–37 construction.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig10_pbif_lambda_tau`].

use trirhythm_paper::fig10_pbif_lambda_tau::Fig10;

picture_through!(Fig10);

//! Fig. 17: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! μ0 at τ = 0.06 (a) and four τ at μ0 = 0.001 (b), with error bars, and the paper's claim (the
//! LLE turns positive past a critical D) checked curve by curve.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig17_lle_noise`] (one
//! LLE-against-noise computation shared with Fig. 18).

use trirhythm_paper::fig17_lle_noise::Fig17;

picture_through!(Fig17);

//! Fig. 18: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! λ at r = 0.998 (a) and four r at λ = 0.998 (b), μ0 = 0.001, τ = 0.025, with error bars, and the
//! paper's claims (the LLE turns positive past a critical D; more impact loss, more chaos)
//! checked curve by curve.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig18_lle_noise_fractional`] (one
//! LLE-against-noise computation shared with Fig. 17).

use trirhythm_paper::fig18_lle_noise_fractional::Fig18;

picture_through!(Fig18);

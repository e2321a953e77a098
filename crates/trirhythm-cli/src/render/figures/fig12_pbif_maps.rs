//! Fig. 12: P-bifurcation maps in the (μ0, r) plane at λ = 0.995 (a, b) and the (λ, r) plane at
//! μ0 = 0.01 (c, d), for ω0 = 0.9 (a, c) and ω0 = 1.0 (b, d; the caption prints 0.9 twice).
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig12_pbif_maps`].

use trirhythm_paper::fig12_pbif_maps::Fig12;

picture_through!(Fig12);

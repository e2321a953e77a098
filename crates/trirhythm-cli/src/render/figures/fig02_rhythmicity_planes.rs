//! Fig. 2: rhythmicity maps of the noise-free averaged system (roots of f, Eq. 18/24):
//! (i) the (α0, β0) plane with γ0 = δ0 = 0, (ii) the (γ0, δ0) plane at (α0, β0) = (0.144, 0.005),
//! with the saddle-node lines (L1, L2, L3) traced exactly.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig02_rhythmicity_planes`].

use trirhythm_paper::fig02_rhythmicity_planes::Fig02;

picture_through!(Fig02);

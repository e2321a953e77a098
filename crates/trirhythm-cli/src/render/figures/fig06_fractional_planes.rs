//! Fig. 6: rhythmicity in the (γ0, δ0) plane for four fractional orders λ, with the
//! saddle-node lines traced exactly.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig06_fractional_planes`].

use trirhythm_paper::fig06_fractional_planes::Fig06;

picture_through!(Fig06);

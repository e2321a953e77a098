//! Fig. 3: rhythmicity in the (γ0, δ0) plane for four restitution coefficients r, with the
//! saddle-node lines traced exactly.
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig03_restitution_planes`].

use trirhythm_paper::fig03_restitution_planes::Fig03;

picture_through!(Fig03);

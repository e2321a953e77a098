//! Analyses of simulated paths: recurrence quantification (Eq. 6–7), ensembles with their
//! stationary statistics and diagnosis, the averaged theory tested against them, oscillation
//! (Hopf) boundaries by simulation, averaging and exact linearisation, and the largest Lyapunov
//! exponent with frozen noise and the critical noise.

pub mod ensemble;
pub mod lyapunov;
pub mod oscillation;
pub mod recurrence;
pub mod versus;

pub use ensemble::{
    merge, run_ensemble, run_paths, EnsembleResult, EnsembleSpec, Estimate, PathStats, Wells,
};
pub use lyapunov::{
    critical_noise, largest_lyapunov, CriticalNoise, CriticalSearch, LyapunovResult, LyapunovSpec,
};
pub use oscillation::{
    boundary, classify_plane, growth_rate, Boundary, BoundaryPoint, Classifier, Growth, Plane,
    Search,
};
pub use recurrence::{RecurrenceMatrix, RecurrenceThreshold};
pub use versus::{compare, escape_time, theory_layout, TheoryComparison, TheoryLayout};

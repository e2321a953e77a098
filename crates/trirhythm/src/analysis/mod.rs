//! Analyses of simulated paths: recurrence quantification (Eq. 6–7), ensembles with their
//! stationary statistics and diagnosis, the averaged theory tested against them, oscillation
//! (Hopf) boundaries by simulation, averaging and exact linearisation, and the largest Lyapunov
//! exponent with frozen noise, the attractors of noise-free starts and the phase reduction; the
//! step guard at the amplitudes a run visits; the P-bifurcation map by simulation beside the
//! theory's.

pub mod ensemble;
pub mod lyapunov;
pub mod oscillation;
pub mod recurrence;
pub mod resolution;
pub mod simulated_map;
pub mod versus;

pub use ensemble::{
    merge, run_ensemble, run_paths, EnsembleResult, EnsembleSpec, Estimate, PathStats, Wells,
};
pub use lyapunov::{largest_lyapunov, LyapunovResult, LyapunovSpec};
pub use oscillation::{
    boundary, classify_plane, growth_rate, Boundary, BoundaryPoint, Classifier, Growth, Method,
    Plane, Search,
};
pub use recurrence::{RecurrenceMatrix, RecurrenceThreshold};
pub use resolution::check_step;
pub use simulated_map::{simulate_map, MapPoint, SimulatedMap, SimulatedMapSpec};
pub use versus::{
    binned, compare, escape_time, theory_layout, wells_bounds, TheoryComparison, TheoryLayout,
};

/// `paths` are indices in 0..`n` of a driver's paths, none asked twice (the pieces of a run that
/// a merge puts together).
pub(crate) fn check_indices(paths: &[u64], n: usize) -> crate::Result<()> {
    let mut seen = vec![false; n];
    for &i in paths {
        if i >= n as u64 {
            return Err(crate::Error::invalid(
                "paths",
                i as f64,
                format!("path indices in 0..{n}"),
            ));
        }
        if std::mem::replace(&mut seen[i as usize], true) {
            return Err(crate::Error::invalid(
                "paths",
                i as f64,
                "each path at most once (this one is asked twice)",
            ));
        }
    }
    Ok(())
}

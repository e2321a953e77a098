//! Analyses of simulated paths: recurrence quantification (Eq. 6–7).

pub mod recurrence;

pub use recurrence::{RecurrenceMatrix, RecurrenceThreshold};

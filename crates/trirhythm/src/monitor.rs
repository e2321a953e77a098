//! Watching a long library call: progress, finished pieces of work (to checkpoint them) and
//! cancellation, through one trait.
//!
//! Every driver that can run for long (ensembles, Lyapunov exponents, oscillation searches,
//! maps, a figure's data) takes a `&dyn Monitor<T>`, where `T` is the piece of work it hands
//! back as soon as it is finished (an ensemble's per-path statistics, a figure's nothing). The
//! caller decides what to do with each call — draw a bar, save a checkpoint, stop the run —
//! and the library never prints or writes.
//!
//! - [`Monitor::progress`]: `done` of `total` units (steps, cells, points); called from worker
//!   threads, often, so it must be cheap.
//! - [`Monitor::finished`]: one piece of work done; an `Err` stops the run with that error (a
//!   checkpoint that could not be written).
//! - [`Monitor::cancelled`]: polled between units of work; when it answers `true` the driver
//!   stops as soon as it can and returns [`Error::Cancelled`]. Nothing half-done is returned.
//!
//! [`Silent`] watches nothing; [`CancelFlag`] stops a run from another thread (a signal
//! handler, a Python `KeyboardInterrupt`, a Dask cancellation); [`OnlyCancel`] hands a
//! monitor's cancellation, and nothing else, to an inner call that reports other pieces, and
//! [`Relay`] its cancellation and progress.
//!
//! # Example
//! ```
//! use trirhythm::monitor::{CancelFlag, Monitor};
//!
//! let flag = CancelFlag::default();
//! assert!(!Monitor::<()>::cancelled(&flag));
//! flag.cancel();
//! assert!(Monitor::<()>::cancelled(&flag));
//! assert!(Monitor::<()>::check(&flag).is_err()); // a driver returns this error
//! ```

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};

/// What a long library call reports to, and asks whether to go on.
pub trait Monitor<T: ?Sized = ()>: Sync {
    /// `done` of `total` units of work finished.
    fn progress(&self, _done: u64, _total: u64) {}

    /// One piece of work is finished (e.g. one path's statistics, to be checkpointed); an error
    /// stops the run with it.
    fn finished(&self, _piece: &T) -> Result<()> {
        Ok(())
    }

    /// Whether the caller wants the run stopped.
    fn cancelled(&self) -> bool {
        false
    }

    /// [`Error::Cancelled`] when [`Monitor::cancelled`], for drivers to use with `?`.
    fn check(&self) -> Result<()> {
        if self.cancelled() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }
}

/// A monitor that watches nothing and never cancels.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl<T: ?Sized> Monitor<T> for Silent {}

/// A monitor whose only job is cancellation: [`CancelFlag::cancel`] from any thread stops the
/// run it watches.
#[derive(Debug, Default)]
pub struct CancelFlag(AtomicBool);

impl CancelFlag {
    /// Ask the watched run to stop.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

impl<T: ?Sized> Monitor<T> for CancelFlag {
    fn cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// Forwards only the cancellation of a monitor of other pieces: what a driver hands to the
/// inner calls it makes (one Lyapunov estimate of a figure's curve, one simulation of a
/// boundary search), so that the caller's stop reaches them while their own progress and
/// pieces stay inside.
#[derive(Clone, Copy)]
pub struct OnlyCancel<'a, T: ?Sized>(pub &'a dyn Monitor<T>);

impl<T: ?Sized, U: ?Sized> Monitor<U> for OnlyCancel<'_, T> {
    fn cancelled(&self) -> bool {
        self.0.cancelled()
    }
}

/// Forwards the progress and the cancellation of a monitor of other pieces, keeping the inner
/// call's pieces inside: what a caller hands to one long inner call whose progress is its own
/// (one ensemble of a figure).
#[derive(Clone, Copy)]
pub struct Relay<'a, T: ?Sized>(pub &'a dyn Monitor<T>);

impl<T: ?Sized, U: ?Sized> Monitor<U> for Relay<'_, T> {
    fn progress(&self, done: u64, total: u64) {
        self.0.progress(done, total);
    }

    fn cancelled(&self) -> bool {
        self.0.cancelled()
    }
}

//! The progress bar: an indicatif bar on a terminal (hidden otherwise) moved by a library
//! [`trirhythm::monitor::Monitor`].
//!
//! Until the first unit of work (a path, a grid row) finishes the bar is a spinner with the
//! elapsed time and no estimate: an estimate from no work done would be a guess (indicatif's
//! own reads "0s" there). From then on the estimate is the elapsed time scaled by the work left,
//! [`eta`]: elapsed · (total − done) / done. Tested by the unit tests below.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A library call's monitor that hands its progress (done, total) to a closure (which moves a
/// progress bar).
pub struct Report<F>(pub F);

impl<T: ?Sized, F: Fn(u64, u64) + Sync> trirhythm::monitor::Monitor<T> for Report<F> {
    fn progress(&self, done: u64, total: u64) {
        (self.0)(done, total)
    }
}

/// The time left from the work done: `elapsed · (total − done) / done`; `None` before the first
/// unit is done (no work, no estimate).
pub fn eta(done: u64, total: u64, elapsed: Duration) -> Option<Duration> {
    if done == 0 {
        return None;
    }
    let left = total.saturating_sub(done) as f64 / done as f64;
    Some(Duration::from_secs_f64(elapsed.as_secs_f64() * left))
}

/// The text after the bar: the elapsed time and, once a unit is done, the estimate.
pub fn status(done: u64, total: u64, elapsed: Duration) -> String {
    let secs = |d: Duration| format!("{}s", d.as_secs());
    match eta(done, total, elapsed) {
        None => format!(
            "{} elapsed, no estimate before the first unit finishes",
            secs(elapsed)
        ),
        // rounded up: work left never reads "0s"
        Some(left) => format!(
            "{} elapsed, about {}s left",
            secs(elapsed),
            left.as_secs_f64().ceil()
        ),
    }
}

/// A progress bar on a terminal (hidden otherwise): a spinner with the elapsed time until the
/// first unit is done, then a bar with the estimate of [`eta`].
pub struct Progress {
    bar: indicatif::ProgressBar,
    started: AtomicBool,
    since: Instant,
}

const WAITING: &str = "{spinner} {prefix} {pos}/{len} ({msg})";
const RUNNING: &str = "{prefix} [{bar:40}] {pos}/{len} ({msg})";

fn style(template: &str) -> indicatif::ProgressStyle {
    indicatif::ProgressStyle::with_template(template)
        .expect("valid template")
        .progress_chars("=> ")
}

impl Progress {
    /// Move to `done` units of the bar's length.
    pub fn set_position(&self, done: u64) {
        let total = self.bar.length().unwrap_or(0);
        self.bar
            .set_message(status(done, total, self.since.elapsed()));
        if done > 0 && !self.started.swap(true, Ordering::Relaxed) {
            self.bar.disable_steady_tick();
            self.bar.set_style(style(RUNNING));
        }
        self.bar.set_position(done);
    }

    /// Set the number of units.
    pub fn set_length(&self, total: u64) {
        self.bar.set_length(total);
    }

    /// Remove the bar from the terminal.
    pub fn finish_and_clear(&self) {
        self.bar.finish_and_clear();
    }
}

/// A progress bar of `len` units on a terminal, hidden otherwise.
pub fn progress(len: u64, message: &str) -> Progress {
    use std::io::IsTerminal;
    let bar = if std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(len)
            .with_message(status(0, len, Duration::ZERO))
            .with_prefix(message.to_string())
            .with_style(style(WAITING));
        bar.enable_steady_tick(Duration::from_millis(250));
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    Progress {
        bar,
        started: AtomicBool::new(false),
        since: Instant::now(),
    }
}

/// The library's [`trirhythm::monitor::Monitor`] drawn as a progress bar on the terminal (hidden otherwise).
pub struct Bar(Progress);

impl Bar {
    /// A bar labelled `message`, a spinner until the first unit is done.
    pub fn new(message: &str) -> Bar {
        Bar(progress(0, message))
    }
}

impl<T: ?Sized> trirhythm::monitor::Monitor<T> for Bar {
    fn progress(&self, done: u64, total: u64) {
        self.0.set_length(total);
        self.0.set_position(done);
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_estimate_before_the_first_unit() {
        assert_eq!(eta(0, 100, Duration::from_secs(3600)), None);
        let s = status(0, 100, Duration::from_secs(3600));
        assert!(s.contains("3600s elapsed"), "{s}");
        assert!(s.contains("no estimate"), "{s}");
        assert!(!s.contains("(0s)") && !s.contains(" 0s left"), "{s}");
    }

    #[test]
    fn the_estimate_scales_the_elapsed_time_by_the_work_left() {
        // 1 of 4 units in 10 s: 3 more take 30 s
        assert_eq!(
            eta(1, 4, Duration::from_secs(10)),
            Some(Duration::from_secs(30))
        );
        assert_eq!(
            status(1, 4, Duration::from_secs(10)),
            "10s elapsed, about 30s left"
        );
        // a fraction of a second left reads 1 s, not 0 s
        assert_eq!(
            status(999, 1000, Duration::from_secs(5)),
            "5s elapsed, about 1s left"
        );
        // done: nothing left; more done than the total (a rounded position) is not negative
        assert_eq!(eta(4, 4, Duration::from_secs(10)), Some(Duration::ZERO));
        assert_eq!(eta(5, 4, Duration::from_secs(10)), Some(Duration::ZERO));
        // 750 of 1000 in 3 s: 1 s left
        let left = eta(750, 1000, Duration::from_secs(3)).unwrap();
        assert!((left.as_secs_f64() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_hidden_bar_takes_progress_quietly() {
        let p = progress(10, "test");
        p.set_position(0);
        p.set_position(3);
        assert!(p.started.load(Ordering::Relaxed));
        p.finish_and_clear();
    }
}

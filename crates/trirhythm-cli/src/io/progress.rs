//! Progress on a terminal (nothing otherwise): an indicatif bar moved by a library
//! [`trirhythm::monitor::Monitor`], and before the first bar a set-up ticker.
//!
//! - **The bar** redraws four times a second, whether or not a unit of work finishes: the
//!   elapsed time, the rate (units per second, or one unit per so many seconds) and the
//!   estimate are computed at each redraw ([`status`]), not when a unit finishes (a bar whose
//!   first unit took minutes read "0s elapsed" for minutes). Until the first unit finishes it
//!   is a spinner with the elapsed time and no estimate: an estimate from no work done would
//!   be a guess. From then on the estimate is the elapsed time scaled by the work left,
//!   [`eta`]: elapsed · (total − done) / done.
//! - **The set-up ticker** ([`start_ticker`], from `main`): a spinner with the elapsed time,
//!   and the step checks made so far with their rate ([`count_check`]), from half a second
//!   after the start until the first bar appears or the command ends — the checks before the
//!   first unit of work (every point of a sweep) took 20 s in silence. Lines written to
//!   standard error meanwhile go through [`note`], which lifts the ticker out of their way.
//!
//! Tested by the unit tests below and `tests/hostile.rs` (on a pseudo-terminal).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
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

/// The rate of `done` units in `elapsed`: "2.5/s", or "one per 40s" below one a second;
/// "none done yet" before the first.
pub fn rate(done: u64, elapsed: Duration) -> String {
    let secs = elapsed.as_secs_f64();
    if done == 0 {
        return "none done yet".into();
    }
    let per_second = done as f64 / secs.max(1e-9);
    if per_second >= 1.0 {
        format!("{per_second:.1}/s")
    } else {
        format!("one per {:.0}s", secs / done as f64)
    }
}

/// The text after the bar: the elapsed time, the rate and, once a unit is done, the estimate.
pub fn status(done: u64, total: u64, elapsed: Duration) -> String {
    let secs = |d: Duration| format!("{}s", d.as_secs());
    match eta(done, total, elapsed) {
        None => format!(
            "{} elapsed, {}, no estimate before the first unit finishes",
            secs(elapsed),
            rate(done, elapsed)
        ),
        // rounded up: work left never reads "0s"
        Some(left) => format!(
            "{} elapsed, {}, about {}s left",
            secs(elapsed),
            rate(done, elapsed),
            left.as_secs_f64().ceil()
        ),
    }
}

/// A progress bar on a terminal (hidden otherwise): a spinner with the elapsed time until the
/// first unit is done, then a bar with the estimate of [`eta`]; redrawn four times a second.
pub struct Progress {
    bar: indicatif::ProgressBar,
    started: AtomicBool,
}

const WAITING: &str = "{spinner} {prefix} {pos}/{len} ({status})";
const RUNNING: &str = "{prefix} [{bar:40}] {pos}/{len} ({status})";

/// The redraw interval of every bar and of the set-up ticker.
const TICK: Duration = Duration::from_millis(250);

fn style(template: &str) -> indicatif::ProgressStyle {
    indicatif::ProgressStyle::with_template(template)
        .expect("valid template")
        .with_key(
            "status",
            |s: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = w.write_str(&status(s.pos(), s.len().unwrap_or(0), s.elapsed()));
            },
        )
        .progress_chars("=> ")
}

impl Progress {
    /// Move to `done` units of the bar's length.
    pub fn set_position(&self, done: u64) {
        if done > 0 && !self.started.swap(true, Ordering::Relaxed) {
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

/// A progress bar of `len` units on a terminal, hidden otherwise. The set-up ticker, if it
/// runs, ends here.
pub fn progress(len: u64, message: &str) -> Progress {
    use std::io::IsTerminal;
    end_ticker();
    let bar = if std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(len)
            .with_prefix(message.to_string())
            .with_style(style(WAITING));
        bar.enable_steady_tick(TICK);
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    Progress {
        bar,
        started: AtomicBool::new(false),
    }
}

/// The set-up ticker's state: what runs, since when, and its spinner once shown.
struct Ticker {
    label: String,
    since: Instant,
    spinner: Option<indicatif::ProgressBar>,
    ended: bool,
}

static TICKER: Mutex<Option<Ticker>> = Mutex::new(None);

/// Step checks made during the set-up (see [`count_check`]).
static CHECKS: AtomicU64 = AtomicU64::new(0);

/// How long the set-up runs before its ticker appears (a quick command shows nothing).
const TICKER_DELAY: Duration = Duration::from_millis(500);

/// Start the set-up ticker of command `label` on a terminal (nothing otherwise): it appears
/// after half a second unless a progress bar has begun or the command has ended.
pub fn start_ticker(label: &str) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return;
    }
    let since = Instant::now();
    *TICKER.lock().unwrap_or_else(|e| e.into_inner()) = Some(Ticker {
        label: label.to_string(),
        since,
        spinner: None,
        ended: false,
    });
    std::thread::spawn(|| {
        std::thread::sleep(TICKER_DELAY);
        let mut t = TICKER.lock().unwrap_or_else(|e| e.into_inner());
        let Some(t) = t.as_mut() else { return };
        if t.ended {
            return;
        }
        let since = t.since;
        let spinner = indicatif::ProgressBar::new_spinner()
            .with_prefix(t.label.clone())
            .with_style(
                indicatif::ProgressStyle::with_template("{spinner} {prefix}: {setup}")
                    .expect("valid template")
                    .with_key(
                        "setup",
                        move |_: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                            let _ = w.write_str(&setup_status(
                                CHECKS.load(Ordering::Relaxed),
                                since.elapsed(),
                            ));
                        },
                    ),
            );
        spinner.enable_steady_tick(TICK);
        t.spinner = Some(spinner);
    });
}

/// The set-up ticker's text: "preparing, 3s elapsed" and, once checks are counted, "412 step
/// checks, 137.3/s".
pub fn setup_status(checks: u64, elapsed: Duration) -> String {
    let mut s = format!("preparing, {}s elapsed", elapsed.as_secs());
    if checks > 0 {
        s.push_str(&format!(
            ", {checks} step checks, {}",
            rate(checks, elapsed)
        ));
    }
    s
}

/// Count one step check of the set-up (shown by the ticker with its rate).
pub fn count_check() {
    CHECKS.fetch_add(1, Ordering::Relaxed);
}

/// End the set-up ticker (the first progress bar begins, or the command ends): its line is
/// cleared and it does not appear again.
pub fn end_ticker() {
    let mut t = TICKER.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(t) = t.as_mut() {
        t.ended = true;
        if let Some(s) = t.spinner.take() {
            s.finish_and_clear();
        }
    }
}

/// Write `line` to standard error, out of the set-up ticker's way when it is shown.
pub fn note(line: &str) {
    let t = TICKER.lock().unwrap_or_else(|e| e.into_inner());
    match t.as_ref().and_then(|t| t.spinner.as_ref()) {
        Some(s) => s.suspend(|| eprintln!("{line}")),
        None => eprintln!("{line}"),
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
        assert!(s.contains("none done yet"), "{s}");
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
            "10s elapsed, one per 10s, about 30s left"
        );
        // a fraction of a second left reads 1 s, not 0 s
        assert_eq!(
            status(999, 1000, Duration::from_secs(5)),
            "5s elapsed, 199.8/s, about 1s left"
        );
        // done: nothing left; more done than the total (a rounded position) is not negative
        assert_eq!(eta(4, 4, Duration::from_secs(10)), Some(Duration::ZERO));
        assert_eq!(eta(5, 4, Duration::from_secs(10)), Some(Duration::ZERO));
        // 750 of 1000 in 3 s: 1 s left
        let left = eta(750, 1000, Duration::from_secs(3)).unwrap();
        assert!((left.as_secs_f64() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn the_rate_and_the_set_up_text() {
        assert_eq!(rate(0, Duration::from_secs(5)), "none done yet");
        assert_eq!(rate(10, Duration::from_secs(4)), "2.5/s");
        assert_eq!(rate(1, Duration::from_secs(40)), "one per 40s");
        // the text moves with the time even when no unit finishes
        assert_ne!(
            status(0, 8, Duration::from_secs(1)),
            status(0, 8, Duration::from_secs(2))
        );
        assert_eq!(
            setup_status(0, Duration::from_secs(3)),
            "preparing, 3s elapsed"
        );
        assert_eq!(
            setup_status(30, Duration::from_secs(3)),
            "preparing, 3s elapsed, 30 step checks, 10.0/s"
        );
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

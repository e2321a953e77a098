//! What the timing examples share: the process's CPU time, medians, and the fig13a problem
//! (three starts: the theory's cycles A ≈ 2.9, 7.4, 12.9) at a chosen λ.
#![allow(dead_code)] // each example uses part of it

use trirhythm::engine::Problem;
use trirhythm::model::preset;

/// CPU seconds all threads of this process have run so far (Linux `schedstat` of every task,
/// in nanoseconds), `None` elsewhere: on a shared machine the time spent waiting for a core
/// does not count. The pools' threads live through the whole run, so none is missed.
pub fn cpu_s() -> Option<f64> {
    let mut total = 0.0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let path = task.ok()?.path().join("schedstat");
        let text = std::fs::read_to_string(path).ok()?;
        total += text.split_whitespace().next()?.parse::<f64>().ok()?;
    }
    Some(total * 1e-9)
}

/// The median (NaN for none).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// The fig13a parameter set at order `lambda`, paths started on the three cycles in turn.
pub fn fig13a_problem(lambda: f64) -> Problem {
    let p = preset("fig13a")
        .unwrap()
        .params
        .with("lambda", lambda)
        .unwrap();
    Problem::from_params(&p)
        .and_then(|q| q.with_starts(&[(2.9, 0.0), (7.4, 0.0), (12.9, 0.0)]))
        .unwrap()
}

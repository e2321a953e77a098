//! The parallel profile (`trirhythm::profile`) of a synthetic workload whose total CPU time and
//! critical path are known: tasks that spin for a given CPU time, in stages nested two deep.
//! The profile is a property of the work, not of the machine: the same for 1, 2 and 8 threads.

use rayon::prelude::*;
use trirhythm::profile::{parallel, record, recording};

/// CPU seconds of the calling thread.
fn thread_cpu_s() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid timespec to write, a constant clock id
    assert_eq!(
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) },
        0
    );
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// Spin until the calling thread has used `ms` milliseconds of CPU.
fn spin(ms: f64) {
    let start = thread_cpu_s();
    let mut x = 0u64;
    while thread_cpu_s() - start < 1e-3 * ms {
        x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
    }
}

/// Stage A: four tasks of 40, 20, 20, 20 ms (critical 40). Then stage B: a task that opens a
/// stage of three 30 ms tasks (critical 30) and a task of 10 ms serial work followed by a
/// stage of two 25 ms tasks (critical 35). Total 100 + 90 + 10 + 50 = 250 ms; critical path
/// 40 + max(30, 35) = 75 ms; 4 + 2 + 3 + 2 = 11 tasks.
fn workload() {
    parallel(|a| {
        [40.0, 20.0, 20.0, 20.0]
            .par_iter()
            .for_each(|&ms| a.task(|| spin(ms)))
    });
    parallel(|b| {
        rayon::join(
            || b.task(|| parallel(|c| [30.0; 3].par_iter().for_each(|&ms| c.task(|| spin(ms))))),
            || {
                b.task(|| {
                    spin(10.0);
                    parallel(|c| [25.0; 2].par_iter().for_each(|&ms| c.task(|| spin(ms))))
                })
            },
        )
    });
}

#[test]
fn a_known_workload_gives_its_total_critical_path_and_bound_for_any_thread_count() {
    for threads in [1, 2, 8] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let ((), p) = pool.install(|| record(workload));
        let close = |got: f64, want: f64| (got - want).abs() <= 0.1 * want + 0.005;
        assert_eq!(p.tasks, 11, "{threads} threads: {p:?}");
        assert!(close(p.total_cpu_s, 0.250), "{threads} threads: {p:?}");
        assert!(close(p.critical_path_s, 0.075), "{threads} threads: {p:?}");
        assert!(
            (p.speedup_bound() - 250.0 / 75.0).abs() < 0.4,
            "{threads} threads: {p:?}"
        );
    }
}

#[test]
fn without_a_recorder_nothing_is_recorded_and_results_pass_through() {
    assert!(!recording());
    let sum: u64 = parallel(|s| (0..100u64).into_par_iter().map(|i| s.task(|| i)).sum());
    assert_eq!(sum, 4950);
    let (inside, p) = record(recording);
    assert!(inside);
    assert_eq!(p.tasks, 0);
    assert!(!recording());
}

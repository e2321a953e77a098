//! A parallel profile of a long call: the CPU time of all its work, the critical path (the
//! longest chain of work that must run one after the other) and the bound they put on the
//! speed-up any number of cores can give, total / critical.
//!
//! # Problem
//! A figure, an ensemble or a sweep is a tree of work: stages that run one after another
//! (pilots, then the wells' paths, then the splittings), each a set of independent tasks
//! (paths, replicas, clones) that may themselves hold stages. With unlimited cores and no
//! overhead its wall time is its critical path; no machine runs it faster than that, and
//! `total / critical` is the largest speed-up it allows.
//!
//! # Method
//! [`record`] runs a closure with a [`Recorder`] attached to the calling thread. Every place
//! that hands independent tasks to rayon opens a stage ([`parallel`]) and runs each task
//! through [`Stage::task`]; the tree of stages and tasks is built as they run, each task
//! remembering the stage it belongs to (never the thread it runs on, so rayon's
//! work stealing cannot misfile it). A node's own time is the CPU time of its thread while it
//! ran (`CLOCK_THREAD_CPUTIME_ID`; wall time off Unix) less that of the nodes run inside it on
//! the same thread (its inline children and the tasks its thread stole while it waited). Then
//!
//! - total = Σ own time over all nodes;
//! - critical(task) = own + Σ critical(its stages), its stages running one after another;
//! - critical(stage) = own + max critical(its tasks), its tasks running side by side.
//!
//! Without [`record`] on the stack, [`parallel`] and [`Stage::task`] read one thread-local
//! and call the closure: nothing is measured, nothing allocated (the benches do not move).
//!
//! # Test
//! `tests/profile.rs`: a synthetic workload (spinning tasks of known CPU time in nested
//! stages) gives its known total, critical path and bound, whatever the thread count.

use std::cell::{Cell, RefCell};
use std::sync::{Arc, Mutex};

/// What a profile found: the CPU time of all work, the critical path, the tasks counted.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Profile {
    /// CPU seconds of all the work, on every thread.
    pub total_cpu_s: f64,
    /// CPU seconds of the longest chain of work that must run one after the other.
    pub critical_path_s: f64,
    /// Tasks recorded (the independent pieces handed to the pool).
    pub tasks: usize,
    /// Wall seconds of the recorded call.
    pub wall_s: f64,
}

impl Profile {
    /// The largest speed-up any number of cores can give: total / critical path (1 for no
    /// work).
    pub fn speedup_bound(&self) -> f64 {
        if self.critical_path_s > 0.0 {
            self.total_cpu_s / self.critical_path_s
        } else {
            1.0
        }
    }

    /// One line: total CPU, critical path, bound, tasks, wall time.
    pub fn line(&self) -> String {
        format!(
            "total CPU {:.2} s, critical path {:.2} s, speed-up bound {:.1}× ({} tasks), wall {:.2} s",
            self.total_cpu_s,
            self.critical_path_s,
            self.speedup_bound(),
            self.tasks,
            self.wall_s
        )
    }
}

/// How a node's children run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Order {
    /// One after another (a task's stages).
    Serial,
    /// Side by side (a stage's tasks).
    Parallel,
}

#[derive(Debug)]
struct Node {
    parent: Option<usize>,
    order: Order,
    own_s: f64,
}

/// The tree being recorded; shared by every thread that runs a piece of the call.
#[derive(Debug, Default)]
pub struct Recorder {
    nodes: Mutex<Vec<Node>>,
}

impl Recorder {
    fn open(&self, parent: Option<usize>, order: Order) -> usize {
        let mut nodes = self.nodes.lock().unwrap_or_else(|e| e.into_inner());
        nodes.push(Node {
            parent,
            order,
            own_s: 0.0,
        });
        nodes.len() - 1
    }

    fn close(&self, node: usize, own_s: f64) {
        let mut nodes = self.nodes.lock().unwrap_or_else(|e| e.into_inner());
        nodes[node].own_s = own_s;
    }

    /// Total, critical path and tasks of the tree recorded so far (wall time 0).
    fn profile(&self) -> Profile {
        let nodes = self.nodes.lock().unwrap_or_else(|e| e.into_inner());
        // children are opened after their parents: one pass from the leaves up
        let mut critical: Vec<f64> = nodes.iter().map(|n| n.own_s).collect();
        let mut below = vec![0.0f64; nodes.len()];
        for k in (0..nodes.len()).rev() {
            critical[k] = nodes[k].own_s + below[k];
            if let Some(p) = nodes[k].parent {
                below[p] = match nodes[p].order {
                    Order::Serial => below[p] + critical[k],
                    Order::Parallel => below[p].max(critical[k]),
                };
            }
        }
        Profile {
            total_cpu_s: nodes.iter().map(|n| n.own_s).sum(),
            critical_path_s: critical.first().copied().unwrap_or(0.0),
            tasks: nodes
                .iter()
                .filter(|n| n.order == Order::Serial && n.parent.is_some())
                .count(),
            wall_s: 0.0,
        }
    }
}

/// Where the work running on a thread belongs: a recorder and a node of its tree.
type Place = (Arc<Recorder>, usize);

thread_local! {
    /// The node the thread's current work belongs to (None: nothing is recorded).
    static CURRENT: RefCell<Option<Place>> = const { RefCell::new(None) };
    /// CPU seconds of the nodes finished on this thread (what an enclosing node subtracts).
    static NESTED: Cell<f64> = const { Cell::new(0.0) };
}

/// CPU seconds of the calling thread (wall seconds off Unix).
fn thread_cpu_s() -> f64 {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid timespec to write; the clock id is a constant of the platform
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        if rc == 0 {
            return t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64;
        }
    }
    use std::sync::OnceLock;
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
}

/// A node being timed on the current thread: made current, its own time taken at the end.
struct Timed {
    place: Place,
    previous: Option<Place>,
    cpu0: f64,
    nested0: f64,
}

impl Timed {
    fn start(recorder: Arc<Recorder>, parent: Option<usize>, order: Order) -> Timed {
        let node = recorder.open(parent, order);
        let place = (recorder, node);
        let previous = CURRENT.with(|c| c.replace(Some(place.clone())));
        Timed {
            place,
            previous,
            cpu0: thread_cpu_s(),
            nested0: NESTED.with(Cell::get),
        }
    }
}

impl Drop for Timed {
    fn drop(&mut self) {
        let elapsed = (thread_cpu_s() - self.cpu0).max(0.0);
        let nested = NESTED.with(Cell::get) - self.nested0;
        self.place
            .0
            .close(self.place.1, (elapsed - nested).max(0.0));
        NESTED.with(|n| n.set(self.nested0 + elapsed));
        CURRENT.with(|c| *c.borrow_mut() = self.previous.take());
    }
}

/// Run `f` with a fresh recorder attached: its result and the profile of all the work it did
/// on this thread and through [`parallel`] stages.
pub fn record<R>(f: impl FnOnce() -> R) -> (R, Profile) {
    let recorder = Arc::new(Recorder::default());
    let wall = std::time::Instant::now();
    let out = {
        let _root = Timed::start(recorder.clone(), None, Order::Serial);
        f()
    };
    let profile = Profile {
        wall_s: wall.elapsed().as_secs_f64(),
        ..recorder.profile()
    };
    (out, profile)
}

/// Whether a [`record`] is watching the calling thread's work.
pub fn recording() -> bool {
    CURRENT.with(|c| c.borrow().is_some())
}

/// A stage of independent tasks: what [`parallel`] hands its closure, to run each task
/// through [`Stage::task`] on any thread of the pool.
pub struct Stage {
    timed: Option<Timed>,
}

/// Run `f`, a stage of independent tasks under the calling thread's current work, each task
/// through [`Stage::task`]; the stage is closed when `f` returns. Costs one thread-local read
/// when nothing is recorded.
///
/// ```
/// use rayon::prelude::*;
/// use trirhythm::profile::{parallel, record};
///
/// let (sum, profile) = record(|| {
///     parallel(|stage| {
///         (0..8u64)
///             .into_par_iter()
///             .map(|i| stage.task(|| (0..100_000u64).fold(i, |a, b| a ^ b.wrapping_mul(a))))
///             .sum::<u64>()
///     })
/// });
/// assert_eq!(profile.tasks, 8);
/// assert!(profile.critical_path_s <= profile.total_cpu_s);
/// # let _ = sum;
/// ```
pub fn parallel<R>(f: impl FnOnce(&Stage) -> R) -> R {
    let parent = CURRENT.with(|c| c.borrow().clone());
    let stage = Stage {
        timed: parent.map(|(r, node)| Timed::start(r, Some(node), Order::Parallel)),
    };
    f(&stage)
}

impl Stage {
    /// Run one task of the stage (on any thread): timed as a child of the stage, the stages
    /// it opens nested under it, one after another.
    pub fn task<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.timed {
            None => f(),
            Some(t) => {
                let _task = Timed::start(t.place.0.clone(), Some(t.place.1), Order::Serial);
                f()
            }
        }
    }
}

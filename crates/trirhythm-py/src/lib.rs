//! The native module `trirhythm._trirhythm` behind the Python package `trirhythm`.
//!
//! It only adapts: every computation is a call of the `trirhythm` or `trirhythm-paper`
//! library, every document the library's serde form (handed to Python as JSON text and parsed
//! there), every error the library's message. Long calls ([`long_call`]) release the GIL, run
//! on a rayon pool of `threads` threads in a second thread, and from the calling thread poll
//! Python's signal handlers and report progress to a Python callback about every 100 ms; a
//! `KeyboardInterrupt` (or an exception in the callback) cancels the run through the
//! library's [`CancelFlag`] and is raised once the run has stopped. Between
//! [`_profile_start`] and [`_profile_stop`] on one Python thread, each long call it makes is
//! run under [`trirhythm::profile::record`] and the profiles add up (the calls run one after
//! another): `trirhythm.profiled` and the sweeps' `profile=True`.
//!
//! Tests: the package's pytest suite (`crates/trirhythm-py/tests`).

use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};
use trirhythm::analysis::ensemble::{self as ens, PathStats};
use trirhythm::analysis::lyapunov::{self as lle, LyapunovSpec};
use trirhythm::analysis::oscillation::{self as osc, Classifier, Search};
use trirhythm::engine::{simulate_with, ImpactMemory, Options, System};
use trirhythm::model::{self, Params};
use trirhythm::monitor::{CancelFlag, Monitor};
use trirhythm::profile::Profile;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::theory::bifurcation::{self as bif, Axis, What};
use trirhythm_paper::critical::{critical_noise, log_noises, CriticalRequest};
use trirhythm_paper::lle::Sizes;
use trirhythm_paper::requests::{EnsembleRequest, MemoryKind, Model, Named};
use trirhythm_paper::FigureOptions;

/// A one-dimensional numpy array.
type Array<'py, T> = Bound<'py, PyArray1<T>>;

/// A classified plane: the axes' values, the counts and the fold curves' JSON (when traced).
type PlaneOut<'py> = (
    Array<'py, f64>,
    Array<'py, f64>,
    Bound<'py, PyAny>,
    Option<String>,
);

/// A library error as a Python exception: bad input is a `ValueError`, a cancelled run a
/// `KeyboardInterrupt`, anything else a `RuntimeError`; the message is the library's.
fn py_err(e: trirhythm::Error) -> PyErr {
    use trirhythm::Error as E;
    match e {
        E::Cancelled => PyKeyboardInterrupt::new_err("cancelled"),
        E::InvalidParameter { .. }
        | E::Unknown { .. }
        | E::Undefined { .. }
        | E::Malformed { .. }
        | E::NotApplicable { .. } => PyValueError::new_err(e.to_string()),
        _ => PyRuntimeError::new_err(e.to_string()),
    }
}

fn json_err(e: serde_json::Error) -> PyErr {
    PyRuntimeError::new_err(format!("serialising a result: {e}"))
}

/// What a long call reports to: progress counters read by the calling thread, and the flag
/// that stops the run.
#[derive(Default)]
struct Watch {
    flag: CancelFlag,
    done: AtomicU64,
    total: AtomicU64,
}

impl<T: ?Sized> Monitor<T> for Watch {
    fn progress(&self, done: u64, total: u64) {
        self.done.store(done, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        Monitor::<()>::cancelled(&self.flag)
    }
}

/// How often the calling thread checks for signals and reports progress.
const POLL: Duration = Duration::from_millis(100);

thread_local! {
    /// The profile of this Python thread's long calls since [`_profile_start`] (`None`: not
    /// profiling).
    static PROFILING: Cell<Option<Profile>> = const { Cell::new(None) };
}

/// Profile this thread's long calls from now on, from zero.
#[pyfunction]
fn _profile_start() {
    PROFILING.with(|p| {
        p.set(Some(Profile {
            total_cpu_s: 0.0,
            critical_path_s: 0.0,
            tasks: 0,
            wall_s: 0.0,
        }))
    });
}

/// Stop profiling this thread's long calls: their profile since [`_profile_start`] as
/// `(total_cpu_s, critical_path_s, tasks, wall_s)` (None when it was not started).
#[pyfunction]
fn _profile_stop() -> Option<(f64, f64, usize, f64)> {
    PROFILING
        .with(|p| p.take())
        .map(|q| (q.total_cpu_s, q.critical_path_s, q.tasks, q.wall_s))
}

/// Run `work` without the GIL on a pool of `threads` threads (`None`: one per core) in a
/// second thread, while this thread polls Python's signals and calls `progress(done, total)`
/// (at most every 100 ms, when it changed). A `KeyboardInterrupt` or an exception of the
/// callback cancels the run and is raised after it stopped.
fn long_call<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&Watch) -> trirhythm::Result<T> + Send,
) -> PyResult<T> {
    if threads == Some(0) {
        return Err(PyValueError::new_err(
            "invalid parameter threads = 0: allowed range is 1 or more (or None: one per core)",
        ));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("starting the thread pool: {e}")))?;
    let watch = Watch::default();
    let profiling = PROFILING.with(|p| p.get()).is_some();
    let (result, raised) = py.detach(|| {
        std::thread::scope(|s| {
            let handle = s.spawn(|| {
                pool.install(|| {
                    if profiling {
                        let (r, p) = trirhythm::profile::record(|| work(&watch));
                        r.map(|v| (v, Some(p)))
                    } else {
                        work(&watch).map(|v| (v, None))
                    }
                })
            });
            let mut raised: Option<PyErr> = None;
            let mut last = (u64::MAX, u64::MAX);
            let mut next_report = Instant::now();
            while !handle.is_finished() {
                std::thread::sleep(Duration::from_millis(10));
                if Instant::now() < next_report || raised.is_some() {
                    continue;
                }
                next_report = Instant::now() + POLL;
                let now = (
                    watch.done.load(Ordering::Relaxed),
                    watch.total.load(Ordering::Relaxed),
                );
                let outcome = Python::attach(|py| -> PyResult<()> {
                    py.check_signals()?;
                    if let Some(cb) = &progress {
                        if now != last && now.1 > 0 {
                            cb.call1(py, now)?;
                        }
                    }
                    Ok(())
                });
                last = now;
                if let Err(e) = outcome {
                    watch.flag.cancel();
                    raised = Some(e);
                }
            }
            let result = handle.join().unwrap_or_else(|_| {
                Err(trirhythm::Error::Undefined {
                    what: "the run",
                    why: "a worker thread panicked".into(),
                })
            });
            (result, raised)
        })
    });
    if let Some(e) = raised {
        return Err(e);
    }
    let (value, profile) = result.map_err(py_err)?;
    if let Some(q) = profile {
        // calls of one thread run one after another: their critical paths add up
        PROFILING.with(|p| {
            p.set(p.get().map(|a| Profile {
                total_cpu_s: a.total_cpu_s + q.total_cpu_s,
                critical_path_s: a.critical_path_s + q.critical_path_s,
                tasks: a.tasks + q.tasks,
                wall_s: a.wall_s + q.wall_s,
            }))
        });
    }
    if let Some(cb) = &progress {
        let t = watch.total.load(Ordering::Relaxed);
        if t > 0 {
            cb.call1(py, (t, t))?;
        }
    }
    Ok(value)
}

/// The model choices of a call: `system`, `barrier`, `memory`, `tolerance` (`None`: the
/// library's default of the step, `trirhythm::engine::step_tolerance`).
fn model(system: &str, barrier: bool, memory: &str, tolerance: Option<f64>) -> PyResult<Model> {
    Ok(Model {
        system: System::parse(system).map_err(py_err)?,
        barrier: if barrier {
            trirhythm::engine::Barrier::On
        } else {
            trirhythm::engine::Barrier::Off
        },
        memory: MemoryKind::parse(memory).map_err(py_err)?,
        tolerance,
    })
}

fn impact(name: &str) -> PyResult<ImpactMemory> {
    ImpactMemory::parse(name).map_err(py_err)
}

fn variant(name: &str) -> PyResult<Variant> {
    Variant::parse(name).map_err(py_err)
}

/// The General kernel's terms of a `trirhythm.Model` (Duffing, Rayleigh, forcing; `None`
/// without a model or for the paper's family), refused by name where the engine does not step
/// a term (as `--model FILE`).
fn terms_of(model: Option<PyRef<'_, PyModel>>) -> PyResult<Option<model::GeneralTerms>> {
    match model {
        None => Ok(None),
        Some(m) => Ok(m.0.engine_terms("the engine").map_err(py_err)?.1),
    }
}

/// `call` for a `model=` outside the paper's family: refused with the library's reason
/// ([`trirhythm::theory::averaging::closed_forms`]), since `call` is built on the paper's
/// averaged theory (its cycles and boundaries), as on the command line.
fn theory_only(model: Option<PyRef<'_, PyModel>>, call: &str) -> PyResult<()> {
    match model.map(|m| trirhythm::theory::averaging::closed_forms(&m.0)) {
        Some(Err(why @ trirhythm::Error::NotApplicable { .. })) => {
            Err(PyValueError::new_err(format!(
                "model: {call} is built on the paper's averaged theory (its cycles and \
                 boundaries): {why}"
            )))
        }
        Some(Err(e)) => Err(py_err(e)),
        _ => Ok(()),
    }
}

/// A validated parameter set (`trirhythm.Params`): immutable; `with_(**values)` makes a new
/// one.
#[pyclass(name = "Params", module = "trirhythm", frozen, eq, hash)]
#[derive(Clone, PartialEq)]
struct PyParams(Params);

/// Equal parameter sets hash alike: the keys and the bits of the values (−0 as 0, as `==`
/// has it; validated parameters hold no NaN).
impl std::hash::Hash for PyParams {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        for (k, v) in self.0.key_values() {
            k.hash(h);
            (v + 0.0).to_bits().hash(h);
        }
    }
}

/// The parameter a key sets (`lambda_` and `lambda`, `alpha0` and `c2`, `beta0` and `c3`,
/// `gamma0` and `c4`, `delta0` and `c5`, `c02` and `c2` set the same one), so that two keys of
/// one call that set the same parameter are refused instead of one overriding the other.
fn slot(key: &str) -> String {
    match key {
        "alpha0" => "c2".into(),
        "beta0" => "c3".into(),
        "gamma0" => "c4".into(),
        "delta0" => "c5".into(),
        _ => match key.strip_prefix('c').map(str::parse::<u64>) {
            Some(Ok(k)) => format!("c{k}"),
            _ => key.into(),
        },
    }
}

#[pymethods]
impl PyParams {
    /// The parameters of `pairs` (key, value) over the defaults (Fig. 4(c)'s set with r = 1,
    /// D = 0, τ = 0), validated.
    #[new]
    #[pyo3(signature = (**values), text_signature = "(**values)")]
    fn new(values: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        PyParams(Params::default()).with_(values)
    }

    /// A copy with `values` (keys as `keys()` lists, `lambda_` for `lambda`, `c<k>` for a
    /// damping coefficient)
    /// changed; the result is validated: a bad value raises `ValueError` naming the key, the
    /// value and the allowed range. Two keys that set the same parameter (`alpha0` and `c2`,
    /// `lambda` and `lambda_`) are refused, naming both.
    #[pyo3(signature = (**values))]
    fn with_(&self, values: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut p = self.0.clone();
        if let Some(values) = values {
            let mut seen: Vec<(String, String)> = Vec::new();
            for (k, v) in values.iter() {
                let given: String = k.extract()?;
                // `lambda` is a Python keyword: `with_(lambda_=0.9)`
                let key = given.strip_suffix('_').unwrap_or(&given).to_string();
                let at = slot(&key);
                if let Some((other, _)) = seen.iter().find(|(_, s)| *s == at) {
                    return Err(PyValueError::new_err(format!(
                        "conflicting parameters {other} and {given}: both set {at}; give one"
                    )));
                }
                seen.push((given.clone(), at));
                let value: f64 = v.extract().map_err(|_| {
                    PyValueError::new_err(format!(
                        "invalid value for parameter {key}: `{}` is not a number",
                        v.repr().map(|r| r.to_string()).unwrap_or_default()
                    ))
                })?;
                p.set(&key, value).map_err(py_err)?;
            }
        }
        p.validate().map_err(py_err)?;
        Ok(PyParams(p))
    }

    /// The value of `key`.
    fn __getitem__(&self, key: &str) -> PyResult<f64> {
        self.0.get(key).map_err(py_err)
    }

    /// The keys, in order.
    fn keys(&self) -> Vec<String> {
        self.0.key_values().into_iter().map(|(k, _)| k).collect()
    }

    /// `{key: value}` in key order.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in self.0.key_values() {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// `Params(mu0=0.01, omega0=1, lambda_=0.99, …)`: every key with its exact value, as
    /// Python that gives the same parameters back.
    fn __repr__(&self) -> String {
        let pairs: Vec<String> = self
            .0
            .key_values()
            .into_iter()
            .map(|(k, v)| {
                let k = if k == "lambda" { "lambda_".into() } else { k };
                format!("{k}={}", trirhythm::error::Exact(v))
            })
            .collect();
        format!("Params({})", pairs.join(", "))
    }

    /// Pickled as its key–value pairs (so that it travels to Dask workers).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyDict>,))> {
        let f = py
            .import("trirhythm._trirhythm")?
            .getattr("_params_from_dict")?;
        Ok((f, (self.to_dict(py)?,)))
    }
}

/// `Params(**d)`, for unpickling.
#[pyfunction]
fn _params_from_dict(d: &Bound<'_, PyDict>) -> PyResult<PyParams> {
    PyParams::new(Some(d))
}

/// The parameters of a preset (`presets()` lists them).
#[pyfunction]
fn preset(name: &str) -> PyResult<PyParams> {
    Ok(PyParams(model::preset(name).map_err(py_err)?.params))
}

/// Every preset as `(name, description, notes)`.
#[pyfunction]
fn presets() -> Vec<(String, String, Vec<String>)> {
    model::presets()
        .into_iter()
        .map(|p| {
            (
                p.name.to_string(),
                p.description.to_string(),
                p.notes.iter().map(|n| n.to_string()).collect(),
            )
        })
        .collect()
}

/// A Python value as JSON for the model's serde form; `at` is its dotted field, named in the
/// error when the value is not a number, string, boolean, list or dict with string keys, or a
/// number that is not finite (JSON has no NaN: the field is refused here, by name).
fn to_json(v: &Bound<'_, PyAny>, at: &str) -> PyResult<serde_json::Value> {
    use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyString, PyTuple};
    use serde_json::Value;
    let field = |name: &str| {
        if at.is_empty() {
            name.to_string()
        } else {
            format!("{at}.{name}")
        }
    };
    Ok(if v.is_instance_of::<PyBool>() {
        Value::Bool(v.extract()?)
    } else if v.is_instance_of::<PyInt>() {
        Value::from(v.extract::<i64>()?)
    } else if v.is_instance_of::<PyString>() {
        Value::String(v.extract()?)
    } else if v.is_instance_of::<PyFloat>() || v.hasattr("__float__")? {
        let x: f64 = v.extract()?;
        serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "invalid parameter {at} = {x}: allowed range is a finite number"
                ))
            })?
    } else if let Ok(d) = v.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, x) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| PyValueError::new_err(format!("model: {at}: keys are strings")))?;
            let value = to_json(&x, &field(&key))?;
            map.insert(key, value);
        }
        Value::Object(map)
    } else if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            out.push(to_json(&x?, &field(&i.to_string()))?);
        }
        Value::Array(out)
    } else {
        return Err(PyValueError::new_err(format!(
            "model: {at}: {} is not a number, string, list or dict",
            v.repr()?
        )));
    })
}

/// One oscillator of the class (`trirhythm.Model`): the keyword arguments are the model
/// file's tables (`leading={"lambda": 0.998}`, `damping={"mu0": 0.005}`, …), validated; a bad
/// field raises `ValueError` naming the dotted field. `Model.load(path)` reads a file,
/// `to_toml()` writes one, `Model.from_params(params)` is the paper's Eq. 1 of a `Params`.
#[pyclass(name = "Model", module = "trirhythm", frozen, eq)]
#[derive(Clone, PartialEq)]
struct PyModel(model::Model);

#[pymethods]
impl PyModel {
    #[new]
    #[pyo3(signature = (**tables))]
    fn new(tables: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let value = match tables {
            Some(t) => to_json(t.as_any(), "")?,
            None => serde_json::Value::Object(Default::default()),
        };
        Ok(PyModel(model::Model::from_tables(value).map_err(py_err)?))
    }

    /// The model of a model file's text.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        Ok(PyModel(model::Model::from_toml_str(text).map_err(py_err)?))
    }

    /// The model of the model file at `path`.
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PyValueError::new_err(format!(
                "model file {}: cannot read it: {e}",
                path.display()
            ))
        })?;
        Self::from_toml(&text)
    }

    /// A copy with `values` set, each named by its dotted field path as in the model file's
    /// errors (`m.with_(**{"restoring.cubic": 0.5, "wall.0.restitution": 0.9})`; a table or
    /// list element that is absent is created), validated as a whole: a bad value raises
    /// `ValueError` naming the field, its value and the allowed range.
    #[pyo3(signature = (**values))]
    fn with_(&self, values: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        use serde_json::Value;
        let mut doc = serde_json::to_value(&self.0).map_err(json_err)?;
        for (k, v) in values.into_iter().flatten() {
            let path: String = k.extract()?;
            let mut at = &mut doc;
            for part in path.split('.') {
                at = match at {
                    Value::Object(map) => map
                        .entry(part.to_string())
                        .or_insert_with(|| Value::Object(Default::default())),
                    Value::Array(list) => {
                        let i: usize = part.parse().map_err(|_| {
                            PyValueError::new_err(format!(
                                "model: {path}: `{part}` is not an index of a list"
                            ))
                        })?;
                        let len = list.len();
                        if i == len {
                            list.push(Value::Object(Default::default()));
                        }
                        list.get_mut(i).ok_or_else(|| {
                            PyValueError::new_err(format!(
                                "model: {path}: index {i} is past the list's end (it has \
                                 {len} elements)"
                            ))
                        })?
                    }
                    _ => {
                        return Err(PyValueError::new_err(format!(
                            "model: {path}: `{part}` is inside a value, not a table"
                        )))
                    }
                };
            }
            *at = to_json(&v, &path)?;
        }
        Ok(PyModel(model::Model::from_tables(doc).map_err(py_err)?))
    }

    /// The paper's Eq. (1) of `params` (the wall at 0, additive noise, the start (1, 0)).
    #[staticmethod]
    fn from_params(params: &PyParams) -> Self {
        PyModel(model::Model::from(&params.0))
    }

    /// The model file's text (`format = 1`, commented; reads back to the same model).
    fn to_toml(&self) -> String {
        self.0.to_toml()
    }

    /// The tables as a dict (what `Model(**d)` takes back).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = serde_json::to_string(&self.0).map_err(json_err)?;
        py.import("json")?.call_method1("loads", (text,))
    }

    /// The paper family's `Params`, or `None` when the model has a term outside it.
    fn paper_params(&self) -> Option<PyParams> {
        self.0.paper_params().map(PyParams)
    }

    /// `(params, barrier, u0, v0, general)` of the model as the engine steps it: the paper
    /// family's part, and whether it has terms of the General kernel (Duffing, Rayleigh,
    /// forcing) that the calls take through `model=`; `ValueError` naming a term the engine
    /// does not step.
    fn _engine(&self) -> PyResult<(PyParams, bool, f64, f64, bool)> {
        let (f, terms) = self.0.engine_terms("the engine").map_err(py_err)?;
        Ok((
            PyParams(f.params),
            f.wall,
            f.start.0,
            f.start.1,
            terms.is_some(),
        ))
    }

    /// `Model(**{tables})`: one line, Python that gives the same model back (`to_toml()`
    /// is the commented file).
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!("Model(**{})", self.to_dict(py)?.repr()?))
    }

    /// Pickled as its file text.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let f = py
            .import("trirhythm._trirhythm")?
            .getattr("Model")?
            .getattr("from_toml")?;
        Ok((f, (self.0.to_toml(),)))
    }
}

/// The averaged theory of a parameter set in one formula variant.
#[pyclass(name = "Theory", module = "trirhythm", frozen)]
struct PyTheory(Theory);

#[pymethods]
impl PyTheory {
    #[new]
    #[pyo3(signature = (params, variant="paper"))]
    fn new(params: &PyParams, variant: &str) -> PyResult<Self> {
        Ok(PyTheory(
            Theory::new(&params.0, self::variant(variant)?).map_err(py_err)?,
        ))
    }

    /// Eq. 5's coefficients `{mu1, beta1, omega1, beta2}`.
    fn equivalents<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let e = self.0.equivalents();
        let d = PyDict::new(py);
        d.set_item("mu1", e.mu1)?;
        d.set_item("beta1", e.beta1)?;
        d.set_item("omega1", e.omega1)?;
        d.set_item("beta2", e.beta2)?;
        Ok(d)
    }

    /// The cycles (D = 0) or modes of P(A) (D > 0): a `Cycles` named tuple of arrays
    /// `(amplitude, stable, fold)`.
    fn cycles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let c = self.0.cycles();
        let arrays = (
            c.iter()
                .map(|c| c.amplitude)
                .collect::<Vec<_>>()
                .into_pyarray(py),
            c.iter()
                .map(|c| c.stable)
                .collect::<Vec<_>>()
                .into_pyarray(py),
            c.iter()
                .map(|c| c.fold)
                .collect::<Vec<_>>()
                .into_pyarray(py),
        );
        py.import("trirhythm._results")?
            .getattr("Cycles")?
            .call1(arrays)
    }

    /// The averaged drift f(A) (Eq. 18) at each amplitude.
    fn drift<'py>(&self, py: Python<'py>, a: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        a.iter()
            .map(|&a| self.0.drift(a))
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// df/dA at each amplitude (`trirhythm drift`'s `df_dA`).
    fn drift_slope<'py>(&self, py: Python<'py>, a: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        a.iter()
            .map(|&a| self.0.drift_slope(a))
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// The energy change per period ΔE(A) (Eq. 20; `trirhythm drift`'s `delta_E`).
    fn energy_change<'py>(&self, py: Python<'py>, a: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        a.iter()
            .map(|&a| self.0.energy_change(a))
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// The FPK drift m1(A) (`trirhythm potential`'s `m1`; +∞ at A = 0 with noise, the limit).
    fn fpk_drift<'py>(&self, py: Python<'py>, a: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        a.iter()
            .map(|&a| self.0.fpk_drift(a))
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// The extrema of U_eff as `Extremum` named tuples `(amplitude, potential, minimum)`
    /// (`trirhythm barriers --format json`'s `extrema`).
    fn extrema<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let make = py.import("trirhythm._results")?.getattr("Extremum")?;
        self.0
            .extrema()
            .into_iter()
            .map(|e| make.call1((e.amplitude, e.potential, e.minimum)))
            .collect()
    }

    /// The pseudo-potential U_eff(A) at each amplitude.
    fn potential<'py>(&self, py: Python<'py>, a: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        a.iter()
            .map(|&a| self.0.potential(a))
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// The energy barriers as `Barrier` named tuples `(well, crest, side, height, name)`,
    /// named `dU1`, `dU2`, … in order, as `trirhythm barriers --format json` names them.
    fn barriers<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let make = py.import("trirhythm._results")?.getattr("Barrier")?;
        self.0
            .barriers()
            .into_iter()
            .enumerate()
            .map(|(i, b)| {
                make.call1((
                    b.well,
                    b.crest,
                    b.side.name(),
                    b.height,
                    format!("dU{}", i + 1),
                ))
            })
            .collect()
    }

    /// The stationary density `kind` (`amplitude` P(A), `energy` P(H), `log-amplitude`)
    /// on `grid`; `joint` takes `grid` and `v` (P(U, U̇) on the outer product).
    #[pyo3(signature = (kind, grid, v=None))]
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        kind: &str,
        grid: Vec<f64>,
        v: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let pdf = self.0.amplitude_pdf().map_err(py_err)?;
        let one = |f: &dyn Fn(f64) -> f64| grid.iter().map(|&x| f(x)).collect::<Vec<_>>();
        let out = match (kind, v) {
            ("amplitude", None) => one(&|a| pdf.density(a)),
            ("log-amplitude", None) => one(&|a| pdf.log_density(a)),
            ("energy", None) => one(&|h| pdf.energy_density(h)),
            ("joint", Some(v)) => {
                let rows: Vec<Vec<f64>> = v
                    .iter()
                    .map(|&vv| grid.iter().map(|&u| pdf.joint_density(u, vv)).collect())
                    .collect();
                return Ok(numpy::PyArray2::from_vec2(py, &rows)
                    .map_err(|e| PyValueError::new_err(e.to_string()))?
                    .into_any());
            }
            ("joint", None) => {
                return Err(PyValueError::new_err(
                    "pdf('joint', u, v): give v, the U̇ grid",
                ))
            }
            _ => {
                return Err(PyValueError::new_err(format!(
                    "unknown kind `{kind}`: expected one of amplitude, log-amplitude, energy, joint"
                )))
            }
        };
        Ok(out.into_pyarray(py).into_any())
    }
}

/// One path (`simulate`): `(t, u, v, eta, summary_json)`; `eta` empty without noise.
#[pyfunction]
#[pyo3(signature = (params, t_end, dt, u0, v0, seed, path, every, system, barrier, memory, tolerance, impact_memory, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _simulate<'py>(
    py: Python<'py>,
    params: &PyParams,
    t_end: f64,
    dt: f64,
    u0: f64,
    v0: f64,
    seed: u64,
    path: u64,
    every: usize,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    impact_memory: &str,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if every == 0 {
        return Err(PyValueError::new_err(
            "invalid parameter every = 0: allowed range is 1 or more",
        ));
    }
    let terms = terms_of(model)?;
    let m = self::model(system, barrier, memory, tolerance)?;
    let method = m.method(dt, impact(impact_memory)?);
    let problem = m
        .problem(&params.0)
        .and_then(|p| p.with_terms(terms))
        .and_then(|p| p.with_start(u0, v0))
        .map_err(py_err)?;
    // the step guard first, as the command line's: a step that cannot resolve the problem is
    // refused naming dt (before t_end is checked as a whole number of such steps)
    let step_warnings = trirhythm::analysis::check_step(&problem, &method)
        .and_then(|r| r.require())
        .map_err(py_err)?
        .warnings();
    let options = Options {
        t_end,
        seed,
        path,
        record_every: every,
        ..Default::default()
    };
    let start = Instant::now();
    let tr = long_call(py, threads, progress, |w| {
        simulate_with(&problem, &method, &options, w)
    })?;
    let summary = trirhythm_paper::views::PathSummary::of(&tr, start.elapsed().as_secs_f64());
    let d = PyDict::new(py);
    d.set_item(
        "summary",
        serde_json::to_string(&summary).map_err(json_err)?,
    )?;
    d.set_item("t", tr.t.into_pyarray(py))?;
    d.set_item("u", tr.u.into_pyarray(py))?;
    d.set_item("v", tr.v.into_pyarray(py))?;
    d.set_item("eta", tr.eta.into_pyarray(py))?;
    d.set_item("step_warnings", step_warnings)?;
    Ok(d)
}

/// An ensemble request from the keyword arguments of `ensemble`.
#[allow(clippy::too_many_arguments)]
fn ensemble_request(
    params: &PyParams,
    paths: usize,
    t_end: f64,
    burn_in: f64,
    seed: u64,
    dt: f64,
    u0: Vec<f64>,
    variant: &str,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    impact_memory: &str,
    bins: usize,
    joint_bins: usize,
    amplitude_max: Option<f64>,
    sample_every: u64,
    terms: Option<model::GeneralTerms>,
) -> PyResult<EnsembleRequest> {
    Ok(EnsembleRequest {
        params: params.0.clone(),
        variant: self::variant(variant)?,
        model: self::model(system, barrier, memory, tolerance)?,
        impact_memory: impact(impact_memory)?,
        dt,
        paths,
        t_end,
        burn_in,
        seed,
        u0,
        bins,
        joint_bins,
        amplitude_max,
        sample_every,
        lanes: trirhythm::engine::Lanes::Auto,
        terms,
    })
}

/// Run paths `which` (all when `None`) of an ensemble; with `merge`, the document of the whole
/// ensemble (JSON), otherwise the paths' statistics (JSON list, for `merge_paths`). `backend`
/// `"cpu"` (the CPU engine) or `"gpu"` (`trirhythm_gpu::run_ensemble` on the GPU, the whole
/// ensemble in one piece; the document adds `"backend": "gpu"`).
#[pyfunction]
#[pyo3(signature = (params, paths, t_end, burn_in, seed, dt, u0, variant, system, barrier, memory, tolerance, impact_memory, bins, joint_bins, amplitude_max, sample_every, which=None, pieces=None, merge=true, model=None, threads=None, progress=None, setup_only=false, backend="cpu"))]
#[allow(clippy::too_many_arguments)]
fn _ensemble(
    py: Python<'_>,
    params: &PyParams,
    paths: usize,
    t_end: f64,
    burn_in: f64,
    seed: u64,
    dt: f64,
    u0: Vec<f64>,
    variant: &str,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    impact_memory: &str,
    bins: usize,
    joint_bins: usize,
    amplitude_max: Option<f64>,
    sample_every: u64,
    which: Option<Vec<u64>>,
    pieces: Option<Vec<String>>,
    merge: bool,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    setup_only: bool,
    backend: &str,
) -> PyResult<String> {
    let backend: trirhythm_gpu::Backend = backend.parse().map_err(py_err)?;
    if backend == trirhythm_gpu::Backend::Gpu && (which.is_some() || pieces.is_some() || !merge) {
        return Err(PyValueError::new_err(
            "backend='gpu' runs the whole ensemble in one piece: ensemble_paths and \
             merge_paths run on the CPU (backend='cpu')",
        ));
    }
    let request = ensemble_request(
        params,
        paths,
        t_end,
        burn_in,
        seed,
        dt,
        u0,
        variant,
        system,
        barrier,
        memory,
        tolerance,
        impact_memory,
        bins,
        joint_bins,
        amplitude_max,
        sample_every,
        terms_of(model)?,
    )?;
    let s = request.setup().map_err(py_err)?;
    if setup_only {
        // what the run would use where the user left it open (a density sweep's common bins)
        return serde_json::to_string(&serde_json::json!({
            "amplitude_max": s.spec.amplitude_max,
            "choices": s.choices,
        }))
        .map_err(json_err);
    }
    // every size, step and range checked before any work
    ens::run_paths(
        &s.problem,
        &s.method,
        &s.spec,
        &[],
        &trirhythm::monitor::Silent,
    )
    .map_err(py_err)?;
    let mut done: Vec<PathStats> = Vec::new();
    for text in pieces.unwrap_or_default() {
        let batch: Vec<PathStats> = serde_json::from_str(&text).map_err(|e| {
            PyValueError::new_err(format!("pieces: not the paths of an ensemble ({e})"))
        })?;
        for p in batch {
            if !ens::fits(&p, &s.spec, &s.problem) {
                return Err(PyValueError::new_err(format!(
                    "pieces: path {} was run for another ensemble (other parameters, sizes or \
                     seed)",
                    p.path
                )));
            }
            if done.iter().any(|d| d.path == p.path) {
                return Err(PyValueError::new_err(format!(
                    "pieces: path {} is given twice",
                    p.path
                )));
            }
            done.push(p);
        }
    }
    let todo: Vec<u64> = match which {
        Some(w) => w,
        None => (0..paths as u64)
            .filter(|i| !done.iter().any(|d| d.path == *i))
            .collect(),
    };
    let start = Instant::now();
    if backend == trirhythm_gpu::Backend::Gpu {
        let r = long_call(py, threads, progress, |w| {
            trirhythm_gpu::run_ensemble(&s.problem, &s.method, &s.spec, w, backend)
        })?;
        let wall = start.elapsed().as_secs_f64();
        let theory = s.comparisons(&r);
        let mut doc = serde_json::to_value(s.document(&r, &theory, wall)).map_err(json_err)?;
        if let Some(o) = doc.as_object_mut() {
            o.insert("backend".into(), "gpu".into());
        }
        return serde_json::to_string(&doc).map_err(json_err);
    }
    let fresh = long_call(py, threads, progress, |w| {
        ens::run_paths(&s.problem, &s.method, &s.spec, &todo, w)
    })?;
    if !merge {
        return serde_json::to_string(&fresh).map_err(json_err);
    }
    done.extend(fresh);
    let r = ens::merge(&s.problem, &s.method, &s.spec, done).map_err(py_err)?;
    let wall = start.elapsed().as_secs_f64();
    let theory = s.comparisons(&r);
    serde_json::to_string(&s.document(&r, &theory, wall)).map_err(json_err)
}

/// An ensemble by well decomposition: the document of `trirhythm ensemble --method wells`
/// (JSON).
#[pyfunction]
#[pyo3(signature = (params, paths, t_end, burn_in, seed, dt, u0, variant, system, barrier, memory, tolerance, impact_memory, bins, joint_bins, amplitude_max, sample_every, clones, max_excursion, max_iterations, separation, core_quantile, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _ensemble_wells(
    py: Python<'_>,
    params: &PyParams,
    paths: usize,
    t_end: f64,
    burn_in: f64,
    seed: u64,
    dt: f64,
    u0: Vec<f64>,
    variant: &str,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    impact_memory: &str,
    bins: usize,
    joint_bins: usize,
    amplitude_max: Option<f64>,
    sample_every: u64,
    clones: usize,
    max_excursion: f64,
    max_iterations: usize,
    separation: f64,
    core_quantile: f64,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let request = ensemble_request(
        params,
        paths,
        t_end,
        burn_in,
        seed,
        dt,
        u0,
        variant,
        system,
        barrier,
        memory,
        tolerance,
        impact_memory,
        bins,
        joint_bins,
        amplitude_max,
        sample_every,
        terms_of(model)?,
    )?;
    let s = request.setup().map_err(py_err)?;
    let wspec = ens::WellsSpec {
        clones,
        max_excursion,
        max_iterations,
        separation,
        core_quantile,
    };
    let start = Instant::now();
    let w = long_call(py, threads, progress, |m| s.run_wells(&wspec, m))?;
    let wall = start.elapsed().as_secs_f64();
    let theory = s.comparisons(&w.result);
    let line = trirhythm_paper::requests::wells_line(&s.method_line, &wspec);
    serde_json::to_string(&s.wells_document(&w, &theory, wall, &line)).map_err(json_err)
}

/// The largest Lyapunov exponent (JSON of the library's result).
#[pyfunction]
#[pyo3(signature = (params, t_end, transient, dt, paths, seed, u0, impact_memory, method, renormalise_every, separation, system, barrier, memory, tolerance, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _lyapunov(
    py: Python<'_>,
    params: &PyParams,
    t_end: f64,
    transient: f64,
    dt: f64,
    paths: usize,
    seed: u64,
    u0: f64,
    impact_memory: &str,
    method: &str,
    renormalise_every: u64,
    separation: f64,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let terms = terms_of(model)?;
    let m = self::model(system, barrier, memory, tolerance)?;
    let pc = m.method(dt, impact(impact_memory)?);
    let problem = m
        .problem(&params.0)
        .and_then(|p| p.with_terms(terms))
        .and_then(|p| p.with_start(u0, 0.0))
        .map_err(py_err)?;
    let spec = LyapunovSpec {
        paths,
        seed,
        transient,
        length: t_end,
        renormalise_every,
        separation,
        method: lyapunov_method(method)?,
        ..Default::default()
    };
    spec.validate().map_err(py_err)?;
    let r = long_call(py, threads, progress, |w| {
        lle::largest_lyapunov(&problem, &pc, &spec, w)
    })?;
    serde_json::to_string(&r).map_err(json_err)
}

/// `tangent` or `two-trajectory`.
fn lyapunov_method(name: &str) -> PyResult<lle::LyapunovMethod> {
    match name {
        "tangent" => Ok(lle::LyapunovMethod::Tangent),
        "two-trajectory" => Ok(lle::LyapunovMethod::TwoTrajectory),
        _ => Err(PyValueError::new_err(format!(
            "unknown method `{name}`: expected one of tangent, two-trajectory"
        ))),
    }
}

/// The critical noise by regime, as `trirhythm critical-noise` (JSON of the paper crate's
/// `critical::CriticalNoise`): the curves of the exponent against D (`noises`, or `points`
/// values log-spaced over `d_range` as `--d-range`/`--points`), one per attractor of the
/// noise-free system, for `params` or each value of `sweep` (key, values), each decided by the
/// regime rules of Figs 17–19. `dt` None: the figures' rule (Δt ≤ τ/10). Everything is checked
/// before any work, the step guard included (its warnings are in the document).
#[pyfunction]
#[pyo3(signature = (params, noises, d_range, points, sweep, t_end, transient, dt, paths, seed, impact_memory, method, renormalise_every, separation, system, barrier, memory, tolerance, variant, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _critical_noise(
    py: Python<'_>,
    params: &PyParams,
    noises: Option<Vec<f64>>,
    d_range: Option<(f64, f64)>,
    points: usize,
    sweep: Option<(String, Vec<f64>)>,
    t_end: f64,
    transient: f64,
    dt: Option<f64>,
    paths: usize,
    seed: u64,
    impact_memory: &str,
    method: &str,
    renormalise_every: u64,
    separation: f64,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    variant: &str,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    theory_only(model, "critical_noise")?;
    let spec = LyapunovSpec {
        paths,
        seed,
        transient,
        length: t_end,
        renormalise_every,
        separation,
        method: lyapunov_method(method)?,
        ..Default::default()
    };
    let noises = match (noises, d_range) {
        (Some(d), None) => d,
        (None, Some((lo, hi))) => log_noises(lo, hi, points).map_err(py_err)?,
        _ => {
            return Err(PyValueError::new_err(
                "give the noise intensities either as noises or as d_range (with points)",
            ))
        }
    };
    let request = CriticalRequest {
        base: params.0.clone(),
        sweep,
        noises,
        sizes: Sizes {
            model: self::model(system, barrier, memory, tolerance)?,
            dt,
            impact_memory: impact(impact_memory)?,
            ..Sizes::of_spec(spec)
        },
        variant: self::variant(variant)?,
    };
    request.validate().map_err(py_err)?;
    let r = long_call(py, threads, progress, |w| critical_noise(&request, w))?;
    serde_json::to_string(&r).map_err(json_err)
}

/// The attractor of the noise-free path from (u0, 0) (JSON of the library's
/// `StartAttractor`); with `u0` None, one start per attractor (JSON list).
#[pyfunction]
#[pyo3(signature = (params, u0, dt, impact_memory, t_max, variant, system, barrier, memory, tolerance, model=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn _attractor(
    py: Python<'_>,
    params: &PyParams,
    u0: Option<f64>,
    dt: f64,
    impact_memory: &str,
    t_max: f64,
    variant: &str,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
) -> PyResult<String> {
    theory_only(model, "attractor")?;
    let m = self::model(system, barrier, memory, tolerance)?;
    let method = m.method(dt, impact(impact_memory)?);
    let problem = m
        .problem(&params.0)
        .and_then(|p| p.with_start(u0.unwrap_or(1.0), 0.0))
        .map_err(py_err)?;
    let spec = lle::AttractorSpec {
        t_max,
        variant: self::variant(variant)?,
        ..Default::default()
    };
    spec.validate().map_err(py_err)?;
    method.validate().map_err(py_err)?;
    match u0 {
        Some(u0) => {
            let s = long_call(py, threads, None, |_| {
                lle::classify_start(&problem, &method, u0, &spec)
            })?;
            serde_json::to_string(&s).map_err(json_err)
        }
        None => {
            let s = long_call(py, threads, None, |_| {
                lle::attractor_starts(&problem, &method, &spec)
            })?;
            serde_json::to_string(&s).map_err(json_err)
        }
    }
}

/// The phase response of the cycle the noise-free path from (u0, 0) reaches and the
/// phase-reduction coefficient (JSON of the library's `PhaseResponse`, with `u0` and the step
/// guard's `step_warnings`), as `trirhythm phase-response`: `u0` None starts on the averaged
/// theory's largest stable amplitude (D = 0), Δt must lie in [1e-4, 0.1], and a step that
/// cannot resolve the problem is refused.
#[pyfunction]
#[pyo3(signature = (params, u0, dt, impact_memory, phases, kick, periods, t_max, variant, system, barrier, memory, tolerance, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _phase_response(
    py: Python<'_>,
    params: &PyParams,
    u0: Option<f64>,
    dt: f64,
    impact_memory: &str,
    phases: usize,
    kick: f64,
    periods: usize,
    t_max: f64,
    variant: &str,
    system: &str,
    barrier: bool,
    memory: &str,
    tolerance: Option<f64>,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, Vec<String>)> {
    theory_only(model, "phase_response")?;
    let variant = self::variant(variant)?;
    if !(lle::DT_RANGE.0..=lle::DT_RANGE.1).contains(&dt) {
        return Err(py_err(trirhythm::Error::invalid("dt", dt, "[1e-4, 0.1]")));
    }
    let spec = lle::PhaseSpec {
        phases,
        kick,
        periods,
        attractor: lle::AttractorSpec {
            t_max,
            variant,
            ..Default::default()
        },
    };
    spec.validate().map_err(py_err)?;
    let u0 = match u0 {
        Some(u0) => u0,
        None => {
            // the command line's default start: the outer cycle of the theory at D = 0
            match trirhythm_paper::lle::outer_amplitude(&params.0, variant).map_err(py_err)? {
                Some(a) => a,
                None => {
                    return Err(PyValueError::new_err(
                        "the averaged theory has no stable cycle here: give the start with u0",
                    ))
                }
            }
        }
    };
    let m = self::model(system, barrier, memory, tolerance)?;
    let method = m.method(dt, impact(impact_memory)?);
    let problem = m
        .problem(&params.0)
        .and_then(|p| p.with_start(u0, 0.0))
        .map_err(py_err)?;
    let warnings = trirhythm::analysis::check_step(&problem, &method)
        .and_then(|r| r.require())
        .map_err(py_err)?
        .warnings();
    let r = long_call(py, threads, progress, |w| {
        lle::phase_response(&problem, &method, u0, &spec, w)
    })?;
    Ok((serde_json::to_string(&r).map_err(json_err)?, warnings))
}

/// The oscillation boundary in the plane (x_key over `x`, y_key in `y_range`) by `method`
/// (JSON of the library's result).
#[pyfunction]
#[pyo3(signature = (params, x_key, x, y_key, y_range, method="simulation", variant="paper", barrier=true, tolerance=1e-3, model=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn _oscillation_boundary(
    py: Python<'_>,
    params: &PyParams,
    x_key: &str,
    x: Vec<f64>,
    y_key: &str,
    y_range: (f64, f64),
    method: &str,
    variant: &str,
    barrier: bool,
    tolerance: f64,
    model: Option<PyRef<'_, PyModel>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    theory_only(model, "oscillation_boundary")?;
    let m = self::model("fractional", barrier, "soe", Some(1e-10))?;
    let template = m.problem(&params.0).map_err(py_err)?;
    let plane =
        osc::Plane::new(&template, (x_key, x), (y_key, y_range.0, y_range.1)).map_err(py_err)?;
    let method = match method {
        "simulation" => osc::Method::Simulation(Classifier::default()),
        "averaging" => osc::Method::Averaging(self::variant(variant)?),
        "exact" => osc::Method::Exact,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown method `{method}`: expected one of simulation, averaging, exact"
            )))
        }
    };
    let search = Search {
        tolerance,
        ..Default::default()
    };
    let b = long_call(py, threads, progress, |w| {
        osc::boundary(&plane, &method, &search, w)
    })?;
    serde_json::to_string(&b).map_err(json_err)
}

/// The count of stable cycles (`rhythmicity`) or of modes of P(A) (`modes`) over a plane of
/// the averaged theory: `(x, y, counts[ny, nx])`.
#[pyfunction]
#[pyo3(signature = (params, x, y, what="rhythmicity", variant="paper", threads=None, progress=None, folds=false))]
#[allow(clippy::too_many_arguments)]
fn _map<'py>(
    py: Python<'py>,
    params: &PyParams,
    x: (String, f64, f64, usize),
    y: (String, f64, f64, usize),
    what: &str,
    variant: &str,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    folds: bool,
) -> PyResult<PlaneOut<'py>> {
    let what = what_of(what)?;
    let ax = Axis::new(&x.0, x.1, x.2, x.3).map_err(py_err)?;
    let ay = Axis::new(&y.0, y.1, y.2, y.3).map_err(py_err)?;
    let plane = bif::Plane::new(&params.0, ax, ay, self::variant(variant)?).map_err(py_err)?;
    let (map, traced) = long_call(py, threads, progress, |w| {
        let report =
            |done: usize, total: usize| Monitor::<()>::progress(w, done as u64, total as u64);
        let map = bif::classify(&plane, what, &report);
        // the fold curves through the map's transitions, as `trirhythm map --folds`
        let traced = folds.then(|| bif::trace_folds(&map));
        Ok((map, traced))
    })?;
    let (nx, ny) = (map.plane.x.count, map.plane.y.count);
    let rows: Vec<Vec<u8>> = map.counts.chunks(nx).map(|r| r.to_vec()).collect();
    debug_assert_eq!(rows.len(), ny);
    let counts = numpy::PyArray2::from_vec2(py, &rows)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let traced = match traced {
        Some(f) => Some(serde_json::to_string(&f).map_err(json_err)?),
        None => None,
    };
    Ok((
        map.plane.x.values().into_pyarray(py),
        map.plane.y.values().into_pyarray(py),
        counts.into_any(),
        traced,
    ))
}

/// The P-bifurcation map by simulation (`trirhythm map --simulate`): at each point of the
/// plane an ensemble of Eq. (1) on `backend` (`cpu` or `gpu`), the modes of its P(A) counted
/// with their range, beside the theory's count (JSON of the library's `SimulatedMap`).
#[pyfunction]
#[pyo3(signature = (params, x, y, variant="paper", paths=8, t_end=1000.0, burn_in=100.0, dt=0.01, seed=1, bins=40, batches=20, impact_memory="restart", amplitude_max=None, z=3.0, z_lenient=2.0, z_strict=4.0, threads=None, progress=None, backend="cpu"))]
#[allow(clippy::too_many_arguments)]
fn _simulated_map(
    py: Python<'_>,
    params: &PyParams,
    x: (String, f64, f64, usize),
    y: (String, f64, f64, usize),
    variant: &str,
    paths: usize,
    t_end: f64,
    burn_in: f64,
    dt: f64,
    seed: u64,
    bins: usize,
    batches: usize,
    impact_memory: &str,
    amplitude_max: Option<f64>,
    z: f64,
    z_lenient: f64,
    z_strict: f64,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    backend: &str,
) -> PyResult<String> {
    use trirhythm::analysis::simulated_map::{simulate_map, ModeRule, SimulatedMapSpec};
    let backend: trirhythm_gpu::Backend = backend.parse().map_err(py_err)?;
    let ax = Axis::new(&x.0, x.1, x.2, x.3).map_err(py_err)?;
    let ay = Axis::new(&y.0, y.1, y.2, y.3).map_err(py_err)?;
    let plane = bif::Plane::new(&params.0, ax, ay, self::variant(variant)?).map_err(py_err)?;
    let spec = SimulatedMapSpec {
        ensemble: ens::EnsembleSpec {
            paths,
            seed,
            burn_in,
            length: t_end,
            bins,
            joint_bins: 2,
            batches,
            ..Default::default()
        },
        method: trirhythm::engine::PredictorCorrector {
            dt,
            impact_memory: impact(impact_memory)?,
            ..Default::default()
        },
        rule: ModeRule {
            z,
            z_lenient,
            z_strict,
        },
        amplitude_max,
    };
    // every input checked before the worker starts
    spec.validate(&plane).map_err(py_err)?;
    let map = long_call(py, threads, progress, |w| {
        // every point's ensemble on the backend, silent inside a point (its cancellation
        // heard)
        let cancel: trirhythm::monitor::OnlyCancel<trirhythm::analysis::simulated_map::MapPoint> =
            trirhythm::monitor::OnlyCancel(w);
        let runner = |problem: &trirhythm::engine::Problem,
                      method: &trirhythm::engine::PredictorCorrector,
                      es: &ens::EnsembleSpec| {
            trirhythm_gpu::run_ensemble(problem, method, es, &cancel, backend)
        };
        simulate_map(&plane, &spec, &runner, w)
    })?;
    serde_json::to_string(&map).map_err(json_err)
}

/// `rhythmicity` (cycles, roots of f) or `modes` (extrema of P(A), roots of m1).
fn what_of(name: &str) -> PyResult<What> {
    match name {
        "rhythmicity" => Ok(What::Rhythmicity),
        "modes" => Ok(What::Modes),
        _ => Err(PyValueError::new_err(format!(
            "unknown map `{name}`: expected one of rhythmicity, modes"
        ))),
    }
}

/// Every branch of cycles (or modes of P(A)) against `key` over [start, stop], traced through
/// its folds by continuation (`trirhythm branches`; JSON of the library's diagram).
#[pyfunction]
#[pyo3(signature = (params, key, start, stop, what="rhythmicity", variant="paper", step=0.004, threads=None))]
#[allow(clippy::too_many_arguments)]
fn _branches(
    py: Python<'_>,
    params: &PyParams,
    key: &str,
    start: f64,
    stop: f64,
    what: &str,
    variant: &str,
    step: f64,
    threads: Option<usize>,
) -> PyResult<String> {
    // the continuation takes at least 1/step steps: bound the work before it starts
    if !(1e-6..=0.1).contains(&step) {
        return Err(PyValueError::new_err(format!(
            "invalid parameter step = {}: allowed range is [1e-6, 0.1] (the fraction of the \
             interval per continuation step)",
            trirhythm::error::Exact(step)
        )));
    }
    let what = what_of(what)?;
    let variant = self::variant(variant)?;
    let base = params.0.clone();
    let key = key.to_string();
    let bd = long_call(py, threads, None, |_| {
        bif::branches(&base, variant, what, &key, start, stop, step)
    })?;
    serde_json::to_string(&bd).map_err(json_err)
}

/// Figure `n`'s data (JSON: the value `figure N --data` writes under `data`).
#[pyfunction]
#[pyo3(signature = (n, quick=false, variant="paper", threads=None, progress=None))]
fn _figure_data(
    py: Python<'_>,
    n: u32,
    quick: bool,
    variant: &str,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let options = FigureOptions {
        quick,
        variant: self::variant(variant)?,
    };
    if !(1..=19).contains(&n) {
        return Err(PyValueError::new_err(format!(
            "invalid parameter n = {n}: allowed range is 1 to 19 (the paper's figures)"
        )));
    }
    let v = long_call(py, threads, progress, |w| {
        trirhythm_paper::compute_json(n, &options, w)
    })?;
    serde_json::to_string(&v).map_err(json_err)
}

/// The version of the library.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _trirhythm(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyParams>()?;
    m.add_class::<PyTheory>()?;
    m.add_class::<PyModel>()?;
    m.add_function(wrap_pyfunction!(preset, m)?)?;
    m.add_function(wrap_pyfunction!(_profile_start, m)?)?;
    m.add_function(wrap_pyfunction!(_profile_stop, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(_params_from_dict, m)?)?;
    m.add_function(wrap_pyfunction!(_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(_ensemble, m)?)?;
    m.add_function(wrap_pyfunction!(_ensemble_wells, m)?)?;
    m.add_function(wrap_pyfunction!(_lyapunov, m)?)?;
    m.add_function(wrap_pyfunction!(_critical_noise, m)?)?;
    m.add_function(wrap_pyfunction!(_attractor, m)?)?;
    m.add_function(wrap_pyfunction!(_phase_response, m)?)?;
    m.add_function(wrap_pyfunction!(_oscillation_boundary, m)?)?;
    m.add_function(wrap_pyfunction!(_map, m)?)?;
    m.add_function(wrap_pyfunction!(_simulated_map, m)?)?;
    m.add_function(wrap_pyfunction!(_branches, m)?)?;
    m.add_function(wrap_pyfunction!(_figure_data, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}

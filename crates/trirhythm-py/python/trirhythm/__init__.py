"""trirhythm: stochastic fractional-order vibro-impact oscillators with several coexisting
limit cycles, from Python.

The computations are the Rust library's (the same code as the ``trirhythm`` command line, so
the same arguments give the same numbers, bit for bit); this package adapts them to numpy
arrays and dictionaries. Long calls release the GIL, accept ``threads=`` (size of their thread
pool; default one per core), ``progress=`` (a callable ``f(done, total)``, or ``True`` for a
tqdm bar) and stop within a second on KeyboardInterrupt.

>>> import trirhythm as tr
>>> p = tr.preset("fig4c").with_(D=0.01)
>>> path = tr.simulate(p, t_end=10.0, seed=1)
>>> path.u.shape
(1001,)

``sweep`` runs any of these functions over a parameter grid, in-process or on a Dask cluster,
into an ``xarray.Dataset`` (see ``docs/python.md``).
"""

from __future__ import annotations

import json
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Literal, NamedTuple, Protocol, Sequence, TypeVar, cast, overload

import numpy as np

from . import _trirhythm as _native
from ._trirhythm import Model, Params, Theory, preset, version

__all__ = [
    "Model",
    "Params",
    "Theory",
    "preset",
    "presets",
    "simulate",
    "Path",
    "ensemble",
    "Ensemble",
    "Stationarity",
    "NotStationaryWarning",
    "ensemble_paths",
    "merge_paths",
    "EnsemblePaths",
    "lyapunov",
    "critical_noise",
    "CriticalNoise",
    "CriticalCurve",
    "CriticalPoint",
    "Bracket",
    "RestRegime",
    "WellEscape",
    "attractor",
    "attractor_starts",
    "Attractor",
    "phase_response",
    "PhaseResponse",
    "oscillation_boundary",
    "rhythmicity_map",
    "modes_map",
    "simulated_map",
    "SimulatedMap",
    "PlaneMap",
    "PlaneMapFolds",
    "Folds",
    "FoldCurve",
    "branches",
    "Branches",
    "BranchCurve",
    "figure_data",
    "sweep",
    "profiled",
    "Profile",
    "version",
]

__version__ = version()


@dataclass(frozen=True)
class Profile:
    """A parallel profile of a call's native work (``trirhythm::profile``): the CPU seconds of
    all its work on every thread, the critical path (the longest chain of work that must run
    one after the other, in CPU seconds), the independent tasks handed to the thread pool and
    the wall seconds. ``speedup_bound`` = total / critical path is the largest speed-up any
    number of cores can give the call. Several native calls made by one call run one after
    another: their totals, critical paths, tasks and wall times add up."""

    total_cpu_s: float
    critical_path_s: float
    tasks: int
    wall_s: float

    @property
    def speedup_bound(self) -> float:
        return self.total_cpu_s / self.critical_path_s if self.critical_path_s > 0 else 1.0

    def __str__(self) -> str:
        return (
            f"total CPU {self.total_cpu_s:.3g} s, critical path {self.critical_path_s:.3g} s, "
            f"bound {self.speedup_bound:.1f}x, {self.tasks} tasks, wall {self.wall_s:.3g} s"
        )


_R = TypeVar("_R")


def profiled(func: Callable[..., _R], *args: Any, **kwargs: Any) -> tuple[_R, Profile]:
    """Call ``func(*args, **kwargs)`` (any trirhythm function, or a function of yours that calls
    them on this thread) and return ``(result, Profile)``: the parallel profile of the native
    work it ran. The result is the same as without profiling, bit for bit.

    >>> import trirhythm as tr
    >>> e, prof = tr.profiled(tr.lyapunov, tr.preset("fig4c"), paths=4, t_end=20.0, seed=1)
    >>> prof.tasks >= 2 and 0 < prof.critical_path_s <= prof.total_cpu_s
    True
    """
    _native._profile_start()
    try:
        result = func(*args, **kwargs)
    finally:
        got = _native._profile_stop()
    if got is None:  # (stopped by the call itself: nothing recorded)
        got = (0.0, 0.0, 0, 0.0)
    return result, Profile(*got)


def presets() -> dict[str, str]:
    """Every preset's name with its description (``preset(name)`` gives its parameters)."""
    return {name: description for name, description, _notes in _native.presets()}


def _progress(progress):
    """A callable ``f(done, total)`` from ``progress`` (``None``, a callable or ``True``)."""
    if progress is None or progress is False:
        return None
    if progress is True:
        from tqdm.auto import tqdm

        bar = tqdm(total=1.0, bar_format="{l_bar}{bar}| {elapsed}<{remaining}")

        def report(done, total):
            bar.n = done / total if total else 0.0
            bar.refresh()
            if total and done >= total:
                bar.close()

        return report
    if not callable(progress):
        raise ValueError(f"progress = {progress!r}: expected None, True or a callable f(done, total)")
    return progress


def _finite(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"invalid parameter {name} = {value!r}: allowed range is a finite number") from None
    return v


def _tolerance(value) -> float | None:
    """The sum-of-exponentials tolerance: ``None`` (the library's default of the step,
    1e-5·dt² within [1e-10, 1e-6]) or a finite number."""
    return None if value is None else _finite("tolerance", value)


def _count(name: str, value, low: int = 0, high: int | None = None) -> int:
    """An integer in [low, high] (``high=None``: no upper end), or ``ValueError`` naming
    ``name``, its value and the range (never ``OverflowError``: a value past what the engine
    holds is out of range like any other)."""
    high = _HIGHEST if high is None else high
    allowed = f"an integer, {low} or more (at most 2**64 - 1)" if high == _HIGHEST else f"an integer, {low} to {high}"
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= int(value) <= high:
        raise ValueError(f"invalid parameter {name} = {value!r}: allowed range is {allowed}")
    return int(value)


# the largest count the engine takes (u64)
_HIGHEST = 2**64 - 1
# an ensemble's or a Lyapunov exponent's paths: 1 to the engine's MAX_PATHS
_MAX_PATHS = 1_000_000


def _check_params(params) -> Params:
    if not isinstance(params, Params):
        raise ValueError(
            f"invalid parameter params = {params!r}: expected a trirhythm.Params (preset(name) or Params(**values))"
        )
    return params


def _from_model(model, params, given):
    """``(params, barrier, u0, v0)`` of ``model`` as the engine steps it: the paper family's
    part, its wall and its start (``ValueError`` naming a term the engine does not step); the
    General kernel's terms (Duffing, Rayleigh, forcing) travel with ``model=`` to the native
    call. ``given`` holds the run's arguments that the model file says instead (wall, start),
    refused when not ``None``."""
    if not isinstance(model, Model):
        raise ValueError(
            f"invalid parameter model = {model!r}: expected a trirhythm.Model (Model(**tables) or Model.load(path))"
        )
    if params is not None:
        raise ValueError("give params or model=, not both (the model holds the parameters)")
    for name, value in given.items():
        if value is not None:
            raise ValueError(
                f"invalid parameter {name} = {value!r}: the model says the wall and the start "
                "(its wall and start tables); leave it out with model="
            )
    params, barrier, u0, v0, _general = model._engine()
    return params, barrier, u0, v0


def _model_options(model, params, options, call, start=True):
    """``(params, options)`` for a call that takes ``model=``: the model's parameters, with its
    wall as ``barrier`` and (``start``) its U(0) as ``u0`` in ``options`` (its U̇(0) must be 0:
    ``call`` starts at rest)."""
    given = {"barrier": options.get("barrier")}
    if start:
        given["u0"] = options.get("u0")
    params, barrier, u0, v0 = _from_model(model, params, given)
    options = {**options, "barrier": barrier}
    if start:
        if v0 != 0.0:
            raise ValueError(f"invalid parameter start.v0 = {v0!r}: {call} starts its paths at rest; set start.v0 = 0")
        options["u0"] = u0
    return params, options


def _short(text: str, most: int = 160) -> str:
    return text if len(text) <= most else text[: most - 1] + "…"


def _span(x: np.ndarray) -> str:
    return f"[{np.min(x):.6g}, {np.max(x):.6g}]" if len(x) else "[]"


@dataclass(repr=False)
class Path:
    """One simulated path: numpy arrays ``t``, ``u``, ``v`` (and ``eta``, the noise, when
    D > 0, else ``None``) and the run's ``summary`` (steps, impacts, final amplitude, …).
    Its repr is one line (sizes and ranges)."""

    t: np.ndarray
    u: np.ndarray
    v: np.ndarray
    eta: np.ndarray | None
    summary: dict

    def __repr__(self) -> str:
        t = f"{self.t[0]:.6g} to {self.t[-1]:.6g}" if len(self.t) else "none"
        eta = "None" if self.eta is None else f"{len(self.eta)} values"
        return _short(
            f"Path({len(self.t)} samples, t {t}, u in {_span(self.u)}, v in {_span(self.v)}, eta {eta}, "
            f"summary={self.summary!r})",
            400,
        )


def simulate(
    params: Params | None = None,
    t_end: float = 200.0,
    dt: float = 0.01,
    u0: float | None = None,
    v0: float | None = None,
    seed: int = 1,
    path: int = 0,
    every: int = 1,
    system: str = "fractional",
    barrier: bool | None = None,
    impact_memory: str = "continuous",
    memory: str = "soe",
    tolerance: float | None = None,
    threads: int | None = None,
    progress=None,
    *,
    model: Model | None = None,
) -> Path:
    """One path of Eq. 1 (``system="fractional"``) or of Eq. 5 / Eq. 9 (``"equivalent"``,
    ``"zhuravlev"``), recorded every ``every`` steps: bit-identical to ``trirhythm simulate``
    with the same arguments. ``path`` picks noise stream ``path`` of ``seed`` (0: the
    command line's path). ``u0=1``, ``v0=0``, ``barrier=True`` unless given. ``model=`` (a
    ``trirhythm.Model``) in place of ``params``: its parameters, terms, walls and start, as
    ``trirhythm simulate --model FILE`` (the General kernel's terms too: Duffing, Rayleigh,
    forcing, a wall off 0 or keeping below, two walls, a speed-dependent restitution)."""
    if model is not None:
        params, barrier, u0, v0 = _from_model(model, params, dict(u0=u0, v0=v0, barrier=barrier))
    u0 = 1.0 if u0 is None else u0
    v0 = 0.0 if v0 is None else v0
    barrier = True if barrier is None else barrier
    _check_params(params)
    d = _native._simulate(
        params,
        _finite("t_end", t_end),
        _finite("dt", dt),
        _finite("u0", u0),
        _finite("v0", v0),
        _count("seed", seed),
        _count("path", path),
        _count("every", every, 1),
        system,
        bool(barrier),
        memory,
        _tolerance(tolerance),
        impact_memory,
        model=model,
        threads=threads,
        progress=_progress(progress),
    )
    for w in d["step_warnings"]:
        warnings.warn(f"simulate: {w}", RuntimeWarning, stacklevel=2)
    eta = d["eta"] if len(d["eta"]) else None
    return Path(d["t"], d["u"], d["v"], eta, json.loads(d["summary"]))


def _nonfinite(x):
    """The library writes non-finite numbers as strings ("NaN", "inf", "-inf")."""
    if isinstance(x, str):
        try:
            return float(x)
        except ValueError:
            return x
    return x


class NotStationaryWarning(UserWarning):
    """Warned when an ensemble is not stationary (some split-R̂ above 1.1, or the mean amplitude
    drifting by more than 3 standard errors between the window's halves): its statistics are
    those of the window run, not of the stationary law. The message gives R̂, the effective
    sample size and the suggested window; ``Ensemble.stationarity`` holds them. Silence it
    with ``warnings.simplefilter("ignore", trirhythm.NotStationaryWarning)``, or turn it into
    an error with ``"error"``."""


def _inf(x) -> float:
    """A number of a document as a float: the library writes NaN and ±∞ as the strings
    ``"NaN"``, ``"inf"``, ``"-inf"``; ``None`` (undefined) reads as NaN."""
    if x is None:
        return float("nan")
    return float(_nonfinite(x))


class Stationarity(NamedTuple):
    """An ensemble's stationarity diagnosis (the document's ``stationarity``, as numbers:
    ``inf`` where R̂ is infinite — the paths never left their wells —, never ``None``).

    ``stationary``: every R̂ ≤ 1.1 and |``drift_z``| ≤ 3; ``r_hat``: the largest split-R̂
    (of the mean amplitude, ``r_hat_amplitude``, and of each well's occupancy,
    ``r_hat_wells``); ``ess``: the effective sample size of the mean amplitude; ``drift``
    (second half − first half of the mean amplitude) and ``drift_z`` (in standard errors);
    ``suggested_length``: the window that the R̂ scaling suggests for R̂ ≤ 1.1; ``method``:
    how the diagnosis was made (``"direct"``: over the paths; ``"wells"``: the worst of the
    well method's conditional runs)."""

    stationary: bool
    r_hat: float
    ess: float
    r_hat_amplitude: float
    r_hat_wells: tuple[float, ...]
    drift: float
    drift_z: float
    suggested_length: float
    method: str

    @classmethod
    def _of(cls, doc: dict) -> "Stationarity":
        st = doc["stationarity"]
        return cls(
            stationary=bool(st["stationary"]),
            r_hat=_inf(st["r_hat"]),
            ess=_inf(st["ess"]),
            r_hat_amplitude=_inf(st["r_hat_amplitude"]),
            r_hat_wells=tuple(_inf(x) for x in st.get("r_hat_wells") or ()),
            drift=_inf(st["drift"]),
            drift_z=_inf(st["drift_z"]),
            suggested_length=_inf(st["suggested_length"]),
            method=doc.get("estimator", "direct"),
        )

    def __str__(self) -> str:
        verdict = "stationary" if self.stationary else "NOT stationary"
        return (
            f"{verdict} (R̂ = {self.r_hat:.3g}, ESS = {self.ess:.0f}, drift {self.drift_z:.1f} s.e.; "
            f"suggested window {self.suggested_length:.4g}; {self.method})"
        )


@dataclass(repr=False)
class Ensemble:
    """An ensemble's result: ``to_dict()`` is the document ``trirhythm ensemble --format json``
    writes (``wall_time_s`` aside); ``statistics()`` the moments with their standard errors;
    ``stationarity`` the diagnosis (a ``Stationarity``: ``stationary``, ``r_hat``, ``ess``, …);
    ``density(kind)`` a histogram. Its repr is a few lines (the moments and the diagnosis);
    the whole document is ``to_dict()``."""

    document: dict

    def to_dict(self) -> dict:
        return self.document

    def __getitem__(self, key):
        return self.document[key]

    @property
    def stationarity(self) -> Stationarity:
        """The stationarity diagnosis, as numbers (``inf`` where R̂ is infinite)."""
        return Stationarity._of(self.document)

    @property
    def stationary(self) -> bool:
        """Whether the ensemble is stationary (``stationarity.stationary``)."""
        return bool(self.document["stationarity"]["stationary"])

    def __repr__(self) -> str:
        lines = [f"Ensemble({self.document.get('estimator', 'direct')}: {self.document.get('method', '')}"]
        for name, (v, e) in self.statistics().items():
            lines.append(f"  {name} = {v:.6g} ± {e:.2g}")
            if len(lines) >= 14:
                lines.append("  …")
                break
        lines.append(f"  stationarity: {self.stationarity}")
        warns = self.document.get("warnings") or []
        if warns:
            lines.append(f"  warnings: {len(warns)} (to_dict()['warnings'])")
        lines.append(")")
        return "\n".join(line if len(line) <= 200 else line[:199] + "…" for line in lines)

    def _warn(self, call: str, stacklevel: int = 3) -> "Ensemble":
        if not self.stationary:
            warnings.warn(f"{call}: the ensemble is {self.stationarity}", NotStationaryWarning, stacklevel=stacklevel)
        return self

    def statistics(self) -> dict[str, tuple[float, float]]:
        """``{name: (value, stderr)}`` for ⟨U⟩, Var U, ⟨U̇⟩, Var U̇, ⟨A⟩ and each well's occupancy."""
        out = {}
        for k in ("mean_u", "var_u", "mean_v", "var_v", "mean_amplitude"):
            e = self.document[k]
            out[k] = (_inf(e["value"]), _inf(e["stderr"]))
        for i, e in enumerate(self.document.get("occupancy") or []):
            out[f"occupancy_{i}"] = (_inf(e["value"]), _inf(e["stderr"]))
        return out

    def density(self, kind: str = "amplitude") -> dict:
        """A histogram as numpy arrays: ``edges`` (bins + 1), ``density`` and ``stderr`` (bins),
        with ``beyond`` (the fraction past the last edge) and ``count``; ``kind`` is
        ``"amplitude"``, ``"turning"`` or ``"energy"``."""
        if kind not in ("amplitude", "turning", "energy"):
            raise ValueError(f"invalid parameter kind = {kind!r}: expected amplitude, turning or energy")
        d = self.document[kind]
        arr = lambda xs: np.array([_inf(x) for x in xs])  # noqa: E731
        return {
            "edges": arr(d["edges"]),
            "density": arr(d["density"]),
            "stderr": arr(d["stderr"]),
            "beyond": _inf(d["beyond"]),
            "count": int(d["count"]),
        }


@dataclass(repr=False)
class EnsemblePaths:
    """Some paths of an ensemble (``ensemble_paths``), to be merged with ``merge_paths``;
    picklable (the statistics travel as exact JSON)."""

    pieces: str
    which: list[int] = field(default_factory=list)

    def __repr__(self) -> str:
        w = self.which
        shown = ", ".join(map(str, w[:8])) + (f", … ({len(w)} paths)" if len(w) > 8 else "")
        return f"EnsemblePaths(which=[{shown}], {len(self.pieces)} characters of statistics)"


_ENSEMBLE_DEFAULTS = dict(
    dt=0.01,
    u0=(),
    variant="paper",
    system="fractional",
    barrier=True,
    memory="soe",
    tolerance=None,
    impact_memory="restart",
    bins=100,
    joint_bins=48,
    amplitude_max=None,
    sample_every=1,
)


_WELLS_DEFAULTS = dict(
    clones=100,
    max_excursion=10_000.0,
    max_iterations=2_000,
    separation=10.0,
    core_quantile=0.1,
)


def _ensemble_args(params, paths, t_end, burn_in, seed, options):
    unknown = set(options) - set(_ENSEMBLE_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown argument(s) {sorted(unknown)}: expected {sorted(_ENSEMBLE_DEFAULTS)}")
    o = {**_ENSEMBLE_DEFAULTS, **options}
    u0 = o["u0"]
    u0 = [float(u0)] if isinstance(u0, (int, float)) else [_finite("u0", x) for x in u0]
    amax = o["amplitude_max"]
    return (
        _check_params(params),
        _count("paths", paths, 1, _MAX_PATHS),
        _finite("t_end", t_end),
        _finite("burn_in", burn_in),
        _count("seed", seed),
        _finite("dt", o["dt"]),
        u0,
        o["variant"],
        o["system"],
        bool(o["barrier"]),
        o["memory"],
        _tolerance(o["tolerance"]),
        o["impact_memory"],
        _count("bins", o["bins"]),
        _count("joint_bins", o["joint_bins"]),
        None if amax is None else _finite("amplitude_max", amax),
        _count("sample_every", o["sample_every"]),
    )


def ensemble(
    params: Params | None = None,
    paths: int = 8,
    t_end: float = 1000.0,
    burn_in: float = 100.0,
    seed: int = 1,
    *,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
    backend: str = "cpu",
    **options,
) -> Ensemble:
    """``paths`` paths (path i is noise stream i of ``seed``), each ``burn_in`` discarded then
    ``t_end`` recorded: the stationary statistics with standard errors, the stationarity
    diagnosis and the averaged theory against them, as ``trirhythm ensemble``. Options and
    defaults are the command line's: ``dt=0.01``, ``u0=()`` (the theory's modes),
    ``variant="paper"``, ``system``, ``barrier``, ``memory``, ``tolerance``,
    ``impact_memory="restart"``, ``bins=100``, ``joint_bins=48``, ``amplitude_max=None``,
    ``sample_every=1``. ``method="wells"`` estimates them by well decomposition, as
    ``trirhythm ensemble --method wells`` (``paths`` replicas of one path per well of ``t_end``;
    options ``clones=100``, ``max_excursion=10000``, ``max_iterations=2000``,
    ``separation=10``, ``core_quantile=0.1``; ``u0`` is refused, the well method starts in each
    of the theory's wells); the document adds ``estimator``, ``decomposition`` and ``bounds``.
    ``model=`` (a ``trirhythm.Model``) in place of ``params``: its parameters, wall and start
    (paths start at rest at ``start.u0``), as ``trirhythm ensemble --model FILE``.
    ``backend="gpu"`` steps the paths on the GPU (the CUDA kernel on the first device, as
    ``trirhythm ensemble --backend gpu``; ``method="direct"`` only; the document adds
    ``"backend": "gpu"``); without a CUDA driver or device it raises ``ValueError`` naming the
    GPU backend and the reason. ``backend="cpu"``, the default, is the CPU engine."""
    if model is not None:
        direct = options.get("method", "direct") == "direct"
        params, options = _model_options(model, params, options, "ensemble", start=direct)
        if direct:
            options["u0"] = [options["u0"]]
    method = options.pop("method", "direct")
    wells = {k: options.pop(k) for k in list(options) if k in _WELLS_DEFAULTS}
    if method == "wells" and "u0" in options:
        raise ValueError(
            f"invalid parameter u0 = {options['u0']!r}: u0 applies to method='direct' only "
            "(method='wells' starts one path in each of the theory's wells, at its mode)"
        )
    args = _ensemble_args(params, paths, t_end, burn_in, seed, options)
    if method == "wells" and backend != "cpu":
        raise ValueError(
            f"invalid parameter backend = {backend!r}: method='wells' runs on the CPU only "
            "(backend='cpu')"
        )
    if method == "wells":
        w = {**_WELLS_DEFAULTS, **wells}
        text = _native._ensemble_wells(
            *args,
            _count("clones", w["clones"]),
            _finite("max_excursion", w["max_excursion"]),
            _count("max_iterations", w["max_iterations"]),
            _finite("separation", w["separation"]),
            _finite("core_quantile", w["core_quantile"]),
            model=model,
            threads=threads,
            progress=_progress(progress),
        )
        return Ensemble(json.loads(text))._warn("ensemble")
    if method != "direct":
        raise ValueError(f"invalid parameter method = {method!r}: expected 'direct' or 'wells'")
    if wells:
        raise ValueError(f"argument(s) {sorted(wells)} need method='wells'")
    text = _native._ensemble(
        *args, model=model, threads=threads, progress=_progress(progress), backend=backend
    )
    return Ensemble(json.loads(text))._warn("ensemble")


def _direct_model(model, params, options):
    """``(params, options)`` of a direct ensemble with ``model=`` (its start as the one u0)."""
    if model is None:
        return params, options
    params, options = _model_options(model, params, options, "ensemble")
    return params, {**options, "u0": [options["u0"]]}


def _ensemble_range(
    base: Params | Model,
    paths: int = 8,
    t_end: float = 1000.0,
    burn_in: float = 100.0,
    seed: int = 1,
    *,
    threads: int | None = None,
    progress=None,
    **options,
) -> float:
    """The histogram range ``amplitude_max`` that ``ensemble(base, …)`` with these options
    uses (the one given, else the one it chooses from the averaged theory), without running
    it: a density sweep's common bins."""
    options.pop("method", None)
    model = base if isinstance(base, Model) else None
    params, options = _direct_model(model, None if model is not None else base, options)
    args = _ensemble_args(params, paths, t_end, burn_in, seed, options)
    return float(json.loads(_native._ensemble(*args, model=model, setup_only=True))["amplitude_max"])


def ensemble_paths(
    params: Params | None,
    which: Iterable[int],
    paths: int = 8,
    t_end: float = 1000.0,
    burn_in: float = 100.0,
    seed: int = 1,
    *,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
    **options,
) -> EnsemblePaths:
    """Run only the paths ``which`` (indices in ``range(paths)``) of the ensemble that
    ``ensemble`` with the same arguments runs; ``merge_paths`` puts the pieces together, in
    any order and any split, into the same result bit for bit. ``model=`` as ``ensemble``."""
    which = [_count("which", i) for i in which]
    params, options = _direct_model(model, params, options)
    args = _ensemble_args(params, paths, t_end, burn_in, seed, options)
    text = _native._ensemble(
        *args, which=which, merge=False, model=model, threads=threads, progress=_progress(progress)
    )
    return EnsemblePaths(text, which)


def merge_paths(
    params: Params | None,
    pieces: Sequence[EnsemblePaths],
    paths: int = 8,
    t_end: float = 1000.0,
    burn_in: float = 100.0,
    seed: int = 1,
    *,
    model: Model | None = None,
    **options,
) -> Ensemble:
    """Merge the pieces of ``ensemble_paths`` (same arguments) into the ensemble's result;
    every path must be given exactly once."""
    params, options = _direct_model(model, params, options)
    args = _ensemble_args(params, paths, t_end, burn_in, seed, options)
    given = sorted(i for p in pieces for i in p.which)
    if given != list(range(paths)):
        raise ValueError(
            f"invalid parameter pieces: they hold paths {given}, expected each of 0..{paths - 1} once"
        )
    text = _native._ensemble(*args, which=[], pieces=[p.pieces for p in pieces], model=model)
    return Ensemble(json.loads(text))._warn("merge_paths")


_LLE_DEFAULTS = dict(
    transient=200.0,
    dt=0.01,
    u0=1.0,
    impact_memory="restart",
    method="two-trajectory",
    renormalise_every=100,
    separation=1e-8,
    system="fractional",
    barrier=True,
    memory="soe",
    tolerance=None,
)


def _lle_args(params, paths, t_end, seed, options):
    unknown = set(options) - set(_LLE_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown argument(s) {sorted(unknown)}: expected {sorted(_LLE_DEFAULTS)}")
    o = {**_LLE_DEFAULTS, **options}
    return dict(
        params=_check_params(params),
        t_end=_finite("t_end", t_end),
        transient=_finite("transient", o["transient"]),
        dt=_finite("dt", o["dt"]),
        paths=_count("paths", paths, 1, _MAX_PATHS),
        seed=_count("seed", seed),
        u0=_finite("u0", o["u0"]),
        impact_memory=o["impact_memory"],
        method=o["method"],
        renormalise_every=_count("renormalise_every", o["renormalise_every"]),
        separation=_finite("separation", o["separation"]),
        system=o["system"],
        barrier=bool(o["barrier"]),
        memory=o["memory"],
        tolerance=_tolerance(o["tolerance"]),
    )


def lyapunov(
    params: Params | None = None,
    paths: int = 8,
    t_end: float = 2000.0,
    seed: int = 1,
    *,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
    **options,
) -> dict:
    """The largest Lyapunov exponent with frozen noise (``trirhythm lyapunov``): a dict with
    ``lle`` ``{value, stderr}``, ``per_path``, ``running``, … Options: ``transient=200``,
    ``dt=0.01``, ``u0=1``, ``impact_memory="restart"``, ``method="two-trajectory"`` or
    ``"tangent"``, ``renormalise_every=100``, ``separation=1e-8``, ``system``, ``barrier``,
    ``memory``, ``tolerance``. ``model=`` (a ``trirhythm.Model``, any the engine steps) in
    place of ``params``: its parameters, terms, wall and start (at rest at ``start.u0``), as
    ``trirhythm lyapunov --model FILE``."""
    if model is not None:
        params, options = _model_options(model, params, options, "lyapunov")
    a = _lle_args(params, paths, t_end, seed, options)
    return json.loads(_native._lyapunov(**a, model=model, threads=threads, progress=_progress(progress)))


@dataclass
class CriticalPoint:
    """One point of a critical-noise curve: ``D``; ``lle`` and ``se``, the mean exponent and its
    standard error over the ``n - merged`` realisations that did not merge (NaN where
    undefined); ``n`` realisations, ``merged`` of them whose copy merged with its reference
    (exponent −∞); ``call`` against δ = 1/W: ``"chaotic"``, ``"not-chaotic"``,
    ``"synchronised"`` (at least half merged) or ``"undecided"``; ``agrees`` whether the
    exponent is equivalent to the phase reduction's −c·D within δ (``None`` where not tested)."""

    D: float
    lle: float
    se: float
    n: int
    merged: int
    call: str
    agrees: bool | None


@dataclass
class Bracket:
    """Where a curve's D_c lies: ``kind`` ``"located"`` (D_c in (``lo``, ``hi``): the largest
    regular D below the smallest chaotic D), ``"below"`` (chaotic from the smallest D: D_c <
    ``hi``, ``lo`` is ``None``), ``"above"`` (regular up to the largest D: D_c > ``lo``, ``hi``
    is ``None``), ``"never"`` (no D_c at all: never chaotic, the exponent falling with D over
    the last decade; ``lo`` the largest D, ``hi`` ``None``) or ``"undecided"`` (both
    ``None``)."""

    kind: str
    lo: float | None
    hi: float | None


@dataclass
class WellEscape:
    """How many of the exponent's reference paths left the cycle's well (amplitude in
    (``lo``, ``hi``), the averaged theory's neighbouring unstable cycles) at noise ``D`` within
    the run of length ``run``: ``escaped`` of ``paths``, their median first exit time
    ``median_time`` (NaN when none left). Where any left, the bracket depends on the window."""

    D: float
    lo: float
    hi: float
    paths: int
    escaped: int
    median_time: float
    run: float


@dataclass
class RestRegime:
    """The rest regime's rule over a rest curve's points at D ≤ 1e-2: the inverse-variance
    ``pooled`` exponent (± ``pooled_se``), the weighted least-squares ``slope`` per decade of D
    (± ``slope_se``), the ``decades`` spanned; ``d_c_zero``: chaotic as D → 0 (pooled above δ,
    slope not significant, at least three decades), D_c = 0."""

    pooled: float
    pooled_se: float
    slope: float
    slope_se: float
    decades: float
    d_c_zero: bool


def _float(x) -> float:
    return float(_nonfinite(x))


@dataclass
class CriticalCurve:
    """One curve of ``critical_noise``: the exponent against D from one start, named by the
    attractor its noise-free path reaches. ``value`` is the swept parameter's (``None`` without
    a sweep); ``attractor`` in words (``"rest"``, ``"outer cycle (A = 12.65)"``), ``regime``
    ``"rest"`` or ``"cycle"``, ``u0`` the start, ``dt`` the step; ``points`` the
    ``CriticalPoint`` s, D ascending; ``bracket`` the ``Bracket`` of D_c; ``rest`` the
    ``RestRegime`` (rest curves; ``None`` on a cycle); ``coefficient`` c of the phase reduction
    λ ≈ −c·D with ``coefficient_uncertainty`` (cycle curves; ``None`` on rest curves and where
    undefined, the reason in ``prediction_note``); ``escape`` the ``WellEscape`` at the ends of
    a located bracket on a cycle (empty otherwise); ``decision`` the rules' outcome in words."""

    value: float | None
    attractor: str
    regime: str
    u0: float
    dt: float
    points: list[CriticalPoint]
    bracket: Bracket
    rest: RestRegime | None
    coefficient: float | None
    coefficient_uncertainty: float | None
    prediction_note: str
    escape: list[WellEscape]
    decision: str

    @classmethod
    def _of(cls, value, doc: dict) -> "CriticalCurve":
        r = doc["rest"]
        b = doc["bracket"]
        return cls(
            value=None if value is None else float(value),
            attractor=doc["attractor"],
            regime=doc["regime"],
            u0=float(doc["u0"]),
            dt=float(doc["dt"]),
            points=[
                CriticalPoint(
                    D=float(q["d"]),
                    lle=_float(q["lle"]),
                    se=_float(q["se"]),
                    n=int(q["n"]),
                    merged=int(q["merged"]),
                    call=q["call"],
                    agrees=q["agrees"],
                )
                for q in doc["points"]
            ],
            bracket=Bracket(b["kind"], b["lo"], b["hi"]),
            rest=None
            if r is None
            else RestRegime(
                pooled=_float(r["pooled"]),
                pooled_se=_float(r["pooled_se"]),
                slope=_float(r["slope"]),
                slope_se=_float(r["slope_se"]),
                decades=_float(r["decades"]),
                d_c_zero=bool(r["d_c_zero"]),
            ),
            coefficient=doc["coefficient"],
            coefficient_uncertainty=doc["coefficient_uncertainty"],
            prediction_note=doc["prediction_note"],
            escape=[
                WellEscape(
                    D=float(e["d"]),
                    lo=_float(e["escape"]["lo"]),
                    hi=_float(e["escape"]["hi"]),
                    paths=int(e["escape"]["paths"]),
                    escaped=int(e["escape"]["escaped"]),
                    median_time=_float(e["escape"]["median_time"]),
                    run=_float(e["escape"]["run"]),
                )
                for e in doc.get("escape", [])
            ],
            decision=doc["decision"],
        )

    @property
    def name(self) -> str:
        """The attractor's short name: ``"rest"``, ``"inner"``, ``"middle"``, ``"outer"``, …"""
        return self.attractor.split(" ")[0]

    def __repr__(self) -> str:
        d = f"D {self.points[0].D:g} to {self.points[-1].D:g}" if self.points else "no D"
        value = "" if self.value is None else f"value={self.value:g}, "
        c = "" if self.coefficient is None else f", coefficient={self.coefficient:.6g}"
        calls = ", ".join(q.call for q in self.points[:6]) + (", …" if len(self.points) > 6 else "")
        return _short(
            f"CriticalCurve({value}{self.attractor!r}, {len(self.points)} points {d} [{calls}], "
            f"bracket={self.bracket}{c})",
            300,
        )

    def arrays(self) -> dict[str, np.ndarray]:
        """The points as numpy arrays: ``D``, ``lle``, ``se``, ``n``, ``merged``, ``call``."""
        return {
            "D": np.array([q.D for q in self.points]),
            "lle": np.array([q.lle for q in self.points]),
            "se": np.array([q.se for q in self.points]),
            "n": np.array([q.n for q in self.points]),
            "merged": np.array([q.merged for q in self.points]),
            "call": np.array([q.call for q in self.points]),
        }


@dataclass
class CriticalNoise:
    """The result of ``critical_noise``: ``curves`` (``CriticalCurve`` s, per parameter value
    the rest curve first, then the cycles by amplitude), ``sweep`` (the swept parameter or
    ``None``), ``noises`` (the D of every curve), ``margin`` δ = 1/W, ``step_warnings``,
    ``notes`` (starts that settled on nothing, realisations that merged). ``to_dict()`` is the
    document ``trirhythm critical-noise --format json`` writes (its ``params`` aside);
    ``statistics()`` what ``sweep`` records."""

    curves: list[CriticalCurve]
    sweep: str | None
    noises: np.ndarray
    margin: float
    step_warnings: list[str]
    notes: list[str]
    document: dict = field(repr=False)

    @classmethod
    def _of(cls, doc: dict) -> "CriticalNoise":
        return cls(
            curves=[CriticalCurve._of(r["value"], c) for r in doc["results"] for c in r["curves"]],
            sweep=doc["sweep"],
            noises=np.array([float(d) for d in doc["noises"]]),
            margin=float(doc["margin"]),
            step_warnings=list(doc["step_warnings"]),
            notes=list(doc["notes"]),
            document=doc,
        )

    def to_dict(self) -> dict:
        return self.document

    def __repr__(self) -> str:
        lines = [f"CriticalNoise(sweep={self.sweep!r}, {len(self.noises)} noises, margin={self.margin:g},"]
        for c in self.curves[:14]:
            lines.append(f"  {c!r},")
        if len(self.curves) > 14:
            lines.append(f"  … {len(self.curves) - 14} more curves,")
        lines.append(f"  {len(self.step_warnings)} step warnings, {len(self.notes)} notes)")
        return "\n".join(lines)

    def statistics(self) -> dict[str, tuple[float, float]]:
        """``{name: (value, stderr)}`` per curve, named by its attractor (``rest``, ``inner``,
        …; suffix ``_i`` for the i-th value of a sweep): ``<name>_dc_lo``, ``<name>_dc_hi``
        (the bracket's ends, NaN where open), on a rest curve ``<name>_pooled``,
        ``<name>_slope`` with their standard errors and ``<name>_dc_zero`` (1 or 0), on a cycle
        ``<name>_coefficient`` with its uncertainty."""
        nan = float("nan")
        values = []
        for c in self.curves:
            if c.value not in values:
                values.append(c.value)
        out = {}
        for c in self.curves:
            tag = c.name if len(values) == 1 else f"{c.name}_{values.index(c.value)}"
            opt = lambda x: nan if x is None else float(x)  # noqa: E731
            out[f"{tag}_dc_lo"] = (opt(c.bracket.lo), nan)
            out[f"{tag}_dc_hi"] = (opt(c.bracket.hi), nan)
            if c.rest is not None:
                out[f"{tag}_pooled"] = (c.rest.pooled, c.rest.pooled_se)
                out[f"{tag}_slope"] = (c.rest.slope, c.rest.slope_se)
                out[f"{tag}_dc_zero"] = (float(c.rest.d_c_zero), nan)
            if c.regime == "cycle":
                out[f"{tag}_coefficient"] = (opt(c.coefficient), opt(c.coefficient_uncertainty))
        return out


_CRITICAL_DEFAULTS = dict(
    transient=200.0,
    dt=None,
    impact_memory="restart",
    method="two-trajectory",
    renormalise_every=100,
    separation=1e-8,
    system="fractional",
    barrier=True,
    memory="soe",
    tolerance=None,
    variant="paper",
)


def critical_noise(
    params: Params | None = None,
    d_range: tuple[float, float] | None = None,
    points: int = 9,
    paths: int = 8,
    t_end: float = 2000.0,
    seed: int = 1,
    *,
    noises: Sequence[float] | None = None,
    sweep: tuple[str, Sequence[float]] | None = None,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
    **options,
) -> CriticalNoise:
    """The largest Lyapunov exponent against the noise intensity D by regime, and each
    attractor's critical noise D_c, with the rules of Figs 17–19 (``trirhythm critical-noise``,
    the same code and bits; docs/verdicts.md, "The Lyapunov claims by regime").

    The starts U(0) = the averaged theory's stable amplitudes, 1 and 0.01 are classified by the
    attractor their noise-free path reaches, and one curve is run per attractor (rest on the
    wall, inner / middle / outer cycle) at D = ``points`` values log-spaced over ``d_range``
    (0 < lo < hi, rounded to 3 significant digits; ``None``: (0.002, 2), with 9 points Fig. 19's
    grid) or at ``noises`` (ascending, each > 0; not with ``d_range``). Each
    point is called against δ = 1/``t_end``; each curve gets the bracket of D_c, a rest curve
    its pooled exponent and slope over D ≤ 1e-2, a cycle the phase-reduction coefficient c.
    The D of ``params`` is not used. ``sweep=(key, values)`` runs the curves at each value of
    a parameter. Options and defaults are the command line's: ``transient=200``, ``dt=None``
    (the figures' rule: the largest of 0.01, 0.005, 0.0025, 0.002, 0.001, … not above τ/10),
    ``impact_memory="restart"``, ``method="two-trajectory"`` or ``"tangent"``,
    ``renormalise_every=100``, ``separation=1e-8``, ``system``, ``barrier``, ``memory``,
    ``tolerance``, ``variant="paper"``. Bad values raise ``ValueError`` naming the argument,
    its value and the allowed range, before any work; the step guard's warnings are warned.
    ``model=`` in place of ``params``: its parameters and wall (a model with terms outside the
    paper's family is refused: the starts and regimes come from the averaged theory)."""
    if model is not None:
        params, options = _model_options(model, params, options, "critical_noise", start=False)
    unknown = set(options) - set(_CRITICAL_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown argument(s) {sorted(unknown)}: expected {sorted(_CRITICAL_DEFAULTS)}")
    o = {**_CRITICAL_DEFAULTS, **options}
    if noises is not None:
        if d_range is not None:
            raise ValueError("give the noise intensities either as noises or as d_range (with points), not both")
        noises = [_finite("noises", d) for d in noises]
    else:
        if d_range is None:
            d_range = (0.002, 2.0)
        try:
            lo, hi = d_range
        except (TypeError, ValueError):
            raise ValueError(f"invalid parameter d_range = {d_range!r}: expected (lo, hi) with 0 < lo < hi") from None
        d_range = (_finite("d_range", lo), _finite("d_range", hi))
    if sweep is not None:
        try:
            key, values = sweep
        except (TypeError, ValueError):
            raise ValueError(f"invalid parameter sweep = {sweep!r}: expected (key, values)") from None
        sweep = (str(key), [_finite(str(key), v) for v in values])
    dt = o["dt"]
    text = _native._critical_noise(
        _check_params(params),
        noises,
        d_range,
        _count("points", points),
        sweep,
        _finite("t_end", t_end),
        _finite("transient", o["transient"]),
        None if dt is None else _finite("dt", dt),
        _count("paths", paths, 1, _MAX_PATHS),
        _count("seed", seed),
        o["impact_memory"],
        o["method"],
        _count("renormalise_every", o["renormalise_every"]),
        _finite("separation", o["separation"]),
        o["system"],
        bool(o["barrier"]),
        o["memory"],
        _tolerance(o["tolerance"]),
        o["variant"],
        model=model,
        threads=threads,
        progress=_progress(progress),
    )
    r = CriticalNoise._of(json.loads(text))
    for w in r.step_warnings:
        warnings.warn(f"critical_noise: {w}", RuntimeWarning, stacklevel=2)
    return r


_MODEL_DEFAULTS = dict(system="fractional", barrier=True, memory="soe", tolerance=None)


def _model_args(options):
    unknown = set(options) - set(_MODEL_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown argument(s) {sorted(unknown)}: expected {sorted(_MODEL_DEFAULTS)}")
    o = {**_MODEL_DEFAULTS, **options}
    return dict(
        system=o["system"],
        barrier=bool(o["barrier"]),
        memory=o["memory"],
        tolerance=_tolerance(o["tolerance"]),
    )


@dataclass
class Attractor:
    """Where the noise-free path from (U(0), U̇(0)) = (``u0``, 0) ends (the library's
    ``StartAttractor``).

    ``kind`` is ``"rest"``, ``"cycle"`` or ``"unsettled"``; ``amplitude`` the cycle's turning
    amplitude max U (extrapolated), the last one when unsettled, 0 at rest; ``period`` the
    cycle's period (``None`` otherwise); ``name`` the averaged theory's stable cycle it
    matches, ``"inner"``, ``"middle"``, ``"outer"``, ``"sole"`` or ``"unmatched"`` (``None``
    unless a cycle), with ``index`` its rank among the theory's stable cycles (ascending) and
    ``theory_amplitude`` its amplitude A0 (``None`` when unmatched); ``label`` is ``"rest"``,
    the cycle's name or ``"unsettled"``; ``variant`` the theory's variant that named it.
    ``decided_at`` (time of the decision), ``turning_points`` and ``remaining`` (the last
    relative amplitude change still expected; NaN before three turning points) describe the
    run (``None`` for a ``PhaseResponse``'s ``cycle``); ``to_dict()`` is the library's
    document."""

    u0: float
    kind: str
    amplitude: float
    period: float | None
    name: str | None
    index: int | None
    theory_amplitude: float | None
    label: str
    decided_at: float | None
    turning_points: int | None
    remaining: float | None
    variant: str
    document: dict = field(repr=False)

    @classmethod
    def _of(cls, doc: dict) -> "Attractor":
        """From the library's ``StartAttractor`` document (or ``{u0, attractor, variant}``)."""
        a = doc["attractor"]
        kind = a["kind"]
        name = a.get("name")
        run = lambda key, f: None if key not in doc else f(_nonfinite(doc[key]))  # noqa: E731
        return cls(
            u0=float(doc["u0"]),
            kind=kind,
            amplitude=float(a.get("amplitude", 0.0)),
            period=a.get("period"),
            name=name,
            index=a.get("index"),
            theory_amplitude=a.get("theory_amplitude"),
            label=name if kind == "cycle" else kind,
            decided_at=run("decided_at", float),
            turning_points=run("turning_points", int),
            remaining=run("remaining", float),
            variant=doc["variant"],
            document=doc,
        )

    def to_dict(self) -> dict:
        return self.document


def attractor(
    params: Params | None = None,
    u0: float | None = None,
    dt: float = 0.01,
    impact_memory: str = "restart",
    t_max: float = 20_000.0,
    variant: str = "paper",
    *,
    threads: int | None = None,
    model: Model | None = None,
    **options,
) -> Attractor:
    """The attractor the noise-free path (D set to 0) from (U(0), U̇(0)) = (``u0``, 0) reaches:
    rest on the wall, a limit cycle named by the averaged theory's stable cycle it matches
    (in ``variant``), or unsettled after ``t_max`` (library ``classify_start``). The run stops
    when the turning amplitudes have settled (Aitken's extrapolation within 1e-5 at three
    turning points in a row) or fallen below 1e-3. Options: ``system``, ``barrier``,
    ``memory``, ``tolerance`` (as ``simulate``; Eq. 9's ``"zhuravlev"`` is refused). The GIL
    is released; the run is not cancellable midway (Ctrl-C is raised when it ends).
    ``model=`` in place of ``params``: its parameters and wall, ``u0`` its ``start.u0`` unless
    given (a model with terms outside the paper's family is refused: the attractors are named
    by the averaged theory)."""
    if model is not None:
        params, options = _model_options(model, params, options, "attractor", start=False)
        if u0 is None:
            u0 = _from_model(model, None, {})[2]
    if u0 is None:
        raise ValueError("invalid parameter u0 = None: give the start U(0) (or model= with its start)")
    m = _model_args(options)
    text = _native._attractor(
        _check_params(params),
        _finite("u0", u0),
        _finite("dt", dt),
        impact_memory,
        _finite("t_max", t_max),
        variant,
        **m,
        model=model,
        threads=threads,
    )
    return Attractor._of(json.loads(text))


def attractor_starts(
    params: Params | None = None,
    dt: float = 0.01,
    impact_memory: str = "restart",
    t_max: float = 20_000.0,
    variant: str = "paper",
    *,
    threads: int | None = None,
    model: Model | None = None,
    **options,
) -> list[tuple[float, Attractor]]:
    """One start per attractor of the noise-free system (library ``attractor_starts``):
    ``[(u0, attractor), …]``, rest first, then the cycles by amplitude, the unsettled last.
    The starts tried are the averaged theory's stable cycle amplitudes, 1 and 0.01, each
    classified as ``attractor`` does (in parallel on ``threads``); the first start of each
    attractor is kept. Options and ``model=`` as ``attractor``."""
    if model is not None:
        params, options = _model_options(model, params, options, "attractor_starts", start=False)
    m = _model_args(options)
    text = _native._attractor(
        _check_params(params),
        None,
        _finite("dt", dt),
        impact_memory,
        _finite("t_max", t_max),
        variant,
        **m,
        model=model,
        threads=threads,
    )
    return [(float(d["u0"]), Attractor._of(d)) for d in json.loads(text)]


@dataclass
class PhaseResponse:
    """The phase response Z(θ) of a stable cycle and the phase-reduction coefficient c of the
    frozen-noise exponent, λ_pred = −c·D under weak noise of the parameters' correlation time
    τ (the library's ``PhaseResponse``; ``trirhythm phase-response``).

    ``theta``, ``z`` (radians per unit impulse of η), ``z_double`` (from twice the kick) and
    ``z_extrapolation`` (Aitken's correction, units of Z) are numpy arrays over the sampled
    phases, θ = 0 at the ``section`` (``"impact"`` or ``"upward_crossing"``). ``cycle`` is the
    ``Attractor`` the start reached, with ``amplitude``, ``period`` and ``omega`` = 2π/T.
    ``coefficient`` is c, or ``None`` with the reason in ``undefined`` (white noise with
    impacts, a response not linear in the kick, copies not settled); ``uncertainty`` is
    |c − c_half| (NaN when undefined). ``linearity`` = max|Z − Z₂|/max|Z| and
    ``extrapolation`` = max|correction|/max|Z| are the diagnostics; ``jump`` = Z(0⁺) − Z(2π⁻)
    at the impact (``z_after``, ``z_before``). ``step_warnings`` are the step guard's, as the
    command line's. ``to_dict()`` is the library's document (the command line's
    ``--format json`` without its run fields)."""

    u0: float
    cycle: Attractor
    amplitude: float
    period: float
    omega: float
    section: str
    impulse: float
    theta: np.ndarray = field(repr=False)
    z: np.ndarray = field(repr=False)
    z_double: np.ndarray = field(repr=False)
    z_extrapolation: np.ndarray = field(repr=False)
    z_after: float
    z_before: float
    jump: float
    correlation_time: float
    coefficient: float | None
    uncertainty: float
    harmonics: int
    tail: float
    linearity: float
    extrapolation: float
    undefined: str | None
    step_warnings: list[str]
    document: dict = field(repr=False)

    def to_dict(self) -> dict:
        return self.document

    def prediction(self, D: float) -> float | None:
        """λ_pred = −c·D at noise intensity ``D`` (``None`` where c is undefined)."""
        if self.coefficient is None:
            return None
        return -self.coefficient * _finite("D", D)


def phase_response(
    params: Params | None = None,
    u0: float | None = None,
    dt: float = 0.01,
    impact_memory: str = "restart",
    phases: int = 128,
    kick: float = 1e-4,
    periods: int = 60,
    t_max: float = 20_000.0,
    variant: str = "paper",
    *,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
    **options,
) -> PhaseResponse:
    """The phase response of the cycle the noise-free path from (``u0``, 0) reaches, measured
    by impulses of η with the real stepper, and c of λ_pred = −c·D (``trirhythm
    phase-response``, bit-identical). Options and defaults are the command line's: ``u0=None``
    (the averaged theory's largest stable amplitude at D = 0, the outer cycle), ``dt=0.01`` in
    [1e-4, 0.1], ``impact_memory="restart"``, ``phases=128`` (even, 8 to 4096, at most T/Δt),
    ``kick=1e-4`` in [1e-8, 1e-2] (relative to A·Ω/2), ``periods=60`` (6 to 100000 sections
    followed), ``t_max=20000`` (to reach the cycle), ``variant``, ``system``, ``barrier``,
    ``memory``, ``tolerance``. A start that reaches no cycle raises ``ValueError``. Where the
    coefficient is undefined it is ``None`` and a ``RuntimeWarning`` gives the reason; the step
    guard's warnings are warned too. ``model=`` in place of ``params``: its parameters and
    wall (terms outside the paper's family are refused: the cycle is named by the averaged
    theory)."""
    if model is not None:
        params, options = _model_options(model, params, options, "phase_response", start=False)
    m = _model_args(options)
    text, step_warnings = _native._phase_response(
        _check_params(params),
        None if u0 is None else _finite("u0", u0),
        _finite("dt", dt),
        impact_memory,
        _count("phases", phases),
        _finite("kick", kick),
        _count("periods", periods),
        _finite("t_max", t_max),
        variant,
        **m,
        model=model,
        threads=threads,
        progress=_progress(progress),
    )
    doc = json.loads(text)
    samples = doc["samples"]
    arr = lambda key: np.array([float(_nonfinite(s[key])) for s in samples])  # noqa: E731
    num = lambda key: float(_nonfinite(doc[key]))  # noqa: E731
    r = PhaseResponse(
        u0=num("u0"),
        cycle=Attractor._of({"u0": doc["u0"], "attractor": doc["cycle"], "variant": variant}),
        amplitude=num("amplitude"),
        period=num("period"),
        omega=num("omega"),
        section=doc["section"],
        impulse=num("impulse"),
        theta=arr("theta"),
        z=arr("z"),
        z_double=arr("z_double"),
        z_extrapolation=arr("extrapolation"),
        z_after=num("z_after"),
        z_before=num("z_before"),
        jump=num("jump"),
        correlation_time=num("correlation_time"),
        coefficient=None if doc.get("coefficient") is None else float(doc["coefficient"]),
        uncertainty=num("uncertainty"),
        harmonics=int(doc["harmonics"]),
        tail=num("tail"),
        linearity=num("linearity"),
        extrapolation=num("extrapolation"),
        undefined=doc.get("undefined"),
        step_warnings=list(step_warnings),
        document=doc,
    )
    for w in step_warnings:
        warnings.warn(f"phase_response: {w}", RuntimeWarning, stacklevel=2)
    if r.coefficient is None:
        warnings.warn(f"phase_response: no coefficient: {r.undefined}", RuntimeWarning, stacklevel=2)
    return r


def oscillation_boundary(
    params: Params | None = None,
    x: tuple[str, Sequence[float]] | None = None,
    y: tuple[str, float, float] | None = None,
    method: str = "simulation",
    variant: str = "paper",
    barrier: bool | None = None,
    tolerance: float = 1e-3,
    *,
    threads: int | None = None,
    progress=None,
    model: Model | None = None,
) -> dict:
    """The oscillation boundary (``trirhythm oscillation``): for each abscissa of
    ``x = (key, values)`` the value of ``y = (key, lo, hi)`` where the rest state loses
    stability, by ``method`` ``"simulation"``, ``"averaging"`` or ``"exact"``. ``model=`` in
    place of ``params``: its parameters and wall (terms outside the paper's family are
    refused: the boundary is the paper family's)."""
    if model is not None:
        params, o = _model_options(model, params, {"barrier": barrier}, "oscillation_boundary", start=False)
        barrier = o["barrier"]
    barrier = True if barrier is None else barrier
    if x is None or y is None:
        raise ValueError("give the abscissa x = (key, values) and the ordinate y = (key, lo, hi)")
    xk, xs = x
    yk, lo, hi = y
    r = _native._oscillation_boundary(
        _check_params(params),
        xk,
        [_finite(xk, v) for v in xs],
        yk,
        (_finite(yk, lo), _finite(yk, hi)),
        method,
        variant,
        bool(barrier),
        _finite("tolerance", tolerance),
        model=model,
        threads=threads,
        progress=_progress(progress),
    )
    return json.loads(r)


def _axis(name, a):
    try:
        key, start, stop, count = a
    except (TypeError, ValueError):
        raise ValueError(f"invalid parameter {name} = {a!r}: expected (key, start, stop, count)") from None
    return (str(key), _finite(f"{name} start", start), _finite(f"{name} stop", stop), _count(f"{name} count", count, 2))


@dataclass(repr=False)
class FoldCurve:
    """One fold curve of a map (``trirhythm map --folds``): where two cycles (or two extrema of
    P(A)) meet and vanish, as arrays ``x``, ``y`` (the plane's parameters) and ``amplitude``
    (the double root's A), in order along the curve; ``system`` (``"drift"``: f = ∂f/∂A = 0;
    ``"fpk"``: the same for m1), and why each end ends it, ``start`` and ``end``
    (``"border"``, ``"cusp"``, ``"zero_amplitude"``, ``"closed"``, ``"failed"``,
    ``"step_limit"``, ``"unbounded"``)."""

    x: np.ndarray
    y: np.ndarray
    amplitude: np.ndarray
    system: str
    start: str
    end: str

    def __repr__(self) -> str:
        return f"FoldCurve({self.system}, {len(self.x)} points, {self.start} to {self.end})"


@dataclass(repr=False)
class Folds:
    """The fold curves traced on a map: ``curves`` (``FoldCurve`` s), ``cusps`` (an (n, 3)
    array of x, y, A where two fold curves meet), ``seeds`` (transitions examined) and
    ``unlocated`` (seeds where no curve point was found); ``to_dict()`` is the library's
    document, the ``folds`` of ``trirhythm map --folds --format json``."""

    curves: list[FoldCurve]
    cusps: np.ndarray
    seeds: int
    unlocated: int
    document: dict

    @classmethod
    def _of(cls, doc: dict) -> "Folds":
        col = lambda pts, k: np.array([_inf(q[k]) for q in pts])  # noqa: E731
        return cls(
            curves=[
                FoldCurve(
                    x=col(c["points"], "x"),
                    y=col(c["points"], "y"),
                    amplitude=col(c["points"], "amplitude"),
                    system=str(c["system"]),
                    start=str(c["start"]),
                    end=str(c["end"]),
                )
                for c in doc["curves"]
            ],
            cusps=np.array([[_inf(q["x"]), _inf(q["y"]), _inf(q["amplitude"])] for q in doc["cusps"]]).reshape(-1, 3),
            seeds=int(doc["seeds"]),
            unlocated=int(doc["unlocated"]),
            document=doc,
        )

    def to_dict(self) -> dict:
        return self.document

    def __repr__(self) -> str:
        lines = [f"Folds({len(self.curves)} curves, {len(self.cusps)} cusps, {self.seeds} seeds, {self.unlocated} unlocated"]
        lines += [f"  {c!r}," for c in self.curves[:16]]
        if len(self.curves) > 16:
            lines.append(f"  … {len(self.curves) - 16} more")
        return "\n".join(lines) + ")"


class PlaneMap(NamedTuple):
    """A classified plane: ``x`` and ``y`` (the axes' values) and ``counts[iy, ix]``; unpacks
    as ``xs, ys, counts = ...``."""

    x: np.ndarray
    y: np.ndarray
    counts: np.ndarray


class PlaneMapFolds(NamedTuple):
    """A classified plane with its fold curves (``folds=True``): ``x``, ``y``,
    ``counts[iy, ix]`` and ``folds`` (``Folds``); unpacks as ``xs, ys, counts, folds = ...``."""

    x: np.ndarray
    y: np.ndarray
    counts: np.ndarray
    folds: Folds


def _plane(params, x, y, what, variant, threads, progress, folds):
    xs, ys, counts, traced = _native._map(
        _check_params(params), _axis("x", x), _axis("y", y), what, variant, threads, _progress(progress), bool(folds)
    )
    if traced is None:
        return PlaneMap(xs, ys, counts)
    return PlaneMapFolds(xs, ys, counts, Folds._of(json.loads(traced)))


# An axis of a map: (key, start, stop, count).
_PlaneAxis = tuple[str, float, float, int]


class _PlaneMapper(Protocol):
    """The type of ``rhythmicity_map`` and ``modes_map``: a ``PlaneMap``, or with
    ``folds=True`` a ``PlaneMapFolds``."""

    @overload
    def __call__(
        self, params: Params, x: _PlaneAxis, y: _PlaneAxis, variant: str = ..., *,
        folds: Literal[False] = ..., threads: int | None = ..., progress: Any = ...,
    ) -> PlaneMap: ...
    @overload
    def __call__(
        self, params: Params, x: _PlaneAxis, y: _PlaneAxis, variant: str = ..., *,
        folds: Literal[True], threads: int | None = ..., progress: Any = ...,
    ) -> PlaneMapFolds: ...


def _plane_mapper(name: str, what: str, doc: str) -> _PlaneMapper:
    """The public map function ``name`` classifying each point of a plane by ``what``."""

    def mapper(
        params: Params,
        x: tuple[str, float, float, int],
        y: tuple[str, float, float, int],
        variant: str = "paper",
        *,
        folds: bool = False,
        threads: int | None = None,
        progress=None,
    ) -> PlaneMap | PlaneMapFolds:
        return _plane(params, x, y, what, variant, threads, progress, folds)

    mapper.__name__ = mapper.__qualname__ = name
    mapper.__doc__ = doc
    return cast(_PlaneMapper, mapper)


rhythmicity_map = _plane_mapper(
    "rhythmicity_map",
    "rhythmicity",
    """Stable-cycle counts of the averaged theory over the plane ``x = (key, start, stop,
    count)`` × ``y = (…)``: a ``PlaneMap`` ``(xs, ys, counts)`` with ``counts[iy, ix]``
    (``trirhythm map``); ``folds=True`` traces the fold curves through the map's transitions
    (``trirhythm map --folds``, the same curves): a ``PlaneMapFolds`` ``(xs, ys, counts,
    folds)``.""",
)
modes_map = _plane_mapper(
    "modes_map",
    "modes",
    """Counts of the modes of the stationary P(A) (D > 0) over a plane, as ``rhythmicity_map``
    (``trirhythm map --what modes``; ``folds=True``: the curves where two extrema of P(A)
    meet).""",
)


@dataclass(repr=False)
class SimulatedMap:
    """The P-bifurcation map by simulation beside the theory's (``trirhythm map
    --simulate``): the axes' values ``x`` and ``y``, and per point, as ``[iy, ix]`` arrays,
    ``theory`` (the theory's count of the modes of P(A)), ``simulated`` with its range
    ``low`` … ``high`` (the counts at z, z_strict and z_lenient standard errors),
    ``stationary`` (the ensemble's verdict) and ``agreement`` (``"agree"``, ``"disagree"``,
    ``"uncertain"``, ``"non_stationary"``, ``"outside_range"``); ``tally`` counts the
    verdicts. ``to_dict()`` is the library's map (every point's density with its standard
    errors, seed, R̂), the document of ``trirhythm map --simulate --format json``."""

    x: np.ndarray
    y: np.ndarray
    theory: np.ndarray
    simulated: np.ndarray
    low: np.ndarray
    high: np.ndarray
    stationary: np.ndarray
    agreement: np.ndarray
    tally: dict
    document: dict

    @classmethod
    def _of(cls, doc: dict) -> "SimulatedMap":
        nx, ny = int(doc["x"]["count"]), int(doc["y"]["count"])

        def grid(f, dtype):
            return np.array([f(p) for p in doc["points"]], dtype=dtype).reshape(ny, nx)

        xs = np.array(sorted({p["ix"]: p["x"] for p in doc["points"]}.items()))[:, 1]
        ys = np.array(sorted({p["iy"]: p["y"] for p in doc["points"]}.items()))[:, 1]
        return cls(
            x=xs,
            y=ys,
            theory=grid(lambda p: p["theory"], np.int64),
            simulated=grid(lambda p: p["simulated"]["count"], np.int64),
            low=grid(lambda p: p["simulated"]["low"], np.int64),
            high=grid(lambda p: p["simulated"]["high"], np.int64),
            stationary=grid(lambda p: p["stationary"], bool),
            agreement=grid(lambda p: p["agreement"], object),
            tally=dict(doc["tally"]),
            document=doc,
        )

    def to_dict(self) -> dict:
        return self.document

    def __repr__(self) -> str:
        t = self.tally
        return (
            f"SimulatedMap({len(self.x)} × {len(self.y)} points: agree {t['agree']}, "
            f"disagree {t['disagree']}, uncertain {t['uncertain']}, "
            f"non_stationary {t['non_stationary']}, outside_range {t['outside_range']})"
        )


def simulated_map(
    params: Params,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    variant: str = "paper",
    *,
    paths: int = 8,
    t_end: float = 1000.0,
    burn_in: float = 100.0,
    dt: float = 0.01,
    seed: int = 1,
    bins: int = 40,
    batches: int = 20,
    impact_memory: str = "restart",
    amplitude_max: float | None = None,
    z: float = 3.0,
    z_lenient: float = 2.0,
    z_strict: float = 4.0,
    threads: int | None = None,
    progress=None,
    backend: str = "cpu",
) -> SimulatedMap:
    """The P-bifurcation map by simulation (``trirhythm map --simulate``, the same numbers
    for the same arguments): at each point of the plane ``x = (key, start, stop, count)`` ×
    ``y = (…)`` an ensemble of Eq. (1) of ``paths`` paths (seed derived from ``seed`` and the
    point's index), the modes of its P(A) counted by the rule of docs/statistics.md beside the
    theory's count (``modes_map``). Needs D > 0 on the whole plane. ``backend="gpu"`` steps
    every point's paths on the GPU (docs/gpu.md; a ValueError naming the reason without a
    CUDA driver and device)."""
    r = _native._simulated_map(
        _check_params(params),
        _axis("x", x),
        _axis("y", y),
        variant,
        _count("paths", paths, 1),
        _finite("t_end", t_end),
        _finite("burn_in", burn_in),
        _finite("dt", dt),
        _count("seed", seed, 0, 2**64 - 1),
        _count("bins", bins, 2),
        _count("batches", batches, 4),
        impact_memory,
        None if amplitude_max is None else _finite("amplitude_max", amplitude_max),
        _finite("z", z),
        _finite("z_lenient", z_lenient),
        _finite("z_strict", z_strict),
        threads=threads,
        progress=_progress(progress),
        backend=backend,
    )
    return SimulatedMap._of(json.loads(r))


class BranchCurve(NamedTuple):
    """One branch of a branch diagram, in order along its arclength: arrays ``param`` (the
    swept parameter), ``amplitude`` and ``stable`` (a stable cycle, or a mode of P(A)), and why
    its first and last points end it, ``start`` and ``end`` (as ``FoldCurve``'s)."""

    param: np.ndarray
    amplitude: np.ndarray
    stable: np.ndarray
    start: str
    end: str


@dataclass(repr=False)
class Branches:
    """Every branch of cycles (``what="rhythmicity"``) or of extrema of P(A) (``"modes"``)
    against one parameter ``key`` over [``start``, ``stop``], traced through its folds
    (``trirhythm branches``): ``branches`` (``BranchCurve`` s), ``folds`` (an (n, 2) array of
    the saddle-nodes' parameter and amplitude), ``hopf`` (parameter values where a branch
    reaches A = 0). ``to_dict()`` is the library's diagram, the document of ``trirhythm
    branches --format json`` less its ``params`` and ``variant``."""

    key: str
    start: float
    stop: float
    what: str
    branches: list[BranchCurve]
    folds: np.ndarray
    hopf: np.ndarray
    document: dict

    def to_dict(self) -> dict:
        return self.document

    def __repr__(self) -> str:
        lines = [
            f"Branches({self.what} against {self.key} in [{self.start:g}, {self.stop:g}]: {len(self.branches)} branches, "
            f"{len(self.folds)} folds, {len(self.hopf)} Hopf points"
        ]
        for b in self.branches[:16]:
            share = float(np.mean(b.stable)) if len(b.stable) else 0.0
            lines.append(
                f"  {len(b.param)} points, A in {_span(b.amplitude)}, {share:.0%} stable, {b.start} to {b.end},"
            )
        if len(self.branches) > 16:
            lines.append(f"  … {len(self.branches) - 16} more")
        return "\n".join(lines) + ")"


def branches(
    params: Params,
    x: tuple[str, float, float],
    what: str = "rhythmicity",
    variant: str = "paper",
    step: float = 0.004,
    *,
    threads: int | None = None,
) -> Branches:
    """The branch diagram of the averaged theory along ``x = (key, start, stop)``: every branch
    of cycles (``what="rhythmicity"``) or of extrema of P(A) (``"modes"``, D > 0), traced by
    continuation through its folds, with the largest step ``step`` (a fraction of the interval,
    in [1e-6, 0.1]) — ``trirhythm branches --x KEY=START:STOP``, the same bits."""
    try:
        key, start, stop = x
    except (TypeError, ValueError):
        raise ValueError(f"invalid parameter x = {x!r}: expected (key, start, stop)") from None
    text = _native._branches(
        _check_params(params),
        str(key),
        _finite("x start", start),
        _finite("x stop", stop),
        what,
        variant,
        _finite("step", step),
        threads,
    )
    doc = json.loads(text)
    col = lambda pts, k, f=float: np.array([f(_inf(q[k])) if f is float else f(q[k]) for q in pts])  # noqa: E731
    return Branches(
        key=doc["key"],
        start=_inf(doc["start"]),
        stop=_inf(doc["stop"]),
        what=str(doc["what"]),
        branches=[
            BranchCurve(
                param=col(b["points"], "param"),
                amplitude=col(b["points"], "amplitude"),
                stable=np.array([bool(q["stable"]) for q in b["points"]], dtype=bool),
                start=str(b["start"]),
                end=str(b["end"]),
            )
            for b in doc["branches"]
        ],
        folds=np.array([[_inf(a), _inf(b)] for a, b in doc["folds"]]).reshape(-1, 2),
        hopf=np.array([_inf(h) for h in doc["hopf"]]),
        document=doc,
    )


def figure_data(n: int, quick: bool = False, variant: str = "paper", *, threads=None, progress=None) -> dict:
    """Figure ``n``'s data: the value ``trirhythm figure N --data`` writes under ``data`` in
    ``figNN.json``."""
    return json.loads(_native._figure_data(_count("n", n, 1), bool(quick), variant, threads, _progress(progress)))


from .sweep import sweep  # noqa: E402  (needs the functions above)

"""Parameter sweeps: one trirhythm computation at every point of a grid, in-process or on a
Dask cluster, into an ``xarray.Dataset``.

- Common random numbers: every point runs with the same ``seed`` (path i is noise stream i of
  the seed at every point), so that differences between points are not noise between seeds.
- Reproducible: each point's result depends on its parameters, ``seed`` and ``kwargs`` only,
  never on the worker, the number of workers, the order, or ``chunk_paths`` (the paths of an
  ensemble split into tasks and merged give the same bits as one call).
- Checkpoints: with ``checkpoint=DIR`` each finished point is saved as one file in DIR (written
  atomically); a rerun of the same sweep skips those points, and a directory made for another
  sweep (another function, grid, base, seed, options or version) is refused.

Dask is imported only when a ``client`` is given.
"""

from __future__ import annotations

import hashlib
import inspect
import itertools
import json
import os
import re
import tempfile
import warnings
from typing import Any, Callable, Mapping, Sequence

import numpy as np

# results that depend on the machine or the moment, never kept
_UNSTABLE = {"wall_time_s", "steps_per_second"}
# ensemble functions that can split their paths across tasks
_SPLITTABLE = {"ensemble"}
# an ensemble's diagnostics: one value per point, no standard error
_DIAGNOSTICS = ("stationary", "r_hat", "ess")
# the densities a sweep can record on common bins
_DENSITIES = ("amplitude", "turning", "energy")
# a point's parallel profile (``profile=True``): machine-dependent, no standard error
_PROFILE = "profile_"
_PROFILE_FIELDS = ("total_cpu_s", "critical_path_s", "tasks", "wall_s")
# a density's bin i in a point's statistics (``density_amplitude[3]``), gathered into one
# variable with a bin dimension when the Dataset is made
_BIN = re.compile(r"^(.+)\[(\d+)\]$")


def _named(func: str) -> Callable:
    import trirhythm

    names = ("ensemble", "lyapunov", "critical_noise", "oscillation_boundary", "simulate")
    if func not in names:
        raise ValueError(f"invalid parameter func = {func!r}: expected one of {', '.join(names)} or a callable")
    return getattr(trirhythm, func)


def _number(x):
    if isinstance(x, bool):
        return float(x)
    if isinstance(x, (int, float, np.integer, np.floating)):
        return float(x)
    if isinstance(x, str):
        try:
            return float(x)  # the library writes non-finite numbers as "NaN", "inf", "-inf"
        except ValueError:
            return None
    return None


def statistics(result: Any) -> dict[str, tuple[float, float]]:
    """The scalar statistics of a result as ``{name: (value, stderr)}`` (stderr NaN where the
    result gives none): an ``Ensemble``'s moments and occupancies with its diagnosis
    (``stationary`` as 1 or 0, ``r_hat``, ``ess``; no standard error), the ``{value, stderr}`` and
    number fields of a dict (a Lyapunov exponent), a ``CriticalNoise``'s brackets, rest-regime
    statistics and coefficients (``CriticalNoise.statistics``), a ``Path``'s summary, a
    number, a ``(value, stderr)`` pair, or a dict of those (what a custom function returns)."""
    import trirhythm

    nan = float("nan")
    if isinstance(result, trirhythm.Ensemble):
        st = result.stationarity
        return {
            **result.statistics(),
            "stationary": (float(st.stationary), nan),
            "r_hat": (st.r_hat, nan),
            "ess": (st.ess, nan),
        }
    if isinstance(result, trirhythm.CriticalNoise):
        return result.statistics()
    if isinstance(result, trirhythm.Path):
        result = result.summary
    if isinstance(result, tuple) and len(result) == 2:
        return {"value": (float(result[0]), float(result[1]))}
    if _number(result) is not None and not isinstance(result, str):
        return {"value": (float(result), nan)}
    if not isinstance(result, Mapping):
        raise TypeError(f"sweep: cannot take statistics from a {type(result).__name__}")
    out = {}
    points = result.get("points")
    if isinstance(points, list) and all(isinstance(p, Mapping) for p in points):
        # an oscillation boundary: each abscissa's y and bracket (suffix _i with several)
        for i, p in enumerate(points):
            for k in ("y", "y_lo", "y_hi", "simulations"):
                if k in p:
                    out[k if len(points) == 1 else f"{k}_{i}"] = (_number(p[k]), nan)
    for k, v in result.items():
        if k in _UNSTABLE:
            continue
        if isinstance(v, Mapping) and "value" in v and "stderr" in v:
            out[k] = (_number(v["value"]), _number(v["stderr"]))
        elif isinstance(v, tuple) and len(v) == 2:
            out[k] = (float(v[0]), float(v[1]))
        elif not isinstance(v, str) and _number(v) is not None:
            out[k] = (_number(v), nan)
        elif isinstance(v, str) and _number(v) is not None:
            out[k] = (_number(v), nan)
    return out


def _takes_seed(f) -> bool:
    try:
        ps = inspect.signature(f).parameters.values()
    except (TypeError, ValueError):
        return True
    return any(p.name == "seed" or p.kind is inspect.Parameter.VAR_KEYWORD for p in ps)


def _point_args(func, point):
    """How a point is handed to ``func``: a ``Params`` positionally; a ``Model`` as ``model=``
    to a trirhythm function, positionally to a callable of the user's."""
    import trirhythm

    if isinstance(point, trirhythm.Model) and isinstance(func, str):
        return (), {"model": point}
    return (point,), {}


def _densities(result, point, densities, variant) -> dict[str, tuple[float, float]]:
    """An ensemble's densities ``densities`` (kinds) bin by bin, as statistics named
    ``density_<kind>[i]`` with their standard errors, the fraction past the last edge
    ``density_<kind>_beyond``, and for P(A) the averaged theory's density at the bin centres
    in both variants, ``theory_amplitude_<variant>[i]`` (NaN where the theory does not apply:
    D = 0, a model outside the paper's family), and the edges ``edges_<kind>[i]`` (the same at
    every point where the range is: the sweep fixes ``amplitude_max``)."""
    import trirhythm

    nan = float("nan")
    out: dict[str, tuple[float, float]] = {}
    for kind in densities:
        d = result.density(kind)
        for i, (v, e) in enumerate(zip(d["density"], d["stderr"])):
            out[f"density_{kind}[{i}]"] = (float(v), float(e))
        out[f"density_{kind}_beyond"] = (d["beyond"], nan)
        for i, x in enumerate(d["edges"]):
            out[f"edges_{kind}[{i}]"] = (float(x), nan)
        if kind == "amplitude":
            edges = d["edges"]
            centres = 0.5 * (edges[:-1] + edges[1:])
            params = point.paper_params() if isinstance(point, trirhythm.Model) else point
            for v in ("paper", "consistent"):
                try:
                    th = trirhythm.Theory(params, v).pdf("amplitude", list(centres))
                except (ValueError, TypeError, RuntimeError):
                    th = np.full(len(centres), nan)
                for i, x in enumerate(th):
                    out[f"theory_amplitude_{v}[{i}]"] = (float(x), nan)
    return out


def _ensemble_statistics(result, point, densities, kwargs):
    out = statistics(result)
    if densities:
        out.update(_densities(result, point, densities, kwargs.get("variant", "paper")))
    return out


def _call(profile, f, *args, **kwargs):
    """``f(*args, **kwargs)``, and with ``profile`` its parallel profile (else None)."""
    import trirhythm

    if profile:
        return trirhythm.profiled(f, *args, **kwargs)
    return f(*args, **kwargs), None


def _profile_statistics(prof) -> dict[str, tuple[float, float]]:
    """A point's profile as statistics (machine-dependent: no standard error)."""
    nan = float("nan")
    if prof is None:
        return {}
    return {f"{_PROFILE}{k}": (float(getattr(prof, k)), nan) for k in _PROFILE_FIELDS}


def _run_point(func, params, seed, kwargs, densities=(), profile=False):
    """One point (runs on a worker): the function's statistics (an ensemble's
    ``NotStationaryWarning`` is not warned here: the sweep records ``stationary``, ``r_hat``
    and ``ess`` per point and warns once), with ``profile`` also its parallel profile
    (``profile_*``). A function without a seed (a deterministic one, such as an oscillation
    boundary) is called without it."""
    import trirhythm

    f = _named(func) if isinstance(func, str) else func
    args, given = _point_args(func, params)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", trirhythm.NotStationaryWarning)
        if _takes_seed(f):
            result, prof = _call(profile, f, *args, seed=seed, **given, **kwargs)
        else:
            result, prof = _call(profile, f, *args, **given, **kwargs)
    if densities:
        out = _ensemble_statistics(result, params, densities, kwargs)
    else:
        out = statistics(result)
    out.update(_profile_statistics(prof))
    return out


def _run_chunk(func, params, seed, which, kwargs, profile=False):
    """Some paths of one point's ensemble (runs on a worker), and with ``profile`` their
    parallel profile."""
    import trirhythm

    args, given = _point_args(func, params)
    return _call(profile, trirhythm.ensemble_paths, *(args or (None,)), which, seed=seed, **given, **kwargs)


def _merge_chunks(params, seed, kwargs, *chunks, densities=(), profile=False):
    """One point's ensemble from its chunks (runs on a worker). With ``profile`` the point's
    profile: the chunks' CPU and tasks added up, the critical path and wall time of the
    longest chunk (chunks run side by side) plus the merge's."""
    import trirhythm

    kw = {k: v for k, v in kwargs.items() if k not in ("threads", "progress")}
    args, given = _point_args("ensemble", params)
    pieces = [c[0] for c in chunks]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", trirhythm.NotStationaryWarning)
        result, prof = _call(profile, trirhythm.merge_paths, *(args or (None,)), pieces, seed=seed, **given, **kw)
    out = _ensemble_statistics(result, params, densities, kwargs)
    if prof is not None:
        parts = [c[1] for c in chunks]
        prof = trirhythm.Profile(
            total_cpu_s=prof.total_cpu_s + sum(p.total_cpu_s for p in parts),
            critical_path_s=prof.critical_path_s + max(p.critical_path_s for p in parts),
            tasks=prof.tasks + sum(p.tasks for p in parts),
            wall_s=prof.wall_s + max(p.wall_s for p in parts),
        )
    out.update(_profile_statistics(prof))
    return out


def _describe(x):
    """A JSON-able description of an argument, for the fingerprint and the attributes."""
    import trirhythm

    if isinstance(x, trirhythm.Params):
        return x.to_dict()
    if callable(x):
        return f"{getattr(x, '__module__', '?')}.{getattr(x, '__qualname__', repr(x))}"
    if isinstance(x, (list, tuple)):
        return [_describe(v) for v in x]
    if isinstance(x, Mapping):
        return {str(k): _describe(v) for k, v in x.items()}
    if isinstance(x, (np.integer, np.floating)):
        return x.item()
    if isinstance(x, (int, float, str, bool)) or x is None:
        return x
    return repr(x)


def _write_atomic(path: str, text: str) -> None:
    d = os.path.dirname(path)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-", suffix=".json")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _encode(stats):
    # repr of a float round-trips exactly; NaN and ±inf as strings
    return {k: [repr(float(v)), repr(float(s))] for k, (v, s) in stats.items()}


def _decode(d):
    return {k: (float(v), float(s)) for k, (v, s) in d.items()}


def _check_writable(directory: str):
    """Refuse, before any work, a checkpoint directory that cannot be written: the directory
    itself when it exists, else the nearest existing directory above it (where it would be
    created) must take a new file (a hidden probe file is created and removed at once)."""
    where = os.path.abspath(directory)
    while not os.path.exists(where):
        up = os.path.dirname(where)
        if up == where:
            break
        where = up
    if not os.path.isdir(where):
        raise ValueError(
            f"invalid parameter checkpoint = {directory!r}: cannot be created, {where!r} is not a directory"
        )
    try:
        fd, probe = tempfile.mkstemp(prefix=".trirhythm-probe-", dir=where)
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        raise ValueError(f"invalid parameter checkpoint = {directory!r}: cannot write in {where!r} ({e})") from None


class _Checkpoint:
    """A directory of one file per finished point, with the sweep's fingerprint."""

    def __init__(self, directory: str, fingerprint: str, description: dict):
        self.dir = os.fspath(directory)
        if os.path.exists(self.dir) and not os.path.isdir(self.dir):
            raise ValueError(f"invalid parameter checkpoint = {self.dir!r}: exists and is not a directory")
        _check_writable(self.dir)
        os.makedirs(self.dir, exist_ok=True)
        tag = os.path.join(self.dir, "sweep.json")
        if os.path.exists(tag):
            with open(tag) as f:
                held = json.load(f)
            if held.get("fingerprint") != fingerprint:
                raise ValueError(
                    f"invalid parameter checkpoint = {self.dir!r}: holds another sweep (different function, "
                    "grid, base parameters, seed, options or trirhythm version); use an empty directory"
                )
        else:
            if any(n.startswith("point-") for n in os.listdir(self.dir)):
                raise ValueError(
                    f"invalid parameter checkpoint = {self.dir!r}: holds point files but no sweep.json naming "
                    "their sweep; use an empty directory"
                )
            _write_atomic(tag, json.dumps({"fingerprint": fingerprint, "sweep": description}, indent=1))
        self.fingerprint = fingerprint

    def _file(self, index):
        return os.path.join(self.dir, "point-" + "-".join(str(i) for i in index) + ".json")

    def load(self, index):
        try:
            with open(self._file(index)) as f:
                d = json.load(f)
        except FileNotFoundError:
            return None
        if d.get("fingerprint") != self.fingerprint or d.get("index") != list(index):
            raise ValueError(f"checkpoint {self._file(index)}: not a point of this sweep; remove it")
        return _decode(d["statistics"])

    def save(self, index, stats):
        doc = {"fingerprint": self.fingerprint, "index": list(index), "statistics": _encode(stats)}
        _write_atomic(self._file(index), json.dumps(doc))


def sweep(
    func,
    grid: Mapping[str, Sequence[float] | np.ndarray],
    *,
    base,
    client=None,
    seed: int = 1,
    chunk_paths: int | None = None,
    checkpoint: str | os.PathLike | None = None,
    progress=None,
    densities: bool | Sequence[str] = False,
    profile: bool = False,
    **kwargs,
):
    """Run ``func`` at every point of ``grid`` around ``base``: a ``Params`` (grid keys are
    parameter keys) or a ``Model`` (grid keys are the model file's dotted field paths, e.g.
    ``"restoring.cubic"``, ``"noise.additive.intensity"``, ``"wall.0.restitution"``; each
    point is ``base.with_(**{key: value})`` and reaches a trirhythm function as ``model=``).

    - ``func``: the name of a trirhythm function (``"ensemble"``, ``"lyapunov"``,
      ``"critical_noise"``, ``"oscillation_boundary"``, ``"simulate"``) called as
      ``func(params, seed=seed, **kwargs)``, or any picklable callable of that form returning
      what ``statistics`` reads (a number, a ``(value, stderr)`` pair, a dict of them).
    - ``grid``: ``{key: values}`` for any parameter keys (``"lambda"``, ``"r"``, ``"D"``, …)
      or model fields; the points are the outer product, each validated before any work.
    - ``client``: ``None`` runs in-process, one point after the other (each call on all
      cores); a ``dask.distributed.Client`` runs one task per point (or per chunk) on its
      workers, each with ``threads=1`` unless ``kwargs`` says otherwise.
    - ``seed``: the same at every point (common random numbers).
    - ``chunk_paths``: with ``func="ensemble"``, split each point's paths into tasks of this
      many paths, merged exactly (the result does not depend on it).
    - ``checkpoint``: a directory keeping each finished point; a rerun resumes.
    - ``progress``: a callable ``f(done, total)`` over points, or ``True`` for a tqdm bar.
    - ``densities``: with ``func="ensemble"``, ``True`` records P(A) at every point (or a list
      of kinds: ``"amplitude"``, ``"turning"``, ``"energy"``) on common bins: the histogram
      range ``amplitude_max`` is the one given, else the one the base's ensemble would choose,
      the same at every point.
    - ``profile``: ``True`` records each point's parallel profile (``trirhythm.profiled``):
      variables ``profile_total_cpu_s``, ``profile_critical_path_s``, ``profile_tasks`` and
      ``profile_wall_s`` (machine-dependent, NaN for points resumed from a checkpoint made
      without it), and the attribute ``profile``: the sweep's total CPU, its longest point's
      critical path and the bound they put on the speed-up (the points being independent).

    Returns an ``xarray.Dataset`` with one dimension per key of ``grid`` (named as the key, and
    ``"lambda"`` for ``"lambda_"``) and, for every statistic, a variable and its standard error
    ``<name>_stderr``; for an ensemble also ``stationary`` (bool), ``r_hat`` and ``ess`` per
    point (``inf`` where R̂ is infinite), with ``NotStationaryWarning`` warned once when some
    point is not stationary; with ``densities``, ``density_<kind>`` and its
    ``density_<kind>_stderr`` over the grid's dimensions and a bin dimension ``<kind>``
    (coordinates: the bin centres, and ``<kind>_lo``, ``<kind>_hi`` its edges), the fraction
    past the last edge ``density_<kind>_beyond``, and for P(A) the averaged theory's density
    at the bin centres, ``theory_amplitude_paper`` and ``theory_amplitude_consistent``. The
    attributes record the function, the base parameters, the seed, the options and the
    trirhythm version.
    """
    import xarray as xr

    import trirhythm

    if not isinstance(base, (trirhythm.Params, trirhythm.Model)):
        raise ValueError(f"invalid parameter base = {base!r}: expected a trirhythm.Params or trirhythm.Model")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"invalid parameter seed = {seed!r}: allowed range is an integer, 0 or more")
    if not grid:
        raise ValueError("invalid parameter grid = {}: give at least one key with its values")
    given_keys = list(grid)
    # `lambda` is a Python keyword: `lambda_` names the same parameter (and its dimension)
    keys = [k[:-1] if isinstance(base, trirhythm.Params) and k.endswith("_") else k for k in given_keys]
    for i, k in enumerate(keys):
        if k in keys[:i]:
            raise ValueError(
                f"invalid parameter grid: keys {given_keys[keys.index(k)]!r} and {given_keys[i]!r} "
                f"both set {k}; give one"
            )
    grid = dict(zip(keys, (grid[k] for k in given_keys)))
    values = []
    for k in keys:
        v = np.asarray(grid[k], dtype=float)
        if v.ndim != 1 or v.size == 0:
            raise ValueError(f"invalid parameter grid[{k!r}]: expected a non-empty list of numbers")
        values.append(v)
    if isinstance(func, str):
        _named(func)
    elif not callable(func):
        raise ValueError(f"invalid parameter func = {func!r}: expected a function name or a callable")
    if chunk_paths is not None:
        if func not in _SPLITTABLE:
            raise ValueError(f"invalid parameter chunk_paths = {chunk_paths}: only func='ensemble' splits its paths")
        if isinstance(chunk_paths, bool) or not isinstance(chunk_paths, (int, np.integer)) or chunk_paths < 1:
            raise ValueError(f"invalid parameter chunk_paths = {chunk_paths!r}: allowed range is 1 or more")
    kinds: tuple[str, ...] = ()
    if densities is not False and densities is not None:
        if func != "ensemble":
            raise ValueError(f"invalid parameter densities = {densities!r}: only func='ensemble' records densities")
        kinds = ("amplitude",) if densities is True else tuple(densities)
        bad = [k for k in kinds if k not in _DENSITIES]
        if bad or not kinds:
            raise ValueError(
                f"invalid parameter densities = {densities!r}: expected True or kinds among {', '.join(_DENSITIES)}"
            )
        if kwargs.get("method", "direct") != "direct":
            raise ValueError(f"invalid parameter densities = {densities!r}: densities need method='direct'")
        if kwargs.get("amplitude_max") is None:
            # common bins: the range the base's ensemble chooses, for every point
            kwargs["amplitude_max"] = trirhythm._ensemble_range(base, **kwargs)
    shape = tuple(len(v) for v in values)
    indices = list(itertools.product(*(range(n) for n in shape)))
    # every point valid before any work: a bad grid value names its key, value and range
    points = {ix: base.with_(**{k: float(values[d][i]) for d, (k, i) in enumerate(zip(keys, ix))}) for ix in indices}
    if client is not None and isinstance(func, str):
        kwargs.setdefault("threads", 1)

    description = {
        "func": _describe(func),
        "grid": {k: [float(x) for x in v] for k, v in zip(keys, values)},
        "base": base.to_dict(),
        "seed": int(seed),
        "kwargs": _describe({k: v for k, v in kwargs.items() if k not in ("threads", "progress")}),
        "trirhythm": trirhythm.__version__,
    }
    if kinds:
        description["densities"] = list(kinds)
    fingerprint = hashlib.sha256(json.dumps(description, sort_keys=True).encode()).hexdigest()
    store = _Checkpoint(checkpoint, fingerprint, description) if checkpoint is not None else None

    report = trirhythm._progress(progress)
    results: dict[tuple, dict] = {}
    if store is not None:
        for ix in indices:
            s = store.load(ix)
            if s is not None:
                results[ix] = s
    todo = [ix for ix in indices if ix not in results]

    def finished(ix, stats):
        results[ix] = stats
        if store is not None:
            store.save(ix, stats)
        if report is not None:
            report(len(results), len(indices))

    if client is None:
        for ix in todo:
            if chunk_paths is None:
                stats = _run_point(func, points[ix], int(seed), kwargs, kinds, profile)
            else:
                paths = kwargs.get("paths", 8)
                chunks = [list(range(a, min(a + chunk_paths, paths))) for a in range(0, paths, chunk_paths)]
                pieces = [_run_chunk(func, points[ix], int(seed), c, kwargs, profile) for c in chunks]
                stats = _merge_chunks(points[ix], int(seed), kwargs, *pieces, densities=kinds, profile=profile)
            finished(ix, stats)
    else:
        from distributed import as_completed

        futures = {}
        for ix in todo:
            p = points[ix]
            if chunk_paths is None:
                fut = client.submit(_run_point, func, p, int(seed), kwargs, kinds, profile, pure=False)
            else:
                paths = kwargs.get("paths", 8)
                chunks = [list(range(a, min(a + chunk_paths, paths))) for a in range(0, paths, chunk_paths)]
                pieces = [client.submit(_run_chunk, func, p, int(seed), c, kwargs, profile, pure=False) for c in chunks]
                fut = client.submit(
                    _merge_chunks, p, int(seed), kwargs, *pieces, densities=kinds, profile=profile, pure=False
                )
            futures[fut] = ix
        try:
            for fut in as_completed(list(futures)):
                finished(futures[fut], fut.result())
        except BaseException:
            client.cancel(list(futures))
            raise

    names: list[str] = []
    binned: dict[str, int] = {}
    for ix in indices:
        for k in results[ix]:
            m = _BIN.match(k)
            if m:
                binned[m.group(1)] = max(binned.get(m.group(1), 0), int(m.group(2)) + 1)
            elif k not in names:
                names.append(k)
    data: dict[str, Any] = {}
    for n in names:
        val = np.full(shape, np.nan)
        err = np.full(shape, np.nan)
        for ix in indices:
            if n in results[ix]:
                val[ix], err[ix] = results[ix][n]
        if n in _DIAGNOSTICS:
            if n == "stationary" and not np.isnan(val).any():
                val = val.astype(bool)
            data[n] = (keys, val)
        elif n.startswith("theory_") or n.endswith("_beyond") or n.startswith(_PROFILE):
            data[n] = (keys, val)
        else:
            data[n] = (keys, val)
            data[f"{n}_stderr"] = (keys, err)
    coords: dict[str, Any] = {k: v for k, v in zip(keys, values)}
    for n, bins in binned.items():
        if n.startswith("edges_"):
            continue
        kind = n.split("_", 1)[1].rsplit("_", 1)[0] if n.startswith("theory_") else n.split("_", 1)[1]
        val = np.full(shape + (bins,), np.nan)
        err = np.full(shape + (bins,), np.nan)
        for ix in indices:
            for i in range(bins):
                got = results[ix].get(f"{n}[{i}]")
                if got is not None:
                    val[ix + (i,)], err[ix + (i,)] = got
        data[n] = ([*keys, kind], val)
        if not n.startswith("theory_"):
            data[f"{n}_stderr"] = ([*keys, kind], err)
    for kind in kinds:
        n = binned[f"edges_{kind}"]
        edges = np.array([[results[ix][f"edges_{kind}[{i}]"][0] for i in range(n)] for ix in indices])
        if (edges == edges[0]).all():
            # common bins (P(A) and the turning amplitudes always; the energy's where ω1 is)
            e = edges[0]
            coords[kind] = 0.5 * (e[:-1] + e[1:])
            coords[f"{kind}_lo"] = (kind, e[:-1])
            coords[f"{kind}_hi"] = (kind, e[1:])
        else:
            data[f"{kind}_edges"] = ([*keys, f"{kind}_edge"], edges.reshape(shape + (n,)))
    if "stationary" in data:
        st = np.asarray(data["stationary"][1])
        bad = int(np.sum(st == 0))
        if bad:
            warnings.warn(
                f"sweep: {bad} of {st.size} points not stationary (the Dataset's stationary, r_hat, ess)",
                trirhythm.NotStationaryWarning,
                stacklevel=2,
            )
    attrs = {
        "func": json.dumps(description["func"]),
        "base": json.dumps(description["base"]),
        "seed": int(seed),
        "seeds": f"common random numbers: every point uses seed {int(seed)} (path i is noise stream i of it)",
        "kwargs": json.dumps(description["kwargs"]),
        "trirhythm": trirhythm.__version__,
        "fingerprint": fingerprint,
    }
    if "stationary" in data:
        attrs["stationarity"] = (
            f"{kwargs.get('method', 'direct')} estimator; stationary: every split-R̂ (mean amplitude, well "
            "occupancies) ≤ 1.1 and the drift between the window's halves within 3 standard errors; r_hat: "
            "the largest split-R̂ (inf: the paths never left their wells); ess: effective sample size of "
            "the mean amplitude"
        )
    if profile:
        attrs["profile"] = _profile_line(data)
    if kinds:
        attrs["amplitude_max"] = float(kwargs["amplitude_max"])
        attrs["densities"] = ", ".join(kinds)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _profile_line(data) -> str:
    """The sweep's profile in one line: the points' total CPU, the longest critical path of a
    point, and their ratio, the bound on the speed-up (the points are independent tasks)."""
    cpu = np.asarray(data.get(f"{_PROFILE}total_cpu_s", ((), np.nan))[1], dtype=float)
    crit = np.asarray(data.get(f"{_PROFILE}critical_path_s", ((), np.nan))[1], dtype=float)
    seen = np.isfinite(cpu) & np.isfinite(crit)
    if not seen.any():
        return "no point was profiled here (all resumed from a checkpoint)"
    total, longest = float(cpu[seen].sum()), float(crit[seen].max())
    bound = total / longest if longest > 0 else 1.0
    return (
        f"{int(seen.sum())} of {cpu.size} points profiled: total CPU {total:.3g} s, the longest "
        f"point's critical path {longest:.3g} s, bound on the speed-up {bound:.1f}x "
        "(machine-dependent; per point: profile_*)"
    )

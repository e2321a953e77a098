"""Types of the compiled module ``trirhythm._trirhythm`` (pyo3; ``src/lib.rs``). The public
names are re-exported by ``trirhythm``; the underscored functions are the package's
internals, called by the Python wrappers that validate their arguments."""

from collections.abc import Callable, Sequence
from os import PathLike
from typing import Any, final

import numpy as np
import numpy.typing as npt

from ._results import Barrier, Cycles, Extremum

_Progress = Callable[[float, float], object] | None

@final
class Params:
    """A validated, immutable, hashable parameter set of the paper's Eq. (1)."""

    def __init__(self, **values: float) -> None: ...
    def with_(self, **values: float) -> Params: ...
    def __getitem__(self, key: str) -> float: ...
    def keys(self) -> list[str]: ...
    def to_dict(self) -> dict[str, float]: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def __reduce__(self) -> tuple[Callable[..., Params], tuple[dict[str, float]]]: ...

@final
class Model:
    """A validated, immutable model of the family (the model file's tables)."""

    def __init__(self, **tables: Any) -> None: ...
    @staticmethod
    def from_toml(text: str) -> Model: ...
    @staticmethod
    def load(path: str | PathLike[str]) -> Model: ...
    @staticmethod
    def from_params(params: Params) -> Model: ...
    def with_(self, **values: Any) -> Model: ...
    def to_toml(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    def paper_params(self) -> Params | None: ...
    def _engine(self) -> tuple[Params, bool, float, float, bool]: ...
    def __reduce__(self) -> tuple[Callable[..., Model], tuple[str]]: ...

@final
class Theory:
    """The averaged theory of a parameter set in one formula variant."""

    def __init__(self, params: Params, variant: str = "paper") -> None: ...
    def equivalents(self) -> dict[str, float]: ...
    def cycles(self) -> Cycles: ...
    def drift(self, a: Sequence[float]) -> npt.NDArray[np.float64]: ...
    def drift_slope(self, a: Sequence[float]) -> npt.NDArray[np.float64]: ...
    def energy_change(self, a: Sequence[float]) -> npt.NDArray[np.float64]: ...
    def fpk_drift(self, a: Sequence[float]) -> npt.NDArray[np.float64]: ...
    def potential(self, a: Sequence[float]) -> npt.NDArray[np.float64]: ...
    def extrema(self) -> list[Extremum]: ...
    def barriers(self) -> list[Barrier]: ...
    def pdf(
        self, kind: str, grid: Sequence[float], v: Sequence[float] | None = None
    ) -> npt.NDArray[np.float64]: ...

def preset(name: str) -> Params: ...
def presets() -> list[tuple[str, str, list[str]]]: ...
def version() -> str: ...
def _profile_start() -> None: ...
def _profile_stop() -> tuple[float, float, int, float] | None: ...
def _params_from_dict(d: dict[str, float]) -> Params: ...
def _simulate(
    params: Params,
    t_end: float,
    dt: float,
    u0: float,
    v0: float,
    seed: int,
    path: int,
    every: int,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    impact_memory: str,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> dict[str, Any]: ...
def _ensemble(
    params: Params,
    paths: int,
    t_end: float,
    burn_in: float,
    seed: int,
    dt: float,
    u0: Sequence[float],
    variant: str,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    impact_memory: str,
    bins: int,
    joint_bins: int,
    amplitude_max: float | None,
    sample_every: int,
    which: Sequence[int] | None = None,
    pieces: Sequence[str] | None = None,
    merge: bool = True,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
    setup_only: bool = False,
    backend: str = "cpu",
) -> str: ...
def _ensemble_wells(
    params: Params,
    paths: int,
    t_end: float,
    burn_in: float,
    seed: int,
    dt: float,
    u0: Sequence[float],
    variant: str,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    impact_memory: str,
    bins: int,
    joint_bins: int,
    amplitude_max: float | None,
    sample_every: int,
    clones: int,
    max_excursion: float,
    max_iterations: int,
    separation: float,
    core_quantile: float,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> str: ...
def _lyapunov(
    params: Params,
    t_end: float,
    transient: float,
    dt: float,
    paths: int,
    seed: int,
    u0: float,
    impact_memory: str,
    method: str,
    renormalise_every: int,
    separation: float,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> str: ...
def _critical_noise(
    params: Params,
    noises: Sequence[float] | None,
    d_range: tuple[float, float] | None,
    points: int,
    sweep: tuple[str, Sequence[float]] | None,
    t_end: float,
    transient: float,
    dt: float | None,
    paths: int,
    seed: int,
    impact_memory: str,
    method: str,
    renormalise_every: int,
    separation: float,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    variant: str,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> str: ...
def _attractor(
    params: Params,
    u0: float | None,
    dt: float,
    impact_memory: str,
    t_max: float,
    variant: str,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    model: Model | None = None,
    threads: int | None = None,
) -> str: ...
def _phase_response(
    params: Params,
    u0: float | None,
    dt: float,
    impact_memory: str,
    phases: int,
    kick: float,
    periods: int,
    t_max: float,
    variant: str,
    system: str,
    barrier: bool,
    memory: str,
    tolerance: float | None,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> tuple[str, list[str]]: ...
def _oscillation_boundary(
    params: Params,
    x_key: str,
    x: Sequence[float],
    y_key: str,
    y_range: tuple[float, float],
    method: str = "simulation",
    variant: str = "paper",
    barrier: bool = True,
    tolerance: float = 1e-3,
    model: Model | None = None,
    threads: int | None = None,
    progress: _Progress = None,
) -> str: ...
def _map(
    params: Params,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    what: str = "rhythmicity",
    variant: str = "paper",
    threads: int | None = None,
    progress: _Progress = None,
    folds: bool = False,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[Any], str | None]: ...
def _simulated_map(
    params: Params,
    x: tuple[str, float, float, int],
    y: tuple[str, float, float, int],
    variant: str = "paper",
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
    progress: _Progress = None,
    backend: str = "cpu",
) -> str: ...
def _branches(
    params: Params,
    key: str,
    start: float,
    stop: float,
    what: str = "rhythmicity",
    variant: str = "paper",
    step: float = 0.004,
    threads: int | None = None,
) -> str: ...
def _figure_data(
    n: int, quick: bool = False, variant: str = "paper", threads: int | None = None, progress: _Progress = None
) -> str: ...

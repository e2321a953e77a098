"""Small named results of the compiled module (``Theory.cycles()``, ``Theory.barriers()``),
defined in Python so that they are plain named tuples: they unpack as tuples did, and their
fields have names."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Cycles(NamedTuple):
    """The averaged theory's limit cycles (D = 0) or the extrema of P(A) (D > 0), by amplitude:
    ``amplitude`` (float array), ``stable`` (bool array: a stable cycle or a mode of P(A)) and
    ``fold`` (bool array: at a fold, where a stable and an unstable cycle meet). Unpacks as
    ``amplitude, stable, fold = theory.cycles()``."""

    amplitude: np.ndarray
    stable: np.ndarray
    fold: np.ndarray

    def __repr__(self) -> str:
        rows = ", ".join(
            f"{a:.6g} {'stable' if s else 'unstable'}{' (fold)' if f else ''}"
            for a, s, f in zip(self.amplitude, self.stable, self.fold)
        )
        return f"Cycles({len(self.amplitude)}: {rows})"


class Extremum(NamedTuple):
    """An extremum of U_eff (Eq. 23): its ``amplitude``, ``potential`` U_eff there, and
    ``minimum`` (a well; ``False``: a crest), as ``trirhythm barriers --format json``'s
    ``extrema``."""

    amplitude: float
    potential: float
    minimum: bool


class Barrier(NamedTuple):
    """One energy barrier of U_eff (Eq. 23) between consecutive extrema: from the well at
    amplitude ``well`` to the crest at ``crest`` on its ``side`` (``"left"``: towards smaller
    amplitude, ``"right"``: towards larger), ``height`` ΔU = U_eff(crest) − U_eff(well), and
    ``name`` ``"dU1"``, ``"dU2"``, … in order, as ``trirhythm barriers --format json`` names
    them (ΔU1, ΔU2, … in the paper's figures)."""

    well: float
    crest: float
    side: str
    height: float
    name: str

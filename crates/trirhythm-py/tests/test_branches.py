"""Branch diagrams and fold curves from Python (issue 37, item 3): the same bits as
`trirhythm branches` and `trirhythm map --folds`."""

import json

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli


def test_branches_are_the_command_lines(cli):
    p = tr.preset("fig5").with_(mu0=0.01)
    b = tr.branches(p, ("r", 0.8, 1.0))
    doc = json.loads(run_cli(cli, "branches", "--preset", "fig5", "--param", "mu0=0.01", "--x", "r=0.8:1", "--format", "json"))
    assert doc.pop("params") and doc.pop("variant") == "paper"
    assert b.to_dict() == doc
    assert len(b.branches) == len(doc["branches"]) >= 1
    first = doc["branches"][0]["points"]
    assert np.array_equal(b.branches[0].param, [q["param"] for q in first])
    assert np.array_equal(b.branches[0].amplitude, [q["amplitude"] for q in first])
    assert b.branches[0].stable.dtype == bool
    assert b.folds.shape == (len(doc["folds"]), 2)
    assert len(repr(b).splitlines()) <= 20


def test_branches_refuse_bad_input():
    p = tr.preset("fig5")
    with pytest.raises(ValueError, match=r"step = 0.5: allowed range is \[1e-6, 0.1\]"):
        tr.branches(p, ("r", 0.8, 1.0), step=0.5)
    with pytest.raises(ValueError, match="x = "):
        tr.branches(p, ("r", 0.8))
    with pytest.raises(ValueError, match="unknown map"):
        tr.branches(p, ("r", 0.8, 1.0), what="wobbly")


def test_map_folds_are_the_command_lines(cli):
    p = tr.preset("fig2ii")
    x, y = ("gamma0", 0.0, 1.2e-4, 41), ("delta0", 1e-8, 6e-7, 41)
    xs, ys, counts, folds = tr.rhythmicity_map(p, x, y, folds=True)
    doc = json.loads(
        run_cli(cli, "map", "--preset", "fig2ii", "--x", "gamma0=0:1.2e-4:41", "--y", "delta0=1e-8:6e-7:41", "--folds",
                "--format", "json")
    )
    assert folds.to_dict() == doc["folds"]
    assert counts.tolist() == doc["counts"]
    assert len(folds.curves) == len(doc["folds"]["curves"]) >= 1
    c = folds.curves[0]
    assert np.array_equal(c.x, [q["x"] for q in doc["folds"]["curves"][0]["points"]])
    assert len(repr(folds).splitlines()) <= 20
    # without folds: the three arrays, as before
    plain = tr.rhythmicity_map(p, x, y)
    assert len(plain) == 3 and np.array_equal(plain.counts, counts)


def _json(out):
    return json.loads(out, parse_constant=float)


def _num(x):
    return float(x) if isinstance(x, str) else x


def test_the_theory_curves_are_the_command_lines(cli):
    th = tr.Theory(tr.preset("fig4c"))
    d = _json(run_cli(cli, "drift", "--preset", "fig4c", "--grid", "0.1:14:5", "--format", "json"))
    a = d["A"]
    assert np.array_equal(th.drift(a), d["f"])
    assert np.array_equal(th.drift_slope(a), d["df_dA"])
    assert np.array_equal(th.energy_change(a), d["delta_E"])
    fig8 = tr.Theory(tr.preset("fig8"))
    d = _json(run_cli(cli, "potential", "--preset", "fig8", "--grid", "0:14:5", "--format", "json"))
    assert np.array_equal(fig8.potential(d["A"]), [_num(x) for x in d["U_eff"]])
    assert np.array_equal(fig8.fpk_drift(d["A"]), [_num(x) for x in d["m1"]])
    assert fig8.fpk_drift([0.0])[0] == np.inf
    d = _json(run_cli(cli, "barriers", "--preset", "fig8", "--format", "json"))
    assert [e._asdict() for e in fig8.extrema()] == d["extrema"]

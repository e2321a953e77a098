"""The P-bifurcation map by simulation from Python (issue 39, item 5): the same bits as
`trirhythm map --simulate`, arrays shaped [iy, ix], bad input refused by name."""

import json

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli

# Fig. 12(d)'s set at λ = 1, white noise, μ0 = 0.01 around r = 0.95, D = 1: two modes of P(A)
# that the paths hop between (tests/simulated_map.rs in the library).
FLAGS = ["--preset", "fig12d", "--param", "lambda=1", "--param", "tau=0", "--param", "mu0=0.01",
         "--x", "r=0.95:0.951:2", "--y", "D=1:1.01:2", "--paths", "8", "--t-end", "20000",
         "--burn-in", "200", "--dt", "0.05", "--batches", "10", "--seed", "3"]


def test_simulated_map_is_the_command_lines(cli):
    p = tr.preset("fig12d").with_(lambda_=1.0, tau=0.0, mu0=0.01)
    m = tr.simulated_map(p, ("r", 0.95, 0.951, 2), ("D", 1.0, 1.01, 2), paths=8, t_end=20000.0,
                         burn_in=200.0, dt=0.05, batches=10, seed=3)
    doc = json.loads(run_cli(cli, "map", "--simulate", *FLAGS, "--format", "json"))
    assert doc.pop("params") and "dt=0.05" in doc.pop("method")
    assert m.to_dict() == doc
    assert m.theory.shape == (2, 2) and m.theory.tolist() == [[2, 2], [2, 2]]
    assert m.simulated.tolist() == [[2, 2], [2, 2]]
    assert m.low.tolist() == m.high.tolist() == [[2, 2], [2, 2]]
    assert np.array_equal(m.x, [0.95, 0.951]) and np.array_equal(m.y, [1.0, 1.01])
    for iy in range(2):
        for ix in range(2):
            expected = "agree" if m.stationary[iy, ix] else "non_stationary"
            assert m.agreement[iy, ix] == expected
    assert sum(m.tally.values()) == 4 and m.tally["agree"] >= 3
    assert "agree" in repr(m)


def test_simulated_map_refuses_bad_input():
    p = tr.preset("fig12d")
    x, y = ("r", 0.9, 1.0, 2), ("D", 0.1, 1.0, 2)
    with pytest.raises(ValueError, match="paths = 0"):
        tr.simulated_map(p, x, y, paths=0)
    with pytest.raises(ValueError, match="z = 1"):
        tr.simulated_map(p, x, y, z=1.0)
    with pytest.raises(ValueError, match="D = 0"):
        tr.simulated_map(p.with_(D=0.0), x, ("mu0", 0.01, 0.02, 2))
    with pytest.raises(ValueError, match="dt = -1"):
        tr.simulated_map(p, x, y, dt=-1.0)

"""`trirhythm.Model`: the keyword arguments are the model file's tables; load, to_toml, the
round trip; `model=` in simulate and ensemble gives the preset's numbers; a bad field or a
term the engine does not step yet is a ValueError naming it."""

import pickle

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli

FIG13A = dict(
    leading={"lambda": 0.998},
    damping={"mu0": 0.005, "coefficients": [1.0, -1.0, 0.144, -0.005, 5.862e-5, -2.13e-7]},
    restoring={"omega0": 1.0},
    wall=[{"position": 0.0, "keep": "above", "restitution": 0.99}],
    noise={"additive": {"intensity": 0.1, "correlation_time": 0.5}},
)


def test_the_keyword_arguments_are_the_files_tables():
    m = tr.Model(**FIG13A)
    assert m.paper_params() == tr.preset("fig13a")
    assert m == tr.Model.from_params(tr.preset("fig13a"))
    assert tr.Model.from_toml(m.to_toml()) == m
    assert tr.Model(**m.to_dict()) == m
    assert pickle.loads(pickle.dumps(m)) == m


def test_load_reads_what_model_show_prints(cli, tmp_path):
    text = run_cli(cli, "model", "show", "--preset", "fig13a")
    path = tmp_path / "fig13a.toml"
    path.write_text(text)
    m = tr.Model.load(str(path))
    assert m == tr.Model(**FIG13A)
    # and a file written from Python checks on the command line
    out = tmp_path / "mine.toml"
    out.write_text(m.to_toml())
    assert "a valid model file" in run_cli(cli, "model", "check", str(out))


@pytest.mark.parametrize(
    "change, field",
    [
        (dict(leading={"lambda": 1.5}), r"leading\.lambda = 1\.5: allowed range is \(0, 1\]"),
        (dict(damping={"mu0": -1.0}), r"damping\.mu0 = -1"),
        (dict(damping={"coefficients": [1.0]}), r"damping\.mu0: missing field"),
        (dict(restoring={"omega0": float("nan")}), r"restoring\.omega0 = NaN: allowed range is a finite number"),
        (dict(wall=[{"position": 0.0, "keep": "left", "restitution": 0.9}]), r"wall\.0\.keep"),
        (dict(wall=[{"position": 0.0, "keep": "above", "restitution": 2.0}]), r"wall\.0\.restitution = 2"),
        (dict(noise={"additive": {"intensity": 0.1, "tau": 0.5}}), r"noise\.additive\.tau: unknown field"),
        (dict(start={"u0": -1.0}), r"start\.u0 = -1"),
        (dict(colour="red"), r"colour: unknown field"),
    ],
)
def test_a_bad_field_is_a_value_error_naming_it(change, field):
    with pytest.raises(ValueError, match=field):
        tr.Model(**{**FIG13A, **change})


def test_model_runs_as_the_preset():
    m = tr.Model(**FIG13A)
    a = tr.simulate(tr.preset("fig13a"), t_end=20.0)
    b = tr.simulate(model=m, t_end=20.0)
    for x, y in [(a.t, b.t), (a.u, b.u), (a.v, b.v), (a.eta, b.eta)]:
        assert np.array_equal(x, y)
    e1 = tr.ensemble(tr.preset("fig13a"), paths=2, t_end=10.0, burn_in=2.0, u0=1.0)
    e2 = tr.ensemble(model=m, paths=2, t_end=10.0, burn_in=2.0)
    assert e1.statistics() == e2.statistics()
    # no wall, another start: the file's, not the defaults
    free = tr.Model(**{**FIG13A, "wall": [], "start": {"u0": -0.5}})
    c = tr.simulate(model=free, t_end=20.0)
    d = tr.simulate(tr.preset("fig13a"), t_end=20.0, barrier=False, u0=-0.5)
    assert np.array_equal(c.u, d.u)


def test_what_the_model_says_is_not_given_twice():
    m = tr.Model(**FIG13A)
    with pytest.raises(ValueError, match="params or model"):
        tr.simulate(tr.preset("fig13a"), model=m)
    with pytest.raises(ValueError, match="u0 = 2.0: the model says"):
        tr.simulate(model=m, u0=2.0)
    with pytest.raises(ValueError, match="barrier = False: the model says"):
        tr.ensemble(model=m, barrier=False)


def test_a_term_the_engine_does_not_step_is_refused_by_name():
    duffing = tr.Model(**{**FIG13A, "restoring": {"omega0": 1.0, "cubic": 0.5}})
    assert duffing.paper_params() is None
    with pytest.raises(ValueError, match=r"restoring\.cubic = 0\.5 .*does not step it yet"):
        tr.ensemble(model=duffing, paths=1, t_end=1.0)
    fractional = tr.Model(**{**FIG13A, "fractional": [{"coefficient": 0.1, "order": 0.5}]})
    with pytest.raises(ValueError, match=r"fractional\.0\.coefficient"):
        tr.simulate(model=fractional, t_end=1.0)
    forced = tr.Model(**{**FIG13A, "forcing": {"amplitude": 0.1, "frequency": 1.0}})
    with pytest.raises(ValueError, match=r"forcing\.amplitude"):
        tr.ensemble(model=forced, paths=1, t_end=1.0)


def test_simulate_steps_a_model_with_two_walls_as_the_command_line():
    """A linear oscillator between a wall at -0.5 and one at 0.8 with r = 1 (the General
    kernel's walls): U stays between them, both are met, and the period is the exact
    2(asin 0.8 + asin 0.5) of the harmonic arcs."""
    import math

    m = tr.Model(
        leading={"lambda": 1.0},
        damping={"mu0": 1.0, "coefficients": [0.0]},
        restoring={"omega0": 1.0},
        wall=[
            {"position": -0.5, "keep": "above", "restitution": 1.0},
            {"position": 0.8, "keep": "below", "restitution": 1.0},
        ],
        start={"u0": 0.0, "v0": 1.0},
    )
    p = tr.simulate(model=m, t_end=30.0, dt=0.005)
    assert p.u.min() >= -0.5 and p.u.max() <= 0.8
    assert p.summary["impacts"] > 15
    # upward crossings of U = 0: one per period
    ups = [p.t[i] for i in range(1, len(p.u)) if p.u[i - 1] < 0.0 <= p.u[i]]
    period = (ups[-1] - ups[0]) / (len(ups) - 1)
    exact = 2.0 * (math.asin(0.8) + math.asin(0.5))
    assert abs(period - exact) < 1e-3 * exact, (period, exact)
    with pytest.raises(ValueError, match="u0 = 2.0: the model says"):
        tr.simulate(model=m, u0=2.0)

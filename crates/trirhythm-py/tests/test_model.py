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


def test_multiplicative_noise_at_a_wall_off_zero_is_stepped():
    """U·η_m beside a wall at δ = −0.5: δ·η_m acts at the wall, the path stays above it."""
    offset = [{"position": -0.5, "keep": "above", "restitution": 0.9}]
    noise = {**FIG13A["noise"], "multiplicative": {"intensity": 0.1}}
    parametric = tr.Model(**{**FIG13A, "wall": offset, "noise": noise})
    assert parametric.paper_params() is None
    t = tr.simulate(model=parametric.with_(**{"start.u0": 1.0}), t_end=50.0, seed=3)
    assert np.all(t.u >= -0.5) and np.min(t.u) < -0.45


def test_a_fractional_term_with_a_wall_is_stepped():
    """K·D^αU beside the paper's wall at 0: the path stays above the wall and meets it."""
    fractional = tr.Model(**{**FIG13A, "fractional": [{"coefficient": 0.2, "order": 0.5}]})
    assert fractional.paper_params() is None
    t = tr.simulate(model=fractional.with_(**{"start.u0": 1.0}), t_end=20.0, seed=3)
    assert np.all(t.u >= 0.0) and np.min(t.u) < 0.05


# Duffing under additive white noise: Ü + cU̇ + ω0²U + k3U³ = η, ⟨η(t)η(s)⟩ = 2Dδ(t − s)
# (h = μ0·P(U) with P = −1: c = μ0). Its stationary density is ∝ exp(−c·H/D),
# H = U̇²/2 + ω0²U²/2 + k3U⁴/4, so ⟨U̇²⟩ = D/c and ⟨U²⟩ is a ratio of two integrals.
DUFFING = dict(
    leading={"lambda": 1.0},
    damping={"mu0": 0.5, "coefficients": [-1.0]},
    restoring={"omega0": 1.0, "cubic": 0.0},
    noise={"additive": {"intensity": 0.25}},
    wall=[],
    start={"u0": 0.5},
)


def _duffing_second_moment(c, d, k3):
    u = np.linspace(-8.0, 8.0, 20001)
    w = np.exp(-(c / d) * (u**2 / 2 + k3 * u**4 / 4))
    return float(np.sum(u**2 * w) / np.sum(w))


def test_with_sets_dotted_fields_and_refuses_bad_ones_by_name():
    m = tr.Model(**DUFFING)
    k = m.with_(**{"restoring.cubic": 2.0, "noise.additive.correlation_time": 0.5})
    assert k.to_dict()["restoring"]["cubic"] == 2.0
    assert k.to_dict()["noise"]["additive"]["correlation_time"] == 0.5
    assert m.to_dict()["restoring"]["cubic"] == 0.0  # a copy: the model is immutable
    walled = m.with_(**{"wall.0": {"position": 0.0, "keep": "above", "restitution": 0.9}, "start.u0": 0.5})
    assert walled.to_dict()["wall"][0]["restitution"] == 0.9
    for change, field in [
        ({"restoring.cubic": float("nan")}, r"restoring\.cubic = NaN"),
        ({"leading.lambda": 2.0}, r"leading\.lambda = 2: allowed range is \(0, 1\]"),
        ({"wall.2.position": 0.0}, r"wall\.2\.position: index 2 is past the list's end"),
        ({"restoring.omega0.x": 1.0}, r"restoring\.omega0\.x"),
        ({"restoring.k7": 1.0}, r"restoring\.k7: unknown field"),
    ]:
        with pytest.raises(ValueError, match=field):
            m.with_(**change)


def test_a_duffing_model_runs_through_every_simulating_call():
    m = tr.Model(**DUFFING).with_(**{"restoring.cubic": 1.0})
    a = tr.simulate(model=m, t_end=20.0, seed=3)
    b = tr.simulate(model=m, t_end=20.0, seed=3)
    linear = tr.simulate(model=tr.Model(**DUFFING), t_end=20.0, seed=3)
    assert np.array_equal(a.u, b.u) and not np.array_equal(a.u, linear.u)
    lle = tr.lyapunov(model=m, paths=2, t_end=200.0, transient=20.0)
    # a damped system: the exponent is negative (the linear one's is −c/2 = −0.25)
    assert lle["lle"]["value"] < 0
    e = tr.ensemble(model=m, paths=2, t_end=50.0, burn_in=10.0, amplitude_max=6.0)
    assert "does not apply" in e["theory"]["paper"]["error"]
    # the pieces of an ensemble of a model merge into the whole, bit for bit
    pieces = [tr.ensemble_paths(None, [i], paths=2, t_end=50.0, burn_in=10.0, model=m, amplitude_max=6.0) for i in (1, 0)]
    merged = tr.merge_paths(None, pieces, paths=2, t_end=50.0, burn_in=10.0, model=m, amplitude_max=6.0)
    assert merged.statistics() == e.statistics()


def test_calls_built_on_the_averaged_theory_refuse_a_duffing_model_with_the_reason():
    m = tr.Model(**DUFFING).with_(**{"restoring.cubic": 1.0})
    for call in (
        lambda: tr.critical_noise(model=m, points=2),
        lambda: tr.attractor(model=m),
        lambda: tr.attractor_starts(model=m),
        lambda: tr.phase_response(model=m),
        lambda: tr.oscillation_boundary(model=m, x=("lambda", [0.9]), y=("mu0", 0.0, 0.1)),
    ):
        with pytest.raises(ValueError, match=r"averaged theory .*restoring\.cubic = 1"):
            call()


def test_a_sweep_over_a_model_field_matches_the_exact_duffing_variance():
    base = tr.Model(**DUFFING)
    ds = tr.sweep(
        "ensemble", {"restoring.cubic": [0.0, 1.0]}, base=base, paths=8, t_end=400.0, burn_in=20.0,
        amplitude_max=6.0, seed=5,
    )
    c, d = 0.5, 0.25
    for i, k3 in enumerate([0.0, 1.0]):
        exact = _duffing_second_moment(c, d, k3)
        value, se = float(ds["var_u"][i]), float(ds["var_u_stderr"][i])
        assert abs(value - exact) < 4 * se + 0.01 * exact, (k3, value, se, exact)
        v, vse = float(ds["var_v"][i]), float(ds["var_v_stderr"][i])
        assert abs(v - d / c) < 4 * vse + 0.01 * d / c, (k3, v, vse)
    # each point is the direct call at that model, bit for bit
    one = tr.ensemble(
        model=base.with_(**{"restoring.cubic": 1.0}), paths=8, t_end=400.0, burn_in=20.0,
        amplitude_max=6.0, seed=5,
    )
    assert one.statistics()["var_u"] == (float(ds["var_u"][1]), float(ds["var_u_stderr"][1]))
    assert "restoring.cubic" in ds.coords


def test_the_own_oscillator_example_runs_from_its_model_file():
    import pathlib
    import subprocess
    import sys

    root = pathlib.Path(__file__).resolve().parents[3]
    out = subprocess.run(
        [sys.executable, str(root / "examples" / "python" / "own_oscillator.py"), "--quick"],
        capture_output=True, text=True, timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert "theory (consistent): occupancy 0.6571" in out.stdout
    assert out.stdout.count("inner well's occupancy") == 4


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

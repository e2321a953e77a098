"""The critical noise by regime (``critical_noise``) against the command line's ``trirhythm
critical-noise`` (the same document, bit for bit), with the regime rules' outcomes on a stable
cycle and in the rest regime, and bad arguments refused by name. Quick sizes: a few paths,
short windows."""

import json
import math

import pytest

import trirhythm as tr
from conftest import run_cli

# Fig. 17(a)'s parameters at μ0 = 0.05 and 0.06: three stable cycles each, the rest state
# unstable; weak noise (λ ≈ −c·D on a cycle)
CYCLES = dict(noises=[0.001, 0.003], paths=4, t_end=100.0, transient=20.0)
CLI_CYCLES = [
    "--preset", "fig17a", "--param", "mu0=0.05", "--noises", "0.001,0.003", "--paths", "4",
    "--t-end", "100", "--transient", "20", "--sweep", "mu0=0.05:0.06:2", "--format", "json",
]


@pytest.fixture(scope="module")
def cli_cycles(cli):
    return json.loads(run_cli(cli, "critical-noise", *CLI_CYCLES))


@pytest.fixture(scope="module")
def cycles(cli_cycles):
    values = [r["value"] for r in cli_cycles["results"]]
    base = tr.preset("fig17a").with_(mu0=0.05)
    return tr.critical_noise(base, sweep=("mu0", values), threads=1, **CYCLES)


def test_the_result_is_the_command_lines_document_on_any_thread_count(cycles, cli_cycles):
    doc = dict(cli_cycles)
    doc.pop("params")
    assert cycles.to_dict() == doc
    values = [r["value"] for r in cli_cycles["results"]]
    again = tr.critical_noise(tr.preset("fig17a"), sweep=("mu0", values), threads=2, **CYCLES)
    assert again.to_dict() == cycles.to_dict()


def test_a_stable_cycle_at_small_noise_is_not_chaotic_and_its_d_c_lies_above(cycles):
    assert cycles.sweep == "mu0" and list(cycles.noises) == [0.001, 0.003]
    assert cycles.margin == 0.01
    assert len(cycles.curves) == 6
    assert [c.value for c in cycles.curves] == [0.05] * 3 + [0.06] * 3
    for c in cycles.curves:
        assert c.regime == "cycle" and c.name in ("inner", "middle", "outer"), c.attractor
        assert c.dt == 0.005  # τ = 0.06: the figures' rule
        assert c.rest is None and c.coefficient > 0
    # at μ0 = 0.05 every cycle is synchronised by the weak noise (at 0.06 the outer cycle's
    # exponent exceeds δ = 1/W over so short a window)
    for c in cycles.curves[:3]:
        assert [q.call for q in c.points] == ["not-chaotic", "not-chaotic"], c
        assert [q.D for q in c.points] == [0.001, 0.003]
        assert all(q.n == 4 and q.merged == 0 and q.lle < 0.01 for q in c.points)
        assert (c.bracket.kind, c.bracket.lo, c.bracket.hi) == ("above", 0.003, None)
        assert c.decision.startswith("not chaotic up to the largest D = 0.003: D_c > 0.003")
    a = cycles.curves[0].arrays()
    assert list(a["D"]) == [0.001, 0.003] and list(a["call"]) == ["not-chaotic"] * 2
    # what sweep records: the brackets and coefficients, per value
    s = cycles.statistics()
    assert s["outer_0_dc_lo"][0] == 0.003 and math.isnan(s["outer_0_dc_hi"][0])
    assert s["inner_1_coefficient"][0] == cycles.curves[3].coefficient


def test_a_located_bracket_says_whether_the_paths_left_the_cycles_well():
    # Fig. 17(a)'s μ0 = 0.001: the outer cycle is regular at D = 0.003 and chaotic at D = 5,
    # where every reference path leaves the cycle's well within the run
    r = tr.critical_noise(
        tr.preset("fig17a").with_(mu0=0.001), noises=[0.003, 5.0], paths=8, t_end=400.0,
        transient=20.0, threads=1,
    )
    outer = [c for c in r.curves if c.name == "outer"]
    assert len(outer) == 1
    c = outer[0]
    assert (c.bracket.kind, c.bracket.lo, c.bracket.hi) == ("located", 0.003, 5.0)
    assert [e.D for e in c.escape] == [0.003, 5.0]
    low, high = c.escape
    assert low.escaped == 0 and math.isnan(low.median_time)
    assert high.escaped == high.paths == 8 and 0 < high.median_time < high.run == 420.0
    assert 0 < low.lo < 12.65 and math.isinf(low.hi)
    assert "the bracket depends on the window" in c.decision
    # no escape is measured where there is no located bracket
    assert all(not x.escape for x in r.curves if x.bracket.kind != "located")


def test_a_rest_regime_parameter_set_gives_a_rest_curve():
    # Fig. 18(b)'s r = 0.8: every start comes to rest on the wall
    r = tr.critical_noise(
        tr.preset("fig18b").with_(r=0.8), noises=[1e-6, 1e-4, 1e-2], paths=3, t_end=50.0, transient=10.0
    )
    assert len(r.curves) == 1
    c = r.curves[0]
    assert (c.attractor, c.regime, c.value, c.dt) == ("rest", "rest", None, 0.0025)
    assert isinstance(c.rest, tr.RestRegime) and c.rest.decades == 4.0
    assert all(math.isfinite(x) for x in (c.rest.pooled, c.rest.pooled_se, c.rest.slope))
    assert c.coefficient is None and all(q.agrees is None for q in c.points)
    s = r.statistics()
    assert s["rest_pooled"] == (c.rest.pooled, c.rest.pooled_se)
    assert s["rest_dc_zero"][0] == float(c.rest.d_c_zero)


def test_sweep_records_a_rest_curve():
    ds = tr.sweep(
        "critical_noise",
        {"r": [0.8]},
        base=tr.preset("fig18b"),
        noises=[1e-6, 1e-4, 1e-2],
        paths=3,
        t_end=50.0,
        transient=10.0,
    )
    assert dict(ds.sizes) == {"r": 1}
    for name in ("rest_pooled", "rest_pooled_stderr", "rest_slope", "rest_dc_zero", "rest_dc_lo"):
        assert name in ds, name
    assert math.isfinite(float(ds["rest_pooled"][0]))


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(d_range=(0.0, 1.0)), "invalid parameter d_range = 0: allowed range is a low end in (0, ∞)"),
        (dict(d_range=(1.0, 0.5)), "invalid parameter d_range = 0.5: allowed range is a high end in (1, ∞)"),
        (dict(d_range=(0.1, 1.0), points=1), "invalid parameter points = 1: allowed range is 2 to 1000"),
        (dict(d_range=(0.1, 1.0), points=-1), "invalid parameter points = -1"),
        (dict(noises=[0.1, 0.05]), "invalid parameter noises = 0.05: allowed range is above"),
        (dict(noises=[]), "invalid parameter noises = 0: allowed range is 1 to 1000 values"),
        (dict(d_range=(0.1, 1.0), noises=[0.1]), "either as noises or as d_range"),
        (dict(sweep=("D", [0.1])), "any parameter but D"),
        (dict(sweep=("lambda", [2.0])), "invalid parameter lambda = 2"),
        (dict(dt=1.0), "invalid parameter dt = 1: allowed range is [1e-4, 0.1]"),
        (dict(paths=0), "invalid parameter paths = 0"),
        (dict(t_end=100.003), "invalid parameter t_end = 100.003"),
        (dict(u0=1.0), "unknown argument(s) ['u0']"),
        (dict(method="wobbly"), "unknown method `wobbly`"),
        (
            dict(d_range=(1e-6, 10.0), points=500, sweep=("mu0", [0.01] * 1000), paths=3),
            "invalid parameter paths = 3: allowed range is 1 to 2 here",
        ),
    ],
)
def test_bad_arguments_are_refused_by_name(kwargs, needle):
    with pytest.raises(ValueError) as e:
        tr.critical_noise(tr.preset("fig17a"), **kwargs)
    assert needle in str(e.value)

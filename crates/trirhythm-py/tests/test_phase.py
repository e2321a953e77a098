"""Attractors of noise-free starts and the phase response, against the command line's
`trirhythm phase-response` (the same bits)."""

import json
import warnings

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli

# the other runs, small enough to keep the suite fast
PHASES, PERIODS = 32, 9


@pytest.fixture(scope="module")
def fig17a():
    return tr.preset("fig17a").with_(mu0=0.01)


@pytest.fixture(scope="module")
def cli_phase(cli):
    # the defaults (128 phases, 60 sections, the outer amplitude): about 1 s
    args = ["--preset", "fig17a", "--param", "mu0=0.01", "--format", "json"]
    return json.loads(run_cli(cli, "phase-response", *args))


@pytest.fixture(scope="module")
def phase(fig17a):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        r = tr.phase_response(fig17a)
    # the step guard's warning (6 steps per τ), as the command line's; no "no coefficient"
    assert [str(w.message) for w in seen] == [f"phase_response: {w}" for w in r.step_warnings]
    return r


def test_the_outer_start_of_fig17a_ends_on_the_outer_cycle(fig17a, cli_phase):
    amplitudes, stable, _ = tr.Theory(fig17a.with_(D=0)).cycles()
    outer = amplitudes[stable][-1]
    a = tr.attractor(fig17a, outer)
    assert (a.kind, a.name, a.label, a.index) == ("cycle", "outer", "outer", 2)
    assert a.theory_amplitude == outer and a.u0 == outer
    # the command line starts phase-response at the same amplitude
    assert cli_phase["u0"] == outer
    assert abs(a.amplitude - cli_phase["amplitude"]) < 0.01 * cli_phase["amplitude"]
    assert a.period > 0 and a.to_dict()["attractor"]["kind"] == "cycle"


def test_a_start_at_one_ends_on_the_inner_cycle(fig17a):
    a = tr.attractor(fig17a, 1.0)
    assert (a.kind, a.name) == ("cycle", "inner"), a


def test_with_the_rest_state_stable_the_start_ends_at_rest():
    p = tr.preset("fig18b").with_(r=0.9)
    a = tr.attractor(p, 1.0)
    assert (a.kind, a.label, a.name, a.period) == ("rest", "rest", None, None), a
    starts = tr.attractor_starts(p)
    assert len(starts) == 1 and starts[0][1].kind == "rest" and starts[0][0] == starts[0][1].u0


def test_the_phase_response_is_the_command_lines_bit_for_bit(phase, cli_phase):
    assert phase.coefficient is not None and phase.coefficient == cli_phase["coefficient"]
    # the whole result: every key of the library's document, the samples included
    for key, value in phase.to_dict().items():
        assert value == cli_phase[key], key
    assert phase.step_warnings == cli_phase["step_warnings"] and len(phase.step_warnings) == 1
    assert phase.theta.shape == phase.z.shape == (128,)
    assert np.array_equal(phase.z, [s["z"] for s in cli_phase["samples"]])
    assert phase.omega == pytest.approx(2 * np.pi / phase.period)
    assert phase.cycle.name == "outer" and phase.section == "impact"
    assert phase.prediction(0.01) == -phase.coefficient * 0.01
    assert 0 < phase.uncertainty < 0.05 * phase.coefficient and phase.linearity < 1e-2


def test_white_noise_has_no_coefficient_and_says_why(fig17a):
    with pytest.warns(RuntimeWarning, match="no coefficient: white noise"):
        r = tr.phase_response(fig17a.with_(tau=0), phases=PHASES, periods=PERIODS)
    assert r.coefficient is None and "diverges" in r.undefined
    assert np.isnan(r.uncertainty) and r.prediction(0.01) is None
    assert r.z.shape == (PHASES,)


def test_bad_arguments_are_refused_by_name(fig17a):
    with pytest.raises(ValueError, match=r"phases = 7: allowed range is an even number from 8 to 4096"):
        tr.phase_response(fig17a, phases=7)
    with pytest.raises(ValueError, match=r"phases = 'many': allowed range is an integer"):
        tr.phase_response(fig17a, phases="many")
    with pytest.raises(ValueError, match=r"dt = 0.5: allowed range is \[1e-4, 0.1\]"):
        tr.phase_response(fig17a, dt=0.5)
    with pytest.raises(ValueError, match=r"kick = 1: allowed range is \[1e-8, 1e-2\]"):
        tr.phase_response(fig17a, kick=1.0)
    with pytest.raises(ValueError, match=r"periods = 3: allowed range is 6 to 100000"):
        tr.phase_response(fig17a, periods=3)
    with pytest.raises(ValueError, match=r"t_max = 0: allowed range is \(0, 1e6\]"):
        tr.attractor(fig17a, 1.0, t_max=0)
    with pytest.raises(ValueError, match=r"unknown variant `best`"):
        tr.attractor(fig17a, 1.0, variant="best")
    with pytest.raises(ValueError, match=r"reaches no cycle \(rest\)"):
        tr.phase_response(tr.preset("fig18b").with_(r=0.9), u0=1.0, phases=PHASES, periods=PERIODS)
    with pytest.raises(ValueError, match=r"unknown argument"):
        tr.attractor(fig17a, 1.0, paths=3)

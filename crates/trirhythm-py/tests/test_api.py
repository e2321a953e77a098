"""The package's functions: errors, shapes, and the same numbers as the command line."""

import json
import pickle

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli


@pytest.fixture
def noisy():
    return tr.preset("fig4c").with_(D=0.01)


# --- errors: ValueError naming the parameter, its value and the allowed range -------------


def test_a_bad_parameter_names_itself_its_value_and_its_range():
    with pytest.raises(ValueError, match=r"lambda = 2: allowed range is \(0, 1\]"):
        tr.preset("fig4c").with_(lambda_=2)
    with pytest.raises(ValueError, match=r"invalid parameter r = -0.5"):
        tr.Params(r=-0.5)
    with pytest.raises(ValueError, match=r"unknown parameter `zeta`"):
        tr.preset("fig4c").with_(zeta=1.0)
    with pytest.raises(ValueError, match=r"parameter D: `'x'` is not a number"):
        tr.preset("fig4c").with_(D="x")
    with pytest.raises(ValueError, match=r"unknown preset `nope`: expected one of .*fig4c"):
        tr.preset("nope")


def test_bad_run_arguments_are_refused_by_name(noisy):
    with pytest.raises(ValueError, match=r"dt = -0.01"):
        tr.simulate(noisy, t_end=1.0, dt=-0.01)
    with pytest.raises(ValueError, match=r"every = 0: allowed range is an integer, 1 or more"):
        tr.simulate(noisy, t_end=1.0, every=0)
    with pytest.raises(ValueError, match=r"unknown system `wobbly`: expected one of fractional, equivalent, zhuravlev"):
        tr.simulate(noisy, t_end=1.0, system="wobbly")
    with pytest.raises(ValueError, match=r"paths = 0"):
        tr.ensemble(noisy, paths=0, t_end=10, burn_in=1)
    with pytest.raises(ValueError, match=r"amplitude_max = 1e-300"):
        tr.ensemble(noisy, paths=2, t_end=10, burn_in=1, amplitude_max=1e-300)
    with pytest.raises(ValueError, match=r"dt = 0.5: allowed range is \[1e-4, 0.1\]"):
        tr.lyapunov(noisy, paths=2, t_end=10, dt=0.5)
    with pytest.raises(ValueError, match=r"threads = 0"):
        tr.simulate(noisy, t_end=1.0, threads=0)
    with pytest.raises(ValueError, match=r"n = 20: allowed range is 1 to 19"):
        tr.figure_data(20)
    with pytest.raises(ValueError, match=r"unknown variant `best`"):
        tr.Theory(noisy, variant="best")


# --- shapes ----------------------------------------------------------------------------------


def test_shapes(noisy):
    p = tr.simulate(noisy, t_end=10.0, every=10)
    assert p.t.shape == p.u.shape == p.v.shape == p.eta.shape == (101,)
    assert p.t[-1] == pytest.approx(10.0)
    quiet = tr.simulate(tr.preset("fig4c"), t_end=1.0)
    assert quiet.eta is None and quiet.u.shape == (101,)
    th = tr.Theory(noisy, variant="consistent")
    a = np.linspace(0.1, 15, 7)
    assert th.drift(a).shape == th.potential(a).shape == th.pdf("amplitude", a).shape == (7,)
    assert th.pdf("joint", a, v=np.linspace(-3, 3, 4)).shape == (4, 7)
    amp, stable, fold = th.cycles()
    assert amp.shape == stable.shape == fold.shape and stable.dtype == bool
    e = tr.ensemble(noisy, paths=2, t_end=10, burn_in=1, bins=16)
    h = e.density("energy")
    assert h["edges"].shape == (17,) and h["density"].shape == h["stderr"].shape == (16,)
    widths = np.diff(e.density()["edges"])
    assert (e.density()["density"] * widths).sum() + e.density()["beyond"] == pytest.approx(1.0)
    xs, ys, counts = tr.rhythmicity_map(noisy, ("gamma0", 0, 1e-4, 5), ("delta0", 0, 1e-6, 3))
    assert xs.shape == (5,) and ys.shape == (3,) and counts.shape == (3, 5)
    assert set(np.unique(counts)) <= {0, 1, 2, 3}


def test_params_pickle_and_read_back(noisy):
    again = pickle.loads(pickle.dumps(noisy))
    assert again == noisy and again["D"] == 0.01
    assert noisy.keys()[:4] == ["mu0", "omega0", "lambda", "r"]
    assert tr.Params(**noisy.to_dict()) == noisy


# --- bit-identity with the command line built from the same tree ------------------------------


def _csv_columns(text):
    rows = [l for l in text.splitlines() if not l.startswith("#")]
    header, body = rows[0].split(","), rows[1:]
    data = np.array([[float(x) for x in r.split(",")] for r in body])
    return header, data


@pytest.mark.parametrize("system", ["fractional", "equivalent"])
def test_simulate_is_the_command_lines_path_bit_for_bit(cli, noisy, system):
    args = ["--preset", "fig4c", "--param", "D=0.01", "--t-end", "20", "--seed", "7", "--u0", "2.5"]
    args += ["--every", "3", "--system", system, "--impact-memory", "restart"]
    header, data = _csv_columns(run_cli(cli, "simulate", *args, "--format", "csv"))
    assert header == ["t", "U", "V", "eta"]
    p = tr.simulate(noisy, t_end=20, seed=7, u0=2.5, every=3, system=system, impact_memory="restart")
    for i, col in enumerate([p.t, p.u, p.v, p.eta]):
        assert np.array_equal(col, data[:, i]), header[i]
    doc = json.loads(run_cli(cli, "simulate", *args, "--format", "json"))
    assert doc["U"] == p.u.tolist() and doc["V"] == p.v.tolist() and doc["eta"] == p.eta.tolist()


def test_ensemble_to_dict_is_the_command_lines_document(cli, noisy):
    args = ["--preset", "fig4c", "--param", "D=0.01", "--paths", "3", "--t-end", "30", "--burn-in", "5"]
    args += ["--seed", "11", "--bins", "20", "--joint-bins", "8"]
    doc = json.loads(run_cli(cli, "ensemble", *args, "--format", "json"))
    mine = tr.ensemble(noisy, paths=3, t_end=30, burn_in=5, seed=11, bins=20, joint_bins=8).to_dict()
    doc.pop("wall_time_s")
    mine.pop("wall_time_s")
    assert mine == doc


def test_the_well_method_is_the_command_lines(cli):
    p = tr.preset("fig13a").with_(r=0.99, D=0.2)
    args = ["--preset", "fig13a", "--param", "r=0.99", "--param", "D=0.2", "--method", "wells"]
    args += ["--paths", "2", "--t-end", "300", "--burn-in", "20", "--clones", "8", "--bins", "20"]
    args += ["--joint-bins", "4"]
    doc = json.loads(run_cli(cli, "ensemble", *args, "--format", "json"))
    mine = tr.ensemble(
        p, paths=2, t_end=300, burn_in=20, bins=20, joint_bins=4, method="wells", clones=8
    ).to_dict()
    doc.pop("wall_time_s")
    mine.pop("wall_time_s")
    assert mine == doc
    assert mine["estimator"] == "wells" and len(mine["decomposition"]["weights"]) == 2
    with pytest.raises(ValueError, match="clones = 1"):
        tr.ensemble(p, paths=2, t_end=300, method="wells", clones=1)
    with pytest.raises(ValueError, match="method"):
        tr.ensemble(p, paths=2, t_end=300, method="splitting")
    with pytest.raises(ValueError, match="clones"):
        tr.ensemble(p, paths=2, t_end=300, clones=8)
    # starts the well method would ignore are refused, as on the command line
    with pytest.raises(ValueError, match="u0"):
        tr.ensemble(p, paths=2, t_end=300, method="wells", u0=[1.0, 2.0])


def test_figure_data_is_the_command_lines(cli, tmp_path):
    run_cli(cli, "figure", "4", "--quick", "--data", "--out-dir", str(tmp_path))
    with open(tmp_path / "fig04.json") as f:
        doc = json.load(f)
    assert tr.figure_data(4, quick=True) == doc["data"]


# --- one ensemble split into pieces ----------------------------------------------------------


def test_split_ensembles_merge_to_the_same_bits(noisy):
    kw = dict(paths=6, t_end=20, burn_in=2, seed=5, bins=16, joint_bins=6)
    whole = tr.ensemble(noisy, **kw).to_dict()
    whole.pop("wall_time_s")
    for split in ([[0, 1, 2, 3, 4, 5]], [[4, 5], [0, 1], [2, 3]], [[i] for i in (5, 3, 1, 0, 2, 4)]):
        pieces = [pickle.loads(pickle.dumps(tr.ensemble_paths(noisy, w, **kw))) for w in split]
        merged = tr.merge_paths(noisy, pieces, **kw).to_dict()
        merged.pop("wall_time_s")
        assert merged == whole, split
    with pytest.raises(ValueError, match="pieces"):
        tr.merge_paths(noisy, [tr.ensemble_paths(noisy, [0], **kw)], **kw)


def test_threads_do_not_change_the_result(noisy):
    kw = dict(paths=4, t_end=15, burn_in=2, seed=3, bins=10, joint_bins=4)
    one = tr.ensemble(noisy, threads=1, **kw).statistics()
    two = tr.ensemble(noisy, threads=2, **kw).statistics()
    assert one == two


def test_progress_reaches_the_callback(noisy):
    seen = []
    tr.simulate(noisy, t_end=200.0, progress=lambda d, t: seen.append((d, t)))
    assert seen and seen[-1][0] == seen[-1][1] > 0
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))


def test_an_exception_in_the_callback_stops_the_call(noisy):
    def boom(done, total):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        tr.simulate(noisy, t_end=5000.0, every=1000, progress=boom)


def test_the_readme_python_example_runs():
    import pathlib
    import re

    readme = (pathlib.Path(__file__).resolve().parents[3] / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, re.S)
    assert blocks, "the README has no Python example"
    assert len(blocks[0].strip().splitlines()) <= 12
    exec(compile(blocks[0], "README.md", "exec"), {})

"""Results a researcher can read (issue 37): the stationarity diagnosis as numbers with a
warning, compact reprs, named fields, Params hashable with a repr that gives it back,
conflicting aliases refused, and errors that name the right argument and range."""

import json
import math
import warnings

import numpy as np
import pytest

import trirhythm as tr
from conftest import run_cli


@pytest.fixture(scope="module")
def readme():
    """The README's example: fig4c at D = 0.01, whose paths never leave their wells."""
    return tr.preset("fig4c").with_(D=0.01)


@pytest.fixture(scope="module")
def not_stationary(readme):
    with pytest.warns(tr.NotStationaryWarning, match=r"NOT stationary \(R̂ = inf"):
        return tr.ensemble(readme, paths=4, t_end=200.0, burn_in=50.0)


def test_a_non_stationary_ensemble_warns_and_its_r_hat_is_inf(not_stationary):
    assert issubclass(tr.NotStationaryWarning, Warning)
    st = not_stationary.stationarity
    assert st.stationary is False and not_stationary.stationary is False
    assert isinstance(st.r_hat, float) and st.r_hat == math.inf
    assert f"{st.r_hat:.2f}" == "inf"  # the TypeError
    assert isinstance(st.ess, float) and st.ess > 0
    assert st.method == "direct"
    # the document follows the library's JSON rule: the string "inf", never null
    assert not_stationary.to_dict()["stationarity"]["r_hat"] == "inf"


def test_the_command_line_writes_the_same_inf(cli):
    out = run_cli(
        cli, "ensemble", "--preset", "fig4c", "--param", "D=0.01", "--paths", "4", "--t-end", "200",
        "--burn-in", "50", "--format", "json",
    )
    assert json.loads(out)["stationarity"]["r_hat"] == "inf"


def test_the_warning_can_be_an_error(readme):
    with warnings.catch_warnings():
        warnings.simplefilter("error", tr.NotStationaryWarning)
        with pytest.raises(tr.NotStationaryWarning):
            tr.ensemble(readme, paths=2, t_end=50.0, burn_in=5.0)


def test_merged_paths_warn_too(readme):
    kw = dict(paths=2, t_end=50.0, burn_in=5.0)
    pieces = [tr.ensemble_paths(readme, [0], **kw), tr.ensemble_paths(readme, [1], **kw)]
    with pytest.warns(tr.NotStationaryWarning, match="merge_paths"):
        tr.merge_paths(readme, pieces, **kw)


def test_a_sweep_records_the_diagnosis_per_point_and_warns_once(readme):
    with pytest.warns(tr.NotStationaryWarning) as caught:
        ds = tr.sweep("ensemble", {"r": [0.9, 0.96]}, base=readme, paths=2, t_end=50.0, burn_in=5.0)
    assert len([w for w in caught if issubclass(w.category, tr.NotStationaryWarning)]) == 1
    assert ds["stationary"].dtype == bool and not ds["stationary"].any()
    assert ds["r_hat"].dtype == float and np.isinf(ds["r_hat"]).all()
    assert (ds["ess"] > 0).all()
    assert "r_hat_stderr" not in ds and "stationary_stderr" not in ds
    assert "direct estimator" in ds.attrs["stationarity"]


def test_reprs_are_short(readme, not_stationary):
    path = tr.simulate(readme, t_end=20.0)
    fig17a = tr.preset("fig17a").with_(mu0=0.01)
    results = [
        not_stationary,
        not_stationary.stationarity,
        path,
        tr.ensemble_paths(readme, [0, 1], paths=2, t_end=20.0, burn_in=2.0),
        tr.Theory(readme).cycles(),
        tr.Theory(tr.preset("fig8")).barriers(),
        tr.attractor(fig17a, 1.0),
        readme,
        tr.Model.from_params(readme),
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        results.append(tr.phase_response(fig17a, phases=16, periods=6))
        results.append(
            tr.critical_noise(fig17a, noises=[0.001, 0.003], paths=2, t_end=50.0, transient=10.0, dt=0.01)
        )
    for r in results:
        text = repr(r)
        assert len(text.splitlines()) <= 20, text
        assert len(text) <= 3000, (type(r).__name__, len(text))
    assert "stationarity: NOT stationary" in repr(not_stationary)


def test_theory_results_have_named_fields_as_the_command_line(cli):
    p = tr.preset("fig8")
    c = tr.Theory(p).cycles()
    amplitude, stable, fold = c  # still unpacks
    assert c.amplitude is amplitude and c.stable.dtype == bool and c.fold.dtype == bool
    bs = tr.Theory(p).barriers()
    doc = json.loads(run_cli(cli, "barriers", "--preset", "fig8", "--format", "json"))
    assert [b.name for b in bs] == [b["name"] for b in doc["barriers"]] == ["dU1", "dU2", "dU3", "dU4"]
    for b, d in zip(bs, doc["barriers"]):
        assert (b.well, b.crest, b.side, b.height) == (d["well"], d["crest"], d["side"], d["height"])


def test_params_are_hashable_immutable_and_their_repr_gives_them_back(readme):
    same = tr.preset("fig4c").with_(D=0.01)
    assert readme == same and hash(readme) == hash(same)
    assert len({readme, same, readme.with_(D=0.02)}) == 2
    text = repr(readme)
    assert text.startswith("Params(mu0=0.01, omega0=1, lambda_=0.998, r=0.96, ")
    assert eval(text, {"Params": tr.Params}) == readme
    with pytest.raises(AttributeError):
        readme.mu0 = 1.0  # type: ignore[misc]
    assert hash(tr.Params(D=-0.0)) == hash(tr.Params(D=0.0))


@pytest.mark.parametrize(
    "values, names",
    [
        ({"alpha0": 0.1, "c2": 0.2}, ("alpha0", "c2")),
        ({"c3": 0.1, "beta0": 0.2}, ("c3", "beta0")),
        ({"lambda": 0.9, "lambda_": 0.95}, ("lambda", "lambda_")),
        ({"c02": 0.1, "c2": 0.2}, ("c02", "c2")),
    ],
)
def test_conflicting_aliases_are_refused_naming_both(values, names):
    with pytest.raises(ValueError, match=rf"conflicting parameters {names[0]} and {names[1]}"):
        tr.Params(**values)
    with pytest.raises(ValueError, match="conflicting"):
        tr.preset("fig4c").with_(**values)


def test_a_sweep_over_lambda_underscore_names_its_dimension_lambda(readme):
    ds = tr.sweep("simulate", {"lambda_": [0.99, 1.0]}, base=readme.with_(D=0.0), t_end=1.0)
    assert list(ds.sizes) == ["lambda"] and "lambda_" not in ds.coords
    with pytest.raises(ValueError, match="both set lambda"):
        tr.sweep("simulate", {"lambda_": [0.99], "lambda": [1.0]}, base=readme, t_end=1.0)


def test_counts_out_of_range_give_one_message(readme):
    for paths in (2**70, -3, 0, 1_000_001):
        with pytest.raises(ValueError, match=r"paths = .*: allowed range is an integer, 1 to 1000000"):
            tr.ensemble(readme, paths=paths, t_end=10.0, burn_in=1.0)
        with pytest.raises(ValueError, match=r"allowed range is an integer, 1 to 1000000"):
            tr.lyapunov(readme, paths=paths, t_end=10.0)
    with pytest.raises(ValueError, match=r"seed = 1180591620717411303424: allowed range is an integer, 0 or more"):
        tr.simulate(readme, t_end=1.0, seed=2**70)


def test_a_step_too_coarse_blames_dt(readme):
    for t_end in (200.0, 15.0):
        with pytest.raises(ValueError, match=r"invalid parameter dt = 10"):
            tr.simulate(readme, t_end=t_end, dt=10)
    with pytest.raises(ValueError, match=r"invalid parameter dt = 10"):
        tr.ensemble(readme, dt=10)

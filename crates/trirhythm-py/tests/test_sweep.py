"""Sweeps: serial against a Dask LocalCluster of 2 workers and against path-split merges
(bit for bit), checkpoints, a worker's heartbeat during a long call, KeyboardInterrupt."""

import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

import trirhythm as tr

KW = dict(paths=4, t_end=15.0, burn_in=2.0, bins=12, joint_bins=4)
GRID = {"lambda": [0.99, 0.998], "r": [0.9, 0.96]}


@pytest.fixture(scope="module")
def base():
    return tr.preset("fig4c").with_(D=0.01)


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def serial(base):
    return tr.sweep("ensemble", GRID, base=base, seed=3, **KW)


def test_the_dataset_has_one_dimension_per_key_and_standard_errors(serial):
    assert serial.sizes == {"lambda": 2, "r": 2}
    assert list(serial.coords["r"].values) == [0.9, 0.96]
    for name in ("mean_amplitude", "var_u", "mean_u"):
        assert name in serial and f"{name}_stderr" in serial
    assert np.all(serial["mean_amplitude_stderr"] > 0)
    assert serial.attrs["seed"] == 3 and "common random numbers" in serial.attrs["seeds"]


def test_each_point_is_the_direct_call_with_the_same_seed(serial, base):
    e = tr.ensemble(base.with_(**{"lambda": 0.998, "r": 0.9}), seed=3, **KW).statistics()
    point = serial.sel({"lambda": 0.998, "r": 0.9})
    assert point["mean_amplitude"].item() == e["mean_amplitude"][0]
    assert point["mean_amplitude_stderr"].item() == e["mean_amplitude"][1]


def test_path_chunks_give_the_same_bits(serial, base):
    for chunk in (1, 3):
        chunked = tr.sweep("ensemble", GRID, base=base, seed=3, chunk_paths=chunk, **KW)
        xr.testing.assert_identical(chunked, serial)


def test_a_local_cluster_gives_the_serial_bits(serial, base, client):
    on_cluster = tr.sweep("ensemble", GRID, base=base, seed=3, client=client, **KW)
    xr.testing.assert_identical(on_cluster, serial)
    chunked = tr.sweep("ensemble", GRID, base=base, seed=3, client=client, chunk_paths=1, **KW)
    xr.testing.assert_identical(chunked, serial)


def test_netcdf_round_trip(serial, tmp_path):
    engine = "h5netcdf" if _has("h5netcdf") else None
    if engine is None and not _has("netCDF4") and not _has("scipy"):
        pytest.skip("no netCDF backend")
    f = tmp_path / "sweep.nc"
    serial.to_netcdf(f, engine=engine)
    back = xr.load_dataset(f, engine=engine)
    xr.testing.assert_identical(back, serial)


def _has(module):
    try:
        __import__(module)
        return True
    except ImportError:
        return False


def _custom(params, seed, scale=1.0):
    """A picklable custom function: a number and a (value, stderr) pair."""
    return {"x": params["lambda"] * scale + seed, "pair": (params["r"], 0.5)}


def test_a_custom_function_and_checkpoints_that_resume(base, tmp_path):
    d = tmp_path / "ck"
    first = tr.sweep(_custom, {"lambda": [0.5, 0.9], "r": [0.1, 0.2, 0.3]}, base=base, seed=2, checkpoint=d, scale=2.0)
    assert first["x"].sel({"lambda": 0.9}).values.tolist() == [3.8] * 3
    assert first["pair_stderr"].values.tolist() == [[0.5] * 3] * 2
    files = sorted(p.name for p in d.iterdir())
    assert "sweep.json" in files and len([f for f in files if f.startswith("point-")]) == 6
    # a resumed sweep computes only the missing points: mark one saved point
    (d / "point-0-0.json").unlink()
    text = (d / "point-1-2.json").read_text().replace('"3.8"', '"99.0"')
    (d / "point-1-2.json").write_text(text)
    again = tr.sweep(_custom, {"lambda": [0.5, 0.9], "r": [0.1, 0.2, 0.3]}, base=base, seed=2, checkpoint=d, scale=2.0)
    assert again["x"].values[1, 2] == 99.0  # taken from the file, not recomputed
    assert again["x"].values[0, 0] == first["x"].values[0, 0]  # recomputed
    with pytest.raises(ValueError, match="holds another sweep"):
        tr.sweep(_custom, {"lambda": [0.5, 0.9], "r": [0.1, 0.2, 0.3]}, base=base, seed=3, checkpoint=d, scale=2.0)


def _never_called(params, seed):
    raise AssertionError("a sweep with an unwritable checkpoint must not start")


def test_an_unwritable_checkpoint_is_refused_before_any_work(base, tmp_path):
    # a checkpoint under a regular file cannot be created (root included)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ValueError, match="checkpoint.*not a directory"):
        tr.sweep(_never_called, {"lambda": [0.5]}, base=base, checkpoint=blocker / "ck")
    assert blocker.read_text() == "x"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_lyapunov_and_boundary_sweeps(base):
    lle = tr.sweep("lyapunov", {"D": [0.01, 0.05]}, base=base, seed=2, paths=2, t_end=20.0, transient=5.0)
    direct = tr.lyapunov(base.with_(D=0.05), paths=2, t_end=20.0, transient=5.0, seed=2)["lle"]
    assert lle["lle"].sel(D=0.05).item() == direct["value"]
    assert lle["lle_stderr"].sel(D=0.05).item() == direct["stderr"]
    fig15 = tr.preset("fig15").with_(lambda_=1.0)
    b = tr.sweep(
        "oscillation_boundary", {"omega0": [1.0, 1.2]}, base=fig15, x=("r", [0.9]), y=("mu0", 0.001, 0.3), method="exact"
    )
    assert b.sizes == {"omega0": 2}
    one = tr.oscillation_boundary(fig15.with_(omega0=1.2), x=("r", [0.9]), y=("mu0", 0.001, 0.3), method="exact")
    assert b["y"].sel(omega0=1.2).item() == one["points"][0]["y"]
    assert b["y_lo"].item(0) <= b["y"].item(0) <= b["y_hi"].item(0)


def test_bad_sweeps_are_refused_before_any_work(base):
    with pytest.raises(ValueError, match=r"lambda = 1.5: allowed range is \(0, 1\]"):
        tr.sweep("ensemble", {"lambda": [0.9, 1.5]}, base=base, **KW)
    with pytest.raises(ValueError, match="func = 'nothing'"):
        tr.sweep("nothing", {"r": [0.9]}, base=base)
    with pytest.raises(ValueError, match="chunk_paths = 2: only func='ensemble'"):
        tr.sweep("lyapunov", {"r": [0.9]}, base=base, chunk_paths=2)


def _long_call():
    import trirhythm as tr

    # a few seconds on one thread (20 million steps)
    return tr.simulate(tr.preset("fig4c").with_(D=0.01), t_end=200000.0, every=10000000, threads=1).summary["steps"]


def test_a_worker_stays_responsive_during_a_long_call(client):
    fut = client.submit(_long_call, pure=False)
    # wait until the call runs
    deadline = time.time() + 10
    while not client.processing() or not any(client.processing().values()):
        assert time.time() < deadline
        time.sleep(0.05)
    time.sleep(0.3)
    # a worker whose task held the GIL could not answer before the task ended: every ping must
    # come back while the task still runs (the time bound is loose for a loaded machine; idle,
    # a ping takes about 10 ms)
    worst = 0.0
    for _ in range(3):
        t = time.perf_counter()
        client.run(lambda: 1)
        worst = max(worst, time.perf_counter() - t)
        assert not fut.done(), (
            f"a ping came back only after the long call ended ({worst:.2f} s): the call held the GIL "
            "(or, on a fast machine, it is too short)"
        )
        time.sleep(0.1)
    assert worst < 2.0, f"a ping took {worst:.2f} s while a task ran"
    assert fut.result() == 20_000_000


def test_keyboard_interrupt_stops_a_long_call_within_a_second(tmp_path):
    # the child takes Python's own Ctrl-C handler whatever it inherits: a runner that starts the
    # suite as a background job passes SIGINT on as ignored, and the test is of the package
    code = (
        "import signal\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "import trirhythm as tr, sys\n"
        "p = tr.preset('fig4c').with_(D=0.01)\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    tr.simulate(p, t_end=1e6, every=1000000)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "running"
    time.sleep(0.5)
    t = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    try:
        out, err = proc.communicate(timeout=5)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the call did not stop within 5 s of SIGINT")
    took = time.perf_counter() - t
    assert proc.returncode == 3, err
    assert "interrupted" in out
    assert took < 1.5, f"stopped {took:.2f} s after SIGINT"


DKW = dict(paths=3, t_end=15.0, burn_in=2.0, bins=10, joint_bins=4)
DGRID = {"r": [0.9, 0.96], "D": [0.01, 0.02]}


@pytest.fixture(scope="module")
def densities(base):
    with pytest.warns(tr.NotStationaryWarning):
        return tr.sweep("ensemble", DGRID, base=base, seed=2, densities=True, **DKW)


def test_a_density_sweep_has_p_of_a_on_common_bins(densities, base):
    ds = densities
    assert ds["density_amplitude"].dims == ("r", "D", "amplitude")
    assert ds.sizes["amplitude"] == 10
    assert ds["density_amplitude_stderr"].dims == ("r", "D", "amplitude")
    amax = tr._ensemble_range(base, **DKW)
    assert ds.attrs["amplitude_max"] == amax
    assert ds["amplitude_hi"].values[-1] == amax and ds["amplitude_lo"].values[0] == 0.0
    # each point is the direct call's histogram at the common range, bit for bit
    e = tr.ensemble(base.with_(r=0.96, D=0.02), seed=2, amplitude_max=amax, **DKW).density()
    point = ds.sel(r=0.96, D=0.02)
    assert np.array_equal(point["density_amplitude"].values, e["density"])
    assert np.array_equal(point["density_amplitude_stderr"].values, e["stderr"])
    assert point["density_amplitude_beyond"].item() == e["beyond"]
    # the theory's P(A) at the bin centres, both variants
    th = tr.Theory(base.with_(r=0.96, D=0.02), "consistent").pdf("amplitude", list(ds["amplitude"].values))
    assert np.array_equal(point["theory_amplitude_consistent"].values, th)
    assert ds["theory_amplitude_paper"].dims == ("r", "D", "amplitude")


def test_a_density_sweep_on_a_local_cluster_is_the_serial_one_bit_for_bit(densities, base, client):
    with pytest.warns(tr.NotStationaryWarning):
        on_cluster = tr.sweep("ensemble", DGRID, base=base, seed=2, client=client, densities=True, **DKW)
    xr.testing.assert_identical(on_cluster, densities)
    with pytest.warns(tr.NotStationaryWarning):
        chunked = tr.sweep("ensemble", DGRID, base=base, seed=2, client=client, chunk_paths=2, densities=True, **DKW)
    xr.testing.assert_identical(chunked, densities)


def test_density_sweeps_take_a_given_range_and_other_kinds(base):
    with pytest.warns(tr.NotStationaryWarning):
        ds = tr.sweep(
            "ensemble", {"r": [0.9]}, base=base, densities=["amplitude", "turning"], amplitude_max=20.0, **DKW
        )
    assert ds.attrs["amplitude_max"] == 20.0 and ds["amplitude_hi"].values[-1] == 20.0
    assert ds["density_turning"].dims == ("r", "turning")
    with pytest.raises(ValueError, match="densities"):
        tr.sweep("lyapunov", {"r": [0.9]}, base=base, densities=True)
    with pytest.raises(ValueError, match="densities"):
        tr.sweep("ensemble", {"r": [0.9]}, base=base, densities=["wobbly"])


def test_a_profiled_call_gives_the_same_result_and_a_consistent_profile(base):
    plain = tr.lyapunov(base, paths=4, t_end=20.0, seed=1)
    same, prof = tr.profiled(tr.lyapunov, base, paths=4, t_end=20.0, seed=1)
    def stable(d):
        return {k: v for k, v in d.items() if k not in ("wall_time_s", "steps_per_second")}

    assert stable(same) == stable(plain)
    # four realisations run as parallel tasks (two lanes of two); the critical path is one
    assert prof.tasks >= 2
    assert 0 < prof.critical_path_s <= prof.total_cpu_s * (1 + 1e-9)
    assert prof.speedup_bound >= 1
    # profiling stops with the call: a later call is not counted anywhere
    assert tr._native._profile_stop() is None


def test_a_profiled_sweep_adds_a_profile_per_point_and_changes_nothing_else(base, serial):
    profiled = tr.sweep("ensemble", GRID, base=base, seed=3, profile=True, **KW)
    chunked = tr.sweep("ensemble", GRID, base=base, seed=3, chunk_paths=2, profile=True, **KW)
    for ds in (profiled, chunked):
        for v in serial.data_vars:
            np.testing.assert_array_equal(ds[v].values, serial[v].values)
        cpu = ds["profile_total_cpu_s"].values
        crit = ds["profile_critical_path_s"].values
        assert (cpu > 0).all() and (crit > 0).all() and (crit <= cpu * (1 + 1e-9)).all()
        assert "bound on the speed-up" in ds.attrs["profile"]
    # two chunks of two paths run side by side: the point's tasks are the chunks' tasks
    assert (chunked["profile_tasks"].values >= 2).all()
    assert "profile" not in serial.attrs and "profile_total_cpu_s" not in serial

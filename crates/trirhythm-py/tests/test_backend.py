"""``ensemble(backend=...)``: ``"cpu"`` is the default's bits; ``"gpu"`` without a CUDA driver or
device raises ``ValueError`` naming the GPU backend and the reason; an unknown name is refused."""

import pytest

import trirhythm as tr

KW = dict(paths=2, t_end=20, burn_in=5, seed=3, bins=16, joint_bins=6)


@pytest.fixture
def noisy():
    return tr.preset("fig4c").with_(D=0.01)


def test_the_cpu_backend_is_the_default_bit_for_bit(noisy):
    default = tr.ensemble(noisy, **KW).to_dict()
    cpu = tr.ensemble(noisy, backend="cpu", **KW).to_dict()
    default.pop("wall_time_s")
    cpu.pop("wall_time_s")
    assert "backend" not in default
    assert cpu == default


def test_the_gpu_backend_without_a_device_raises_the_reason(noisy):
    try:
        e = tr.ensemble(noisy, backend="gpu", **KW)
    except ValueError as error:
        message = str(error)
        assert message.startswith("the GPU backend does not apply to this model: it assumes "), message
        # what failed, exactly: the driver's library, the device, or (with both) the kernel
        assert any(
            w in message for w in ("libcuda", "the driver is loaded but", "the ensemble kernel")
        ), message
        return
    # a machine with a GPU and the kernel: the document says where it ran
    assert e.to_dict()["backend"] == "gpu"


def test_an_unknown_backend_is_refused_naming_the_choices(noisy):
    with pytest.raises(ValueError, match=r"^unknown backend `tpu`: expected one of cpu, gpu$"):
        tr.ensemble(noisy, backend="tpu", **KW)


def test_the_well_method_runs_on_the_cpu_only(noisy):
    with pytest.raises(ValueError, match=r"backend = 'gpu': method='wells' runs on the CPU only"):
        tr.ensemble(noisy, method="wells", backend="gpu", **KW)


def test_the_simulated_map_takes_the_backend():
    p = tr.preset("fig13a")
    kw = dict(paths=2, t_end=40.0, burn_in=4.0, dt=0.05, batches=4, seed=2)
    x, y = ("D", 0.1, 0.2, 2), ("tau", 0.5, 0.6, 2)
    default = tr.simulated_map(p, x, y, **kw).to_dict()
    cpu = tr.simulated_map(p, x, y, backend="cpu", **kw).to_dict()
    assert cpu == default
    try:
        tr.simulated_map(p, x, y, backend="gpu", **kw)
    except ValueError as error:
        assert "a CUDA driver and device" in str(error), str(error)
    with pytest.raises(ValueError, match=r"^unknown backend `tpu`"):
        tr.simulated_map(p, x, y, backend="tpu", **kw)

"""A (λ, r) plane of Monte Carlo ensembles: the mean amplitude ⟨A⟩ with its standard error.

Run as a script (``python examples/python/sweep_plane.py``) or cell by cell in Jupyter (the
``# %%`` markers). With ``--dask`` the points run on a LocalCluster of two workers; any other
Dask cluster works the same way (``docs/python.md``). Needs ``pip install ./crates/trirhythm-py
"dask[distributed]" xarray matplotlib``.
"""

# %%
import sys

import matplotlib

if "ipykernel" not in sys.modules:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import trirhythm as tr

base = tr.preset("fig4c").with_(D=0.1)
grid = {"lambda": np.linspace(0.99, 1.0, 4), "r": np.linspace(0.9, 0.99, 4)}
run = dict(paths=6, t_end=300.0, burn_in=50.0)

# %%
client = None
if "--dask" in sys.argv:
    from dask.distributed import Client, LocalCluster

    client = Client(LocalCluster(n_workers=2, threads_per_worker=1))
ds = tr.sweep("ensemble", grid, base=base, seed=1, client=client, progress=True, **run)
print(ds[["mean_amplitude", "mean_amplitude_stderr"]])

# %%
fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
ds["mean_amplitude"].plot(ax=a, x="r", y="lambda", cmap="viridis")
a.set_title("⟨A⟩ (common random numbers)")
for lam in ds["lambda"].values:
    row = ds.sel({"lambda": lam})
    b.errorbar(row["r"], row["mean_amplitude"], yerr=2 * row["mean_amplitude_stderr"], capsize=3, label=f"λ = {lam:.4f}")
b.set_xlabel("r")
b.set_ylabel("⟨A⟩ ± 2 s.e.")
b.legend(fontsize=8)
out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else "sweep_plane.png"
fig.savefig(out, dpi=120)
print("wrote", out)

"""A (λ, r) plane of Monte Carlo ensembles: the mean amplitude ⟨A⟩ with its standard error.

Run as a script (``python examples/python/sweep_plane.py``) or cell by cell in Jupyter (the
``# %%`` markers). With ``--dask`` the points run on a LocalCluster of two workers; any other
Dask cluster works the same way (``docs/python.md``); ``--quick`` is a 2 × 2 plane of short
runs (seconds), ``--out FILE`` names the picture. Needs ``pip install
"./crates/trirhythm-py[all]"``.

The work is inside ``main()`` under ``if __name__ == "__main__":``: Dask's workers are new
processes that import this file, and must not start a cluster of their own.
"""

# %%
from __future__ import annotations

import sys
from typing import Any

import matplotlib

if "ipykernel" not in sys.modules:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import trirhythm as tr


def main(argv: list[str]) -> None:
    quick = "--quick" in argv
    base = tr.preset("fig4c").with_(D=0.1)
    n = 2 if quick else 4
    grid = {"lambda": np.linspace(0.99, 1.0, n), "r": np.linspace(0.9, 0.99, n)}
    run: dict[str, Any] = dict(paths=2, t_end=20.0, burn_in=5.0) if quick else dict(paths=6, t_end=300.0, burn_in=50.0)

    # %%
    client = None
    if "--dask" in argv:
        from dask.distributed import Client, LocalCluster

        client = Client(LocalCluster(n_workers=2, threads_per_worker=1))
    try:
        ds = tr.sweep("ensemble", grid, base=base, seed=1, client=client, progress=not quick, **run)
    finally:
        if client is not None:
            client.close()
    print(ds[["mean_amplitude", "mean_amplitude_stderr", "stationary", "r_hat"]])

    # %%
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    ds["mean_amplitude"].plot(ax=a, x="r", y="lambda", cmap="viridis")
    a.set_title("⟨A⟩ (common random numbers)")
    for lam in ds["lambda"].values:
        row = ds.sel({"lambda": lam})
        b.errorbar(
            row["r"], row["mean_amplitude"], yerr=2 * row["mean_amplitude_stderr"], capsize=3, label=f"λ = {lam:.4f}"
        )
    b.set_xlabel("r")
    b.set_ylabel("⟨A⟩ ± 2 s.e.")
    b.legend(fontsize=8)
    out = argv[argv.index("--out") + 1] if "--out" in argv else "sweep_plane.png"
    fig.savefig(out, dpi=120)
    print("wrote", out)


if __name__ == "__main__":
    main(sys.argv[1:])

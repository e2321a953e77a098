"""Two systems of the family from their model files, against what could be read of their papers
(docs/published-systems.md): the numbers of the comparison and one figure.

    python examples/published/published_systems.py                   # about 30 s on 2 cores
    python examples/published/published_systems.py --out fig.png     # the figure elsewhere

It runs the command line (`$TRIRHYTHM`, else target/release/trirhythm, else `trirhythm` on the
PATH; build it with `cargo build --release -p trirhythm-cli`) and needs numpy and matplotlib.

1. The trirhythmic van der Pol oscillator of Saha, Gangopadhyay and Ray (arXiv:2008.03499),
   examples/models/trirhythmic-vdp.toml: the averaged drift f(A) of `trirhythm drift` against
   the amplitude equation printed in the paper, the cycles of `trirhythm cycles` (five,
   stable-unstable-stable-unstable-stable, as printed), and three deterministic paths of
   `trirhythm simulate`, one in each stable cycle's basin, settling on the averaged radii.
2. The vibro-impact Duffing oscillator between two barriers of Yang, Xu, Gu and Huang (Chaos,
   Solitons and Fractals 87, 2016), examples/models/bilateral-vibroimpact-duffing.toml: an
   ensemble of `trirhythm ensemble` at r = 1 against the exact stationary density
   p ~ exp(-c H / D) on [-1, 1] (the paper's own parameters and densities were not readable),
   and the same oscillator at r = 0.8 beside it.
"""

import argparse
import json
import math
import os
import pathlib
import shutil
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
TRI = ROOT / "examples" / "models" / "trirhythmic-vdp.toml"
VI = ROOT / "examples" / "models" / "bilateral-vibroimpact-duffing.toml"

# the printed parameters (the model file's damping.coefficients) and amplitude equation
ALPHA, BETA, GAMMA, DELTA = 0.144, 0.005, 5.862e-5, 2.13e-7
# the chosen parameters of the two-barrier oscillator (the model file)
C, K3, D, WALL = 0.05, 0.5, 0.02, 1.0


def binary() -> str:
    if os.environ.get("TRIRHYTHM"):
        return os.environ["TRIRHYTHM"]
    built = ROOT / "target" / "release" / "trirhythm"
    if built.exists():
        return str(built)
    found = shutil.which("trirhythm")
    if not found:
        raise SystemExit("no trirhythm binary: cargo build --release -p trirhythm-cli")
    return found


def run(*args: str) -> str:
    out = subprocess.run([binary(), *args], capture_output=True, text=True, check=True)
    return out.stdout


def printed_drift(mu0: float, a: np.ndarray) -> np.ndarray:
    """r' of the paper's extended van der Pol amplitude equation."""
    x = a * a
    poly = 512 - 128 * x + 64 * ALPHA * x**2 - 40 * BETA * x**3 + 28 * GAMMA * x**4 - 21 * DELTA * x**5
    return mu0 * a / 1024 * poly


def trirhythmic(tmp: pathlib.Path):
    text = TRI.read_text()
    mu0 = float(text.split("mu0 = ")[1].split()[0])
    cycles = json.loads(run("cycles", "--model", str(TRI), "--format", "json"))["cycles"]
    rows = [r.split(",") for r in run("drift", "--model", str(TRI), "--format", "csv").splitlines()]
    rows = [r for r in rows if r[0] and not r[0].startswith("#") and r[0] != "A"]
    a = np.array([float(r[0]) for r in rows])
    f = np.array([float(r[1]) for r in rows])
    scale = np.abs(printed_drift(mu0, a)).max()
    worst = np.abs(f - printed_drift(mu0, a)).max() / scale
    print("trirhythmic van der Pol (arXiv:2008.03499), mu0 =", mu0)
    print(f"  drift f(A) vs the printed amplitude equation, {len(a)} points on [0, {a[-1]:g}]: "
          f"max |difference| / max |f| = {worst:.1e}")
    pattern = "-".join("S" if c["stable"] else "U" for c in cycles)
    print(f"  cycles: {len(cycles)}, {pattern} (printed: five, S-U-S-U-S)")
    paths = []
    for start in (2.4, 8.0, 12.5):
        model = tmp / f"tri-{start}.toml"
        model.write_text(text.replace("u0 = 2.4", f"u0 = {start}"))
        out = tmp / f"tri-{start}.csv"
        run("simulate", "--model", str(model), "--t-end", "20000", "--every", "20", "--out", str(out))
        lines = [r for r in out.read_text().splitlines() if r and r[0] not in "#t"]
        data = np.array([[float(x) for x in r.split(",")[:3]] for r in lines])
        t, amp = data[:, 0], np.hypot(data[:, 1], data[:, 2])
        settled = amp[t >= 19000].mean()
        paths.append((start, t, amp, settled))
    stable = [c["amplitude"] for c in cycles if c["stable"]]
    for (start, _, _, settled), radius in zip(paths, stable):
        print(f"  U(0) = {start:4}: mean amplitude over t in [19000, 20000] {settled:.4f}, "
              f"averaged radius {radius:.4f} ({100 * (settled / radius - 1):+.2f} %)")
    return mu0, a, f, cycles, paths


def trapezoid(y: np.ndarray, x: np.ndarray) -> float:
    return float(((y[1:] + y[:-1]) * np.diff(x)).sum() / 2)


def exact_moments(k: int, n: int = 4000) -> float:
    """<U^k> of p(U) ~ exp(-(c/D)(U^2/2 + k3 U^4/4)) on [-WALL, WALL] (Simpson)."""
    u = np.linspace(-WALL, WALL, n + 1)
    w = np.exp(-(C / D) * (u**2 / 2 + K3 * u**4 / 4))
    s = np.ones(n + 1)
    s[1:-1:2], s[2:-1:2] = 4, 2
    return float((s * w * u**k).sum() / (s * w).sum())


def exact_bins(edges: np.ndarray) -> np.ndarray:
    """The exact p(U) averaged over each bin (zero beyond the walls)."""
    fine = np.linspace(-WALL, WALL, 20001)
    w = np.exp(-(C / D) * (fine**2 / 2 + K3 * fine**4 / 4))
    w /= trapezoid(w, fine)
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        m = (fine >= lo) & (fine <= hi)
        out.append(trapezoid(w[m], fine[m]) / (hi - lo) if m.sum() > 1 else 0.0)
    return np.array(out)


def two_barrier(tmp: pathlib.Path):
    print("two-barrier vibro-impact Duffing (Yang et al. 2016; chosen parameters), r = 1 and 0.8")
    runs = {}
    for r in (1.0, 0.8):
        model = tmp / f"vi-{r}.toml"
        model.write_text(VI.read_text().replace("restitution = 1.0", f"restitution = {r}"))
        doc = json.loads(run("ensemble", "--model", str(model), "--paths", "8", "--t-end", "20000",
                             "--burn-in", "200", "--amplitude-max", "3", "--format", "json"))
        joint = doc["joint"]
        ue, ve = np.array(joint["u_edges"]), np.array(joint["v_edges"])
        dens = np.array(joint["density"])
        pu = dens.sum(axis=1) * np.diff(ve)
        pv = dens.sum(axis=0) * np.diff(ue)
        runs[r] = (doc, ue, ve, pu, pv)
        vu, vv = doc["var_u"], doc["var_v"]
        line = f"  r = {r}: Var U = {vu['value']:.5f} ± {vu['stderr']:.5f}, Var U' = {vv['value']:.5f} ± {vv['stderr']:.5f}"
        if r == 1.0:
            ex_u, ex_v = exact_moments(2), D / C
            line += (f"; exact {ex_u:.5f} ({(vu['value'] - ex_u) / vu['stderr']:+.1f} s.e.), "
                     f"{ex_v:.5f} ({(vv['value'] - ex_v) / vv['stderr']:+.1f} s.e.)")
        print(line + f"; stationary: {doc['stationarity']['stationary']}")
    # the paper's second excitation: parametric noise U*eta_m beside the additive one (r = 1):
    # elastic walls balance the energy exactly, <U'^2> = (D_a + D_m <U^2>)/c
    model = tmp / "vi-parametric.toml"
    model.write_text(VI.read_text() + "\n[noise.multiplicative]\nintensity = 0.005\n")
    doc = json.loads(run("ensemble", "--model", str(model), "--paths", "8", "--t-end", "20000",
                         "--burn-in", "200", "--amplitude-max", "3", "--format", "json"))
    vu, vv = doc["var_u"], doc["var_v"]
    balance = (D + 0.005 * vu["value"]) / C
    se = math.hypot(vv["stderr"], 0.005 / C * vu["stderr"])
    print(f"  r = 1.0, parametric D_m = 0.005: Var U = {vu['value']:.5f} ± {vu['stderr']:.5f}, "
          f"Var U' = {vv['value']:.5f} ± {vv['stderr']:.5f}; energy balance (D_a + D_m Var U)/c = "
          f"{balance:.5f} ({(vv['value'] - balance) / se:+.1f} s.e.); "
          f"stationary: {doc['stationarity']['stationary']}")
    return runs


def figure(tri, runs, out: pathlib.Path) -> None:
    mu0, a, f, cycles, paths = tri
    fig, ax = plt.subplots(2, 2, figsize=(10, 7.5))
    p = ax[0, 0]
    fine = np.linspace(0, a[-1], 1000)
    p.plot(fine, printed_drift(mu0, fine) / mu0, color="0.6", lw=4, label="printed amplitude equation")
    p.plot(a, f / mu0, color="C0", lw=1.2, label="trirhythm drift")
    for c in cycles:
        p.plot(c["amplitude"], 0, "o", color="C0" if c["stable"] else "white", mec="C0")
    p.axhline(0, color="k", lw=0.5)
    p.set_ylim(-8, 8)
    p.set_xlabel("A")
    p.set_ylabel("f(A) / μ₀")
    p.set_title("(a) extended van der Pol: f(A) and its five cycles", fontsize=10)
    p.legend(fontsize=8)
    p = ax[0, 1]
    for (start, t, amp, _), c in zip(paths, ("C0", "C1", "C2")):
        # the mean over one period 2π (the samples are 0.2 apart), which averaging describes
        n = int(round(2 * math.pi / (t[1] - t[0])))
        smooth = np.convolve(amp, np.ones(n) / n, mode="valid")
        p.plot(t[n // 2 : n // 2 + len(smooth)], smooth, color=c, lw=1.2, label=f"U(0) = {start}")
    for cyc in cycles:
        p.axhline(cyc["amplitude"], color="k" if cyc["stable"] else "0.6", lw=0.6,
                  ls="-" if cyc["stable"] else "--")
    p.set_xlabel("t")
    p.set_ylabel("√(U² + U̇²), mean over 2π")
    p.set_title(f"(b) three paths (μ₀ = {mu0:g}) and the averaged radii", fontsize=10)
    p.legend(fontsize=8, loc="center right")
    p = ax[1, 0]
    _, ue, _, pu1, _ = runs[1.0]
    _, _, _, pu8, _ = runs[0.8]
    mid = 0.5 * (ue[1:] + ue[:-1])
    keep = np.abs(mid) < WALL
    inside = ue[(ue >= -WALL - 1e-12) & (ue <= WALL + 1e-12)]
    p.stairs(pu1[keep], inside, color="C0", label="ensemble, r = 1")
    p.stairs(pu8[keep], inside, color="C3", label="ensemble, r = 0.8")
    u = np.linspace(-WALL, WALL, 400)
    w = np.exp(-(C / D) * (u**2 / 2 + K3 * u**4 / 4))
    p.plot(u, w / trapezoid(w, u), color="k", lw=1, label="exact, r = 1")
    p.plot(mid[keep], exact_bins(ue)[keep], "k.", ms=4, label="exact, bin averages")
    p.set_xlabel("U")
    p.set_ylabel("p(U)")
    p.set_title("(c) two barriers at ±1: displacement", fontsize=10)
    p.legend(fontsize=8)
    p = ax[1, 1]
    _, _, ve, _, pv1 = runs[1.0]
    _, _, _, _, pv8 = runs[0.8]
    p.stairs(pv1, ve, color="C0", label="ensemble, r = 1")
    p.stairs(pv8, ve, color="C3", label="ensemble, r = 0.8")
    v = np.linspace(ve[0], ve[-1], 400)
    p.plot(v, np.exp(-v**2 * C / (2 * D)) / math.sqrt(2 * math.pi * D / C), "k", lw=1,
           label="exact, r = 1: N(0, D/c)")
    p.set_xlabel("U̇")
    p.set_ylabel("p(U̇)")
    p.set_title("(d) two barriers at ±1: velocity", fontsize=10)
    p.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"figure: {out}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(pathlib.Path(__file__).with_name("published-systems.png")))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        tri = trirhythmic(tmp)
        runs = two_barrier(tmp)
    figure(tri, runs, pathlib.Path(args.out))


if __name__ == "__main__":
    main()

"""Your own oscillator from Python (docs/own-oscillator.md, section 7): the birhythmic van der
Pol model file, its averaged theory, an ensemble with its diagnostics against it, and a sweep
over one of the file's fields.

    python examples/python/own_oscillator.py            # the guide's sizes (seconds to a minute)
    python examples/python/own_oscillator.py --quick    # seconds
"""

import argparse
import pathlib
import warnings

import trirhythm as tr

FILE = pathlib.Path(__file__).resolve().parents[1] / "models" / "birhythmic-vdp.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, for a test")
    quick = ap.parse_args().quick
    paths, t_end, burn_in = (4, 500.0, 50.0) if quick else (16, 20000.0, 500.0)

    m = tr.Model.load(str(FILE))
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        e = tr.ensemble(model=m, paths=paths, t_end=t_end, burn_in=burn_in)
    for w in said:
        print(f"warning: {w.message}")
    s = e.statistics()
    print(f"mean amplitude {s['mean_amplitude'][0]:.4f} ± {s['mean_amplitude'][1]:.4f}")
    print(f"inner well's occupancy {s['occupancy_0'][0]:.4f} ± {s['occupancy_0'][1]:.4f}")
    print(f"stationary: {e['stationarity']['stationary']}")
    theory = e["theory"]["consistent"]
    print(f"theory (consistent): occupancy {theory['occupancy'][0]:.4f}")

    ds = tr.sweep(
        "ensemble",
        {"noise.additive.intensity": [0.005, 0.01, 0.02]},
        base=m,
        paths=paths,
        t_end=t_end,
        burn_in=burn_in,
    )
    for d, occ, se in zip(ds["noise.additive.intensity"].values, ds["occupancy_0"].values, ds["occupancy_0_stderr"].values):
        print(f"D = {d:g}: inner well's occupancy {occ:.4f} ± {se:.4f}")


if __name__ == "__main__":
    main()

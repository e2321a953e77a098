"""The package as a new user meets it (issue 37): the README's install line with its extras,
the example script on Dask, what the README's commands leave in the tree, the types
(py.typed, the compiled module's stub, mypy --strict on the examples and the docs' snippets)
and the compiled functions' signatures."""

import inspect
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

import trirhythm as tr
from trirhythm import _trirhythm as native

ROOT = pathlib.Path(__file__).resolve().parents[3]
PACKAGE = pathlib.Path(tr.__file__).resolve().parent
ALL = {"dask[distributed]", "xarray", "matplotlib", "h5netcdf", "h5py", "tqdm"}


def test_the_all_extra_brings_what_the_docs_use_and_the_readme_installs_it():
    tomllib = pytest.importorskip("tomllib")
    project = tomllib.loads((ROOT / "crates/trirhythm-py/pyproject.toml").read_text())["project"]
    assert set(project["optional-dependencies"]["all"]) == ALL
    readme = (ROOT / "README.md").read_text()
    assert 'v/bin/pip install "./crates/trirhythm-py[all]"' in readme
    assert '"./crates/trirhythm-py[all]"' in (ROOT / "docs/python.md").read_text()


def test_what_the_readme_creates_is_ignored():
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    for path in ("report/index.html", "report/figures/fig01.png", "v/bin/python", "out/fig01.csv"):
        r = subprocess.run(["git", "check-ignore", "-q", path], cwd=ROOT)
        assert r.returncode == 0, f"{path} is not ignored"


def test_the_example_runs_on_dask(tmp_path):
    pytest.importorskip("distributed")
    pytest.importorskip("matplotlib")
    out = tmp_path / "plane.png"
    r = subprocess.run(
        [sys.executable, str(ROOT / "examples/python/sweep_plane.py"), "--dask", "--quick", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=240,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr[-3000:]
    assert "Nanny failed" not in r.stderr
    assert out.stat().st_size > 1000


def test_the_package_is_typed():
    assert (PACKAGE / "py.typed").exists()
    stub = (PACKAGE / "_trirhythm.pyi").read_text()
    public = [n for n in dir(native) if not n.startswith("__")]
    for name in public:
        assert re.search(rf"^(def|class) {name}\b", stub, re.M), f"{name} missing from the stub"


def test_every_compiled_function_has_a_signature():
    for name in dir(native):
        f = getattr(native, name)
        if name.startswith("__") or not callable(f):
            continue
        sig = inspect.signature(f)  # raises ValueError without a text signature
        assert sig.parameters or name in ("presets", "version", "_profile_start", "_profile_stop"), name
    assert "variant" in inspect.signature(tr.Theory).parameters
    assert "values" in inspect.signature(tr.Params).parameters


def _snippets(doc: pathlib.Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", doc.read_text(), re.S)


def test_mypy_strict_passes_on_the_examples_and_the_docs_snippets(tmp_path):
    pytest.importorskip("mypy")
    files = [str(p) for p in sorted((ROOT / "examples/python").glob("*.py"))]
    for doc in (ROOT / "docs/python.md", ROOT / "README.md"):
        for i, code in enumerate(_snippets(doc)):
            f = tmp_path / f"{doc.stem}_{i}.py"
            f.write_text(code)
            files.append(str(f))
    r = subprocess.run(
        [
            sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir", str(tmp_path / "cache"),
            # third-party calls without annotations (Dask's), and modules the docs name but the
            # test environment need not have (dask_jobqueue)
            "--untyped-calls-exclude=distributed", "--untyped-calls-exclude=dask_jobqueue",
            "--ignore-missing-imports", *files,
        ],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stdout[-5000:]

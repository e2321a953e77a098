"""The tutorial notebook runs clean (issue 37, item 7), and the Python API reference renders
from the docstrings (pdoc): both skipped where the tools are not installed (scripts/test
installs them)."""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def test_the_tour_notebook_runs_clean(monkeypatch):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    pytest.importorskip("distributed")
    pytest.importorskip("matplotlib")
    path = ROOT / "examples/python/tour.ipynb"
    nb = nbformat.read(path, as_version=4)
    # committed without outputs, so that a diff shows the code
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code")
    monkeypatch.setenv("TRIRHYTHM_QUICK", "1")
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}})
    client.execute()  # raises CellExecutionError on the first failing cell
    text = "".join(
        str(o.get("text", "")) + str((o.get("data") or {}).get("text/plain", ""))
        for c in nb.cells
        if c.cell_type == "code"
        for o in c.outputs
    )
    assert "Traceback" not in text
    assert "stationarity:" in text and "True" in text  # the diagnosis; the cluster's Dataset is the serial one


def test_the_api_reference_renders(tmp_path):
    pdoc = pytest.importorskip("pdoc")
    import trirhythm

    pdoc.pdoc("trirhythm", output_directory=tmp_path)
    page = (tmp_path / "trirhythm.html").read_text()
    for name in ("NotStationaryWarning", "Stationarity", "sweep", "branches", "Ensemble"):
        assert name in page, name
    assert os.path.exists(tmp_path / "trirhythm" / "sweep.html")
    assert trirhythm.__doc__.split("\n")[0][:40] in page

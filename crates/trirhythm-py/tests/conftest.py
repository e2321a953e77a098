"""Shared fixtures: the command-line binary built from the same tree (for bit-identity)."""

import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def cli():
    """The `trirhythm` binary: $TRIRHYTHM_BIN, else target/release/trirhythm of this tree
    (built if missing)."""
    given = os.environ.get("TRIRHYTHM_BIN")
    if given:
        return given
    binary = ROOT / "target" / "release" / "trirhythm"
    if not binary.exists():
        if shutil.which("cargo") is None:
            pytest.skip("no trirhythm binary and no cargo to build it (set TRIRHYTHM_BIN)")
        subprocess.run(["cargo", "build", "--release", "-q", "-p", "trirhythm-cli"], cwd=ROOT, check=True)
    return str(binary)


def run_cli(cli, *args):
    out = subprocess.run([cli, *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout

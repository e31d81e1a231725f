"""Shared fixtures: where the packaged FMUs and the Rust master are, and which FMUs there are.

`cargo xtask test` sets FMU_DIR and CRANE_COSIM; run by hand, the defaults point into target/.
The FMU list is the index `cargo xtask package` writes next to the archives (FMU_DIR/index.json,
one entry per FMU crate), so no test keeps a list of its own.
"""
import functools
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent


def fmu_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("FMU_DIR", ROOT / "target" / "fmu")).resolve()


@functools.lru_cache(maxsize=None)
def fmu_index() -> tuple:
    """The entries of FMU_DIR/index.json: per FMU its model_identifier, summary, archive, platforms,
    readme (relative to the repository) and reference files (options, inputs or None, results)."""
    path = fmu_dir() / "index.json"
    if not path.exists():
        pytest.fail(f"{path} is missing: run `cargo xtask package` first", pytrace=False)
    entries = json.loads(path.read_text())["fmus"]
    if not entries:
        pytest.fail(f"{path} lists no FMU", pytrace=False)
    return tuple(entries)


def fmu_names() -> list:
    """The model identifiers of every packaged FMU, in the index's order (by name)."""
    return [entry["model_identifier"] for entry in fmu_index()]


def fmu_entry(name: str) -> dict:
    """The index entry of one FMU."""
    return next(entry for entry in fmu_index() if entry["model_identifier"] == name)


def fmu_path(name: str) -> pathlib.Path:
    path = fmu_dir() / f"{name}.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: run `cargo xtask package` first")
    return path


@pytest.fixture
def master() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("CRANE_COSIM", ROOT / "target" / "release" / "crane-cosim"))
    if not path.exists():
        pytest.fail(f"{path} is missing: run `cargo build --release -p crane-cosim` first")
    return path


def physics_example(name: str, request: dict) -> dict:
    """The JSON that the physics crate's example `name` prints for the JSON `request` on its
    standard input (built in the test-release profile)."""
    out = subprocess.run(
        ["cargo", "run", "--profile", "test-release", "--quiet", "-p", "physics", "--example", name],
        cwd=ROOT, check=True, capture_output=True, text=True, input=json.dumps(request),
    )
    return json.loads(out.stdout)

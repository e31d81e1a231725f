"""Shared fixtures: where the packaged FMUs and the Rust master are.

`cargo xtask test` sets FMU_DIR and CRANE_COSIM; run by hand, the defaults point into target/.
"""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent


def fmu_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("FMU_DIR", ROOT / "target" / "fmu")).resolve()


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

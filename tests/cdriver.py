"""tests/windows/driver.c, the minimal FMI 2.0 co-simulation driver in C, and what its tests share:
the plan it runs (from the model description and the cross-check files), running it, reading its
output and the relative difference of two results. tests/windows/test_win64.py builds it for
Windows (run under Wine), tests/aarch64/test_aarch64.py for aarch64 Linux (run under QEMU), both
against the native build on the x86_64 Linux library."""
import shutil
import subprocess

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.util import read_csv

from conftest import ROOT, fmu_dir, fmu_path

DRIVER = ROOT / "tests" / "windows" / "driver.c"
FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"]
# The tolerance of the cross-platform comparisons: ≤ 1e-12·max(1, |value|).
TOLERANCE = 1e-12


def tool(name, installs):
    """The path of the program `name`; a missing one fails the test (`cargo xtask test` installs
    it, as `installs` says)."""
    path = shutil.which(name)
    if path is None:
        pytest.fail(f"{name} is missing: `cargo xtask test` installs it ({installs})")
    return path


def write_plan(name, path):
    """The driver's plan: GUID, experiment, input value references in _in.csv's column order and
    typed output value references in _ref.csv's column order. Returns the input CSV (or "-") and
    the reference results."""
    md = read_model_description(str(fmu_path(name)))
    by_name = {v.name: v for v in md.modelVariables}
    opt = dict(line.split(",", 1) for line in (fmu_dir() / f"{name}_ref.opt").read_text().splitlines() if line)
    opt = {key.strip(): float(value) for key, value in opt.items()}
    ref = read_csv(fmu_dir() / f"{name}_ref.csv")
    inputs_csv = fmu_dir() / f"{name}_in.csv"
    inputs = read_csv(inputs_csv).dtype.names[1:] if inputs_csv.exists() else ()
    letter = {"Real": "r", "Integer": "i", "Boolean": "b"}
    outputs = [f"{letter[by_name[n].type]}{by_name[n].valueReference}" for n in ref.dtype.names[1:]]
    path.write_text(f"guid {md.guid}\n"
                    f"experiment {opt['StartTime']!r} {opt['StopTime']!r} {opt['StepSize']!r}\n"
                    f"inputs {' '.join(str(by_name[n].valueReference) for n in inputs)}\n"
                    f"outputs {' '.join(outputs)}\n")
    return (str(inputs_csv) if inputs else "-"), ref


def run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, f"{command}: {done.stderr}"


def load(path):
    return np.loadtxt(path, delimiter=",", ndmin=2)


def as_array(ref):
    """The reference results (a structured array from read_csv) as a float matrix, time first."""
    return np.column_stack([ref[n].astype(float) for n in ref.dtype.names])


def worst_difference(a, b):
    """The largest |a - b| / max(1, |b|) over all rows and columns."""
    assert a.shape == b.shape, (a.shape, b.shape)
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))

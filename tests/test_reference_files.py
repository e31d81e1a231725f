"""The fmi-cross-check files next to each FMU (`<model>_in.csv`, `_ref.csv`, `_ref.opt`, written by
`cargo xtask package` with the Rust master) let any importer check itself. FMPy is such an
importer: reading nothing but those files and running the FMU with its default start values, it
must reproduce the reference (max abs difference ≤ 1e-9·max(1, |ref|); in practice 0)."""
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.util import read_csv

from conftest import fmu_dir, fmu_entry, fmu_names, fmu_path

MODELS = fmu_names()


def read_opt(path):
    """The `Key, value` lines of a cross-check options file as floats."""
    pairs = (line.split(",", 1) for line in path.read_text().splitlines() if line.strip())
    return {key.strip(): float(value) for key, value in pairs}


def reference_files(name):
    """(options, inputs or None, reference) of one FMU, the files its index entry names; a missing
    file fails the test."""
    folder, files = fmu_dir(), fmu_entry(name)["reference"]
    for file in (files["options"], files["results"], files["inputs"]):
        if file is not None and not (folder / file).exists():
            pytest.fail(f"{folder / file} is missing: run `cargo xtask package` first")
    return (read_opt(folder / files["options"]),
            read_csv(folder / files["inputs"]) if files["inputs"] is not None else None,
            read_csv(folder / files["results"]))


def variables(name, causality):
    md = read_model_description(str(fmu_path(name)))
    return [v.name for v in md.modelVariables if v.causality == causality]


@pytest.mark.parametrize("name", MODELS)
def test_fmpy_reproduces_the_reference_files(name):
    opt, inputs, ref = reference_files(name)
    outputs = list(ref.dtype.names[1:])
    # Every output is recorded, and every input has a column (held at its start when not driven).
    assert outputs == variables(name, "output")
    assert (list(inputs.dtype.names[1:]) if inputs is not None else []) == variables(name, "input")
    result = simulate_fmu(str(fmu_path(name)), start_time=opt["StartTime"], stop_time=opt["StopTime"],
                          output_interval=opt["StepSize"], relative_tolerance=opt["RelTol"],
                          input=inputs, output=outputs)
    assert len(result) == len(ref), (len(result), len(ref))
    assert np.max(np.abs(result["time"] - ref["time"])) < 1e-12
    worst = max(float(np.max(np.abs(result[n].astype(float) - ref[n]) / np.maximum(1.0, np.abs(ref[n]))))
                for n in outputs)
    columns = 0 if inputs is None else len(inputs.dtype.names) - 1
    print(f"{name}: FMPy vs {name}_ref.csv, {len(ref)} rows, {columns} inputs, {len(outputs)} outputs: "
          f"max relative difference {worst:.3e}")
    assert worst <= 1e-9

"""FMUs from other exporters run in crane-cosim and in FMPy on the same grid and must agree.

* `container.fmu`, made here by FMPy's container FMU exporter around the packaged pendulum: FMPy's
  Co-Simulation-only binary, which reads its configuration and the nested FMU from its resources
  folder and forwards inputs, parameters and outputs to the pendulum.
* `Schedule.fmu`, built here with PythonFMU (PyPI `pythonfmu`) from third_party/schedule.py: a
  Co-Simulation-only FMU without Model Exchange symbols, with Real, Integer, Boolean and String
  variables, that reads a CSV file from its resources folder.
* `stair.fmu`, compiled here with gcc from third_party/stair.c against FMPy's FMI 2.0 headers: a
  Co-Simulation-only FMU that ends its run with fmi2Discard and fmi2Terminated = true (FMPy then
  stops normally), or, with `terminate = false`, discards without terminating (an error).
"""
import csv
import ctypes
import json
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig
import zipfile

import fmpy
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.container_fmu import Configuration
from fmpy.container_fmu.cli import create_container_fmu
from fmpy.container_fmu.config import Component
from fmpy.model_description import CoSimulation, ModelDescription, ModelVariable, Unknown

from conftest import fmu_path

THIRD_PARTY = pathlib.Path(__file__).resolve().parent / "third_party"
SCHEDULE = THIRD_PARTY / "schedule.csv"


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """Builds the three FMUs once: {"schedule": path, "stair": path, "container": path}."""
    out = tmp_path_factory.mktemp("third_party")
    subprocess.run(
        [sys.executable, "-m", "pythonfmu", "build", "-f", str(THIRD_PARTY / "schedule.py"), str(SCHEDULE),
         "-d", str(out)],
        check=True, capture_output=True,
    )
    return {"schedule": out / "Schedule.fmu", "stair": build_stair(out), "container": build_container(out)}


# The container's variables: (name, causality, the pendulum variable it forwards to).
CONTAINER_VARIABLES = [
    ("theta_x0", "parameter", "theta_x0"),
    ("tip_x", "input", "tip.x"),
    ("tip_vx", "input", "tip.vx"),
    ("tip_ax", "input", "tip.ax"),
    ("theta_x", "output", "theta_x"),
    ("theta_y", "output", "theta_y"),
    ("tension", "output", "tension"),
]


def build_container(out, pendulum=None, fmi_version="2.0", name="container"):
    """FMPy's container FMU around the packaged pendulum (FMI 2.0 by default, or `pendulum`),
    forwarding CONTAINER_VARIABLES; the container is an FMI `fmi_version` FMU ("2.0" or "3.0")."""
    pendulum = pendulum or fmu_path("pendulum")
    nested = read_model_description(str(pendulum))
    targets = {v.name: v for v in nested.modelVariables}
    component = Component(name="pendulum", filename=pendulum, modelDescription=nested)
    real = "Float64" if fmi_version.startswith("3.") else "Real"
    model = ModelDescription(
        fmiVersion=fmi_version, modelName=name, instantiationToken="{5f0e8a4c-7d0b-4c1e-9a57-3c2b1d0e9f11}",
        coSimulation=CoSimulation(modelIdentifier="container_fmu", canHandleVariableCommunicationStepSize=True,
                                  fixedInternalStepSize=0.01),
    )
    # create_container_fmu numbers the variables from 0 in order, but the container binary reads
    # value reference k as its k-th forwarded variable counting from 1 (with the first forwarded
    # variable at 0, every output returned the variable before it): a time variable takes 0.
    model.modelVariables.append(ModelVariable(name="time", type=real, causality="independent",
                                              variability="continuous"))
    mappings = {}
    for variable_name, causality, target in CONTAINER_VARIABLES:
        fixed = causality == "parameter"
        variable = ModelVariable(name=variable_name, type=real, causality=causality,
                                 variability="fixed" if fixed else "continuous", initial="exact" if fixed else None,
                                 start={"parameter": "-0.3", "input": "0.0"}.get(causality))
        model.modelVariables.append(variable)
        mappings[variable] = [(component, targets[target])]
    model.outputs = [Unknown(index=i + 1, variable=v) for i, v in enumerate(model.modelVariables)
                     if v.causality == "output"]
    model.initialUnknowns = list(model.outputs)  # the outputs are calculated in Initialization Mode too
    configuration = Configuration(parallelDoStep=False, modelDescription=model, components=[component],
                                  connections=[], variableMappings=mappings)
    fmu, unpacked = out / f"{name}.fmu", out / name
    unpacked.mkdir()  # create_container_fmu empties it, then builds the archive in it
    create_container_fmu(configuration, unpacked, fmu)
    return fmu


def build_stair(out):
    return compile_fmu(out, "stair", "fmi2Functions.h", "linux64")


def compile_fmu(out, identifier, header, platform):
    """out/<identifier>.fmu: third_party/<identifier>.c compiled with gcc against FMPy's copy of
    the FMI `header`, with third_party/<identifier>.xml as its model description, the library
    in binaries/<platform>/."""
    headers = pathlib.Path(fmpy.__file__).parent / "c-code"
    assert (headers / header).exists(), f"FMPy has no {header}"
    library = out / f"{identifier}.so"
    compiler = shutil.which("gcc") or shutil.which("cc")
    subprocess.run(
        [compiler, "-shared", "-fPIC", "-O2", "-std=c99", "-Wall", "-Werror", f"-I{headers}",
         "-o", str(library), str(THIRD_PARTY / f"{identifier}.c"), "-lm"],
        check=True,
    )
    fmu = out / f"{identifier}.fmu"
    with zipfile.ZipFile(fmu, "w") as archive:
        archive.write(THIRD_PARTY / f"{identifier}.xml", "modelDescription.xml")
        archive.write(library, f"binaries/{platform}/{identifier}.so")
    return fmu


def python_library():
    """The shared Python library of this interpreter, by path or by soname.

    A PythonFMU binary does not link it: the process hosting the FMU must provide Python's
    symbols, as the Python process running FMPy does. crane-cosim is not a Python process, so it
    gets the library preloaded (`cargo xtask test` installs it where the interpreter lacks it).
    """
    soname = sysconfig.get_config_var("INSTSONAME")
    path = pathlib.Path(sysconfig.get_config_var("LIBDIR")) / soname
    return str(path) if path.exists() else soname


def run_master(master, tmp_path, fmu, start, stop, step, record, inputs=None, python=False):
    """Runs one instance "x" of `fmu` in crane-cosim (with Python's library preloaded for a
    PythonFMU); returns (process, CSV rows as dicts, summary)."""
    system = {
        "fmus": {"m": str(fmu)},
        "instances": [{"name": "x", "fmu": "m", "start": start}],
        "start_time": 0.0, "stop_time": stop, "step_size": step,
        "record": {"variables": [f"x.{name}" for name in record]},
    }
    if inputs is not None:
        (tmp_path / "inputs.csv").write_text(inputs)
        system["inputs"] = [{"instance": "x", "file": "inputs.csv"}]
    (tmp_path / "system.json").write_text(json.dumps(system))
    out, summary = tmp_path / "out.csv", tmp_path / "summary.json"
    process = subprocess.run(
        [str(master), "run", str(tmp_path / "system.json"), "--output", str(out), "--summary", str(summary)],
        capture_output=True, text=True, env={**os.environ, "LD_PRELOAD": python_library()} if python else None,
    )
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    return process, rows, json.loads(summary.read_text())


def exported_functions(fmu, tmp_path, identifier, platform="linux64"):
    with zipfile.ZipFile(fmu) as archive:
        library = archive.extract(f"binaries/{platform}/{identifier}.so", tmp_path / "extracted")
    return ctypes.CDLL(library)


def label_at(time):
    """The schedule's label active at `time` (the last row whose time is reached)."""
    with open(SCHEDULE, newline="") as f:
        rows = list(csv.DictReader(f))
    return [row["label"] for row in rows if float(row["time"]) <= time + 1e-9][-1]


def test_pythonfmu_schedule_matches_fmpy_bit_for_bit(master, fmus, tmp_path):
    fmu = fmus["schedule"]
    model = read_model_description(str(fmu))
    assert model.coSimulation is not None and model.modelExchange is None
    library = exported_functions(fmu, tmp_path, model.coSimulation.modelIdentifier)
    assert hasattr(library, "fmi2DoStep") and not hasattr(library, "fmi2EnterEventMode")

    step, stop = 0.1, 1.0
    times = np.arange(11) * step
    ramp = 0.1 + 0.25 * times
    inputs = "time,u\n" + "".join(f"{float(t)!r},{float(u)!r}\n" for t, u in zip(times, ramp))
    outputs = ["y", "phase", "lifting", "label"]
    process, rows, summary = run_master(master, tmp_path, fmu, {"gain": 3.0}, stop, step, outputs, inputs, python=True)
    assert process.returncode == 0, process.stderr
    assert summary["status"] == "completed" and summary["steps_completed"] == 10

    signal = np.array(list(zip(times, ramp)), dtype=[("time", float), ("u", float)])
    reference = simulate_fmu(
        str(fmu), start_time=0.0, stop_time=stop, step_size=step, output_interval=step,
        start_values={"gain": 3.0}, input=signal, output=outputs[:3],
    )
    assert len(rows) == len(reference) == 11
    for row, expected in zip(rows, reference):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        assert float(row["x.y"]) == expected["y"]
        assert int(row["x.phase"]) == expected["phase"]
        assert row["x.lifting"] == ("1" if expected["lifting"] else "0")
    # FMPy does not record strings: the labels are checked against the resource file itself
    # (one has a comma and one has quotes, so the CSV quoting is checked too).
    assert [row["x.label"] for row in rows[1:]] == [label_at(float(row["time"])) for row in rows[1:]]
    assert {"lift \"high\"", "lower, slowly"} <= {row["x.label"] for row in rows}


def test_stair_ends_the_run_with_discard_and_terminated_like_fmpy(master, fmus, tmp_path):
    fmu = fmus["stair"]
    assert not hasattr(exported_functions(fmu, tmp_path, "stair"), "fmi2EnterEventMode")
    step, stop = 0.2, 4.0
    process, rows, summary = run_master(master, tmp_path, fmu, {"end_time": 2.5}, stop, step, ["level", "counter"])
    assert process.returncode == 0, process.stderr
    assert 'terminated by instance "x" at t = 2.5 s' in process.stdout
    assert summary["status"] == "terminated" and summary["error"] is None
    assert summary["termination"] == {"instance": "x", "time": 2.5}
    # The last row is the last communication point every instance completed: t = 12 · 0.2.
    assert summary["steps_completed"] == 12 and summary["end_time"] == pytest.approx(2.4, abs=1e-12)
    assert len(rows) == 13 and float(rows[-1]["time"]) == pytest.approx(2.4, abs=1e-12)

    reference = simulate_fmu(
        str(fmu), start_time=0.0, stop_time=stop, step_size=step, output_interval=step,
        start_values={"end_time": 2.5}, output=["level", "counter"],
    )
    # FMPy also ends at the discard, adding a row at fmi2LastSuccessfulTime.
    assert reference["time"][-1] == summary["termination"]["time"]
    common = reference[:-1]
    assert len(common) == len(rows)
    for row, expected in zip(rows, common):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        assert float(row["x.level"]) == expected["level"]
        assert int(row["x.counter"]) == expected["counter"]
    assert rows[-1]["x.counter"] == "4"


def test_stair_ending_the_run_at_a_step_end_keeps_that_row_like_fmpy(master, fmus, tmp_path):
    """end_time on a communication point: the FMU computes the step 2.2 → 2.4 whole and then asks
    to end the run. FMPy, fmusim and the FMU Compliance Checker keep the row of t = 2.4."""
    step, stop = 0.2, 4.0
    start = {"end_time": 2.4}
    process, rows, summary = run_master(master, tmp_path, fmus["stair"], start, stop, step, ["level", "counter"])
    assert process.returncode == 0, process.stderr
    assert summary["status"] == "terminated" and summary["termination"]["time"] == pytest.approx(2.4, abs=1e-12)
    assert summary["steps_completed"] == 12 and summary["end_time"] == pytest.approx(2.4, abs=1e-12)
    reference = simulate_fmu(
        str(fmus["stair"]), start_time=0.0, stop_time=stop, step_size=step, output_interval=step,
        start_values=start, output=["level", "counter"],
    )
    assert len(rows) == len(reference) == 13
    for row, expected in zip(rows, reference):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        assert float(row["x.level"]) == expected["level"] and int(row["x.counter"]) == expected["counter"]
    assert rows[-1]["x.counter"] == "4"


def without_default_experiment(fmu, tmp_path):
    """A copy of `fmu` whose model description has no DefaultExperiment."""
    bare = tmp_path / "bare.fmu"
    with zipfile.ZipFile(fmu) as source, zipfile.ZipFile(bare, "w") as target:
        for entry in source.infolist():
            data = source.read(entry)
            if entry.filename == "modelDescription.xml":
                text = data.decode()
                start = text.index("<DefaultExperiment")
                text = text[:start] + text[text.index("/>", start) + 2:]
                data = text.encode()
            target.writestr(entry, data)
    return bare


def test_a_lone_fmu_without_a_default_experiment_runs_with_fmpys_defaults(master, fmus, tmp_path):
    """No stop time and no step size anywhere: 1 s after the start at FMPy's auto_interval, said on
    stderr, and the rows are FMPy's own; `info` says the default run is not given."""
    bare = without_default_experiment(fmus["stair"], tmp_path)
    info = subprocess.run([str(master), "info", str(bare)], capture_output=True, text=True)
    assert info.returncode == 0 and "default run    not given" in info.stdout, info.stdout
    for extra, stop, step in [([], 1.0, 0.002), (["--stop-time", "3"], 3.0, 0.005)]:
        out = tmp_path / "bare.csv"
        process = subprocess.run([str(master), "run", str(bare), "-o", str(out), "--start", "end_time=10", *extra],
                                 capture_output=True, text=True)
        assert process.returncode == 0, process.stderr
        assert f"stepping {step} s" in process.stderr, process.stderr
        assert ("gives no stop time: running to 1 s" in process.stderr) == (not extra), process.stderr
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
        reference = simulate_fmu(str(bare), stop_time=None if not extra else stop, start_values={"end_time": 10.0},
                                 output=["counter"])
        assert len(rows) == len(reference) == round(stop / step) + 1
        for row, expected in zip(rows, reference):
            assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
            assert int(row["bare.counter"]) == expected["counter"]


def test_stair_discarding_without_terminating_is_an_error_naming_it(master, fmus, tmp_path):
    start = {"end_time": 2.5, "terminate": False}
    process, rows, summary = run_master(master, tmp_path, fmus["stair"], start, 4.0, 0.2, ["level", "counter"])
    assert process.returncode != 0
    assert 'instance "x" discarded the step from t = 2.4 s (step 12 of 20) without asking to end ' \
        "the simulation (fmi2Terminated is false)" in process.stderr
    assert "the FMU logged: end_time reached" in process.stderr
    assert summary["status"] == "failed" and "termination" not in summary
    assert len(rows) == 13


def tip_motion(times):
    """5 cm · sin(2 t) along x: position, velocity, acceleration."""
    return 0.05 * np.sin(2 * times), 0.1 * np.cos(2 * times), -0.2 * np.sin(2 * times)


def container_on_tip_motion(master, tmp_path, fmu, outputs, step, stop):
    """Runs the container `fmu` (a pendulum inside, theta_x0 = -0.2) for 200 steps of `step` on
    the tip motion in crane-cosim and in FMPy, and checks that both give the same rows: the tip's
    (x, vx, ax), the input CSV and crane-cosim's rows."""
    times = np.arange(201) * step
    x, vx, ax = tip_motion(times)
    inputs = "time,tip_x,tip_vx,tip_ax\n" + "".join(
        f"{float(t)!r},{float(a)!r},{float(b)!r},{float(c)!r}\n" for t, a, b, c in zip(times, x, vx, ax))
    process, rows, _ = run_master(master, tmp_path, fmu, {"theta_x0": -0.2}, stop, step, outputs, inputs)
    assert process.returncode == 0, process.stderr

    signal = np.array(list(zip(times, x, vx, ax)), dtype=[(n, float) for n in ("time", "tip_x", "tip_vx", "tip_ax")])
    reference = simulate_fmu(
        str(fmu), start_time=0.0, stop_time=stop, step_size=step, output_interval=step,
        start_values={"theta_x0": -0.2}, input=signal, output=outputs,
    )
    assert len(rows) == len(reference) == 201
    for row, expected in zip(rows, reference):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        assert [float(row[f"x.{n}"]) for n in outputs] == [expected[n] for n in outputs]
    assert min(float(row["x.theta_x"]) for row in rows) < -0.19, "the pendulum swings"
    return (x, vx, ax), inputs, rows


def bare_pendulum_difference(master, tmp_path, pendulum, inputs, rows, outputs, step, stop):
    """The largest difference between the container's `rows` and those of the bare `pendulum`
    FMU in crane-cosim on the same `inputs` (the container's column names as the pendulum's)."""
    bare = tmp_path / "bare"
    bare.mkdir()
    inputs = inputs.replace("tip_x,tip_vx,tip_ax", "tip.x,tip.vx,tip.ax")
    process, bare_rows, _ = run_master(master, bare, pendulum, {"theta_x0": -0.2}, stop, step, outputs, inputs)
    assert process.returncode == 0, process.stderr
    assert [row["time"] for row in bare_rows] == [row["time"] for row in rows]
    return max(abs(float(a[f"x.{n}"]) - float(b[f"x.{n}"])) for a, b in zip(rows, bare_rows) for n in outputs)


def test_fmpy_container_matches_fmpy_and_the_bare_pendulum_bit_for_bit(master, fmus, tmp_path):
    fmu = fmus["container"]
    assert read_model_description(str(fmu)).modelExchange is None
    assert not hasattr(exported_functions(fmu, tmp_path, "container_fmu"), "fmi2EnterEventMode")
    step, stop = 0.01, 2.0
    outputs = ["theta_x", "theta_y", "tension"]
    _, inputs, rows = container_on_tip_motion(master, tmp_path, fmu, outputs, step, stop)

    # The same run on the pendulum itself: the container only forwards values; the results
    # differ in the last digit at most.
    difference = bare_pendulum_difference(master, tmp_path, fmu_path("pendulum"), inputs, rows, outputs, step, stop)
    print(f"container vs bare pendulum: max |difference| = {difference:.3g}")
    assert difference <= 1e-12

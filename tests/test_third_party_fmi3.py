"""FMI 3.0 FMUs from other exporters run in crane-cosim and in FMPy on the same grid and must agree.

* `stair3.fmu`, compiled here with gcc from third_party/stair3.c against FMPy's FMI 3.0 headers: a
  Co-Simulation-only FMU exporting every function of fmi3Functions.h, with Float64, Int32, Boolean
  and String variables (set with `--start`, recorded, and compared with FMPy's values, the strings
  read by a recorder that extends FMPy's), the FMI 3.0 counterpart of stair.fmu
  (test_third_party.py). It ends its run by returning fmi3OK with terminateSimulation = true from
  the step that reaches `end_time`, computed whole (it may not return early): crane-cosim keeps
  that step's row and ends the run as "terminated" there, and FMPy stops after the same step, with
  the same rows bit for bit. Told so by its String parameter `ending`, it instead returns early
  (earlyReturn = true, lastSuccessfulTime = end_time) or asks for event handling
  (eventHandlingNeeded = true) although crane-cosim instantiated it without early return and
  without Event Mode, or (`terminate` false) returns fmi3Discard: crane-cosim ends the run as
  failed, keeps the rows before, and says why. FMPy refuses the early return and the discard too,
  but ignores the event request and runs on.
* FMPy 0.3.32's container FMU in FMI 3.0 mode around the packaged FMI 3.0 pendulum
  (target/fmu/fmi3/pendulum.fmu): `create_container_fmu` writes an FMI 3.0 description and puts
  FMPy's binary in binaries/x86_64-linux/ when the container's description is FMI 3.0 (in
  binaries/linux64/ for FMI 2.0); that one binary exports both the fmi2 and the fmi3 functions, and
  its configuration names each component's FMI major version ("2" or "3"), so an FMI 3.0 container
  may hold FMI 3.0 or FMI 2.0 FMUs and an FMI 2.0 container FMI 3.0 ones. All three run here, in
  crane-cosim and FMPy bit for bit alike. The container steps its component by its
  fixedInternalStepSize (h = 0.01 every step, the time accumulated): the bare pendulum stepped so
  gives the container's values bit for bit; the bare pendulum in crane-cosim, stepped by
  t_{k+1} - t_k, differs in the last digit at most.
* FMI 3.0 FMUs with a Binary or a String array variable, made here from stair3: crane-cosim
  refuses them naming the variable (FMPy validates them: they are valid FMUs crane-cosim cannot
  convert).
"""
import csv
import json
import pathlib
import re
import shutil
import subprocess
import zipfile

import fmpy
import fmpy.simulation
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import fmu_path
from test_fmi3 import fmi3_path
from test_third_party import (CONTAINER_VARIABLES, bare_pendulum_difference, build_container, compile_fmu,
                              container_on_tip_motion, exported_functions, run_master)

STAIR3 = "stair3"
X86_64_LINUX = "x86_64-linux"
# The containers: name -> (the container's FMI version, the pendulum archive's FMI major version).
CONTAINERS = {"container3": ("3.0", 3), "container3_of_fmi2": ("3.0", 2), "container2_of_fmi3": ("2.0", 3)}


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """Builds the FMUs once: {"stair3": path, "container3": path, ...}."""
    out = tmp_path_factory.mktemp("third_party_fmi3")
    built = {STAIR3: compile_fmu(out, STAIR3, "fmi3Functions.h", X86_64_LINUX)}
    for name, (version, pendulum) in CONTAINERS.items():
        nested = fmi3_path("pendulum") if pendulum == 3 else fmu_path("pendulum")
        built[name] = build_container(out, nested, fmi_version=version, name=name)
    return built


def header_functions():
    """The function names fmi3Functions.h declares (FMI3_Export fmi3…TYPE fmi3…;)."""
    header = pathlib.Path(fmpy.__file__).parent / "c-code" / "fmi3Functions.h"
    return re.findall(r"^FMI3_Export\s+\w+TYPE\s+(\w+);", header.read_text(), re.MULTILINE)


def cli_value(value):
    """A --start value as crane-cosim reads it: JSON for numbers and booleans, else the text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        try:
            json.loads(value)
        except ValueError:
            return value
        raise AssertionError(f"{value!r} would be read as JSON, not as a string")
    return repr(value)


def run_alone(master, tmp_path, fmu, start, record):
    """`crane-cosim run FMU --start NAME=VALUE… --record NAME…`; returns (process, rows, summary)."""
    out, summary = tmp_path / "out.csv", tmp_path / "summary.json"
    args = [str(master), "run", str(fmu), "--output", str(out), "--summary", str(summary)]
    for name, value in start.items():
        args += ["--start", f"{name}={cli_value(value)}"]
    for name in record:
        args += ["--record", name]
    process = subprocess.run(args, capture_output=True, text=True)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    return process, rows, json.loads(summary.read_text())


class StringRecorder(fmpy.simulation.Recorder):
    """FMPy's recorder, also reading the String outputs at every sample (FMPy's own leaves them out)."""

    def __init__(self, fmu, modelDescription, variableNames=None, interval=None):
        super().__init__(fmu, modelDescription, variableNames, interval)
        self.string_outputs = [v for v in modelDescription.modelVariables
                               if v.type == "String" and v.causality == "output"]
        self.strings = []
        StringRecorder.last = self

    def sample(self, time, force=False):
        super().sample(time, force)
        values = self.fmu.getString([v.valueReference for v in self.string_outputs])
        self.strings.append(dict(zip((v.name for v in self.string_outputs), values)))


def simulate_with_strings(monkeypatch, fmu, **options):
    """FMPy's simulate_fmu, and the String outputs of each recorded row."""
    monkeypatch.setattr(fmpy.simulation, "Recorder", StringRecorder)
    result = simulate_fmu(str(fmu), **options)
    return result, StringRecorder.last.strings


OUTPUTS = ["level", "counter", "reached"]


def assert_rows_equal(rows, reference, strings):
    """crane-cosim's rows equal FMPy's bit for bit: Float64, Int32, Boolean and String outputs."""
    assert len(rows) == len(reference) == len(strings)
    for row, expected, text in zip(rows, reference, strings):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        assert float(row["stair3.level"]) == expected["level"]
        assert int(row["stair3.counter"]) == expected["counter"]
        assert row["stair3.reached"] == ("1" if expected["reached"] else "0")
        assert row["stair3.phase"] == text["phase"]


def test_stair3_is_a_valid_cosimulation_only_fmu_exporting_every_fmi3_function(fmus, tmp_path):
    fmu = fmus[STAIR3]
    assert validate_fmu(str(fmu)) == []
    model = read_model_description(str(fmu))
    assert model.fmiVersion == "3.0" and model.coSimulation is not None and model.modelExchange is None
    assert {v.type for v in model.modelVariables} == {"Float64", "Int32", "Boolean", "String"}
    library = exported_functions(fmu, tmp_path, STAIR3, X86_64_LINUX)
    functions = header_functions()
    assert len(functions) > 70 and "fmi3DoStep" in functions and "fmi3InstantiateModelExchange" in functions
    assert [name for name in functions if not hasattr(library, name)] == []
    assert not hasattr(library, "fmi2DoStep")
    print(f"stair3.fmu: FMPy validates it; it exports all {len(functions)} functions of fmi3Functions.h")


@pytest.mark.parametrize("end_time, last", [(2.5, 2.6), (2.4, 2.4)])
def test_stair3_ends_the_run_with_terminate_simulation_like_fmpy(master, fmus, tmp_path, monkeypatch, end_time, last):
    """terminateSimulation comes with a step computed whole (no early return: the FMU reached the
    step's end): crane-cosim keeps that step's row and ends there, "terminated", as FMPy does.
    end_time = 2.5 s lies inside the step 2.4 → 2.6, 2.4 s on a communication point."""
    fmu = fmus[STAIR3]
    start = {"end_time": end_time, "height": 0.3, "terminate": True, "ending": "terminate"}
    process, rows, summary = run_alone(master, tmp_path, fmu, start, OUTPUTS + ["phase"])
    assert process.returncode == 0, process.stderr
    assert f'terminated by instance "stair3" at t = {last} s' in process.stdout, process.stdout
    assert "fmi3DoStep set terminateSimulation" in process.stderr, process.stderr
    assert summary["status"] == "terminated" and summary["error"] is None
    assert summary["termination"]["instance"] == "stair3"
    assert summary["termination"]["time"] == pytest.approx(last, abs=1e-12)
    steps = round(last / 0.2)
    assert summary["steps_completed"] == steps and summary["end_time"] == pytest.approx(last, abs=1e-12)

    reference, strings = simulate_with_strings(
        monkeypatch, fmu, start_time=0.0, stop_time=4.0, step_size=0.2, output_interval=0.2, start_values=start,
        output=OUTPUTS,
    )
    # FMPy stops after the same step.
    assert reference["time"][-1] == pytest.approx(last, abs=1e-12)
    assert len(rows) == steps + 1
    assert_rows_equal(rows, reference, strings)
    assert [row["stair3.phase"] for row in rows] == ["climbing"] * steps + ["terminate"]
    assert rows[-1]["stair3.reached"] == "1" and rows[-2]["stair3.reached"] == "0"
    counter = int(last / 0.5 + 1e-9)  # the half seconds reached
    assert int(rows[-1]["stair3.counter"]) == counter and float(rows[-1]["stair3.level"]) == counter * 0.3
    print(f"stair3 end_time = {end_time}: {len(rows)} rows, crane-cosim = FMPy bit for bit, terminated at {last} s")


# How stair3 ends the step reaching end_time = 2.5 s, and what crane-cosim says of it.
MISBEHAVIOURS = {
    "early return": ({"ending": "early return"},
                     "fmi3DoStep returned early (earlyReturn), which this importer did not allow "
                     "(t = 2.4000000000000004, lastSuccessfulTime = 2.5)"),
    "event": ({"ending": "event"},
              "fmi3DoStep set eventHandlingNeeded, but the instance was created without Event Mode "
              "(t = 2.4000000000000004, lastSuccessfulTime = 2.6)"),
    # stair3 writes terminateSimulation = true with its fmi3Discard, where FMI 3.0 leaves it undefined.
    "discard": ({"terminate": False},
                "fmi3DoStep returned fmi3Discard with terminateSimulation set; FMI 3.0 leaves the output arguments "
                "undefined then, so the request to end the simulation is not taken (t = 2.4000000000000004)"),
}


@pytest.mark.parametrize("case", MISBEHAVIOURS)
def test_stair3_returning_early_asking_for_events_or_discarding_ends_the_run_saying_why(
        master, fmus, tmp_path, monkeypatch, case):
    fmu = fmus[STAIR3]
    start, why = MISBEHAVIOURS[case]
    process, rows, summary = run_alone(master, tmp_path, fmu, start, OUTPUTS + ["phase"])
    assert process.returncode == 1, process.stderr
    assert "panicked" not in process.stderr
    assert 'error: instance "stair3" discarded the step from t = 2.4 s (step 12 of 20)' in process.stderr
    assert why in process.stderr, process.stderr
    assert summary["status"] == "failed" and why in summary["error"] and "termination" not in summary
    assert summary["steps_completed"] == 12 and len(rows) == 13

    # The rows kept are FMPy's up to the last communication point before end_time.
    options = dict(start_time=0.0, step_size=0.2, output_interval=0.2, start_values=start, output=OUTPUTS)
    reference, strings = simulate_with_strings(monkeypatch, fmu, stop_time=2.4, **options)
    assert_rows_equal(rows, reference, strings)
    assert [row["stair3.phase"] for row in rows] == ["climbing"] * 13
    if case == "event":
        # FMPy, without Event Mode, leaves eventHandlingNeeded aside and runs on.
        reference = simulate_fmu(str(fmu), stop_time=4.0, **options)
        assert list(reference["reached"]) == [False] * 13 + [True] * 8
    else:
        expected = "Early Return is not allowed" if case == "early return" else "fmi3DoStep failed with status 2"
        with pytest.raises(Exception, match=expected):
            simulate_fmu(str(fmu), stop_time=4.0, **options)
    print(f"stair3 {case}: crane-cosim failed at t = 2.4 s saying: {why}")


@pytest.mark.parametrize("name", CONTAINERS)
def test_fmpy_fmi3_container_matches_fmpy_and_the_bare_pendulum_bit_for_bit(master, fmus, tmp_path, name):
    version, pendulum = CONTAINERS[name]
    fmu = fmus[name]
    model = read_model_description(str(fmu))
    assert model.fmiVersion == version and model.modelExchange is None
    assert validate_fmu(str(fmu)) == []
    platform = X86_64_LINUX if version == "3.0" else "linux64"
    library = exported_functions(fmu, tmp_path, "container_fmu", platform)
    assert hasattr(library, "fmi3DoStep") and hasattr(library, "fmi2DoStep")
    with zipfile.ZipFile(fmu) as archive:
        configuration = json.loads(archive.read("resources/container.json"))
    assert [c["fmiMajorVersion"] for c in configuration["components"]] == [str(pendulum)]

    step, stop = 0.01, 2.0
    outputs = [n for n, causality, _ in CONTAINER_VARIABLES if causality == "output"]
    (x, vx, ax), inputs, rows = container_on_tip_motion(master, tmp_path, fmu, outputs, step, stop)

    # The container only forwards values, and steps the pendulum by its fixedInternalStepSize
    # (h = 0.01 every step): the bare pendulum stepped so gives its values bit for bit.
    nested = fmi3_path("pendulum") if pendulum == 3 else fmu_path("pendulum")
    fixed = pendulum_in_fixed_steps(nested, -0.2, (x, vx, ax), step, outputs)
    assert [[float(row[f"x.{n}"]) for n in outputs] for row in rows] == fixed

    # The same run on the bare FMI 3.0 pendulum in crane-cosim, which steps by t_{k+1} - t_k (off
    # 0.01 by an ulp at times): the results differ in the last digit at most.
    difference = bare_pendulum_difference(master, tmp_path, fmi3_path("pendulum"), inputs, rows, outputs, step, stop)
    print(f"{name} (FMI {version} container, FMI {pendulum}.0 pendulum): crane-cosim = FMPy = the bare pendulum in "
          f"fixed steps bit for bit over {len(rows)} rows; vs the bare FMI 3.0 pendulum in crane-cosim: "
          f"max |difference| = {difference:.3g}")
    assert difference <= 1e-12


def pendulum_in_fixed_steps(fmu, theta_x0, tip, step, outputs):
    """The pendulum `fmu` (FMI 2.0 or 3.0) through FMPy's API, stepped as FMPy's container steps
    its components: h = `step` every step, the time accumulated. `tip` holds the tip's x, vx and
    ax at each communication point; returns each point's `outputs`."""
    model = read_model_description(str(fmu))
    references = {v.name: v.valueReference for v in model.modelVariables}
    unpacked = fmpy.extract(str(fmu))
    instance = fmpy.instantiate_fmu(unpacked, model, "CoSimulation")
    fmi3 = model.fmiVersion.startswith("3.")
    get, set_ = (instance.getFloat64, instance.setFloat64) if fmi3 else (instance.getReal, instance.setReal)
    inputs = [references[n] for n in ("tip.x", "tip.vx", "tip.ax")]
    unknowns = [references[n] for n in outputs]
    set_([references["theta_x0"]], [theta_x0])
    if fmi3:
        instance.enterInitializationMode(startTime=0.0, stopTime=None)
    else:
        instance.setupExperiment(startTime=0.0)
        instance.enterInitializationMode()
    set_(inputs, [float(values[0]) for values in tip])
    instance.exitInitializationMode()
    results, time = [get(unknowns)], 0.0
    for k in range(len(tip[0]) - 1):
        set_(inputs, [float(values[k]) for values in tip])
        instance.doStep(currentCommunicationPoint=time, communicationStepSize=step)
        time += step
        results.append(get(unknowns))
    instance.terminate()
    instance.freeInstance()
    shutil.rmtree(unpacked, ignore_errors=True)
    return [list(map(float, values)) for values in results]


# Variables no FMI 2.0-style row can carry (crane-cosim converts the other FMI 3.0 types and
# arrays, tests/test_third_party_fmi3_types.py), each added to stair3's description.
UNCONVERTED = {
    "binary": ('<Binary name="blob" valueReference="9" causality="output" variability="discrete" '
               'initial="calculated"/>',
               '<Output valueReference="9"/>',
               'variable "blob" is an FMI 3.0 Binary, which this importer cannot exchange'),
    "string-array": ('<String name="words" valueReference="9" causality="parameter" variability="fixed">'
                     '<Dimension start="2"/><Start value="a"/><Start value="b"/></String>', None,
                     'variable "words" is a String array, which this importer cannot exchange'),
}


def with_variable(fmu, identifier, copy, variable, output=None):
    """Writes to ``copy`` the FMI 3.0 ``fmu`` (its x86_64-linux library only) with ``variable``
    added to its description and, for an output, its ``<Output …/>`` element ``output`` listed
    among the outputs and initial unknowns; returns ``copy``."""
    with zipfile.ZipFile(fmu) as source:
        description = source.read("modelDescription.xml").decode()
        library = source.read(f"binaries/{X86_64_LINUX}/{identifier}.so")
    description = description.replace("  </ModelVariables>", f"    {variable}\n  </ModelVariables>")
    if output:
        # An output is listed among the outputs (before the first InitialUnknown) and the initial unknowns.
        description = description.replace("    <InitialUnknown", f"    {output}\n    <InitialUnknown", 1)
        initial = output.replace("<Output", "<InitialUnknown")
        description = description.replace("  </ModelStructure>", f"    {initial}\n  </ModelStructure>")
    with zipfile.ZipFile(copy, "w") as archive:
        archive.writestr("modelDescription.xml", description)
        archive.writestr(f"binaries/{X86_64_LINUX}/{identifier}.so", library)
    return copy


def assert_refused(master, fmu, tmp_path, expected):
    """Asserts that ``fmu`` is a valid FMI 3.0 FMU that ``info`` and ``run`` both refuse, without a
    panic, with a message containing ``expected``; returns the standard error of ``run``."""
    assert validate_fmu(str(fmu)) == [], "a valid FMI 3.0 FMU"
    for command in (["info", str(fmu)], ["run", str(fmu), "--output", str(tmp_path / "out.csv")]):
        process = subprocess.run([str(master), *command], capture_output=True, text=True)
        assert process.returncode == 1, process.stdout + process.stderr
        assert expected in process.stderr and "panicked" not in process.stderr, process.stderr
    return process.stderr


@pytest.mark.parametrize("case", UNCONVERTED)
def test_fmi3_variables_no_row_can_carry_are_refused_naming_the_variable(master, fmus, tmp_path, case):
    variable, output, message = UNCONVERTED[case]
    fmu = with_variable(fmus[STAIR3], STAIR3, tmp_path / f"{case}.fmu", variable, output)
    stderr = assert_refused(master, fmu, tmp_path, message)
    print(f"{case}: {stderr.strip()}")

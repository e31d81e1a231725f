"""The FMI 3.0 archives (`target/fmu/fmi3/<model>.fmu`): built from the same variable tables and the
same binaries as the FMI 2.0 ones, they validate in FMPy, declare the same variables, and FMPy's
simulate_fmu gives the FMI 2.0 archive's results bit for bit on every reference case."""
import json
import pathlib
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.util import read_csv
from fmpy.validation import validate_fmu

from conftest import ROOT, fmu_dir, fmu_entry, fmu_names, fmu_path
from test_reference_files import reference_files

NAMES = fmu_names()
# The independent variable every FMI 3.0 description declares (fmus/export/src/fmi3/xml.rs).
TIME_VR = 2**31 - 1


def fmi3_path(name):
    path = fmu_dir() / fmu_entry(name)["fmi3_archive"]
    if not path.exists():
        pytest.fail(f"{path} is missing: run `cargo xtask package` first")
    return path


@pytest.mark.parametrize("name", NAMES)
def test_fmpy_validate_is_clean(name):
    problems = validate_fmu(str(fmi3_path(name)))
    assert problems == [], problems
    md = read_model_description(str(fmi3_path(name)))
    assert md.fmiVersion == "3.0" and md.coSimulation is not None and md.modelExchange is None
    print(f"fmpy validate fmi3/{name}.fmu: no problems")


@pytest.mark.parametrize("name", NAMES)
def test_the_archive_carries_the_fmi2_binaries_under_fmi3_platform_tuples(name):
    archive = zipfile.ZipFile(fmi3_path(name))
    binaries = sorted(n for n in archive.namelist() if n.startswith("binaries/"))
    suffix = {"x86_64-linux": "so", "x86_64-windows": "dll", "aarch64-linux": "so"}
    platforms = fmu_entry(name)["fmi3_platforms"]
    assert "x86_64-linux" in platforms
    assert binaries == sorted(f"binaries/{p}/{name}.{suffix[p]}" for p in platforms), binaries
    fmi2 = zipfile.ZipFile(fmu_path(name))
    assert archive.read(f"binaries/x86_64-linux/{name}.so") == fmi2.read(f"binaries/linux64/{name}.so"), \
        "one library exports both APIs"
    page = archive.read("documentation/index.html").decode()
    assert "3.0 (Co-Simulation)" in page and "Instantiation token" in page


def fmi2_variables(name):
    """(name, value reference, type, causality, variability, unit, start) of the FMI 2.0 XML."""
    root = ET.fromstring(zipfile.ZipFile(fmu_path(name)).read("modelDescription.xml"))
    types = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean", "String": "String"}
    rows = []
    for v in root.find("ModelVariables"):
        typed = next(iter(v))
        rows.append((v.get("name"), int(v.get("valueReference")), types[typed.tag], v.get("causality"),
                     v.get("variability"), typed.get("unit"), typed.get("start")))
    return rows


def fmi3_variables(name):
    root = ET.fromstring(zipfile.ZipFile(fmi3_path(name)).read("modelDescription.xml"))
    rows = []
    for v in root.find("ModelVariables"):
        start = v.get("start")
        if v.tag == "String" and v.find("Start") is not None:
            start = v.find("Start").get("value")
        rows.append((v.get("name"), int(v.get("valueReference")), v.tag, v.get("causality"),
                     v.get("variability"), v.get("unit"), start))
    return rows


@pytest.mark.parametrize("name", NAMES)
def test_the_variables_are_those_of_the_fmi2_description_plus_time(name):
    """The names map 1:1 (every vector stays scalars), with the same value references, causality,
    variability, unit and start; FMI 3.0 adds only the independent variable `time`."""
    fmi3 = fmi3_variables(name)
    assert fmi3[0] == ("time", TIME_VR, "Float64", "independent", "continuous", None, None)
    assert fmi3[1:] == fmi2_variables(name)
    references = [r for _, r, *_ in fmi3]
    assert len(set(references)) == len(references), "FMI 3.0 value references are unique"
    print(f"fmi3/{name}.fmu: {len(fmi3) - 1} variables as in FMI 2.0, plus time")


@pytest.mark.parametrize("name", NAMES)
def test_fmpy_runs_the_fmi3_archive_to_the_fmi2_results_bit_for_bit(name):
    """Each FMU on its reference case (the fmi-cross-check files next to the archives): FMPy's
    simulate_fmu on the FMI 3.0 archive and on the FMI 2.0 archive, compared bit for bit."""
    opt, inputs, ref = reference_files(name)
    outputs = list(ref.dtype.names[1:])
    kwargs = dict(start_time=opt["StartTime"], stop_time=opt["StopTime"], output_interval=opt["StepSize"],
                  relative_tolerance=opt["RelTol"], input=inputs, output=outputs)
    fmi3 = simulate_fmu(str(fmi3_path(name)), **kwargs)
    fmi2 = simulate_fmu(str(fmu_path(name)), **kwargs)
    assert len(fmi3) == len(fmi2) == len(ref)
    for column in ["time"] + outputs:
        a, b = np.ascontiguousarray(fmi3[column]), np.ascontiguousarray(fmi2[column])
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), f"{name}.{column} differs"
    print(f"{name}: FMI 3.0 = FMI 2.0 bit for bit, {len(ref)} rows x {len(outputs)} outputs")


@pytest.mark.parametrize("name", NAMES)
def test_the_fmi3_archives_have_their_cross_check_files(name):
    """fmi3/<model>_ref.csv etc., the cross-check files next to the FMI 3.0 archive, are the FMI 2.0
    ones: FMPy reproduces those from the FMI 2.0 archive (test_reference_files.py) and the FMI 3.0
    archive gives the same bits (above)."""
    files = fmu_entry(name)["reference"]
    folder = fmu_dir() / "fmi3"
    for file in (files["options"], files["results"], files["inputs"]):
        if file is not None:
            assert (folder / file).read_bytes() == (fmu_dir() / file).read_bytes(), file


# The closed loop through crane-cosim, with its FMUs taken from the FMI 3.0 archives (all, or every
# other one: a system mixing both versions), against the same loop of FMI 2.0 archives.
LOOP_STOP = 20.0
LOOP_START = {"pendulum.theta_x0": -0.4, "pendulum.release_time": 2.0, "controller.mode": 2,
              "controller.feedback": 1, "controller.active_from": 2.0, "platform.profile": 1}


def loop_system(tmp_path, fmi3_models, input_derivatives):
    """systems/closed_loop.json with the archives of `fmi3_models` replaced by their FMI 3.0
    archives, written to tmp_path (archive paths made absolute)."""
    system = json.loads((ROOT / "systems" / "closed_loop.json").read_text())
    for name, path in system["fmus"].items():
        model = pathlib.Path(path).stem
        folder = fmu_dir() / "fmi3" if model in fmi3_models else fmu_dir()
        system["fmus"][name] = str(folder / f"{model}.fmu")
    system["input_derivatives"] = input_derivatives
    system["stop_time"] = LOOP_STOP
    path = tmp_path / f"loop_{len(fmi3_models)}_{input_derivatives}.json"
    path.write_text(json.dumps(system))
    return path


def run_loop(master, tmp_path, fmi3_models, input_derivatives=False):
    path = loop_system(tmp_path, fmi3_models, input_derivatives)
    out = path.with_suffix(".csv")
    starts = [arg for key, value in LOOP_START.items() for arg in ("--start", f"{key}={value}")]
    subprocess.run([str(master), "run", str(path), "-o", str(out), "-q", *starts], check=True)
    return read_csv(str(out))


LOOP_MODELS = ("platform", "crane", "pendulum", "imu", "controller")


@pytest.mark.parametrize("fmi3_models", [LOOP_MODELS, LOOP_MODELS[1::2]], ids=["all-fmi3", "mixed"])
def test_the_closed_loop_of_fmi3_fmus_is_the_fmi2_loop_bit_for_bit(master, tmp_path, fmi3_models):
    """Without input derivatives (interpolation the same in both versions) the loop of FMI 3.0
    FMUs, and a loop mixing FMI 2.0 and 3.0 FMUs, give the FMI 2.0 loop's results bit for bit."""
    (tmp_path / "2").mkdir()
    fmi2 = run_loop(master, tmp_path / "2", ())
    fmi3 = run_loop(master, tmp_path, fmi3_models)
    assert fmi3.dtype.names == fmi2.dtype.names and len(fmi3) == len(fmi2) == int(LOOP_STOP / 0.01) + 1
    for column in fmi2.dtype.names:
        assert np.ascontiguousarray(fmi3[column]).tobytes() == np.ascontiguousarray(fmi2[column]).tobytes(), column
    print(f"closed loop, {', '.join(fmi3_models)} as FMI 3.0: {len(fmi2)} rows x {len(fmi2.dtype.names) - 1} "
          "columns equal to the FMI 2.0 loop bit for bit")


def test_fmi3_fmus_hold_their_inputs_where_the_fmi2_loop_interpolates(master, tmp_path):
    """The shipped loop passes the pendulum the tip's slopes (input_derivatives, FMI 2.0's
    fmi2SetRealInputDerivatives). FMI 3.0 has no input derivatives, so with the same system file
    the FMI 3.0 loop holds the inputs over each step: it gives exactly the FMI 2.0 loop without
    input derivatives. How far that is from the interpolated FMI 2.0 loop is the effect of the
    interpolation itself (measured and printed; the compensated loop's deadbands and quantisers
    turn a small change of the tip's path within a step into a visible one later)."""
    for folder in ("interpolated", "held"):
        (tmp_path / folder).mkdir()
    interpolated = run_loop(master, tmp_path / "interpolated", (), input_derivatives=True)
    held = run_loop(master, tmp_path / "held", (), input_derivatives=False)
    fmi3 = run_loop(master, tmp_path, LOOP_MODELS, input_derivatives=True)
    for column in held.dtype.names:
        assert np.ascontiguousarray(fmi3[column]).tobytes() == np.ascontiguousarray(held[column]).tobytes(), column
    worst = {c: float(np.max(np.abs(fmi3[c] - interpolated[c]))) for c in ("pendulum.theta_x", "pendulum.theta_y")}
    print(f"closed loop, profile 1, {LOOP_STOP:g} s: FMI 3.0 (held inputs) = FMI 2.0 without input derivatives "
          f"bit for bit; vs FMI 2.0 with them, max |difference| {worst} rad")
    assert max(worst.values()) > 0, "input derivatives changed nothing: the comparison would show nothing"


def test_an_ssp_archive_of_the_mixed_loop_runs_as_the_system_file_does(master, tmp_path):
    """`export --ssp` packs a system mixing FMI 2.0 and 3.0 archives; running the SSP gives the
    system file's results bit for bit."""
    system = loop_system(tmp_path, LOOP_MODELS[1::2], False)
    ssp = tmp_path / "mixed.ssp"
    subprocess.run([str(master), "export", str(system), "--ssp", str(ssp)], check=True, capture_output=True)
    with zipfile.ZipFile(ssp) as archive:
        packed = archive.read("SystemStructure.ssd").decode()
        versions = {zipfile.ZipFile(archive.open(n)).read("modelDescription.xml").decode().split('fmiVersion="')[1][:3]
                    for n in archive.namelist() if n.endswith(".fmu")}
    assert versions == {"2.0", "3.0"}, (versions, packed[:200])
    starts = [arg for key, value in LOOP_START.items() for arg in ("--start", f"{key}={value}")]
    for path in (system, ssp):
        subprocess.run([str(master), "run", str(path), "-o", str(path.with_suffix(".out.csv")), "-q", *starts],
                       check=True)
    direct, packed = (read_csv(str(p.with_suffix(".out.csv"))) for p in (system, ssp))
    assert direct.dtype.names == packed.dtype.names
    for column in direct.dtype.names:
        assert np.ascontiguousarray(direct[column]).tobytes() == np.ascontiguousarray(packed[column]).tobytes(), column
    print(f"mixed FMI 2.0 / 3.0 loop as SSP: {len(packed)} rows equal to the system file's run")

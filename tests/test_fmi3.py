"""The FMI 3.0 archives (`target/fmu/fmi3/<model>.fmu`): built from the same variable tables and the
same binaries as the FMI 2.0 ones, they validate in FMPy, declare the same variables, and FMPy's
simulate_fmu gives the FMI 2.0 archive's results bit for bit on every reference case."""
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import fmu_dir, fmu_entry, fmu_names, fmu_path
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

"""Every packaged FMU validates in FMPy and follows the model-description rules of SPEC §2."""
import xml.etree.ElementTree as ET
import zipfile

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from conftest import fmu_dir, fmu_path

# Every FMU the project builds. Listed rather than globbed, so that a missing FMU fails its
# checks (fmu_path fails) instead of dropping out of the parametrization; anything else found
# in the directory is checked too.
REQUIRED = ["controller", "crane", "imu", "pendulum", "platform"]
NAMES = sorted(set(REQUIRED) | {p.stem for p in fmu_dir().glob("*.fmu")})


def test_fmus_are_packaged():
    names = {p.stem for p in fmu_dir().glob("*.fmu")}
    assert set(REQUIRED) <= names, f"missing from {fmu_dir()}: {sorted(set(REQUIRED) - names)}"


@pytest.fixture(params=NAMES)
def path(request):
    return fmu_path(request.param)


def test_fmpy_validate_is_clean(path):
    problems = validate_fmu(str(path))
    assert problems == [], problems
    print(f"fmpy validate {path.name}: no problems")


def test_archive_layout(path):
    md = read_model_description(str(path))
    ident = md.coSimulation.modelIdentifier
    names = zipfile.ZipFile(path).namelist()
    assert "modelDescription.xml" in names
    assert f"binaries/linux64/{ident}.so" in names
    assert "documentation/index.html" in names
    assert md.modelExchange is None
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate
    assert md.coSimulation.canHandleVariableCommunicationStepSize


def test_variable_attribute_rules(path):
    """Checked on the raw XML: FMPy fills in defaults (e.g. initial) that the file must not carry."""
    root = ET.fromstring(zipfile.ZipFile(path).read("modelDescription.xml"))
    units = {u.get("name") for u in root.iter("Unit")}
    variables = root.find("ModelVariables").findall("ScalarVariable")
    outputs = []
    for i, v in enumerate(variables, start=1):
        typed = next(iter(v))
        name, causality, initial, start = v.get("name"), v.get("causality"), v.get("initial"), typed.get("start")
        if causality == "input":
            assert start is not None and initial is None, name
        elif causality == "output":
            assert initial == "calculated" and start is None, name
            outputs.append(i)
        elif causality == "parameter":
            assert v.get("variability") in ("fixed", "tunable") and initial == "exact" and start is not None, name
        if typed.get("unit") is not None:
            assert typed.get("unit") in units, f"{name}: unit {typed.get('unit')} not declared"
    structure = root.find("ModelStructure")
    assert [int(u.get("index")) for u in structure.find("Outputs")] == outputs
    assert [int(u.get("index")) for u in structure.find("InitialUnknowns")] == outputs
    vrs = [(next(iter(v)).tag, v.get("valueReference")) for v in variables]
    assert len(vrs) == len(set(vrs)), "duplicate value references"

"""Every packaged FMU validates in FMPy and follows the model-description rules of SPEC §2."""
import xml.etree.ElementTree as ET
import zipfile

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from conftest import ROOT, fmu_dir, fmu_entry, fmu_index, fmu_names, fmu_path

# Every FMU the project builds, from the index rather than globbed, so that a missing archive
# fails its checks (fmu_path fails) instead of dropping out of the parametrization.
NAMES = fmu_names()


def test_the_index_lists_every_archive_with_its_reference_files_and_readme():
    """index.json (one entry per FMU crate, written by `cargo xtask package`) and the folder agree:
    the same archives, each with its fmi-cross-check files and the README it documents."""
    archives = sorted(p.stem for p in fmu_dir().glob("*.fmu"))
    assert archives == sorted(NAMES), f"archives in {fmu_dir()}: {archives}, index.json: {NAMES}"
    for entry in fmu_index():
        name, reference = entry["model_identifier"], entry["reference"]
        assert entry["archive"] == f"{name}.fmu" and "linux64" in entry["platforms"], entry
        assert reference["options"] == f"{name}_ref.opt" and reference["results"] == f"{name}_ref.csv", entry
        for file in (reference["options"], reference["results"]):
            assert (fmu_dir() / file).is_file(), f"{name}: {file} is missing"
        # An input table exists exactly when the index names one (the FMU has inputs).
        inputs = fmu_dir() / f"{name}_in.csv"
        assert inputs.is_file() == (reference["inputs"] == inputs.name), (name, reference["inputs"])
        assert (ROOT / entry["readme"]).is_file(), f"{name}: {entry['readme']} is missing"
    print(f"index.json: {len(NAMES)} FMUs ({', '.join(NAMES)}), each archived with reference files and README")


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
    # The archive carries the binaries the index says it does, and no others.
    suffix = {"linux64": "so", "aarch64-linux": "so", "win64": "dll"}
    binaries = sorted(n for n in names if n.startswith("binaries/"))
    assert binaries == sorted(f"binaries/{p}/{ident}.{suffix[p]}" for p in fmu_entry(ident)["platforms"]), binaries
    assert "documentation/index.html" in names
    assert md.modelExchange is None
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate
    assert md.coSimulation.canHandleVariableCommunicationStepSize


def test_variable_attribute_rules(path):
    """Checked on the raw XML: FMPy fills in defaults (e.g. initial) that the file must not carry."""
    root = ET.fromstring(zipfile.ZipFile(path).read("modelDescription.xml"))
    units = {u.get("name") for u in root.iter("Unit")}
    variables = root.find("ModelVariables").findall("ScalarVariable")
    outputs, calculated = [], []
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
        elif causality == "calculatedParameter":
            assert v.get("variability") in ("fixed", "tunable") and initial in (None, "calculated") and start is None, name
            calculated.append(i)
        if typed.get("unit") is not None:
            assert typed.get("unit") in units, f"{name}: unit {typed.get('unit')} not declared"
    structure = root.find("ModelStructure")
    assert [int(u.get("index")) for u in structure.find("Outputs")] == outputs
    # FMI 2.0 §2.2.8: the initial unknowns are the outputs and the calculated parameters, by index.
    assert [int(u.get("index")) for u in structure.find("InitialUnknowns")] == sorted(outputs + calculated)
    vrs = [(next(iter(v)).tag, v.get("valueReference")) for v in variables]
    assert len(vrs) == len(set(vrs)), "duplicate value references"

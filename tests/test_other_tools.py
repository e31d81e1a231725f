"""The closed loop in other tools: `crane-cosim export` writes the compensated demo scenario as an
SSP 1.0 archive and as an OSP system structure; libcosim (through libcosimpy, a Jacobi master)
runs both like `crane-cosim run --algorithm jacobi` and logs no warning or error for our FMUs;
FMPy reads the archive and validates it against the SSP 1.0 schema.
"""
import csv
import json
import re
import subprocess
import sys
import zipfile

import pytest
from fmpy.ssp.ssd import read_ssd

from conftest import ROOT

SCENARIO = ROOT / "scenarios" / "demo_still_compensated.json"
# The load is released and compensation starts at 10 s: 10 s of both.
STOP = 20.0
LOAD = ["pendulum.load.x", "pendulum.load.y", "pendulum.load.z"]
# libcosim and crane-cosim's Jacobi do the same arithmetic; only how each forms the communication
# times may differ, in the last bits.
TOLERANCE = 1e-9
# libcosim logs to standard output, lines like "[date] [thread] [warning] message".
PROBLEM = re.compile(r"\[(warning|error|fatal)\]")


def run(*args):
    result = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    assert result.returncode == 0, f"{args} failed:\n{result.stderr}"
    return result


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in row] for row in rows[1:]]


@pytest.fixture
def exported(master, tmp_path):
    """The scenario exported to tmp_path (still.ssp, osp/) and run by crane-cosim with Jacobi."""
    run(master, "export", SCENARIO, "--stop-time", STOP, "--ssp", tmp_path / "still.ssp", "--osp", tmp_path / "osp")
    run(master, "run", SCENARIO, "--stop-time", STOP, "--algorithm", "jacobi", "-o", tmp_path / "jacobi.csv", "-q")
    return tmp_path


def libcosim(structure, header, tmp_path, name):
    """Runs `structure` to STOP in libcosim, logging from info on; its results (steps 1..n, the
    variables of `header`) and its log lines."""
    system = tmp_path / f"{name}.json"
    system.write_text(json.dumps({"stop_time": STOP, "step_size": 0.01, "record": {"variables": header[1:]}}))
    results = tmp_path / f"{name}.csv"
    script = ROOT / "bench" / "libcosim_master.py"
    result = run(sys.executable, script, "--log-level", "info", structure, system, results)
    # The script's own last line reports its wall time.
    log = result.stdout.splitlines()[:-1] + result.stderr.splitlines()
    return read_csv(results), log


@pytest.mark.parametrize("structure", ["still.ssp", "osp/OspSystemStructure.xml"])
def test_libcosim_runs_the_export_like_crane_cosim_jacobi_without_warnings(exported, structure):
    header, jacobi = read_csv(exported / "jacobi.csv")
    (libcosim_header, rows), log = libcosim(exported / structure, header, exported, "libcosim")

    # The log was captured (FMI Library reports loading each binary) and holds no problem.
    assert any("[info]" in line for line in log), log
    assert [line for line in log if PROBLEM.search(line)] == []
    assert libcosim_header == header
    # libcosim's samples start after t0.
    assert len(rows) == len(jacobi) - 1 == round(STOP / 0.01)
    columns = [header.index(name) for name in LOAD]
    time_difference = max(abs(a[0] - b[0]) for a, b in zip(rows, jacobi[1:]))
    difference = max(abs(a[c] - b[c]) for a, b in zip(rows, jacobi[1:]) for c in columns)
    print(f"\n{structure}: libcosim vs crane-cosim Jacobi, load position max |difference| {difference:.3g} m")
    assert time_difference <= 1e-9
    assert difference <= TOLERANCE
    # The load moved (10 s of compensated swing), so agreement is not trivial.
    assert max(abs(row[columns[1]]) for row in jacobi) > 0.1


def test_the_log_check_sees_libcosims_warnings(exported):
    """A start value for an output is ignored by libcosim with a warning, which the check finds."""
    archive = exported / "still.ssp"
    bad = exported / "bad.ssp"
    with zipfile.ZipFile(archive) as source, zipfile.ZipFile(bad, "w") as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "SystemStructure.ssd":
                binding = '<ssv:Parameter name="release_time">'
                bad_value = '<ssv:Parameter name="theta_x"><ssv:Real value="0.1"/></ssv:Parameter>'
                data = data.decode().replace(binding, bad_value + binding, 1).encode()
            target.writestr(item, data)
    header, _ = read_csv(exported / "jacobi.csv")
    _, log = libcosim(bad, header, exported, "bad")
    problems = [line for line in log if PROBLEM.search(line)]
    # (libcosim applies the set twice: by its name and as the default set.)
    assert problems and all("Non-input causality for variable pendulum:theta_x" in line for line in problems), log


def test_fmpy_reads_the_archive_and_it_validates_against_the_ssp_schema(exported):
    # validate=True checks SystemStructure.ssd against the SSP 1.0 XML schemas shipped with FMPy.
    ssd = read_ssd(str(exported / "still.ssp"), validate=True)
    components = ssd.system.elements
    assert [c.name for c in components] == ["platform", "crane", "pendulum", "imu1", "imu2", "controller"]
    assert [c.source for c in components][:3] == ["resources/platform.fmu", "resources/crane.fmu", "resources/pendulum.fmu"]
    assert len(ssd.system.connections) == 88
    pendulum = components[2].parameterBindings[0].parameterValues[0].parameters
    values = {p.name: (p.type, p.value) for p in pendulum}
    assert values["theta_x0"] == ("Real", "-0.40142572795869574")
    assert values["release_time"] == ("Real", "10.0")

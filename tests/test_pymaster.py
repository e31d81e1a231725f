"""The Python master over FMPy (tests/pymaster.py) and the Rust master run the same system file
and must agree (SPEC §7)."""
import json
import subprocess

import numpy as np
import pytest

import signals
from conftest import fmu_path
from pymaster import PyMaster

H = 0.01
STOP = 10.0


def pendulum_and_imu_system(tmp_path, algorithm):
    """The load IMU riding on a pendulum whose tip follows a recorded trajectory."""
    times = np.arange(0, int(round(STOP / H)) + 1) * H
    table = signals.table(times)
    csv = tmp_path / "tip.csv"
    with open(csv, "w") as f:
        f.write(",".join(table.dtype.names) + "\n")
        for row in table:
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    wires = [("load.q0", "q0"), ("load.q1", "q1"), ("load.q2", "q2"), ("load.q3", "q3"),
             ("load.wx", "w.x"), ("load.wy", "w.y"), ("load.wz", "w.z"),
             ("load.ax", "a.x"), ("load.ay", "a.y"), ("load.az", "a.z")]
    system = {
        "fmus": {"pendulum": str(fmu_path("pendulum")), "imu": str(fmu_path("imu"))},
        "instances": [
            {"name": "load", "fmu": "pendulum", "start": {"theta_x0": -0.2, "theta_y0": 0.1}},
            {"name": "imu2", "fmu": "imu", "start": {"seed": 2}},
        ],
        "connections": [{"from": f"load.{a}", "to": f"imu2.{b}"} for a, b in wires],
        "inputs": [{"instance": "load", "file": csv.name}],
        "start_time": 0.0, "stop_time": STOP, "step_size": H,
        "input_derivatives": True,
        "algorithm": algorithm,
    }
    path = tmp_path / "system.json"
    path.write_text(json.dumps(system))
    return path


@pytest.mark.parametrize("algorithm", ["gauss-seidel", "jacobi"])
def test_python_master_reproduces_the_rust_master(master, tmp_path, algorithm):
    path = pendulum_and_imu_system(tmp_path, algorithm)
    out = tmp_path / "rust.csv"
    subprocess.run([str(master), "run", str(path), "--output", str(out), "-q"], check=True)
    rust = np.genfromtxt(out, delimiter=",", names=True, deletechars="")
    python = PyMaster(path).run()
    assert rust.dtype.names == python.dtype.names
    assert len(rust) == len(python) == int(round(STOP / H)) + 1
    diff = max(float(np.max(np.abs(rust[n] - python[n]))) for n in rust.dtype.names)
    print(f"pendulum -> imu ({algorithm}), {STOP:g} s: Rust master vs Python FMPy master max abs difference {diff:.3e}")
    assert diff <= 1e-9
    # The IMU rode the swinging load: its gyro sees the swing rate (~0.2 rad at ~3.7 rad/s).
    assert np.std(python["imu2.gyro.x"]) > 0.2


def test_python_master_reproduces_the_closed_loop_with_noise(master, tmp_path):
    """The whole closed loop (six instances, sensor feedback, seeded noise on), 15 s."""
    import pathlib
    root = pathlib.Path(__file__).resolve().parent.parent
    scenario = json.loads((root / "scenarios" / "demo_profile1_compensated.json").read_text())
    scenario["system"] = str(root / "systems" / "closed_loop.json")
    scenario["stop_time"] = 15.0
    system = json.loads((root / "systems" / "closed_loop.json").read_text())
    system["fmus"] = {alias: str(fmu_path(pathlib.Path(p).stem)) for alias, p in system["fmus"].items()}
    for instance in system["instances"]:
        for key, value in scenario["start"].items():
            name, _, variable = key.partition(".")
            if name == instance["name"]:
                instance["start"][variable] = value
    system["stop_time"] = scenario["stop_time"]
    path = tmp_path / "closed_loop.json"
    path.write_text(json.dumps(system))
    out = tmp_path / "rust.csv"
    subprocess.run([str(master), "run", str(path), "--output", str(out), "-q"], check=True)
    rust = np.genfromtxt(out, delimiter=",", names=True, deletechars="")
    python = PyMaster(path).run()
    load = ["pendulum.load.x", "pendulum.load.y", "pendulum.load.z"]
    diff = max(float(np.max(np.abs(rust[n] - python[n]))) for n in load)
    print(f"closed loop with noise, profile 1, compensated, 15 s: Rust vs Python master, load position max abs difference {diff:.3e} m")
    assert diff <= 1e-9
    # The loop did something: the swing after release is being damped.
    assert np.max(np.abs(python["pendulum.theta_x"][python["time"] > 12])) < 0.4

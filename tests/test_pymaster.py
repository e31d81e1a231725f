"""The Python master over FMPy (tests/pymaster.py) and the Rust master run the same system file
and must agree (SPEC §7)."""
import json
import pathlib
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
    assert_gyro_rides_the_load(python, lag=1 if algorithm == "jacobi" else 0)


def assert_gyro_rides_the_load(result, lag):
    """The IMU rode the swinging load: each gyro axis is the load's angular rate about that axis
    plus noise (σ ≈ 3.5 mrad/s), `lag` steps late (Jacobi gathers every input before anything
    steps, Gauss-Seidel steps the pendulum first). The swing is real (~0.2 rad at ~3.7 rad/s): a
    wrong lag leaves 22 mrad/s on x, swapped x and y wires 0.86 rad/s. A std bound on the gyro
    alone would pass either."""
    assert np.std(result["load.load.wx"]) > 0.5
    n = len(result) - lag
    for axis in "xyz":
        error = result[f"imu2.gyro.{axis}"][lag:] - result[f"load.load.w{axis}"][:n]
        rms = float(np.sqrt(np.mean(error**2)))
        print(f"  gyro.{axis} vs load.w{axis} {lag} step(s) earlier: rms {rms * 1e3:.2f} mrad/s")
        assert rms < 0.005, axis


ROOT = pathlib.Path(__file__).resolve().parent.parent
RELEASE = 10.0


def closed_loop_system(tmp_path, scenario_name, stop):
    """systems/closed_loop.json with a scenario's start values, the packaged FMUs and `stop`."""
    scenario = json.loads((ROOT / "scenarios" / scenario_name).read_text())
    system = json.loads((ROOT / "systems" / "closed_loop.json").read_text())
    system["fmus"] = {alias: str(fmu_path(pathlib.Path(p).stem)) for alias, p in system["fmus"].items()}
    for instance in system["instances"]:
        for key, value in scenario["start"].items():
            name, _, variable = key.partition(".")
            if name == instance["name"]:
                instance["start"][variable] = value
    assert scenario["start"]["pendulum.release_time"] == RELEASE
    system["stop_time"] = stop
    path = tmp_path / scenario_name
    path.write_text(json.dumps(system))
    return path


def run_rust(master, path):
    out = path.with_suffix(".csv")
    subprocess.run([str(master), "run", str(path), "--output", str(out), "-q"], check=True)
    return np.genfromtxt(out, delimiter=",", names=True, deletechars="")


def swing_amplitude(result, start, end):
    """Largest |theta_x| in [start, end): the released swing (the ship rolls the load little)."""
    t = result["time"]
    return float(np.max(np.abs(result["pendulum.theta_x"][(t >= start) & (t < end)])))


def test_python_master_reproduces_the_closed_loop_with_noise(master, tmp_path):
    """The whole closed loop (six instances, sensor feedback, seeded noise on), 15 s."""
    stop = 15.0
    path = closed_loop_system(tmp_path, "demo_profile1_compensated.json", stop)
    rust = run_rust(master, path)
    python = PyMaster(path).run()
    load = ["pendulum.load.x", "pendulum.load.y", "pendulum.load.z"]
    diff = max(float(np.max(np.abs(rust[n] - python[n]))) for n in load)
    print(f"closed loop with noise, profile 1, compensated, {stop:g} s: Rust vs Python master, load position max abs difference {diff:.3e} m")
    assert diff <= 1e-9
    assert_compensation_damps_the_swing(python, run_rust(master, closed_loop_system(tmp_path, "demo_profile1_off.json", stop)))


def assert_compensation_damps_the_swing(compensated, off):
    """The loop did something: 4-5 s after release the compensated swing is about half the swing
    with the crane off, which only the air damps (τ = 73 s: 0.40 rad -> 0.38 rad)."""
    released = swing_amplitude(off, RELEASE, RELEASE + 0.5)
    late = RELEASE + 4.0, RELEASE + 5.0
    with_crane, without = swing_amplitude(compensated, *late), swing_amplitude(off, *late)
    print(f"|theta_x| {late[0]:g}-{late[1]:g} s: compensated {with_crane:.3f} rad, crane off {without:.3f} rad (released at {released:.3f} rad)")
    assert without > 0.9 * released, "crane off, the swing barely decays"
    assert with_crane < 0.7 * without

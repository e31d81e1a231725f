"""The Rust master and FMPy drive the pendulum FMU with the same recorded inputs and must agree
(SPEC §7: max abs difference ≤ 1e-9)."""
import json
import subprocess

import numpy as np
from fmpy import simulate_fmu
from fmpy.util import read_csv

import signals
from conftest import fmu_path
from rig import Rig

H = 0.01
STOP = 20.0
START = {"theta_x0": -0.3, "theta_y0": 0.2, "omega_x0": 0.1}
OUTPUTS = ["theta_x", "theta_y", "omega_x", "omega_y", "load.x", "load.y", "load.z",
           "load.vx", "load.vy", "load.vz", "load.ax", "load.ay", "load.az", "load.q0", "load.q1",
           "load.q2", "load.q3", "load.wx", "load.wy", "load.wz", "tension"]


def run_master(master, tmp_path, derivatives):
    times = np.arange(0, int(round(STOP / H)) + 1) * H
    inputs = signals.table(times)
    csv_in = tmp_path / "tip.csv"
    with open(csv_in, "w") as f:
        f.write(",".join(inputs.dtype.names) + "\n")
        for row in inputs:
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    system = {
        "fmus": {"pendulum": str(fmu_path("pendulum"))},
        "instances": [{"name": "load", "fmu": "pendulum", "start": START}],
        "inputs": [{"instance": "load", "file": csv_in.name}],
        "start_time": 0.0, "stop_time": STOP, "step_size": H,
        "input_derivatives": derivatives,
        "record": {"variables": [f"load.{n}" for n in OUTPUTS]},
    }
    path = tmp_path / "system.json"
    path.write_text(json.dumps(system))
    out = tmp_path / "out.csv"
    subprocess.run([str(master), "run", str(path), "--output", str(out)], check=True)
    return inputs, np.genfromtxt(out, delimiter=",", names=True, deletechars="")


def max_difference(rust, other):
    assert len(rust) == len(other), (len(rust), len(other))
    assert np.max(np.abs(rust["time"] - other["time"])) < 1e-12
    return max(float(np.max(np.abs(rust[f"load.{n}"] - other[n]))) for n in OUTPUTS)


def test_master_matches_fmpy_with_held_inputs(master, tmp_path):
    inputs, rust = run_master(master, tmp_path, derivatives=False)
    fmpy = simulate_fmu(str(fmu_path("pendulum")), start_values=START, input=inputs,
                        stop_time=STOP, output_interval=H, output=OUTPUTS)
    diff = max_difference(rust, fmpy)
    print(f"Rust master vs FMPy simulate_fmu (held inputs, 20 s, {len(OUTPUTS)} outputs): max abs difference {diff:.3e}")
    assert diff <= 1e-9


def test_master_matches_fmpy_with_interpolated_inputs(master, tmp_path):
    inputs, rust = run_master(master, tmp_path, derivatives=True)
    times = inputs["time"]
    channels = {n: (lambda col: (lambda t: float(np.interp(t, times, col))))(inputs[n]) for n in signals.INPUTS}
    rig = Rig(fmu_path("pendulum"))
    try:
        fmpy = rig.run(START, channels, OUTPUTS, STOP, H, derivatives=True)
    finally:
        rig.close()
    diff = max_difference(rust, fmpy)
    print(f"Rust master vs FMPy FMU2Slave (input derivatives, 20 s): max abs difference {diff:.3e}")
    assert diff <= 1e-9

"""The Rust master and FMPy drive each FMU with the same recorded inputs and must agree
(SPEC §7: max abs difference ≤ 1e-9; in practice the results are bit-identical)."""
import csv
import json
import subprocess

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu

from conftest import ROOT, fmu_path
from rig import Rig

H = 0.01


def wave(mean, amplitude, omega, phase):
    return lambda t: mean + amplitude * np.sin(omega * t + phase)


def reference_signals():
    """Input waves per FMU from references/signals.csv, the file the packaged fmi-cross-check
    reference files are sampled from (in file order)."""
    waves = {}
    with open(ROOT / "references" / "signals.csv", newline="") as f:
        for row in csv.DictReader(f):
            numbers = (float(row[k]) for k in ("mean", "amplitude", "omega", "phase"))
            waves.setdefault(row["model"], {})[row["input"]] = wave(*numbers)
    return waves


# Start values on top of the FMU defaults the reference files run with, so that this comparison
# also covers non-default initialisation: initial angles, other seeds, the pick-and-place set-point.
START = {
    "pendulum": {"theta_x0": -0.3, "theta_y0": 0.2, "omega_x0": 0.1},
    "rigging": {"theta_x0": -0.3, "theta_y0": 0.2, "omega_x0": 0.1, "sling.dtheta_x0": 0.2, "sling.omega_y0": -0.3},
    "crane": {"noise": True, "seed": 11},
    "imu": {"noise": True, "seed": 5, "mag_inclination": 0.3},
    "controller": {"mode": 2, "feedback": 1, "setpoint": 1, "active_from": 1.0, "cf_init": 0},
}
# Per FMU: start values and input functions of time (sampled at 10 ms).
SIGNALS = reference_signals()
CASES = {name: (start, SIGNALS[name]) for name, start in START.items()}


def input_table(inputs, stop):
    times = np.arange(0, int(round(stop / H)) + 1) * H
    dtype = [("time", float)] + [(n, float) for n in inputs]
    return np.array([(t, *[f(t) for f in inputs.values()]) for t in times], dtype=dtype)


def run_master(master, tmp_path, name, start, inputs, stop, derivatives=False):
    csv_in = tmp_path / "inputs.csv"
    with open(csv_in, "w") as f:
        f.write(",".join(inputs.dtype.names) + "\n")
        for row in inputs:
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    system = {
        "fmus": {name: str(fmu_path(name))},
        "instances": [{"name": "x", "fmu": name, "start": start}],
        "inputs": [{"instance": "x", "file": csv_in.name}],
        "start_time": 0.0, "stop_time": stop, "step_size": H,
        "input_derivatives": derivatives,
    }
    path = tmp_path / "system.json"
    path.write_text(json.dumps(system))
    out = tmp_path / "out.csv"
    subprocess.run([str(master), "run", str(path), "--output", str(out), "-q"], check=True)
    return np.genfromtxt(out, delimiter=",", names=True, deletechars="")


def outputs_of(name):
    md = read_model_description(str(fmu_path(name)))
    return [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]


def max_difference(rust, other, outputs):
    assert len(rust) == len(other), (len(rust), len(other))
    assert np.max(np.abs(rust["time"] - other["time"])) < 1e-12
    return max(float(np.max(np.abs(rust[f"x.{n}"] - other[n]))) for n in outputs)


@pytest.mark.parametrize("name", sorted(CASES))
def test_master_matches_fmpy_with_recorded_inputs(master, tmp_path, name):
    start, functions = CASES[name]
    stop = 20.0
    inputs = input_table(functions, stop)
    rust = run_master(master, tmp_path, name, start, inputs, stop)
    outputs = outputs_of(name)
    fmpy = simulate_fmu(str(fmu_path(name)), start_values=start, input=inputs,
                        stop_time=stop, output_interval=H, output=outputs)
    diff = max_difference(rust, fmpy, outputs)
    print(f"{name}: Rust master vs FMPy simulate_fmu, {stop:g} s, {len(outputs)} outputs: max abs difference {diff:.3e}")
    assert diff <= 1e-9


def test_master_matches_fmpy_with_interpolated_pendulum_inputs(master, tmp_path):
    start, functions = CASES["pendulum"]
    stop = 20.0
    inputs = input_table(functions, stop)
    rust = run_master(master, tmp_path, "pendulum", start, inputs, stop, derivatives=True)
    times = inputs["time"]
    channels = {n: (lambda col: (lambda t: float(np.interp(t, times, col))))(inputs[n]) for n in functions}
    outputs = outputs_of("pendulum")
    rig = Rig(fmu_path("pendulum"))
    try:
        fmpy = rig.run(start, channels, outputs, stop, H, derivatives=True)
    finally:
        rig.close()
    diff = max_difference(rust, fmpy, outputs)
    print(f"pendulum: Rust master vs FMPy FMU2Slave with input derivatives, {stop:g} s: max abs difference {diff:.3e}")
    assert diff <= 1e-9

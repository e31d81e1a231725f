"""The IMU FMU simulated by FMPy: exact readings at a static rolled orientation with the noise off,
noise statistics with it on, determinism and direct feedthrough (SPEC §4.4, §8.1)."""
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException

from conftest import fmu_path
from rig import Rig

G = 9.80665
DEG = np.pi / 180
OUTPUTS = ["gyro.x", "gyro.y", "gyro.z", "acc.x", "acc.y", "acc.z", "mag.x", "mag.y", "mag.z"]
SIGMA = {"gyro": 0.0035, "acc": 0.01, "mag": 0.01}
LSB = {"gyro": 0.00007, "acc": 0.0006, "mag": 0.0001}

# Rolled 30° about x (starboard down), at rest, turning slowly: q = (cos 15°, sin 15°, 0, 0).
ROLL = 30 * DEG
ROLLED = {"q0": np.cos(ROLL / 2), "q1": np.sin(ROLL / 2), "q2": 0.0, "q3": 0.0, "w.x": 0.01, "w.y": -0.02, "w.z": 0.03}
# Hand-computed: gyro = ω; acc = Rx(φ)ᵀ (0, 0, −g) = (0, −g sin φ, −g cos φ); mag = Rx(φ)ᵀ (1, 0, 0).
EXPECTED = {
    "gyro.x": 0.01, "gyro.y": -0.02, "gyro.z": 0.03,
    "acc.x": 0.0, "acc.y": -G / 2, "acc.z": -G * np.sqrt(3) / 2,
    "mag.x": 1.0, "mag.y": 0.0, "mag.z": 0.0,
}


def simulate(start_values, stop_time=1.0):
    return simulate_fmu(
        str(fmu_path("imu")),
        start_values=start_values,
        stop_time=stop_time,
        output_interval=0.01,
        output=OUTPUTS,
    )


def quantize(x, lsb):
    return lsb * np.round(x / lsb)


def test_ports_follow_the_spec():
    md = read_model_description(str(fmu_path("imu")))
    variables = {v.name: v for v in md.modelVariables}
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    assert inputs == ["q0", "q1", "q2", "q3", "w.x", "w.y", "w.z", "a.x", "a.y", "a.z"]
    assert outputs == OUTPUTS
    assert [variables[n].unit for n in OUTPUTS] == ["rad/s"] * 3 + ["m/s2"] * 3 + ["1"] * 3
    assert float(variables["q0"].start) == 1.0
    assert variables["noise"].type == "Boolean" and variables["seed"].type == "Integer"
    assert not md.coSimulation.canInterpolateInputs


def test_static_roll_without_noise_reads_the_hand_computed_values():
    ideal = {"noise": False, "gyro.lsb": 0.0, "acc.lsb": 0.0, "mag.lsb": 0.0}
    result = simulate({**ROLLED, **ideal})
    for name in OUTPUTS:
        error = np.max(np.abs(result[name] - EXPECTED[name]))
        assert error < 1e-12, f"{name}: max error {error}"
    print(f"imu rolled 30°, noise off: acc = ({result['acc.x'][0]:.6f}, {result['acc.y'][0]:.6f}, "
          f"{result['acc.z'][0]:.6f}) m/s², {len(result)} samples exact to 1e-12")


def test_static_roll_with_quantisation_reads_the_rounded_values():
    result = simulate({**ROLLED, "noise": False})
    for name in OUTPUTS:
        expected = quantize(EXPECTED[name], LSB[name.split(".")[0]])
        error = np.max(np.abs(result[name] - expected))
        assert error < 1e-12, f"{name}: max error {error}"


def test_noise_statistics_match_the_parameters():
    result = simulate({**ROLLED, "seed": 11}, stop_time=100.0)
    n = len(result)
    for name in OUTPUTS:
        sensor = name.split(".")[0]
        sigma, lsb = SIGMA[sensor], LSB[sensor]
        error = result[name] - EXPECTED[name]
        mean, std = float(np.mean(error)), float(np.std(error, ddof=1))
        expected_std = np.sqrt(sigma**2 + lsb**2 / 12)
        print(f"imu {name}: mean error {mean:+.2e} (limit ±{4 * sigma / np.sqrt(n):.1e}), "
              f"std {std:.4e} vs σ {sigma:.4e} ({100 * (std / expected_std - 1):+.2f} %), {n} samples")
        assert abs(mean) < 4 * sigma / np.sqrt(n) + lsb / 2, name
        # Standard error of a sample std: σ/√(2n) ≈ 0.7 %; allow 5 %.
        assert abs(std / expected_std - 1) < 0.05, name


def test_reruns_are_bit_identical_and_seeds_differ():
    a = simulate({**ROLLED, "seed": 3})
    b = simulate({**ROLLED, "seed": 3})
    c = simulate({**ROLLED, "seed": 4})
    for name in OUTPUTS:
        assert np.array_equal(a[name], b[name]), name
        assert not np.array_equal(a[name], c[name]), name


def test_outputs_follow_inputs_set_after_a_step():
    """Direct feedthrough: inputs set at a communication point show in the outputs read there."""
    rig = Rig(fmu_path("imu"))
    vr = rig.vr
    s = rig.slave
    try:
        s.instantiate()
        s.setupExperiment(startTime=0.0)
        s.setBoolean([vr["noise"]], [False])
        s.setReal([vr["acc.lsb"]], [0.0])
        s.enterInitializationMode()
        s.exitInitializationMode()
        assert s.getReal([vr["acc.x"], vr["acc.y"], vr["acc.z"]]) == pytest.approx([0, 0, -G], abs=1e-12)
        s.doStep(currentCommunicationPoint=0.0, communicationStepSize=0.01)
        pitch = 20 * DEG  # nose up: acc = (g sin θ, 0, −g cos θ)
        s.setReal([vr["q0"], vr["q1"], vr["q2"], vr["q3"]], [np.cos(pitch / 2), 0.0, np.sin(pitch / 2), 0.0])
        acc = s.getReal([vr["acc.x"], vr["acc.y"], vr["acc.z"]])
        assert acc == pytest.approx([G * np.sin(pitch), 0.0, -G * np.cos(pitch)], abs=1e-12)
        # A zero quaternion is refused at the next step.
        s.setReal([vr["q0"], vr["q1"], vr["q2"], vr["q3"]], [0.0, 0.0, 0.0, 0.0])
        with pytest.raises(FMICallException):
            s.doStep(currentCommunicationPoint=0.01, communicationStepSize=0.01)
        s.freeInstance()
    finally:
        rig.close()

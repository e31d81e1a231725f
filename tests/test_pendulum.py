"""The pendulum FMU simulated by FMPy against an independent SciPy integration (SPEC §7)."""
import numpy as np
import pytest
from fmpy import simulate_fmu

import pendulum_reference as ref
import signals
from conftest import fmu_path
from rig import Rig

DEG = np.pi / 180
LP = 0.7


# The pendulum's accuracy rule (docs/specification.md): the load position within 1e-7 m RMSD of
# the SciPy integration over 60 s, for a free swing and for a moving tip with a changing length.
TOLERANCE = 1e-7


def rmsd(a, b):
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=0))))


def fixed_tip(t):
    z = np.zeros(3)
    return z, z, z, LP, 0.0, 0.0


@pytest.mark.parametrize("thx, thy", [(20, 20), (-20, 20), (20, -20), (-20, -20), (-20, 0), (0, 20)])
def test_free_swing_matches_scipy(thx, thy):
    result = simulate_fmu(
        str(fmu_path("pendulum")),
        start_values={"theta_x0": thx * DEG, "theta_y0": thy * DEG, "lp": LP},
        stop_time=60.0,
        output_interval=0.01,
        output=["load.x", "load.y", "load.z", "theta_x", "theta_y"],
    )
    t = result["time"]
    _, x = ref.simulate([thx * DEG, thy * DEG, 0, 0], fixed_tip, t)
    expected = ref.load_position(x, np.zeros(3), LP)
    got = np.stack([result["load.x"], result["load.y"], result["load.z"]])
    error = rmsd(got, expected)
    print(f"pendulum vs SciPy, 60 s, ({thx}°, {thy}°): load-position RMSD {error:.3e} m")
    assert error < TOLERANCE


# A driven case: tip and cable length sampled at 10 ms and interpolated linearly by the FMU
# (input derivatives, accelerations reconciled with the velocity slopes), the same signals
# integrated by SciPy.
H = 0.01


def step_of(t):
    k = np.floor(t / H + 1e-9)
    return k * H, (k + 1) * H


def sampled(f):
    """Piecewise-linear interpolant of f through the 10 ms grid."""
    def value(t):
        t0, t1 = step_of(t)
        return f(t0) + (f(t1) - f(t0)) * (t - t0) / H
    return value


def reconciled(acc, vel):
    """The acceleration ramp the FMU builds when the velocity has a derivative: it ends at the
    sample acc(t1) and its mean over the step is the velocity's secant slope. It jumps at the
    sample times, so it is evaluated on the step starting at `t0`."""
    def value(t, t0):
        t1 = t0 + H
        end = acc(t1)
        start = 2 * (vel(t1) - vel(t0)) / H - end
        return start + (end - start) * (t - t0) / H
    return value


CHANNELS = {name: signals.channel(name) for name in signals.INPUTS}


def test_driven_swing_with_interpolated_inputs_matches_scipy():
    stop = 60.0
    rig = Rig(fmu_path("pendulum"))
    try:
        result = rig.run(
            {"theta_x0": -15 * DEG, "theta_y0": 10 * DEG},
            CHANNELS,
            ["load.x", "load.y", "load.z"],
            stop,
            H,
            derivatives=True,
        )
    finally:
        rig.close()
    lin = {name: sampled(f) for name, f in CHANNELS.items()}
    acc_of = {axis: reconciled(CHANNELS[f"tip.a{axis}"], CHANNELS[f"tip.v{axis}"]) for axis in "xyz"}
    lp_ddot = reconciled(CHANNELS["lp_ddot"], CHANNELS["lp_dot"])

    def tip(t, t0=None):
        t0 = step_of(t)[0] if t0 is None else t0
        pos = np.array([lin["tip.x"](t), lin["tip.y"](t), lin["tip.z"](t)])
        vel = np.array([lin["tip.vx"](t), lin["tip.vy"](t), lin["tip.vz"](t)])
        acc = np.array([acc_of[axis](t, t0) for axis in "xyz"])
        return pos, vel, acc, lin["lp"](t), lin["lp_dot"](t), lp_ddot(t, t0)

    t = result["time"]
    _, x = ref.simulate([-15 * DEG, 10 * DEG, 0, 0], tip, t, breakpoints=t, segmented=True)
    tips = np.array([tip(ti)[0] for ti in t]).T
    lps = np.array([tip(ti)[3] for ti in t])
    expected = ref.load_position(x, tips, lps)
    got = np.stack([result["load.x"], result["load.y"], result["load.z"]])
    error = rmsd(got, expected)
    print(f"pendulum vs SciPy, driven tip and length, interpolated inputs, 60 s: RMSD {error:.3e} m")
    assert error < TOLERANCE

"""The rigging FMU (fmus/rigging) as a drop-in for the pendulum FMU, both built FMUs under FMPy.

With no sling, no hook mass and a rigid hoist rope the rigging takes the pendulum's code path:
every output the two FMUs share must come out with equal bits, driven by the same interpolated
inputs (tip motion and hoist length with their derivatives) through a held phase and a release.
A double pendulum with an elastic hoist rope under heave goes slack and re-catches without an
error, and the slack flag and peak snap load show it.
"""
import numpy as np

import signals
from conftest import fmu_path
from rig import Rig

H = 0.01
SHARED = [
    "theta_x", "theta_y", "omega_x", "omega_y",
    "load.x", "load.y", "load.z", "load.vx", "load.vy", "load.vz", "load.ax", "load.ay", "load.az",
    "load.q0", "load.q1", "load.q2", "load.q3", "load.wx", "load.wy", "load.wz",
    "tension", "cable.fx", "cable.fy", "cable.fz", "cable.f0x", "cable.f0y", "cable.f0z", "cable.mass",
]
CHANNELS = {name: signals.channel(name) for name in signals.INPUTS}
SWING = {"theta_x0": -0.4, "theta_y0": 0.15, "omega_x0": 0.2, "omega_y0": -0.1, "release_time": 2.0}


def run(name, start, inputs=CHANNELS, outputs=SHARED, stop=20.0):
    rig = Rig(fmu_path(name), instance_name=name)
    try:
        return rig.run(start, inputs, outputs, stop, H, derivatives=True)
    finally:
        rig.close()


def test_no_sling_and_a_rigid_rope_is_the_pendulum_fmu_to_the_bit():
    pendulum = run("pendulum", SWING)
    rigging = run("rigging", {**SWING, "sling.length": 0.0, "hook.mass": 0.0, "mass": 0.3018})
    differing = [n for n in SHARED if not np.array_equal(pendulum[n].view(np.uint64), rigging[n].view(np.uint64))]
    worst = max((float(np.max(np.abs(pendulum[n] - rigging[n]))) for n in SHARED), default=0.0)
    print(f"rigging (sling 0, rigid) vs pendulum FMU, 20 s, {len(SHARED)} outputs: differing {differing}, max {worst:e}")
    assert differing == [] and worst == 0.0


def test_the_default_rigging_differs_from_the_pendulum():
    """Control: the comparison above can fail. The default rig (0.2 m sling) swings otherwise."""
    pendulum = run("pendulum", SWING, stop=5.0)
    rigging = run("rigging", SWING, stop=5.0)
    gap = float(np.max(np.abs(pendulum["load.x"] - rigging["load.x"])))
    print(f"default rigging vs pendulum: load.x differs by up to {gap:.3f} m in 5 s")
    assert gap > 1e-3


def test_an_elastic_rope_under_heave_goes_slack_and_catches():
    a, w = 0.03, 20.0
    heave = {
        "tip.z": lambda t: a * np.sin(w * t),
        "tip.vz": lambda t: a * w * np.cos(w * t),
        "tip.az": lambda t: -a * w * w * np.sin(w * t),
    }
    out = ["tension", "hoist.peak_snap", "load.z", "hook.z"]
    rig = Rig(fmu_path("rigging"))
    try:
        result = rig.run({"hoist.law": 1, "hoist.damping_time": 1e-3}, heave, out, 10.0, H, derivatives=True)
    finally:
        rig.close()
    zero = int(np.sum(result["tension"] == 0.0))
    peak = float(result["hoist.peak_snap"][-1])
    print(f"elastic rope under heave: zero tension at {zero} of {len(result)} points, peak snap {peak:.2f} N")
    assert len(result) == 1001 and zero > 100 and peak > 2 * 0.3018 * 9.80665
    assert np.all(np.isfinite(result["load.z"]))

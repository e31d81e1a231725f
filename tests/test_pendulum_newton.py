"""Newton's second law for the load, checked on the pendulum FMU's own outputs.

tests/pendulum_reference.py re-types eqs. 4.131-4.132 from the thesis, as the Rust code does, so a
misreading shared by both would pass test_pendulum.py. This check shares no transcription with
the code: it takes the load's position, velocity and acceleration as the FMU reports them, the
tip position the rig drove, and the drag law as a force (section 7.2.3), and asks whether

    m a = m g z - T e_r + F_drag,   F_drag = -m kx (v.e_x) e_x - m ky (v.e_y) e_y

holds at every communication point. Cable directions come from the positions, the swing
directions from the angles through the rotations Rx(theta_x) Ry(theta_y), not from the sines
and cosines of eqs. 4.94-4.96. Drag is tangential, so the tangential part of m (g z - a) must be
the negative drag and the radial part must be the tension output (positive when the cable pulls
the load toward the tip).
"""
import numpy as np
import pytest

from conftest import fmu_path
from rig import Rig

G = 9.80665
MASS = 0.3018
H = 0.001
STOP = 6.0
# Forces here are ~3 N; the identity is algebraic at each output instant, so only rounding is
# left (~1e-15 N). Drag reaches ~1e-2 N with the thesis' constants and ~0.15 N with the strong ones,
# so a wrong sign, axis or term misses by far more than this.
FORCE_TOL = 1e-11
INPUTS = ["tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az", "lp", "lp_dot", "lp_ddot"]


def brisk_tip(t):
    """A tip shaken at up to ~2 m/s² and a cable reeled at up to 0.23 m/s, so that the inertial
    and Coriolis terms of eqs. 4.131-4.132 are comparable to gravity's tangential part."""
    a = np.array([0.05, 0.04, 0.03])
    w = np.array([5.0, 7.0, 4.0])
    pos = a * np.sin(w * t) + np.array([0.0, -0.5, -0.15])
    vel = a * w * np.cos(w * t)
    acc = -a * w**2 * np.sin(w * t)
    lp = 0.7 + 0.15 * np.sin(1.5 * t)
    return (*pos, *vel, *acc, lp, 0.225 * np.cos(1.5 * t), -0.3375 * np.sin(1.5 * t))


def channel(i):
    return lambda t: brisk_tip(t)[i]


def run(kappa_x, kappa_y):
    rig = Rig(fmu_path("pendulum"))
    outputs = ["theta_x", "theta_y", "tension"] + [f"load.{q}{a}" for q in ("", "v", "a") for a in "xyz"]
    try:
        return rig.run(
            {"theta_x0": 0.3, "theta_y0": -0.2, "mass": MASS, "kappa_x": kappa_x, "kappa_y": kappa_y, "g": G},
            {name: channel(i) for i, name in enumerate(INPUTS)},
            outputs,
            STOP,
            H,
            derivatives=True,
        )
    finally:
        rig.close()


def vectors(r, kind):
    return np.stack([r[f"load.{kind}{a}"] for a in "xyz"], axis=1)


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def cable(thx, thy):
    """Unit vector tip -> load: the hanging direction z rotated by the X-Y sequence."""
    return rot_x(thx) @ rot_y(thy) @ np.array([0.0, 0.0, 1.0])


def swing_directions(thx, thy):
    """Unit directions in which theta_x and theta_y move the load: theta_x turns the cable
    about the world x axis, theta_y about the x-rotated y axis (d/dθ R(θ) e = axis × R(θ) e)."""
    e_r = cable(thx, thy)
    ex = np.cross([1.0, 0.0, 0.0], e_r)
    ey = np.cross(rot_x(thx) @ np.array([0.0, 1.0, 0.0]), e_r)
    return ex / np.linalg.norm(ex), ey / np.linalg.norm(ey)


def frames(r):
    """Per sample: e_r from the positions (checked against the angles), e_x, e_y from the angles."""
    tip = np.array([brisk_tip(t)[:3] for t in r["time"]])
    lp = np.array([brisk_tip(t)[9] for t in r["time"]])
    rel = vectors(r, "") - tip
    length = np.linalg.norm(rel, axis=1)
    assert np.max(np.abs(length - lp)) < 1e-12, "the load hangs at the cable length"
    e_r = rel / length[:, None]
    from_angles = np.array([cable(a, b) for a, b in zip(r["theta_x"], r["theta_y"])])
    assert np.max(np.abs(e_r - from_angles)) < 1e-12, "positions and angles describe one cable"
    e_x, e_y = map(np.array, zip(*[swing_directions(a, b) for a, b in zip(r["theta_x"], r["theta_y"])]))
    return e_r, e_x, e_y


def dot(a, b):
    return np.einsum("ij,ij->i", a, b)


def balance(r, kappa_x, kappa_y):
    """Residuals (N) of the e_x, e_y and radial components of Newton's law for the load."""
    e_r, e_x, e_y = frames(r)
    v, a = vectors(r, "v"), vectors(r, "a")
    # m (g z - a) = T e_r - F_drag: what the cable and the air must supply beyond gravity.
    f = MASS * (G * np.array([0.0, 0.0, 1.0]) - a)
    drag_x = -MASS * kappa_x * dot(v, e_x)
    drag_y = -MASS * kappa_y * dot(v, e_y)
    return dot(f, e_x) + drag_x, dot(f, e_y) + drag_y, dot(f, e_r) - r["tension"]


@pytest.mark.parametrize("kappa_x, kappa_y", [(0.0, 0.0), (0.0272, 0.018), (0.6, 0.25)])
def test_load_obeys_newton_with_tangential_drag(kappa_x, kappa_y):
    r = run(kappa_x, kappa_y)
    res_x, res_y, res_r = balance(r, kappa_x, kappa_y)
    _, e_x, e_y = frames(r)
    a = vectors(r, "a")
    tip_acc = np.array([brisk_tip(t)[6:9] for t in r["time"]])
    drag = MASS * np.hypot(kappa_x * dot(vectors(r, "v"), e_x), kappa_y * dot(vectors(r, "v"), e_y))
    print(
        f"pendulum Newton, kappa = ({kappa_x}, {kappa_y}), {STOP:g} s at {H * 1e3:g} ms: residuals "
        f"e_x {np.max(np.abs(res_x)):.2e} N, e_y {np.max(np.abs(res_y)):.2e} N, radial {np.max(np.abs(res_r)):.2e} N; "
        f"max drag {drag.max():.2e} N, max m|a| tangential {MASS * np.max(np.hypot(dot(a, e_x), dot(a, e_y))):.2f} N, "
        f"max m|a_tip| {MASS * np.max(np.linalg.norm(tip_acc, axis=1)):.2f} N, tension {r['tension'].min():.3f}..{r['tension'].max():.3f} N"
    )
    # The swing and the shaking are large, so the tangential balance is not 0 = 0.
    assert MASS * np.max(np.hypot(dot(a, e_x), dot(a, e_y))) > 0.5
    assert kappa_x == 0 or drag.max() > 1e5 * FORCE_TOL
    assert np.max(np.abs(res_x)) < FORCE_TOL
    assert np.max(np.abs(res_y)) < FORCE_TOL
    assert np.max(np.abs(res_r)) < FORCE_TOL


def test_outputs_are_one_instant():
    """Velocity and acceleration outputs are the derivatives of the position and velocity
    outputs at the same communication point (not a value from inside the step): central
    differences over 1 ms agree to ~3e-5, a value half a step late is off by ~1e-2."""
    r = run(0.6, 0.25)
    t = r["time"]
    for kind, rate in (("", "v"), ("v", "a")):
        x, dx = vectors(r, kind), vectors(r, rate)
        central = (x[2:] - x[:-2]) / (t[2:] - t[:-2])[:, None]
        error = np.max(np.abs(central - dx[1:-1]))
        lagged = np.max(np.abs(central - (dx[1:-1] + dx[:-2]) / 2))
        print(f"load.{rate} vs central difference of load.{kind or 'pos'}: {error:.2e} (half a step late: {lagged:.2e})")
        assert error < 1e-4
        assert lagged > 10 * error

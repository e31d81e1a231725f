"""The crane FMU in FMPy: a recorded command sequence and a rolling ship (SPEC §4.2).

Commands are held over each 10 ms step, as the myRIO holds its outputs. The ship motion is fed
the way a Gauss–Seidel master with the platform stepped first feeds it: before the step from t_k
to t_k+1 the crane receives the ship motion at t_k+1, so every recorded row is consistent in time
(the ship inputs act directly on the world-frame tip outputs).
"""
import numpy as np
import pytest
from fmpy import read_model_description

from conftest import fmu_path
from rig import Rig

H = 0.01
NEUTRAL = {"base": 1.65, "boom": 1.65, "jib": 1.65, "winch": 0.5}
DEADBAND = {"base": (-0.145, 0.145), "boom": (-0.145, 0.525), "jib": (-0.145, 0.175), "winch": (-0.0165, 0.0)}
TF = {"base": (185.6, 13.8), "boom": (458.0, 31.61), "jib": (640.09, 48.32), "winch": (37928.0, 24.43)}
R_BASE = np.array([0.0, -0.225, 0.0])

# The recorded command sequence: from each time on (s), u.base, u.boom, u.jib (V), u.winch (duty).
SEQUENCE = [
    (0.0, 1.65, 1.65, 1.65, 0.50),  # at rest
    (0.5, 2.30, 2.10, 1.65, 0.50),  # base out; boom inside its 0.525 V deadband
    (2.5, 1.65, 2.60, 1.00, 0.60),  # base off; boom out, jib in, winch paying out
    (4.5, 3.30, 1.65, 1.65, 0.45),  # base at full command into its stroke end; winch hauling in
    (7.0, 1.65, 1.65, 1.65, 0.50),  # all neutral
]
STOP = 8.0
AXES = ["base", "boom", "jib", "winch"]
SWITCHES = [row[0] for row in SEQUENCE[1:]]


def command(axis):
    column = 1 + AXES.index(axis)

    def f(t):
        value = SEQUENCE[0][column]
        for row in SEQUENCE:
            if t >= row[0] - 1e-9:
                value = row[column]
        return value

    return f


def steady_rate(axis, u):
    """K/a·(u − neutral − crossed deadband bound) (mm/s or deg/s)."""
    lower, upper = DEADBAND[axis]
    x = min(max(u, 0.0), 3.3 if axis != "winch" else 1.0) - NEUTRAL[axis]
    lin = x - upper if x > upper else x - lower if x < lower else 0.0
    gain, pole = TF[axis]
    return gain / pole * lin


TRUTH = ["d.base", "d.boom", "d.jib", "winch.angle", "lp", "lp_dot", "lp_ddot",
         "tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az",
         "tip_base.x", "tip_base.y", "tip_base.z", "pot.base", "pot.boom", "pot.jib", "encoder"]


@pytest.fixture(scope="module")
def start():
    """The FMU's start values (the default pose is defined once, in the Rust physics crate)."""
    return {v.name: v.start for v in read_model_description(str(fmu_path("crane"))).modelVariables}


@pytest.fixture(scope="module")
def d0(start):
    """The initial extensions (m): the start values of d0.base, d0.boom, d0.jib."""
    return {a: float(start[f"d0.{a}"]) for a in ["base", "boom", "jib"]}


def stroke_end_arrival(d0_mm, end_mm=50.0):
    """When the base reaches the end of its stroke (s), in closed form.

    Each command is held from its switch time, so between switches ẍ = −a ẋ + K u with the
    linearised input u (eqs. 3.5, Table 3.2) and, from (x0, v0) after τ s,
    v = v∞ + (v0 − v∞) e^(−aτ), x = x0 + v∞ τ + (v0 − v∞)(1 − e^(−aτ))/a, v∞ = K u/a.
    Returns the arrival time and the position (mm) along the way, for the segment it happens in.
    """
    gain, pole = TF["base"]
    x, v = d0_mm, 0.0
    column = 1 + AXES.index("base")
    for row, (end, *_) in zip(SEQUENCE, SEQUENCE[1:] + [(STOP,)]):
        start, v_inf = row[0], steady_rate("base", row[column])

        def position(tau, x=x, v=v, v_inf=v_inf):
            return x + v_inf * tau + (v - v_inf) * (1 - np.exp(-pole * tau)) / pole

        if position(end - start) >= end_mm:
            # x(τ) is increasing here (v ≥ 0, v∞ > 0): bisection to the last bit.
            lo, hi = 0.0, end - start
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if position(mid) < end_mm else (lo, mid)
            return start + hi, lambda t, start=start, position=position: position(t - start)
        tau = end - start
        x, v = position(tau), v_inf + (v - v_inf) * np.exp(-pole * tau)
    raise AssertionError("the base never reaches its stroke end")


@pytest.fixture(scope="module")
def recorded():
    rig = Rig(fmu_path("crane"))
    try:
        return rig.run({}, {f"u.{a}": command(a) for a in AXES}, TRUTH, STOP, H)
    finally:
        rig.close()


def window(r, start, end):
    """Rows with start ≤ t ≤ end."""
    t = r["time"]
    return (t >= start - 1e-9) & (t <= end + 1e-9)


def test_constant_commands_give_the_steady_velocities(recorded):
    r = recorded
    t = r["time"]
    for (start, *u), (end, *_) in zip(SEQUENCE[1:3], SEQUENCE[2:4]):
        for axis, value in zip(AXES, u):
            if axis == "base" and value == NEUTRAL[axis]:
                continue  # coasting to a stop, not steady
            # The average rate over the last 0.2 s of a 2 s segment: the transient has decayed
            # by e^(−a·1.8 s) < 1e-10.
            sel = window(r, end - 0.2, end)
            signal = r["winch.angle"] if axis == "winch" else r[f"d.{axis}"] * 1000.0
            rate = np.polyfit(t[sel], signal[sel], 1)[0]
            expected = steady_rate(axis, value)
            unit = "deg/s" if axis == "winch" else "mm/s"
            print(f"{start:.1f}–{end:.1f} s {axis:5} at {value}: {rate:+.6f} {unit} (K/a·(u − neutral − deadband) = {expected:+.6f})")
            assert rate == pytest.approx(expected, rel=1e-8, abs=1e-9)


def test_nothing_moves_inside_the_deadband_or_at_rest(recorded, d0):
    r = recorded
    sel = window(r, 0.0, 2.5)
    assert np.all(r["d.boom"][sel] == d0["boom"]), "boom moved inside its deadband"
    assert np.all(r["d.jib"][window(r, 0.0, 2.5)] == d0["jib"])
    rest = window(r, 0.0, 0.5)
    assert np.all(r["tip.vx"][rest] == 0.0) and np.all(r["lp_dot"][rest] == 0.0)


def test_the_base_stops_at_its_stroke_end(recorded, d0):
    r = recorded
    t, d = r["time"], r["d.base"]
    at_end = np.flatnonzero(d == 0.05)
    assert at_end.size > 0 and np.all(d <= 0.05)
    first = t[at_end[0]]
    arrival, closed_form = stroke_end_arrival(d0["base"] * 1000.0)
    print(f"base reaches 50 mm at {arrival:.6f} s (closed form), first sample there {first:.2f} s, "
          f"and stays: {np.all(d[t >= first] == 0.05)}")
    # The integration is exact for held commands, so the first sample at the stroke end is the
    # first communication point at or after the closed-form arrival, and the samples before it lie
    # on the closed-form trajectory.
    assert first == pytest.approx(np.ceil(arrival / H - 1e-9) * H, abs=1e-9)
    before = (t >= 4.5 - 1e-9) & (t < first - 1e-9)
    error = np.abs(d[before] * 1000.0 - closed_form(t[before])).max()
    print(f"base from 4.5 s to the stroke end: largest deviation from the closed form {error:.2e} mm")
    assert error < 1e-9
    assert np.all(d[t >= first] == 0.05)
    # The potentiometer reads the top converter code (less at most a few noise LSBs).
    pot = r["pot.base"][t >= first]
    assert pot.max() <= 4095 * 5 / 4096 and pot.mean() > 4.99


def test_rates_are_the_derivatives_of_the_positions(recorded):
    r = recorded
    t = r["time"]
    # Away from command switches (the accelerations jump there: the commands are held) and from
    # the base's arrival at its stroke end (the velocity jumps to zero there).
    arrival = t[np.flatnonzero(r["d.base"] == 0.05)[0]]
    far = np.ones_like(t, dtype=bool)
    for s in SWITCHES + [arrival]:
        far &= np.abs(t - s) > 0.3
    far[:2] = far[-2:] = False
    pos = np.stack([r["tip.x"], r["tip.y"], r["tip.z"]])
    vel = np.stack([r["tip.vx"], r["tip.vy"], r["tip.vz"]])
    acc = np.stack([r["tip.ax"], r["tip.ay"], r["tip.az"]])
    fd_vel = (np.roll(pos, -1, axis=1) - np.roll(pos, 1, axis=1)) / (2 * H)
    fd_acc = (np.roll(vel, -1, axis=1) - np.roll(vel, 1, axis=1)) / (2 * H)
    fd_lp = (np.roll(r["lp"], -1) - np.roll(r["lp"], 1)) / (2 * H)
    ev = np.abs(vel - fd_vel)[:, far].max()
    ea = np.abs(acc - fd_acc)[:, far].max()
    el = np.abs(r["lp_dot"] - fd_lp)[far].max()
    print(f"tip velocity vs differences of positions {ev:.2e} m/s (speeds up to {np.abs(vel).max():.3f}), "
          f"acceleration vs differences of velocities {ea:.2e} m/s², lp_dot {el:.2e} m/s")
    assert ev < 1e-5 and ea < 1e-4 and el < 1e-5
    # Still water: the world tip is the base-frame tip shifted to port.
    base = np.stack([r["tip_base.x"], r["tip_base.y"], r["tip_base.z"]])
    assert np.abs(pos - (base + R_BASE[:, None])).max() < 1e-15


def test_the_pendulum_length_follows_the_winch_and_the_jib(recorded, start):
    r = recorded
    d_jib = r["d.jib"] * 1000.0
    lp = (325 + r["winch.angle"] / 360 * np.pi * 41.26 + 0.010668 * d_jib**2 + 0.5327 * d_jib + 0.59982) / 1000
    assert np.abs(lp - r["lp"]).max() < 1e-15
    assert r["lp"][0] == pytest.approx(float(start["lp0"]), abs=1e-15)


def test_sensor_noise_statistics(recorded):
    r = recorded
    lsb = 5 / 4096
    errors = np.concatenate([r[f"pot.{a}"] - 100 * r[f"d.{a}"] for a in ["boom", "jib"]])
    expected = np.sqrt(0.0012**2 + lsb**2 / 12)
    print(f"potentiometers: mean error {errors.mean() * 1e3:+.3f} mV, std {errors.std() * 1e3:.3f} mV (expected {expected * 1e3:.3f})")
    assert abs(errors.mean()) < 4 * expected / np.sqrt(errors.size)
    assert errors.std() == pytest.approx(expected, rel=0.1)
    enc = r["encoder"] - r["winch.angle"]
    expected = np.sqrt(0.06**2 + (360 / 4096) ** 2 / 12)
    print(f"encoder: mean error {enc.mean():+.4f}°, std {enc.std():.4f}° (expected {expected:.4f})")
    assert enc.std() == pytest.approx(expected, rel=0.1)
    codes = r["encoder"] / (360 / 4096)
    assert np.abs(codes - np.round(codes)).max() < 1e-6


def test_tip_motion_under_ship_roll_is_rigid_body_kinematics():
    amp, w = np.radians(5.0), 1.2

    def ahead(f):
        return lambda t: f(t + H)

    ship = {
        "ship.roll": lambda t: amp * np.sin(w * t),
        "ship.wx": lambda t: amp * w * np.cos(w * t),
        "ship.alphax": lambda t: -amp * w * w * np.sin(w * t),
        "ship.z": lambda t: 0.02 * np.sin(0.8 * t),
        "ship.vz": lambda t: 0.016 * np.cos(0.8 * t),
        "ship.az": lambda t: -0.0128 * np.sin(0.8 * t),
    }
    inputs = {name: ahead(f) for name, f in ship.items()}
    inputs.update({"u.base": lambda t: 2.2, "u.jib": lambda t: 1.0})
    rig = Rig(fmu_path("crane"))
    try:
        r = rig.run({}, inputs, TRUTH, 3.0, H)
    finally:
        rig.close()
    t = r["time"]
    pos = np.stack([r["tip.x"], r["tip.y"], r["tip.z"]])
    vel = np.stack([r["tip.vx"], r["tip.vy"], r["tip.vz"]])
    acc = np.stack([r["tip.ax"], r["tip.ay"], r["tip.az"]])
    inner = (t > 0.5) & (t < t[-1] - 0.02)
    fd_vel = (np.roll(pos, -1, axis=1) - np.roll(pos, 1, axis=1)) / (2 * H)
    fd_acc = (np.roll(pos, -1, axis=1) - 2 * pos + np.roll(pos, 1, axis=1)) / H**2
    ev = np.abs(vel - fd_vel)[:, inner].max()
    ea = np.abs(acc - fd_acc)[:, inner].max()
    print(f"ship rolling ±5° at 1.2 rad/s, heaving, crane slewing: tip velocity vs differences {ev:.2e} m/s, "
          f"acceleration vs second differences {ea:.2e} m/s² (accelerations up to {np.abs(acc).max():.3f} m/s²)")
    assert ev < 2e-5 and ea < 2e-4
    # The position itself: p = p_ship + R_x(roll) (r_base + p_tip/J12).
    roll = amp * np.sin(w * t)
    base = np.stack([r["tip_base.x"], r["tip_base.y"], r["tip_base.z"]]) + R_BASE[:, None]
    c, s = np.cos(roll), np.sin(roll)
    expected = np.stack([base[0], c * base[1] - s * base[2], s * base[1] + c * base[2] + 0.02 * np.sin(0.8 * t)])
    assert np.abs(pos - expected)[:, 1:].max() < 1e-12

"""Each catalogue crane in the crane FMU `knuckle_boom` against an independent model written from
its description (cranes/*.json, `extends` merged here) and the documented equations: H1-H14 of
docs/hydraulics.md, F1-F5 and the load coupling of fmus/knuckle_boom/README.md, the mechanism
and the mass matrix of docs/knuckle-boom-arm.md. No Rust is ported; the FMU runs in FMPy with its
noise off, the ship at rest and 10 ms communication steps.

1. Full-valve speeds, unloaded: boom and jib cylinders extending and retracting, slew, rope.
   A pressure-compensated valve meters Q_max at full spool (H3), so a cylinder runs at
   Q_max/A_A extending and Q_max/A_B retracting (A = count x one cylinder's area), the slew at
   Q_max/(D n), the rope at Q_max/(D n) r_d (open circuit) or D_p w_p/(D n) r_d (closed, H16).
   A retracting cylinder drains its piston side through the counterbalance valve (H6), fully
   open once k·p_A + R·p_B is `opening_range` above its `setting`; where that valve cannot pass A_A/A_B times the meter-in
   flow (osp_test_crane's OSP valve, 20 L/min at 5 bar), the speed is the valve's: solved here
   from H2, H3, H6 and H7 at steady speed. Tolerances: 1.5 % against the leak-free figure, since
   the spool's laminar leakage C_T p_line is at most 1.67e-12 x 30 MPa = 5e-5 m3/s, 1.25 % of
   240 L/min (less of the bigger valves), and 0.3 % against the figure with the leakages (H3,
   H9, H16) at the measured pressures.
2. Holding pressures after a boom move with the rated load: p_A = (F + p_B A_B)/A_A, F the
   static joint torque from the link masses, centres of mass and the load at the tip over the
   mechanism's lever dL/dθ at the joints the FMU settled at.
3. The boom's hydraulic natural frequency at three strokes with the rated load, excited by a
   2 % step of the rope force with every valve centred. H13 with the load lumped rigidly into
   the boom's inertia overestimates it by 15-30 %: the load hangs on the winch's oil column
   (H14) and the jib on its cylinder, and both give. So the model is the linearised arm of
   F1-F5: boom, jib and drum with the mass matrix of docs/knuckle-boom-arm.md plus the load's
   inertia along the rope (m g g^T, m r_d g, J_w + m r_d^2), the stiffnesses of H13 (times
   lever^2) and H14, the friction's small-speed slopes (b + F_c/v_s) as damping. Its step
   response and the FMU's are fitted with the same damped sine; the natural frequencies
   sqrt(w_d^2 + sigma^2) agree within 3 %: one sine fitted to mixed, damped modes, the
   friction's tanh, linear only well below v_s (a 10 % step gives up to -5.8 % on
   osp_test_crane), and the closed-circuit winch's creep, which the linear model lacks.
4. Hoisting the rated load at full command: rope speed against item 1's figure with the motor's
   and pump's leakage, and the motor's pressure difference against the static
   (T r_d/n + b w_m + tau_c tanh(w_m/w_s))/D (H8), within 1 %.

`pytest -s` prints each crane's figures and a table per crane at the end.
"""
import json
import math
import pathlib
import shutil

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from scipy.linalg import expm
from scipy.optimize import brentq, curve_fit

from conftest import ROOT, fmu_path

CRANES = ["osp_derived", "osp_test_crane", "ahc_10t"]
H = 0.01
RESULTS = {}


# ---------------------------------------------------------------- the description, merged here

def merge(base, over):
    """`extends`: objects merge field by field, everything else (arrays, numbers, null) replaces."""
    if isinstance(base, dict) and isinstance(over, dict):
        out = dict(base)
        for key, value in over.items():
            out[key] = merge(base[key], value) if key in base else value
        return out
    return over


def description(name):
    data = json.loads((ROOT / "cranes" / f"{name}.json").read_text())
    parent = data.pop("extends", None)
    return merge(description(parent), data) if parent else data


# ---------------------------------------------------------------- the independent model

class Mechanism:
    """Two pins across a joint (docs/knuckle-boom-arm.md): L(θ), dL/dθ and θ(L)."""

    def __init__(self, c):
        a, b = c["lower_pin"], c["upper_pin"]
        self.ra, self.rb = math.hypot(*a), math.hypot(*b)
        self.offset = math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])
        self.lmin = c["min_length"]

    def length(self, theta):
        psi = theta + self.offset
        length = math.sqrt(self.ra**2 + self.rb**2 - 2 * self.ra * self.rb * math.cos(psi))
        return length, self.ra * self.rb * math.sin(psi) / length

    def angle(self, length):
        return math.acos((self.ra**2 + self.rb**2 - length**2) / (2 * self.ra * self.rb)) - self.offset


def areas(drive):
    c = drive["cylinder"]
    a = math.pi * c["bore"] ** 2 / 4
    return c["count"] * a, c["count"] * (a - math.pi * c["rod"] ** 2 / 4)


def volumes(drive, x):
    c = drive["cylinder"]
    a = math.pi * c["bore"] ** 2 / 4
    b = a - math.pi * c["rod"] ** 2 / 4
    return c["count"] * (c["dead_volume"] + a * x), c["count"] * (c["dead_volume"] + b * (c["stroke"] - x))


def phi(dp, dpt):
    """H2's regularised square root."""
    return dp / (dp * dp + dpt * dpt) ** 0.25


def static_torques(cr, th2, th3, load):
    """Joint torques (boom, jib) holding the arm and `load` kg at the tip, level deck (N m)."""
    arm = cr["arm"]
    _, boom, jib = arm["links"]
    lb, lj, g = arm["boom_length"], arm["jib_length"], arm["g"]
    c2, c23 = math.cos(th2), math.cos(th2 + th3)
    t3 = g * (jib["mass"] * jib["com"] + load * lj) * c23
    return g * (boom["mass"] * boom["com"] + (jib["mass"] + load) * lb) * c2 + t3, t3


def cylinder_force(cr, name, joints, load):
    """Static rod force of the boom or jib cylinder (N, pushing) at joints (θ2, θ3)."""
    torque = static_torques(cr, *joints, load)[0 if name == "boom" else 1]
    theta = joints[0] if name == "boom" else joints[1]
    return torque / Mechanism(cr["arm"][f"{name}_cylinder"]).length(theta)[1]


def boom_inertia(cr, th2, th3, load):
    """The boom's inertia about its pivot with the jib locked and the load lumped at the tip,
    counted along the rope only (the README's load coupling): m ρ²."""
    arm = cr["arm"]
    _, boom, jib = arm["links"]
    lb, lj = arm["boom_length"], arm["jib_length"]
    cj = np.array([lb * math.cos(th2) + jib["com"] * math.cos(th2 + th3),
                   lb * math.sin(th2) + jib["com"] * math.sin(th2 + th3)])
    rho = lb * math.cos(th2) + lj * math.cos(th2 + th3)
    return (boom["transverse"] + boom["mass"] * boom["com"] ** 2 + jib["transverse"]
            + jib["mass"] * cj @ cj + load * rho**2)


def omega_h13(cr, x, m_eff):
    aa, ab = areas(cr["boom"])
    va, vb = volumes(cr["boom"], x)
    return math.sqrt(cr["oil"]["bulk_modulus"] * (aa**2 / va + ab**2 / vb) / m_eff)


def linear_arm(cr, th2, th3, xb, xj, load):
    """M, C, K of the linearised boom-jib-drum system about a rest, and the generalised force of
    a unit rope force at the tip (q = θ2, θ3, φ)."""
    arm = cr["arm"]
    _, boom, jib = arm["links"]
    lb, lj = arm["boom_length"], arm["jib_length"]
    winch, beta = cr["winch"], cr["oil"]["bulk_modulus"]
    motor, r = winch["drive"], winch["drum_radius"]
    ij, mj, cj = jib["transverse"], jib["mass"], jib["com"]
    m11 = boom["transverse"] + boom["mass"] * boom["com"] ** 2 + ij + mj * (lb**2 + cj**2 + 2 * lb * cj * math.cos(th3))
    m12 = ij + mj * (cj**2 + lb * cj * math.cos(th3))
    m22 = ij + mj * cj**2
    # g = Jᵀe: the tip's motion along the rope (down) per joint rate
    g = -np.array([lb * math.cos(th2) + lj * math.cos(th2 + th3), lj * math.cos(th2 + th3)])
    mass = np.zeros((3, 3))
    mass[:2, :2] = np.array([[m11, m12], [m12, m22]]) + load * np.outer(g, g)
    mass[:2, 2] = mass[2, :2] = load * r * g
    mass[2, 2] = winch["inertia"] + load * r * r
    stiff, damp = [], []
    for name, theta, x in (("boom", th2, xb), ("jib", th3, xj)):
        d = cr[name]
        aa, ab = areas(d)
        va, vb = volumes(d, x)
        lever = Mechanism(arm[f"{name}_cylinder"]).length(theta)[1]
        c = d["cylinder"]
        stiff.append(beta * (aa**2 / va + ab**2 / vb) * lever**2)                       # H13
        damp.append(c["count"] * (c["viscous"] + c["coulomb"] / c["coulomb_speed"]) * lever**2)
    n, disp, vline = motor["gear"], motor["displacement"], motor["line_volume"]
    stiff.append(beta * (n * disp) ** 2 * 2 / vline)                                     # H14
    damp.append(n * n * (motor["viscous"] + motor["coulomb"] / motor["coulomb_speed"]))
    brake = motor.get("brake")
    if brake:  # H18: the valves are centred, so the brake is applied; far below its holding torque
        # the Dahl element is the spring k_b with the damper c_b on the drum
        stiff[-1] += brake["stiffness"]
        damp[-1] += brake["damping"]
    return mass, np.diag(damp), np.diag(stiff), np.append(g, r)


def linear_step_response(cr, rest, load, force_step, lever, duration):
    """The boom stroke's response (m) to a rope force step, sampled every H."""
    mass, damp, stiff, f = linear_arm(cr, *rest, load)
    mi = np.linalg.inv(mass)
    a = np.block([[np.zeros((3, 3)), np.eye(3)], [-mi @ stiff, -mi @ damp]])
    b = np.concatenate([np.zeros(3), mi @ f * force_step])
    # exact zero-order-hold discretisation of ẋ = A x + b
    aug = np.zeros((7, 7))
    aug[:6, :6], aug[:6, 6] = a * H, b * H
    step = expm(aug)
    x, out = np.zeros(6), [0.0]
    for _ in range(int(round(duration / H))):
        x = step[:6, :6] @ x + step[:6, 6]
        out.append(lever * x[0])
    return np.array(out)


def damped_sine_fit(t, x, omega_guess):
    """ω_n = sqrt(ω_d² + σ²) of c + a e^(−σt) sin(ω_d t + φ) fitted to x(t)."""
    def f(t, c, a, sigma, wd, ph):
        return c + a * np.exp(-sigma * t) * np.sin(wd * t + ph)

    best = None
    for w in (0.7 * omega_guess, 0.85 * omega_guess, omega_guess, 1.15 * omega_guess):
        for ph in (0.0, 1.5, 3.0):
            try:
                p, _ = curve_fit(f, t, x, p0=[x[-1], np.ptp(x) / 2, 2.0, w, ph], maxfev=20000)
            except RuntimeError:
                continue
            residual = np.sum((f(t, *p) - x) ** 2)
            if p[3] > 0 and (best is None or residual < best[0]):
                best = (residual, p)
    return math.hypot(best[1][3], best[1][2])


def valve_leak(valve, supply, p_line):
    """H3's laminar leakage into a fully opened meter-in line: + C_P (p_S − p), − C_T (p − p_T)."""
    return valve["leak_supply"] * (supply["pressure"] - p_line) - valve["leak_tank"] * (p_line - supply["tank"])


def retract_speed(cr, name, force):
    """Steady retracting speed (m/s, positive) of a cylinder at full spool under a pushing load
    `force` (N): the compensated meter-in on the rod side (H3), friction (H7), and the piston
    side draining through the counterbalance valve at its pilot (H6: p_B at rest through H6b, or
    H6c's commanded p_cmd at full spool), its port relief (H5) and the valve's A→T edge (H2, H3)
    in series. When that path drains more than the meter-in fills even at p_B = p_T (an
    overrunning load on a commanded valve), the rod side draws the difference through its
    make-up check (H5) below tank. Returns the speed with the spool's leakage, whether the CBV
    limits it (the compensator below its cap), and p_B."""
    d, ps, pt = cr[name], cr["supply"]["pressure"], cr["supply"]["tank"]
    valve, cyl, cbv, relief = d["valve"], d["cylinder"], d["holding"], d["relief"]
    aa, ab = areas(d)
    k = valve["rated_flow"] / math.sqrt(valve["rated_drop"])
    dpt = valve["transition"]

    def meter_in(p):
        return min(k * phi(ps - p, dpt), valve["max_flow"]) + valve_leak(valve, cr["supply"], p)

    def into_rod_side(pb):
        """Meter-in plus, below tank, the make-up check (H5)."""
        return meter_in(pb) + relief["makeup_gain"] * max(0.0, pt - pb)

    def through_cbv(pb):
        """What the piston side drains at rod-side pressure pb, minus what the speed asks."""
        v = into_rod_side(pb) / ab
        pa = (force + pb * ab - cyl["count"] * (cyl["viscous"] * v + cyl["coulomb"] * math.tanh(v / cyl["coulomb_speed"]))) / aa
        # H6: the poppet opens on k·p_A + R·π above its setting; π = p_B at steady speed (H6b),
        # or the commanded pilot p_cmd·|u| at |u| = 1 (H6c)
        pilot = cbv["command_pilot"] if cbv["command_pilot"] > 0 else pb
        opening = min(max((cbv["load_ratio"] * pa + cbv["pilot_ratio"] * pilot - cbv["setting"]) / cbv["opening_range"],
                          0.0), 1.0)
        kcb = cbv["rated_flow"] / math.sqrt(cbv["rated_drop"]) * opening
        # the massless line between the CBV and the valve: what the CBV passes, the A→T edge drains
        line = brentq(lambda p: kcb * phi(pa - p, dpt) - k * phi(p - pt, dpt) + valve_leak(valve, cr["supply"], p),
                      pt - 1e6, max(pa, pt) + 1e6)
        return kcb * phi(pa - line, dpt) + relief["gain"] * max(0.0, pa - relief["pressure"]) - aa * v

    # p_B rises until the counterbalance valve passes A_A/A_B times the meter-in flow; an
    # overrunning load pulls it below tank instead
    pb = brentq(through_cbv, pt - 1e6, ps) if through_cbv(pt) > 0 else brentq(through_cbv, pt, ps)
    return into_rod_side(pb) / ab, k * phi(ps - pb, dpt) < valve["max_flow"], pb


def rope_speed(cr, circuit):
    w = cr["winch"]
    motor = w["drive"]
    flow = w["pump"]["displacement"] * w["pump"]["speed"] if circuit == "Closed" else motor["valve"]["max_flow"]
    return flow / (motor["displacement"] * motor["gear"]) * w["drum_radius"]


# ---------------------------------------------------------------- the FMU

@pytest.fixture(scope="module")
def fmu():
    path = fmu_path("knuckle_boom")
    md = read_model_description(str(path))
    folder = extract(str(path))
    yield md, folder, {v.name: (v.valueReference, v.type) for v in md.modelVariables}
    shutil.rmtree(folder, ignore_errors=True)


def run(fmu, crane, outputs, stop, inputs=lambda t: {}, init=None, start=None, parameters=()):
    """Runs the crane for `stop` s. inputs(t) is held over [t, t + H); `init` is set before
    initialization (default: inputs(0)). Returns times, an array of outputs, the parameters."""
    md, folder, var = fmu
    s = FMU2Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=f"verify_{crane}")
    s.instantiate()
    s.setupExperiment(startTime=0.0, stopTime=stop)
    s.setString([var["crane"][0]], [crane])
    s.setBoolean([var["noise"][0]], [False])
    for name, value in (start or {}).items():
        ref, kind = var[name]
        (s.setInteger if kind == "Integer" else s.setReal)([ref], [value])

    def apply(u):
        if u:
            s.setReal([var[n][0] for n in u], [float(v) for v in u.values()])

    apply(init if init is not None else inputs(0.0))
    s.enterInitializationMode()
    s.exitInitializationMode()
    values = {p: s.getReal([var[p][0]])[0] for p in parameters}
    refs = [var[o][0] for o in outputs]
    rows = [s.getReal(refs)]
    n = int(round(stop / H))
    for k in range(n):
        apply(inputs(k * H))
        s.doStep(currentCommunicationPoint=k * H, communicationStepSize=H)
        rows.append(s.getReal(refs))
    s.terminate()
    s.freeInstance()
    return np.arange(n + 1) * H, np.array(rows), values


def ramp(t, rise=0.4):
    """The full-scale controller's spool ramp (5 1/s): full opening in 0.4 s."""
    return min(max(t / rise, 0.0), 1.0)


def mean_rate(t, x, t0, t1):
    """Least-squares slope of x over [t0, t1]: the mean speed, insensitive to a residual ripple."""
    w = (t >= t0) & (t <= t1)
    return np.polyfit(t[w], x[w], 1)[0]


def record(crane, item, fmu_value, model_value, unit, fmt="{:.5g}"):
    rel = fmu_value / model_value - 1 if model_value else float("nan")
    RESULTS.setdefault(crane, []).append((item, fmt.format(fmu_value), fmt.format(model_value), unit, rel))
    print(f"{crane}: {item}: FMU {fmt.format(fmu_value)} vs model {fmt.format(model_value)} {unit} ({rel:+.2%})")
    return rel


@pytest.fixture(scope="module", autouse=True)
def table():
    yield
    for crane, rows in RESULTS.items():
        print(f"\n{crane}\n| item | FMU | model | unit | FMU/model − 1 |\n| --- | --- | --- | --- | --- |")
        for item, f, m, unit, rel in rows:
            print(f"| {item} | {f} | {m} | {unit} | {rel:+.2%} |")


def gravity(cr):
    return cr["arm"]["g"]


# ---------------------------------------------------------------- 1. full-valve speeds

CHATTER = pytest.mark.xfail(strict=True, reason=(
    "model gap kept bit for bit: osp_derived's winch keeps the third wave's pilot-operated lowering "
    "valve, which chatters paying out at full spool (p_B -0.7...21 MPa unloaded) while the make-up "
    "valve adds flow, 10 % above the metered speed (docs/full-scale.md); the other cranes' "
    "counterbalance valve (docs/hydraulics.md H6) does not"))
SPEED_CASES = [pytest.param(crane, drive, sign, marks=CHATTER if (crane, drive, sign) == ("osp_derived", "winch", 1)
                            else ())
               for crane in CRANES for drive in ("boom", "jib", "slew", "winch") for sign in (1, -1)]


@pytest.mark.parametrize("crane, drive, sign", SPEED_CASES)
def test_full_valve_speed_unloaded(fmu, crane, drive, sign):
    cr = description(crane)
    supply = cr["supply"]
    circuit = cr["winch"]["circuit"]
    outputs = ["stroke.boom", "stroke.jib", "joint.slew", "lp", "joint.boom", "joint.jib",
               "p.boom.a", "p.boom.b", "p.jib.a", "p.jib.b", "p.slew.a", "p.slew.b", "p.winch.a", "p.winch.b"]
    column = {"boom": 0, "jib": 1, "slew": 2, "winch": 3}
    t, y, _ = run(fmu, crane, outputs, 3.0, lambda t: {f"spool.{drive}": sign * ramp(t)})
    measured = abs(mean_rate(t, y[:, column[drive]], 1.5, 3.0))
    p = {o: y[t >= 1.5, i].mean() for i, o in enumerate(outputs)}
    limited = False
    if drive in ("boom", "jib"):
        aa, ab = areas(cr[drive])
        valve = cr[drive]["valve"]
        unit = "m/s"
        if sign > 0:
            ideal = valve["max_flow"] / aa
            leaky = (valve["max_flow"] + valve_leak(valve, supply, p[f"p.{drive}.a"])) / aa
            label = f"{drive} cylinder extending"
        else:
            joints = (p["joint.boom"], p["joint.jib"])
            leaky, limited, pb = retract_speed(cr, drive, cylinder_force(cr, drive, joints, 0.0))
            ideal = leaky if limited else valve["max_flow"] / ab
            label = f"{drive} cylinder retracting" + (" (CBV-limited)" if limited else "")
            print(f"{crane}: {drive} retracting: model p_B {pb / 1e6:.3f} MPa, FMU {p[f'p.{drive}.b'] / 1e6:.3f} MPa")
            if limited:
                print(f"{crane}: {drive} retracting is limited by its counterbalance valve: rated.{drive}.retract, "
                      f"Q_max/A_B = {valve['max_flow'] / ab:.5f} m/s, is not reached")
    elif drive == "slew":
        motor = cr["slew"]
        nd = motor["displacement"] * motor["gear"]
        hi, lo = (p["p.slew.a"], p["p.slew.b"]) if sign > 0 else (p["p.slew.b"], p["p.slew.a"])
        ideal = motor["valve"]["max_flow"] / nd
        leaky = (motor["valve"]["max_flow"] + valve_leak(motor["valve"], supply, hi) - motor["leakage"] * (hi - lo)) / nd
        label, unit = f"slew rate {'+' if sign > 0 else '−'}", "rad/s"
    else:
        w = cr["winch"]
        motor = w["drive"]
        nd = motor["displacement"] * motor["gear"]
        ideal = rope_speed(cr, circuit)
        # hoisting (spool −1) feeds A; the leakages: H3 (open), H16 and the motor's H9
        hi, lo = (p["p.winch.a"], p["p.winch.b"]) if sign < 0 else (p["p.winch.b"], p["p.winch.a"])
        if circuit == "Closed":
            flow = w["pump"]["displacement"] * w["pump"]["speed"] - (w["pump"]["leakage"] + motor["leakage"]) * (hi - lo)
        else:
            flow = motor["valve"]["max_flow"] + valve_leak(motor["valve"], supply, hi) - motor["leakage"] * (hi - lo)
        leaky = flow / nd * w["drum_radius"]
        label, unit = f"rope {'hoisting' if sign < 0 else 'paying out'} ({circuit.lower()} circuit)", "m/s"
    record(crane, label, measured, ideal, unit)
    assert measured == pytest.approx(leaky, rel=3e-3), f"{label}: with the leakages {leaky:.6g}"
    assert measured == pytest.approx(ideal, rel=1.5e-2), label


# ---------------------------------------------------------------- 2. holding pressures

@pytest.mark.parametrize("crane", CRANES)
def test_holding_pressures_after_a_boom_move(fmu, crane):
    cr = description(crane)
    load = cr["rating"]["safe_working_load"]
    f0 = load * gravity(cr)
    outputs = ["joint.boom", "joint.jib", "p.boom.a", "p.boom.b", "p.jib.a", "p.jib.b", "tension", "stroke.boom", "stroke.jib"]

    def spool(t):
        return {"cable.f0z": f0, "cable.mass": load, "spool.boom": 0.6 * ramp(t) if t < 2.0 else 0.0}

    t, y, _ = run(fmu, crane, outputs, 10.0, spool)
    # the last second's mean: the rod side still drifts towards the centred valve's neutral
    # pressure through the spool's leakage, and the closed-circuit winch creeps
    last = dict(zip(outputs, y[t >= 9.0].mean(axis=0)))
    joints = (last["joint.boom"], last["joint.jib"])
    assert abs(y[-1, 7] - y[0, 7]) > 0.005, "the boom did not move"
    assert np.ptp(y[t >= 9.0, 7]) < 5e-4, "the boom has not settled"
    # the mechanism: strokes are L(θ) − L_min
    for i, name in ((7, "boom"), (8, "jib")):
        mech = Mechanism(cr["arm"][f"{name}_cylinder"])
        assert y[-1, i] == pytest.approx(mech.length(y[-1, 0 if name == "boom" else 1])[0] - mech.lmin, abs=1e-9)
    assert last["tension"] == pytest.approx(f0, rel=1e-3)
    for name in ("boom", "jib"):
        aa, ab = areas(cr[name])
        force = cylinder_force(cr, name, joints, load)
        model = (force + last[f"p.{name}.b"] * ab) / aa
        record(crane, f"holding p.{name}.a", last[f"p.{name}.a"] / 1e6, model / 1e6, "MPa", "{:.4f}")
        assert last[f"p.{name}.a"] == pytest.approx(model, rel=1e-3)


# ---------------------------------------------------------------- 3. hydraulic natural frequency

STEP = 0.02  # of the rope force: the cylinder's speed stays far below the friction's v_s (H7)


@pytest.mark.parametrize("crane", CRANES)
def test_boom_hydraulic_frequency_at_three_strokes(fmu, crane):
    cr = description(crane)
    load = cr["rating"]["safe_working_load"]
    f0 = load * gravity(cr)
    mech = Mechanism(cr["arm"]["boom_cylinder"])
    stroke = cr["boom"]["cylinder"]["stroke"]
    outputs = ["stroke.boom", "stroke.jib", "joint.boom", "joint.jib"]
    duration = 1.5
    for fraction in (0.25, 0.5, 0.75):
        q0 = {"q0.boom": mech.angle(mech.lmin + fraction * stroke), "q0.jib": -math.pi / 3}
        t, y, _ = run(fmu, crane, outputs, duration, lambda t: {"cable.f0z": f0, "cable.mass": load},
                      init={"cable.f0z": (1 - STEP) * f0, "cable.mass": load}, start=q0)
        rest = (y[0, 2], y[0, 3], y[0, 0], y[0, 1])
        lever = mech.length(rest[0])[1]
        m_eff = boom_inertia(cr, rest[0], rest[1], load) / lever**2
        h13 = omega_h13(cr, rest[2], m_eff)
        model = linear_step_response(cr, rest, load, STEP * f0, lever, duration)
        w_model = damped_sine_fit(t, model, 0.8 * h13)
        w_fmu = damped_sine_fit(t, y[:, 0] - y[0, 0], w_model)
        print(f"{crane}: stroke {rest[2]:.3f} m: H13 with the load rigid in J = {h13:.2f} rad/s "
              f"(m_eff {m_eff:.4g} kg, lever {lever:.4f} m)")
        record(crane, f"ω_h at stroke {rest[2]:.2f} m", w_fmu, w_model, "rad/s", "{:.2f}")
        assert w_fmu == pytest.approx(w_model, rel=0.03)


# ---------------------------------------------------------------- 4. rated load hoisting

@pytest.mark.parametrize("crane", CRANES)
def test_hoisting_the_rated_load(fmu, crane):
    cr = description(crane)
    load = cr["rating"]["safe_working_load"]
    g = gravity(cr)
    w = cr["winch"]
    motor, circuit, r = w["drive"], w["circuit"], w["drum_radius"]
    n, disp = motor["gear"], motor["displacement"]
    outputs = ["lp", "p.winch.a", "p.winch.b", "tension", "drum.rate"]
    t, y, par = run(fmu, crane, outputs, 6.0,
                    lambda t: {"cable.f0z": load * g, "cable.mass": load, "spool.winch": -ramp(t, 1.5)},
                    start={"lp0": 40.0}, parameters=["winch.line_pull", "drum.radius"])
    sel = t >= 3.0
    speed = -mean_rate(t, y[:, 0], 3.0, 6.0)
    dp = (y[sel, 1] - y[sel, 2]).mean()
    tension = y[sel, 3].mean()
    omega_m = n * speed / r
    torque = tension * r / n + motor["viscous"] * omega_m + motor["coulomb"] * math.tanh(omega_m / motor["coulomb_speed"])
    dp_model = torque / disp
    if circuit == "Closed":
        flow = w["pump"]["displacement"] * w["pump"]["speed"] - (w["pump"]["leakage"] + motor["leakage"]) * dp
        working = w["pump"]["relief"]["pressure"]
    else:
        flow = motor["valve"]["max_flow"] + valve_leak(motor["valve"], cr["supply"], y[sel, 1].mean()) - motor["leakage"] * dp
        working = cr["supply"]["pressure"]
    speed_model = flow / (disp * n) * r
    record(crane, f"rope speed hoisting {load / 1000:g} t", speed, speed_model, "m/s")
    record(crane, "winch Δp hoisting", dp / 1e6, dp_model / 1e6, "MPa", "{:.3f}")
    print(f"{crane}: static Δp without friction {tension * r / n / disp / 1e6:.3f} MPa, tension {tension:.0f} N "
          f"(m g = {load * g:.0f} N), leak-free rope speed {rope_speed(cr, circuit):.4f} m/s")
    record(crane, "line pull at working pressure", par["winch.line_pull"] / 1e3,
           working * disp * n / r / 1e3, "kN", "{:.1f}")
    assert tension == pytest.approx(load * g, rel=5e-3)
    assert speed == pytest.approx(speed_model, rel=1e-2)
    assert speed == pytest.approx(rope_speed(cr, circuit), rel=2e-2)
    assert dp == pytest.approx(dp_model, rel=1e-2)
    assert par["winch.line_pull"] == pytest.approx(working * disp * n / r, rel=1e-9)


# ---------------------------------------------------------------- lowering the boom under load

@pytest.mark.parametrize("crane", CRANES)
def test_boom_lowers_the_rated_load_with_a_taut_rope(fmu, crane):
    """The counterbalance valve meters a lowering boom smoothly: the tension stays near m g, and
    the rod side stays above the oil's vapour pressure (about −0.1 MPa gauge)."""
    cr = description(crane)
    load = cr["rating"]["safe_working_load"]
    f0 = load * gravity(cr)
    t, y, _ = run(fmu, crane, ["tension", "p.boom.a", "p.boom.b"], 5.0,
                  lambda t: {"cable.f0z": f0, "cable.mass": load, "spool.boom": -0.3 * ramp(t)})
    w = t >= 2.0
    print(f"{crane}: lowering the boom at spool -0.3 with {load / 1000:g} t: tension "
          f"{y[w, 0].min() / 1e3:.1f}-{y[w, 0].max() / 1e3:.1f} kN, p_A {y[w, 1].min() / 1e6:.2f}-{y[w, 1].max() / 1e6:.2f} MPa, "
          f"p_B {y[w, 2].min() / 1e6:.2f}-{y[w, 2].max() / 1e6:.2f} MPa")
    assert y[w, 0].min() > 0.8 * f0 and y[w, 0].max() < 1.2 * f0
    assert y[w, 2].min() > -0.1e6

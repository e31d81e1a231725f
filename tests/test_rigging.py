"""The hook-and-load rigging (physics::rigging, run through the physics crate's `rigging_run`
example) against an independent SciPy model written from docs/rigging.md's equations, in a
different formulation: Cartesian vectors relative to the tip (W axes, the tip's acceleration as
an inertial force) — a rigid rope's unit vector n with |n| = 1 held by a Lagrange multiplier, an
elastic rope's chord — Newton's law on each body, the rigid ropes' tensions as the multipliers of
their length constraints, the elastic ropes' tension T = max(0, k δ + β k δ̇) with k = EA/l₀, and
the thesis' linear drag across the rope each body hangs from (§7.2.3, docs/rigging.md "Drag"). The Rust model uses the ropes' X–Y angles (rigid)
or chords (elastic) and Kane's equations, so a misreading of the angles' kinematics would not be
shared. Both take the hoist length, its rate and its acceleration as the inputs give them.

Three 60 s runs at test scale with a moving tip and a changing hoist length: the double pendulum
on rigid ropes, an elastic hoist rope with a rigid sling, both elastic. Both sides see the same
inputs: each ramped linearly over a 10 ms step between samples of analytic signals. solve_ivp
(DOP853, rtol 1e-11) restarts at every step, where the ramps kink. The figure of merit is the load
position's RMSD over all steps, asserted ≤ 1e-6 m (issue: "load position RMSD ≤ 1e-6 m over 60 s
with a moving tip and a changing hoist length").
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from conftest import physics_example

H = 0.01
DURATION = 60.0
TIP = {"tip_amplitude": [0.05, 0.04, 0.02], "tip_omega": [1.5, 2.0, 2.5],
       "lp0": 0.7, "lp_amplitude": 0.1, "lp_omega": 0.8,
       "hoist_angles": [0.2, -0.15], "sling_angles": [-0.1, 0.25], "duration": DURATION, "step": H}
LOAD = {"mass": 0.2, "kappa_x": 0.0272, "kappa_y": 0.018, "g": 9.80665}
# Bounce of 0.3 kg on 0.7 m at about 30 rad/s (k = m ω²), lightly damped (ζ = β ω / 2 ≈ 3 %).
HOIST_ELASTIC = {"Elastic": {"ea": 190.0, "damping_time": 0.002}}
SLING_ELASTIC = {"Elastic": {"ea": 60.0, "damping_time": 0.001}}
CASES = {
    "rigid rope, rigid sling": ("Rigid", "Rigid"),
    "elastic rope, rigid sling": (HOIST_ELASTIC, "Rigid"),
    "elastic rope, elastic sling": (HOIST_ELASTIC, SLING_ELASTIC),
}


def rust_run(request):
    return physics_example("rigging_run", request)


class Inputs:
    """The tip's motion and the hoist length as both models see them: the analytic signals
    sampled every H and ramped linearly within each step (docs/rigging.md, Integration)."""

    def __init__(self, p):
        self.a, self.w = np.array(p["tip_amplitude"]), np.array(p["tip_omega"])
        self.l0, self.la, self.lw = p["lp0"], p["lp_amplitude"], p["lp_omega"]

    def exact(self, t):
        s, c = np.sin(self.w * t), np.cos(self.w * t)
        ls, lc = np.sin(self.lw * t), np.cos(self.lw * t)
        return (self.a * s, self.a * self.w * c, -self.a * self.w ** 2 * s,
                self.l0 + self.la * ls, self.la * self.lw * lc, -self.la * self.lw ** 2 * ls)

    def ramped(self, t, t0):
        start, end = self.exact(t0), self.exact(t0 + H)
        f = (t - t0) / H
        return tuple(a + (b - a) * f for a, b in zip(start, end))


class Model:
    """The rigging in W axes relative to the tip (a frame translating with the tip, so the inertial
    force −m a_t acts on each body). Each rope's coordinates: a rigid rope's unit vector n (3
    numbers kept on |n| = 1 by a Lagrange multiplier, the chord l n), an elastic rope's chord s.
    The unknowns of every instant — both coordinate accelerations and the rigid ropes' tensions —
    solve one linear system: Newton's law on hook and load and |n|'s second derivative."""

    def __init__(self, params):
        self.mh, self.ml = params["hook_mass"], params["load"]["mass"]
        self.kh, self.kx, self.ky = params["hook_drag"], params["load"]["kappa_x"], params["load"]["kappa_y"]
        self.g = params["load"]["g"]
        self.ls = params["sling_length"]
        self.hoist, self.sling = params["hoist"], params["sling"]

    @staticmethod
    def across(e):
        """ê_x, ê_y: the unit directions in which a rope's θx and θy move its lower end, from the
        rope's unit vector e = (sin θy, −cos θy sin θx, cos θy cos θx)."""
        cy = np.hypot(e[1], e[2])
        sy, sx, cx = e[0], -e[1] / cy, e[2] / cy
        return np.array([0.0, -cx, -sx]), np.array([cy, sy * sx, -sy * cx])

    def drag(self, m, v, e, kx, ky):
        ex, ey = self.across(e)
        return -m * (kx * v.dot(ex) * ex + ky * v.dot(ey) * ey)

    @staticmethod
    def elastic(law, s, sd, l0, l0d):
        r = np.linalg.norm(s)
        e = s / r
        k = law["Elastic"]["ea"] / l0
        return max(0.0, k * (r - l0) + law["Elastic"]["damping_time"] * k * (e.dot(sd) - l0d))

    def kinematics(self, y, lp, lpd):
        """Hook and load relative to the tip (positions, velocities) and the ropes' unit vectors."""
        q1, q1d, q2, q2d = y[0:3], y[3:6], y[6:9], y[9:12]
        if self.hoist == "Rigid":
            rh, rhd = lp * q1, lpd * q1 + lp * q1d
        else:
            rh, rhd = q1, q1d
        if self.sling == "Rigid":
            rl, rld = rh + self.ls * q2, rhd + self.ls * q2d
        else:
            rl, rld = rh + q2, rhd + q2d
        return rh, rhd, rl, rld, rh / np.linalg.norm(rh), (rl - rh) / np.linalg.norm(rl - rh)

    def rhs(self, t, y, inputs, t0):
        _, vt, at, lp, lpd, lpdd = inputs.ramped(t, t0)
        q1d, q2d = y[3:6], y[9:12]
        rh, rhd, rl, rld, e1, e2 = self.kinematics(y, lp, lpd)
        z = np.array([0.0, 0.0, self.g])
        fh = self.mh * (z - at) + self.drag(self.mh, vt + rhd, e1, self.kh, self.kh)
        fl = self.ml * (z - at) + self.drag(self.ml, vt + rld, e2, self.kx, self.ky)
        if self.hoist != "Rigid":
            fh = fh - self.elastic(self.hoist, rh, rhd, lp, lpd) * e1
        if self.sling != "Rigid":
            t2 = self.elastic(self.sling, rl - rh, rld - rhd, self.ls, 0.0)
            fh, fl = fh + t2 * e2, fl - t2 * e2
        # r̈_h = P1 q̈1 + c1, r̈_l = r̈_h + P2 q̈2: a rigid rope's chord l n has
        # (l n)'' = l n̈ + 2 l̇ ṅ + l̈ n; an elastic rope's chord is its coordinate.
        rigid1, rigid2 = self.hoist == "Rigid", self.sling == "Rigid"
        p1 = lp if rigid1 else 1.0
        c1 = lpdd * y[0:3] + 2 * lpd * q1d if rigid1 else np.zeros(3)
        p2 = self.ls if rigid2 else 1.0
        n = 6 + rigid1 + rigid2
        a, b = np.zeros((n, n)), np.zeros(n)
        eye = np.eye(3)
        # m_h r̈_h + T1 e1 − T2 e2 = F_h;  m_l r̈_l + T2 e2 = F_l;  n·n̈ = −|ṅ|² per rigid rope.
        a[0:3, 0:3], b[0:3] = self.mh * p1 * eye, fh - self.mh * c1
        a[3:6, 0:3], a[3:6, 3:6], b[3:6] = self.ml * p1 * eye, self.ml * p2 * eye, fl - self.ml * c1
        row = 6
        if rigid1:
            a[0:3, row] = e1
            a[row, 0:3], b[row] = y[0:3], -q1d.dot(q1d)
            row += 1
        if rigid2:
            a[0:3, row], a[3:6, row] = -e2, e2
            a[row, 3:6], b[row] = y[6:9], -q2d.dot(q2d)
        x = np.linalg.solve(a, b)
        return np.concatenate([q1d, x[0:3], q2d, x[3:6]])

    def start(self, inputs, hook, load):
        """The coordinates and rates of a start given as hook and load positions and velocities
        in W."""
        xt, vt, _, lp, lpd, _ = inputs.exact(0.0)
        rh, rhd = np.array(hook["pos"]) - xt, np.array(hook["vel"]) - vt
        rl, rld = np.array(load["pos"]) - xt, np.array(load["vel"]) - vt
        if self.hoist == "Rigid":
            q1 = rh / lp
            q1d = (rhd - lpd * q1) / lp
        else:
            q1, q1d = rh, rhd
        q2, q2d = (rl - rh, rld - rhd) if self.sling != "Rigid" else ((rl - rh) / self.ls, (rld - rhd) / self.ls)
        return np.concatenate([q1, q1d, q2, q2d])


def scipy_loads(model, inputs, start, steps):
    """Load positions in W at every step end, from the Rust model's start (hook and load at rest
    relative to the tip at the given rope angles)."""
    y = model.start(inputs, start["hook"], start["load"])
    loads = []
    for k in range(steps):
        t0 = k * H
        sol = solve_ivp(model.rhs, (t0, t0 + H), y, method="DOP853", rtol=1e-11, atol=1e-13, args=(inputs, t0))
        assert sol.success, sol.message
        y = sol.y[:, -1]
        xt, _, _, lp, lpd, _ = inputs.ramped(t0 + H, t0)
        loads.append(xt + model.kinematics(y, lp, lpd)[2])
    return np.array(loads)


@pytest.mark.parametrize("case", CASES)
def test_the_rigging_matches_an_independent_cartesian_scipy_model(case):
    hoist, sling = CASES[case]
    params = {"load": LOAD, "hook_mass": 0.1, "hook_drag": 0.018, "sling_length": 0.2,
              "hoist": hoist, "sling": sling}
    out = rust_run({**TIP, "params": params})
    rust = np.array(out["load"])
    reference = scipy_loads(Model(out["input"]["params"]), Inputs(out["input"]), out["start"], len(rust))
    rmsd = float(np.sqrt(np.mean(np.sum((rust - reference) ** 2, axis=1))))
    travel = float(np.ptp(rust, axis=0).max())
    slack = sum(1 for t in out["hoist_tension"] if t <= 0.0)
    print(f"\n{case}: load RMSD {rmsd:.2e} m over {DURATION:g} s (load range {travel:.3f} m, "
          f"hoist tension {min(out['hoist_tension']):.3f}..{max(out['hoist_tension']):.3f} N, slack steps {slack})")
    assert travel > 0.05, "the tip and the hoist length move the load"
    assert rmsd <= 1e-6

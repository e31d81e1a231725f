"""The hydraulic test rig (physics::hydraulics::rig, run through the physics crate's
`hydraulic_drive` example) against an independent SciPy model written from the equations of
docs/hydraulics.md: H1 (spool deadband), H2 (regularised turbulent orifice), H3 (4/3 critical-centre
valve with compensated meter-in and laminar spool leakage), H4 (chamber pressure build-up), H5 (port
relief and make-up), H6 (counterbalance valve in series with the valve, solved exactly at the
massless line node) with its pilot lag H6b, H7 (rod force with friction and end stops) and Newton's
law on the mass.

One 20 s run with a 100 t load: hold, extend (a ramp through the deadband), hold, retract (opening
the counterbalance valve), hold. solve_ivp (DOP853, rtol 1e-10) integrates between the program's
breakpoints; the Rust side is fixed-step RK4. The figure of merit is the relative RMS difference
RMS(rust - scipy) / RMS(scipy) of the stroke and both pressures (samples every 10 ms), asserted
≤ 1e-6 at the crane FMU's 1 ms substep and ≤ 1e-7 at 0.1 ms (RK4's fourth order: the 1 ms error is
90-340 times the 0.1 ms one, not 10^4, because the right-hand side has kinks: deadband, meter-in
cap, check valve and counterbalance opening).
"""

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from conftest import physics_example

SEQUENCE = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.6], [5.0, 0.6], [6.0, 0.0], [9.0, 0.0], [10.0, -0.5],
            [13.0, -0.5], [14.0, 0.0], [20.0, 0.0]]
DURATION = 20.0
SAMPLE_INTERVAL = 0.01


def rig_example(request):
    return physics_example("hydraulic_drive", request)


class Model:
    """The valve-cylinder-mass rig from the documented equations; `p` is the rig's parameter JSON."""

    def __init__(self, p):
        d, c, v = p["drive"], p["drive"]["cylinder"], p["drive"]["valve"]
        self.beta = p["oil"]["bulk_modulus"]
        self.ps, self.pt = p["supply"]["pressure"], p["supply"]["tank"]
        self.m, self.g, self.f_ext = p["mass"], p["gravity"], p["external_force"]
        self.area_a = np.pi * c["bore"] ** 2 / 4                       # H4
        self.area_b = self.area_a - np.pi * c["rod"] ** 2 / 4          # H4
        self.stroke, self.v_dead = c["stroke"], c["dead_volume"]
        self.b, self.fc, self.vs = c["viscous"], c["coulomb"], c["coulomb_speed"]
        self.k_stop, self.c_stop = c["stop_stiffness"], c["stop_damping"]
        self.k = v["rated_flow"] / np.sqrt(v["rated_drop"])            # H2
        self.dead, self.dpt, self.q_max = v["deadband"], v["transition"], v["max_flow"]
        self.c_p, self.c_t = v["leak_supply"], v["leak_tank"]
        self.cbv = d["holding"]
        self.relief = d["relief"]

    def phi(self, dp):                                                 # H2
        return dp / (dp * dp + self.dpt ** 2) ** 0.25

    def u_eff(self, u):                                                # H1
        u = min(max(u, -1.0), 1.0)
        return np.sign(u) * max(0.0, abs(u) - self.dead) / (1.0 - self.dead)

    def valve_into_line(self, p_line, o_in, o_out):                    # H3: net flow into a service line
        meter_in = min(max(self.k * o_in * self.phi(self.ps - p_line), 0.0), o_in * self.q_max)
        meter_out = self.k * o_out * self.phi(p_line - self.pt)
        return meter_in + self.c_p * (self.ps - p_line) - meter_out - self.c_t * (p_line - self.pt)

    def pilot(self, pb, lagged):                                       # H6b: what the poppet sees
        return lagged if self.cbv is not None and self.cbv["pilot_lag"] > 0.0 else pb

    def pilot_rate(self, pb, lagged):                                  # H6b: dπ/dt = (p_B − π)/τ
        if self.cbv is None or self.cbv["pilot_lag"] == 0.0:
            return 0.0
        return (pb - lagged) / self.cbv["pilot_lag"]

    def flow_a(self, pa, pilot, o):                                    # H3 + H6 on port A
        o_in, o_out = max(o, 0.0), max(-o, 0.0)
        q_open = self.valve_into_line(pa, o_in, o_out)
        if self.cbv is None or q_open >= 0.0:
            return q_open                                              # check valve passes (or no CBV)
        cbv = self.cbv
        o_cb = min(max((cbv["load_ratio"] * pa + cbv["pilot_ratio"] * pilot - cbv["setting"]) / cbv["opening_range"], 0.0), 1.0)
        k_cb = cbv["rated_flow"] / np.sqrt(cbv["rated_drop"]) * o_cb
        if k_cb == 0.0:
            return 0.0

        def balance(p_line):
            return self.valve_into_line(p_line, o_in, o_out) + k_cb * self.phi(pa - p_line)

        low, step = min(self.pt, pa - 1.0), 1e5
        while balance(low) < 0.0:
            low, step = low - step, 2 * step
        p_line = brentq(balance, low, pa, xtol=1e-10, rtol=4 * np.finfo(float).eps, maxiter=500)
        return -k_cb * self.phi(pa - p_line)

    def port_relief(self, p):                                          # H5: net flow into a chamber
        r = self.relief
        full = r["pressure"] + r["rated_flow"] / r["gain"]             # finite capacity: orifice above p_full
        out = r["gain"] * max(0.0, p - r["pressure"]) if p <= full else r["rated_flow"] * math.sqrt(p / full)
        return -out + r["makeup_gain"] * max(0.0, self.pt - p)

    def stop_force(self, x, v):                                        # H7 end stops
        if x < 0.0:
            return max(0.0, -self.k_stop * x - self.c_stop * v)
        if x > self.stroke:
            return min(0.0, -self.k_stop * (x - self.stroke) - self.c_stop * v)
        return 0.0

    def rhs(self, u, y):
        x, v, pa, pb, lagged = y
        o = self.u_eff(u)
        qa = self.flow_a(pa, self.pilot(pb, lagged), o) + self.port_relief(pa)
        qb = self.valve_into_line(pb, max(-o, 0.0), max(o, 0.0)) + self.port_relief(pb)
        floor = 0.01 * self.v_dead
        va = max(self.v_dead + self.area_a * x, floor)
        vb = max(self.v_dead + self.area_b * (self.stroke - x), floor)
        dpa = self.beta / va * (qa - self.area_a * v)                  # H4
        dpb = self.beta / vb * (qb + self.area_b * v)                  # H4
        friction = self.b * v + self.fc * np.tanh(v / self.vs)
        force = pa * self.area_a - pb * self.area_b - friction + self.stop_force(x, v)   # H7
        return [v, (force - self.m * self.g + self.f_ext) / self.m, dpa, dpb, self.pilot_rate(pb, lagged)]


def spool(t):
    times, values = zip(*SEQUENCE)
    return float(np.interp(t, times, values))


def scipy_run(model, y0, t_eval):
    """The model at `t_eval`, integrated piece by piece between the spool program's breakpoints
    (where u(t) has kinks)."""
    breaks = sorted({t for t, _ in SEQUENCE if 0.0 < t < DURATION} | {0.0, DURATION})
    scale = np.array([1e-12, 1e-12, 1e-4, 1e-4, 1e-4])
    pieces, y = [], np.array(y0, dtype=float)
    for t0, t1 in zip(breaks[:-1], breaks[1:]):
        last = t1 == DURATION
        inside = t_eval[(t_eval >= t0) & ((t_eval <= t1) if last else (t_eval < t1))]
        times = inside if last and inside.size and inside[-1] == t1 else np.append(inside, t1)
        sol = solve_ivp(lambda t, y: model.rhs(spool(t), y), (t0, t1), y, method="DOP853",
                        t_eval=times, rtol=1e-10, atol=scale, max_step=0.01)
        assert sol.success, sol.message
        pieces.append(sol.y[:, :inside.size])
        y = sol.y[:, -1]
    return np.hstack(pieces)


def relative_rms(rust, reference):
    return float(np.sqrt(np.mean((rust - reference) ** 2)) / np.sqrt(np.mean(reference ** 2)))


def test_the_rig_matches_an_independent_scipy_model():
    results = {}
    reference = None
    for substep in (1e-3, 1e-4):
        every = int(round(SAMPLE_INTERVAL / substep))
        out = rig_example({"program": SEQUENCE, "duration": DURATION, "stroke": 0.6,
                           "record_every": every, "rig": {"substep": substep}})
        t = np.array(out["t"])
        rust = np.array([out["pos"], out["vel"], out["p_a"], out["p_b"], out["pilot"]])
        if reference is None:
            init = out["initial"]
            model = Model(out["rig"])
            reference = scipy_run(model, [init["pos"], init["vel"], init["p_a"], init["p_b"], init["pilot"]], t)
            cbv = np.array(out["cbv_opening"])
            print(f"\nrun: x {rust[0, 0]:.4f} -> max {rust[0].max():.4f} -> {rust[0, -1]:.4f} m, p_A "
                  f"{rust[2].min() * 1e-6:.2f}..{rust[2].max() * 1e-6:.2f} MPa, p_B {rust[3].min() * 1e-6:.2f}.."
                  f"{rust[3].max() * 1e-6:.2f} MPa, CBV opening max {cbv.max():.3f}")
        errors = {name: relative_rms(rust[i], reference[i]) for i, name in ((0, "x"), (2, "p_A"), (3, "p_B"))}
        spans = {name: float(np.sqrt(np.mean((rust[i] - reference[i]) ** 2)) / np.ptp(reference[i]))
                 for i, name in ((0, "x"), (2, "p_A"), (3, "p_B"))}
        results[substep] = errors
        print(f"RK4 substep {substep * 1e3:g} ms: relative RMS " +
              ", ".join(f"{k} {v:.2e}" for k, v in errors.items()) +
              "; RMS / range " + ", ".join(f"{k} {v:.2e}" for k, v in spans.items()))
    assert max(results[1e-3].values()) <= 1e-6
    assert max(results[1e-4].values()) <= 1e-7

"""Independent NumPy/SciPy implementation of the pendulum FMU's equations, for cross-checks.

Thesis eqs. 4.131-4.132 (angles), 4.94-4.96 (load position) and the aerodynamic damping of
section 7.2.3: drag force -m*kx*(v.ex)*ex - m*ky*(v.ey)*ey on the load, with ex, ey the unit
directions in which theta_x and theta_y move it, applied as generalised forces. Written from the
equations, not from the Rust code; but a misreading of eqs. 4.131-4.132 shared with the code
would pass, which is why tests/test_pendulum_newton.py also checks Newton's law on the FMU's
outputs.
"""
import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665


def rhs(t, x, tip, kx, ky, g=G):
    """x = [theta_x, theta_y, omega_x, omega_y]; tip(t) -> (pos, vel, acc, lp, lp_dot, lp_ddot)."""
    thx, thy, wx, wy = x
    _, v_tip, a, lp, lpd, _ = tip(t)
    sx, cx, sy, cy = np.sin(thx), np.cos(thx), np.sin(thy), np.cos(thy)
    thx_dd = (-g * sx - 2 * cy * lpd * wx + 2 * lp * sy * wx * wy) / (cy * lp) + (a[1] * cx + a[2] * sx) / (cy * lp)
    thy_dd = (-cy * lp * sy * wx**2 - 2 * lpd * wy - cx * sy * g) / lp + (-a[0] * cy - a[1] * sx * sy + a[2] * cx * sy) / lp
    # Load velocity: derivative of eqs. 4.94-4.96.
    er = np.array([sy, -cy * sx, cx * cy])
    d_thx = np.array([0.0, -cy * cx, -cy * sx])
    d_thy = np.array([cy, sy * sx, -sy * cx])
    v = v_tip + lpd * er + lp * (d_thx * wx + d_thy * wy)
    ex, ey = d_thx / cy, d_thy
    thx_dd += -kx * v.dot(ex) / (lp * cy)
    thy_dd += -ky * v.dot(ey) / lp
    return [wx, wy, thx_dd, thy_dd]


def load_position(x, tip_pos, lp):
    thx, thy = x[0], x[1]
    return np.stack([
        tip_pos[0] + lp * np.sin(thy),
        tip_pos[1] - lp * np.cos(thy) * np.sin(thx),
        tip_pos[2] + lp * np.cos(thy) * np.cos(thx),
    ])


def simulate(x0, tip, t_eval, kx=0.0272, ky=0.018, breakpoints=(), segmented=False):
    """States at `t_eval` (rtol 1e-10, DOP853), restarting the integrator at input kinks.

    With `segmented`, `tip(t, a)` also receives the start `a` of the segment being integrated,
    so inputs that jump at breakpoints are evaluated from inside the segment at its ends."""
    edges = sorted({float(t_eval[0]), float(t_eval[-1]), *map(float, breakpoints)})
    x = np.asarray(x0, dtype=float)
    columns = [x[:, None]] if t_eval[0] == edges[0] else []
    for a, b in zip(edges[:-1], edges[1:]):
        inside = t_eval[(t_eval > a) & (t_eval < b)]
        t_seg = np.concatenate([[a], inside, [b]])
        seg_tip = (lambda t, a=a: tip(t, a)) if segmented else tip
        sol = solve_ivp(rhs, (a, b), x, method="DOP853", rtol=1e-10, atol=1e-12, t_eval=t_seg, args=(seg_tip, kx, ky))
        assert sol.success, sol.message
        columns.append(sol.y[:, 1:])
        x = sol.y[:, -1]
    states = np.concatenate(columns, axis=1)
    times = np.concatenate([[edges[0]], *[np.concatenate([t_eval[(t_eval > a) & (t_eval < b)], [b]]) for a, b in zip(edges[:-1], edges[1:])]])
    keep = np.isin(times, t_eval)
    return times[keep], states[:, keep]

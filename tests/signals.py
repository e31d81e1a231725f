"""Smooth, mutually consistent crane-tip and cable-length trajectories for driving the pendulum."""
import numpy as np

INPUTS = ["tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az", "lp", "lp_dot", "lp_ddot"]


def tip_motion(t):
    """(pos, vel, acc) of the tip in W (m, m/s, m/s²) and (lp, lp_dot, lp_ddot)."""
    pos = np.array([0.02 * np.sin(2.0 * t), -0.5 + 0.03 * np.sin(3.1 * t), -0.15 + 0.01 * np.cos(1.3 * t)])
    vel = np.array([0.04 * np.cos(2.0 * t), 0.093 * np.cos(3.1 * t), -0.013 * np.sin(1.3 * t)])
    acc = np.array([-0.08 * np.sin(2.0 * t), -0.2883 * np.sin(3.1 * t), -0.0169 * np.cos(1.3 * t)])
    lp = 0.7 + 0.1 * np.sin(0.4 * t)
    return pos, vel, acc, lp, 0.04 * np.cos(0.4 * t), -0.016 * np.sin(0.4 * t)


def channel(name):
    """The named input as a function of time."""
    index = INPUTS.index(name)
    group, axis = divmod(index, 3)

    def f(t):
        m = tip_motion(t)
        return m[group][axis] if group < 3 else m[3 + axis]

    return f


def table(times):
    """Structured array `time, <inputs>` as FMPy's `input=` and CSV writers expect."""
    dtype = [("time", float)] + [(n, float) for n in INPUTS]
    return np.array([(t, *[channel(n)(t) for n in INPUTS]) for t in times], dtype=dtype)

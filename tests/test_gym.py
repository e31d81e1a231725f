"""crane_cosim.gym.CraneEnv from the wheel (`cargo xtask wheel`), at test and full scale:
Gymnasium's own checker passes, a zero residual reproduces the campaign's compensated run bit for
bit, a random policy does measurably worse, resets are deterministic by seed, and the swing energy
of the reward is the pendulum's (checked by differentiating its position numerically).
"""
import json
import math
import time

import numpy
import pytest
from gymnasium.utils.env_checker import check_env

from test_python_package import crane_cosim, same_frames  # noqa: F401  (the wheel's fixture)


@pytest.fixture(scope="module")
def gym(crane_cosim):  # noqa: F811
    import crane_cosim.gym

    return crane_cosim.gym


def episode_return(env, policy, seed):
    observation, _ = env.reset(seed=seed)
    total, steps, done = 0.0, 0, False
    while not done:
        observation, reward, terminated, truncated, _ = env.step(policy(observation))
        total, steps, done = total + reward, steps + 1, terminated or truncated
    return total, steps


@pytest.mark.parametrize("action, scale", [("residual", "test"), ("command", "test"), ("residual", "full")])
def test_the_environment_passes_gymnasiums_checker(gym, action, scale):
    env = gym.CraneEnv(test=89, action=action, scale=scale)
    check_env(env, skip_render_check=True)
    env.close()


@pytest.mark.parametrize("scale", ["test", "full"])
def test_a_zero_residual_is_the_campaigns_run_bit_for_bit(crane_cosim, gym, scale):  # noqa: F811
    env = gym.CraneEnv(test=89, variant=2, sea="campaign", scale=scale)
    total, steps = episode_return(env, lambda observation: numpy.zeros(3), seed=0)
    assert steps == 12000  # the test's 120 s after the 10 s hold
    _, _, start, stop_time, _ = crane_cosim._native.campaign_run(89, 2, scale == "full")
    system = gym.FULL_SCALE_SYSTEM if scale == "full" else gym.SYSTEM
    reference = crane_cosim.run(system, start={name: json.loads(v) for name, v in start}, stop_time=stop_time)
    same_frames(env.simulation.results(), reference)
    print(f"089-2 at {scale} scale with a zero residual: return {total:.3f} over {steps} steps, the campaign's run bit for bit")
    env.close()


@pytest.mark.parametrize("scale", ["test", "full"])
def test_a_random_policy_does_measurably_worse(gym, scale):
    env = gym.CraneEnv(test=89, variant=2, sea="campaign", scale=scale)
    zero, _ = episode_return(env, lambda observation: numpy.zeros(3), seed=0)
    env.action_space.seed(1)
    random, _ = episode_return(env, lambda observation: env.action_space.sample(), seed=0)
    print(f"089-2 at {scale} scale, return: the law {zero:.3f}, with a uniformly random residual {random:.3f}")
    assert random < zero - 0.1 * abs(zero)
    env.close()


def test_the_full_scale_residual_acts_only_where_the_anti_sway_law_runs(gym):
    with pytest.raises(ValueError, match="test scale only"):
        gym.CraneEnv(test=89, action="command", scale="full")
    # 001: crane off (the arm's mode 0 at full scale).
    with pytest.raises(ValueError, match="anti-sway law"):
        gym.CraneEnv(test=1, scale="full")


def test_the_full_scale_estimates_are_what_the_control_software_reads(gym):
    # Truth feedback (no encoder noise): the control software's tip comes from the encoders'
    # 17 bits (within 0.5 mm at the tip of the ~20 m arm), the load's position is the pendulum's.
    # So the swing angles from the load relative to that tip are the pendulum's within
    # 0.5 mm / 17.5 m of rope, and the load and length errors are the truth's exactly.
    observed = [gym.CraneEnv(test=89, variant=1, sea="campaign", scale="full", observe=o) for o in ("estimates", "truth")]
    traces = []
    for env in observed:
        trace = [env.reset(seed=0)[0]]
        trace += [env.step(numpy.array([0.5, -0.5, 0.2]))[0] for _ in range(500)]
        traces.append(numpy.array(trace))
        env.close()
    estimates, truth = traces
    swing = numpy.abs(truth[:, :2]).max()
    difference = numpy.abs(estimates - truth).max(axis=0)
    print(f"full scale: swing up to {swing:.2e} rad; estimates - truth per observation: {difference}")
    assert swing > 1e-3  # a sign error in either angle would differ by twice the swing
    assert difference[:2].max() < 5e-5
    assert numpy.all(estimates[0, 2:4] == 0.0)  # no sample before the test: no first rate
    assert difference[4:7].max() == 0.0 and difference[10:].max() == 0.0
    assert difference[7:10].max() < 1e-3


def test_resets_are_deterministic_by_seed(gym):
    env = gym.CraneEnv(test=89, variant=2)
    traces = []
    for seed in (7, 7, 8):
        observation, _ = env.reset(seed=seed)
        trace = [observation]
        for _ in range(300):
            trace.append(env.step(numpy.array([0.2, -0.1, 0.0]))[0])
        traces.append(numpy.array(trace))
    assert traces[0].tobytes() == traces[1].tobytes()
    assert not numpy.array_equal(traces[0], traces[2])
    env.close()


def test_the_swing_energy_is_the_pendulums(gym):
    # The load relative to the tip, r = lp (sin ty, -cos ty sin tx, cos ty cos tx) (eqs. 4.94-4.96,
    # NED: z down), differentiated numerically along a motion through (tx, ty) at rates (wx, wy).
    lp, tx, ty, wx, wy, h = 0.7, 0.3, -0.2, 0.8, -0.5, 1e-6

    def position(t):
        x, y = tx + wx * t, ty + wy * t
        return numpy.array([math.sin(y), -math.cos(y) * math.sin(x), math.cos(y) * math.cos(x)]) * lp

    velocity = (position(h) - position(-h)) / (2 * h)
    expected = 0.5 * velocity @ velocity + 9.81 * (lp - position(0)[2])
    assert gym.swing_energy(tx, ty, wx, wy, lp) == pytest.approx(expected, rel=1e-8)
    assert gym.swing_energy(0.0, 0.0, 0.0, 0.0, lp) == 0.0
    numpy.testing.assert_allclose(gym.rope_angles(position(0), lp), [tx, ty], rtol=1e-12)


@pytest.mark.parametrize("scale", ["test", "full"])
def test_steps_per_second(gym, scale):
    env = gym.CraneEnv(test=89, variant=2, sea="campaign", scale=scale)
    env.reset(seed=0)
    began, steps = time.perf_counter(), 0
    while steps < 3000:
        env.step(numpy.zeros(3))
        steps += 1
    rate = steps / (time.perf_counter() - began)
    print(f"CraneEnv at {scale} scale: {rate:,.0f} environment steps per second (one core, measured, not asserted)")
    env.close()

"""crane_cosim.gym.CraneEnv from the wheel (`cargo xtask wheel`): Gymnasium's own checker passes,
a zero residual reproduces the campaign's compensated run bit for bit, a random policy does
measurably worse, resets are deterministic by seed, and the swing energy of the reward is the
pendulum's (checked by differentiating its position numerically).
"""
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


@pytest.mark.parametrize("action", ["residual", "command"])
def test_the_environment_passes_gymnasiums_checker(gym, action):
    env = gym.CraneEnv(test=89, action=action)
    check_env(env, skip_render_check=True)
    env.close()


def test_a_zero_residual_is_the_campaigns_run_bit_for_bit(crane_cosim, gym):  # noqa: F811
    env = gym.CraneEnv(test=89, variant=2, sea="campaign")
    total, steps = episode_return(env, lambda observation: numpy.zeros(3), seed=0)
    assert steps == 12000  # the test's 120 s after the 10 s hold
    _, _, start, stop_time, _ = crane_cosim._native.campaign_run(89, 2, False)
    reference = crane_cosim.run(gym.SYSTEM, start={name: __import__("json").loads(v) for name, v in start}, stop_time=stop_time)
    same_frames(env.simulation.results(), reference)
    print(f"089-2 with a zero residual: return {total:.3f} over {steps} steps, the campaign's run bit for bit")
    env.close()


def test_a_random_policy_does_measurably_worse(gym):
    env = gym.CraneEnv(test=89, variant=2, sea="campaign")
    zero, _ = episode_return(env, lambda observation: numpy.zeros(3), seed=0)
    env.action_space.seed(1)
    random, _ = episode_return(env, lambda observation: env.action_space.sample(), seed=0)
    print(f"089-2 return: thesis' law {zero:.3f}, with a uniformly random residual {random:.3f}")
    assert random < zero - 0.1 * abs(zero)
    env.close()


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


def test_steps_per_second(gym):
    env = gym.CraneEnv(test=89, variant=2, sea="campaign")
    env.reset(seed=0)
    began, steps = time.perf_counter(), 0
    while steps < 3000:
        env.step(numpy.zeros(3))
        steps += 1
    rate = steps / (time.perf_counter() - began)
    print(f"CraneEnv: {rate:,.0f} environment steps per second (one core, measured, not asserted)")
    env.close()

"""Trains stable-baselines3's PPO on crane_cosim's Gymnasium environment: a residual on top of the
thesis' anti-sway law (test 089: world-frame compensation, fixed set-point, ship profile 1, sensor
feedback), and compares the learnt policy with the zero residual (the thesis' law alone) on
held-out sea states. Not part of the test suite (it needs torch); docs/python.md says what it
reached when run.

    pip install target/wheels/crane_cosim-*.whl[gym] stable-baselines3
    python examples/train_ppo.py --steps 200000 --out out/ppo

Writes out/ppo/learning_curve.csv (episode, environment steps, return) and out/ppo/model.zip, and
prints the mean return of the zero residual and of the learnt policy over the evaluation seeds.
"""

import argparse
import csv
import pathlib

import numpy
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.monitor import Monitor

from crane_cosim.gym import CraneEnv


class LearningCurve(BaseCallback):
    """Collects each finished episode's return and the environment steps taken so far."""

    def __init__(self):
        super().__init__()
        self.rows = []

    def _on_step(self) -> bool:
        for info in self.locals.get("infos", []):
            if "episode" in info:
                self.rows.append((len(self.rows) + 1, self.num_timesteps, info["episode"]["r"]))
        return True


def evaluate(env, policy, seeds):
    """Mean and standard deviation of the return of `policy` over episodes seeded `seeds`."""
    returns = []
    for seed in seeds:
        observation, _ = env.reset(seed=seed)
        total, done = 0.0, False
        while not done:
            observation, reward, terminated, truncated, _ = env.step(policy(observation))
            total, done = total + reward, terminated or truncated
        returns.append(total)
    return float(numpy.mean(returns)), float(numpy.std(returns))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200_000, help="environment steps to train for")
    parser.add_argument("--test", type=int, default=89, help="campaign test of each episode")
    parser.add_argument("--seed", type=int, default=0, help="seed of PPO and the training sea states")
    parser.add_argument("--eval-seeds", type=int, default=5, help="held-out sea states to evaluate on")
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out/ppo"))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    env = Monitor(CraneEnv(test=args.test, variant=2, action="residual"))
    env.reset(seed=args.seed)
    model = PPO("MlpPolicy", env, n_steps=2048, batch_size=256, gamma=0.995, seed=args.seed, verbose=0)
    curve = LearningCurve()
    model.learn(total_timesteps=args.steps, callback=curve)
    model.save(args.out / "model.zip")
    with (args.out / "learning_curve.csv").open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["episode", "steps", "return"])
        writer.writerows(curve.rows)

    evaluation = CraneEnv(test=args.test, variant=2, action="residual")
    seeds = range(10_000, 10_000 + args.eval_seeds)  # sea states the training never drew from
    zero = evaluate(evaluation, lambda observation: numpy.zeros(3), seeds)
    learnt = evaluate(evaluation, lambda observation: model.predict(observation, deterministic=True)[0], seeds)
    print(f"return over {args.eval_seeds} held-out sea states (mean ± std):")
    print(f"  thesis' law (zero residual): {zero[0]:.3f} ± {zero[1]:.3f}")
    print(f"  PPO residual after {args.steps} steps: {learnt[0]:.3f} ± {learnt[1]:.3f}")


if __name__ == "__main__":
    main()

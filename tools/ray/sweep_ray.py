#!/usr/bin/env python3
"""Run a crane-cosim sweep study on a Ray cluster: one Ray task per case, then `sweep collect`.

Each task runs `crane-cosim sweep run STUDY -o OUT --case-index I` on whichever node Ray places
it; the case writes OUT/cases/<id>.json itself. The study, its scenario, system and FMUs, the
crane-cosim binary and OUT must therefore be at the same paths on every node: a shared file
system (NFS, a cluster file system, or one machine). That is the same contract as Slurm array
jobs and Kubernetes Indexed Jobs (docs/sweeps.md, "The case-index contract"): case files are
written whole through a rename, so tasks on several nodes can fill one folder, and the results
do not depend on where or in which order the cases ran. The driver checks the contract: a task
whose case file it cannot see afterwards counts as failed.

Failures are retried at two levels: Ray re-runs a task whose worker process or node died
(`--max-retries`), and the driver submits a case again when crane-cosim exits non-zero (a failed
case, a missing file), up to `--attempts` runs in all. Then it runs `crane-cosim sweep collect
OUT` (results.csv, results.parquet, plots/) and exits non-zero if a case still failed.

    python tools/ray/sweep_ray.py study.json -o out/study                    # a local Ray instance
    python tools/ray/sweep_ray.py study.json -o out/study --address auto     # the cluster of `ray start`
    python tools/ray/sweep_ray.py study.json -o out/study --address HEAD:6379 --attempts 3

Progress goes to standard output, one line per finished attempt: the case, its status, the Ray
node that ran it and the attempt number.
"""
from __future__ import annotations

import argparse
import csv
import io
import json
import pathlib
import subprocess
import sys
import time

import ray

import ray_driver


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = ray_driver.parser(__doc__, "study", "case")
    parser.add_argument("--max-retries", type=int, default=2,
                        help="Ray's re-runs of a task whose worker or node died")
    parser.add_argument("--plots", choices=["png", "svg", "none"], default="png", help="plots of `sweep collect`")
    return ray_driver.parse(parser, argv)


def plan(crane_cosim: str, study: pathlib.Path) -> list[str]:
    """The study's case ids in index order, from `crane-cosim sweep plan`."""
    text = subprocess.run([crane_cosim, "sweep", "plan", str(study)], check=True, capture_output=True,
                          text=True).stdout
    return [row["case"] for row in csv.DictReader(io.StringIO(text))]


def case_status(out: pathlib.Path, case_id: str) -> str:
    """The status in the case file as the driver sees it ("missing" if it cannot read it)."""
    try:
        return json.loads((out / "cases" / f"{case_id}.json").read_text())["status"]
    except (OSError, ValueError, KeyError):
        return "missing"


class Driver:
    """Reports each finished attempt of the cases and which failed on every one."""

    def __init__(self, args: argparse.Namespace, ids: list[str]):
        self.args, self.ids = args, ids
        self.study, self.out = str(args.study.resolve()), args.out.resolve()
        self.failed: list[int] = []
        self.nodes: set[str] = set()
        self.settled = 0

    def command(self, index: int) -> list[str]:
        return [self.args.crane_cosim, "sweep", "run", self.study, "-o", str(self.out), "--case-index", str(index),
                "--quiet"]

    def run(self) -> None:
        self.failed = ray_driver.run_with_retries(range(len(self.ids)), self.command, self.args.attempts,
                                                  self.settle, self.nodes, max_retries=self.args.max_retries)

    def settle(self, index: int, result: ray_driver.Result, attempt: int, last: bool) -> bool:
        """Reports an attempt; whether the case is done."""
        case_id = self.ids[index]
        status = case_status(self.out, case_id) if result["code"] == 0 else "failed"
        again = status != "done" and not last
        self.settled += not again
        print(f"[{self.settled}/{len(self.ids)}] case {case_id}: {status} on node {result['node']} (attempt {attempt})",
              flush=True)
        if status == "done":
            return True
        reason = ray_driver.reason(result, f"exit code {result['code']}")
        if status == "missing":
            reason = f"no case file in {self.out}: is the output folder shared by every node?"
        print(f"case {case_id}: {reason}" + ("; submitted again" if again else "; giving up"), flush=True)
        return False


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    ids = plan(args.crane_cosim, args.study)
    args.out.mkdir(parents=True, exist_ok=True)
    nodes, cpus = ray_driver.start(args.address)
    print(f"{len(ids)} cases on {nodes} Ray nodes ({cpus:g} CPUs)", flush=True)
    clock = time.monotonic()
    driver = Driver(args, ids)
    driver.run()
    wall = time.monotonic() - clock
    ray.shutdown()
    failed = ", ".join(ids[i] for i in sorted(driver.failed)) or "none"
    print(f"{len(ids)} cases in {wall:.1f} s on {len(driver.nodes)} nodes; failed: {failed}", flush=True)
    subprocess.run([args.crane_cosim, "sweep", "collect", str(args.out), "--plots", args.plots], check=True)
    return 1 if driver.failed else 0


if __name__ == "__main__":
    sys.exit(main())

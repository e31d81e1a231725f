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
import shutil
import subprocess
import sys
import time

import ray


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study", type=pathlib.Path, help="the study file (JSON)")
    parser.add_argument("-o", "--out", type=pathlib.Path, required=True, help="output folder (shared by all nodes)")
    parser.add_argument("--address", help="Ray cluster address (HOST:PORT or 'auto'); default: start a local Ray")
    parser.add_argument("--crane-cosim", default="crane-cosim",
                        help="the crane-cosim binary, at this path on every node [default: from PATH]")
    parser.add_argument("--attempts", type=int, default=3,
                        help="runs of a case at most, counting the first (a non-zero exit submits it again)")
    parser.add_argument("--max-retries", type=int, default=2,
                        help="Ray's re-runs of a task whose worker or node died")
    parser.add_argument("--plots", choices=["png", "svg", "none"], default="png", help="plots of `sweep collect`")
    args = parser.parse_args(argv)
    if args.attempts < 1:
        parser.error("--attempts must be at least 1")
    # Absolute: Ray's workers do not run in this directory.
    found = shutil.which(args.crane_cosim)
    args.crane_cosim = str(pathlib.Path(found or args.crane_cosim).resolve())
    return args


def plan(crane_cosim: str, study: pathlib.Path) -> list[str]:
    """The study's case ids in index order, from `crane-cosim sweep plan`."""
    text = subprocess.run([crane_cosim, "sweep", "plan", str(study)], check=True, capture_output=True,
                          text=True).stdout
    return [row["case"] for row in csv.DictReader(io.StringIO(text))]


@ray.remote(num_cpus=1)
def run_case(crane_cosim: str, study: str, out: str, index: int) -> dict:
    """Runs one case on this node; its exit code, the end of its error output and the node."""
    command = [crane_cosim, "sweep", "run", study, "-o", out, "--case-index", str(index), "--quiet"]
    finished = subprocess.run(command, capture_output=True, text=True)
    return {"code": finished.returncode, "error": finished.stderr.strip()[-2000:],
            "node": ray.get_runtime_context().get_node_id()}


def case_status(out: pathlib.Path, case_id: str) -> str:
    """The status in the case file as the driver sees it ("missing" if it cannot read it)."""
    try:
        return json.loads((out / "cases" / f"{case_id}.json").read_text())["status"]
    except (OSError, ValueError, KeyError):
        return "missing"


class Driver:
    """Submits the cases, re-submits failed ones and reports each finished attempt."""

    def __init__(self, args: argparse.Namespace, ids: list[str]):
        self.args, self.ids = args, ids
        self.study, self.out = str(args.study.resolve()), args.out.resolve()
        self.attempts = [0] * len(ids)
        self.running: dict[ray.ObjectRef, int] = {}
        self.failed: list[int] = []
        self.nodes: set[str] = set()
        self.settled = 0

    def submit(self, index: int) -> None:
        self.attempts[index] += 1
        options = run_case.options(max_retries=self.args.max_retries, scheduling_strategy="SPREAD")
        self.running[options.remote(self.args.crane_cosim, self.study, str(self.out), index)] = index

    def run(self) -> None:
        for index in range(len(self.ids)):
            self.submit(index)
        while self.running:
            [ref], _ = ray.wait(list(self.running), num_returns=1)
            self.settle(self.running.pop(ref), ref)

    def settle(self, index: int, ref: ray.ObjectRef) -> None:
        """Reports an attempt; submits the case again if it failed and may run again."""
        case_id, attempt = self.ids[index], self.attempts[index]
        try:
            result = ray.get(ref)
        except ray.exceptions.RayError as error:  # the task's worker or node died, past Ray's retries
            result = {"code": None, "error": f"{type(error).__name__}: {error}", "node": "?"}
        status = case_status(self.out, case_id) if result["code"] == 0 else "failed"
        if result["node"] != "?":
            self.nodes.add(result["node"])
        again = status != "done" and attempt < self.args.attempts
        self.settled += not again
        print(f"[{self.settled}/{len(self.ids)}] case {case_id}: {status} on node {result['node']} (attempt {attempt})",
              flush=True)
        if status == "done":
            return
        reason = result["error"].splitlines()[-1] if result["error"] else f"exit code {result['code']}"
        if status == "missing":
            reason = f"no case file in {self.out}: is the output folder shared by every node?"
        print(f"case {case_id}: {reason}" + ("; submitted again" if again else "; giving up"), flush=True)
        if again:
            self.submit(index)
        else:
            self.failed.append(index)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    ids = plan(args.crane_cosim, args.study)
    args.out.mkdir(parents=True, exist_ok=True)
    ray.init(address=args.address, log_to_driver=False)
    nodes = [n for n in ray.nodes() if n["Alive"]]
    cpus = sum(n["Resources"].get("CPU", 0) for n in nodes)
    print(f"{len(ids)} cases on {len(nodes)} Ray nodes ({cpus:g} CPUs)", flush=True)
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

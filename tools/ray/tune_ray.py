#!/usr/bin/env python3
"""Run a crane-cosim tuning on a Ray cluster: each generation's candidates as Ray tasks.

The search itself stays in crane-cosim: `crane-cosim tune TUNING -o OUT --ask` runs the reference
runs if they are missing and prints the next generation's candidates that have no file yet; each
is then one Ray task, `crane-cosim tune TUNING -o OUT --candidate ID`, which writes
OUT/candidates/ID.json itself (whole, through a rename). When a generation's files are all there
the driver asks again; CMA-ES replays the search from the files (docs/tuning.md), so the
candidates, and the result, are the same as those of `crane-cosim tune` on one machine. At the
end, `crane-cosim tune TUNING -o OUT` finds every candidate evaluated and writes the report.

As for sweeps (tools/ray/sweep_ray.py, docs/sweeps.md), the tuning file, its system and FMUs,
the crane-cosim binary and OUT must be at the same paths on every node (a shared file system).
A candidate whose task fails is submitted again, up to --attempts runs.

    python tools/ray/tune_ray.py studies/tuning/truth.json -o out/tune              # a local Ray
    python tools/ray/tune_ray.py studies/tuning/truth.json -o out/tune --address auto
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

import ray

import ray_driver


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    args = ray_driver.parse(ray_driver.parser(__doc__, "tuning", "candidate"), argv)
    args.tuning, args.out = args.tuning.resolve(), args.out.resolve()
    return args


def ask(args: argparse.Namespace) -> dict:
    """The next generation's missing candidates, or {"finished": true}."""
    command = [args.crane_cosim, "tune", str(args.tuning), "-o", str(args.out), "--ask", "--jobs", "1"]
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def run_generation(args: argparse.Namespace, generation: int, candidates: list[str], nodes: set[str]) -> None:
    """Evaluates `candidates` on the cluster (each candidate's runs one after the other); raises if
    one fails on every attempt."""
    reasons = {}

    def command(candidate: str) -> list[str]:
        return [args.crane_cosim, "tune", str(args.tuning), "-o", str(args.out), "--candidate", candidate,
                "--jobs", "1", "--quiet"]

    def settle(candidate: str, result: ray_driver.Result, attempt: int, last: bool) -> bool:
        written = (args.out / "candidates" / f"{candidate}.json").is_file()
        ok = result["code"] == 0 and written
        print(f"generation {generation}: {candidate} {'done' if ok else 'failed'} on node {result['node']} "
              f"(attempt {attempt})", flush=True)
        reasons[candidate] = (attempt, ray_driver.reason(result, "no candidate file"))
        return ok

    failed = ray_driver.run_with_retries(candidates, command, args.attempts, settle, nodes)
    if failed:
        attempts, reason = reasons[failed[0]]
        raise RuntimeError(f"candidate {failed[0]} failed {attempts} times: {reason}")


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    alive, cpus = ray_driver.start(args.address)
    print(f"{alive} Ray nodes ({cpus:g} CPUs)", flush=True)
    clock, nodes, evaluated = time.monotonic(), set(), 0
    try:
        while not (step := ask(args)).get("finished"):
            run_generation(args, step["generation"], step["candidates"], nodes)
            evaluated += len(step["candidates"])
    except RuntimeError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    finally:
        ray.shutdown()
    print(f"{evaluated} candidates in {time.monotonic() - clock:.1f} s on {len(nodes)} nodes", flush=True)
    subprocess.run([args.crane_cosim, "tune", str(args.tuning), "-o", str(args.out), "--quiet"], check=True)
    print(f"report: {args.out / 'report.md'}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

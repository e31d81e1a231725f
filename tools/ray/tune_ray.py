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
import pathlib
import shutil
import subprocess
import sys
import time

import ray


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tuning", type=pathlib.Path, help="the tuning file (JSON)")
    parser.add_argument("-o", "--out", type=pathlib.Path, required=True, help="output folder (shared by all nodes)")
    parser.add_argument("--address", help="Ray cluster address (HOST:PORT or 'auto'); default: start a local Ray")
    parser.add_argument("--crane-cosim", default="crane-cosim",
                        help="the crane-cosim binary, at this path on every node [default: from PATH]")
    parser.add_argument("--attempts", type=int, default=3,
                        help="runs of a candidate at most, counting the first")
    args = parser.parse_args(argv)
    if args.attempts < 1:
        parser.error("--attempts must be at least 1")
    found = shutil.which(args.crane_cosim)
    args.crane_cosim = str(pathlib.Path(found or args.crane_cosim).resolve())
    args.tuning, args.out = args.tuning.resolve(), args.out.resolve()
    return args


def ask(args: argparse.Namespace) -> dict:
    """The next generation's missing candidates, or {"finished": true}."""
    command = [args.crane_cosim, "tune", str(args.tuning), "-o", str(args.out), "--ask", "--jobs", "1"]
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


@ray.remote(num_cpus=1)
def evaluate(crane_cosim: str, tuning: str, out: str, candidate: str) -> dict:
    """Evaluates one candidate on this node (its runs one after the other)."""
    command = [crane_cosim, "tune", tuning, "-o", out, "--candidate", candidate, "--jobs", "1", "--quiet"]
    finished = subprocess.run(command, capture_output=True, text=True)
    return {"code": finished.returncode, "error": finished.stderr.strip()[-2000:],
            "node": ray.get_runtime_context().get_node_id()}


def run_generation(args: argparse.Namespace, generation: int, candidates: list[str], nodes: set[str]) -> None:
    """Evaluates `candidates` on the cluster; raises if one fails on every attempt."""
    attempts = {c: 0 for c in candidates}
    running = {}

    def submit(candidate: str) -> None:
        attempts[candidate] += 1
        task = evaluate.options(scheduling_strategy="SPREAD")
        running[task.remote(args.crane_cosim, str(args.tuning), str(args.out), candidate)] = candidate

    for candidate in candidates:
        submit(candidate)
    while running:
        [ref], _ = ray.wait(list(running), num_returns=1)
        candidate = running.pop(ref)
        try:
            result = ray.get(ref)
        except ray.exceptions.RayError as error:
            result = {"code": None, "error": f"{type(error).__name__}: {error}", "node": "?"}
        nodes.add(result["node"])
        written = (args.out / "candidates" / f"{candidate}.json").is_file()
        ok = result["code"] == 0 and written
        print(f"generation {generation}: {candidate} {'done' if ok else 'failed'} on node {result['node']} "
              f"(attempt {attempts[candidate]})", flush=True)
        if ok:
            continue
        if attempts[candidate] >= args.attempts:
            reason = result["error"].splitlines()[-1] if result["error"] else "no candidate file"
            raise RuntimeError(f"candidate {candidate} failed {attempts[candidate]} times: {reason}")
        submit(candidate)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    ray.init(address=args.address, log_to_driver=False)
    alive = [n for n in ray.nodes() if n["Alive"]]
    print(f"{len(alive)} Ray nodes ({sum(n['Resources'].get('CPU', 0) for n in alive):g} CPUs)", flush=True)
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
    print(f"{evaluated} candidates in {time.monotonic() - clock:.1f} s on {len(nodes - {'?'})} nodes", flush=True)
    subprocess.run([args.crane_cosim, "tune", str(args.tuning), "-o", str(args.out), "--quiet"], check=True)
    print(f"report: {args.out / 'report.md'}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

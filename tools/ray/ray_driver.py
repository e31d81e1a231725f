"""What the Ray drivers of sweeps (sweep_ray.py) and tunings (tune_ray.py) share.

Both run `crane-cosim` commands as Ray tasks, one per case or candidate, on whichever node Ray
places them; each command writes its own file into the output folder, which must therefore be at
the same path on every node (a shared file system), as must the crane-cosim binary. A command that
fails is submitted again up to the driver's `--attempts` runs; the driver says per attempt
whether its command succeeded.
"""
from __future__ import annotations

import argparse
import pathlib
import shutil
import subprocess
import sys
from typing import Callable, Hashable, Iterable

import ray
import ray.cloudpickle

# The task below travels to the workers whole, as a script's own functions do, rather than as a
# reference to this module, which a worker could import only with the tools folder on its path.
ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])

#: What a task returns: the command's exit code (None where Ray lost the task), the end of its
#: error output and the Ray node that ran it ("?" where unknown).
Result = dict


def parser(doc: str, name: str, unit: str) -> argparse.ArgumentParser:
    """The arguments both drivers take: the `name` file (JSON), the output folder, the Ray
    address, the binary and the attempts per `unit` (a case, a candidate)."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument(name, type=pathlib.Path, help=f"the {name} file (JSON)")
    parser.add_argument("-o", "--out", type=pathlib.Path, required=True, help="output folder (shared by all nodes)")
    parser.add_argument("--address", help="Ray cluster address (HOST:PORT or 'auto'); default: start a local Ray")
    parser.add_argument("--crane-cosim", default="crane-cosim",
                        help="the crane-cosim binary, at this path on every node [default: from PATH]")
    parser.add_argument("--attempts", type=int, default=3,
                        help=f"runs of a {unit} at most, counting the first (a failed run submits it again)")
    return parser


def parse(parser: argparse.ArgumentParser, argv: list[str] | None) -> argparse.Namespace:
    """The parsed arguments, with the binary as an absolute path: Ray's workers do not run in
    this directory."""
    args = parser.parse_args(argv)
    if args.attempts < 1:
        parser.error("--attempts must be at least 1")
    found = shutil.which(args.crane_cosim)
    args.crane_cosim = str(pathlib.Path(found or args.crane_cosim).resolve())
    return args


def start(address: str | None) -> tuple[int, float]:
    """Connects to the cluster at `address` (a new local Ray without one): its live nodes and
    their CPUs."""
    ray.init(address=address, log_to_driver=False)
    alive = [n for n in ray.nodes() if n["Alive"]]
    return len(alive), sum(n["Resources"].get("CPU", 0) for n in alive)


@ray.remote(num_cpus=1)
def run_command(command: list[str]) -> Result:
    """Runs `command` on this node to its end."""
    finished = subprocess.run(command, capture_output=True, text=True)
    return {"code": finished.returncode, "error": finished.stderr.strip()[-2000:],
            "node": ray.get_runtime_context().get_node_id()}


def outcome(ref: ray.ObjectRef) -> Result:
    """The result of a finished task, or what stands for it when Ray lost the task's worker or
    node (past its own retries)."""
    try:
        return ray.get(ref)
    except ray.exceptions.RayError as error:
        return {"code": None, "error": f"{type(error).__name__}: {error}", "node": "?"}


def reason(result: Result, otherwise: str) -> str:
    """The last line of a failed command's error output, `otherwise` if it said nothing."""
    return result["error"].splitlines()[-1] if result["error"] else otherwise


def run_with_retries(keys: Iterable[Hashable], command: Callable[[Hashable], list[str]], attempts: int,
                     settle: Callable[[Hashable, Result, int, bool], bool], nodes: set[str],
                     max_retries: int | None = None) -> list:
    """Runs `command(key)` for every key as a Ray task, spread over the nodes, and submits a key
    again until `settle(key, result, attempt, last)` calls it done or it ran `attempts` times
    (`last` tells `settle` which attempt is the final one, for its report). Adds the nodes that
    ran a task to `nodes`; `max_retries` is Ray's own re-runs of a task whose worker or node died.
    The keys that failed on every attempt, in the order they gave up."""
    tries: dict = {}
    running: dict = {}
    options = {"scheduling_strategy": "SPREAD"}
    if max_retries is not None:
        options["max_retries"] = max_retries

    def submit(key: Hashable) -> None:
        tries[key] = tries.get(key, 0) + 1
        running[run_command.options(**options).remote(command(key))] = key

    for key in keys:
        submit(key)
    failed = []
    while running:
        [ref], _ = ray.wait(list(running), num_returns=1)
        key = running.pop(ref)
        result = outcome(ref)
        if result["node"] != "?":
            nodes.add(result["node"])
        last = tries[key] >= attempts
        if settle(key, result, tries[key], last):
            continue
        if last:
            failed.append(key)
        else:
            submit(key)
    return failed


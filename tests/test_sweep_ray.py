"""Distributed sweeps: the Ray driver (tools/ray/sweep_ray.py) on a real Ray cluster of two nodes
started on this machine, and the Slurm and Kubernetes job files of docs/jobs.

The cluster is a head node and a worker node of one CPU each (`ray start --block`, each in its
own process group with its session under target/), stopped by signalling those groups.
"""
import json
import os
import pathlib
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

import pytest
import yaml

from conftest import ROOT

STUDY = ROOT / "tests" / "sweep" / "study.json"
DRIVER = ROOT / "tools" / "ray" / "sweep_ray.py"
TUNE_DRIVER = ROOT / "tools" / "ray" / "tune_ray.py"
RAY = pathlib.Path(sys.executable).parent / "ray"
INDEX_VARIABLES = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"]
FLAKY_CASE = 3
START_TIMEOUT = 120
# The test cluster runs without Ray's token authentication whatever the user's own Ray left
# behind: a local `ray.init()` (e.g. tools/ray/*_ray.py without --address) writes
# ~/.ray/auth_token, after which nodes started here would demand a token the drivers lack.
os.environ["RAY_AUTH_MODE"] = "disabled"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_node(args):
    """Starts a Ray node (one CPU, a 100 MB object store) in its own process group; returns once
    it has joined the cluster, fails the test if that takes more than START_TIMEOUT seconds."""
    command = [str(RAY), "start", "--block", "--num-cpus=1", "--object-store-memory=100000000",
               "--node-ip-address=127.0.0.1", "--disable-usage-stats", *args]
    node = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    # A node that hangs is ended, which ends its output and the loop below.
    watchdog = threading.Timer(START_TIMEOUT, os.killpg, (node.pid, signal.SIGKILL))
    watchdog.start()
    log = []
    try:
        for line in node.stdout:
            log.append(line)
            if "Ray runtime started" in line:
                return node
    finally:
        watchdog.cancel()
    stop_nodes([node])
    pytest.fail("a Ray node did not start:\n" + "".join(log))


def stop_nodes(nodes):
    """Ends every process of the nodes' groups (raylet, GCS, workers): SIGTERM, then SIGKILL
    for what is left after a grace period (a Ray node takes up to half a minute to end itself)."""
    for node in nodes:
        try:
            os.killpg(node.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
    deadline = time.monotonic() + 3
    for node in nodes:
        try:
            node.wait(timeout=max(deadline - time.monotonic(), 0.1))
        except subprocess.TimeoutExpired:
            pass
        try:
            os.killpg(node.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        node.wait()


@pytest.fixture(scope="module")
def ray_cluster():
    """The address of a running two-node Ray cluster (head and one worker on this machine)."""
    # Ray's sockets live about 60 characters deeper, and a socket path has at most 107: in a
    # deeply nested clone, a short folder in the system's temporary directory instead.
    session_dir = ROOT / "target" / "ray"
    if len(str(session_dir)) > 45:
        session_dir = pathlib.Path(tempfile.mkdtemp(prefix="ray-"))
    shutil.rmtree(session_dir, ignore_errors=True)
    session_dir.mkdir(parents=True)
    port = free_port()
    nodes = [start_node(["--head", f"--port={port}", f"--temp-dir={session_dir}", "--include-dashboard=false"])]
    try:
        nodes.append(start_node([f"--address=127.0.0.1:{port}"]))
        yield f"127.0.0.1:{port}"
    finally:
        stop_nodes(nodes)


def flaky_master(master, folder):
    """A crane-cosim wrapper that fails the first run of case FLAKY_CASE (mkdir is atomic: only
    one run creates the marker), then behaves as crane-cosim after a second's pause. The test's
    cases take some 20 ms, less than the second node needs to start its first Python worker, so
    the head alone would run them all; at a second each, Ray must use both nodes' CPUs, as in a
    real study whose cases take seconds."""
    marker = folder / "failed-once"
    script = folder / "crane-cosim"
    script.write_text(f"""#!/bin/sh
case " $* " in *" --case-index {FLAKY_CASE} "*)
    if mkdir '{marker}' 2>/dev/null; then echo 'injected failure' >&2; exit 3; fi;;
esac
case " $* " in *" sweep run "*) sleep 1;; esac
exec '{master}' "$@"
""")
    script.chmod(0o755)
    return script


def test_the_ray_driver_runs_every_case_on_both_nodes_retries_a_failure_and_matches_the_local_pool(
        master, ray_cluster, tmp_path):
    local = tmp_path / "local"
    subprocess.run([master, "sweep", "run", STUDY, "-o", local, "--jobs", "2", "--quiet"], check=True)
    subprocess.run([master, "sweep", "collect", local, "--plots", "none"], check=True, capture_output=True)

    out = tmp_path / "ray"
    command = [sys.executable, DRIVER, STUDY, "-o", out, "--address", ray_cluster,
               "--crane-cosim", flaky_master(master, tmp_path), "--plots", "none"]
    driver = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert driver.returncode == 0, driver.stdout + driver.stderr
    output = driver.stdout
    assert "8 cases on 2 Ray nodes (2 CPUs)" in output, output

    attempts = re.findall(r"case (\d{4}): (\w+) on node (\w+) \(attempt (\d)\)", output)
    done = {case: int(attempt) for case, status, _, attempt in attempts if status == "done"}
    assert done == {f"{i:04d}": 2 if i == FLAKY_CASE else 1 for i in range(8)}, output
    failed = [(case, attempt) for case, status, _, attempt in attempts if status != "done"]
    assert failed == [(f"{FLAKY_CASE:04d}", "1")], output
    assert "injected failure; submitted again" in output
    assert len({node for _, _, node, _ in attempts}) == 2, f"tasks ran on one node only:\n{output}"

    assert (out / "results.csv").read_bytes() == (local / "results.csv").read_bytes()


def test_the_driver_gives_up_after_its_attempts_and_exits_non_zero(master, ray_cluster, tmp_path):
    broken = tmp_path / "crane-cosim"
    broken.write_text(f"""#!/bin/sh
case " $* " in *" --case-index 1 "*) echo 'always fails' >&2; exit 2;; esac
exec '{master}' "$@"
""")
    broken.chmod(0o755)
    single = tmp_path / "study.json"
    text = STUDY.read_text().replace('"cases": 8', '"cases": 2').replace('"base.json"', f'"{STUDY.parent / "base.json"}"')
    single.write_text(text)
    out = tmp_path / "out"
    command = [sys.executable, DRIVER, single, "-o", out, "--address", ray_cluster, "--crane-cosim", broken,
               "--attempts", "2", "--plots", "none"]
    driver = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert driver.returncode == 1, driver.stdout + driver.stderr
    assert "case 0001: always fails; submitted again" in driver.stdout
    assert "case 0001: always fails; giving up" in driver.stdout
    assert "failed: 0001" in driver.stdout
    assert "results.csv: 1 done, 0 failed, 1 pending" in driver.stdout


def test_the_tuning_driver_evaluates_each_generation_on_the_cluster_and_matches_one_process(
        master, ray_cluster, tmp_path):
    tuning = json.loads((ROOT / "studies" / "tuning" / "reduced.json").read_text())
    tuning["system"] = str(ROOT / "systems" / "closed_loop.json")
    file = tmp_path / "tuning.json"
    file.write_text(json.dumps(tuning))
    local = tmp_path / "local"
    subprocess.run([master, "tune", file, "-o", local, "--quiet"], check=True)

    out = tmp_path / "ray"
    command = [sys.executable, TUNE_DRIVER, file, "-o", out, "--address", ray_cluster, "--crane-cosim", master]
    driver = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert driver.returncode == 0, driver.stdout + driver.stderr
    finished = re.findall(r"generation (\d+): (g\d{3}-k\d{2}) done on node (\w+)", driver.stdout)
    assert sorted(c for _, c, _ in finished) == sorted(p.stem for p in (local / "candidates").iterdir()), driver.stdout
    assert "12 candidates in" in driver.stdout, driver.stdout

    def without_wall_time(path):
        value = json.loads(path.read_text())
        value.pop("wall_time")
        return value

    for candidate in (local / "candidates").iterdir():
        assert without_wall_time(out / "candidates" / candidate.name) == without_wall_time(candidate)
    assert without_wall_time(out / "summary.json") == without_wall_time(local / "summary.json")
    assert (out / "best.json").read_bytes() == (local / "best.json").read_bytes()


def test_the_slurm_array_script_runs_the_case_of_its_task_index(master, tmp_path):
    script = ROOT / "docs" / "jobs" / "slurm-array.sh"
    subprocess.run(["bash", "-n", script], check=True)
    text = script.read_text()
    assert "--array=0-$((n - 1))" in text and "sweep collect" in text
    environment = clean_environment(master, SLURM_ARRAY_TASK_ID="5")
    subprocess.run(["bash", script, STUDY, tmp_path / "out"], check=True, env=environment)
    assert sorted(p.name for p in (tmp_path / "out" / "cases").iterdir()) == ["0005.json"]


def test_the_kubernetes_job_is_indexed_and_its_command_runs_the_case_of_its_completion_index(master, tmp_path):
    job = yaml.safe_load((ROOT / "docs" / "jobs" / "k8s-indexed-job.yaml").read_text())
    assert (job["kind"], job["spec"]["completionMode"]) == ("Job", "Indexed")
    assert job["spec"]["completions"] >= job["spec"]["parallelism"] >= 1
    pod = job["spec"]["template"]["spec"]
    [container] = pod["containers"]
    command = container["command"]
    assert command[:3] == ["crane-cosim", "sweep", "run"] and "--case-index" not in command
    mounted = {m["mountPath"] for m in container["volumeMounts"]}
    assert all(any(arg.startswith(m) for m in mounted) for arg in (command[3], command[command.index("-o") + 1]))
    assert {v["name"] for v in pod["volumes"]} == {m["name"] for m in container["volumeMounts"]}
    # The pod's command with this machine's paths: the index comes from JOB_COMPLETION_INDEX.
    command = [master, *command[1:3], STUDY, *command[4:]]
    command[command.index("-o") + 1] = tmp_path / "out"
    subprocess.run(command, check=True, env=clean_environment(master, JOB_COMPLETION_INDEX="6"))
    assert sorted(p.name for p in (tmp_path / "out" / "cases").iterdir()) == ["0006.json"]


def clean_environment(master, **variables):
    """This process's environment without either index variable, crane-cosim on the PATH, plus
    `variables`."""
    environment = {k: v for k, v in os.environ.items() if k not in INDEX_VARIABLES}
    environment["PATH"] = f"{pathlib.Path(master).parent}{os.pathsep}{environment.get('PATH', '')}"
    return {**environment, **variables}

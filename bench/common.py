"""What the bench's masters share: reading the system file the bench writes (a crane-cosim
system file with absolute FMU paths), the communication grid, writing results and reporting the
wall time to `cargo xtask bench` (one JSON line on standard output)."""
import json
import pathlib


def load_system(path):
    """The system file as a dict, with its recorded variables as (instance, variable) pairs."""
    system = json.loads(pathlib.Path(path).read_text())
    record = (system.get("record") or {}).get("variables")
    if not record:
        raise SystemExit(f"{path}: the bench needs record.variables")
    system["record_pairs"] = [split(name) for name in record]
    return system


def split(reference):
    """'crane.tip.x' -> ('crane', 'tip.x')."""
    instance, _, variable = reference.partition(".")
    return instance, variable


def steps(system):
    """Number of macro steps from start_time to stop_time (as crane-cosim counts them)."""
    return round((system["stop_time"] - system.get("start_time", 0.0)) / system["step_size"])


def write_csv(path, system, rows):
    """Results in crane-cosim's layout: time, then the recorded variables; repr() is the
    shortest text that reads back as the same double."""
    header = ["time"] + [f"{i}.{v}" for i, v in system["record_pairs"]]
    lines = [",".join(header)] + [",".join(repr(float(x)) for x in row) for row in rows]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def report(wall_s):
    print(json.dumps({"wall_s": wall_s}))

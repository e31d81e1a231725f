"""libcosim (through libcosimpy) running a system that `crane-cosim export` wrote, as an OSP
system structure or an SSP archive: fixed-step (Jacobi) stepping, the system's recorded
variables kept by libcosim's buffered time-series observer at every step.

Usage: libcosim_master.py [--log-level LEVEL] STRUCTURE SYSTEM.json RESULTS.csv
STRUCTURE is an OspSystemStructure.xml or a .ssp archive; SYSTEM.json gives the recorded variables,
stop time and step size (prints {"wall_s": ...}: loading to the samples read back). libcosim logs
to standard error from LEVEL on (default warning).
"""
import argparse
import time

from libcosimpy.CosimEnums import CosimVariableType
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver

from common import load_system, report, steps, write_csv

NANOSECONDS = 1_000_000_000


def variable_reference(execution, index, name):
    for v in execution.slave_variables(index):
        if v.name.decode() == name:
            if v.type != CosimVariableType.REAL.value:
                raise SystemExit(f"{name}: the bench records Real variables only")
            return v.reference
    raise SystemExit(f"no variable {name} in slave {index}")


def load(structure):
    """An execution of an SSP archive (by its extension) or of an OSP system structure."""
    if structure.endswith(".ssp"):
        return CosimExecution.from_ssp_file(structure)
    return CosimExecution.from_osp_config_file(structure)


def main(structure, system_path, csv_path, log_level):
    system = load_system(system_path)
    n = steps(system)
    # libcosim logs at trace level by default, which also switches the FMUs' call logging on:
    # measured that way, the run would mostly format log lines.
    log_output_level(CosimLogLevel[log_level.upper()])
    clock = time.perf_counter()
    execution = load(structure)
    observer = CosimObserver.create_time_series(buffer_size=n + 1)
    execution.add_observer(observer)
    recorded = []
    for instance, variable in system["record_pairs"]:
        index = execution.slave_index_from_instance_name(instance)
        if index is None:
            raise SystemExit(f"no slave {instance}")
        reference = variable_reference(execution, index, variable)
        observer.start_time_series(index, reference, CosimVariableType.REAL)
        recorded.append((index, reference))
    if not execution.simulate_until(round(system["stop_time"] * NANOSECONDS)):
        raise SystemExit("libcosim failed")
    # Steps 1..n (libcosimpy's sample reader trims at step number 0, so t0 is left out).
    columns = [observer.time_series_real_samples(i, r, from_step=1, sample_count=n) for i, r in recorded]
    wall = time.perf_counter() - clock
    times = columns[0][0]
    if any(len(c[2]) != n for c in columns):
        raise SystemExit(f"expected {n} samples per variable")
    rows = [[times[k] / NANOSECONDS] + [c[2][k] for c in columns] for k in range(n)]
    write_csv(csv_path, system, rows)
    report(wall)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--log-level", default="warning", choices=[level.name.lower() for level in CosimLogLevel])
    parser.add_argument("structure")
    parser.add_argument("system")
    parser.add_argument("results")
    arguments = parser.parse_args()
    main(arguments.structure, arguments.system, arguments.results, arguments.log_level)

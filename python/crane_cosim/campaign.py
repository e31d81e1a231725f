"""The thesis' simulation campaign, sweep studies and tuning from Python: ``crane_cosim.campaign``,
``sweep`` and ``tune``, each the command of the same name."""

from __future__ import annotations

import io
import os
import pathlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence

from . import _native
from ._options import PathLike, optional_path, start_values

if TYPE_CHECKING:
    import pandas

_PACKAGE_SYSTEMS = pathlib.Path(__file__).resolve().parent / "systems"


@dataclass
class CampaignResult:
    """What ``campaign`` returns.

    Attributes:
        runs: one row per run, the columns of the output folder's ``metrics.csv`` (id, test,
            variant, the §7.2.2 metrics, wall time, error).
        tables: one row per row of Tables 7.1-7.3 and variant (1, 2), with or without test pairs:
            ``table``, ``metric``, ``variant``, ``thesis`` (the thesis' simulated mean reduction,
            %), ``reduction`` (ours, %; None without a pair), ``pairs``, ``band`` (docs/acceptance.md;
            empty where none) and ``met``.
        failures: ``"id: error"`` of each run that failed (the campaign goes on without it).
        output: the folder with the scenarios, metrics, report and figures.
    """

    runs: pandas.DataFrame
    tables: pandas.DataFrame
    failures: list[str]
    output: pathlib.Path


def default_system(full_scale: bool = False) -> pathlib.Path:
    """The closed loop a campaign runs: ``systems/<file>`` of the current directory when there is
    one (a checkout), else the one shipped in the package (its FMUs inside it)."""
    name = "full_scale_ahc.json" if full_scale else "closed_loop.json"
    local = pathlib.Path("systems") / name
    return local if local.is_file() else _PACKAGE_SYSTEMS / name


def campaign(
    tests: str = "1-104",
    variants: Sequence[int] = (1, 2),
    *,
    output: PathLike = "out/campaign",
    system: Optional[PathLike] = None,
    jobs: int = 0,
    start: Optional[Mapping[str, Any]] = None,
    start_file: Optional[PathLike] = None,
    crane: Optional[PathLike] = None,
    keep_results: bool = False,
    full_scale: bool = False,
    attitude_filter: str = "complementary",
    thesis_init: bool = False,
    check: bool = False,
) -> CampaignResult:
    """Runs the campaign as ``crane-cosim campaign`` does and returns its metrics and tables.

    ``tests`` selects as ``--tests`` does (``"1-104"``, ``"89,91,101-104"``), ``variants`` as
    ``--variants`` (1 truth, 2 sensors, 3 sensors and the EKF); ``output`` is the folder written
    (scenarios/, metrics.csv, metrics.json, report.md, figures/; a folder another program wrote is
    refused), ``system`` the closed loop (default: ``default_system``), ``jobs`` the worker
    threads (0: one per core), ``start`` start values every run gets (``--start``) after those of
    the scenario file ``start_file`` (``--start-file``, e.g. a tuning's best.json), ``crane``
    the full-scale crane's description for the crane and its controller (``--crane``: a catalogue
    name such as ``"ahc_10t"`` or a JSON file, docs/crane-description.md; needs ``full_scale``),
    ``keep_results`` every run's CSV in ``output/runs/``, ``full_scale`` the full-scale crane,
    ``attitude_filter`` the sensor variants' estimator (``"complementary"`` or ``"madgwick"``),
    ``thesis_init`` the thesis' start (filters at the identity, no 10 s hold), and ``check``
    raises ``SimulationError`` when a band of docs/acceptance.md is not met (or none could be
    judged), after the files are written. The interpreter's lock is released while it runs.

    Raises ``SimulationError`` when the campaign cannot start or its files cannot be written; a
    run that fails is listed in ``failures`` instead.
    """
    import pandas

    chosen = system if system is not None else default_system(full_scale)
    options = {
        "tests": str(tests),
        "variants": [int(v) for v in variants],
        "system": os.fspath(chosen),
        "output": os.fspath(output),
        "jobs": int(jobs),
        "start": start_values(start),
        "start_file": optional_path(start_file),
        "crane": None if crane is None else os.fspath(crane),
        "keep_results": bool(keep_results),
        "full_scale": bool(full_scale),
        "attitude_filter": str(attitude_filter),
        "thesis_init": bool(thesis_init),
        "check": bool(check),
    }
    metrics, rows, failures = _native.campaign(options)
    columns = ["table", "metric", "variant", "thesis", "reduction", "pairs", "band", "met"]
    return CampaignResult(
        runs=pandas.read_csv(io.StringIO(metrics)),
        tables=pandas.DataFrame(rows, columns=columns),
        failures=list(failures),
        output=pathlib.Path(output),
    )


@dataclass
class SweepResult:
    """What ``sweep`` returns.

    Attributes:
        cases: the output folder's ``results.csv``: one row per case (case, seed, status, the
            study's parameters, its metrics).
        done, failed, skipped: cases run now, failed now, and done by an earlier run.
        output: the folder (cases/, manifest.json, results.csv, results.parquet, plots/).
    """

    cases: pandas.DataFrame
    done: int
    failed: int
    skipped: int
    output: pathlib.Path


def sweep(
    study: PathLike, *, output: PathLike, jobs: int = 0, plots: bool = False, max_cases: int = 1_000_000
) -> SweepResult:
    """Runs the cases of a sweep study (docs/sweeps.md) not done yet in ``output`` and collects
    the folder, as ``crane-cosim sweep run STUDY -o OUTPUT`` then ``sweep collect OUTPUT`` do
    (PNG plots with ``plots``); an interrupted sweep goes on where it stopped. A study planning
    more than ``max_cases`` cases is refused (``--max-cases``). The interpreter's lock is released
    while it runs. Raises ``SimulationError`` when the study cannot run; a case that fails counts
    in ``failed`` and shows in ``cases["status"]``.
    """
    import pandas

    options = {
        "study": os.fspath(study),
        "output": os.fspath(output),
        "jobs": int(jobs),
        "max_cases": int(max_cases),
        "plots": bool(plots),
    }
    csv, (done, failed, skipped) = _native.sweep(options)
    cases = pandas.read_csv(io.StringIO(csv))
    return SweepResult(cases=cases, done=done, failed=failed, skipped=skipped, output=pathlib.Path(output))


@dataclass
class TuneResult:
    """What ``tune`` returns.

    Attributes:
        best: the id of the best candidate (e.g. ``g007-k03``); its start values are the output
            folder's ``best.json``, a scenario overlay ``campaign(start_file=…)`` takes.
        report: the output folder's ``report.md``.
        output: the folder (candidates, log.csv, best.json, report.md, the convergence plot).
    """

    best: str
    report: pathlib.Path
    output: pathlib.Path


def tune(tuning: PathLike, *, output: PathLike = "out/tune", jobs: int = 0) -> TuneResult:
    """Tunes controller parameters with CMA-ES as ``crane-cosim tune TUNING -o OUTPUT`` does
    (docs/tuning.md), resuming where an earlier run into ``output`` stopped. The interpreter's
    lock is released while it runs. Raises ``SimulationError`` when the tuning cannot run.
    """
    options = {"tuning": os.fspath(tuning), "output": os.fspath(output), "jobs": int(jobs)}
    report, best = _native.tune(options)
    return TuneResult(best=best, report=pathlib.Path(report), output=pathlib.Path(output))

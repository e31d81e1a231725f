"""Co-simulation of the knuckle-boom crane FMUs from Python.

``run`` runs a system file, scenario file, SSP archive, OSP system structure or one FMU as
``crane-cosim run`` does and returns the recorded rows as a pandas DataFrame, bit for bit the
numbers of the CSV that command writes. ``fmu_path`` gives the path of an FMU shipped inside the
package (FMI 2.0 or 3.0), which FMPy and other importers can open.

The system and scenario files of the repository name their FMUs as ``../target/fmu/…``, relative
to themselves: ``run`` on them works from a checkout in which ``cargo xtask package`` has been run.
"""

from __future__ import annotations

import os
import pathlib
import warnings
from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence

from . import _native
from ._convert import PathLike, _frame, _options
from ._native import SavedState, SimulationError
from .campaign import CampaignResult, SweepResult, campaign, sweep
from .simulation import Simulation

if TYPE_CHECKING:
    import pandas

__all__ = [
    "CampaignResult",
    "SavedState",
    "Simulation",
    "SimulationError",
    "SweepResult",
    "campaign",
    "fmu_names",
    "fmu_path",
    "run",
    "sweep",
]

_FMU_DIR = pathlib.Path(__file__).resolve().parent / "fmu"


def _fmu_folder(fmi_version: int) -> pathlib.Path:
    if fmi_version == 2:
        return _FMU_DIR
    if fmi_version == 3:
        return _FMU_DIR / "fmi3"
    raise ValueError(f"fmi_version {fmi_version!r}: expected 2 or 3")


def fmu_names(fmi_version: int = 2) -> list[str]:
    """The names of the FMUs shipped in the package for FMI ``fmi_version`` (2 or 3), sorted."""
    folder = _fmu_folder(fmi_version)
    return sorted(path.stem for path in folder.glob("*.fmu")) if folder.is_dir() else []


def fmu_path(name: str, fmi_version: int = 2) -> pathlib.Path:
    """The path of the shipped FMU ``name`` (e.g. ``"pendulum"``, ``"knuckle_boom"``,
    ``"rigging"``) for FMI ``fmi_version`` (2 or 3), inside the installed package.

    Raises ``FileNotFoundError`` naming the FMUs there are when there is none of that name.
    """
    path = _fmu_folder(fmi_version) / f"{name}.fmu"
    if not path.is_file():
        known = ", ".join(fmu_names(fmi_version)) or "none"
        raise FileNotFoundError(f"no FMI {fmi_version} FMU named {name!r} in the package; there are: {known}")
    return path


def run(
    system: PathLike,
    *,
    start: Optional[Mapping[str, Any]] = None,
    stop_time: Optional[float] = None,
    step_size: Optional[float] = None,
    record: Optional[Sequence[str]] = None,
    record_interval: Optional[float] = None,
    algorithm: Optional[str] = None,
    inputs: Optional[Sequence[PathLike]] = None,
    force: bool = False,
) -> pandas.DataFrame:
    """Runs ``system`` as ``crane-cosim run`` does and returns the recorded rows.

    ``system`` is a system or scenario file (JSON), an SSP archive, an OSP system structure or one
    ``.fmu`` (run alone with its default experiment). The keywords are the command's options:

    * ``start``: ``{"instance.variable": value}`` (``{"variable": value}`` for one FMU) replacing
      the file's start values (``--start``); a number, bool, string, or ``{"path": "x.csv"}`` /
      a ``pathlib.Path`` for a file relative to the working directory;
    * ``stop_time``, ``step_size``, ``record_interval`` in seconds, ``algorithm``
      (``"gauss-seidel"`` or ``"jacobi"``);
    * ``record``: names or patterns (``*``, ``?``) of variables recorded after the file's
      (``--record``);
    * ``inputs``: input CSVs (``--input``);
    * ``force``: run even if the time grid or the results are over the workload limits.

    The DataFrame has the column ``time`` and one column per recorded variable, as
    ``float64`` (integers and booleans too), each value the one the command's CSV reads back to;
    ``df.attrs["units"]`` maps each column to its unit (``None`` without one). The notes and
    warnings the command prints are issued as Python warnings. The interpreter's lock is released
    while the system is loaded and stepped.

    Raises ``SimulationError`` with the message the command prints (without its ``error:``).
    """
    native = _native.run(
        os.fspath(system), _options(start, stop_time, step_size, record_interval, algorithm, record, inputs, force)
    )
    for note in native[4]:
        warnings.warn(note, stacklevel=2)
    return _frame(native)

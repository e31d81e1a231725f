"""What the public functions share: the options dictionaries the extension reads (each key a
field of the extension's request), start values as JSON, and the DataFrame of a recording."""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence, Union

from ._native import SimulationError

if TYPE_CHECKING:
    import pandas

PathLike = Union[str, "os.PathLike[str]"]


def json_value(name: str, value: Any) -> str:
    """A start value as the JSON text ``--start NAME=VALUE`` would give (floats as their shortest
    round-trip decimal, so the FMU gets the same bits)."""
    if isinstance(value, os.PathLike):
        value = {"path": os.fspath(value)}
    try:
        return json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as error:
        raise SimulationError(f"start value of {name}: {error}") from None


def start_values(start: Optional[Mapping[str, Any]]) -> list[tuple[str, str]]:
    """Start values as the extension takes them: ``(name, JSON text)``."""
    return [(str(name), json_value(name, value)) for name, value in (start or {}).items()]


def optional_path(path: Optional[PathLike]) -> Optional[str]:
    return None if path is None else os.fspath(path)


def run_options(
    start: Optional[Mapping[str, Any]],
    stop_time: Optional[float],
    step_size: Optional[float],
    record_interval: Optional[float],
    algorithm: Optional[str],
    record: Optional[Sequence[str]],
    inputs: Optional[Sequence[PathLike]],
    force: bool,
) -> dict[str, Any]:
    """The options of ``run`` and ``Simulation`` as the extension reads them."""
    return {
        "start": start_values(start),
        "stop_time": None if stop_time is None else float(stop_time),
        "step_size": None if step_size is None else float(step_size),
        "record_interval": None if record_interval is None else float(record_interval),
        "algorithm": algorithm,
        "record": [str(pattern) for pattern in (record or [])],
        "inputs": [os.fspath(path) for path in (inputs or [])],
        "force": bool(force),
    }


def frame(native: tuple) -> pandas.DataFrame:
    """The DataFrame of the extension's (names, units, times, columns, warnings)."""
    import numpy
    import pandas

    names, units, times, columns, _ = native
    data = {"time": numpy.frombuffer(times, dtype="<f8")}
    for name, column in zip(names, columns):
        data[name] = numpy.frombuffer(column, dtype="<f8")
    result = pandas.DataFrame(data, copy=True)
    result.attrs["units"] = {"time": "s", **dict(zip(names, units))}
    return result

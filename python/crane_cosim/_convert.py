"""What the package's modules share: start values as JSON, ``run``'s options as the extension
takes them and its results as a DataFrame. The modules import them from here, not from the
package, which imports the modules."""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence, Union

from ._native import SimulationError

if TYPE_CHECKING:
    import pandas

PathLike = Union[str, "os.PathLike[str]"]


def _json_value(name: str, value: Any) -> str:
    """A start value as the JSON text ``--start NAME=VALUE`` would give (floats as their shortest
    round-trip decimal, so the FMU gets the same bits)."""
    if isinstance(value, os.PathLike):
        value = {"path": os.fspath(value)}
    try:
        return json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as error:
        raise SimulationError(f"start value of {name}: {error}") from None


def _frame(native: tuple) -> pandas.DataFrame:
    """The DataFrame of the extension's (names, units, times, columns, warnings)."""
    import numpy
    import pandas

    names, units, times, columns, _ = native
    data = {"time": numpy.frombuffer(times, dtype="<f8")}
    for name, column in zip(names, columns):
        data[name] = numpy.frombuffer(column, dtype="<f8")
    frame = pandas.DataFrame(data, copy=True)
    frame.attrs["units"] = {"time": "s", **dict(zip(names, units))}
    return frame


def _options(
    start: Optional[Mapping[str, Any]],
    stop_time: Optional[float],
    step_size: Optional[float],
    record_interval: Optional[float],
    algorithm: Optional[str],
    record: Optional[Sequence[str]],
    inputs: Optional[Sequence[PathLike]],
    force: bool,
) -> tuple:
    """The options of ``run`` as the extension takes them after the system: one tuple."""
    return (
        [(str(name), _json_value(name, value)) for name, value in (start or {}).items()],
        None if stop_time is None else float(stop_time),
        None if step_size is None else float(step_size),
        None if record_interval is None else float(record_interval),
        algorithm,
        [str(pattern) for pattern in (record or [])],
        [os.fspath(path) for path in (inputs or [])],
        bool(force),
    )

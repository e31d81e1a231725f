"""A co-simulation stepped from Python: ``crane_cosim.Simulation``."""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Optional, Sequence

from . import _native
from ._convert import _frame, _options
from ._native import SavedState

if TYPE_CHECKING:
    import pandas

    from ._convert import PathLike


class Simulation:
    """A system, scenario, SSP archive, OSP structure or one FMU, loaded, instantiated and
    initialized as ``crane-cosim run`` does it, then stepped on request.

    Between steps, any variable can be read (``get``, ``get_reals``) and parameters and inputs
    written (``set``); a connected input is overwritten by its connection at the next step. The
    whole co-simulation state (every instance's FMU state and what the master carries between
    steps) can be saved and restored: a restored simulation continues bit for bit as it did after
    the save. ``results()`` gives the rows recorded so far as ``run`` gives them: stepping to the
    stop time in any pieces records exactly the rows of one ``run``.

    The keywords are those of ``crane_cosim.run``. Use it as a context manager, or call
    ``close()``, to terminate and free the FMU instances. The interpreter's lock is released while
    the system is loaded and stepped.

    Raises ``SimulationError`` with the message ``crane-cosim run`` prints.
    """

    def __init__(
        self,
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
    ) -> None:
        options = _options(start, stop_time, step_size, record_interval, algorithm, record, inputs, force)
        self._native = _native.Simulation(os.fspath(system), options)
        for note in self._native.warnings:
            warnings.warn(note, stacklevel=2)

    @property
    def time(self) -> float:
        """The communication point reached (s)."""
        return self._native.time

    @property
    def steps_completed(self) -> int:
        """Macro steps completed since the start."""
        return self._native.steps_completed

    @property
    def steps(self) -> int:
        """Macro steps from the start to the stop time."""
        return self._native.steps

    @property
    def step_size(self) -> float:
        """The size (s) of the coming macro step."""
        return self._native.step_size

    @property
    def stop_time(self) -> float:
        """The stop time (s)."""
        return self._native.stop_time

    @property
    def done(self) -> bool:
        """True once the stop time is reached, an instance ended the run, or it is closed."""
        return self._native.done

    @property
    def instances(self) -> list[str]:
        """The instance names, in stepping order."""
        return self._native.instances

    def variables(self) -> list[tuple[str, str, str, Optional[str]]]:
        """Every variable of every instance as ``(name, causality, type, unit)``, e.g.
        ``("pendulum.theta_x", "output", "real", "rad")``."""
        return self._native.variables()

    def step(self, count: int = 1) -> float:
        """Takes ``count`` macro steps (fewer when the run ends first) and returns the time
        reached. Stepping a finished run raises ``SimulationError``."""
        if count < 0:
            raise ValueError(f"count {count}: expected 0 or more steps")
        return self._native.step(int(count))

    def advance_to(self, time: float) -> float:
        """Steps to the communication point at ``time`` (s), or the first one after it, and
        returns the time reached; nothing happens if it is already there or beyond."""
        return self._native.advance_to(float(time))

    def run(self) -> float:
        """Steps to the stop time (or until an instance ends the run); returns the time reached."""
        return self._native.run()

    def get(self, name: str) -> Any:
        """The current value of one variable (``"instance.variable"``; a lone FMU's also
        without the instance), as ``float``, ``int``, ``bool`` or ``str``."""
        return self._native.get([name])[0]

    def get_many(self, names: Iterable[str]) -> list[Any]:
        """The current values of several variables, in order."""
        return self._native.get(list(names))

    def get_reals(self, names: Sequence[str]) -> list[float]:
        """The current values of Real variables: the quick path for a loop that reads the same
        names every step."""
        return self._native.get_reals(list(names))

    def set(self, values: Mapping[str, Any]) -> None:
        """Sets ``{"instance.variable": value}`` before the next step."""
        self._native.set(list(values.items()))

    def save(self) -> SavedState:
        """The whole co-simulation state now, for ``restore`` (of this simulation, or another
        one of the same system and options)."""
        return self._native.save()

    def restore(self, state: SavedState) -> None:
        """Goes back (or forward) to ``state``; the rows recorded after it are dropped and
        recorded again as the simulation goes on."""
        self._native.restore(state)

    def results(self) -> pandas.DataFrame:
        """The rows recorded so far, as ``run`` returns them (units in ``df.attrs["units"]``)."""
        return _frame(self._native.results())

    def close(self) -> None:
        """Terminates and frees the FMU instances; later calls but ``close`` raise."""
        self._native.close()

    def __enter__(self) -> Simulation:
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"Simulation(time={self.time!r}, steps_completed={self.steps_completed}, steps={self.steps})"

"""Type stubs of the extension module (see crane_cosim.run for the documented API)."""

from typing import Any, Optional

class SimulationError(Exception):
    """A run that could not be loaded or did not complete; the message is the one
    `crane-cosim run` prints."""

def run(
    system: str,
    start: list[tuple[str, str]],
    stop_time: Optional[float],
    step_size: Optional[float],
    record_interval: Optional[float],
    algorithm: Optional[str],
    record: list[str],
    inputs: list[str],
    force: bool,
) -> tuple[list[str], list[Optional[str]], bytes, list[bytes], list[str]]: ...

class SavedState:
    """The whole co-simulation state at a communication point (``Simulation.save``)."""

    @property
    def time(self) -> float: ...
    @property
    def steps_completed(self) -> int: ...
    def instance_states(self) -> list[bytes]: ...

class Simulation:
    def __init__(
        self,
        system: str,
        start: list[tuple[str, str]],
        stop_time: Optional[float],
        step_size: Optional[float],
        record_interval: Optional[float],
        algorithm: Optional[str],
        record: list[str],
        inputs: list[str],
        force: bool,
    ) -> None: ...
    @property
    def time(self) -> float: ...
    @property
    def steps_completed(self) -> int: ...
    @property
    def steps(self) -> int: ...
    @property
    def step_size(self) -> float: ...
    @property
    def stop_time(self) -> float: ...
    @property
    def done(self) -> bool: ...
    @property
    def instances(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    def variables(self) -> list[tuple[str, str, str, Optional[str]]]: ...
    def step(self, count: int) -> float: ...
    def advance_to(self, time: float) -> float: ...
    def run(self) -> float: ...
    def get(self, names: list[str]) -> list[Any]: ...
    def get_reals(self, names: list[str]) -> list[float]: ...
    def set(self, values: list[tuple[str, Any]]) -> None: ...
    def save(self) -> SavedState: ...
    def restore(self, state: SavedState) -> None: ...
    def results(self) -> tuple[list[str], list[Optional[str]], bytes, list[bytes], list[str]]: ...
    def close(self) -> None: ...

def campaign_run(
    test: int, variant: int, full_scale: bool
) -> tuple[str, str, list[tuple[str, str]], float, float]: ...
def campaign(
    tests: str,
    variants: list[int],
    system: str,
    output: str,
    jobs: int,
    start: list[tuple[str, str]],
    keep_results: bool,
    full_scale: bool,
) -> tuple[
    str,
    list[tuple[str, str, int, Optional[float], Optional[float], int, str, Optional[bool]]],
    list[str],
]: ...

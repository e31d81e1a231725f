"""Type stubs of the extension module (see crane_cosim.run for the documented API)."""

from typing import Optional

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

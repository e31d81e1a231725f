"""A Gymnasium environment of the crane: ``crane_cosim.gym.CraneEnv`` (id ``crane_cosim/Crane-v0``).

One episode is one test of the thesis' campaign (tests 001-104, docs/campaign.md) over a closed
loop shipped in the package: at test scale (``scale="test"``, default) ``systems/closed_loop.json``
(platform, crane, pendulum, two IMUs, controller); at full scale (``scale="full"``)
``systems/full_scale_ahc.json`` (the 120 m vessel, the hydraulic knuckle-boom crane, a 5 t load on
the Froude-scaled rope, its control software: docs/full-scale.md), the test as the full-scale
campaign runs it. The environment holds the load still until the test proper starts (release,
control and ship motion at 10 s), then gives the agent one action per macro step (10 ms) until the
test's end (130 s: 120 s of control, 12,000 steps).

Actions (``action=``):

* ``"residual"`` (default): a correction on top of the controller's law, the action in [-1, 1]^3
  scaled by ``max_residual`` (world frame W, North-East-Down). At test scale it is added to the
  commanded tip after the thesis' delta law (eqs. 6.28-6.30; inputs ``residual.tip.*``, m); at
  full scale to the tip velocity of the anti-sway law (inputs ``residual.tip.v*``, m/s; the
  compensated tests only, where that law runs). A zero action leaves the closed loop exactly as it
  is: the run is the campaign's, bit for bit.
* ``"command"`` (test scale): the controller's world-frame tip command itself: the controller runs
  inverse kinematics only (``mode`` 1) on its external set-point (``setpoint`` 2), which is the
  fixed set-point plus the action times ``max_command`` (m); the agent replaces the anti-sway law.

Observations (``observe=``, 13 values: the load's two swing angles and their rates by difference,
the load's, the tip's and the hoist length's errors against the set-point, the ship's roll and
pitch) are what the controller has (``"estimates"``, default) or the simulation's truth
(``"truth"``). At test scale the controller's estimates: the load angles from the load IMU's
complementary filter, the lengths from the potentiometers, encoder and filters, the ship from the
deck IMU. At full scale what the control software reads: the tip from the (noisy) joint encoders,
the load's position (the angles from it relative to the tip), the motion reference unit's roll and
pitch.

The reward per step is minus the weighted sum, times the step (s), of the §7.2.2 quantities: the
swing energy per unit mass relative to that of a 10° swing (eq. 7.11 for the potential part, the
kinetic part from eqs. 4.94-4.96 with the tip held), the squared load set-point error relative to
(50 mm)² at test scale, (1.25 m)² at full scale (Froude: lengths ×25), and the actuator effort
(squared deviation of each command from neutral relative to its half range: the three voltages
and the winch duty at test scale, the four valve spools at full scale).
"""

from __future__ import annotations

import json
import math
import pathlib
from dataclasses import dataclass
from typing import Any, Optional

import gymnasium
import numpy
from gymnasium import spaces

from . import _native
from .simulation import Simulation

__all__ = ["CraneEnv", "SYSTEM", "FULL_SCALE_SYSTEM", "register", "rope_angles", "swing_energy"]

_SYSTEMS = pathlib.Path(__file__).resolve().parent / "systems"
#: The test-scale closed loop shipped in the package, its FMUs inside it.
SYSTEM = _SYSTEMS / "closed_loop.json"
#: The full-scale closed loop shipped in the package.
FULL_SCALE_SYSTEM = _SYSTEMS / "full_scale_ahc.json"

#: Gravity (m/s²), as the pendulum FMU has it (``pendulum.g``).
_G = 9.81
#: A 10° swing: the swing energy the reward counts as one unit.
_REFERENCE_ANGLE = math.radians(10.0)
#: Tests whose set-point moves (pick-and-place, 097-104): no fixed tip for the "command" action.
_MOVING_SETPOINT = range(97, 105)


@dataclass(frozen=True)
class _Scale:
    """The names and units of one scale's closed loop."""

    system: pathlib.Path
    #: Every name of the scale's loop (``crane_cosim._native.crane_names``).
    names: dict[str, Any]
    #: The inputs the residual action sets, and the action's default scale (m or m/s).
    residual: list[str]
    max_residual: float
    #: The controller's mode parameter and the mode in which its law runs (the residual acts).
    mode: str
    law_mode: int
    #: Observed: θx, θy (``None``: from the load relative to the tip), load xyz, tip xyz, hoist
    #: length, ship roll and pitch.
    estimates: tuple[Optional[list[str]], list[str]]
    truth: tuple[Optional[list[str]], list[str]]
    #: The set-point: load xyz, tip xyz, hoist length.
    setpoint: list[str]
    #: The reward's truth: θx, θy, ωx, ωy, lp, load xyz; then the actuator commands with their
    #: neutral values and half ranges.
    swing: list[str]
    commands: list[str]
    neutral: tuple[float, ...]
    half_range: tuple[float, ...]
    #: The load set-point error the reward counts as one unit (m).
    reference_error: float
    #: The noise seeds drawn anew each episode with ``sea="random"`` (besides ``platform.seed``).
    noise_seeds: list[str]


def _names(scale: str) -> dict[str, Any]:
    """The names of the scale's closed loop (``crane-names``: instances and variables)."""
    return json.loads(_native.crane_names(scale))


def _scale(scale: str, system: pathlib.Path, **units: Any) -> _Scale:
    """One scale's names as the environment reads them, and ``units``: its action's scale, its
    commands' neutral and half range, the set-point error counted as one unit."""
    n = _names(scale)
    controller = n["test"] or {}
    return _Scale(
        system=system,
        names=n,
        residual=n["residual"]["axes"],
        mode=n["mode"],
        law_mode=2,
        # The full-scale control software has no angle estimates: they come from the load and tip.
        estimates=(
            controller.get("estimated_theta"),
            [*n["estimated_load"]["axes"], *n["estimated_tip"]["axes"], n["estimated_lp"], *n["estimated_tilt"]],
        ),
        truth=(n["theta"], [*n["load"]["axes"], *n["tip"]["axes"], n["lp"], *n["ship"][3:5]]),
        setpoint=[*n["setpoint"]["axes"], *n["tip_reference"]["axes"], n["lp_reference"]],
        # The pendulum's truth the reward reads: θx, θy, ωx, ωy, lp, load xyz.
        swing=[*n["theta"], *n["omega"], n["rope_length"], *n["load"]["axes"]],
        commands=n["commands"],
        # Each episode's draws go to the seeds in the order of their names.
        noise_seeds=sorted(n["noise_seeds"]),
        **units,
    )


_TEST_SCALE = _scale(
    "test",
    SYSTEM,
    max_residual=0.05,
    # Actuator voltages 0-3.3 V and the winch duty 0-1 (Table 3.1).
    neutral=(1.65, 1.65, 1.65, 0.5),
    half_range=(1.65, 1.65, 1.65, 0.5),
    reference_error=0.05,
)

_FULL_SCALE = _scale(
    "full",
    FULL_SCALE_SYSTEM,
    max_residual=0.2,
    # The four valve spools, -1..1 (docs/full-scale.md).
    neutral=(0.0, 0.0, 0.0, 0.0),
    half_range=(1.0, 1.0, 1.0, 1.0),
    # The test scale's 50 mm, Froude-scaled (lengths ×25).
    reference_error=1.25,
)


def swing_energy(theta_x: float, theta_y: float, omega_x: float, omega_y: float, lp: float) -> float:
    """The pendulum's energy per unit mass (J/kg) about its rest below the tip, the tip held:
    potential ``g lp (1 - cos θx cos θy)`` (thesis eq. 7.11) plus kinetic ``½ |d/dt r|²`` of the
    load position relative to the tip, ``r = lp (sin θy, -cos θy sin θx, cos θy cos θx)``
    (eqs. 4.94-4.96), which is ``½ lp² (θy'² + cos² θy θx'²)``."""
    potential = _G * lp * (1.0 - math.cos(theta_x) * math.cos(theta_y))
    kinetic = 0.5 * lp * lp * (omega_y * omega_y + (math.cos(theta_y) * omega_x) ** 2)
    return potential + kinetic


def rope_angles(offset: numpy.ndarray, lp: float) -> numpy.ndarray:
    """The swing angles (θx, θy) (rad) of a load at ``offset`` (m, W) from the tip on a rope of
    ``lp`` (m): the inverse of ``r = lp (sin θy, -cos θy sin θx, cos θy cos θx)`` (eqs.
    4.94-4.96), θy from the x offset (clipped to the rope's length), θx from y and z."""
    theta_y = math.asin(max(-1.0, min(1.0, offset[0] / lp)))
    theta_x = math.atan2(-offset[1], offset[2])
    return numpy.array([theta_x, theta_y])


class CraneEnv(gymnasium.Env):
    """The crane's closed loop as a Gymnasium environment (see the module's doc).

    Parameters:
        test: the campaign test of each episode (1-104; default 089: world-frame compensation,
            fixed set-point, ship profile 1).
        variant: 1 truth feedback, 2 sensor feedback (noise in the sensors; default).
        scale: ``"test"`` (the thesis' crane, default) or ``"full"`` (the hydraulic offshore crane).
        action: ``"residual"`` or ``"command"`` (test scale only).
        observe: ``"estimates"`` or ``"truth"``.
        sea: ``"random"`` (default): each ``reset`` draws a new wave realisation (``platform.seed``)
            and new noise seeds from the episode's seed; ``"campaign"``: the campaign's own
            realisation and seeds every episode.
        max_residual: the residual action's scale (m at test scale, default 0.05; m/s at full
            scale, default 0.2).
        max_command: the command action's scale (m).
        weights: the reward's weights of (swing energy, set-point error, effort).
        system: the closed loop's system file (default: the scale's one in the package).
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        test: int = 89,
        variant: int = 2,
        action: str = "residual",
        observe: str = "estimates",
        sea: str = "random",
        max_residual: Optional[float] = None,
        max_command: float = 0.1,
        weights: tuple[float, float, float] = (1.0, 1.0, 0.01),
        system: Optional[str] = None,
        scale: str = "test",
    ) -> None:
        _check_choice("action", action, ("residual", "command"))
        _check_choice("observe", observe, ("estimates", "truth"))
        _check_choice("sea", sea, ("random", "campaign"))
        _check_choice("scale", scale, ("test", "full"))
        self._scale = _FULL_SCALE if scale == "full" else _TEST_SCALE
        if action == "command" and (scale == "full" or test in _MOVING_SETPOINT):
            reason = "runs at test scale only" if scale == "full" else "needs a fixed set-point; test {test}'s moves"
            raise ValueError(f"the 'command' action {reason.format(test=test)}")
        self.run_id, self.description, start, self._stop_time, self._active_from = _native.campaign_run(
            int(test), int(variant), scale == "full"
        )
        self._start = {name: json.loads(value) for name, value in start}
        if scale == "full" and self._start.get(self._scale.mode) != self._scale.law_mode:
            raise ValueError(f"test {test} at full scale: the arm does not run the anti-sway law the residual acts on")
        if action == "command":
            names = self._scale.names
            self._start.update({names["mode"]: 1, names["setpoint_source"]: 2})
        self.test, self.variant, self.scale, self._action, self._sea = test, variant, scale, action, sea
        if action == "residual":
            self._action_scale = self._scale.max_residual if max_residual is None else max_residual
        else:
            self._action_scale = max_command
        self._weights = weights
        self._system = system or str(self._scale.system)
        self._angles, positions = self._scale.estimates if observe == "estimates" else self._scale.truth
        # Everything a step reads, in one call: observed, set-point, reward.
        self._read = [*(self._angles or []), *positions, *self._scale.setpoint, *self._scale.swing]
        self._read += self._scale.commands
        self._simulation: Optional[Simulation] = None
        self._fixed_tip = numpy.zeros(3)
        self._previous_angles = numpy.zeros(2)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(3,), dtype=numpy.float64)
        self.observation_space = spaces.Box(-numpy.inf, numpy.inf, shape=(13,), dtype=numpy.float64)

    @property
    def simulation(self) -> Simulation:
        """The episode's simulation (to read any variable, or its ``results()``)."""
        if self._simulation is None:
            raise RuntimeError("reset() first")
        return self._simulation

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict[str, Any]] = None):
        super().reset(seed=seed)
        start = dict(self._start)
        if self._sea == "random":
            seeds = self._scale.noise_seeds
            draws = self.np_random.integers(1, 2**31 - 1, size=1 + len(seeds))
            start[self._scale.names["ship_seed"]] = int(draws[0])
            start.update({name: int(value) for name, value in zip(seeds, draws[1:])})
        self.close()
        self._simulation = Simulation(self._system, start=start, stop_time=self._stop_time)
        if self._action == "command":
            self._fixed_tip = numpy.array(self._simulation.get_reals(self._scale.names["test"]["fixed_setpoint"][:3]))
        self._apply(numpy.zeros(3))
        self._simulation.advance_to(self._active_from - self._simulation.step_size)
        self._previous_angles = self._observed_angles(self._read_all())
        self._simulation.step()
        if self._angles is None:
            # The full-scale control software gives its tip from the first active sample on, the
            # one this step took: no earlier angle to difference, the first rates are zero.
            self._previous_angles = self._observed_angles(self._read_all())
        observation, _ = self._observe()
        return observation, {"time": self._simulation.time, "run": self.run_id}

    def step(self, action):
        simulation = self.simulation
        self._apply(numpy.clip(numpy.asarray(action, dtype=numpy.float64), -1.0, 1.0))
        simulation.step()
        observation, reward = self._observe()
        return observation, reward, False, simulation.done, {"time": simulation.time}

    def close(self) -> None:
        if self._simulation is not None:
            self._simulation.close()
            self._simulation = None

    def _apply(self, action: numpy.ndarray) -> None:
        scaled = action * self._action_scale
        if self._action == "residual":
            self.simulation.set(dict(zip(self._scale.residual, scaled.tolist())))
        else:
            self.simulation.set(dict(zip(self._scale.names["test"]["setpoint_inputs"][:3], (self._fixed_tip + scaled).tolist())))

    def _read_all(self) -> numpy.ndarray:
        return numpy.array(self.simulation.get_reals(self._read))

    def _observed_angles(self, values: numpy.ndarray) -> numpy.ndarray:
        """θx, θy as observed: read, or from the load relative to the tip on the rope."""
        if self._angles is not None:
            return values[:2]
        return rope_angles(values[0:3] - values[3:6], values[6])

    def _observe(self) -> tuple[numpy.ndarray, float]:
        """The observation and the reward after a step, from one read of every variable."""
        values = self._read_all()
        angles = self._observed_angles(values)
        positions = values[(0 if self._angles is None else 2) :]
        rates = (angles - self._previous_angles) / self.simulation.step_size
        self._previous_angles = angles
        setpoint, truth = positions[9:16], positions[16:]
        errors = positions[:7] - setpoint
        observation = numpy.concatenate([angles, rates, errors, positions[7:9]])
        return observation, self._reward(truth, setpoint[:3])

    def _reward(self, truth: numpy.ndarray, load_setpoint: numpy.ndarray) -> float:
        theta_x, theta_y, omega_x, omega_y, lp = truth[:5]
        load, commands = truth[5:8], truth[8:]
        energy = swing_energy(theta_x, theta_y, omega_x, omega_y, lp) / (_G * lp * (1.0 - math.cos(_REFERENCE_ANGLE)))
        error = float(numpy.sum((load - load_setpoint) ** 2)) / self._scale.reference_error**2
        effort = float(numpy.sum(((commands - self._scale.neutral) / self._scale.half_range) ** 2))
        swing_weight, error_weight, effort_weight = self._weights
        return -self.simulation.step_size * (swing_weight * energy + error_weight * error + effort_weight * effort)


def _check_choice(name: str, value: str, choices: tuple[str, ...]) -> None:
    if value not in choices:
        raise ValueError(f"{name} {value!r}: expected one of {', '.join(map(repr, choices))}")


def register() -> None:
    """Registers ``crane_cosim/Crane-v0`` with Gymnasium (done on importing this module)."""
    if "crane_cosim/Crane-v0" not in gymnasium.registry:
        gymnasium.register(id="crane_cosim/Crane-v0", entry_point="crane_cosim.gym:CraneEnv")


register()

"""A Gymnasium environment of the crane: ``crane_cosim.gym.CraneEnv`` (id ``crane_cosim/Crane-v0``).

One episode is one test of the thesis' campaign (tests 001-104, docs/campaign.md) over the closed
loop shipped in the package (``crane_cosim/systems/closed_loop.json``: platform, crane, pendulum,
two IMUs, controller). The environment holds the load still until the test proper starts (release,
control and ship motion at 10 s), then gives the agent one action per macro step (10 ms) until the
test's end (130 s: 120 s of control, 12,000 steps).

Actions (``action=``):

* ``"residual"`` (default): a correction of the controller's commanded tip, added after the
  thesis' delta law (eqs. 6.28-6.30) through the controller's ``residual.tip.*`` inputs; the
  action in [-1, 1]^3 is scaled by ``max_residual`` (m, world frame W, North-East-Down). A zero
  action leaves the thesis' closed loop exactly as it is: the run is the campaign's, bit for bit.
* ``"command"``: the controller's world-frame tip command itself: the controller runs inverse
  kinematics only (``mode`` 1) on its external set-point (``setpoint`` 2), which is the fixed
  set-point plus the action times ``max_command`` (m); the agent replaces the anti-sway law.

Observations (``observe=``) are what the controller estimates (``"estimates"``, default: the load
angles from the load IMU's complementary filter and their rates by difference, the load, tip and
length errors against the set-point from the potentiometers, encoder and filters, the ship's roll
and pitch from the deck IMU) or the same quantities from the simulation's truth (``"truth"``).

The reward per step is minus the weighted sum, times the step (s), of the §7.2.2 quantities: the
swing energy per unit mass relative to that of a 10° swing (eq. 7.11 for the potential part, the
kinetic part from eqs. 4.94-4.96 with the tip held), the squared load set-point error relative to
(50 mm)², and the actuator effort (squared deviation of the three voltages and the winch duty from
neutral, relative to their ranges).
"""

from __future__ import annotations

import math
import pathlib
from typing import Any, Optional

import gymnasium
import numpy
from gymnasium import spaces

from . import Simulation, _native

__all__ = ["CraneEnv", "SYSTEM", "register"]

#: The closed loop shipped in the package, its FMUs inside it.
SYSTEM = pathlib.Path(__file__).resolve().parent / "systems" / "closed_loop.json"

#: Gravity (m/s²), as the pendulum FMU has it (``pendulum.g``).
_G = 9.81
#: A 10° swing: the swing energy the reward counts as one unit.
_REFERENCE_ANGLE = math.radians(10.0)
#: The load set-point error the reward counts as one unit (m).
_REFERENCE_ERROR = 0.05
#: Neutral commands and their half ranges: actuator voltages 0-3.3 V, winch duty 0-1 (Table 3.1).
_NEUTRAL_VOLTS, _HALF_VOLTS, _NEUTRAL_DUTY, _HALF_DUTY = 1.65, 1.65, 0.5, 0.5

_AXES = ("x", "y", "z")
_RESIDUAL = [f"controller.residual.tip.{a}" for a in _AXES]
_EXTERNAL = [f"controller.sp_in.tip.{a}" for a in _AXES]
_FIXED_TIP = [f"controller.sp.tip.{a}" for a in _AXES]

_ESTIMATES = [
    "controller.est.theta_x",
    "controller.est.theta_y",
    *[f"controller.est.load.{a}" for a in _AXES],
    *[f"controller.est.tip.{a}" for a in _AXES],
    "controller.est.lp",
    "controller.est.ship.roll",
    "controller.est.ship.pitch",
]
_TRUTH = [
    "pendulum.theta_x",
    "pendulum.theta_y",
    *[f"pendulum.load.{a}" for a in _AXES],
    *[f"crane.tip.{a}" for a in _AXES],
    "crane.lp",
    "platform.ship.roll",
    "platform.ship.pitch",
]
_SETPOINT = [
    *[f"controller.sp.load.{a}" for a in _AXES],
    *[f"controller.sp.ref.tip.{a}" for a in _AXES],
    "controller.sp.ref.lp",
]
#: What the reward is computed from: the truth, whatever the agent observes.
_REWARD = [
    "pendulum.theta_x",
    "pendulum.theta_y",
    "pendulum.omega_x",
    "pendulum.omega_y",
    "pendulum.lp",
    *[f"pendulum.load.{a}" for a in _AXES],
    "controller.u.base",
    "controller.u.boom",
    "controller.u.jib",
    "controller.u.winch",
]
#: The noise seeds of the closed loop's noisy instances, drawn anew each episode with ``sea="random"``.
_NOISE_SEEDS = ["crane.seed", "imu1.seed", "imu2.seed"]
#: Tests whose set-point moves (pick-and-place, 097-104): no fixed tip for the "command" action.
_MOVING_SETPOINT = range(97, 105)


def swing_energy(theta_x: float, theta_y: float, omega_x: float, omega_y: float, lp: float) -> float:
    """The pendulum's energy per unit mass (J/kg) about its rest below the tip, the tip held:
    potential ``g lp (1 - cos θx cos θy)`` (thesis eq. 7.11) plus kinetic ``½ |d/dt r|²`` of the
    load position relative to the tip, ``r = lp (sin θy, -cos θy sin θx, cos θy cos θx)``
    (eqs. 4.94-4.96), which is ``½ lp² (θy'² + cos² θy θx'²)``."""
    potential = _G * lp * (1.0 - math.cos(theta_x) * math.cos(theta_y))
    kinetic = 0.5 * lp * lp * (omega_y * omega_y + (math.cos(theta_y) * omega_x) ** 2)
    return potential + kinetic


class CraneEnv(gymnasium.Env):
    """The test-scale crane's closed loop as a Gymnasium environment (see the module's doc).

    Parameters:
        test: the campaign test of each episode (1-104; default 089: world-frame compensation,
            fixed set-point, ship profile 1).
        variant: 1 truth feedback, 2 sensor feedback (noise in the crane and both IMUs; default).
        action: ``"residual"`` or ``"command"``.
        observe: ``"estimates"`` or ``"truth"``.
        sea: ``"random"`` (default): each ``reset`` draws a new wave realisation (``platform.seed``)
            and new noise seeds from the episode's seed; ``"campaign"``: the campaign's own
            realisation and seeds every episode.
        max_residual, max_command: the action's scale (m).
        weights: the reward's weights of (swing energy, set-point error, effort).
        system: the closed loop's system file (default: the one in the package).
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        test: int = 89,
        variant: int = 2,
        action: str = "residual",
        observe: str = "estimates",
        sea: str = "random",
        max_residual: float = 0.05,
        max_command: float = 0.1,
        weights: tuple[float, float, float] = (1.0, 1.0, 0.01),
        system: Optional[str] = None,
    ) -> None:
        if action not in ("residual", "command"):
            raise ValueError(f"action {action!r}: expected 'residual' or 'command'")
        if observe not in ("estimates", "truth"):
            raise ValueError(f"observe {observe!r}: expected 'estimates' or 'truth'")
        if sea not in ("random", "campaign"):
            raise ValueError(f"sea {sea!r}: expected 'random' or 'campaign'")
        if action == "command" and test in _MOVING_SETPOINT:
            raise ValueError(f"test {test}: its set-point moves; the 'command' action needs a fixed one")
        self.run_id, self.description, start, self._stop_time, self._active_from = _native.campaign_run(
            int(test), int(variant), False
        )
        self._start = {name: _json(value) for name, value in start}
        if action == "command":
            self._start.update({"controller.mode": 1, "controller.setpoint": 2})
        self.test, self.variant, self._action, self._sea = test, variant, action, sea
        self._scale = max_residual if action == "residual" else max_command
        self._weights = weights
        self._system = system or str(SYSTEM)
        self._observed = _ESTIMATES if observe == "estimates" else _TRUTH
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
            draws = self.np_random.integers(1, 2**31 - 1, size=1 + len(_NOISE_SEEDS))
            start["platform.seed"] = int(draws[0])
            start.update({name: int(value) for name, value in zip(_NOISE_SEEDS, draws[1:])})
        self.close()
        self._simulation = Simulation(self._system, start=start, stop_time=self._stop_time)
        self._fixed_tip = numpy.array(self._simulation.get_reals(_FIXED_TIP))
        self._apply(numpy.zeros(3))
        self._simulation.advance_to(self._active_from - self._simulation.step_size)
        self._previous_angles = numpy.array(self._simulation.get_reals(self._observed[:2]))
        self._simulation.step()
        return self._observation(), {"time": self._simulation.time, "run": self.run_id}

    def step(self, action):
        simulation = self.simulation
        self._apply(numpy.clip(numpy.asarray(action, dtype=numpy.float64), -1.0, 1.0))
        simulation.step()
        observation = self._observation()
        reward = self._reward()
        return observation, reward, False, simulation.done, {"time": simulation.time}

    def close(self) -> None:
        if self._simulation is not None:
            self._simulation.close()
            self._simulation = None

    def _apply(self, action: numpy.ndarray) -> None:
        scaled = action * self._scale
        if self._action == "residual":
            self.simulation.set(dict(zip(_RESIDUAL, scaled.tolist())))
        else:
            self.simulation.set(dict(zip(_EXTERNAL, (self._fixed_tip + scaled).tolist())))

    def _observation(self) -> numpy.ndarray:
        simulation = self.simulation
        values = numpy.array(simulation.get_reals(self._observed))
        setpoint = numpy.array(simulation.get_reals(_SETPOINT))
        angles = values[:2]
        rates = (angles - self._previous_angles) / simulation.step_size
        self._previous_angles = angles
        errors = values[2:9] - setpoint
        return numpy.concatenate([angles, rates, errors[:3], errors[3:6], errors[6:7], values[9:11]])

    def _reward(self) -> float:
        theta_x, theta_y, omega_x, omega_y, lp, *rest = self.simulation.get_reals(_REWARD)
        load = numpy.array(rest[:3])
        volts, duty = numpy.array(rest[3:6]), rest[6]
        setpoint = numpy.array(self.simulation.get_reals(_SETPOINT[:3]))
        energy = swing_energy(theta_x, theta_y, omega_x, omega_y, lp) / (_G * lp * (1.0 - math.cos(_REFERENCE_ANGLE)))
        error = float(numpy.sum((load - setpoint) ** 2)) / _REFERENCE_ERROR**2
        effort = float(numpy.sum(((volts - _NEUTRAL_VOLTS) / _HALF_VOLTS) ** 2)) + ((duty - _NEUTRAL_DUTY) / _HALF_DUTY) ** 2
        swing_weight, error_weight, effort_weight = self._weights
        return -self.simulation.step_size * (swing_weight * energy + error_weight * error + effort_weight * effort)


def _json(text: str) -> Any:
    import json

    return json.loads(text)


def register() -> None:
    """Registers ``crane_cosim/Crane-v0`` with Gymnasium (done on importing this module)."""
    if "crane_cosim/Crane-v0" not in gymnasium.registry:
        gymnasium.register(id="crane_cosim/Crane-v0", entry_point="crane_cosim.gym:CraneEnv")


register()

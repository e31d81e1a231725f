//! The whole crane plant: three linear actuators and the winch driven by their hardware
//! commands, and the kinematic chain they move (thesis §3.5.2–3.5.3).

use super::actuator::{Actuator, AxisState, Propagator};
use super::mechanisms::STROKE;
use super::motion::{chain_motion, ChainMotion};
use super::winch::CableModel;
use super::{KinematicsError, MM_PER_M};
use crate::motion::AxisMotion;
use serde::{Deserialize, Serialize};

/// Hardware commands: actuator voltages (V, 0–3.3, neutral 1.65) for base, boom and jib, and
/// the winch duty cycle (0–1, neutral 0.5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Commands {
    /// Base, boom and jib actuator voltages (V, 0–3.3, neutral 1.65; Table 3.2).
    pub volts: [f64; 3],
    /// Winch duty cycle (0–1, neutral 0.5; Table 3.2).
    pub duty: f64,
}

default_is_const!(Commands, NEUTRAL);

impl Commands {
    /// Every actuator at its neutral command (Table 3.2): nothing moves.
    pub const NEUTRAL: Commands = Commands {
        volts: [Actuator::BASE.neutral, Actuator::BOOM.neutral, Actuator::JIB.neutral],
        duty: Actuator::WINCH.neutral,
    };
}

/// A crane pose at rest: the actuator extensions and the pendulum length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CranePose {
    /// Base, boom and jib actuator extensions (m, 0–0.05).
    pub extensions: [f64; 3],
    /// Pendulum length l_p (m), tip to load.
    pub lp: f64,
}

/// The default start of the crane: extensions 25.74, 30.65 and 23.7 mm put the tip within
/// 0.05 mm of the thesis' fixed set-point (3, −502, −153) mm in W on a level deck (§7.3,
/// Table 7.6), with the 700 mm pendulum of the tests.
pub const DEFAULT_POSE: CranePose = CranePose { extensions: [0.02574, 0.03065, 0.0237], lp: 0.7 };

/// Configuration of the plant (not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CraneConfig {
    /// Base, boom and jib actuators (mm).
    pub actuators: [Actuator; 3],
    /// Winch motor (deg).
    pub winch: Actuator,
    pub cable: CableModel,
}

default_is_const!(CraneConfig);

impl CraneConfig {
    /// The thesis' actuators (Table 3.2, eqs. 3.5–3.8) and cable model (eqs. 3.1–3.4).
    pub const DEFAULT: CraneConfig = CraneConfig {
        actuators: [Actuator::BASE, Actuator::BOOM, Actuator::JIB],
        winch: Actuator::WINCH,
        cable: CableModel::THESIS,
    };
}

/// The propagators of the base, boom and jib actuators and of the winch over one step of `h`
/// seconds: everything a step needs that depends on h alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepPropagators {
    /// The step (s).
    pub h: f64,
    actuators: [Propagator; 3],
    winch: Propagator,
}

/// The plant's continuous state: actuator positions and velocities (mm, mm/s) and the winch
/// angle from its home position and its rate (deg, deg/s).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct CraneState {
    pub actuators: [AxisState; 3],
    pub winch: AxisState,
}

impl CraneState {
    /// Actuator extensions (m).
    pub fn extensions(&self) -> [f64; 3] {
        self.actuators.map(|a| a.pos / MM_PER_M)
    }
}

impl CraneConfig {
    pub fn validate(&self) -> Result<(), String> {
        for (name, actuator) in ["base", "boom", "jib", "winch"].iter().zip(self.actuators.iter().chain([&self.winch]))
        {
            actuator.validate().map_err(|e| format!("{name} actuator: {e}"))?;
        }
        self.cable.validate()
    }

    /// The state at rest with the actuators at `extensions` (m, within 0–50 mm) and the winch
    /// angle chosen so the pendulum length is `lp` (m) (step 4 of §3.5.3).
    pub fn initial_state(&self, extensions: [f64; 3], lp: f64) -> Result<CraneState, String> {
        for (name, d) in ["base", "boom", "jib"].iter().zip(extensions) {
            if !(0.0..=STROKE).contains(&d) {
                return Err(format!("initial {name} extension {d} m is outside the 0–{STROKE} m stroke"));
            }
        }
        if !(lp > 0.0 && lp.is_finite()) {
            return Err(format!("initial pendulum length must be > 0 m, got {lp}"));
        }
        Ok(CraneState {
            actuators: extensions.map(|d| AxisState { pos: d * MM_PER_M, vel: 0.0 }),
            winch: AxisState { pos: self.cable.winch_angle(lp, extensions[2]), vel: 0.0 },
        })
    }

    /// Advances the plant by `h` seconds with the commands held (exact zero-order hold).
    pub fn advance(&self, s: &CraneState, cmd: &Commands, h: f64) -> CraneState {
        self.advance_with(s, cmd, &self.propagators(h))
    }

    /// The propagators of the four axes over a step of `h` seconds.
    pub fn propagators(&self, h: f64) -> StepPropagators {
        StepPropagators { h, actuators: self.actuators.map(|a| a.propagator(h)), winch: self.winch.propagator(h) }
    }

    /// [`CraneConfig::advance`] by `step.h` seconds, given this plant's propagators over that
    /// step (which a model stepping with a fixed h computes once).
    pub fn advance_with(&self, s: &CraneState, cmd: &Commands, step: &StepPropagators) -> CraneState {
        CraneState {
            actuators: [0, 1, 2]
                .map(|i| self.actuators[i].advance_with(&s.actuators[i], cmd.volts[i], &step.actuators[i])),
            winch: self.winch.advance_with(&s.winch, cmd.duty, &step.winch),
        }
    }

    /// Actuator extensions (m, m/s, m/s²) and the winch angle (deg, deg/s, deg/s²) in state `s`
    /// under the commands `cmd` (the accelerations follow from the commands).
    pub fn axis_motion(&self, s: &CraneState, cmd: &Commands) -> ([AxisMotion; 3], AxisMotion) {
        let linear = [0, 1, 2].map(|i| {
            let (a, x) = (&self.actuators[i], &s.actuators[i]);
            AxisMotion { pos: x.pos / MM_PER_M, vel: x.vel / MM_PER_M, acc: a.acceleration(x, cmd.volts[i]) / MM_PER_M }
        });
        let winch = AxisMotion { pos: s.winch.pos, vel: s.winch.vel, acc: self.winch.acceleration(&s.winch, cmd.duty) };
        (linear, winch)
    }

    /// The kinematic chain (joints, tip in J12, pendulum length) with exact derivatives.
    pub fn motion(&self, s: &CraneState, cmd: &Commands) -> Result<ChainMotion, KinematicsError> {
        let (linear, winch) = self.axis_motion(s, cmd);
        chain_motion(&linear, &winch, &self.cable)
    }
}

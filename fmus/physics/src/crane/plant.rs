//! The whole crane plant: three linear actuators and the winch driven by their hardware
//! commands, and the kinematic chain they move (thesis §3.5.2–3.5.3).

use super::actuator::{Actuator, AxisState};
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
    pub volts: [f64; 3],
    pub duty: f64,
}

impl Default for Commands {
    /// Every actuator at its neutral command.
    fn default() -> Self {
        Commands { volts: [1.65; 3], duty: 0.5 }
    }
}

/// Configuration of the plant (not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CraneConfig {
    /// Base, boom and jib actuators (mm).
    pub actuators: [Actuator; 3],
    /// Winch motor (deg).
    pub winch: Actuator,
    pub cable: CableModel,
}

impl Default for CraneConfig {
    fn default() -> Self {
        CraneConfig {
            actuators: [Actuator::BASE, Actuator::BOOM, Actuator::JIB],
            winch: Actuator::WINCH,
            cable: CableModel::default(),
        }
    }
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
        CraneState {
            actuators: [0, 1, 2].map(|i| self.actuators[i].advance(&s.actuators[i], cmd.volts[i], h)),
            winch: self.winch.advance(&s.winch, cmd.duty, h),
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

//! The operator's hold on the controller: its external set-point inputs (`sp_in.tip.*`,
//! `sp_in.lp`, used with `setpoint` = 2) and its tunable `mode`, written into the controller
//! instance before each of its steps.

use std::sync::{Arc, Mutex, PoisonError};

use cosim_engine::simulator::{Simulator, SimulatorError, Wrapper};
use fmu_import::value::Value;

/// What the operator commands (m, W = NED).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Commands {
    /// Tip set-point.
    pub tip: [f64; 3],
    /// Cable length set-point: the load hangs `lp` below the tip.
    pub lp: f64,
    /// The controller's mode: 2 compensated, 1 inverse kinematics only, 0 hold.
    pub mode: i32,
}

impl Commands {
    /// The load set-point (m, W): the tip set-point with the cable below it.
    pub fn load(&self) -> [f64; 3] {
        [self.tip[0], self.tip[1], self.tip[2] + self.lp]
    }

    /// Moves the load set-point by `delta` (m, W): north and east move the tip, down pays out
    /// cable.
    pub fn move_load(&mut self, delta: [f64; 3]) {
        self.tip[0] += delta[0];
        self.tip[1] += delta[1];
        self.lp += delta[2];
    }
}

/// The controller's value references the operator writes.
#[derive(Debug, Clone, Copy)]
pub struct Inputs {
    /// `sp_in.tip.x`, `sp_in.tip.y`, `sp_in.tip.z`, `sp_in.lp`.
    pub setpoint: [u32; 4],
    pub mode: u32,
}

/// Sets the operator's commands into the controller instance before every step.
pub struct Operator {
    pub inputs: Inputs,
    pub commands: Arc<Mutex<Commands>>,
}

impl Wrapper for Operator {
    fn before_step(&mut self, controller: &mut dyn Simulator) -> Result<(), SimulatorError> {
        let commands = *self.commands.lock().unwrap_or_else(PoisonError::into_inner);
        let [x, y, z] = commands.tip;
        controller.set_real(&self.inputs.setpoint, &[x, y, z, commands.lp])?;
        controller.set_value(self.inputs.mode, &Value::Integer(commands.mode))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moving_the_load_moves_the_tip_across_and_the_cable_length_down() {
        let mut commands = Commands { tip: [0.003, -0.502, -0.153], lp: 0.7, mode: 2 };
        assert_eq!(commands.load(), [0.003, -0.502, -0.153 + 0.7]);
        // North and east move the tip; up (W z negative) shortens the cable.
        commands.move_load([0.1, -0.02, -0.05]);
        assert_eq!(commands.tip, [0.003 + 0.1, -0.502 - 0.02, -0.153]);
        assert_eq!(commands.lp, 0.7 - 0.05);
    }
}

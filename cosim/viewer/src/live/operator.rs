//! The operator's hold on the controller: its external set-point inputs (`sp_in.tip.*`,
//! `sp_in.lp`, used with `setpoint` = 2) and its tunable `mode`, written into the controller
//! instance before each of its steps.

use std::sync::{Arc, Mutex, PoisonError};

use cosim_engine::simulator::{Simulator, SimulatorError};
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

/// The controller instance with the operator's commands set before every step.
pub struct Operated {
    pub inner: Box<dyn Simulator>,
    pub inputs: Inputs,
    pub commands: Arc<Mutex<Commands>>,
}

impl Operated {
    fn apply(&mut self) -> Result<(), SimulatorError> {
        let commands = *self.commands.lock().unwrap_or_else(PoisonError::into_inner);
        let [x, y, z] = commands.tip;
        self.inner.set_real(&self.inputs.setpoint, &[x, y, z, commands.lp])?;
        self.inner.set_value(self.inputs.mode, &Value::Integer(commands.mode))
    }
}

impl Simulator for Operated {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Result<(), SimulatorError> {
        self.inner.setup_experiment(start, stop)
    }
    fn enter_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.inner.enter_initialization_mode()
    }
    fn exit_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.inner.exit_initialization_mode()
    }
    fn do_step(&mut self, current: f64, step: f64) -> Result<(), SimulatorError> {
        self.apply()?;
        self.inner.do_step(current, step)
    }
    fn terminated(&self) -> Result<bool, SimulatorError> {
        self.inner.terminated()
    }
    fn last_successful_time(&self) -> Result<f64, SimulatorError> {
        self.inner.last_successful_time()
    }
    fn terminate(&mut self) -> Result<(), SimulatorError> {
        self.inner.terminate()
    }
    fn set_time_hint(&mut self, time: f64) {
        self.inner.set_time_hint(time)
    }
    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError> {
        self.inner.get_real(vrs, values)
    }
    fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SimulatorError> {
        self.inner.get_integer(vrs, values)
    }
    fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SimulatorError> {
        self.inner.get_boolean(vrs, values)
    }
    fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SimulatorError> {
        self.inner.get_string(vrs)
    }
    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError> {
        self.inner.set_real(vrs, values)
    }
    fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SimulatorError> {
        self.inner.set_integer(vrs, values)
    }
    fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SimulatorError> {
        self.inner.set_boolean(vrs, values)
    }
    fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SimulatorError> {
        self.inner.set_string(vrs, values)
    }
    fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Result<(), SimulatorError> {
        self.inner.set_real_input_derivatives(vrs, orders, values)
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

//! The operator's hold on the controller: its external set-point inputs (`sp_in.tip.*`,
//! `sp_in.lp`, used with `setpoint` = 2), where it has them, and its tunable `mode`, written
//! into the controller instance before each of its steps.

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

    /// The commands after moving the load set-point by `delta`, or why the move is refused: a
    /// delta that is not finite or larger than [`MAX_STEP`] on an axis, or a set-point that
    /// leaves [`TIP_NORTH`], [`TIP_EAST`] or [`CABLE`].
    pub fn checked_move(&self, delta: [f64; 3]) -> Result<Commands, String> {
        let shown = delta.map(distance).join(", ");
        let refuse = |why: String| format!("move [{shown}]: {why}");
        if let Some(d) = delta.iter().find(|d| !d.is_finite()) {
            return Err(refuse(format!("{d} is not a finite distance")));
        }
        for (d, axis) in delta.iter().zip(AXES) {
            if d.abs() > MAX_STEP {
                return Err(refuse(format!("{} m {axis} is more than {MAX_STEP} m per move", distance(d.abs()))));
            }
        }
        let mut next = *self;
        next.move_load(delta);
        let checks = [
            ("tip north", self.tip[0], delta[0], next.tip[0], TIP_NORTH),
            ("tip east", self.tip[1], delta[1], next.tip[1], TIP_EAST),
            ("cable length", self.lp, delta[2], next.lp, CABLE),
        ];
        for (name, from, by, to, (low, high)) in checks {
            if !(low..=high).contains(&to) {
                let by = if by < 0.0 { format!("− {}", -by) } else { format!("+ {by}") };
                return Err(refuse(format!("{name} {from:.3} m {by} m = {to:.3} m is outside {low}…{high} m")));
            }
        }
        Ok(next)
    }
}

/// `d` as the operator typed it, huge or tiny ones in exponent form.
fn distance(d: f64) -> String {
    if d != 0.0 && !(1e-6..1e6).contains(&d.abs()) {
        format!("{d:e}")
    } else {
        d.to_string()
    }
}

/// Largest set-point move per command and axis (m): ten key presses of the page.
pub const MAX_STEP: f64 = 0.1;
/// The directions of a move's components (W = NED).
const AXES: [&str; 3] = ["north", "east", "down"];
/// Tip set-point north, W x (m): the pick-and-place profile's ±0.10 m travel plus a margin.
pub const TIP_NORTH: (f64, f64) = (-0.15, 0.15);
/// Tip set-point east, W y (m): ±0.05 m about the fixed set-point's −0.502 m. At the box's far
/// corner (±0.15, −0.55) the tip is 0.36 m from the slew axis at y = −0.225 m, inside the
/// boom + jib reach of 0.375 m (l3y 225 mm + l4y 150 mm), so the arm is never stretched straight.
pub const TIP_EAST: (f64, f64) = (-0.55, -0.45);
/// Cable length set-point (m): the profile's 0.70…1.00 m with a margin; never slack nor so short
/// that the load swings up to the tip (θy near 90°).
pub const CABLE: (f64, f64) = (0.2, 1.2);

/// The controller's value references the operator writes.
#[derive(Debug, Clone, Copy)]
pub struct Inputs {
    /// `sp_in.tip.x`, `sp_in.tip.y`, `sp_in.tip.z`, `sp_in.lp`; none for a controller without
    /// external set-point inputs (the full-scale crane's).
    pub setpoint: Option<[u32; 4]>,
    /// `mode`, the controller's mode.
    pub mode: u32,
}

/// Sets the operator's commands into the controller instance before every step.
pub struct Operator {
    /// The value references written.
    pub inputs: Inputs,
    /// The page's latest commands.
    pub commands: Arc<Mutex<Commands>>,
}

impl Wrapper for Operator {
    fn before_step(&mut self, controller: &mut dyn Simulator) -> Result<(), SimulatorError> {
        let commands = *self.commands.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(setpoint) = &self.inputs.setpoint {
            let [x, y, z] = commands.tip;
            controller.set_real(setpoint, &[x, y, z, commands.lp])?;
        }
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

    #[test]
    fn a_move_out_of_bounds_is_refused_with_the_reason() {
        let commands = Commands { tip: [0.003, -0.502, -0.153], lp: 0.7, mode: 2 };
        let refused = |delta: [f64; 3]| commands.checked_move(delta).unwrap_err();
        assert_eq!(refused([0.0, 0.0, -5.0]), "move [0, 0, -5]: 5 m down is more than 0.1 m per move");
        assert_eq!(refused([1e308, 0.0, 0.0]), "move [1e308, 0, 0]: 1e308 m north is more than 0.1 m per move");
        assert_eq!(refused([f64::NAN, 0.0, 0.0]), "move [NaN, 0, 0]: NaN is not a finite distance");
        assert_eq!(refused([f64::INFINITY, 0.0, 0.0]), "move [inf, 0, 0]: inf is not a finite distance");
        let near = Commands { tip: [0.003, -0.502, -0.153], lp: 0.25, mode: 2 };
        assert_eq!(
            near.checked_move([0.0, 0.0, -0.1]).unwrap_err(),
            "move [0, 0, -0.1]: cable length 0.250 m − 0.1 m = 0.150 m is outside 0.2…1.2 m"
        );
        let east = Commands { tip: [0.003, -0.46, -0.153], lp: 0.7, mode: 2 };
        assert_eq!(
            east.checked_move([0.0, 0.05, 0.0]).unwrap_err(),
            "move [0, 0.05, 0]: tip east -0.460 m + 0.05 m = -0.410 m is outside -0.55…-0.45 m"
        );
        let moved = commands.checked_move([0.1, -0.02, -0.05]).unwrap();
        assert_eq!((moved.tip, moved.lp), ([0.003 + 0.1, -0.502 - 0.02, -0.153], 0.7 - 0.05));
    }
}

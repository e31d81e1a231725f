//! The recorded variables a frame is drawn from, and a [`Sample`] read from any row of them.

use crate::scene::Sample;

/// Ship surge, sway, heave, roll, pitch, yaw (the platform's outputs).
const SHIP: [&str; 6] = [
    "platform.ship.x",
    "platform.ship.y",
    "platform.ship.z",
    "platform.ship.roll",
    "platform.ship.pitch",
    "platform.ship.yaw",
];
/// The crane's joint angles.
const JOINTS: [&str; 3] = ["crane.joint.theta2z", "crane.joint.theta3x", "crane.joint.theta4x"];
/// The load, from the pendulum.
const LOAD: [&str; 3] = ["pendulum.load.x", "pendulum.load.y", "pendulum.load.z"];
const THETA: [&str; 2] = ["pendulum.theta_x", "pendulum.theta_y"];
/// The controller's estimate of the load and its set-point.
const ESTIMATED_LOAD: [&str; 3] = ["controller.est.load.x", "controller.est.load.y", "controller.est.load.z"];
const SETPOINT: [&str; 3] = ["controller.sp.load.x", "controller.sp.load.y", "controller.sp.load.z"];

/// Every variable the view needs, in the order [`Columns::sample`] reads them.
pub fn required() -> impl Iterator<Item = &'static str> {
    SHIP.into_iter().chain(JOINTS).chain(LOAD).chain(THETA).chain(ESTIMATED_LOAD).chain(SETPOINT)
}

/// Where each required variable sits among a row's values.
#[derive(Debug, Clone)]
pub struct Columns {
    index: Vec<usize>,
}

impl Columns {
    /// The positions of the required variables in `names`, or the names that are missing.
    pub fn find(names: &[String]) -> Result<Columns, Vec<&'static str>> {
        let found: Vec<_> = required().map(|name| (name, names.iter().position(|n| n == name))).collect();
        let missing: Vec<_> = found.iter().filter(|(_, i)| i.is_none()).map(|(name, _)| *name).collect();
        if !missing.is_empty() {
            return Err(missing);
        }
        Ok(Columns { index: found.into_iter().filter_map(|(_, i)| i).collect() })
    }

    /// The sample at `time` of a row whose `value(i)` is the value of the i-th name given to
    /// [`Columns::find`].
    pub fn sample(&self, time: f64, value: impl Fn(usize) -> f64) -> Sample {
        let mut values = self.index.iter().map(|&i| value(i));
        let mut next = || values.next().unwrap_or(f64::NAN);
        Sample {
            time,
            ship: std::array::from_fn(|_| next()),
            joints: std::array::from_fn(|_| next()),
            load: std::array::from_fn(|_| next()),
            theta: std::array::from_fn(|_| next()),
            estimated_load: std::array::from_fn(|_| next()),
            setpoint: std::array::from_fn(|_| next()),
        }
    }
}

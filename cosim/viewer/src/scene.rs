//! What the viewer draws at one instant, in the world frame W (North-East-Down, m): the deck
//! pose, the crane's joints and tip from its forward kinematics, the load and the two ghost
//! markers (the controller's estimated load and its set-point).
//!
//! The crane points come from the joint angles the crane FMU records (`crane.joint.*`) through
//! the same functions the FMU evaluates for `tip.*`: the serial chain of eqs. 4.73–4.75 in the
//! base frame J12 ([`kinematics::forward`]), the base offset [`CRANE_BASE`] in the ship frame B
//! and the ship's rigid-body transform ([`ShipMotion::point_in_world`]). A drawn tip therefore
//! lands where `crane.tip.*` says, to rounding.

use physics::crane::kinematics::{self, L2Z, L3Y};
use physics::crane::motion::CRANE_BASE;
use physics::crane::MM_PER_M;
use physics::math::Vec3;
use physics::motion::{PointMotion, ShipMotion};
use serde::Serialize;

/// The recorded values one frame is drawn from (SI units, W = NED unless said otherwise).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Time (s).
    pub time: f64,
    /// Ship surge, sway, heave (m, W) and roll, pitch, yaw (rad, Z–Y–X): the platform's outputs.
    pub ship: [f64; 6],
    /// Joint angles θ2z, θ3x, θ4x (rad): the crane's `joint.*` outputs.
    pub joints: [f64; 3],
    /// The load (m, W): the pendulum's `load.*`.
    pub load: [f64; 3],
    /// Pendulum angles θx, θy (rad): the pendulum's `theta_x`, `theta_y`.
    pub theta: [f64; 2],
    /// The controller's estimated load (m, W): `est.load.*`.
    pub estimated_load: [f64; 3],
    /// The controller's load set-point (m, W): `sp.load.*`.
    pub setpoint: [f64; 3],
}

/// Everything drawn at one instant (m and rad, W = NED; quaternion scalar first, W←B).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    pub time: f64,
    /// Origin of the ship (deck) frame B.
    pub deck_position: [f64; 3],
    /// Attitude of B, (w, x, y, z).
    pub deck_attitude: [f64; 4],
    /// The crane's joints from the deck up: slewing base J2,1, boom pivot J2,2, jib pivot, tip J4,2.
    pub crane: [[f64; 3]; 4],
    pub load: [f64; 3],
    pub estimated_load: [f64; 3],
    pub setpoint: [f64; 3],
    /// θx, θy (rad).
    pub theta: [f64; 2],
    /// Distance from the load to its set-point (m).
    pub setpoint_error: f64,
}

/// The crane's joints in its base frame J12 (m) for the joint angles (θ2z, θ3x, θ4x) (rad): the
/// slewing base, the top of the tower l2z, the end of the boom l3y (eqs. 4.73–4.75 without the
/// jib term) and the tip ([`kinematics::forward`], eqs. 4.73–4.75).
pub fn joints_in_base(theta: &[f64; 3]) -> [Vec3; 4] {
    let (s2, c2) = theta[0].sin_cos();
    let (s3, c3) = theta[1].sin_cos();
    let boom_reach = c3 * L3Y;
    let jib_pivot = Vec3::new(s2 * boom_reach, -(c2 * boom_reach), -(s3 * L3Y) - L2Z) / MM_PER_M;
    let [x, y, z] = kinematics::forward(theta);
    [Vec3::zeros(), Vec3::new(0.0, 0.0, -L2Z / MM_PER_M), jib_pivot, Vec3::new(x, y, z)]
}

/// The ship's pose as the crane FMU sees it (its `ship.*` inputs; the rates do not move points).
fn ship_pose(ship: &[f64; 6]) -> ShipMotion {
    let [x, y, z, roll, pitch, yaw] = *ship;
    ShipMotion { pos: Vec3::new(x, y, z), roll, pitch, yaw, ..ShipMotion::default() }
}

impl Frame {
    /// The frame of one sample.
    pub fn of(sample: &Sample) -> Frame {
        let ship = ship_pose(&sample.ship);
        // r = r_base + p/J12 in B, then p_W = p_ship + R r: the crane FMU's `tip_in_world`.
        let in_world = |p: Vec3| {
            let point = ship.point_in_world(&PointMotion { pos: CRANE_BASE + p, ..PointMotion::default() });
            point.pos.into()
        };
        let attitude = ship.attitude();
        let q = attitude.quaternion();
        let distance = Vec3::from(sample.load) - Vec3::from(sample.setpoint);
        Frame {
            time: sample.time,
            deck_position: ship.pos.into(),
            deck_attitude: [q.w, q.i, q.j, q.k],
            crane: joints_in_base(&sample.joints).map(in_world),
            load: sample.load,
            estimated_load: sample.estimated_load,
            setpoint: sample.setpoint,
            theta: sample.theta,
            setpoint_error: distance.norm(),
        }
    }

    /// The tip (m, W).
    pub fn tip(&self) -> [f64; 3] {
        self.crane[3]
    }
}

#[cfg(test)]
mod tests;

//! What the viewer draws at one instant, in the world frame W (North-East-Down, m): the deck
//! pose, the crane's joints and tip from its forward kinematics, the full-scale crane's luffing
//! cylinders, the load and, where the recording has them, the two ghost markers (the
//! controller's estimated load and its set-point).
//!
//! Two cranes ([`Crane`]). The thesis' test-scale crane is drawn from the joint angles its FMU
//! records (`crane.joint.*`) through the same functions the FMU evaluates for `tip.*`: the serial
//! chain of eqs. 4.73–4.75 in the base frame J12 ([`kinematics::forward`]) and the base offset
//! [`CRANE_BASE`] in the ship frame B. The full-scale knuckle-boom crane is drawn from its
//! `knuckle_boom.joint.*` through [`ArmParams::skeleton`], the chain its FMU evaluates for
//! `tip.*`, and its base offset [`ArmParams::base`]. Both go to W by the ship's rigid-body
//! transform ([`ShipMotion::point_in_world`]), so a drawn tip lands where the FMU's `tip.*` says,
//! to rounding.

use physics::crane::kinematics::{self, L2Z, L3Y};
use physics::crane::motion::CRANE_BASE;
use physics::crane::MM_PER_M;
use physics::knuckle_boom::{ArmParams, Mechanism};
use physics::math::Vec3;
use physics::motion::{PointMotion, ShipMotion};
use serde::Serialize;

/// Which crane is drawn, with what its geometry depends on.
// One `Crane` is made per view and copied into each frame's drawing: the arm's few hundred bytes
// are cheaper than a box, which would also cost the const `FULL_SCALE` and `Copy`.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Crane {
    /// The thesis' test-scale crane (FMU `crane`, systems/closed_loop.json), about 1 m tall.
    TestScale,
    /// The full-scale hydraulic knuckle-boom crane (FMU `knuckle_boom`, systems/full_scale*.json),
    /// drawn with the arm of its crane description and its pedestal foot at the FMU's `base.*`
    /// (m, ship frame B; see [`crate::replay::crane_of`]).
    FullScale { arm: ArmParams },
}

impl Crane {
    /// The default full-scale crane (the catalogue's `osp_derived`) with its pedestal at the
    /// FMU's default base (0, −8, 0) m.
    pub const FULL_SCALE: Crane = Crane::FullScale { arm: ArmParams::DEFAULT };

    /// The arm parameters the full-scale crane is drawn with; none for the test-scale crane.
    pub fn arm(&self) -> Option<ArmParams> {
        match *self {
            Crane::TestScale => None,
            Crane::FullScale { arm } => Some(arm),
        }
    }

    /// The page's name of the crane's scale: `"test"` or `"full"` (the scene's size and camera).
    pub fn scale(&self) -> &'static str {
        match self {
            Crane::TestScale => "test",
            Crane::FullScale { .. } => "full",
        }
    }
}

/// The recorded values one frame is drawn from (SI units, W = NED unless said otherwise).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Time (s).
    pub time: f64,
    /// Ship surge, sway, heave (m, W) and roll, pitch, yaw (rad, Z–Y–X): the platform's outputs.
    pub ship: [f64; 6],
    /// Joint angles (rad): the test-scale crane's `joint.theta2z`, `theta3x`, `theta4x`, or the
    /// full-scale crane's `joint.slew`, `boom`, `jib`.
    pub joints: [f64; 3],
    /// The load (m, W): the pendulum's `load.*`.
    pub load: [f64; 3],
    /// Pendulum angles θx, θy (rad): the pendulum's `theta_x`, `theta_y`.
    pub theta: [f64; 2],
    /// The controller's estimated load (m, W): `est.load.*`, where the controller has one.
    pub estimated_load: Option<[f64; 3]>,
    /// The controller's load set-point (m, W): `sp.load.*`, where the controller has one.
    pub setpoint: Option<[f64; 3]>,
    /// The hook (m, W): a rigging's `hook.*`, where the recording has it.
    pub hook: Option<[f64; 3]>,
}

/// Everything drawn at one instant (m and rad, W = NED; quaternion scalar first, W←B). The
/// optional parts are left out of the JSON when absent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    /// Simulated time (s).
    pub time: f64,
    /// Origin of the ship (deck) frame B.
    pub deck_position: [f64; 3],
    /// Attitude of B, (w, x, y, z).
    pub deck_attitude: [f64; 4],
    /// The crane's joints from the deck up: test scale the slewing base J2,1, boom pivot J2,2,
    /// jib pivot and tip J4,2; full scale the pedestal foot, boom pivot, knuckle and tip.
    pub crane: [[f64; 3]; 4],
    /// The full-scale crane's boom and jib cylinders, three points each: the barrel's pin, the
    /// barrel's end (where the rod comes out) and the rod's pin.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cylinders: Option<[[f64; 3]; 6]>,
    /// The load's position.
    pub load: [f64; 3],
    /// The hook between the hoist rope and the sling, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hook: Option<[f64; 3]>,
    /// The controller's estimated load, where it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated_load: Option<[f64; 3]>,
    /// The controller's load set-point, where it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub setpoint: Option<[f64; 3]>,
    /// θx, θy (rad).
    pub theta: [f64; 2],
    /// Distance from the load to its set-point (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub setpoint_error: Option<f64>,
}

/// The test-scale crane's joints in its base frame J12 (m) for the joint angles (θ2z, θ3x, θ4x)
/// (rad): the slewing base, the top of the tower l2z, the end of the boom l3y (eqs. 4.73–4.75
/// without the jib term) and the tip ([`kinematics::forward`], eqs. 4.73–4.75).
pub fn joints_in_base(theta: &[f64; 3]) -> [Vec3; 4] {
    let (s2, c2) = theta[0].sin_cos();
    let (s3, c3) = theta[1].sin_cos();
    let boom_reach = c3 * L3Y;
    let jib_pivot = Vec3::new(s2 * boom_reach, -(c2 * boom_reach), -(s3 * L3Y) - L2Z) / MM_PER_M;
    let [x, y, z] = kinematics::forward(theta);
    [Vec3::zeros(), Vec3::new(0.0, 0.0, -L2Z / MM_PER_M), jib_pivot, Vec3::new(x, y, z)]
}

/// The full-scale crane's points in the ship frame B (m) at the joints `q` = (slew, boom, jib)
/// (rad): the chain of [`ArmParams::skeleton`] (foot, boom pivot, knuckle, tip) and each
/// cylinder's barrel pin, barrel end and rod pin, all moved from the crane base frame K to B by
/// the base offset (K and B are aligned).
pub fn full_scale_in_ship(arm: &ArmParams, q: &[f64; 3]) -> ([Vec3; 4], [Vec3; 6]) {
    let s = arm.skeleton(q);
    let [boom, jib] = [(s.boom_cylinder, &arm.boom_cylinder), (s.jib_cylinder, &arm.jib_cylinder)]
        .map(|(pins, mechanism)| barrel_and_rod(pins, mechanism));
    let cylinders = [boom[0], boom[1], boom[2], jib[0], jib[1], jib[2]];
    ([s.foot, s.pivot, s.knuckle, s.tip].map(|p| arm.base + p), cylinders.map(|p| arm.base + p))
}

/// A cylinder between its `pins` as drawn: the barrel from the lower pin as long as the
/// retracted pin-to-pin length (the barrel and the rod's eye when the rod is all in), the rod
/// out of it to the upper pin.
fn barrel_and_rod(pins: [Vec3; 2], mechanism: &Mechanism) -> [Vec3; 3] {
    let [lower, upper] = pins;
    let length = (upper - lower).norm();
    let barrel = if length > 0.0 { (mechanism.min_length / length).min(1.0) } else { 0.0 };
    [lower, lower + (upper - lower) * barrel, upper]
}

/// The ship's pose as the crane FMU sees it (its `ship.*` inputs; the rates do not move points).
fn ship_pose(ship: &[f64; 6]) -> ShipMotion {
    let [x, y, z, roll, pitch, yaw] = *ship;
    ShipMotion { pos: Vec3::new(x, y, z), roll, pitch, yaw, ..ShipMotion::default() }
}

impl Frame {
    /// The frame of one sample of `crane`.
    pub fn of(crane: &Crane, sample: &Sample) -> Frame {
        let ship = ship_pose(&sample.ship);
        // p_W = p_ship + R r, r the point in B: the crane FMUs' `tip_in_world`.
        let in_world =
            |r: Vec3| -> [f64; 3] { ship.point_in_world(&PointMotion { pos: r, ..PointMotion::default() }).pos.into() };
        let (joints, cylinders) = match crane.arm() {
            None => (joints_in_base(&sample.joints).map(|p| CRANE_BASE + p), None),
            Some(arm) => {
                let (joints, cylinders) = full_scale_in_ship(&arm, &sample.joints);
                (joints, Some(cylinders.map(in_world)))
            }
        };
        let attitude = ship.attitude();
        let q = attitude.quaternion();
        let distance = |setpoint: [f64; 3]| (Vec3::from(sample.load) - Vec3::from(setpoint)).norm();
        Frame {
            time: sample.time,
            deck_position: ship.pos.into(),
            deck_attitude: [q.w, q.i, q.j, q.k],
            crane: joints.map(in_world),
            cylinders,
            load: sample.load,
            hook: sample.hook,
            estimated_load: sample.estimated_load,
            setpoint: sample.setpoint,
            theta: sample.theta,
            setpoint_error: sample.setpoint.map(distance),
        }
    }

    /// The tip (m, W).
    pub fn tip(&self) -> [f64; 3] {
        self.crane[3]
    }
}

#[cfg(test)]
mod tests;

//! The motion vocabulary shared by the ship, the platform, the crane and the estimators: a scalar
//! coordinate, a point and a rigid body with their first and second time derivatives, and the
//! ship's six degrees of freedom.
//!
//! Frames and units: world frame W North-East-Down (x north, y east, z down), ship (deck) frame B
//! (x bow, y starboard, z down), aligned with W at rest. Positions in m, angles in rad; the ship's
//! attitude is the Z–Y–X sequence R = R_z(yaw) R_y(pitch) R_x(roll) (W←B, eq. 5.1 / C.49).
//!
//! The rigid-body kinematics of a point moving relative to the ship, with r its position in B, ṙ
//! and r̈ its velocity and acceleration relative to B (in B coordinates), R the ship attitude, ω
//! and α the ship's angular velocity and acceleration in B:
//!
//! ```text
//! p = p_ship + R r
//! v = v_ship + R (ω × r + ṙ)
//! a = a_ship + R (α × r + ω × (ω × r) + 2 ω × ṙ + r̈)
//! ```

use crate::math::{euler_zyx, euler_zyx_body_rates, Quat, Vec3};
use num_dual::{DualStruct, HyperDual64};
use serde::{Deserialize, Serialize};

/// Index of surge (m, W x) in a six-vector of ship motions.
pub const SURGE: usize = 0;
/// Index of sway (m, W y).
pub const SWAY: usize = 1;
/// Index of heave (m, W z, positive down).
pub const HEAVE: usize = 2;
/// Index of roll (rad, Z–Y–X, applied last).
pub const ROLL: usize = 3;
/// Index of pitch (rad, Z–Y–X).
pub const PITCH: usize = 4;
/// Index of yaw (rad, Z–Y–X, applied first).
pub const YAW: usize = 5;

/// Names of the six degrees of freedom, in index order.
pub const DOF_NAMES: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

/// A scalar coordinate with its first and second time derivatives (the unit is stated where it
/// is used: m, rad, or the winch's deg).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AxisMotion {
    pub pos: f64,
    pub vel: f64,
    pub acc: f64,
}

impl AxisMotion {
    /// The hyper-dual number q + q̇ ε1 + q̇ ε2 + q̈ ε1ε2: any function evaluated on it returns
    /// f + ḟ ε1 + ḟ ε2 + f̈ ε1ε2 (forward-mode automatic differentiation in time).
    pub fn jet(&self) -> HyperDual64 {
        HyperDual64::new(self.pos, self.vel, self.vel, self.acc)
    }

    /// The value, first and second time derivative a hyper-dual result carries (see [`Self::jet`]).
    pub fn from_jet(x: &HyperDual64) -> AxisMotion {
        AxisMotion { pos: x.re(), vel: x.eps1, acc: x.eps1eps2 }
    }
}

/// A point's position, velocity and acceleration (m, m/s, m/s²; the frame is stated where used).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PointMotion {
    pub pos: Vec3,
    pub vel: Vec3,
    pub acc: Vec3,
}

/// Motion of the ship (deck) frame B: the platform's outputs.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ShipMotion {
    /// Position of B's origin in W (m): surge, sway, heave.
    pub pos: Vec3,
    /// Attitude angles (rad), applied yaw–pitch–roll (Z–Y–X): R = R_z(yaw) R_y(pitch) R_x(roll).
    pub roll: f64,
    pub pitch: f64,
    pub yaw: f64,
    /// Velocity and acceleration of B's origin in W (m/s, m/s²).
    pub vel: Vec3,
    pub acc: Vec3,
    /// Angular velocity and angular acceleration of B, in B (rad/s, rad/s²).
    pub omega: Vec3,
    pub alpha: Vec3,
}

impl ShipMotion {
    /// A ship at rest at W's origin.
    pub const AT_REST: ShipMotion = ShipMotion {
        pos: Vec3::new(0.0, 0.0, 0.0),
        roll: 0.0,
        pitch: 0.0,
        yaw: 0.0,
        vel: Vec3::new(0.0, 0.0, 0.0),
        acc: Vec3::new(0.0, 0.0, 0.0),
        omega: Vec3::new(0.0, 0.0, 0.0),
        alpha: Vec3::new(0.0, 0.0, 0.0),
    };

    /// Orientation W←B.
    pub fn attitude(&self) -> Quat {
        euler_zyx(self.roll, self.pitch, self.yaw)
    }

    /// World motion (W) of a point moving relative to the ship, given by its position, velocity
    /// and acceleration relative to B, in B coordinates (m, m/s, m/s²): rigid-body kinematics with
    /// the transport, centripetal and Coriolis terms (the module documentation's equations).
    pub fn point_in_world(&self, r: &PointMotion) -> PointMotion {
        self.point_in_world_at(&self.attitude(), r)
    }

    /// [`Self::point_in_world`] with the attitude W←B already evaluated (`rotation` =
    /// [`Self::attitude`]), for callers that also need it for other vectors.
    pub fn point_in_world_at(&self, rotation: &Quat, r: &PointMotion) -> PointMotion {
        let (w, alpha) = (&self.omega, &self.alpha);
        let w_r = w.cross(&r.pos);
        PointMotion {
            pos: self.pos + rotation * r.pos,
            vel: self.vel + rotation * (w_r + r.vel),
            acc: self.acc + rotation * (alpha.cross(&r.pos) + w.cross(&w_r) + w.cross(&r.vel) * 2.0 + r.acc),
        }
    }
}

/// Surge, sway, heave (m, W; heave positive down) and roll, pitch, yaw (rad, Z–Y–X angles of B
/// relative to W), each with its first and second time derivatives, indexed by [`SURGE`] …
/// [`YAW`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DeckMotion {
    pub dof: [AxisMotion; 6],
}

impl DeckMotion {
    /// Whether `other` holds the same bits in every field: unlike `==`, tells 0.0 from −0.0 (a
    /// cached result computed from one must not stand in for the other).
    pub fn same_bits(&self, other: &DeckMotion) -> bool {
        let bits = |m: &DeckMotion| m.dof.map(|a| [a.pos.to_bits(), a.vel.to_bits(), a.acc.to_bits()]);
        bits(self) == bits(other)
    }

    /// The positions (m) and angles (rad) alone.
    pub fn pose(&self) -> [f64; 6] {
        self.dof.map(|d| d.pos)
    }

    /// Pose, linear velocity and acceleration in W, angular velocity and acceleration in B (the
    /// Z–Y–X kinematic equation, [`euler_zyx_body_rates`]).
    pub fn to_ship_motion(&self) -> ShipMotion {
        let d = &self.dof;
        let angles = [d[ROLL].pos, d[PITCH].pos, d[YAW].pos];
        let rates = [d[ROLL].vel, d[PITCH].vel, d[YAW].vel];
        let accelerations = [d[ROLL].acc, d[PITCH].acc, d[YAW].acc];
        let (omega, alpha) = euler_zyx_body_rates(angles, rates, accelerations);
        ShipMotion {
            pos: Vec3::new(d[SURGE].pos, d[SWAY].pos, d[HEAVE].pos),
            roll: angles[0],
            pitch: angles[1],
            yaw: angles[2],
            vel: Vec3::new(d[SURGE].vel, d[SWAY].vel, d[HEAVE].vel),
            acc: Vec3::new(d[SURGE].acc, d[SWAY].acc, d[HEAVE].acc),
            omega,
            alpha,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deck() -> DeckMotion {
        let axis = |pos: f64, vel: f64, acc: f64| AxisMotion { pos, vel, acc };
        DeckMotion {
            dof: [
                axis(0.3, -0.1, 0.02),
                axis(-0.2, 0.05, -0.01),
                axis(0.4, 0.3, -0.2),
                axis(0.03, -0.02, 0.01),
                axis(-0.02, 0.01, 0.005),
                axis(0.1, 0.004, -0.002),
            ],
        }
    }

    #[test]
    fn ship_motion_carries_the_pose_and_the_body_rates() {
        let m = deck();
        let s = m.to_ship_motion();
        let d = &m.dof;
        assert_eq!((s.pos.x, s.pos.y, s.pos.z), (d[SURGE].pos, d[SWAY].pos, d[HEAVE].pos));
        assert_eq!((s.vel.x, s.vel.y, s.acc.z), (d[SURGE].vel, d[SWAY].vel, d[HEAVE].acc));
        assert!(s.attitude().angle_to(&euler_zyx(d[ROLL].pos, d[PITCH].pos, d[YAW].pos)) < 1e-15);
        let (omega, alpha) = euler_zyx_body_rates(
            [d[ROLL].pos, d[PITCH].pos, d[YAW].pos],
            [d[ROLL].vel, d[PITCH].vel, d[YAW].vel],
            [d[ROLL].acc, d[PITCH].acc, d[YAW].acc],
        );
        assert_eq!((s.omega, s.alpha), (omega, alpha));
        assert_eq!(m.pose(), d.map(|a| a.pos));
    }

    #[test]
    fn same_bits_tells_signed_zeros_apart() {
        let m = deck();
        assert!(m.same_bits(&m));
        let (mut zero, mut negative) = (DeckMotion::default(), DeckMotion::default());
        negative.dof[PITCH].acc = -0.0;
        assert!(zero == negative && !zero.same_bits(&negative));
        zero.dof[PITCH].acc = 0.0;
        assert!(zero.same_bits(&DeckMotion::default()));
    }

    #[test]
    fn still_water_is_the_default() {
        assert_eq!(DeckMotion::default().to_ship_motion(), ShipMotion::default());
    }

    #[test]
    fn a_jet_carries_the_derivatives_through_a_function() {
        // f(q) = q²: ḟ = 2 q q̇, f̈ = 2 q̇² + 2 q q̈.
        let q = AxisMotion { pos: 1.5, vel: -0.4, acc: 0.3 };
        let f = AxisMotion::from_jet(&(q.jet() * q.jet()));
        assert!((f.pos - 2.25).abs() < 1e-15 && (f.vel + 1.2).abs() < 1e-15 && (f.acc - 1.22).abs() < 1e-15, "{f:?}");
    }

    #[test]
    fn a_point_fixed_on_a_spinning_ship_moves_on_a_circle() {
        // Yaw rate ω about z, the point 2 m ahead of the origin: v = ω × r, a = −ω² r.
        let ship = ShipMotion { omega: Vec3::new(0.0, 0.0, 0.5), ..ShipMotion::default() };
        let p = ship.point_in_world(&PointMotion { pos: Vec3::new(2.0, 0.0, 0.0), ..PointMotion::default() });
        assert_eq!(p.pos, Vec3::new(2.0, 0.0, 0.0));
        assert!((p.vel - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
        assert!((p.acc - Vec3::new(-0.5, 0.0, 0.0)).norm() < 1e-15);
    }
}

//! Positions from the estimated ship attitude, the crane's forward kinematics and the pendulum
//! angles (thesis §5.2.1).
//!
//! The crane base frame J12 is aligned with the ship frame B and sits at r_base in B, so a point
//! p given in J12 is, in the world frame W (eq. 5.65 written with rotation matrices),
//!
//! ```text
//! ^W p = p_ship + R_ship (r_base + ^J12 p)
//! ```
//!
//! with p_ship the ship's surge, sway and heave and R_ship its attitude (W←B). The load hangs at
//! (eqs. 5.62–5.64)
//!
//! ```text
//! x_p = x_t + l_p sin θy,   y_p = y_t − l_p cos θy sin θx,   z_p = z_t + l_p cos θy cos θx.
//! ```

use crate::math::{Quat, Vec3};

/// The pose of the crane base frame J12 in W: where the ship carries the crane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseFrame {
    /// Origin of J12 in W (m).
    pub origin: Vec3,
    /// Attitude W←J12 (= W←B).
    pub attitude: Quat,
}

impl BaseFrame {
    /// The base frame for the ship at `ship_position` (m, W) with attitude `ship_attitude` (W←B),
    /// the crane standing at `crane_base` (m, B).
    pub fn new(ship_position: &Vec3, ship_attitude: &Quat, crane_base: &Vec3) -> Self {
        BaseFrame { origin: ship_position + ship_attitude * crane_base, attitude: *ship_attitude }
    }

    /// A point given in J12 (m), in W (eq. 5.65).
    pub fn to_world(&self, p: &Vec3) -> Vec3 {
        self.origin + self.attitude * p
    }

    /// A point given in W (m), in J12: the inverse of [`BaseFrame::to_world`].
    pub fn to_base(&self, p: &Vec3) -> Vec3 {
        self.attitude.inverse_transform_vector(&(p - self.origin))
    }
}

/// The load position (m, W) hanging `lp` (m) below the tip `tip` (m, W) at the pendulum angles
/// θx, θy (rad), eqs. 5.62–5.64.
pub fn load_position(tip: &Vec3, lp: f64, theta_x: f64, theta_y: f64) -> Vec3 {
    let (sx, cx) = theta_x.sin_cos();
    let (sy, cy) = theta_y.sin_cos();
    tip + Vec3::new(sy, -cy * sx, cy * cx) * lp
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crane::motion::{tip_in_world, ChainMotion, CRANE_BASE};
    use crate::estimation::euler::pendulum_orientation;
    use crate::math::euler_zyx;
    use crate::motion::{PointMotion, ShipMotion};

    #[test]
    fn the_base_frame_places_the_tip_like_the_crane_model() {
        let ship = ShipMotion {
            pos: Vec3::new(0.01, -0.02, 0.005),
            roll: 0.05,
            pitch: -0.03,
            yaw: 0.02,
            ..ShipMotion::default()
        };
        let tip_base = Vec3::new(0.003, -0.277, -0.153);
        let chain =
            ChainMotion { tip: PointMotion { pos: tip_base, ..PointMotion::default() }, ..ChainMotion::default() };
        let frame = BaseFrame::new(&ship.pos, &euler_zyx(ship.roll, ship.pitch, ship.yaw), &CRANE_BASE);
        let world = frame.to_world(&tip_base);
        assert!((world - tip_in_world(&ship, &chain).pos).norm() < 1e-15);
        assert!((frame.to_base(&world) - tip_base).norm() < 1e-15);
    }

    #[test]
    fn the_load_hangs_along_the_body_z_axis_of_its_orientation() {
        let tip = Vec3::new(0.003, -0.502, -0.153);
        let (x, y, lp) = (0.2, -0.1, 0.7);
        let expected = tip + pendulum_orientation(x, y, 0.0) * Vec3::z() * lp;
        assert!((load_position(&tip, lp, x, y) - expected).norm() < 1e-15);
        // At rest the load is l_p below the tip (z down).
        assert_eq!(load_position(&tip, lp, 0.0, 0.0), tip + Vec3::new(0.0, 0.0, lp));
    }
}

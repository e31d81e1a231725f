//! Velocities and accelerations of the crane chain and of the tip in the world frame.
//!
//! Time derivatives of the kinematic chain are exact, by forward-mode automatic differentiation:
//! each actuator coordinate q(t) enters as the hyper-dual number q + q̇ ε1 + q̇ ε2 + q̈ ε1ε2, and
//! any function f evaluated on such numbers returns f + ḟ ε1 + ḟ ε2 + f̈ ε1ε2, since the ε1ε2
//! part is ∇f·q̈ + q̇ᵀ ∇²f q̇ = d²f/dt². The mechanism and serial kinematics are written generic
//! over [`Scalar`](super::Scalar), so one evaluation gives position, velocity and acceleration.
//!
//! The tip in the world frame W follows from the ship motion by rigid-body kinematics. With
//! r = r_base + p_tip/J12 in the ship frame B (J12 is aligned with B), R the ship attitude
//! (W←B), ω and α the ship's angular velocity and acceleration in B:
//!
//! ```text
//! p = p_ship + R r
//! v = v_ship + R (ω × r + ṙ)
//! a = a_ship + R (α × r + ω × (ω × r) + 2 ω × ṙ + r̈)
//! ```

use super::mechanisms::joints_from_actuators;
use super::winch::CableModel;
use super::{kinematics, KinematicsError};
use crate::math::{euler_zyx, Quat, Vec3};
use num_dual::{DualStruct, HyperDual64};
use serde::{Deserialize, Serialize};

/// Origin of the crane base frame J12 in the ship frame B (m): 0.225 m to port of the deck centre
/// (Fig. 3.7b).
pub const CRANE_BASE: Vec3 = Vec3::new(0.0, -0.225, 0.0);

/// A scalar coordinate with its first and second time derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AxisMotion {
    pub pos: f64,
    pub vel: f64,
    pub acc: f64,
}

impl AxisMotion {
    /// q + q̇ ε1 + q̇ ε2 + q̈ ε1ε2.
    fn jet(&self) -> HyperDual64 {
        HyperDual64::new(self.pos, self.vel, self.vel, self.acc)
    }

    fn from_jet(x: HyperDual64) -> AxisMotion {
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

/// The crane's kinematic chain at one instant, relative to its base frame J12.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ChainMotion {
    /// Joint angles θ2z, θ3x, θ4x (rad, rad/s, rad/s²).
    pub joints: [AxisMotion; 3],
    /// The tip J4,2 in J12 (m, m/s, m/s²).
    pub tip: PointMotion,
    /// Pendulum length l_p (m, m/s, m/s²).
    pub lp: AxisMotion,
}

/// The chain's motion for actuator extensions `extensions` (m, m/s, m/s²) and the winch angle
/// `winch` (deg, deg/s, deg/s²): mechanism forward kinematics, eqs. 4.73–4.75 and 3.1–3.4 with
/// exact derivatives.
pub fn chain_motion(
    extensions: &[AxisMotion; 3],
    winch: &AxisMotion,
    cable: &CableModel,
) -> Result<ChainMotion, KinematicsError> {
    let d = extensions.map(|e| e.jet());
    let theta = joints_from_actuators(&d)?;
    let tip = kinematics::forward(&theta);
    let lp = cable.length(winch.jet(), d[2]);
    let part = |f: fn(&HyperDual64) -> f64| Vec3::new(f(&tip[0]), f(&tip[1]), f(&tip[2]));
    Ok(ChainMotion {
        joints: theta.map(AxisMotion::from_jet),
        tip: PointMotion { pos: part(|x| x.re), vel: part(|x| x.eps1), acc: part(|x| x.eps1eps2) },
        lp: AxisMotion::from_jet(lp),
    })
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
    /// Orientation W←B.
    pub fn attitude(&self) -> Quat {
        euler_zyx(self.roll, self.pitch, self.yaw)
    }

    /// World motion of a point moving relative to the ship, given by its position, velocity and
    /// acceleration relative to B, in B coordinates (rigid-body kinematics with the transport,
    /// centripetal and Coriolis terms).
    pub fn point_in_world(&self, r: &PointMotion) -> PointMotion {
        let rotation = self.attitude();
        let (w, alpha) = (&self.omega, &self.alpha);
        let w_r = w.cross(&r.pos);
        PointMotion {
            pos: self.pos + rotation * r.pos,
            vel: self.vel + rotation * (w_r + r.vel),
            acc: self.acc + rotation * (alpha.cross(&r.pos) + w.cross(&w_r) + w.cross(&r.vel) * 2.0 + r.acc),
        }
    }
}

/// The tip's motion in W for the chain's motion in J12 and the ship's motion.
pub fn tip_in_world(ship: &ShipMotion, chain: &ChainMotion) -> PointMotion {
    let relative = PointMotion { pos: CRANE_BASE + chain.tip.pos, ..chain.tip };
    ship.point_in_world(&relative)
}

#[cfg(test)]
mod tests;

//! Velocities and accelerations of the crane chain and of the tip in the world frame.
//!
//! Time derivatives of the kinematic chain are exact, by forward-mode automatic differentiation:
//! each actuator coordinate q(t) enters as the hyper-dual number q + q̇ ε1 + q̇ ε2 + q̈ ε1ε2, and
//! any function f evaluated on such numbers returns f + ḟ ε1 + ḟ ε2 + f̈ ε1ε2, since the ε1ε2
//! part is ∇f·q̈ + q̇ᵀ ∇²f q̇ = d²f/dt². The mechanism and serial kinematics are written generic
//! over [`Scalar`](crate::math::Scalar), so one evaluation gives position, velocity and acceleration.
//!
//! The tip in the world frame W follows from the ship motion by rigid-body kinematics
//! ([`ShipMotion::point_in_world`]) with r = r_base + p_tip/J12 in the ship frame B (J12 is aligned
//! with B).

use super::mechanisms::joints_from_actuators;
use super::winch::CableModel;
use super::{kinematics, KinematicsError};
use crate::math::Vec3;
use crate::motion::{AxisMotion, PointMotion, ShipMotion};
use num_dual::HyperDual64;
use serde::{Deserialize, Serialize};

/// Origin of the crane base frame J12 in the ship frame B (m): 0.225 m to port of the deck centre
/// (Fig. 3.7b).
pub const CRANE_BASE: Vec3 = Vec3::new(0.0, -0.225, 0.0);

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
        joints: theta.map(|x| AxisMotion::from_jet(&x)),
        tip: PointMotion { pos: part(|x| x.re), vel: part(|x| x.eps1), acc: part(|x| x.eps1eps2) },
        lp: AxisMotion::from_jet(&lp),
    })
}

/// The tip's motion in W for the chain's motion in J12 and the ship's motion.
pub fn tip_in_world(ship: &ShipMotion, chain: &ChainMotion) -> PointMotion {
    let relative = PointMotion { pos: CRANE_BASE + chain.tip.pos, ..chain.tip };
    ship.point_in_world(&relative)
}

#[cfg(test)]
mod tests;

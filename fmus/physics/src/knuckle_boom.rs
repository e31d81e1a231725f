//! The full-scale offshore knuckle-boom arm: geometry, the two luffing-cylinder mechanisms,
//! kinematics and rigid-body dynamics on a moving deck. Pure functions of the joint state; the
//! FMU that uses them integrates.
//!
//! - [`params`]: the arm's parameters ([`ArmParams::DEFAULT`], with the source of every value)
//!   and their validation;
//! - [`mechanism`]: a two-pin hydraulic cylinder between two links, joint angle ↔ pin-to-pin
//!   length and the lever arm;
//! - [`kinematics`]: the joint geometry, tip motion in the base and world frames, inverse
//!   kinematics and the points a viewer draws;
//! - [`dynamics`]: recursive Newton–Euler inverse dynamics with the ship's motion as base motion,
//!   the mass matrix, forward dynamics and the energy.
//!
//! # Frames and units
//!
//! SI units (m, rad, s, kg, N, N·m). World W: North-East-Down, gravity along +z. Ship frame B: x
//! bow, y starboard, z down. Crane base frame K: aligned with B, origin at the pedestal foot on
//! deck at [`ArmParams::base`] (B coordinates). Every position this module returns is in K,
//! relative to K's origin, unless it says W.
//!
//! # Joints
//!
//! `q = [θ1, θ2, θ3]` (rad):
//! - θ1, slew, about K's z axis (down): the boom plane's horizontal direction is
//!   e = (cos θ1, sin θ1, 0) in K (θ1 = −π/2 reaches to port, −y);
//! - θ2, boom luff: the boom's elevation above the horizontal (positive up) about the boom
//!   pivot, which sits [`ArmParams::pedestal_height`] above the deck and
//!   [`ArmParams::pivot_offset`] out from the slew axis along e;
//! - θ3, jib: the jib's angle relative to the boom line (positive up; a folded knuckle has
//!   θ3 < 0).
//!
//! The axis of joints 2 and 3 is n = e × u, u = (0, 0, −1) the upward unit vector in K; a
//! positive rotation about n turns e toward u. Tip in K (Siciliano et al. 2009, §2.9.1, the
//! planar two-link arm carried by the slew rotation):
//!
//! ```text
//! ρ = a_p + L_b cos θ2 + L_j cos(θ2 + θ3)          (outreach from the slew axis)
//! h = h_p + L_b sin θ2 + L_j sin(θ2 + θ3)          (height above the deck)
//! p = (ρ cos θ1, ρ sin θ1, −h)
//! ```
//!
//! Joint torques are the torques the actuators apply at the joints about +z (θ1) and +n (θ2,
//! θ3), N·m; the cylinders' forces follow from them through the lever arm dL/dθ
//! (F = τ / (dL/dθ), virtual work).

pub mod dynamics;
pub mod kinematics;
pub mod mechanism;
pub mod params;

pub use kinematics::Skeleton;
pub use mechanism::Mechanism;
pub use params::{ArmParams, LinkInertia};

/// Joint angles, rates or accelerations `[θ1 slew, θ2 boom, θ3 jib]` (rad, rad/s, rad/s²), or
/// joint torques (N·m) in the same order.
pub type Joints = [f64; 3];

#[cfg(test)]
mod tests;

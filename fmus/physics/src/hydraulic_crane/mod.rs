//! The full-scale offshore knuckle-boom crane: the rigid arm of [`crate::knuckle_boom`] driven by
//! the hydraulic drives of [`crate::hydraulics`], with the winch that pays out the hoist rope
//! (docs/full-scale.md).
//!
//! - [`plant`]: the coupled state (joint angles and rates, the chamber pressures of the four
//!   drives, the winch drum), its right-hand side and the fixed-step integration over one
//!   communication step;
//! - [`sensors`]: the sensors an industrial crane has — absolute joint encoders, cylinder stroke
//!   transducers, pressure transducers, the winch drum encoder — with seeded noise.
//!
//! Coupling: the boom and jib cylinders act on joints 2 and 3 through their pin-to-pin
//! mechanisms, τ = F·dL/dθ (virtual work: the cylinder's power F·L̇ equals τ·θ̇); the slew motor
//! drives joint 1 through its gear. The winch is lumped at the jib tip: the hoist rope leaves the
//! crane there, so the rope's only force on the arm is the cable force at the tip (an input),
//! and the drum's reaction torque is internal to the jib. The rope between the tip and the load is
//! the pendulum's cable; its length is the drum's payout.

pub mod plant;
pub mod sensors;

#[cfg(test)]
mod tests;

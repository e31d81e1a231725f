//! Control of the full-scale offshore crane ([`crate::hydraulic_crane`]): joint loops on the
//! valve spools, world-frame anti-sway and active heave compensation (docs/full-scale.md; the
//! thesis' Chapter 6 carried to the full-scale hydraulic crane of its future work 4, §8.3).
//!
//! - [`drives`]: from an actuator speed to a spool command, the inverse of the pressure-
//!   compensated valve with its deadband, and each drive's rated speed;
//! - [`antisway`]: the LQR design of §6.2 at the full-scale hoist length, on the tip-velocity
//!   model a hydraulic arm gives;
//! - [`setpoint`]: the references held, or moved by the pick-and-place profile at full scale;
//! - [`controller`]: one sample of the control software — references latched at the first
//!   sample, positioning or compensation of the arm, heave compensation by the winch or the arm.

pub mod antisway;
pub mod controller;
pub mod drives;
pub mod setpoint;

#[cfg(test)]
mod tests;

//! Pure-Rust models of the test-scale maritime crane system (no FFI).
//!
//! Frames and units follow the specification: SI units, world frame W North-East-Down
//! (x north, y east, z down, gravity along +z), quaternions scalar-first W←body.
//! Equation numbers refer to the thesis "Motion Compensation and Robotic Control of Maritime
//! Cranes".

pub mod control;
pub mod crane;
pub mod estimation;
pub mod imu;
pub mod integrate;
pub mod math;
pub mod noise;
pub mod pendulum;
pub mod platform;
pub mod ship;

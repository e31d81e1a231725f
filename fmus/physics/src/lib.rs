//! Pure-Rust models of the test-scale maritime crane system (no FFI).
//!
//! Frames and units follow the specification: SI units, world frame W North-East-Down
//! (x north, y east, z down, gravity along +z), quaternions scalar-first W←body.
//! Equation numbers refer to the thesis "Motion Compensation and Robotic Control of Maritime
//! Cranes".
//!
//! The top-level modules form layers: a module uses its own children and modules of lower layers,
//! never one that uses it (checked for every crate by `cargo xtask layers`).
//!
//! 0. [`check`], [`math`], [`integrate`], [`noise`]: value checks, vocabulary and numerics;
//! 1. [`motion`] (the shared motion types and the ship's degree-of-freedom indices), [`imu`],
//!    [`pendulum`], [`hydraulics`] (valves, counterbalance valves, cylinders, motors);
//! 2. [`crane`], [`platform`], [`knuckle_boom`] (the full-scale arm: kinematics, cylinder
//!    mechanisms, rigid-body dynamics on a moving deck), [`rigging`] (hook and load: a double
//!    pendulum on rigid or elastic, slack-capable ropes);
//! 3. [`ship`] (its sources are scaled to fit the platform), [`estimation`];
//! 4. [`control`], [`hydraulic_crane`] (the full-scale crane: arm, drives and winch coupled, its
//!    sensors);
//! 5. [`offshore_control`] (the full-scale crane's joint loops, anti-sway and heave compensation).

/// Makes a type's documented constant its `Default`: `default_is_const!(Valve)` gives
/// `Valve::default() == Valve::DEFAULT`, `default_is_const!(Commands, NEUTRAL)` names another
/// constant. Defined before the modules so that every module can use it.
macro_rules! default_is_const {
    ($ty:ident) => {
        default_is_const!($ty, DEFAULT);
    };
    ($ty:ident, $constant:ident) => {
        impl Default for $ty {
            fn default() -> Self {
                Self::$constant
            }
        }
    };
}

pub mod check;
pub mod control;
pub mod crane;
pub mod estimation;
pub mod hydraulic_crane;
pub mod hydraulics;
pub mod imu;
pub mod integrate;
pub mod knuckle_boom;
pub mod math;
pub mod motion;
pub mod noise;
pub mod offshore_control;
pub mod pendulum;
pub mod platform;
pub mod rigging;
pub mod ship;

//! The one math vocabulary of the workspace: vector, rotation and constant names.

pub use nalgebra::{Matrix3, SVector, UnitQuaternion, Vector3};

/// A 3-vector of f64 (SI units; the frame is stated where it is used).
pub type Vec3 = Vector3<f64>;
/// A unit quaternion, scalar first, rotating body coordinates into the reference frame.
pub type Quat = UnitQuaternion<f64>;

/// Standard gravity (m/s²), the thesis' g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Rotation about x by `angle` (rad).
pub fn rot_x(angle: f64) -> Quat {
    Quat::from_axis_angle(&Vec3::x_axis(), angle)
}

/// Rotation about y by `angle` (rad).
pub fn rot_y(angle: f64) -> Quat {
    Quat::from_axis_angle(&Vec3::y_axis(), angle)
}

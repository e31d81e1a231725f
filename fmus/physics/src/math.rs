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

/// Rotation about z by `angle` (rad).
pub fn rot_z(angle: f64) -> Quat {
    Quat::from_axis_angle(&Vec3::z_axis(), angle)
}

/// Orientation from yaw–pitch–roll (Z–Y–X) angles (rad): R = R_z(yaw) R_y(pitch) R_x(roll), the
/// ship attitude convention of eq. 5.1 / C.49.
pub fn euler_zyx(roll: f64, pitch: f64, yaw: f64) -> Quat {
    Quat::from_euler_angles(roll, pitch, yaw)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_zyx_is_yaw_then_pitch_then_roll() {
        let (roll, pitch, yaw) = (0.3, -0.2, 1.1);
        let composed = rot_z(yaw) * rot_y(pitch) * rot_x(roll);
        assert!(euler_zyx(roll, pitch, yaw).angle_to(&composed) < 1e-15);
    }
}

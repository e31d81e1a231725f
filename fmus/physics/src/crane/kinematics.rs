//! Forward and inverse kinematics of the crane's serial RRR chain (thesis §4.2.5).
//!
//! Joints: θ2z slews the tower about the base frame's z axis, θ3x raises the boom and θ4x folds
//! the jib, both about local x axes. Links: the tower l2z along −z, the boom l3y and the jib l4y
//! along −y (eqs. 4.67–4.69). With r = l4y cos(θ3x + θ4x) + l3y cos θ3x, the tip in J12 is
//! (eqs. 4.73–4.75)
//!
//! ```text
//! x_t = r sin θ2z,   y_t = −r cos θ2z,   z_t = −l2z − l4y sin(θ3x + θ4x) − l3y sin θ3x.
//! ```
//!
//! Units: positions in m and angles in rad at the API; the link lengths are the thesis' mm values
//! and positions are converted at the boundary.

use super::mechanisms::{actuators_from_joints, joints_from_actuators};
use super::{KinematicsError, MM_PER_M};
use crate::math::Scalar;
use crate::math::Vec3;

/// Tower length l2z (mm), from J2,1 to the boom pivot J2,2 (Appendix D).
pub const L2Z: f64 = 184.6;
/// Boom length l3y (mm), boom pivot to jib pivot.
pub const L3Y: f64 = 225.0;
/// Jib length l4y (mm), jib pivot to the tip J4,2.
pub const L4Y: f64 = 150.0;

/// Tip position (x_t, y_t, z_t) in J12 (m) from the joint angles (θ2z, θ3x, θ4x) (rad),
/// eqs. 4.73–4.75.
pub fn forward<D: Scalar>(theta: &[D; 3]) -> [D; 3] {
    let [t2, t3, t4] = *theta;
    let (s2, c2) = t2.sin_cos();
    let (s3, c3) = t3.sin_cos();
    let (s34, c34) = (t3 + t4).sin_cos();
    let reach = c34 * L4Y + c3 * L3Y;
    let x = s2 * reach;
    let y = -(c2 * reach);
    let z = -(s34 * L4Y) - s3 * L3Y - L2Z;
    [x / MM_PER_M, y / MM_PER_M, z / MM_PER_M]
}

/// Joint angles (θ2z, θ3x, θ4x) (rad) that put the tip at `tip` (m, J12): eqs. 4.78,
/// 4.80–4.86 (+ root, as in Appendix D `IK_Crane`) and 4.88.
///
/// Fails when the target is not finite, lies on the slewing axis, or is out of the boom and jib's
/// geometric reach. Whether the actuators can reach the angles is checked by
/// [`actuators_for_tip`].
pub fn inverse(tip: &Vec3) -> Result<[f64; 3], KinematicsError> {
    if !tip.iter().all(|v| v.is_finite()) {
        return Err(KinematicsError::NotFinite);
    }
    let target = [tip.x, tip.y, tip.z];
    let (x, y, z) = (tip.x * MM_PER_M, tip.y * MM_PER_M, tip.z * MM_PER_M);
    let horizontal = x.hypot(y);
    if horizontal < 1e-9 {
        return Err(KinematicsError::OnSlewAxis { target });
    }
    // Eq. 4.78.
    let theta2 = x.atan2(-y);
    // Eqs. 4.80–4.86.
    let k1 = x * x + y * y + 2.0 * L2Z * z + L3Y * L3Y + L2Z * L2Z + z * z - L4Y * L4Y;
    let k2 = 2.0 * (L3Y * L2Z + L3Y * z);
    let k3 = 2.0 * L3Y * horizontal;
    let (a, b, c) = (k1 + k3, 2.0 * k2, k1 - k3);
    let discriminant = b * b - 4.0 * a * c;
    if !(discriminant >= 0.0) {
        let distance = horizontal.hypot(z + L2Z) / MM_PER_M;
        return Err(KinematicsError::OutOfReach {
            target,
            distance,
            min: (L3Y - L4Y).abs() / MM_PER_M,
            max: (L3Y + L4Y) / MM_PER_M,
        });
    }
    let theta3 = 2.0 * (discriminant.sqrt() - b).atan2(2.0 * a);
    // Eq. 4.88.
    let theta4 = (-z - L2Z - L3Y * theta3.sin()).atan2(horizontal - L3Y * theta3.cos()) - theta3;
    Ok([theta2, theta3, theta4])
}

/// Tip position in J12 (m) from the actuator extensions (m): mechanism forward kinematics, then
/// eqs. 4.73–4.75.
pub fn tip_from_actuators(d: &[f64; 3]) -> Result<Vec3, KinematicsError> {
    let [x, y, z] = forward(&joints_from_actuators(d)?);
    Ok(Vec3::new(x, y, z))
}

/// Actuator extensions (m) that put the tip at `tip` (m, J12): crane inverse kinematics, then
/// the mechanisms' inverse kinematics. Fails also when an extension leaves the 0–50 mm stroke.
pub fn actuators_for_tip(tip: &Vec3) -> Result<[f64; 3], KinematicsError> {
    actuators_from_joints(&inverse(tip)?)
}

#[cfg(test)]
mod tests;

//! The one math vocabulary of the workspace: vector, rotation and constant names.

pub use nalgebra::{Matrix3, SVector, UnitQuaternion, Vector3};
use num_dual::DualNum;

/// A 3-vector of f64 (SI units; the frame is stated where it is used).
pub type Vec3 = Vector3<f64>;
/// A unit quaternion, scalar first, rotating body coordinates into the reference frame.
pub type Quat = UnitQuaternion<f64>;

/// Standard gravity (m/s²), the thesis' g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// A real number the kinematics can be evaluated with: `f64`, or a `num-dual` number that carries
/// exact derivatives along (e.g. `HyperDual64` for first and second time derivatives).
pub trait Scalar: DualNum<Primitive = f64> + Copy {}

impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}

/// The components (x, y, z) of `v`, in a `const` context too (e.g. the start values of an FMU's
/// variable table, which is a `static`).
pub const fn components(v: &Vec3) -> [f64; 3] {
    v.data.0[0]
}

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

/// The matrix of [`euler_zyx`] (W←B), R = R_z(yaw) R_y(pitch) R_x(roll), as rows, for any scalar
/// that carries derivatives (`f64`, or a `num-dual` number).
pub fn euler_zyx_matrix<D: Scalar>(roll: D, pitch: D, yaw: D) -> [[D; 3]; 3] {
    let (sf, cf) = roll.sin_cos();
    let (st, ct) = pitch.sin_cos();
    let (sp, cp) = yaw.sin_cos();
    [
        [cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf],
        [sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf],
        [-st, ct * sf, ct * cf],
    ]
}

/// Angular velocity ω and angular acceleration α of a body whose attitude is given by Z–Y–X
/// angles ([`euler_zyx`]), both expressed in the body frame (rad/s, rad/s²).
///
/// `angles`, `rates` and `accelerations` are (roll φ, pitch θ, yaw ψ) and their first and second
/// time derivatives. ω = (φ̇ − ψ̇ sin θ, θ̇ cos φ + ψ̇ cos θ sin φ, −θ̇ sin φ + ψ̇ cos θ cos φ)
/// (the kinematic equation of the Z–Y–X sequence, eq. C.49's rates), and α = dω/dt: the body
/// components of the angular acceleration are the time derivatives of the body components of ω,
/// because ω × ω = 0.
pub fn euler_zyx_body_rates(angles: [f64; 3], rates: [f64; 3], accelerations: [f64; 3]) -> (Vec3, Vec3) {
    let [phi, theta, _] = angles;
    let [dphi, dtheta, dpsi] = rates;
    let [ddphi, ddtheta, ddpsi] = accelerations;
    let (sf, cf) = phi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let omega = Vec3::new(dphi - dpsi * st, dtheta * cf + dpsi * ct * sf, -dtheta * sf + dpsi * ct * cf);
    let alpha = Vec3::new(
        ddphi - ddpsi * st - dpsi * dtheta * ct,
        ddtheta * cf - dtheta * dphi * sf + ddpsi * ct * sf - dpsi * dtheta * st * sf + dpsi * dphi * ct * cf,
        -ddtheta * sf - dtheta * dphi * cf + ddpsi * ct * cf - dpsi * dtheta * st * cf - dpsi * dphi * ct * sf,
    );
    (omega, alpha)
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

    #[test]
    fn euler_zyx_matrix_is_the_quaternion_rotation() {
        let (roll, pitch, yaw) = (0.4, -0.7, 2.1);
        let r = euler_zyx(roll, pitch, yaw).to_rotation_matrix();
        let m = euler_zyx_matrix(roll, pitch, yaw);
        for (i, row) in m.iter().enumerate() {
            for (j, value) in row.iter().enumerate() {
                assert!((value - r[(i, j)]).abs() < 1e-15, "R[{i}][{j}]");
            }
        }
    }

    /// ω from the attitude's finite difference (R(t)ᵀ Ṙ(t) = [ω×]) and α from ω's, along a smooth
    /// attitude trajectory with large angles.
    #[test]
    fn body_rates_match_finite_differences_of_the_attitude() {
        let angles = |t: f64| [0.5 * (1.3 * t).sin() + 0.2, 0.4 * (0.9 * t + 1.0).cos(), 1.5 * (0.7 * t).sin()];
        let rates = |t: f64| [0.65 * (1.3 * t).cos(), -0.36 * (0.9 * t + 1.0).sin(), 1.05 * (0.7 * t).cos()];
        let accs = |t: f64| [-0.845 * (1.3 * t).sin(), -0.324 * (0.9 * t + 1.0).cos(), -0.735 * (0.7 * t).sin()];
        let q = |t: f64| {
            let [r, p, y] = angles(t);
            euler_zyx(r, p, y)
        };
        let h = 1e-5;
        for t in [0.0, 0.8, 2.5, 4.1] {
            let (omega, alpha) = euler_zyx_body_rates(angles(t), rates(t), accs(t));
            // Body-frame rotation over [t − h, t + h]: q(t)⁻¹ q(t ± h) ≈ exp(±h ω/2).
            let fd_omega =
                ((q(t).inverse() * q(t + h)).scaled_axis() - (q(t).inverse() * q(t - h)).scaled_axis()) / (2.0 * h);
            assert!((omega - fd_omega).norm() < 1e-8, "t = {t}: ω {omega:?} vs {fd_omega:?}");
            let w = |s: f64| euler_zyx_body_rates(angles(s), rates(s), accs(s)).0;
            let fd_alpha = (w(t + h) - w(t - h)) / (2.0 * h);
            assert!((alpha - fd_alpha).norm() < 1e-8, "t = {t}: α {alpha:?} vs {fd_alpha:?}");
        }
    }
}

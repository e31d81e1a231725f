//! Angles from an orientation quaternion q = q0 + q1 î + q2 ĵ + q3 k̂ (W←body, scalar first),
//! read off the rotation matrix of eqs. 5.34 / 5.58.
//!
//! Ship, yaw–pitch–roll (Z–Y–X), R = R_z(θ1z) R_y(θ1y) R_x(θ1x), eqs. 5.35–5.37:
//!
//! ```text
//! θ1x = atan2(2(q0q1 + q2q3), q0² − q1² − q2² + q3²)
//! θ1y = atan2(−2(q1q3 − q0q2), √(1 − 4(q1q3 − q0q2)²))
//! θ1z = atan2(2(q1q2 + q0q3), q0² + q1² − q2² − q3²)
//! ```
//!
//! Load, roll–pitch–yaw (X–Y–Z), R = R_x(θx) R_y(θy) R_z(θz), eqs. 5.59–5.61:
//!
//! ```text
//! θx = atan2(−2(q2q3 − q0q1), q0² − q1² − q2² + q3²)
//! θy = atan2(2(q0q2 + q1q3), √(1 − 4(q0q2 + q1q3)²))
//! θz = atan2(−2(q1q2 − q0q3), q0² + q1² − q2² − q3²)
//! ```
//!
//! θx and θy are the pendulum angles of the dynamic model (§4.3); θz is a twist about the cable.
//! The square roots are clamped at zero so rounding at ±90° cannot produce NaN.

use crate::math::{rot_x, rot_y, rot_z, Quat};

/// Ship roll, pitch and yaw (θ1x, θ1y, θ1z) in rad, eqs. 5.35–5.37.
pub fn ship_angles(q: &Quat) -> [f64; 3] {
    let [q0, q1, q2, q3] = components(q);
    let s = q1 * q3 - q0 * q2;
    [
        (2.0 * (q0 * q1 + q2 * q3)).atan2(q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3),
        (-2.0 * s).atan2((1.0 - 4.0 * s * s).max(0.0).sqrt()),
        ship_yaw(q),
    ]
}

/// Ship yaw θ1z in rad, eq. 5.37: [`ship_angles`]`[2]` without the arctangents of the other two.
pub fn ship_yaw(q: &Quat) -> f64 {
    let [q0, q1, q2, q3] = components(q);
    (2.0 * (q1 * q2 + q0 * q3)).atan2(q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3)
}

/// Pendulum angles (θx, θy) and the twist θz in rad, eqs. 5.59–5.61.
pub fn pendulum_angles(q: &Quat) -> [f64; 3] {
    let [q0, q1, q2, q3] = components(q);
    let [theta_x, theta_y] = cable_angles(q);
    [theta_x, theta_y, (-2.0 * (q1 * q2 - q0 * q3)).atan2(q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3)]
}

/// The cable angles (θx, θy) of [`pendulum_angles`] (eqs. 5.59–5.60), without the twist's
/// arctangent when only the swing matters.
pub fn cable_angles(q: &Quat) -> [f64; 2] {
    let [q0, q1, q2, q3] = components(q);
    let s = q0 * q2 + q1 * q3;
    [
        (-2.0 * (q2 * q3 - q0 * q1)).atan2(q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3),
        (2.0 * s).atan2((1.0 - 4.0 * s * s).max(0.0).sqrt()),
    ]
}

/// The load orientation R_x(θx) R_y(θy) R_z(θz) (eqs. 5.54–5.57), which
/// [`pendulum_angles`] inverts. The ship's Z–Y–X counterpart is [`crate::math::euler_zyx`].
pub fn pendulum_orientation(theta_x: f64, theta_y: f64, theta_z: f64) -> Quat {
    rot_x(theta_x) * rot_y(theta_y) * rot_z(theta_z)
}

fn components(q: &Quat) -> [f64; 4] {
    let q = q.quaternion();
    [q.w, q.i, q.j, q.k]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::euler_zyx;

    const DEG: f64 = std::f64::consts::PI / 180.0;

    /// A grid of angles within ±89° (pitch) and ±179° (the others).
    fn grid() -> impl Iterator<Item = [f64; 3]> {
        let a = [-179.0, -120.0, -45.0, -5.0, 0.0, 3.0, 60.0, 150.0, 179.0];
        let b = [-89.0, -60.0, -10.0, 0.0, 0.5, 30.0, 75.0, 89.0];
        a.into_iter()
            .flat_map(move |x| b.into_iter().flat_map(move |y| a.into_iter().map(move |z| [x * DEG, y * DEG, z * DEG])))
    }

    /// The largest difference between the grid's angles and those extracted from their rotation.
    fn worst_round_trip(forward: impl Fn(f64, f64, f64) -> Quat, extract: impl Fn(&Quat) -> [f64; 3]) -> f64 {
        grid()
            .map(|[a, b, c]| {
                extract(&forward(a, b, c)).iter().zip([a, b, c]).map(|(g, e)| (g - e).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_angles_invert_the_forward_rotations() {
        let ship = worst_round_trip(euler_zyx, ship_angles);
        let load = worst_round_trip(pendulum_orientation, pendulum_angles);
        println!("angle round trips over the grid: ship Z-Y-X max error {ship:.2e} rad, pendulum X-Y-Z {load:.2e} rad");
        assert!(ship < 1e-9 && load < 1e-9);
    }

    #[test]
    fn the_pendulum_orientation_hangs_the_cable_like_the_dynamic_model() {
        // The body z axis is the cable direction e_r = (sin θy, −cos θy sin θx, cos θy cos θx)
        // (eqs. 4.94–4.96), and a twist leaves it alone.
        let (x, y) = (-0.3, 0.2);
        let e_r = pendulum_orientation(x, y, 0.7) * crate::math::Vec3::z();
        let expected = crate::math::Vec3::new(y.sin(), -y.cos() * x.sin(), y.cos() * x.cos());
        assert!((e_r - expected).norm() < 1e-15);
    }

    #[test]
    fn angles_stay_finite_at_the_pitch_singularity() {
        let ship = ship_angles(&euler_zyx(0.2, std::f64::consts::FRAC_PI_2, 0.1));
        let load = pendulum_angles(&pendulum_orientation(0.2, std::f64::consts::FRAC_PI_2, 0.1));
        assert!(ship.iter().chain(&load).all(|a| a.is_finite()));
        assert!((ship[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-7);
        assert!((load[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-7);
    }
}

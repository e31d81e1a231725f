//! Test scenarios shared by the attitude filters' tests: an ideal IMU, a ship-like rotation and
//! a driver that runs a filter along a known rotation and returns its errors.

use crate::estimation::attitude::AttitudeFilter;
use crate::estimation::euler::pendulum_angles;
use crate::imu::{readings, ImuMotion, ImuParams};
use crate::math::{euler_zyx, Quat, Vec3};
use crate::pendulum::{self, PendulumParams, Swing, TipMotion};

pub const DEG: f64 = std::f64::consts::PI / 180.0;
/// Sample interval (s), the controller's 100 Hz.
pub const DT: f64 = 0.01;

/// An IMU without noise or quantisation: readings are the true values.
pub fn ideal_imu() -> ImuParams {
    let mut p = ImuParams { noise: false, ..ImuParams::default() };
    p.gyro.lsb = 0.0;
    p.acc.lsb = 0.0;
    p.mag.lsb = 0.0;
    p
}

/// Runs `update` (gyro, specific force, magnetometer, dt → estimate) on the readings of an IMU
/// moving along `truth(t)` (rotation about a fixed point, rates from the orientation's exact
/// derivative) for `seconds`, and returns the attitude errors (rad) of every sample.
pub fn run(
    mut update: impl FnMut(&Vec3, &Vec3, &Vec3, f64) -> Quat,
    imu: &ImuParams,
    truth: impl Fn(f64) -> Quat,
    seconds: f64,
) -> Vec<f64> {
    let n = (seconds / DT).round() as u64;
    (0..=n)
        .map(|k| {
            let t = k as f64 * DT;
            let q = truth(t);
            // Body rate ω = 2 Im(q* q̇), q̇ by a central difference (error ~1e-10 rad/s).
            let h = 1e-5;
            let omega =
                ((q.inverse() * truth(t + h)).scaled_axis() - (q.inverse() * truth(t - h)).scaled_axis()) / (2.0 * h);
            let r =
                readings(imu, &ImuMotion { orientation: q, angular_velocity: omega, acceleration: Vec3::zeros() }, k);
            update(&r.gyro, &r.acc, &r.mag, DT).angle_to(&q)
        })
        .collect()
}

pub fn rms(errors: &[f64]) -> f64 {
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
}

/// Ship-like rotation: roll 8°, pitch 4°, yaw 3° oscillating at different periods.
pub fn ship_rotation(t: f64) -> Quat {
    euler_zyx(
        8.0 * DEG * (0.6 * t).sin(),
        4.0 * DEG * (0.8 * t + 1.0).sin() + 1.0 * DEG,
        3.0 * DEG * (0.35 * t).sin() + 20.0 * DEG,
    )
}

/// The load IMU of a 0.7 m pendulum held at θx = −10°, θy = 5° for 2 s (as a hand holds it
/// before a test; the filter aligns on the first sample), then released from a fixed tip, with
/// the SPEC §8.1 noise (seed 9): the errors (rad) of the estimated pendulum angles over the 30 s
/// after release, the norm of the θx and θy errors.
pub fn swinging_load(filter: &mut AttitudeFilter) -> Vec<f64> {
    let (p, lp) = (PendulumParams::default(), 0.7);
    let tip = TipMotion { lp, ..TipMotion::default() };
    let mut swing = Swing { theta_x: -10.0 * DEG, theta_y: 5.0 * DEG, ..Swing::default() };
    let imu = ImuParams { seed: 9, ..ImuParams::default() };
    let release = 200;
    let mut errors = Vec::new();
    for k in 0..3200u64 {
        let held = k < release;
        let load = if held {
            pendulum::load_kinematics(&p, &swing, &tip, (0.0, 0.0))
        } else {
            pendulum::load_motion(&p, &swing, &tip)
        };
        let motion = ImuMotion {
            orientation: load.orientation,
            angular_velocity: load.angular_velocity,
            acceleration: load.acc,
        };
        let r = readings(&imu, &motion, k);
        if k == 0 {
            filter.align(&r.acc, &r.mag);
        }
        let [x, y, _] = pendulum_angles(&filter.update(&r.gyro, &r.acc, &r.mag, DT));
        if !held {
            errors.push((x - swing.theta_x).hypot(y - swing.theta_y));
            swing = pendulum::advance(&p, &swing, &tip, &TipMotion::default(), DT).unwrap();
        }
    }
    errors
}

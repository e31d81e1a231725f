use super::*;
use crate::estimation::attitude::AttitudeFilter;
use crate::estimation::euler::ship_angles;
use crate::estimation::scenarios::{self, ideal_imu, rms, ship_rotation, DEG, DT};
use crate::imu::{readings, ImuMotion, ImuParams};
use crate::math::{euler_zyx, rot_x, rot_z};

/// Unit vectors spread over the sphere (a Fibonacci lattice).
fn directions(n: usize) -> impl Iterator<Item = Vec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n).map(move |i| {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let r = (1.0 - z * z).sqrt();
        let phi = golden * i as f64;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

#[test]
fn the_gravity_delta_solves_eq_5_17_in_both_branches() {
    for g_p in directions(500) {
        let delta = Quat::new_normalize(gravity_delta(&g_p));
        assert!((gravity_delta(&g_p).norm() - 1.0).abs() < 1e-12, "Δq_a is a unit quaternion");
        let rotated = delta * Vec3::new(0.0, 0.0, -1.0);
        assert!((rotated - g_p).norm() < 1e-12, "ĝ_P = {g_p:?}: Δq_a ĝ Δq_a* = {rotated:?}");
    }
}

#[test]
fn the_magnetic_delta_solves_eq_5_24_with_a_rotation_about_z() {
    for eta in directions(500).chain([Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.0, -0.6, 0.8)]) {
        let raw = magnetic_delta(&eta);
        assert!(raw.i == 0.0 && raw.j == 0.0, "only a k component");
        assert!((raw.norm() - 1.0).abs() < 1e-12);
        let horizontal = eta.x.hypot(eta.y);
        let rotated = Quat::new_normalize(raw) * Vec3::new(horizontal, 0.0, eta.z);
        assert!((rotated - eta).norm() < 1e-12, "η̂_P = {eta:?}: got {rotated:?}");
    }
}

#[test]
fn interpolation_weights_run_from_identity_to_the_delta() {
    // A small delta (LERP branch) and a large one (SLERP branch).
    for angle in [10.0 * DEG, 120.0 * DEG] {
        let delta = rot_x(angle).into_inner();
        assert!(interpolate(&delta, 0.0, 0.9).angle() < 1e-15);
        assert!(interpolate(&delta, 1.0, 0.9).angle_to(&rot_x(angle)) < 1e-12);
        // SLERP moves along the great circle: weight α turns by α·angle exactly.
        if delta.w <= 0.9 {
            assert!((interpolate(&delta, 0.3, 0.9).angle() - 0.3 * angle).abs() < 1e-12);
        }
    }
    // The two branches agree to a few percent where they meet (Δq_0 = β = 0.9, a 51.7° delta).
    let at_beta = rot_x(2.0 * 0.9f64.acos()).into_inner();
    let lerp = interpolate(&at_beta, 0.05, 0.899_999);
    let slerp = interpolate(&at_beta, 0.05, 0.9);
    assert!(lerp.angle_to(&slerp) < 0.05 * slerp.angle(), "LERP and SLERP differ by {}", lerp.angle_to(&slerp));
}

#[test]
fn the_adaptive_gains_follow_eqs_5_21_and_5_27() {
    let p = FilterParams::SHIP;
    assert_eq!(p.accelerometer_gain(0.0), 0.05);
    assert_eq!(p.accelerometer_gain(0.1), 0.05);
    assert!((p.accelerometer_gain(0.15) - 0.025).abs() < 1e-15);
    assert_eq!(p.accelerometer_gain(0.2), 0.0);
    assert_eq!(p.accelerometer_gain(3.0), 0.0);
    assert_eq!(p.magnetometer_gain(&Quaternion::identity()), 1.0);
    let delta = rot_z(60.0 * DEG).into_inner();
    assert!((p.magnetometer_gain(&delta) - (-(1.0 - (30.0 * DEG).cos())).exp()).abs() < 1e-15);
    FilterParams::SHIP.validate().unwrap();
    FilterParams::LOAD.validate().unwrap();
}

#[test]
fn the_quaternion_exponential_integrates_a_constant_rate_exactly() {
    let omega = Vec3::new(0.3, -0.7, 1.1);
    let start = euler_zyx(0.1, 0.2, 0.3);
    let mut q = start;
    for _ in 0..1000 {
        q = integrate(&q, &omega, DT);
    }
    let exact = start * Quat::from_scaled_axis(omega * 10.0);
    println!("10 s at a constant rate: integration error {:.2e} rad", q.angle_to(&exact));
    assert!(q.angle_to(&exact) < 1e-12);
}

#[test]
fn alignment_from_one_sample_recovers_the_orientation() {
    let imu = ideal_imu();
    for (roll, pitch, yaw) in [(0.0, 0.0, 0.0), (0.3, -0.2, 1.0), (-1.2, 0.7, -2.5), (0.05, 0.02, 3.0)] {
        let truth = euler_zyx(roll, pitch, yaw);
        let r = readings(&imu, &ImuMotion { orientation: truth, ..ImuMotion::default() }, 0);
        let mut filter = ComplementaryFilter::new(FilterParams::SHIP);
        filter.align(&r.acc, &r.mag);
        assert!(filter.orientation().angle_to(&truth) < 1e-12, "roll {roll}, pitch {pitch}, yaw {yaw}");
    }
}

/// Runs the filter started from `start` along `truth` (see [`scenarios::run`]).
fn run(params: FilterParams, imu: &ImuParams, truth: impl Fn(f64) -> Quat, start: Quat, seconds: f64) -> Vec<f64> {
    let mut filter = ComplementaryFilter::new(params);
    filter.orientation = start;
    scenarios::run(|gyro, acc, mag, dt| filter.update(gyro, acc, mag, dt), imu, truth, seconds)
}

#[test]
fn the_filter_converges_from_a_wrong_start_and_tracks_a_rotation() {
    // Started 30° in roll, −20° in pitch and −60° in yaw away from the identity, the identity
    // itself 20° in yaw from the truth.
    for start in [euler_zyx(30.0 * DEG, -20.0 * DEG, -60.0 * DEG), Quat::identity()] {
        let initial = start.angle_to(&ship_rotation(0.0));
        let errors = run(FilterParams::SHIP, &ideal_imu(), ship_rotation, start, 60.0);
        let converged = errors.iter().position(|e| *e < 0.1 * DEG).expect("converges") as f64 * DT;
        let tracking = rms(&errors[1000..]);
        let worst = errors[1000..].iter().cloned().fold(0.0, f64::max);
        println!(
            "ship filter, noise-free, started {:.1}° off: within 0.1° after {converged:.2} s; error 10-60 s \
                RMS {:.1e}°, max {:.1e}°",
            initial / DEG,
            tracking / DEG,
            worst / DEG
        );
        assert!(converged < 5.0);
        assert!(tracking < 0.1 * DEG);
    }
}

#[test]
fn with_sensor_noise_the_error_stays_below_one_degree() {
    // SPEC §8.1 noise and quantisation on all nine channels.
    let imu = ImuParams { seed: 7, ..ImuParams::default() };
    for (name, params) in [("ship (Table 5.1)", FilterParams::SHIP), ("load (Table 5.2)", FilterParams::LOAD)] {
        let errors = run(params, &imu, ship_rotation, Quat::identity(), 60.0);
        let tracking = rms(&errors[1000..]);
        // Roll/pitch and yaw separately.
        println!("{name} filter with §8.1 noise: attitude RMS error 10-60 s {:.3}°", tracking / DEG);
        assert!(tracking < 1.0 * DEG);
    }
}

#[test]
fn large_non_gravitational_acceleration_is_not_trusted() {
    // A level IMU accelerating north at 1.5 m/s² and up at 2.5 m/s²: ‖a‖ = 12.4 m/s²,
    // e_a = 0.26 > β_a,ul = 0.2, so the accelerometer gets no weight and the estimate stays level.
    let imu = ideal_imu();
    let mut filter = ComplementaryFilter::new(FilterParams::SHIP);
    let up = ImuMotion { acceleration: Vec3::new(1.5, 0.0, -2.5), ..ImuMotion::default() };
    for k in 0..200 {
        let r = readings(&imu, &up, k);
        filter.update(&r.gyro, &r.acc, &r.mag, DT);
    }
    assert!(filter.orientation().angle() < 1e-12, "rejected: {}", filter.orientation().angle());
    // The horizontal part alone barely changes the magnitude (e_a = 0.012), so it is trusted and
    // tilts the estimate toward atan(1.5/g): the filter cannot tell it from gravity.
    let sideways = ImuMotion { acceleration: Vec3::new(1.5, 0.0, 0.0), ..ImuMotion::default() };
    for k in 0..200 {
        let r = readings(&imu, &sideways, k);
        filter.update(&r.gyro, &r.acc, &r.mag, DT);
    }
    let [roll, pitch, _] = ship_angles(&filter.orientation());
    println!(
        "1.5 m/s² sideways for 2 s tilts the estimate by {:.2}° pitch (atan(1.5/g) = {:.2}°)",
        pitch / DEG,
        (1.5 / G).atan() / DEG
    );
    assert!(roll.abs() < 1e-9 && pitch.abs() > 1.0 * DEG);
}

const G: f64 = STANDARD_GRAVITY;

#[test]
fn the_load_filter_follows_a_swinging_pendulum() {
    let mut filter = AttitudeFilter::Complementary(ComplementaryFilter::new(FilterParams::LOAD));
    let errors = scenarios::swinging_load(&mut filter);
    let worst = errors.iter().cloned().fold(0.0, f64::max);
    println!(
        "load filter (Table 5.2) on a 0.7 m pendulum released from θx = −10°, θy = 5°, §8.1 noise, 30 s: \
            angle error RMS {:.3}°, max {:.3}°",
        rms(&errors) / DEG,
        worst / DEG
    );
    // Nearly all of the error is the design's, not the noise's (noise-free: 0.88° RMS): a freely
    // swinging load's specific force points along the cable, so the accelerometer correction
    // pulls the estimate toward hanging straight; the small load gain ᾱ_a = 0.005 makes that a
    // high-pass with a 0.08 Hz corner, below the 0.6 Hz swing.
    assert!(rms(&errors) < 1.0 * DEG);
}

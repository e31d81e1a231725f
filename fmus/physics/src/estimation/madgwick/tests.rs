use super::*;
use crate::estimation::attitude::AttitudeFilter;
use crate::estimation::complementary::{ComplementaryFilter, FilterParams};
use crate::estimation::scenarios::{self, ideal_imu, rms, ship_rotation, DEG, DT};
use crate::imu::{readings, ImuMotion, ImuParams};
use crate::math::euler_zyx;

/// f(q) of eqs. 25 and 29 computed directly as q* d q − s, to check the printed rows against.
fn objective(q: &Quat, d: &Vec3, s: &Vec3) -> Vec3 {
    q.inverse() * d - s
}

#[test]
fn the_objectives_and_jacobians_match_eqs_25_26_29_30() {
    let q = euler_zyx(0.3, -0.5, 2.0);
    let (a, m, bx, bz) = (Vec3::new(0.1, -0.2, 0.97), Vec3::new(0.5, 0.3, 0.8), 0.6, 0.8);
    let field = |c: [f64; 4]| field_objective(c, &m, bx, bz);
    let gravity = |c: [f64; 4]| gravity_objective(c, &a);
    let c = scalar_first(&q);
    assert!((gravity(c).0 - objective(&q, &Vec3::z(), &a)).norm() < 1e-15);
    assert!((field(c).0 - objective(&q, &Vec3::new(bx, 0.0, bz), &m)).norm() < 1e-15);
    // Each Jacobian column against a central difference in that quaternion component.
    for i in 0..4 {
        let h = 1e-6;
        let (mut up, mut down) = (c, c);
        up[i] += h;
        down[i] -= h;
        for (name, f) in [("gravity", &gravity as &dyn Fn([f64; 4]) -> _), ("field", &field)] {
            let slope = (f(up).0 - f(down).0) / (2.0 * h);
            let column = f(c).1.column(i).into_owned();
            assert!((slope - column).norm() < 1e-8, "{name} Jacobian column {i}: {column:?}, numerically {slope:?}");
        }
    }
}

#[test]
fn at_the_true_orientation_a_still_imu_stays_put() {
    let truth = euler_zyx(0.3, -0.2, 1.0);
    let r = readings(&ideal_imu(), &ImuMotion { orientation: truth, ..ImuMotion::default() }, 0);
    assert!(error_gradient(&truth, &r.acc, &r.mag).norm() < 1e-14);
    let mut filter = MadgwickFilter::new(MadgwickParams::SPEC_NOISE);
    filter.align(&r.acc, &r.mag);
    for _ in 0..1000 {
        filter.update(&r.gyro, &r.acc, &r.mag, DT);
    }
    // The correction has the fixed magnitude β (the gradient is normalised, eq. 43), so even
    // the rounding-level error left by the alignment is answered by a full step of β Δt: the
    // estimate dithers about the truth by that much and no more.
    let step = MadgwickParams::SPEC_NOISE.beta * DT;
    let error = filter.orientation().angle_to(&truth);
    println!("still IMU: error after 10 s {error:.2e} rad, β Δt = {step:.2e}");
    assert!(error < 2.0 * step, "drifted {error}");
}

/// Runs the filter started from `start` along the ship-like rotation (see [`scenarios::run`]).
fn run(params: MadgwickParams, imu: &ImuParams, start: Quat, seconds: f64) -> Vec<f64> {
    let mut filter = MadgwickFilter { params, orientation: start };
    scenarios::run(|gyro, acc, mag, dt| filter.update(gyro, acc, mag, dt), imu, ship_rotation, seconds)
}

#[test]
fn the_filter_converges_from_a_wrong_start_and_tracks_a_rotation() {
    // The correction turns the estimate at most at 2β rad/s (β bounds ‖q̇‖): 0.35°/s at the
    // SPEC β, so from 83.5° off convergence takes minutes; a large β converges in seconds.
    let start = euler_zyx(30.0 * DEG, -20.0 * DEG, -60.0 * DEG);
    for (beta, seconds, within) in [(0.1, 60.0, 30.0), (MadgwickParams::SPEC_NOISE.beta, 600.0, 450.0)] {
        let errors = run(MadgwickParams { beta }, &ideal_imu(), start, seconds);
        let converged = errors.iter().position(|e| *e < 0.1 * DEG).expect("converges") as f64 * DT;
        let tracking = rms(&errors[errors.len() - 5000..]);
        println!(
            "Madgwick β = {beta:.5} rad/s, noise-free, started {:.1}° off: within 0.1° after {converged:.2} \
                s; error over the last 50 s RMS {:.1e}°",
            errors[0] / DEG,
            tracking / DEG
        );
        assert!(converged < within);
        // What remains is lag, not noise: eq. 11 integrates the rate at the end of each step (the
        // complementary filter the step's average, eq. 5.13), and the bounded correction only
        // slowly pulls the estimate back.
        assert!(tracking < 0.1 * DEG, "tracking RMS {tracking} rad");
    }
}

/// The two filters on the same readings: the complementary filter with `complementary`, the
/// Madgwick filter with the SPEC β.
fn both(complementary: FilterParams) -> [(&'static str, AttitudeFilter); 2] {
    [
        ("complementary", AttitudeFilter::Complementary(ComplementaryFilter::new(complementary))),
        ("Madgwick", AttitudeFilter::Madgwick(MadgwickFilter::new(MadgwickParams::SPEC_NOISE))),
    ]
}

#[test]
fn with_sensor_noise_both_filters_track_the_ship() {
    // SPEC §8.1 noise and quantisation on all nine channels; both filters aligned on the first
    // sample, as the controller starts them by default.
    let imu = ImuParams { seed: 7, ..ImuParams::default() };
    let first = readings(&imu, &ImuMotion { orientation: ship_rotation(0.0), ..ImuMotion::default() }, 0);
    let mut results = Vec::new();
    for (name, mut filter) in both(FilterParams::SHIP) {
        filter.align(&first.acc, &first.mag);
        let errors = scenarios::run(|g, a, m, dt| filter.update(g, a, m, dt), &imu, ship_rotation, 60.0);
        let tracking = rms(&errors[1000..]);
        println!("ship, {name} filter with §8.1 noise: attitude RMS error 10-60 s {:.3}°", tracking / DEG);
        results.push(tracking);
    }
    assert!(results[1] < 1.0 * DEG);
}

#[test]
fn with_sensor_noise_both_filters_follow_a_swinging_load() {
    let mut results = Vec::new();
    for (name, mut filter) in both(FilterParams::LOAD) {
        let errors = scenarios::swinging_load(&mut filter);
        println!(
            "load, {name} filter on a 0.7 m pendulum released from θx = −10°, θy = 5°, §8.1 noise, 30 s: \
                angle error RMS {:.3}°",
            rms(&errors) / DEG
        );
        results.push(rms(&errors));
    }
    assert!(results[1] < 1.0 * DEG);
}

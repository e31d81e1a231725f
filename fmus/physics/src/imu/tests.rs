use super::*;
use crate::math::{rot_x, rot_y};
use crate::noise::mean_std;

const DEG: f64 = std::f64::consts::PI / 180.0;
const G: f64 = STANDARD_GRAVITY;

/// No noise, no quantisation: readings equal the true values exactly.
fn ideal() -> ImuParams {
    let mut p = ImuParams { noise: false, ..ImuParams::default() };
    p.gyro.lsb = 0.0;
    p.acc.lsb = 0.0;
    p.mag.lsb = 0.0;
    p
}

fn at_rest(orientation: Quat) -> ImuMotion {
    ImuMotion { orientation, ..ImuMotion::default() }
}

fn rot_z(angle: f64) -> Quat {
    Quat::from_axis_angle(&Vec3::z_axis(), angle)
}

fn assert_close(actual: &Vec3, expected: [f64; 3], what: &str) {
    let err = (actual - Vec3::from(expected)).amax();
    assert!(err < 1e-12, "{what}: got {actual:?}, expected {expected:?} (error {err:e})");
}

#[test]
fn level_at_rest_reads_minus_g_and_north() {
    let omega = Vec3::new(0.01, -0.02, 0.03);
    let r = readings(&ideal(), &ImuMotion { angular_velocity: omega, ..ImuMotion::default() }, 0);
    assert_close(&r.gyro, [0.01, -0.02, 0.03], "gyro");
    assert_close(&r.acc, [0.0, 0.0, -G], "acc");
    assert_close(&r.mag, [1.0, 0.0, 0.0], "mag");
}

#[test]
fn rolled_30_degrees_about_x() {
    // Starboard down: body y tilts toward +z, so the (upward) specific force has a −y part.
    let r = readings(&ideal(), &at_rest(rot_x(30.0 * DEG)), 5);
    assert_close(&r.acc, [0.0, -G * 0.5, -G * 3f64.sqrt() / 2.0], "acc");
    assert_close(&r.mag, [1.0, 0.0, 0.0], "mag");
    assert_close(&r.gyro, [0.0, 0.0, 0.0], "gyro");
}

#[test]
fn pitched_20_degrees_about_y() {
    // Nose up: body x tilts toward −z; the field (north, horizontal) gains a +z body component.
    let (s, c) = (20.0 * DEG).sin_cos();
    let r = readings(&ideal(), &at_rest(rot_y(20.0 * DEG)), 5);
    assert_close(&r.acc, [G * s, 0.0, -G * c], "acc");
    assert_close(&r.mag, [c, 0.0, s], "mag");
}

#[test]
fn yawed_60_degrees_about_z() {
    // Heading 60° east of north: north lies to the left (−y) of the sensor's x axis.
    let (s, c) = (60.0 * DEG).sin_cos();
    let r = readings(&ideal(), &at_rest(rot_z(60.0 * DEG)), 5);
    assert_close(&r.acc, [0.0, 0.0, -G], "acc");
    assert_close(&r.mag, [c, -s, 0.0], "mag");
}

#[test]
fn yaw_pitch_roll_combined() {
    // Z–Y–X (yaw ψ, pitch θ, roll φ): R = Rz Ry Rx; Rᵀ e_z and Rᵀ e_x from the closed forms.
    let (psi, theta, phi) = (-40.0 * DEG, 10.0 * DEG, 25.0 * DEG);
    let q = rot_z(psi) * rot_y(theta) * rot_x(phi);
    let (sps, cps) = psi.sin_cos();
    let (sth, cth) = theta.sin_cos();
    let (sph, cph) = phi.sin_cos();
    let r = readings(&ideal(), &at_rest(q), 0);
    assert_close(&r.acc, [G * sth, -G * cth * sph, -G * cth * cph], "acc");
    assert_close(&r.mag, [cps * cth, cps * sth * sph - sps * cph, cps * sth * cph + sps * sph], "mag");
}

#[test]
fn linear_acceleration_adds_to_the_specific_force() {
    let motion = ImuMotion { acceleration: Vec3::new(1.0, -2.0, 3.0), ..ImuMotion::default() };
    assert_close(&readings(&ideal(), &motion, 0).acc, [1.0, -2.0, 3.0 - G], "acc, level");
    // Free fall reads zero whatever the orientation.
    let falling = ImuMotion { acceleration: Vec3::new(0.0, 0.0, G), ..at_rest(rot_x(0.3) * rot_y(-1.1)) };
    assert_close(&readings(&ideal(), &falling, 0).acc, [0.0, 0.0, 0.0], "acc, free fall");
    // Rolled 90°: the sensor's y axis points down, so a downward acceleration shows on +y.
    let rolled = ImuMotion { acceleration: Vec3::new(0.0, 0.0, 1.0), ..at_rest(rot_x(90.0 * DEG)) };
    assert_close(&readings(&ideal(), &rolled, 0).acc, [0.0, 1.0 - G, 0.0], "acc, rolled 90°");
}

#[test]
fn declination_and_inclination_turn_the_field() {
    let p = ImuParams { mag_declination: 5.95 * DEG, mag_inclination: 70.0 * DEG, ..ideal() };
    let (sd, cd) = (5.95 * DEG).sin_cos();
    let (si, ci) = (70.0 * DEG).sin_cos();
    assert_close(&readings(&p, &ImuMotion::default(), 0).mag, [ci * cd, ci * sd, si], "mag, level");
    // Yawing the sensor by the declination puts the horizontal field on its x axis.
    assert_close(&readings(&p, &at_rest(rot_z(5.95 * DEG)), 0).mag, [ci, 0.0, si], "mag, yawed by D");
    assert!((p.magnetic_field().norm() - 1.0).abs() < 1e-15);
}

#[test]
fn biases_add_and_quantisation_rounds() {
    let mut p = ideal();
    p.gyro.bias = Vec3::new(0.001, -0.002, 0.003);
    p.acc.bias = Vec3::new(0.1, 0.0, -0.1);
    p.mag.bias = Vec3::new(0.0, 0.05, 0.0);
    let r = readings(&p, &ImuMotion::default(), 0);
    assert_close(&r.gyro, [0.001, -0.002, 0.003], "gyro bias");
    assert_close(&r.acc, [0.1, 0.0, -G - 0.1], "acc bias");
    assert_close(&r.mag, [1.0, 0.05, 0.0], "mag bias");

    let q = ImuParams { noise: false, ..ImuParams::default() };
    let r = readings(&q, &at_rest(rot_x(30.0 * DEG)), 0);
    let lsb = q.acc.lsb;
    let expected = [0.0, (-G * 0.5 / lsb).round() * lsb, (-G * 3f64.sqrt() / 2.0 / lsb).round() * lsb];
    assert_close(&r.acc, expected, "quantised acc");
    assert!((r.acc.z + G * 3f64.sqrt() / 2.0).abs() <= lsb / 2.0);
}

#[test]
fn zero_and_non_finite_quaternions_are_refused() {
    assert!(orientation_from_components([0.0; 4]).is_err());
    assert!(orientation_from_components([f64::NAN, 0.0, 0.0, 1.0]).is_err());
    assert!(orientation_from_components([1e-9, 0.0, 0.0, 0.0]).is_err());
    let q = orientation_from_components([2.0, 0.0, 0.0, 0.0]).unwrap();
    assert_eq!(q, Quat::identity());
    // Scalar first: (cos 15°, sin 15°, 0, 0) is a 30° roll.
    let h = 15.0 * DEG;
    let q = orientation_from_components([3.0 * h.cos(), 3.0 * h.sin(), 0.0, 0.0]).unwrap();
    assert!(q.angle_to(&rot_x(30.0 * DEG)) < 1e-15);
}

#[test]
fn invalid_parameters_are_refused() {
    assert!(ImuParams::default().validate().is_ok());
    let mut p = ImuParams::default();
    p.gyro.sigma.y = -1.0;
    assert!(p.validate().is_err());
    let mut p = ImuParams::default();
    p.acc.lsb = f64::NAN;
    assert!(p.validate().is_err());
    assert!(ImuParams { mag_inclination: 2.0, ..ImuParams::default() }.validate().is_err());
    assert!(ImuParams { g: -1.0, ..ImuParams::default() }.validate().is_err());
}

#[test]
fn noise_statistics_match_the_parameters() {
    const N: u64 = 100_000;
    let p = ImuParams { seed: 31, ..ImuParams::default() };
    let motion = at_rest(rot_x(30.0 * DEG) * rot_z(20.0 * DEG));
    let truth = readings(&ideal(), &motion, 0);
    let n = N as f64;
    let mut noise = ImuNoise::default();
    let all: Vec<ImuReadings> = (0..N).map(|k| readings_with(&p, &motion, &noise.draw(&p, k))).collect();
    for sensor in Sensor::ALL {
        let samples: Vec<Vec3> = all.iter().map(|r| *r.sensor(sensor)).collect();
        let e = p.errors(sensor);
        for axis in 0..3 {
            let x: Vec<f64> = samples.iter().map(|v| v[axis] - truth.sensor(sensor)[axis]).collect();
            let (mean, std) = mean_std(&x);
            let sigma = e.sigma[axis];
            // Quantisation adds lsb²/12 to the variance and at most lsb/2 to the mean (it is
            // dithered by the noise, so in practice far less).
            let expected_std = (sigma * sigma + e.lsb * e.lsb / 12.0).sqrt();
            let mean_limit = 4.0 * sigma / n.sqrt();
            println!(
                "{sensor:?} {}: mean error {mean:+.3e} (limit ±{mean_limit:.1e}), std {std:.5e} vs σ \
                    {sigma:.5e} ({:+.2} %)",
                ["x", "y", "z"][axis],
                100.0 * (std / expected_std - 1.0)
            );
            assert!(mean.abs() < mean_limit, "{sensor:?} axis {axis}: mean {mean}");
            assert!((std / expected_std - 1.0).abs() < 0.02, "{sensor:?} axis {axis}: std {std} vs {expected_std}");
        }
    }
}

#[test]
fn the_nine_channels_carry_independent_noise() {
    let p = ImuParams { seed: 8, ..ImuParams::default() };
    let r = readings(&p, &ImuMotion::default(), 12);
    let errors = [
        r.gyro / p.gyro.sigma.x,
        (r.acc - Vec3::new(0.0, 0.0, -G)) / p.acc.sigma.x,
        (r.mag - Vec3::x()) / p.mag.sigma.x,
    ];
    let all: Vec<f64> = errors.iter().flat_map(|v| v.iter().copied()).collect();
    for i in 0..all.len() {
        for j in 0..i {
            assert_ne!(all[i], all[j], "channels {i} and {j} repeat a sample");
        }
    }
}

#[test]
fn readings_repeat_bit_for_bit_and_ignore_query_order() {
    let p = ImuParams { seed: 4, ..ImuParams::default() };
    let motion = ImuMotion {
        orientation: rot_x(0.2) * rot_y(-0.3),
        angular_velocity: Vec3::new(0.1, 0.2, -0.3),
        acceleration: Vec3::new(0.5, -0.4, 0.3),
    };
    let forward: Vec<ImuReadings> = (0..200).map(|k| readings(&p, &motion, k)).collect();
    // Backwards through one noise memo, each sample drawn three times.
    let mut noise = ImuNoise::default();
    for k in (0..200u64).rev() {
        for _ in 0..3 {
            let r = readings_with(&p, &motion, &noise.draw(&p, k));
            for sensor in Sensor::ALL {
                let (v, f) = (r.sensor(sensor), forward[k as usize].sensor(sensor));
                assert!(v.iter().zip(f.iter()).all(|(a, b)| a.to_bits() == b.to_bits()), "k = {k}, {sensor:?}");
            }
        }
    }
    // A second "run" from scratch is bit-identical too.
    let again: Vec<ImuReadings> = (0..200).map(|k| readings(&p, &motion, k)).collect();
    assert_eq!(forward, again);
}

#[test]
fn seeds_separate_instances() {
    let motion = ImuMotion::default();
    let a = ImuParams { seed: 1, ..ImuParams::default() };
    let b = ImuParams { seed: 2, ..ImuParams::default() };
    let differ = (0..100).filter(|&k| readings(&a, &motion, k) != readings(&b, &motion, k)).count();
    assert_eq!(differ, 100, "different seeds must give different noise at every step");
    let same = ImuParams { seed: 1, ..ImuParams::default() };
    assert!((0..100).all(|k| readings(&a, &motion, k) == readings(&same, &motion, k)));
}

#[test]
fn integrating_the_gyro_recovers_a_constant_rotation() {
    // Constant body rate ω from q0: q(t) = q0 ⊗ exp(ω t / 2). Integrating the gyro readings with
    // the exact exponential update q ← q ⊗ exp(ω_meas h / 2) must return q(T), and the
    // accelerometer must agree with the integrated attitude at every sample.
    let p = ideal();
    let q0 = rot_z(10.0 * DEG) * rot_x(-5.0 * DEG);
    let omega = Vec3::new(0.3, -0.2, 0.5);
    let h = 0.01;
    let steps = 1000u64;
    let truth = |k: u64| q0 * Quat::from_scaled_axis(omega * (k as f64 * h));
    let mut q = q0;
    for k in 0..steps {
        let motion = ImuMotion { orientation: truth(k), angular_velocity: omega, ..ImuMotion::default() };
        let r = readings(&p, &motion, k);
        let gravity_from_attitude = q.inverse_transform_vector(&Vec3::new(0.0, 0.0, -G));
        assert!(
            (r.acc - gravity_from_attitude).amax() < 1e-9,
            "step {k}: acc {:?} vs {gravity_from_attitude:?}",
            r.acc
        );
        q *= Quat::from_scaled_axis(r.gyro * h);
    }
    let error = q.angle_to(&truth(steps));
    let expected = q0 * Quat::from_scaled_axis(omega * (steps as f64 * h));
    println!(
        "gyro integration over {} s at |ω| = {:.3} rad/s: attitude error {error:.2e} rad",
        steps as f64 * h,
        omega.norm()
    );
    assert!(error < 1e-10, "attitude error {error} rad");
    assert!(q.angle_to(&expected) < 1e-10);
}

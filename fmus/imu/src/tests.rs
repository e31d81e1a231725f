//! The FMU model driven through its variable table, as an FMI host would drive it.

use super::*;
use fmu_export::harness::{get_real, instantiate, set_boolean, set_integer, set_real};
use fmu_model::{Causality, Value};
use physics::math::{rot_x, rot_y, STANDARD_GRAVITY};
use physics::noise::mean_std;

const DEG: f64 = std::f64::consts::PI / 180.0;
const G: f64 = STANDARD_GRAVITY;
const OUTPUTS: [&str; 9] = ["gyro.x", "gyro.y", "gyro.z", "acc.x", "acc.y", "acc.z", "mag.x", "mag.y", "mag.z"];

fn outputs(m: &Imu) -> [f64; 9] {
    OUTPUTS.map(|name| get_real(m, name))
}

/// Noise off and quantisation off: the readings are the exact true values.
fn ideal() -> Imu {
    let mut m = instantiate::<Imu>();
    set_boolean(&mut m, "noise", false);
    for lsb in ["gyro.lsb", "acc.lsb", "mag.lsb"] {
        set_real(&mut m, lsb, 0.0);
    }
    m
}

fn set_orientation(m: &mut Imu, q: &Quat) {
    for (name, value) in ["q0", "q1", "q2", "q3"].iter().zip([q.w, q.i, q.j, q.k]) {
        set_real(m, name, value);
    }
}

fn assert_outputs(m: &Imu, expected: [f64; 9], what: &str) {
    let actual = outputs(m);
    for ((name, a), e) in OUTPUTS.iter().zip(actual).zip(expected) {
        assert!((a - e).abs() < 1e-12, "{what}: {name} = {a}, expected {e}");
    }
}

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<Imu>().unwrap();
    assert!(description.xml.contains(r#"name="mag_inclination""#));
    assert!(description.xml.contains(r#"canInterpolateInputs="false""#));
    assert!(description.guid.starts_with('{'));
    for v in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        assert!(matches!(v.value, Value::Real { derivative: None, .. }), "{} must not be interpolated", v.name);
    }
}

#[test]
fn static_orientations_give_the_exact_readings() {
    let (s30, c30) = (30.0 * DEG).sin_cos();
    let (s20, c20) = (20.0 * DEG).sin_cos();
    let (s45, c45) = (45.0 * DEG).sin_cos();
    let mut m = ideal();
    m.initialize(0.0).unwrap();
    assert_outputs(&m, [0.0, 0.0, 0.0, 0.0, 0.0, -G, 1.0, 0.0, 0.0], "level");

    // Rolled 30° about x, given as a non-unit quaternion (normalised inside): 3·(cos 15°, sin 15°, 0, 0).
    for (name, value) in [("q0", 3.0 * (15.0 * DEG).cos()), ("q1", 3.0 * (15.0 * DEG).sin()), ("q2", 0.0), ("q3", 0.0)]
    {
        set_real(&mut m, name, value);
    }
    assert_outputs(&m, [0.0, 0.0, 0.0, 0.0, -G * s30, -G * c30, 1.0, 0.0, 0.0], "rolled 30°");

    set_orientation(&mut m, &rot_y(20.0 * DEG));
    assert_outputs(&m, [0.0, 0.0, 0.0, G * s20, 0.0, -G * c20, c20, 0.0, s20], "pitched 20°");

    set_orientation(&mut m, &Quat::from_axis_angle(&Vec3::z_axis(), 45.0 * DEG));
    set_real(&mut m, "w.x", 0.1);
    set_real(&mut m, "w.y", -0.2);
    set_real(&mut m, "w.z", 0.3);
    assert_outputs(&m, [0.1, -0.2, 0.3, 0.0, 0.0, -G, c45, -s45, 0.0], "yawed 45°, turning");

    // Accelerating north at 2 m/s² while rolled 30°.
    set_orientation(&mut m, &rot_x(30.0 * DEG));
    set_real(&mut m, "a.x", 2.0);
    assert_outputs(&m, [0.1, -0.2, 0.3, 2.0, -G * s30, -G * c30, 1.0, 0.0, 0.0], "rolled 30°, accelerating");
}

#[test]
fn declination_inclination_biases_and_quantisation() {
    let mut m = ideal();
    set_real(&mut m, "mag_declination", 5.95 * DEG);
    set_real(&mut m, "mag_inclination", 60.0 * DEG);
    set_real(&mut m, "gyro.bias.z", 0.005);
    set_real(&mut m, "acc.bias.x", -0.1);
    m.initialize(0.0).unwrap();
    let (sd, cd) = (5.95 * DEG).sin_cos();
    let (si, ci) = (60.0 * DEG).sin_cos();
    assert_outputs(&m, [0.0, 0.0, 0.005, -0.1, 0.0, -G, ci * cd, ci * sd, si], "tilted field, biased");

    let mut q = instantiate::<Imu>();
    set_boolean(&mut q, "noise", false);
    set_orientation(&mut q, &rot_x(30.0 * DEG));
    q.initialize(0.0).unwrap();
    let round = |x: f64, lsb: f64| (x / lsb).round() * lsb;
    let acc_lsb = 0.0006;
    assert_outputs(
        &q,
        [0.0, 0.0, 0.0, 0.0, round(-G * 0.5, acc_lsb), round(-G * (30.0 * DEG).cos(), acc_lsb), 1.0, 0.0, 0.0],
        "quantised",
    );
}

#[test]
fn a_zero_quaternion_is_an_error() {
    let mut m = instantiate::<Imu>();
    set_orientation(&mut m, &Quat::identity());
    set_real(&mut m, "q0", 0.0);
    let message = m.initialize(0.0).unwrap_err();
    assert!(message.contains("quaternion"), "{message}");
    assert!(get_real(&m, "acc.z").is_nan());
    set_real(&mut m, "q3", 1.0);
    m.initialize(0.0).unwrap();
    set_real(&mut m, "q3", 0.0);
    assert!(m.do_step(0.0, 0.01).is_err());
}

#[test]
fn the_sample_index_is_the_number_of_completed_steps() {
    let mut m = instantiate::<Imu>();
    set_integer(&mut m, "seed", 77);
    set_orientation(&mut m, &(rot_x(0.1) * rot_y(0.2)));
    set_real(&mut m, "w.y", 0.05);
    m.initialize(0.0).unwrap();
    let params = m.params;
    let motion = ImuMotion { orientation: m.orientation().unwrap(), angular_velocity: m.w, acceleration: m.a };
    let h = 0.01;
    let at_start = outputs(&m);
    for k in 0..50u64 {
        let expected = physics::imu::readings(&params, &motion, k);
        let flat: Vec<f64> =
            [expected.gyro, expected.acc, expected.mag].iter().flat_map(|v| v.iter().copied()).collect();
        for (name, (a, e)) in OUTPUTS.iter().zip(outputs(&m).iter().zip(&flat)) {
            assert_eq!(a.to_bits(), e.to_bits(), "{name} at k = {k}");
        }
        m.do_step(k as f64 * h, h).unwrap();
    }
    // Re-initialising starts again at k = 0.
    m.initialize(0.0).unwrap();
    assert_eq!(outputs(&m).map(f64::to_bits), at_start.map(f64::to_bits));
}

/// Steps an instance `n` times at 10 ms, reading the outputs once after initialization and after
/// every step.
fn run(mut m: Imu, n: usize) -> Vec<[f64; 9]> {
    m.initialize(0.0).unwrap();
    let mut out = vec![outputs(&m)];
    for i in 0..n {
        m.do_step(i as f64 * 0.01, 0.01).unwrap();
        out.push(outputs(&m));
    }
    out
}

fn seeded(seed: i32) -> Imu {
    let mut m = instantiate::<Imu>();
    set_integer(&mut m, "seed", seed);
    set_orientation(&mut m, &rot_x(30.0 * DEG));
    m
}

#[test]
fn noise_statistics_match_the_parameters() {
    const N: usize = 20_000;
    let mut m = seeded(5);
    set_real(&mut m, "gyro.sigma.y", 0.007);
    set_real(&mut m, "acc.sigma.z", 0.02);
    let sigma: [f64; 9] = [0.0035, 0.007, 0.0035, 0.01, 0.01, 0.02, 0.01, 0.01, 0.01];
    let lsb: [f64; 9] = [0.00007, 0.00007, 0.00007, 0.0006, 0.0006, 0.0006, 0.0001, 0.0001, 0.0001];
    let truth = {
        let mut t = m.clone();
        set_boolean(&mut t, "noise", false);
        for name in ["gyro.lsb", "acc.lsb", "mag.lsb"] {
            set_real(&mut t, name, 0.0);
        }
        t.initialize(0.0).unwrap();
        outputs(&t)
    };
    let samples = run(m, N - 1);
    let n = N as f64;
    for (i, name) in OUTPUTS.iter().enumerate() {
        let x: Vec<f64> = samples.iter().map(|s| s[i] - truth[i]).collect();
        let (mean, std) = mean_std(&x);
        let expected = (sigma[i] * sigma[i] + lsb[i] * lsb[i] / 12.0).sqrt();
        let limit = 4.0 * sigma[i] / n.sqrt();
        let excess = 100.0 * (std / expected - 1.0);
        print!("imu FMU {name}: mean error {mean:+.3e} (limit ±{limit:.1e}), ");
        println!("std {std:.4e} vs σ {:.4e} ({excess:+.2} %), {N} steps", sigma[i]);
        assert!(mean.abs() < limit, "{name}: mean error {mean}");
        // The standard error of a sample std is σ/√(2n) ≈ 0.5 % here.
        assert!((std / expected - 1.0).abs() < 0.03, "{name}: std {std} vs {expected}");
    }
}

#[test]
fn readings_do_not_depend_on_how_often_or_in_what_order_they_are_read() {
    let reference = run(seeded(9), 100);
    // Same instance data, but every output read several times, in reverse order, with FMU-state
    // snapshots taken and restored (an importer that retries steps) in between.
    let mut m = seeded(9);
    m.initialize(0.0).unwrap();
    for (i, expected) in reference.iter().enumerate() {
        for _ in 0..3 {
            for (j, name) in OUTPUTS.iter().enumerate().rev() {
                assert_eq!(get_real(&m, name).to_bits(), expected[j].to_bits(), "{name} after {i} steps");
            }
        }
        let snapshot = m.clone();
        m.do_step(i as f64 * 0.01, 0.01).unwrap();
        let _ = outputs(&m);
        m = snapshot;
        m.do_step(i as f64 * 0.01, 0.01).unwrap();
    }
    // A rerun is bit-identical.
    let again = run(seeded(9), 100);
    assert!(reference.iter().flatten().zip(again.iter().flatten()).all(|(a, b)| a.to_bits() == b.to_bits()));
}

/// The readings are remembered between getters, so an input set after a read must forget them:
/// the readings follow every input at once (direct feedthrough), exactly as if never read before.
#[test]
fn an_input_set_after_a_read_acts_at_once() {
    let stepped = || {
        let mut m = seeded(12);
        m.initialize(0.0).unwrap();
        m.do_step(0.0, 0.01).unwrap();
        m
    };
    let (mut read, mut unread) = (stepped(), stepped());
    let before = outputs(&read);
    for (name, value) in [("q1", 0.3), ("w.z", 0.2), ("a.x", 1.5), ("q3", -0.1)] {
        set_real(&mut read, name, value);
        set_real(&mut unread, name, value);
        let _ = outputs(&read);
    }
    assert_ne!(outputs(&read), before);
    assert_eq!(outputs(&read).map(f64::to_bits), outputs(&unread).map(f64::to_bits));
    let motion = ImuMotion { orientation: read.orientation().unwrap(), angular_velocity: read.w, acceleration: read.a };
    let expected = physics::imu::readings(&read.params, &motion, 1);
    let flat = [expected.gyro, expected.acc, expected.mag].map(|v| v.map(f64::to_bits));
    assert_eq!(
        outputs(&read).map(f64::to_bits).as_slice(),
        flat.iter().flat_map(|v| v.iter().copied()).collect::<Vec<_>>()
    );
}

/// A serialized FMU state carries no noise memo or remembered readings; the restored instance
/// must continue bit for bit, also past the steps where the memo refills its buffer.
#[test]
fn a_serialized_state_continues_bit_for_bit() {
    let mut m = seeded(3);
    m.initialize(0.0).unwrap();
    for i in 0..20 {
        m.do_step(i as f64 * 0.01, 0.01).unwrap();
    }
    let _ = outputs(&m);
    let mut restored: Imu = fmu_export::harness::round_trip(&m);
    for i in 20..60 {
        assert_eq!(outputs(&restored).map(f64::to_bits), outputs(&m).map(f64::to_bits), "after {i} steps");
        m.do_step(i as f64 * 0.01, 0.01).unwrap();
        restored.do_step(i as f64 * 0.01, 0.01).unwrap();
    }
}

#[test]
fn instances_are_independent() {
    // Interleaved stepping of three instances in one process: equal seeds agree, different differ.
    let mut a = seeded(1);
    let mut b = seeded(2);
    let mut c = seeded(1);
    for m in [&mut a, &mut b, &mut c] {
        m.initialize(0.0).unwrap();
    }
    for i in 0..100 {
        let t = i as f64 * 0.01;
        let (ya, yb, yc) = (outputs(&a), outputs(&b), outputs(&c));
        assert_eq!(ya.map(f64::to_bits), yc.map(f64::to_bits), "same seed, step {i}");
        assert!(ya.iter().zip(&yb).filter(|(x, y)| x != y).count() >= 7, "different seeds, step {i}: {ya:?} {yb:?}");
        a.do_step(t, 0.01).unwrap();
        b.do_step(t, 0.01).unwrap();
        // c is read an extra time and stepped last: no effect on its samples.
        let _ = outputs(&c);
        c.do_step(t, 0.01).unwrap();
    }
}

#[test]
fn a_constant_rotation_integrated_from_the_gyro_returns_the_orientation() {
    // The sensor turns at a constant body rate ω; at each communication point the host sets the
    // true orientation q(t_k) = q0 ⊗ exp(ω t_k / 2). Integrating the gyro output from q0 with the
    // exact update q ← q ⊗ exp(ω h / 2) must land on q(T); the accelerometer must agree with the
    // integrated attitude throughout.
    let mut m = ideal();
    let q0 = rot_x(-10.0 * DEG);
    let omega = Vec3::new(0.2, 0.4, -0.3);
    for (name, value) in ["w.x", "w.y", "w.z"].iter().zip(omega.iter()) {
        set_real(&mut m, name, *value);
    }
    let h = 0.01;
    let n = 500;
    let truth = |k: usize| q0 * Quat::from_scaled_axis(omega * (k as f64 * h));
    set_orientation(&mut m, &q0);
    m.initialize(0.0).unwrap();
    let mut q = q0;
    for k in 0..n {
        let y = outputs(&m);
        let specific_force = q.inverse_transform_vector(&Vec3::new(0.0, 0.0, -G));
        assert!((Vec3::new(y[3], y[4], y[5]) - specific_force).amax() < 1e-9, "step {k}");
        q *= Quat::from_scaled_axis(Vec3::new(y[0], y[1], y[2]) * h);
        m.do_step(k as f64 * h, h).unwrap();
        set_orientation(&mut m, &truth(k + 1));
    }
    let error = q.angle_to(&truth(n));
    println!("imu FMU: gyro integration over {} s, attitude error {error:.2e} rad", n as f64 * h);
    assert!(error < 1e-10, "attitude error {error} rad");
}

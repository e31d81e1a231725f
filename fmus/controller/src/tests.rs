//! The FMU model driven through its variable table, as an FMI host would drive it.

use super::*;
use fmu_export::harness::{
    assert_codes_are_the_range, get_boolean, get_real, instantiate, set_boolean, set_integer, set_real,
};
use fmu_model::{Causality, Value};

const H: f64 = 0.01;

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<CraneController>().unwrap();
    assert!(description.xml.contains(r#"canInterpolateInputs="false""#));
    for v in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        assert!(matches!(v.value, Value::Real { derivative: None, .. }), "{} must not be interpolated", v.name);
    }
    // The SPEC §4.5 output names.
    for name in [
        "u.base",
        "u.boom",
        "u.jib",
        "u.winch",
        "est.load.x",
        "est.load.y",
        "est.load.z",
        "est.theta_x",
        "est.theta_y",
        "est.ship.roll",
        "est.ship.pitch",
        "est.ship.yaw",
        "sp.load.x",
        "sp.load.y",
        "sp.load.z",
        "sp.d.base",
        "sp.d.boom",
        "sp.d.jib",
        "sp.winch",
    ] {
        assert!(VARIABLES.iter().any(|v| v.name == name && v.causality == Causality::Output), "missing output {name}");
    }
}

#[test]
fn start_values_survive_the_port_units() {
    // The start values are the physics defaults converted to the port units (V/m, m); the
    // setters convert back. The round trip is exact, so a bare instance computes with exactly the
    // physics defaults.
    let m = instantiate::<CraneController>();
    assert_eq!(m.config, ControllerConfig::DEFAULT);
    assert_eq!(m.inputs, Inputs::AT_REST);
}

#[test]
fn integer_codes_are_exactly_the_declared_ranges() {
    assert_codes_are_the_range::<CraneController, _>("mode", ModeCodes::decode, ModeCodes::code);
    assert_codes_are_the_range::<CraneController, _>("feedback", FeedbackCodes::decode, FeedbackCodes::code);
    assert_codes_are_the_range::<CraneController, _>("setpoint", SetpointCodes::decode, SetpointCodes::code);
    assert_codes_are_the_range::<CraneController, _>("cf_init", AlignCodes::decode, AlignCodes::code);
    assert_codes_are_the_range::<CraneController, _>("attitude_filter", AttitudeCodes::decode, AttitudeCodes::code);
    assert_codes_are_the_range::<CraneController, _>("k.schedule", ScheduleCodes::decode, ScheduleCodes::code);
}

#[test]
fn a_bare_instance_holds_the_crane_at_the_set_point() {
    let mut m = initialized(&[], &[]);
    for k in 0..100 {
        m.do_step(k as f64 * H, H).unwrap();
    }
    // The start inputs describe the crane at the fixed set-point: the actuators need nothing.
    for name in ["u.base", "u.boom", "u.jib"] {
        assert_eq!(get_real(&m, name), 1.65, "{name}");
    }
    assert!(get_boolean(&m, "active") && !get_boolean(&m, "sp.limited"));
    let load = [get_real(&m, "est.load.x"), get_real(&m, "est.load.y"), get_real(&m, "est.load.z")];
    println!(
        "bare instance: est.load {load:.4?} m, sp.d {:.5} {:.5} {:.5} m, sp.winch {:.2} deg, u.winch {:.4}",
        get_real(&m, "sp.d.base"),
        get_real(&m, "sp.d.boom"),
        get_real(&m, "sp.d.jib"),
        get_real(&m, "sp.winch"),
        get_real(&m, "u.winch")
    );
    assert!((get_real(&m, "sp.load.z") - (-0.153 + 0.7)).abs() < 1e-15);
    assert!((load[2] - 0.547).abs() < 2e-3);
    // The default encoder reading is the set-point's length in the controller's own cable model:
    // the winch is on its reference and stays.
    assert_eq!(get_real(&m, "sp.winch"), get_real(&m, "encoder"));
    assert_eq!(get_real(&m, "u.winch"), 0.5);
}

#[test]
fn an_instance_with_every_value_at_its_default_holds_the_crane_still() {
    let mut m = initialized(&[], &[]);
    let neutral = [("u.base", 1.65), ("u.boom", 1.65), ("u.jib", 1.65), ("u.winch", 0.5)];
    let mut worst = [0.0f64; 4];
    for k in 0..300 {
        m.do_step(k as f64 * H, H).unwrap();
        for (w, (name, value)) in worst.iter_mut().zip(neutral) {
            *w = w.max((get_real(&m, name) - value).abs());
        }
    }
    println!(
        "bare instance over 3 s: largest |u - neutral| base {:.3e} V, boom {:.3e} V, jib {:.3e} V, winch {:.3e}; \
         after 3 s u.winch {:.4}, encoder {:.3} deg, sp.winch {:.3} deg",
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        get_real(&m, "u.winch"),
        get_real(&m, "encoder"),
        get_real(&m, "sp.winch")
    );
    assert!(worst.iter().all(|w| *w < 1e-12), "{worst:?}");
}

#[test]
fn the_relative_encoder_starts_at_encoder_lp0_or_else_at_sp_lp() {
    // The default encoder input is the 0.7 m set-point's angle on the controller's drum.
    let first_length = |lp0: f64, relative: bool| {
        let mut m = instantiate::<CraneController>();
        set_real(&mut m, "sp.lp", 0.9);
        set_real(&mut m, "encoder.lp0", lp0);
        set_boolean(&mut m, "encoder.relative", relative);
        m.initialize(0.0).unwrap();
        m.do_step(0.0, H).unwrap();
        (get_real(&m, "encoder.lp0"), get_real(&m, "est.lp"))
    };
    let (lp0, length) = first_length(0.7, true);
    assert_eq!(lp0, 0.7);
    assert!((length - 0.7).abs() < 1e-12, "{length}");
    let (lp0, length) = first_length(0.0, true);
    assert_eq!(lp0, 0.0);
    assert!((length - 0.9).abs() < 1e-12, "{length}");
    // Read as an absolute angle, the encoder gives the 0.7 m whatever encoder.lp0 says.
    let (_, length) = first_length(0.5, false);
    assert!((length - 0.7).abs() < 1e-12, "{length}");
}

#[test]
fn hold_mode_commands_nothing_and_active_from_delays_the_commands() {
    let mut m = initialized(&[("mode", 0)], &[("pot.base", 1.0)]);
    m.do_step(0.0, H).unwrap();
    assert_eq!((get_real(&m, "u.base"), get_real(&m, "u.winch")), (1.65, 0.5));

    let mut m = initialized(&[], &[("active_from", 0.05), ("pot.base", 1.0)]);
    let mut commands = Vec::new();
    for k in 0..10 {
        m.do_step(k as f64 * H, H).unwrap();
        commands.push(get_real(&m, "u.base"));
    }
    // Samples at 0.01 … 0.04 s are inactive; from 0.05 s the base extends toward 25.7 mm.
    assert!(commands[..4].iter().all(|u| *u == 1.65), "{commands:?}");
    assert!(commands[4..].iter().all(|u| *u > 1.65 + 0.145), "{commands:?}");
}

#[test]
fn truth_feedback_uses_the_truth_inputs() {
    let mut m =
        initialized(&[("feedback", 0)], &[("truth.theta_x", 0.1), ("truth.theta_y", -0.05), ("truth.ship.roll", 0.02)]);
    m.do_step(0.0, H).unwrap();
    assert_eq!(
        (get_real(&m, "est.theta_x"), get_real(&m, "est.theta_y"), get_real(&m, "est.ship.roll")),
        (0.1, -0.05, 0.02)
    );
    // The delta law moves the tip set-point toward the load: −0.1 θx in y, +0.1 θy in x.
    assert!((get_real(&m, "sp.cmd.tip.y") - (-0.502 - 0.01)).abs() < 1e-12);
    assert!((get_real(&m, "sp.cmd.tip.x") - (0.003 - 0.005)).abs() < 1e-12);
}

#[test]
fn the_pick_and_place_set_point_is_timed_from_active_from() {
    let mut m = initialized(&[("setpoint", 1)], &[("active_from", 5.0)]);
    let mut t = 0.0;
    while t < 22.5 - 1e-9 {
        m.do_step(t, H).unwrap();
        t += H;
    }
    // 17.5 s into the profile: half-way down from 0.70 to 1.00 m.
    assert!((get_real(&m, "sp.ref.lp") - 0.85).abs() < 1e-9, "{}", get_real(&m, "sp.ref.lp"));
    assert_eq!(get_real(&m, "sp.ref.tip.x"), 0.10);
}

#[test]
fn a_non_finite_input_is_an_error() {
    let mut m = initialized(&[], &[]);
    set_real(&mut m, "imu2.acc.z", f64::NAN);
    assert!(m.do_step(0.0, H).unwrap_err().contains("not finite"));
}

/// The sample clock cannot stall: at t = 1e300 the period is far below the resolution of t, so
/// every sample time rounds to the start and the old loop sampled forever; the samples a step
/// spans are counted first and a step with too many is refused.
#[test]
fn a_step_spanning_too_many_samples_is_refused_instead_of_sampling_forever() {
    let mut m = instantiate::<CraneController>();
    m.initialize(1e300).unwrap();
    let message = m.do_step(1e300, 1.0).unwrap_err();
    assert!(message.contains("at most 100000 per step"), "{message}");

    let mut m = initialized(&[], &[("sample_period", 1e-4)]);
    let message = m.do_step(0.0, SampleClock::MAX_STEP_SIZE).unwrap_err();
    assert!(message.contains("spans 10000000 samples of 0.0001 s"), "{message}");
    assert_eq!(m.clock.samples(), 0, "nothing was sampled");
    m.do_step(0.0, 10.0).unwrap();
    assert_eq!(m.clock.samples(), 100_000);
}

/// A still ship rolled 10°, the filters started at the identity (`cf_init` = 0), read after
/// `seconds`: the estimated roll (rad) and the instance.
fn rolled_ship(attitude_filter: i32, ship_beta: Option<f64>, seconds: f64) -> (f64, CraneController) {
    let roll: f64 = 10f64.to_radians();
    let mut m = instantiate::<CraneController>();
    set_integer(&mut m, "cf_init", 0);
    set_integer(&mut m, "attitude_filter", attitude_filter);
    if let Some(beta) = ship_beta {
        set_real(&mut m, "mw1.beta", beta);
    }
    // Specific force of a still IMU rolled by `roll` about x (NED): g (0, −sin, −cos).
    set_real(&mut m, "imu1.acc.y", -9.80665 * roll.sin());
    set_real(&mut m, "imu1.acc.z", -9.80665 * roll.cos());
    m.initialize(0.0).unwrap();
    let steps = (seconds / H).round() as usize;
    for k in 0..steps {
        m.do_step(k as f64 * H, H).unwrap();
    }
    (get_real(&m, "est.ship.roll"), m)
}

#[test]
fn attitude_filter_selects_madgwick_with_its_gain() {
    // The complementary filter's accelerometer gain (5 % a sample) has the 10° roll within 1 s;
    // Madgwick's correction turns the estimate by at most 2β rad/s (0.35°/s at the default
    // β = 0.00303 rad/s), so the roll is still well under 1° (the 1 Hz output low-pass only
    // lowers it further); with β = 1 rad/s it is there as quickly as the complementary filter's.
    let (complementary, _) = rolled_ship(0, None, 1.0);
    let (madgwick, _) = rolled_ship(1, None, 1.0);
    let (fast, _) = rolled_ship(1, Some(1.0), 1.0);
    let slow_limit = 2.0 * 0.75f64.sqrt() * 0.0035 * 1.0;
    println!(
        concat!(
            "still ship rolled 10°, started at the identity, after 1 s: est.ship.roll complementary ",
            "{:.3}°, Madgwick {:.3}° (β = 0.00303), {:.3}° (β = 1)",
        ),
        complementary.to_degrees(),
        madgwick.to_degrees(),
        fast.to_degrees()
    );
    assert!(complementary.to_degrees() > 8.0, "{complementary}");
    assert!(madgwick > 0.0 && madgwick < slow_limit, "{madgwick}");
    assert!(fast.to_degrees() > 8.0, "{fast}");
}

/// The Madgwick filter's estimate is part of the FMU state: a restored instance continues bit
/// for bit (it would restart the estimate from the identity if the state were not carried).
#[test]
fn a_serialized_state_carries_the_madgwick_estimate() {
    let (_, mut m) = rolled_ship(1, None, 2.0);
    let mut restored: CraneController = fmu_export::harness::round_trip(&m);
    for k in 200..400 {
        m.do_step(k as f64 * H, H).unwrap();
        restored.do_step(k as f64 * H, H).unwrap();
        assert_eq!(get_real(&m, "est.ship.roll").to_bits(), get_real(&restored, "est.ship.roll").to_bits());
    }
    assert!(matches!(m.controller.config.attitude, AttitudeFilterKind::Madgwick));
}

/// An instance with the Integer variables `integers` and then the Real variables `reals` set,
/// initialized at t = 0: the set-up of most tests.
fn initialized(integers: &[(&str, i32)], reals: &[(&str, f64)]) -> CraneController {
    let mut m = instantiate::<CraneController>();
    for &(name, code) in integers {
        set_integer(&mut m, name, code);
    }
    for &(name, value) in reals {
        set_real(&mut m, name, value);
    }
    m.initialize(0.0).unwrap();
    m
}

/// An instance with `feedback` whose deck IMU heaves: a level IMU whose specific force carries
/// the heave acceleration −A w² sin(w t) of a 10 mm, 0.7 rad/s motion (W z down, −g at rest).
fn heaving(feedback: i32) -> CraneController {
    initialized(&[("feedback", feedback)], &[])
}

/// Steps `m` from `from` to `to` s, setting the heaving IMU's specific force before each step.
fn heave_on(m: &mut CraneController, from: usize, to: usize) {
    let (a, w) = (0.01, 0.7);
    for k in from..to {
        let t = (k + 1) as f64 * H;
        set_real(m, "imu1.acc.z", -9.80665 - a * w * w * (w * t).sin());
        m.do_step(k as f64 * H, H).unwrap();
    }
}

/// The value of every output.
fn outputs(m: &CraneController) -> Vec<u64> {
    VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output && matches!(v.value, Value::Real { .. }))
        .map(|v| get_real(m, v.name).to_bits())
        .collect()
}

#[test]
fn feedback_2_estimates_heave_with_the_ekf_and_reads_no_ship_truth() {
    let mut ekf = heaving(2);
    let mut garbage = heaving(2);
    for name in ["ship.x", "ship.y", "ship.z", "truth.tip.x", "truth.lp", "truth.theta_x", "truth.ship.roll"] {
        set_real(&mut garbage, name, 123.0);
    }
    for k in (0..3000).step_by(100) {
        heave_on(&mut ekf, k, k + 100);
        heave_on(&mut garbage, k, k + 100);
        assert_eq!(outputs(&ekf), outputs(&garbage), "t = {} s", (k + 100) as f64 * H);
    }
    // The 20 s window identified the 0.7 rad/s heave; at 30 s the estimate is its position
    // sin(w t)·10 mm (the mode's phase and amplitude from the FFT, refined by the filter).
    let truth = 0.01 * (0.7f64 * 30.0).sin();
    let (z, vz) = (get_real(&ekf, "est.ship.z"), get_real(&ekf, "est.ship.vz"));
    println!(
        "heave at 30 s: EKF {z:.5} m ({vz:.5} m/s), truth {truth:.5} m ({:.5} m/s)",
        0.007 * (0.7f64 * 30.0).cos()
    );
    assert!((z - truth).abs() < 2e-3 && (vz - 0.007 * (0.7f64 * 30.0).cos()).abs() < 2e-3, "{z} {vz}");
    // The same garbage moves the sensor variant's crane: it reads surge/sway/heave from ship.*.
    let (mut sensors, mut fooled) = (heaving(1), heaving(1));
    set_real(&mut fooled, "ship.z", 123.0);
    heave_on(&mut sensors, 0, 10);
    heave_on(&mut fooled, 0, 10);
    assert_eq!(get_real(&fooled, "est.ship.z"), 123.0);
    assert!(get_real(&fooled, "est.tip.z") - get_real(&sensors, "est.tip.z") > 100.0);
}

/// The EKF is part of the FMU state: an instance restored after the identification continues bit
/// for bit (one that lost the filter would estimate zero until its next window).
#[test]
fn a_serialized_state_carries_the_ekf() {
    let mut m = heaving(2);
    heave_on(&mut m, 0, 2200);
    assert_ne!(get_real(&m, "est.ship.z"), 0.0);
    let mut restored: CraneController = fmu_export::harness::round_trip(&m);
    for k in (2200..3000).step_by(50) {
        heave_on(&mut m, k, k + 50);
        heave_on(&mut restored, k, k + 50);
        assert_eq!(outputs(&m), outputs(&restored), "t = {} s", (k + 50) as f64 * H);
    }
}

/// The angle gain's schedule is part of the FMU state: restored after designs at 1.0 m, an
/// instance keeps that design for a length within 1 % of it, as the original does (one that lost
/// the schedule would start it afresh from the set-point's 0.7 m and design at 1.005 m).
#[test]
fn a_serialized_state_carries_the_angle_gains_schedule() {
    let scheduled =
        || initialized(&[("feedback", 0), ("k.schedule", 1)], &[("truth.lp", 1.0), ("truth.theta_x", -0.1)]);
    let mut m = scheduled();
    m.do_step(0.0, H).unwrap();
    let mut restored: CraneController = fmu_export::harness::round_trip(&m);
    for instance in [&mut m, &mut restored] {
        set_real(instance, "truth.lp", 1.005);
        instance.do_step(H, H).unwrap();
    }
    assert_eq!(outputs(&m), outputs(&restored));
    // The gain is the design at 1.0 m: Δy_t = k_θ e_θx, k_θ 5 % below k.angle's 0.1 m/rad.
    let delta = get_real(&m, "sp.cmd.tip.y") - get_real(&m, "truth.tip.y");
    assert!((delta - m.controller.angle_gain() * 0.1).abs() < 1e-15, "{delta}");
    assert!(delta < 0.96 * 0.01, "{delta}");
    // Fixed (the default), the same run keeps k.angle.
    let mut fixed = scheduled();
    set_integer(&mut fixed, "k.schedule", 0);
    fixed.initialize(0.0).unwrap();
    fixed.do_step(0.0, H).unwrap();
    let delta = get_real(&fixed, "sp.cmd.tip.y") - get_real(&fixed, "truth.tip.y");
    assert!((delta - 0.1 * 0.1).abs() < 1e-15, "{delta}");
}

#[test]
fn the_largest_sensible_step_is_the_sample_period() {
    // A longer communication step holds the inputs over several samples: the export layer warns.
    let mut m = instantiate::<CraneController>();
    assert_eq!(m.largest_sensible_step(), Some(0.01));
    set_real(&mut m, "sample_period", 0.005);
    assert_eq!(m.largest_sensible_step(), Some(0.005));
}

//! The FMU model driven through its variable table, as an FMI host would drive it.

use super::*;
use fmu_export::harness::{get_real, instantiate, set_boolean, set_integer, set_real};
use fmu_model::{Causality, Value};
use physics::control::setpoint::Setpoint;
use physics::crane::actuator::Actuator;
use physics::crane::motion::CRANE_BASE;
use physics::math::{euler_zyx, Vec3};

const H: f64 = 0.01;

fn vector(m: &Crane, prefix: &str, names: [&str; 3]) -> Vec3 {
    Vec3::new(
        get_real(m, &format!("{prefix}{}", names[0])),
        get_real(m, &format!("{prefix}{}", names[1])),
        get_real(m, &format!("{prefix}{}", names[2])),
    )
}

fn run(m: &mut Crane, seconds: f64) {
    let n = (seconds / H).round() as usize;
    for _ in 0..n {
        m.do_step(0.0, H).unwrap();
    }
}

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<Crane>().unwrap();
    assert!(description.xml.contains(r#"name="ship.alphaz""#));
    assert!(description.xml.contains(r#"canInterpolateInputs="false""#));
    for v in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        assert!(matches!(v.value, Value::Real { derivative: None, .. }), "{} must not be interpolated", v.name);
    }
}

#[test]
fn a_bare_instance_starts_at_rest_near_the_set_point() {
    let mut m = instantiate::<Crane>();
    m.initialize(0.0).unwrap();
    let tip = vector(&m, "tip.", ["x", "y", "z"]);
    println!("default start: tip in W {:.2?} mm, lp {:.6} m", (tip * 1000.0).as_slice(), get_real(&m, "lp"));
    // The default pose puts the tip on the controller's fixed set-point, to within 0.05 mm.
    assert!((tip - Setpoint::FIXED.tip).amax() < 5e-5);
    assert!((tip - (CRANE_BASE + vector(&m, "tip_base.", ["x", "y", "z"]))).amax() < 1e-15);
    assert!((get_real(&m, "lp") - DEFAULT_POSE.lp).abs() < 1e-15);
    // Neutral commands: nothing moves.
    run(&mut m, 1.0);
    assert_eq!(vector(&m, "tip.", ["x", "y", "z"]), tip);
    assert_eq!(vector(&m, "tip.", ["vx", "vy", "vz"]), Vec3::zeros());
    assert_eq!((get_real(&m, "lp_dot"), get_real(&m, "lp_ddot")), (0.0, 0.0));
}

#[test]
fn a_constant_voltage_gives_the_steady_velocity() {
    let mut m = instantiate::<Crane>();
    m.initialize(0.0).unwrap();
    let u = 1.65 + 0.175 + 0.5;
    set_real(&mut m, "u.jib", u);
    run(&mut m, 1.0);
    let d1 = get_real(&m, "d.jib");
    run(&mut m, 0.5);
    let rate = (get_real(&m, "d.jib") - d1) / 0.5;
    let expected = 640.09 / 48.32 * 0.5 / 1000.0;
    println!("jib at {u} V: {:.4} mm/s (K/a·(u − 1.65 − 0.175) = {:.4} mm/s)", rate * 1000.0, expected * 1000.0);
    assert!((rate - expected).abs() < 1e-12);
    // The winch: lp grows at (K/a)(duty − 0.5)·π·D/360 once the jib has stopped.
    set_real(&mut m, "u.jib", 1.65);
    set_real(&mut m, "u.winch", 0.6);
    run(&mut m, 2.0);
    let expected_lp_dot = 37928.0 / 24.43 * 0.1 * std::f64::consts::PI * 0.04126 / 360.0;
    println!("winch at duty 0.6: lp_dot {:.5} m/s (expected {expected_lp_dot:.5})", get_real(&m, "lp_dot"));
    assert!((get_real(&m, "lp_dot") - expected_lp_dot).abs() < 1e-12);
}

#[test]
fn deadband_parameters_are_used() {
    let mut m = instantiate::<Crane>();
    set_real(&mut m, "deadband.boom.upper", 0.2);
    m.initialize(0.0).unwrap();
    set_real(&mut m, "u.boom", 1.65 + 0.3);
    run(&mut m, 0.5);
    assert!(get_real(&m, "d.boom") > DEFAULT_POSE.extensions[1]);
    // With the thesis' 0.525 V the same command does nothing.
    let mut thesis = instantiate::<Crane>();
    thesis.initialize(0.0).unwrap();
    set_real(&mut thesis, "u.boom", 1.65 + 0.3);
    run(&mut thesis, 0.5);
    assert_eq!(get_real(&thesis, "d.boom"), DEFAULT_POSE.extensions[1]);
    assert_eq!(Actuator::BOOM.deadband.upper, 0.525);
}

/// The steady rates (mm/s, deg/s) of the base, boom, jib and winch 0.3 V (duty 0.1) past their
/// upper deadbands, with every gain K and pole a multiplied by `gain` and `pole`.
fn steady_rates(gain: f64, pole: f64) -> [f64; 4] {
    let mut m = instantiate::<Crane>();
    let defaults = [Actuator::BASE, Actuator::BOOM, Actuator::JIB, Actuator::WINCH];
    for (name, actuator) in ["base", "boom", "jib", "winch"].into_iter().zip(defaults) {
        set_real(&mut m, &format!("gain.{name}"), actuator.plant.gain * gain);
        set_real(&mut m, &format!("pole.{name}"), actuator.plant.pole * pole);
    }
    m.initialize(0.0).unwrap();
    for (name, actuator) in ["u.base", "u.boom", "u.jib"].into_iter().zip(defaults) {
        set_real(&mut m, name, 1.65 + actuator.deadband.upper + 0.3);
    }
    set_real(&mut m, "u.winch", 0.6);
    let outputs = ["d.base", "d.boom", "d.jib", "winch.angle"];
    run(&mut m, 1.0);
    let start = outputs.map(|name| get_real(&m, name));
    run(&mut m, 0.5);
    [0, 1, 2, 3].map(|i| (get_real(&m, outputs[i]) - start[i]) / 0.5)
}

#[test]
fn transfer_function_parameters_set_each_actuator_s_gain_and_pole() {
    // The steady rate is K/a times the linearised input (eq. 3.5-3.8): 1.2 K and 0.8 a give 1.5×
    // (to the e^(−a·1 s) left of the start transient after one second).
    let nominal = steady_rates(1.0, 1.0);
    let changed = steady_rates(1.2, 0.8);
    for (axis, (a, b)) in ["base", "boom", "jib", "winch"].iter().zip(nominal.iter().zip(changed)) {
        assert!((b / a - 1.5).abs() < 1e-4, "{axis}: {a} → {b}");
    }
    // The defaults are the thesis' constants: eq. 3.7's jib rate K/a·0.3 V in m/s.
    assert!((nominal[2] / (640.09 / 48.32 * 0.3 / 1000.0) - 1.0).abs() < 1e-9, "{}", nominal[2]);
}

#[test]
fn sensor_noise_parameters_set_the_standard_deviations() {
    // The crane at rest: readings vary with the noise alone.
    let readings = |pot_sigma: f64, encoder_sigma: f64| {
        let mut m = instantiate::<Crane>();
        set_real(&mut m, "pot.sigma", pot_sigma);
        set_real(&mut m, "encoder.sigma", encoder_sigma);
        m.initialize(0.0).unwrap();
        let mut values = Vec::new();
        for _ in 0..2000 {
            m.do_step(0.0, H).unwrap();
            values.push([get_real(&m, "pot.base"), get_real(&m, "encoder")]);
        }
        let std = |k: usize| {
            let mean = values.iter().map(|v| v[k]).sum::<f64>() / values.len() as f64;
            (values.iter().map(|v| (v[k] - mean).powi(2)).sum::<f64>() / values.len() as f64).sqrt()
        };
        [std(0), std(1)]
    };
    assert_eq!(readings(0.0, 0.0), [0.0, 0.0], "no noise: constant readings");
    // Well above the converters' steps (1.22 mV, 0.088°) the spread is the σ set.
    let [pot, encoder] = readings(0.012, 0.6);
    assert!((pot / 0.012 - 1.0).abs() < 0.05 && (encoder / 0.6 - 1.0).abs() < 0.05, "{pot} V, {encoder}°");
}

#[test]
fn the_ship_motion_acts_directly_on_the_tip() {
    let mut m = instantiate::<Crane>();
    m.initialize(0.0).unwrap();
    let base = vector(&m, "tip_base.", ["x", "y", "z"]);
    for (name, value) in [
        ("ship.x", 0.1),
        ("ship.z", -0.02),
        ("ship.roll", 0.05),
        ("ship.pitch", -0.03),
        ("ship.yaw", 0.2),
        ("ship.wx", 0.3),
    ] {
        set_real(&mut m, name, value);
    }
    let expected = Vec3::new(0.1, 0.0, -0.02) + euler_zyx(0.05, -0.03, 0.2) * (CRANE_BASE + base);
    assert!((vector(&m, "tip.", ["x", "y", "z"]) - expected).amax() < 1e-15);
    let w = Vec3::new(0.3, 0.0, 0.0);
    let v = euler_zyx(0.05, -0.03, 0.2) * w.cross(&(CRANE_BASE + base));
    assert!((vector(&m, "tip.", ["vx", "vy", "vz"]) - v).amax() < 1e-15);
}

const TIP_OUTPUTS: [&str; 9] = ["tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az"];

fn tip_outputs(m: &Crane) -> [u64; 9] {
    TIP_OUTPUTS.map(|name| get_real(m, name).to_bits())
}

/// The tip in W is remembered between getters, so a ship input set after a read must forget it:
/// the tip follows every ship input at once (direct feedthrough), exactly as if never read before.
#[test]
fn a_ship_input_set_after_a_read_moves_the_tip_at_once() {
    let stepped = || {
        let mut m = instantiate::<Crane>();
        m.initialize(0.0).unwrap();
        set_real(&mut m, "u.boom", 2.5);
        m.do_step(0.0, H).unwrap();
        m
    };
    let (mut read, mut unread) = (stepped(), stepped());
    let before = tip_outputs(&read);
    for (name, value) in [("ship.z", -0.02), ("ship.roll", 0.05), ("ship.wx", 0.3), ("ship.alphaz", 0.1)] {
        set_real(&mut read, name, value);
        set_real(&mut unread, name, value);
        let _ = tip_outputs(&read);
    }
    assert_ne!(tip_outputs(&read), before);
    assert_eq!(tip_outputs(&read), tip_outputs(&unread));
}

/// A serialized FMU state carries no noise memos or remembered tip; the restored instance must
/// continue bit for bit, also past the steps where a memo refills its buffer.
#[test]
fn a_serialized_state_continues_bit_for_bit() {
    const OUTPUTS: [&str; 5] = ["pot.base", "pot.boom", "pot.jib", "encoder", "tip.ax"];
    let mut m = instantiate::<Crane>();
    set_real(&mut m, "ship.roll", 0.05);
    m.initialize(0.0).unwrap();
    set_real(&mut m, "u.jib", 2.5);
    set_real(&mut m, "u.winch", 0.7);
    run(&mut m, 0.2);
    let _ = tip_outputs(&m);
    let mut restored: Crane = fmu_export::harness::round_trip(&m);
    for i in 20..60 {
        let (a, b) = (OUTPUTS.map(|n| get_real(&m, n).to_bits()), OUTPUTS.map(|n| get_real(&restored, n).to_bits()));
        assert_eq!(a, b, "after {i} steps");
        assert_eq!(tip_outputs(&m), tip_outputs(&restored), "after {i} steps");
        m.do_step(0.0, H).unwrap();
        restored.do_step(0.0, H).unwrap();
    }
}

/// The plant's propagators are kept from step to step; a step of another size must not reuse
/// them. Steps of changing size, two of them into the boom's stroke end, against the plant.
#[test]
fn each_step_size_advances_by_its_own_propagators() {
    let mut m = instantiate::<Crane>();
    m.initialize(0.0).unwrap();
    let commands = Commands { volts: [0.4, 3.3, 2.2], duty: 0.8 };
    for (name, value) in ["u.base", "u.boom", "u.jib", "u.winch"].iter().zip([0.4, 3.3, 2.2, 0.8]) {
        set_real(&mut m, name, value);
    }
    let mut expected = m.state;
    for h in [0.01, 0.01, 0.005, 0.02, 0.01, 1.0, 0.25, 0.01] {
        m.do_step(0.0, h).unwrap();
        expected = CraneConfig::DEFAULT.advance(&expected, &commands, h);
        assert_eq!(m.state, expected, "step of {h} s");
    }
    assert_eq!(get_real(&m, "d.boom"), 0.05, "the boom reached its stroke end");
}

#[test]
fn sensors_read_the_actuators_and_the_winch() {
    let mut m = instantiate::<Crane>();
    set_boolean(&mut m, "noise", false);
    m.initialize(0.0).unwrap();
    let lsb = 5.0 / 4096.0;
    for (pot, d) in ["pot.base", "pot.boom", "pot.jib"].iter().zip(["d.base", "d.boom", "d.jib"]) {
        assert!((get_real(&m, pot) - get_real(&m, d) * 100.0).abs() <= 0.5 * lsb);
    }
    assert!((get_real(&m, "encoder") - get_real(&m, "winch.angle")).abs() <= 0.5 * 360.0 / 4096.0);
    // With noise, two instances with the same seed agree sample for sample; another seed differs.
    let trace = |seed: i32| {
        let mut m = instantiate::<Crane>();
        set_integer(&mut m, "seed", seed);
        m.initialize(0.0).unwrap();
        (0..50)
            .map(|_| {
                m.do_step(0.0, H).unwrap();
                [get_real(&m, "pot.base"), get_real(&m, "encoder")]
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(trace(5), trace(5));
    assert_ne!(trace(5), trace(6));
}

#[test]
fn bad_parameters_are_errors() {
    let mut m = instantiate::<Crane>();
    set_real(&mut m, "deadband.jib.lower", 0.1);
    assert!(m.initialize(0.0).is_err());
}

//! The FMU driven through its variable table, as an FMI host would drive it. The control law's
//! own tests are in `physics::offshore_control`; these hold the table, the sampling and the modes.

use super::*;
use fmu_export::harness::{
    assert_codes_are_the_range, get_boolean, get_real, instantiate, set_integer, set_real, set_string,
};
use fmu_model::{Causality, Value};
use physics::offshore_control::drives::RatedSpeeds;

const H: f64 = 0.01;
const SPOOLS: [&str; 4] = ["spool.slew", "spool.boom", "spool.jib", "spool.winch"];

/// An instance with the Real variables `reals` set, initialized at t = 0: the set-up of most tests.
fn initialized(reals: &[(&str, f64)]) -> KnuckleBoomController {
    let mut m = instantiate::<KnuckleBoomController>();
    for &(name, value) in reals {
        set_real(&mut m, name, value);
    }
    m.initialize(0.0).unwrap();
    m
}

fn spools(m: &KnuckleBoomController) -> [f64; 4] {
    SPOOLS.map(|name| get_real(m, name))
}

/// Steps of `h` from `t0` to `t1`.
fn run(m: &mut KnuckleBoomController, t0: f64, t1: f64, h: f64) {
    let n = ((t1 - t0) / h).round() as usize;
    for k in 0..n {
        m.do_step(t0 + k as f64 * h, h).unwrap();
    }
}

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<KnuckleBoomController>().unwrap();
    assert!(description.xml.contains(r#"canInterpolateInputs="false""#));
    for v in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        assert!(matches!(v.value, Value::Real { derivative: None, .. }), "{} must not be interpolated", v.name);
    }
    // The crane's spool inputs have these names (knuckle_boom's table).
    for name in SPOOLS {
        assert!(VARIABLES.iter().any(|v| v.name == name && v.causality == Causality::Output), "missing {name}");
    }
}

#[test]
fn integer_codes_are_exactly_the_declared_ranges() {
    assert_codes_are_the_range::<KnuckleBoomController, _>("mode", ModeCodes::decode, ModeCodes::code);
    assert_codes_are_the_range::<KnuckleBoomController, _>("heave", HeaveCodes::decode, HeaveCodes::code);
    assert_codes_are_the_range::<KnuckleBoomController, _>("setpoint", SetpointCodes::decode, SetpointCodes::code);
    assert_codes_are_the_range::<KnuckleBoomController, _>("lqr.schedule", ScheduleCodes::decode, ScheduleCodes::code);
}

#[test]
fn the_pick_and_place_set_point_is_timed_from_active_from_at_full_scale() {
    let mut m = instantiate::<KnuckleBoomController>();
    set_integer(&mut m, "setpoint", 1);
    set_real(&mut m, "active_from", 5.0);
    m.initialize(0.0).unwrap();
    run(&mut m, 0.0, 5.0, 1.0);
    let start = ["setpoint.x", "setpoint.z"].map(|name| get_real(&m, name));
    // 87.5 s in, half way down the pick (the test scale's 17.5 s, l_p 0.85 m): 3.75 m of the
    // 7.5 m paid out, the load's set-point as much lower; 300 s in, half way along the move (the
    // test scale's 60 s, x = 0): the tip 2.5 m of its 5 m towards −x.
    run(&mut m, 5.0, 92.5, 0.5);
    assert!((get_real(&m, "setpoint.z") - start[1] - 3.75).abs() < 1e-9, "{}", get_real(&m, "setpoint.z"));
    assert!((get_real(&m, "setpoint.x") - start[0]).abs() < 1e-12);
    run(&mut m, 92.5, 305.0, 0.5);
    assert!((get_real(&m, "setpoint.x") - start[0] + 2.5).abs() < 1e-9, "{}", get_real(&m, "setpoint.x"));
    assert!((get_real(&m, "setpoint.z") - start[1]).abs() < 1e-9);
}

#[test]
fn a_bare_instance_holds_still_and_samples_from_start_plus_one_period() {
    let mut m = instantiate::<KnuckleBoomController>();
    m.initialize(2.0).unwrap();
    // No sample at initialization: the outputs are the centred spools until t = 2.01 s.
    assert_eq!(spools(&m), [0.0; 4]);
    assert_eq!(get_real(&m, "load_height.ref"), 0.0);
    run(&mut m, 2.0, 3.0, H);
    // The inputs are the crane's default start: every joint on its reference, the load height
    // on its own. Nothing moves.
    assert_eq!(spools(&m), [0.0; 4]);
    assert!(!get_boolean(&m, "saturated"));
    let tip_z = get_real(&m, "tip.z");
    assert_eq!(get_real(&m, "load_height"), tip_z + 10.0);
    assert_eq!(get_real(&m, "load_height.ref"), get_real(&m, "load_height"));
}

#[test]
fn a_displaced_boom_is_driven_back_at_k_q_through_its_lever_and_the_deadband() {
    // The ramp out of the way: the spool is the law's in one sample.
    let mut m = initialized(&[("spool_rate", 1000.0)]);
    m.do_step(0.0, H).unwrap();
    let boom = get_real(&m, "joint.boom");
    // 10 mrad below the latched elevation: q̇_c = 2 1/s · 0.01 rad = 0.02 rad/s up.
    set_real(&mut m, "joint.boom", boom - 0.01);
    m.do_step(H, H).unwrap();
    let crane = &CONFIG.crane;
    let [(_, lever), _] = crane.arm.cylinders(&[INPUTS.joints[0], boom - 0.01, INPUTS.joints[2]]);
    let extend = RatedSpeeds::of(crane).cylinders[0].0;
    let opening = lever * 0.02 / extend;
    let d = crane.boom.valve.deadband;
    let expected = opening.signum() * (d + (1.0 - d) * opening.abs());
    let spool = get_real(&m, "spool.boom");
    println!("boom 10 mrad low: lever {lever:.4} m/rad, opening {opening:.4}, spool {spool:.6}");
    assert!((spool - expected).abs() < 1e-12, "spool {spool}, expected {expected}");
    assert!((get_real(&m, "opening.boom") - opening).abs() < 1e-12);
    assert!(spool > d, "raising the boom extends its cylinder");
    assert_eq!((get_real(&m, "spool.slew"), get_real(&m, "spool.jib")), (0.0, 0.0));
}

#[test]
fn the_winch_pays_out_as_the_deck_heaves_up() {
    let mut m = initialized(&[("spool_rate", 1000.0)]);
    m.do_step(0.0, H).unwrap();
    // The deck rises at 0.2 m/s (W z down): the load keeps its height if the rope pays out at
    // 0.2 m/s; the crane's joints are on their references, so the arm adds nothing.
    set_real(&mut m, "ship.vz", -0.2);
    m.do_step(H, H).unwrap();
    let rate = get_real(&m, "command.lp_dot");
    assert!((rate - 0.2).abs() < 1e-12, "rope rate {rate}");
    let rope = RatedSpeeds::of(&CONFIG.crane).rope;
    assert!((get_real(&m, "opening.winch") - 0.2 / rope).abs() < 1e-12);
    // Without heave compensation the winch holds its length.
    set_integer(&mut m, "heave", 0);
    m.do_step(2.0 * H, H).unwrap();
    assert_eq!(get_real(&m, "command.lp_dot"), 0.0);
    assert_eq!(get_real(&m, "spool.winch"), 0.0);
}

#[test]
fn the_outputs_do_not_depend_on_how_the_master_divides_the_steps() {
    let sampled = |h: f64| {
        let mut m = initialized(&[]);
        let mut t = 0.0;
        let mut trace = Vec::new();
        // The deck heaves with a step in velocity at t = 0.2 s; read every 0.1 s.
        for block in 0..10 {
            if block == 2 {
                set_real(&mut m, "ship.vz", -0.1);
                set_real(&mut m, "joint.jib", INPUTS.joints[2] + 0.02);
            }
            run(&mut m, t, t + 0.1, h);
            t += 0.1;
            trace.push(spools(&m));
        }
        trace
    };
    let fine = sampled(0.01);
    assert_eq!(fine, sampled(0.05));
    assert_eq!(fine, sampled(0.1));
    assert!(fine[9][JIB] != 0.0 && fine[9][WINCH] > 0.0, "{:?}", fine[9]);
}

#[test]
fn heave_by_the_arm_needs_compensation_mode() {
    let mut m = instantiate::<KnuckleBoomController>();
    set_integer(&mut m, "heave", 2);
    let error = m.initialize(0.0).unwrap_err();
    assert!(error.contains("needs mode = 2"), "{error}");
    // Switched while running, the sample refuses it.
    let mut m = initialized(&[]);
    m.do_step(0.0, H).unwrap();
    set_integer(&mut m, "heave", 2);
    let error = m.do_step(H, H).unwrap_err();
    assert!(error.contains("needs mode = 2"), "{error}");
}

#[test]
fn mode_off_centres_every_spool() {
    let mut m = initialized(&[]);
    m.do_step(0.0, H).unwrap();
    set_real(&mut m, "joint.slew", 0.3);
    set_real(&mut m, "ship.vz", -0.3);
    set_integer(&mut m, "mode", 0);
    m.do_step(H, H).unwrap();
    assert_eq!(spools(&m), [0.0; 4]);
}

#[test]
fn a_non_finite_input_and_an_oversized_step_are_errors() {
    let mut m = initialized(&[]);
    set_real(&mut m, "load.vy", f64::NAN);
    let error = m.do_step(0.0, H).unwrap_err();
    assert!(error.contains("load.v") && error.contains("t = 0.01 s"), "{error}");

    let mut m = initialized(&[("sample_period", 1e-4)]);
    let error = m.do_step(0.0, 20.0).unwrap_err();
    assert!(error.contains("at most 100000 per step"), "{error}");
}

#[test]
fn a_saved_state_resumes_bit_for_bit() {
    let mut m = initialized(&[]);
    set_real(&mut m, "ship.vz", -0.1);
    set_real(&mut m, "joint.boom", INPUTS.joints[1] - 0.01);
    run(&mut m, 0.0, 0.5, H);
    let mut copy = fmu_export::harness::round_trip(&m);
    set_real(&mut m, "joint.slew", 0.01);
    set_real(&mut copy, "joint.slew", 0.01);
    run(&mut m, 0.5, 1.0, H);
    run(&mut copy, 0.5, 1.0, H);
    assert_eq!(spools(&m), spools(&copy));
    assert_eq!(get_real(&m, "load_height.ref"), get_real(&copy, "load_height.ref"));
}

#[test]
fn nothing_acts_or_latches_before_active_from() {
    let mut m = initialized(&[("active_from", 0.5)]);
    set_real(&mut m, "ship.vz", -0.2);
    run(&mut m, 0.0, 0.49, H);
    assert_eq!((spools(&m), get_real(&m, "setpoint.z")), ([0.0; 4], 0.0));
    // The first active sample latches the set-point: the load under the tip at 10 m.
    set_real(&mut m, "ship.z", -1.0);
    run(&mut m, 0.49, 0.5, H);
    let tip = [get_real(&m, "tip.x"), get_real(&m, "tip.y"), get_real(&m, "tip.z")];
    assert_eq!([get_real(&m, "setpoint.x"), get_real(&m, "setpoint.y")], [tip[0], tip[1]]);
    assert_eq!(get_real(&m, "setpoint.z"), tip[2] + 10.0);
    // The winch starts paying out, at the ramp's 5 1/s · 10 ms.
    assert_eq!(get_real(&m, "spool.winch"), 0.05);
}

/// Scheduled, the anti-sway gain follows the hoist length sample by sample: the same whatever
/// the master's step, and after a save and restore (the last design is in the state: a restored
/// instance that lost it would design afresh at 20.1 m, within 1 % of the last design's 20 m).
#[test]
fn a_scheduled_gain_depends_on_the_samples_only() {
    let run = |h: f64, restore_at: Option<usize>| {
        let mut m = instantiate::<KnuckleBoomController>();
        set_integer(&mut m, "mode", 2);
        set_integer(&mut m, "lqr.schedule", 1);
        m.initialize(0.0).unwrap();
        let tip = m.controller.config.crane.arm.tip_in_world(&INPUTS.ship, &INPUTS.joints, &[0.0; 3], &[0.0; 3]);
        let mut trace = Vec::new();
        // The hoist length 10 → 20 → 20.1 m, the load 0.1 m out in x.
        for (block, lp) in [10.0, 20.0, 20.1].into_iter().enumerate() {
            set_real(&mut m, "lp", lp);
            set_real(&mut m, "load.x", tip.pos.x + 0.1);
            set_real(&mut m, "load.z", tip.pos.z + lp);
            if restore_at == Some(block) {
                m = fmu_export::harness::round_trip(&m);
            }
            run(&mut m, block as f64 * 0.1, (block + 1) as f64 * 0.1, h);
            trace.push((get_real(&m, "command.vx"), m.controller.antisway().unwrap().gain));
        }
        trace
    };
    let fine = run(0.01, None);
    assert_eq!(fine, run(0.05, None));
    assert_eq!(fine, run(0.1, Some(2)));
    let at =
        |lp: f64| physics::offshore_control::antisway::AntiSway::design(lp, CONFIG.gravity, &CONFIG.weights).unwrap().0;
    assert_eq!(fine[1].1, at(20.0).gain);
    assert_eq!(fine[2].1, at(20.0).gain);
}

#[test]
fn an_absurd_input_is_refused_instead_of_passing_through_to_the_outputs() {
    // Every Real input but the residual and the crane's interface (bounded by their declared
    // ranges) at ±1e300: the sample fails naming the input instead of reporting tip.* and
    // setpoint.* of ±1e300.
    let bounded = |name: &str| name.starts_with("residual.") || CRANE_INTERFACE.iter().any(|(n, _)| *n == name);
    let inputs = VARIABLES.iter().filter(|v| v.causality == Causality::Input && !bounded(v.name));
    for v in inputs {
        for bad in [1e300, -1e300, 2e6] {
            let mut m = initialized(&[]);
            set_real(&mut m, v.name, bad);
            let error = m.do_step(0.0, H).expect_err(v.name);
            let stem = v.name.trim_end_matches(['x', 'y', 'z']);
            assert!(error.contains(stem) && error.contains("beyond ±1e6"), "{}: {error}", v.name);
            for output in ["tip.x", "setpoint.z"] {
                assert!(
                    get_real(&m, output).abs() < 1e6,
                    "{output} = {} after {} = {bad}",
                    get_real(&m, output),
                    v.name
                );
            }
        }
    }
    // A large but possible value (a ship 100 km from the origin) still runs.
    let mut m = initialized(&[]);
    set_real(&mut m, "ship.x", 1e5);
    m.do_step(0.0, H).unwrap();
}

#[test]
fn the_largest_sensible_step_is_the_sample_period() {
    // A longer communication step holds the inputs over several samples: the export layer warns.
    let mut m = instantiate::<KnuckleBoomController>();
    assert_eq!(m.largest_sensible_step(), Some(0.01));
    set_real(&mut m, "sample_period", 0.005);
    assert_eq!(m.largest_sensible_step(), Some(0.005));
}

/// The crane's interface outputs for the description `crane` mounted at the default base.
fn crane_outputs(crane: &str) -> Vec<(&'static str, f64)> {
    let params = crane_description::load(crane, None).unwrap().params(CONFIG.crane.arm.base);
    let r = RatedSpeeds::of(&params);
    let [(be, br), (je, jr)] = r.cylinders;
    let values = [crane_description::fingerprint(&params), be, br, je, jr, r.slew, r.rope];
    CRANE_INTERFACE.iter().map(|(name, _)| *name).zip(values).collect()
}

#[test]
fn a_connected_crane_that_is_the_controllers_own_is_accepted() {
    for crane in ["osp_derived", "ahc_10t"] {
        let mut m = instantiate::<KnuckleBoomController>();
        set_string(&mut m, "crane", crane);
        for (name, value) in crane_outputs(crane) {
            set_real(&mut m, name, value);
        }
        m.initialize(0.0).unwrap();
        run(&mut m, 0.0, 0.1, H);
    }
}

#[test]
fn a_crane_with_other_drive_sizes_is_refused_naming_both_values() {
    // The crane runs the AHC crane's description, the controller the default one.
    let mut m = instantiate::<KnuckleBoomController>();
    for (name, value) in crane_outputs("ahc_10t") {
        set_real(&mut m, name, value);
    }
    m.initialize(0.0).unwrap();
    let e = m.do_step(0.0, H).unwrap_err();
    let ahc = crane_outputs("ahc_10t")[1].1;
    let own = RatedSpeeds::of(&CONFIG.crane).cylinders[0].0;
    assert!(e.contains(&format!("rated.boom.extend is {ahc} m/s at the crane and {own} m/s here")), "{e}");
    // Only the mounting point differs: the fingerprint says so.
    let mut m = instantiate::<KnuckleBoomController>();
    for (name, value) in crane_outputs("osp_derived") {
        set_real(&mut m, name, value);
    }
    set_real(&mut m, "base.y", -5.0);
    m.initialize(0.0).unwrap();
    let e = m.do_step(0.0, H).unwrap_err();
    assert!(e.contains("crane.fingerprint") && e.contains("base.*"), "{e}");
}

#[test]
fn the_controllers_drive_model_comes_from_its_description() {
    let mut m = instantiate::<KnuckleBoomController>();
    set_string(&mut m, "crane", "ahc_10t");
    m.initialize(0.0).unwrap();
    let ahc = crane_description::load("ahc_10t", None).unwrap();
    assert_eq!(m.controller.config.crane, ahc.params(CONFIG.crane.arm.base));
}

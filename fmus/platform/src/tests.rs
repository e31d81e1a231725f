//! The FMU model driven through its variable table, as an FMI host would drive it.

use super::*;
use fmu_export::harness::{
    assert_codes_are_the_range, get_boolean, get_real, instantiate, set_boolean, set_integer, set_real, variable,
};
use fmu_model::{Causality, Value};
use physics::math::{euler_zyx, Quat, Vec3, STANDARD_GRAVITY};
use physics::platform::kinematics::{exact_inverse, PlatformGeometry};
use std::path::Path;

const H: f64 = 0.01;
const OUTPUTS: [&str; 22] = [
    "ship.x",
    "ship.y",
    "ship.z",
    "ship.roll",
    "ship.pitch",
    "ship.yaw",
    "ship.q0",
    "ship.q1",
    "ship.q2",
    "ship.q3",
    "ship.vx",
    "ship.vy",
    "ship.vz",
    "ship.ax",
    "ship.ay",
    "ship.az",
    "ship.wx",
    "ship.wy",
    "ship.wz",
    "ship.alphax",
    "ship.alphay",
    "ship.alphaz",
];

fn set_string(m: &mut Platform, name: &str, value: &str) {
    match variable::<Platform>(name).value {
        Value::String { set: Some(set), .. } => set(m, value),
        _ => panic!("{name} is not a settable String"),
    }
}

fn get(m: &Platform, names: [&str; 3]) -> Vec3 {
    Vec3::new(get_real(m, names[0]), get_real(m, names[1]), get_real(m, names[2]))
}

/// The orientation output as a unit quaternion.
fn attitude(m: &Platform) -> Quat {
    let q = [get_real(m, "ship.q0"), get_real(m, "ship.q1"), get_real(m, "ship.q2"), get_real(m, "ship.q3")];
    assert!((q.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-15);
    physics::imu::orientation_from_components(q).unwrap()
}

fn la(m: &Platform) -> [f64; 5] {
    ["la1", "la2", "la3", "la4", "la5"].map(|n| get_real(m, n))
}

/// An instance of ship motion `profile` (0 still water, 1-3 the sea states, 4 sine) with the Real
/// parameters `reals` set, initialized at t = 0: the set-up of most tests.
fn started(profile: i32, reals: &[(&str, f64)]) -> Platform {
    let mut m = instantiate::<Platform>();
    set_integer(&mut m, "profile", profile);
    for &(name, value) in reals {
        set_real(&mut m, name, value);
    }
    m.initialize(0.0).unwrap();
    m
}

/// Profile 1 with the yaw the platform mechanism adds, initialized at t = 0.
fn profile_one_with_the_mechanism_yaw() -> Platform {
    let mut m = instantiate::<Platform>();
    set_integer(&mut m, "profile", 1);
    set_boolean(&mut m, "mechanism_yaw", true);
    m.initialize(0.0).unwrap();
    m
}

/// Runs `m` (initialized) for `steps` steps and returns the outputs at every communication point.
fn record(m: &mut Platform, steps: usize) -> Vec<Vec<f64>> {
    let mut rows = vec![OUTPUTS.iter().map(|n| get_real(m, n)).collect::<Vec<_>>()];
    for k in 0..steps {
        m.do_step(k as f64 * H, H).unwrap();
        rows.push(OUTPUTS.iter().map(|n| get_real(m, n)).collect());
    }
    rows
}

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<Platform>().unwrap();
    assert!(description.xml.contains(r#"name="la_limit""#));
    assert!(description.xml.contains(r#"name="motion_file""#));
    assert!(VARIABLES.iter().all(|v| v.causality != Causality::Input), "the platform has no inputs");
    assert_eq!(SINE_OMEGA, (STANDARD_GRAVITY / 0.7).sqrt());
}

#[test]
fn integer_codes_are_exactly_the_declared_ranges() {
    assert_codes_are_the_range::<Platform, _>("profile", SourceCodes::decode, SourceCodes::code);
    assert_codes_are_the_range::<Platform, _>("crane_location", LocationCodes::decode, LocationCodes::code);
    assert_codes_are_the_range::<Platform, _>("ik_model", ModelCodes::decode, ModelCodes::code);
}

#[test]
fn a_bare_instance_is_still_water_at_the_neutral_pose() {
    let mut m = started(0, &[]);
    for _ in 0..3 {
        for name in OUTPUTS {
            let expected = if name == "ship.q0" { 1.0 } else { 0.0 };
            assert_eq!(get_real(&m, name), expected, "{name}");
        }
        assert!(la(&m).iter().all(|x| (x - 0.1).abs() < 1e-15), "{:?}", la(&m));
        assert!(!get_boolean(&m, "la_limit"));
        m.do_step(0.0, H).unwrap();
    }
}

#[test]
fn profile_1_stays_inside_the_limits_with_consistent_derivatives() {
    let mut m = started(1, &[]);
    let rows = record(&mut m, 12_000);
    let index = |name: &str| OUTPUTS.iter().position(|n| *n == name).unwrap();
    // Second-order central differences of the 10 ms samples against the exact derivatives.
    let mut worst: f64 = 0.0;
    for k in 1..rows.len() - 1 {
        for (x, v, a) in
            [("ship.x", "ship.vx", "ship.ax"), ("ship.y", "ship.vy", "ship.ay"), ("ship.z", "ship.vz", "ship.az")]
        {
            let fd_v = (rows[k + 1][index(x)] - rows[k - 1][index(x)]) / (2.0 * H);
            let fd_a = (rows[k + 1][index(v)] - rows[k - 1][index(v)]) / (2.0 * H);
            let scale_v = 1e-3 + rows[k][index(v)].abs();
            let scale_a = 1e-3 + rows[k][index(a)].abs();
            worst =
                worst.max((fd_v - rows[k][index(v)]).abs() / scale_v).max((fd_a - rows[k][index(a)]).abs() / scale_a);
        }
    }
    println!("profile 1, 120 s: translational derivatives vs central differences, worst relative error {worst:.2e}");
    assert!(worst < 2e-3);
    // Yaw stays zero, the quaternion is the Z–Y–X attitude.
    assert!(rows.iter().all(|r| r[index("ship.yaw")] == 0.0));
    let r = &rows[4321];
    let q = euler_zyx(r[index("ship.roll")], r[index("ship.pitch")], 0.0);
    assert!((q.w - r[index("ship.q0")]).abs() < 1e-15 && (q.i - r[index("ship.q1")]).abs() < 1e-15);
}

#[test]
fn set_points_and_the_limit_flag_over_the_profiles() {
    for profile in 1..=3 {
        let mut m = started(profile, &[]);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..12_000 {
            let x = la(&m);
            lo = x.iter().fold(lo, |a, b| a.min(*b));
            hi = x.iter().fold(hi, |a, b| a.max(*b));
            assert!(!get_boolean(&m, "la_limit"), "profile {profile}: limit at t = {}", k as f64 * H);
            m.do_step(k as f64 * H, H).unwrap();
        }
        println!("profile {profile}: set-points {:.1} … {:.1} mm over 120 s, la_limit never set", lo * 1e3, hi * 1e3);
        assert!(lo > 0.0 && hi < 0.2);
    }
}

#[test]
fn angular_velocity_and_acceleration_follow_the_attitude() {
    let m = profile_one_with_the_mechanism_yaw();
    let h = 1e-4;
    for t in [3.0, 47.5, 100.0] {
        let at = |time: f64| {
            let mut c = m.clone();
            c.do_step(time - h, h).unwrap();
            (
                attitude(&c),
                get(&c, ["ship.wx", "ship.wy", "ship.wz"]),
                get(&c, ["ship.alphax", "ship.alphay", "ship.alphaz"]),
            )
        };
        let (q, w, alpha) = at(t);
        let (q_plus, w_plus, _) = at(t + h);
        let (q_minus, w_minus, _) = at(t - h);
        let fd_w = ((q.inverse() * q_plus).scaled_axis() - (q.inverse() * q_minus).scaled_axis()) / (2.0 * h);
        let fd_alpha = (w_plus - w_minus) / (2.0 * h);
        assert!((w - fd_w).norm() < 1e-9, "t = {t}: ω {w:?} vs {fd_w:?}");
        assert!((alpha - fd_alpha).norm() < 1e-8, "t = {t}: α {alpha:?} vs {fd_alpha:?}");
    }
}

#[test]
fn the_mechanism_yaw_is_the_dependent_yaw_of_the_exact_chain() {
    let mut m = profile_one_with_the_mechanism_yaw();
    let mut largest: f64 = 0.0;
    for k in 0..2_000 {
        m.do_step(k as f64 * H, H).unwrap();
        let pose = [
            get_real(&m, "ship.x"),
            get_real(&m, "ship.y"),
            get_real(&m, "ship.z"),
            get_real(&m, "ship.roll"),
            get_real(&m, "ship.pitch"),
        ];
        let expected = exact_inverse(&m.geometry, &pose).unwrap().yaw;
        assert_eq!(get_real(&m, "ship.yaw"), expected);
        largest = largest.max(expected.abs());
    }
    println!("profile 1, mechanism yaw over 20 s: up to {:.2e} deg", largest.to_degrees());
    assert!(largest > 0.0);
}

#[test]
fn the_sine_profile_and_the_stern_frame() {
    let mut m = instantiate::<Platform>();
    set_integer(&mut m, "profile", 4);
    set_real(&mut m, "sine_amplitude", 0.003);
    set_real(&mut m, "sine_omega", 2.0);
    set_integer(&mut m, "crane_location", 1);
    m.initialize(0.0).unwrap();
    m.do_step(0.0, 0.5).unwrap();
    let s = 0.003 * 1.0f64.sin();
    // Ship surge = sway = s; in the stern frame x_P = −sway, y_P = surge.
    assert!((get_real(&m, "ship.x") + s).abs() < 1e-15 && (get_real(&m, "ship.y") - s).abs() < 1e-15);
    assert!((get_real(&m, "ship.vy") - 0.006 * 1.0f64.cos()).abs() < 1e-15);
    assert!((get_real(&m, "la1") - 0.1 - s).abs() < 1e-12, "LA1 follows sway in P");
    assert!((get_real(&m, "la2") - 0.1 + s).abs() < 1e-12, "LA2 follows surge in P");
    // A too fast sine sets the flag (and keeps running).
    let mut fast = instantiate::<Platform>();
    set_integer(&mut fast, "profile", 4);
    set_real(&mut fast, "sine_amplitude", 0.01);
    fast.initialize(0.0).unwrap();
    assert!(get_boolean(&fast, "la_limit"), "3.74 rad/s × 10 mm = 37 mm/s");
}

#[test]
fn time_offset_shifts_the_profile() {
    let sample = |offset: f64, t: f64| {
        let mut m = instantiate::<Platform>();
        set_integer(&mut m, "profile", 3);
        set_real(&mut m, "time_offset", offset);
        m.initialize(t).unwrap();
        OUTPUTS.map(|n| get_real(&m, n))
    };
    assert_eq!(sample(-10.0, 25.0), sample(0.0, 15.0));
}

#[test]
fn a_motion_file_relative_to_the_resources_folder_is_interpolated() {
    let dir = std::env::temp_dir().join(format!("platform-fmu-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("deck.csv"),
        "time,surge,sway,heave,roll,pitch,yaw\n0,0,0,0,0,0,0\n1,0.01,-0.01,0.005,0.02,0.01,0\n2,0,0,0,0,0,0\n",
    )
    .unwrap();
    let env = fmu_export::Environment { instance_name: "p".into(), resource_dir: Some(dir.clone()) };
    let mut m = fmu_export::instance::with_start_values::<Platform>(&env).unwrap();
    set_integer(&mut m, "profile", 5);
    set_string(&mut m, "motion_file", "deck.csv");
    m.initialize(1.0).unwrap();
    assert_eq!([get_real(&m, "ship.x"), get_real(&m, "ship.y"), get_real(&m, "ship.z")], [0.01, -0.01, 0.005]);
    assert_eq!([get_real(&m, "ship.roll"), get_real(&m, "ship.pitch")], [0.02, 0.01]);
    m.do_step(1.0, 0.25).unwrap();
    assert!(get_real(&m, "ship.vx").is_finite() && get_real(&m, "ship.ax") != 0.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_or_malformed_motion_file_fails_initialization() {
    let dir = std::env::temp_dir().join(format!("platform-fmu-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.csv"), "time,surge,sway,heave,roll,pitch,yaw\n0,0,0,0,0,0,0\n1,0,0,oops,0,0,0\n")
        .unwrap();
    let attempt = |file: &str| {
        let mut m = instantiate::<Platform>();
        set_integer(&mut m, "profile", 5);
        set_string(&mut m, "motion_file", file);
        m.initialize(0.0).unwrap_err()
    };
    let missing = attempt(dir.join("absent.csv").to_str().unwrap());
    assert!(missing.contains("cannot read motion file") && missing.contains("absent.csv"), "{missing}");
    let malformed = attempt(dir.join("bad.csv").to_str().unwrap());
    assert!(malformed.contains("line 3: heave = \"oops\" is not a finite number"), "{malformed}");
    assert!(attempt("").contains("motion_file is empty"));
    println!("missing: {missing}\nmalformed: {malformed}");
    std::fs::remove_dir_all(Path::new(&dir)).unwrap();
}

#[test]
fn initialization_is_idempotent_and_instances_are_deterministic() {
    let run = || {
        let mut m = started(2, &[]);
        m.initialize(0.0).unwrap();
        record(&mut m, 500)
    };
    assert_eq!(run(), run());
}

/// Every Real output (deck motion and set-points) as bits, with the limit flag, at `steps` + 1
/// communication points from t = 0 (`set` sets the parameters before initialization).
fn run_bits(set: impl Fn(&mut Platform), steps: usize) -> Vec<(Vec<u64>, bool)> {
    let mut m = instantiate::<Platform>();
    set(&mut m);
    m.initialize(0.0).unwrap();
    let row = |m: &Platform| {
        (OUTPUTS.iter().map(|n| get_real(m, n)).chain(la(m)).map(f64::to_bits).collect(), get_boolean(m, "la_limit"))
    };
    let mut rows = vec![row(&m)];
    for k in 0..steps {
        m.do_step(k as f64 * H, H).unwrap();
        rows.push(row(&m));
    }
    rows
}

/// A named way of setting an instance's parameters.
type Case = (&'static str, fn(&mut Platform));

#[test]
fn the_default_motion_window_changes_nothing() {
    let cases: [Case; 4] = [
        ("profile 1", |m| set_integer(m, "profile", 1)),
        ("profile 2, stern, mechanism yaw, time_offset -2.5", |m| {
            set_integer(m, "profile", 2);
            set_integer(m, "crane_location", 1);
            set_boolean(m, "mechanism_yaw", true);
            set_real(m, "time_offset", -2.5);
        }),
        ("sine", |m| set_integer(m, "profile", 4)),
        ("profile 3, simplified, time_offset 7", |m| {
            set_integer(m, "profile", 3);
            set_integer(m, "ik_model", 1);
            set_real(m, "time_offset", 7.0);
        }),
    ];
    for (name, set) in cases {
        let untouched = run_bits(set, 3_000);
        let explicit = run_bits(
            |m| {
                set(m);
                set_real(m, "motion_start", 0.0);
                set_real(m, "fade_in", 0.0);
            },
            3_000,
        );
        assert!(untouched == explicit, "{name}: setting the defaults changed an output");
    }
    // And the deck motion is the source sampled at t + time_offset, bit for bit, as before the
    // window existed (port side, no mechanism yaw: the deck is the requested motion).
    let config = SourceConfig { kind: SourceKind::Sea(ProfileId::One), ..SourceConfig::default() };
    let mut source = MotionSource::build(&config, None, &Hull::default(), &PlatformGeometry::default()).unwrap();
    let mut m = started(1, &[("time_offset", -2.5)]);
    for k in 0..3_000 {
        m.do_step(k as f64 * H, H).unwrap();
        let expected = source.sample(k as f64 * H + H + -2.5).to_ship_motion();
        assert!(m.ship == expected, "t = {}", k as f64 * H + H);
    }
}

/// A communication point: t, the deck outputs, the set-points, the limit flag.
type Row = (f64, [f64; 22], [f64; 5], bool);

/// Profile 1 with `motion_start` 10 s and `fade_in` `fade` (s), 30 s, at every communication
/// point.
fn windowed_run(fade: f64) -> Vec<Row> {
    let mut m = started(1, &[("motion_start", 10.0), ("fade_in", fade)]);
    let mut rows = vec![(0.0, OUTPUTS.map(|n| get_real(&m, n)), la(&m), get_boolean(&m, "la_limit"))];
    for k in 0..3_000 {
        m.do_step(k as f64 * H, H).unwrap();
        rows.push((k as f64 * H + H, OUTPUTS.map(|n| get_real(&m, n)), la(&m), get_boolean(&m, "la_limit")));
    }
    rows
}

/// Central differences of the 10 ms samples of surge, sway, heave against the exact velocities
/// and accelerations, relative to 1 mm/s (mm/s²) + the value: the worst error at the samples
/// `within` selects.
fn worst_derivative_error(rows: &[Row], within: impl Fn(f64) -> bool) -> f64 {
    let index = |name: &str| OUTPUTS.iter().position(|n| *n == name).unwrap();
    let mut worst: f64 = 0.0;
    for k in (1..rows.len() - 1).filter(|&k| within(rows[k].0)) {
        let (prev, row, next) = (&rows[k - 1].1, &rows[k].1, &rows[k + 1].1);
        for (x, v, a) in
            [("ship.x", "ship.vx", "ship.ax"), ("ship.y", "ship.vy", "ship.ay"), ("ship.z", "ship.vz", "ship.az")]
        {
            let fd_v = (next[index(x)] - prev[index(x)]) / (2.0 * H);
            let fd_a = (next[index(v)] - prev[index(v)]) / (2.0 * H);
            worst = worst.max((fd_v - row[index(v)]).abs() / (1e-3 + row[index(v)].abs()));
            worst = worst.max((fd_a - row[index(a)]).abs() / (1e-3 + row[index(a)].abs()));
        }
    }
    worst
}

#[test]
fn the_deck_rests_until_motion_start_and_fades_in_smoothly() {
    let rows = windowed_run(5.0);
    let index = |name: &str| OUTPUTS.iter().position(|n| *n == name).unwrap();
    // At rest through t = 10 s: the neutral pose, every rate zero, the actuators at mid-stroke.
    let resting = rows.iter().filter(|r| r.0 <= 10.0).count();
    assert_eq!(resting, 1001);
    for (t, outputs, la, limit) in &rows[..resting] {
        for (name, value) in OUTPUTS.iter().zip(outputs) {
            assert_eq!(*value, if *name == "ship.q0" { 1.0 } else { 0.0 }, "{name} at t = {t}");
        }
        assert!(la.iter().all(|x| (x - 0.1).abs() < 1e-15) && !limit, "t = {t}: {la:?}");
    }
    // Moving from the first step after 10 s on, every translation and angle but yaw.
    for name in ["ship.x", "ship.y", "ship.z", "ship.roll", "ship.pitch", "ship.vx", "ship.ax", "ship.wx"] {
        assert!(rows[resting].1[index(name)] != 0.0, "{name} at t = {}", rows[resting].0);
    }
    // From t = 15 s on: the unweighted profile with profile time t − 10 s, which is what
    // time_offset = −10 s gives without the window.
    let mut shifted = instantiate::<Platform>();
    set_integer(&mut shifted, "profile", 1);
    set_real(&mut shifted, "time_offset", -10.0);
    shifted.initialize(0.0).unwrap();
    let mut compared = 0;
    for (k, row) in rows.iter().enumerate().skip(1) {
        shifted.do_step((k - 1) as f64 * H, H).unwrap();
        if row.0 >= 15.0 {
            assert_eq!(row.1, OUTPUTS.map(|n| get_real(&shifted, n)), "t = {}", row.0);
            assert_eq!(row.2, la(&shifted));
            compared += 1;
        }
    }
    assert!(compared >= 1500);
    // No jumps: the exact derivatives match central differences of the samples across the fade,
    // strictly inside it and after it as tightly as for the bare profile. On the two samples at
    // its ends the difference straddles the step of the jerk (the weight is C², w''' = 60/T³ at
    // both ends), which costs O(h) there and nothing more.
    let ends = |t: f64| (t - 10.0).abs() < H / 2.0 || (t - 15.0).abs() < H / 2.0;
    let inside = worst_derivative_error(&rows, |t| t > 10.0 && !ends(t));
    let at_ends = worst_derivative_error(&rows, ends);
    // Switching on at once instead: the velocity and acceleration step at 10 s.
    let hard = worst_derivative_error(&windowed_run(0.0), |t| (t - 10.0).abs() < 1.5 * H);
    let first = &rows[resting].1;
    println!(
        "profile 1, motion_start 10 s, fade_in 5 s: outputs exactly at rest through t = 10 s; first step after it \
         |a| = {:.1e} m/s2; derivatives vs central differences worst relative error {inside:.2e} after the start, \
         {at_ends:.2e} on the fade's two end samples, {hard:.1e} around a hard start (fade_in 0); la_limit {}",
        first[index("ship.ax")].hypot(first[index("ship.ay")]).hypot(first[index("ship.az")]),
        if rows.iter().any(|r| r.3) { "set" } else { "never set" }
    );
    assert!(inside < 2e-3);
    assert!(at_ends < 1e-2);
    assert!(hard > 1.0);
    assert!(rows.iter().all(|r| !r.3), "profile 1 faded in over 5 s stays within the actuator limits");
}

#[test]
fn an_invalid_fade_in_fails_initialization() {
    for fade in [-1.0, f64::NAN] {
        let mut m = instantiate::<Platform>();
        set_integer(&mut m, "profile", 1);
        set_real(&mut m, "fade_in", fade);
        assert!(m.initialize(0.0).unwrap_err().contains("fade_in"), "{fade}");
    }
}

#[test]
fn a_resting_deck_is_driven_again_when_the_inverse_model_changes() {
    // Past the end of a motion file the deck holds a tilted pose; the outputs of the exact chain
    // are kept while nothing changes, and switching to the simplified model mid-run gives what an
    // instance started with it gives (a cache that ignored the model would keep the exact values).
    let dir = std::env::temp_dir().join(format!("platform-fmu-held-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("held.csv"), "0,0,0,0,0,0,0\n0.5,0.02,-0.01,0.01,0.05,-0.04,0\n").unwrap();
    let file = dir.join("held.csv");
    let started = |model: i32| {
        let mut m = instantiate::<Platform>();
        set_integer(&mut m, "profile", 5);
        set_string(&mut m, "motion_file", file.to_str().unwrap());
        set_integer(&mut m, "ik_model", model);
        m.initialize(1.0).unwrap();
        m
    };
    let mut m = started(0);
    let exact = la(&m);
    m.do_step(1.0, H).unwrap();
    assert_eq!(la(&m), exact);
    set_integer(&mut m, "ik_model", 1);
    m.do_step(1.0 + H, H).unwrap();
    let simplified = la(&started(1));
    assert!((exact[0] - simplified[0]).abs() > 1e-4, "the models differ in this pose");
    assert_eq!(la(&m).map(f64::to_bits), simplified.map(f64::to_bits));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_saved_state_replays_the_profile_bit_for_bit() {
    // Saved at 1.5 s, the instance runs on across two phasor anchors (2 s, 3 s). The restored
    // copy is first evaluated elsewhere (a later grid point, a time off the grid), as an importer
    // probing or retrying might, and then retraces the outputs the uninterrupted run recorded, bit
    // for bit: the motion depends on the time alone, not on what was evaluated before.
    let bits = |m: &Platform| OUTPUTS.iter().map(|n| get_real(m, n)).chain(la(m)).map(f64::to_bits).collect::<Vec<_>>();
    let mut m = started(1, &[]);
    let mut reference = Vec::new();
    let mut saved = None;
    for k in 0..400 {
        if k == 150 {
            saved = Some(m.clone());
        }
        m.do_step(k as f64 * H, H).unwrap();
        reference.push(bits(&m));
    }
    let mut restored = saved.unwrap();
    restored.update(9.0).unwrap();
    restored.update(1.505).unwrap();
    for (k, expected) in reference.iter().enumerate().skip(150) {
        restored.do_step(k as f64 * H, H).unwrap();
        assert_eq!(&bits(&restored), expected, "step {k}");
    }
}

mod full_scale;

//! The rigging FMU's tests; each names what it would catch. `cargo test --release -p rigging --
//! --show-output` prints the measured figures.

use super::*;
use fmu_export::harness::{get_boolean, get_real, get_xyz, instantiate, round_trip, set_integer, set_real, variable};
use fmu_model::Value;
use physics::pendulum::{self, LoadMotion};
use physics::rigging::chord_rate;

const H: f64 = 0.01;

/// Sets an interpolated input through its row: the value, then its derivative for the coming step
/// (what fmi2SetReal and fmi2SetRealInputDerivatives do).
fn set_input(m: &mut Rigging, name: &str, value: f64, derivative: f64) {
    match variable::<Rigging>(name).value {
        Value::Real { set: Some(set), derivative: Some(d), .. } => {
            set(m, value);
            d(m, Some(derivative));
        }
        _ => panic!("{name} is not an interpolated input"),
    }
}

/// The pendulum FMU's input names, in the order of [`inputs`].
const INPUT_NAMES: [&str; 12] =
    ["tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az", "lp", "lp_dot", "lp_ddot"];

/// A moving tip and a changing hoist length (values and their time derivatives at `t`): the
/// reference files' waves (references/signals.csv) with consistent derivatives.
fn inputs(t: f64) -> [(f64, f64); 12] {
    let wave = |mean: f64, amp: f64, w: f64, phase: f64| {
        let (s, c) = (w * t + phase).sin_cos();
        [(mean + amp * s, amp * w * c), (amp * w * c, -amp * w * w * s), (-amp * w * w * s, -amp * w * w * w * c)]
    };
    let (x, y, z, l) =
        (wave(0.0, 0.02, 2.0, 0.0), wave(-0.5, 0.03, 3.1, 0.0), wave(-0.15, 0.01, 1.3, 1.5), wave(0.7, 0.1, 0.4, 0.0));
    [x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2], l[0], l[1], l[2]]
}

fn drive(m: &mut Rigging, t: f64) {
    for (name, (value, derivative)) in INPUT_NAMES.iter().zip(inputs(t)) {
        set_input(m, name, value, derivative);
    }
}

/// A heave of the tip beyond g (30 mm at 20 rad/s, a peak acceleration of 12 m/s²) that throws
/// hook and load up on an elastic hoist rope: tip.z, tip.vz and tip.az at `t` with their rates.
fn heave(m: &mut Rigging, t: f64) {
    let (a, w) = (0.03, 20.0);
    let (s, c) = (w * t).sin_cos();
    set_input(m, "tip.z", a * s, a * w * c);
    set_input(m, "tip.vz", a * w * c, -a * w * w * s);
    set_input(m, "tip.az", -a * w * w * s, -a * w * w * w * c);
}

fn vector(m: &Rigging, prefix: &str) -> Vec3 {
    Vec3::from(get_xyz(m, prefix))
}

/// The pendulum FMU's step and outputs (fmus/pendulum/src/lib.rs, `Pendulum::do_step` and
/// `update_outputs`), restated on physics::pendulum: the FMU crates are cdylibs that cannot be
/// linked into one test. The FMU itself is compared in tests/test_rigging_fmu.py.
struct PendulumFmu {
    params: PendulumParams,
    initial: Swing,
    release_time: f64,
    input: TipMotion,
    input_rate: TipMotion,
    slopes: VelocitySlopes,
    swing: Swing,
    input_now: TipMotion,
    time: f64,
    load: LoadMotion,
}

impl PendulumFmu {
    fn new(params: PendulumParams, initial: Swing, release_time: f64) -> PendulumFmu {
        PendulumFmu {
            params,
            initial,
            release_time,
            input: INPUT,
            input_rate: TipMotion::default(),
            slopes: VelocitySlopes::default(),
            swing: Swing::default(),
            input_now: TipMotion::default(),
            time: 0.0,
            load: LoadMotion::default(),
        }
    }

    fn set(&mut self, t: f64) {
        let v = inputs(t);
        let (value, rate) = (&mut self.input, &mut self.input_rate);
        for (i, (x, d)) in v.into_iter().enumerate() {
            match i {
                0..=2 => (value.pos[i], rate.pos[i]) = (x, d),
                3..=5 => (value.vel[i - 3], rate.vel[i - 3]) = (x, d),
                6..=8 => (value.acc[i - 6], rate.acc[i - 6]) = (x, d),
                9 => (value.lp, rate.lp) = (x, d),
                10 => (value.lp_dot, rate.lp_dot) = (x, d),
                _ => (value.lp_ddot, rate.lp_ddot) = (x, d),
            }
        }
        self.slopes = VelocitySlopes { tip: [true; 3], lp: true };
    }

    fn held(&self) -> bool {
        self.time < self.release_time
    }

    fn held_swing(&self) -> Swing {
        Swing { omega_x: 0.0, omega_y: 0.0, ..self.initial }
    }

    fn outputs(&mut self) {
        self.load = if self.held() {
            load_kinematics(&self.params, &self.swing, &self.input_now, (0.0, 0.0))
        } else {
            pendulum::load_motion(&self.params, &self.swing, &self.input_now)
        };
        assert!(self.load.tension > 0.0);
    }

    fn initialize(&mut self) {
        self.time = 0.0;
        self.swing = if self.held() { self.held_swing() } else { self.initial };
        self.input_now = self.input;
        self.outputs();
    }

    fn do_step(&mut self, t: f64, h: f64) {
        let end = t + h;
        if end <= self.release_time {
            self.swing = self.held_swing();
        } else {
            let free_from = (self.release_time - t).max(0.0);
            if free_from > 0.0 {
                self.swing = self.initial;
            }
            let (input, rate) = self.input.reconciled(&self.input_rate, &self.slopes, h);
            let start = input.ramp(&rate, free_from);
            self.swing = pendulum::advance(&self.params, &self.swing, &start, &rate, h - free_from).unwrap();
        }
        self.time = end;
        self.input_now = self.input.ramp(&self.input_rate, h);
        self.outputs();
    }

    /// The pendulum FMU's outputs by name (its getters).
    fn output(&self, name: &str) -> f64 {
        let (l, s) = (&self.load, &self.swing);
        let q = &l.orientation;
        match name {
            "theta_x" => s.theta_x,
            "theta_y" => s.theta_y,
            "omega_x" => s.omega_x,
            "omega_y" => s.omega_y,
            "load.x" => l.pos.x,
            "load.y" => l.pos.y,
            "load.z" => l.pos.z,
            "load.vx" => l.vel.x,
            "load.vy" => l.vel.y,
            "load.vz" => l.vel.z,
            "load.ax" => l.acc.x,
            "load.ay" => l.acc.y,
            "load.az" => l.acc.z,
            "load.q0" => q.w,
            "load.q1" => q.i,
            "load.q2" => q.j,
            "load.q3" => q.k,
            "load.wx" => l.angular_velocity.x,
            "load.wy" => l.angular_velocity.y,
            "load.wz" => l.angular_velocity.z,
            "tension" => l.tension,
            "cable.fx" => l.cable_force.x,
            "cable.fy" => l.cable_force.y,
            "cable.fz" => l.cable_force.z,
            "cable.f0x" => l.free_cable_force.x,
            "cable.f0y" => l.free_cable_force.y,
            "cable.f0z" => l.free_cable_force.z,
            "cable.mass" => self.params.mass,
            _ => panic!("the pendulum has no output {name}"),
        }
    }
}

/// Every output the pendulum FMU has.
const SHARED_OUTPUTS: [&str; 28] = [
    "theta_x",
    "theta_y",
    "omega_x",
    "omega_y",
    "load.x",
    "load.y",
    "load.z",
    "load.vx",
    "load.vy",
    "load.vz",
    "load.ax",
    "load.ay",
    "load.az",
    "load.q0",
    "load.q1",
    "load.q2",
    "load.q3",
    "load.wx",
    "load.wy",
    "load.wz",
    "tension",
    "cable.fx",
    "cable.fy",
    "cable.fz",
    "cable.f0x",
    "cable.f0y",
    "cable.f0z",
    "cable.mass",
];

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmu_export::fmi2::xml::render::<Rigging>().unwrap();
    for name in INPUT_NAMES.iter().chain(SHARED_OUTPUTS.iter()) {
        assert!(description.xml.contains(&format!(r#"name="{name}""#)), "{name}");
    }
    for name in ["hoist.law", "sling.law"] {
        fmu_export::harness::assert_codes_are_the_range::<Rigging, RopeLaw>(
            name,
            |code| rope_law(code, ROPE),
            law_code,
        );
    }
}

/// The pendulum's ports with the pendulum's causality and variability (a drop-in replacement):
/// same names, same value references and kinds, so a system file only swaps the FMU.
#[test]
fn the_pendulum_ports_are_all_there() {
    let kinds = |name: &str| {
        let v = variable::<Rigging>(name);
        (v.vr, v.causality, v.variability, v.type_name())
    };
    for (i, name) in INPUT_NAMES.iter().enumerate() {
        let (vr, causality, _, ty) = kinds(name);
        assert_eq!((vr, causality, ty), (100 + i as u32, fmu_model::Causality::Input, "Real"), "{name}");
    }
    for name in SHARED_OUTPUTS {
        let (_, causality, _, ty) = kinds(name);
        assert_eq!((causality, ty), (fmu_model::Causality::Output, "Real"), "{name}");
    }
    for name in ["theta_x0", "theta_y0", "omega_x0", "omega_y0", "mass", "kappa_x", "kappa_y", "g", "release_time"] {
        assert_eq!(kinds(name).1, fmu_model::Causality::Parameter, "{name}");
    }
}

/// Runs the rigging with `setup` applied and the pendulum FMU restated with `params` side by
/// side for `steps` steps of the moving-tip inputs; returns the largest difference of every
/// shared output (0 = equal bits; NaN never).
fn against_pendulum(
    setup: impl Fn(&mut Rigging),
    params: PendulumParams,
    initial: Swing,
    release: f64,
    steps: usize,
) -> f64 {
    let mut m = instantiate::<Rigging>();
    setup(&mut m);
    let mut p = PendulumFmu::new(params, initial, release);
    drive(&mut m, 0.0);
    p.set(0.0);
    m.initialize(0.0).unwrap();
    p.initialize();
    let mut worst = 0.0_f64;
    for k in 0..=steps {
        for name in SHARED_OUTPUTS {
            let (a, b) = (get_real(&m, name), p.output(name));
            assert!(a.is_finite() && b.is_finite(), "{name} step {k}");
            if a.to_bits() != b.to_bits() {
                worst = worst.max((a - b).abs().max(f64::MIN_POSITIVE));
            }
        }
        if k == steps {
            break;
        }
        let t = k as f64 * H;
        drive(&mut m, t);
        p.set(t);
        m.do_step(t, H).unwrap();
        p.do_step(t, H);
    }
    worst
}

/// With no sling, no hook mass and a rigid rope the rigging is the pendulum FMU to the bit: every
/// shared output at every one of 3000 communication points (30 s) with a moving tip, a changing
/// hoist length, an initial swing and a release at 2 s (held phase included). Catches any output
/// that is computed on another path than the pendulum's (order of operations included).
#[test]
fn no_sling_and_a_rigid_rope_is_the_pendulum_to_the_bit() {
    let initial = Swing { theta_x: -0.4, theta_y: 0.15, omega_x: 0.2, omega_y: -0.1 };
    let pendulum_rig = |m: &mut Rigging| {
        set_real(m, "sling.length", 0.0);
        set_real(m, "hook.mass", 0.0);
        set_real(m, "mass", PendulumParams::DEFAULT.mass);
        set_real(m, "theta_x0", initial.theta_x);
        set_real(m, "theta_y0", initial.theta_y);
        set_real(m, "omega_x0", initial.omega_x);
        set_real(m, "omega_y0", initial.omega_y);
        set_real(m, "release_time", 2.0);
    };
    let worst = against_pendulum(pendulum_rig, PendulumParams::DEFAULT, initial, 2.0, 3000);
    println!("sling 0, hook 0, rigid: largest difference of the 28 shared outputs over 3000 steps {worst:e}");
    assert_eq!(worst, 0.0);
    // The default hook and load lumped without a sling: the pendulum with their total mass and
    // the mass-weighted drag (RiggingParams::lumped), also to the bit.
    let lumped_rig = |m: &mut Rigging| {
        set_real(m, "sling.length", 0.0);
        set_real(m, "theta_x0", 0.3);
    };
    let p = RiggingParams { sling_length: 0.0, ..instantiate::<Rigging>().params().unwrap() }.lumped();
    let worst = against_pendulum(lumped_rig, p, Swing { theta_x: 0.3, ..INITIAL }, 0.0, 1000);
    println!("sling 0, default hook 0.1006 kg + load 0.2012 kg vs pendulum of {} kg: {worst:e}", p.mass);
    assert_eq!(worst, 0.0);
    // Control: the check can fail. A different load mass changes the tension outputs.
    let heavier = |m: &mut Rigging| {
        pendulum_rig(m);
        set_real(m, "mass", 0.31);
    };
    assert!(against_pendulum(heavier, PendulumParams::DEFAULT, initial, 2.0, 100) > 0.0);
}

/// A sling of decreasing length converges to the pendulum: the load's position difference after
/// 10 s falls about tenfold per decade of l_s (first order, as physics::rigging's own test).
#[test]
fn a_short_sling_converges_to_the_pendulum() {
    let lumped = PendulumParams { mass: 0.3018, ..PendulumParams::DEFAULT };
    let mut errors = vec![];
    for ls in [0.1, 0.01, 0.001] {
        let mut m = instantiate::<Rigging>();
        set_real(&mut m, "sling.length", ls);
        set_real(&mut m, "hook.mass", 0.1006);
        set_real(&mut m, "mass", 0.2012);
        set_real(&mut m, "hook.kappa", 0.0);
        set_real(&mut m, "kappa_x", 0.0);
        set_real(&mut m, "kappa_y", 0.0);
        set_real(&mut m, "theta_x0", 0.25);
        set_real(&mut m, "lp", 0.7 - ls);
        m.initialize(0.0).unwrap();
        let mut p = PendulumFmu::new(
            PendulumParams { kappa_x: 0.0, kappa_y: 0.0, ..lumped },
            Swing { theta_x: 0.25, ..INITIAL },
            0.0,
        );
        p.input.lp = 0.7 - ls;
        p.initialize();
        let mut worst = 0.0_f64;
        for k in 0..1000 {
            m.do_step(k as f64 * H, H).unwrap();
            p.do_step(k as f64 * H, H);
            // The pendulum's point at the rope's length 0.7 − l_s, the rig's load l_s further out.
            worst = worst.max((vector(&m, "hook.") - p.load.pos).norm());
        }
        errors.push(worst);
    }
    println!("sling 0.1, 0.01, 0.001 m: hook vs pendulum point, max over 10 s {errors:?} m");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((5.0..=20.0).contains(&ratio), "{errors:?}");
    }
}

/// Heave of the tip beyond g throws hook and load up on an elastic hoist rope: the rope goes slack
/// and catches them again, again and again, with no error; the run goes to the end; the slack flag
/// shows both states and the peak snap load exceeds the static weight. Catches a slack rope that
/// ends the run (the pendulum's behaviour) or a flag or peak that is never set.
#[test]
fn an_elastic_rope_under_heave_goes_slack_and_catches_without_an_error() {
    let mut m = instantiate::<Rigging>();
    set_integer(&mut m, "hoist.law", ELASTIC);
    set_real(&mut m, "hoist.damping_time", 1e-3);
    heave(&mut m, 0.0);
    m.initialize(0.0).unwrap();
    let weight = 0.3018 * PendulumParams::DEFAULT.g;
    assert!(!get_boolean(&m, "slack") && get_real(&m, "hoist.peak_snap") == 0.0);
    let (mut slack, mut taut, mut catches, mut was_slack) = (0, 0, 0, false);
    let mut peak_tension = 0.0_f64;
    for k in 0..2000 {
        let t = k as f64 * H;
        heave(&mut m, t);
        m.do_step(t, H).unwrap();
        let now = get_boolean(&m, "hoist.slack");
        assert_eq!(get_boolean(&m, "slack"), now || get_boolean(&m, "sling.slack"));
        if now {
            slack += 1;
            assert_eq!(get_real(&m, "tension"), 0.0);
        } else {
            taut += 1;
        }
        catches += (was_slack && !now) as usize;
        was_slack = now;
        peak_tension = peak_tension.max(get_real(&m, "tension"));
    }
    let peak = get_real(&m, "hoist.peak_snap");
    println!(
        "heave 30 mm at 20 rad/s on EA = 1000 N: slack at {slack} of 2000 points, {catches} catches, peak snap \
         {peak:.3} N (sampled at the substeps) vs {peak_tension:.3} N at the points, static weight {weight:.3} N"
    );
    assert!(slack > 0 && taut > 0 && catches > 1);
    assert!(peak > 2.0 * weight && peak >= peak_tension, "{peak}");
    assert_eq!(get_real(&m, "cable.mass"), 0.0);
}

/// A state taken at any point (clone = fmi2GetFMUstate, the serialized image = another instance
/// after fmi2DeSerializeFMUstate) continues to the bit, also through slack phases (the snap record
/// is part of the state). Catches a field left out of the state or of its serialization.
#[test]
fn state_get_set_and_serialize_continue_to_the_bit() {
    let mut m = instantiate::<Rigging>();
    set_integer(&mut m, "hoist.law", ELASTIC);
    set_integer(&mut m, "sling.law", ELASTIC);
    set_real(&mut m, "sling.dtheta_x0", 0.3);
    set_real(&mut m, "release_time", 0.5);
    let drive_and_heave = |m: &mut Rigging, t: f64| {
        drive(m, t);
        heave(m, t);
    };
    drive_and_heave(&mut m, 0.0);
    m.initialize(0.0).unwrap();
    let names: Vec<&str> =
        VARIABLES.iter().filter(|v| v.causality == fmu_model::Causality::Output).map(|v| v.name).collect();
    let snapshot = |m: &Rigging| -> Vec<u64> {
        names
            .iter()
            .map(|n| match variable::<Rigging>(n).value {
                Value::Boolean { get, .. } => get(m) as u64,
                _ => get_real(m, n).to_bits(),
            })
            .collect()
    };
    let mut copies: Vec<(usize, Rigging)> = vec![];
    let mut trace = vec![];
    for k in 0..300 {
        if k == 40 || k == 150 {
            copies.push((k, m.clone()));
            copies.push((k, round_trip(&m)));
        }
        let t = k as f64 * H;
        drive_and_heave(&mut m, t);
        m.do_step(t, H).unwrap();
        trace.push(snapshot(&m));
    }
    assert!(get_real(&m, "hoist.peak_snap") > 0.0, "the run has a slack phase");
    for (from, mut copy) in copies {
        for (k, expected) in trace.iter().enumerate().skip(from) {
            let t = k as f64 * H;
            drive_and_heave(&mut copy, t);
            copy.do_step(t, H).unwrap();
            assert_eq!(&snapshot(&copy), expected, "from {from}, step {k}");
        }
    }
}

/// NaN or infinite inputs and bad parameters are errors from initialize or the step, never a
/// panic or NaN outputs. Catches a missing check (physics::rigging would integrate NaN).
#[test]
fn nan_inputs_and_bad_parameters_are_errors() {
    for name in INPUT_NAMES {
        for bad in [f64::NAN, f64::INFINITY] {
            let mut m = instantiate::<Rigging>();
            m.initialize(0.0).unwrap();
            m.do_step(0.0, H).unwrap();
            set_real(&mut m, name, bad);
            let message = m.do_step(H, H).unwrap_err();
            assert!(message.contains("not finite"), "{name}: {message}");
            assert!(m.initialize(0.0).is_err(), "{name}");
        }
    }
    type Setup = fn(&mut Rigging);
    let cases: [(&str, Setup); 8] = [
        ("hook mass 0 with a sling", |m| set_real(m, "hook.mass", 0.0)),
        ("an elastic sling of length 0", |m| {
            set_real(m, "sling.length", 0.0);
            set_integer(m, "sling.law", ELASTIC)
        }),
        ("rope law 2", |m| set_integer(m, "hoist.law", 2)),
        ("negative sling", |m| set_real(m, "sling.length", -0.1)),
        ("NaN load mass", |m| set_real(m, "mass", f64::NAN)),
        ("EA 0", |m| {
            set_integer(m, "hoist.law", ELASTIC);
            set_real(m, "hoist.ea", 0.0)
        }),
        ("negative damping", |m| {
            set_integer(m, "sling.law", ELASTIC);
            set_real(m, "sling.damping_time", -1.0)
        }),
        ("lp 0", |m| set_real(m, "lp", 0.0)),
    ];
    for (what, setup) in cases {
        let mut m = instantiate::<Rigging>();
        setup(&mut m);
        let message = m.initialize(0.0).unwrap_err();
        println!("{what}: {message}");
        assert!(m.do_step(0.0, H).is_err(), "{what}");
    }
    // A rigid rope that would have to push is an error, as the pendulum's slack cable.
    let mut m = instantiate::<Rigging>();
    m.initialize(0.0).unwrap();
    set_real(&mut m, "tip.az", 20.0);
    let message = m.do_step(0.0, H).unwrap_err();
    assert!(message.contains("rigid hoist rope goes slack at t = 0.01 s"), "{message}");
    // A start rate whose square overflows is named as too large, not as a slack rope.
    let mut m = instantiate::<Rigging>();
    set_real(&mut m, "release_time", 0.0);
    set_real(&mut m, "omega_x0", 1e300);
    let message = m.initialize(0.0).and_then(|()| m.do_step(0.0, H)).unwrap_err();
    assert!(message.contains("the swing state is too large to compute with"), "{message}");
    assert!(message.contains("omega_x: 1e300") && !message.contains("slack"), "{message}");
}

/// The crane's force coupling: cable.f0 is F₀ of the exactly affine tip force and cable.mass the
/// mass along it. Hanging straight at rest: F₀ = the whole weight, m = hook + load. Swinging (rigid
/// rope, rigid sling out of line): the crane's form A = −m e eᵀ, b = −m e is exact (README: the
/// tensions depend on the tip acceleration only through e·a_t). Catches a wrong sign or projection
/// of cable.mass, or a rig whose coupling is not of the crane's form.
#[test]
fn the_crane_coupling_outputs() {
    let mut m = instantiate::<Rigging>();
    m.initialize(0.0).unwrap();
    let f0 = |m: &Rigging| vector(m, "cable.f0");
    let weight = 0.3018 * PendulumParams::DEFAULT.g;
    assert!((f0(&m) - Vec3::new(0.0, 0.0, weight)).norm() <= 1e-12 * weight, "{}", f0(&m));
    assert!((get_real(&m, "cable.mass") - 0.3018).abs() <= 1e-12, "{}", get_real(&m, "cable.mass"));
    let mut m = instantiate::<Rigging>();
    set_real(&mut m, "theta_x0", 0.3);
    set_real(&mut m, "sling.dtheta_x0", -0.4);
    set_real(&mut m, "sling.dtheta_y0", 0.2);
    m.initialize(0.0).unwrap();
    let (mut worst_along, mut worst_across) = (0.0_f64, 0.0_f64);
    for k in 0..200 {
        m.do_step(k as f64 * H, H).unwrap();
        let p = m.params().unwrap();
        let c = tip_coupling(&p, &m.state, &m.input_now).unwrap();
        let e = c.free_force.normalize();
        let mass = get_real(&m, "cable.mass");
        assert!(mass > 0.0);
        assert_eq!(c.free_force, f0(&m));
        // The crane's model of the same sensitivities: A = −m e eᵀ, b = −m e.
        let along = (c.per_tip_acc * e + e * mass).norm().max((c.per_lp_acc + e * mass).norm()) / mass;
        let across = (c.per_tip_acc + e * e.transpose() * mass).norm() / mass;
        worst_along = worst_along.max(along);
        worst_across = worst_across.max(across);
    }
    println!(
        "double pendulum swinging: the crane's form matches b and A e to {worst_along:.1e}, the whole \
         of A to {worst_across:.1e} relative"
    );
    assert!(worst_along <= 1e-9 && worst_across <= 1e-9, "{worst_along} {worst_across}");
}

/// The outputs hang together: load = hook + sling chord of the sling's length, the angles
/// describe the chords, the orientations are unit quaternions. Catches swapped getters.
#[test]
fn outputs_are_consistent() {
    for (hoist, sling) in [(RIGID, RIGID), (ELASTIC, RIGID), (RIGID, ELASTIC), (ELASTIC, ELASTIC)] {
        let mut m = instantiate::<Rigging>();
        set_integer(&mut m, "hoist.law", hoist);
        set_integer(&mut m, "sling.law", sling);
        set_real(&mut m, "theta_x0", 0.2);
        set_real(&mut m, "sling.dtheta_y0", 0.3);
        m.initialize(0.0).unwrap();
        for k in 0..300 {
            let t = k as f64 * H;
            drive(&mut m, t);
            m.do_step(t, H).unwrap();
            let v = |prefix: &str| vector(&m, prefix);
            let e = |tx: f64, ty: f64| Vec3::new(ty.sin(), -ty.cos() * tx.sin(), ty.cos() * tx.cos());
            let (tip, hook, load) = (m.input_now.pos, v("hook."), v("load."));
            let chord = get_real(&m, "hoist.chord");
            let e1 = e(get_real(&m, "theta_x"), get_real(&m, "theta_y"));
            assert!((hook - tip - e1 * chord).norm() <= 1e-12, "{hoist}{sling} step {k}");
            let e2 = e(get_real(&m, "sling.theta_x"), get_real(&m, "sling.theta_y"));
            let r2 = (load - hook).norm();
            assert!((load - hook - e2 * r2).norm() <= 1e-12, "{hoist}{sling} step {k}");
            assert!((r2 / 0.2 - 1.0).abs() <= 0.05, "{r2}");
            // The angle rates are the chords' rates (finite differences would be coarser).
            let (vh, vl) = (v("hook.v"), v("load.v"));
            let s2 = Swing {
                theta_x: get_real(&m, "sling.theta_x"),
                theta_y: get_real(&m, "sling.theta_y"),
                omega_x: get_real(&m, "sling.omega_x"),
                omega_y: get_real(&m, "sling.omega_y"),
            };
            let across = (vl - vh) - e2 * e2.dot(&(vl - vh));
            assert!((chord_rate(r2, &s2) - across).norm() <= 1e-9, "{hoist}{sling} step {k}");
            for q in ["load.q", "hook.q"] {
                let n: f64 = (0..4).map(|i| get_real(&m, &format!("{q}{i}")).powi(2)).sum();
                assert!((n - 1.0).abs() <= 1e-12);
            }
        }
    }
}

/// The full-scale rigging (5 t on a 300 kg hook and a 3 m sling) released from rest 0.5 rad out on
/// 10 m of elastic steel rope starts with the tension of its start state, (m_h + m_l) g cos θ =
/// 45.6 kN, and swings with both ropes taut. Started stretched by the hanging weight instead, it
/// began at 52.0 kN (14 % over) and oscillated axially about the tension it should have had; at
/// larger angles (1/cos θ − 1 > 1) or with a sling out of line that excess throws the hook up and
/// slackens the ropes.
#[test]
fn an_elastic_rigging_released_at_an_angle_swings_without_slack() {
    let mut m = instantiate::<Rigging>();
    for (name, value) in [
        ("mass", 5000.0),
        ("hook.mass", 300.0),
        ("sling.length", 3.0),
        ("hoist.ea", 4e7),
        ("lp", 10.0),
        ("theta_x0", 0.5),
        ("release_time", 0.0),
    ] {
        set_real(&mut m, name, value);
    }
    set_integer(&mut m, "hoist.law", ELASTIC);
    m.initialize(0.0).unwrap();
    let start_tension = get_real(&m, "tension");
    for k in 0..500 {
        m.do_step(k as f64 * H, H).unwrap();
        assert!(!get_boolean(&m, "slack"), "slack at t = {} s", (k + 1) as f64 * H);
    }
    let (hoist, sling) = (get_real(&m, "hoist.peak_snap"), get_real(&m, "sling.peak_snap"));
    assert_eq!((hoist, sling), (0.0, 0.0), "snap loads recorded");
    let released = 5300.0 * PendulumParams::DEFAULT.g * 0.5_f64.cos();
    assert!((start_tension - released).abs() < 1e-6 * released, "{start_tension} N against {released} N");
}

#[test]
fn a_held_elastic_rigging_couples_to_the_crane_as_the_held_rigid_one() {
    // Before release hook and load ride with the tip; under a tip accelerating at 3 m/s² the
    // elastic rigging must give the crane the held bodies' inertia as cable.mass and the force of
    // an unaccelerated tip, as the rigid one does. Fed the acceleration through cable.f0 instead
    // (cable.mass 0), a 5.3 t load under the full-scale crane diverged within 0.2 s.
    let held = |law: i32| {
        let mut m = instantiate::<Rigging>();
        for (name, value) in
            [("mass", 5000.0), ("hook.mass", 300.0), ("sling.length", 3.0), ("hoist.ea", 4.4e7), ("lp", 10.0)]
        {
            set_real(&mut m, name, value);
        }
        set_real(&mut m, "release_time", 10.0);
        set_integer(&mut m, "hoist.law", law);
        set_input(&mut m, "tip.az", 3.0, 0.0);
        m.initialize(0.0).unwrap();
        m.do_step(0.0, H).unwrap();
        (vector(&m, "cable.f0"), get_real(&m, "cable.mass"))
    };
    let (rigid, elastic) = (held(0), held(ELASTIC));
    println!(
        "held under a 3 m/s² tip: cable.f0 {} / {} N, cable.mass {} / {} kg (rigid / elastic)",
        rigid.0.z, elastic.0.z, rigid.1, elastic.1
    );
    assert_eq!(rigid, elastic);
    assert!((rigid.1 - 5300.0).abs() < 1e-9 && (rigid.0.z - 5300.0 * PendulumParams::DEFAULT.g).abs() < 1e-6);
}

use super::dynamics::evaluate;
use super::*;
use crate::math::Vec3;
use crate::pendulum::tests::moving_tip;
use crate::pendulum::{PendulumParams, Swing};

const DEG: f64 = std::f64::consts::PI / 180.0;
const G: f64 = crate::math::STANDARD_GRAVITY;

fn fixed_tip(lp: f64) -> TipMotion {
    TipMotion { lp, ..TipMotion::default() }
}

/// Hook `m_h` and load `m_l` (kg), no drag, the given ropes.
fn rig(m_h: f64, m_l: f64, ls: f64, hoist: RopeLaw, sling: RopeLaw) -> RiggingParams {
    RiggingParams {
        load: PendulumParams { mass: m_l, kappa_x: 0.0, kappa_y: 0.0, g: G },
        hook_mass: m_h,
        hook_drag: 0.0,
        sling_length: ls,
        hoist,
        sling,
    }
}

fn elastic(ea: f64) -> RopeLaw {
    RopeLaw::Elastic(ElasticRope { ea, damping_time: 0.0 })
}

/// Simulates `seconds` in communication steps of `h` with the tip fixed; returns (t, state).
fn free_run(p: &RiggingParams, s0: RiggingState, lp: f64, seconds: f64, h: f64) -> Vec<(f64, RiggingState)> {
    let (u, zero) = (fixed_tip(lp), TipMotion::default());
    let n = (seconds / h).round() as usize;
    let mut s = s0;
    let mut out = Vec::with_capacity(n + 1);
    out.push((0.0, s));
    for k in 0..n {
        s = advance(p, &s, &u, &zero, h).unwrap();
        out.push(((k + 1) as f64 * h, s));
    }
    out
}

/// Angular frequency (rad/s) from the upward zero crossings of `samples` (linear interpolation
/// between samples), over as many whole periods as the record holds.
fn crossing_frequency(samples: &[(f64, f64)]) -> f64 {
    let crossings: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect();
    assert!(crossings.len() >= 3, "too few crossings: {}", crossings.len());
    let periods = (crossings.len() - 1) as f64;
    2.0 * std::f64::consts::PI * periods / (crossings[crossings.len() - 1] - crossings[0])
}

/// The two small-angle normal modes of the rigid double pendulum, simulated from a pure-mode
/// initial condition (planar, 10⁻³ rad) and timed by zero crossings, against the closed form of
/// `normal_modes` over mass ratios m_l/m_h = 0.1–10 and sling/hoist ratios 0.1–1. Fails on a wrong
/// mass matrix or coupling term (the frequencies move by far more than 0.5 %).
#[test]
fn small_angle_normal_modes_match_the_closed_form_eigenproblem() {
    let lp = 1.0;
    let m_h = 1.0;
    let mut worst: f64 = 0.0;
    for ratio in [0.1, 1.0, 10.0] {
        for ls_ratio in [0.1, 0.5, 1.0] {
            let (m_l, ls) = (ratio * m_h, ls_ratio * lp);
            let p = rig(m_h, m_l, ls, RopeLaw::Rigid, RopeLaw::Rigid);
            let (w1, w2) = normal_modes(m_h, m_l, lp, ls, G);
            let mut measured = [0.0; 2];
            for (slot, omega) in [w1, w2].into_iter().enumerate() {
                let shape = mode_shape(m_h, m_l, lp, ls, G, omega);
                let amplitude = 1e-3 / shape.abs().max(1.0);
                let s0 = RiggingState {
                    hoist: Vec3::new(amplitude, 0.0, 0.0),
                    sling: Vec3::new(amplitude * shape, 0.0, 0.0),
                    ..RiggingState::default()
                };
                let seconds = 12.0 * 2.0 * std::f64::consts::PI / omega;
                let trace = free_run(&p, s0, lp, seconds, 1e-3);
                // The sling angle crosses zero in both modes (the hoist angle too); time it.
                let signal: Vec<(f64, f64)> = trace.iter().map(|(t, s)| (*t, s.sling.x)).collect();
                measured[slot] = crossing_frequency(&signal);
            }
            let errors = [measured[0] / w1 - 1.0, measured[1] / w2 - 1.0];
            println!(
                "normal modes m_l/m_h = {ratio:>4}, l_s/l_p = {ls_ratio:>3}: ω₁ {:.5} vs {w1:.5} rad/s ({:+.1e}), \
                 ω₂ {:.5} vs {w2:.5} rad/s ({:+.1e})",
                measured[0], errors[0], measured[1], errors[1]
            );
            worst = worst.max(errors[0].abs()).max(errors[1].abs());
        }
    }
    println!("normal modes: worst relative error {worst:.2e} (limit 5e-3)");
    assert!(worst < 5e-3, "worst relative frequency error {worst}");
}

/// Relative energy drift over 60 s of a free, undamped run from `s0` (10 ms steps), the smallest
/// rope and sling tensions on the way (N) and the final snap record.
fn energy_drift(p: &RiggingParams, s0: RiggingState, lp: f64) -> (f64, f64, f64, SnapRecord) {
    let u = fixed_tip(lp);
    let trace = free_run(p, s0, lp, 60.0, 0.01);
    let e0 = energy(p, &trace[0].1, &u).unwrap();
    let (mut drift, mut t1, mut t2): (f64, f64, f64) = (0.0, f64::INFINITY, f64::INFINITY);
    for (_, s) in &trace {
        drift = drift.max((energy(p, s, &u).unwrap() - e0).abs() / e0.abs());
        let m = rigging_motion(p, s, &u).unwrap();
        (t1, t2) = (t1.min(m.hoist_tension), t2.min(m.sling_tension));
    }
    (drift, t1, t2, trace[trace.len() - 1].1.snap)
}

/// A chord of length `r` at the X–Y angles (θx, θy).
fn chord(theta_x: f64, theta_y: f64, r: f64) -> Vec3 {
    Vec3::new(theta_y.sin(), -theta_y.cos() * theta_x.sin(), theta_y.cos() * theta_x.cos()) * r
}

/// Without drag and rope damping, with the tip fixed, mechanical plus strain energy stays constant
/// to 1e-8 relative over 60 s, for rigid and elastic ropes (taut throughout: asserted). Fails on a
/// non-conservative term (a missing bias acceleration, a mass matrix not symmetric with the
/// coupling, a tension law that is not the strain energy's gradient). A run through slack phases
/// is printed too: each catch is a kink in the force, where RK4 is no longer fourth order.
#[test]
fn energy_is_conserved_without_damping_for_a_fixed_tip() {
    let (lp, ls, m_h, m_l) = (1.0, 0.5, 1.0, 2.0);
    // Hoist bounce √(675/3) = 15 rad/s, sling's relative bounce √(150·1.5) = 15 rad/s.
    let (ea_hoist, ea_sling) = (675.0, 75.0);
    let (hoist_angles, sling_angles) = ((10.0 * DEG, -8.0 * DEG), (5.0 * DEG, 12.0 * DEG));
    let rigid = RiggingState {
        hoist: Vec3::new(hoist_angles.0, hoist_angles.1, 0.0),
        sling: Vec3::new(sling_angles.0, sling_angles.1, 0.0),
        ..RiggingState::default()
    };
    let (hoist_chord, sling_chord) =
        (chord(hoist_angles.0, hoist_angles.1, 1.05), chord(sling_angles.0, sling_angles.1, 0.55));
    let cases = [
        ("rigid rope, rigid sling", rig(m_h, m_l, ls, RopeLaw::Rigid, RopeLaw::Rigid), rigid),
        (
            "elastic rope, rigid sling",
            rig(m_h, m_l, ls, elastic(ea_hoist), RopeLaw::Rigid),
            RiggingState { hoist: hoist_chord, ..rigid },
        ),
        (
            "rigid rope, elastic sling",
            rig(m_h, m_l, ls, RopeLaw::Rigid, elastic(ea_sling)),
            RiggingState { sling: sling_chord, ..rigid },
        ),
        (
            "elastic rope, elastic sling",
            rig(m_h, m_l, ls, elastic(ea_hoist), elastic(ea_sling)),
            RiggingState { hoist: hoist_chord, sling: sling_chord, ..rigid },
        ),
        (
            "elastic rope, no sling",
            rig(m_h, m_l, 0.0, elastic(ea_hoist), RopeLaw::Rigid),
            RiggingState { hoist: hoist_chord, ..RiggingState::default() },
        ),
    ];
    for (name, p, s0) in cases {
        p.validate().unwrap();
        let (drift, t1, t2, _) = energy_drift(&p, s0, lp);
        println!(
            "energy drift over 60 s, {name}: {drift:.2e} relative (limit 1e-8); min tensions {t1:.2} N, {t2:.2} N"
        );
        assert!(t1 > 0.0 && t2 > 0.0, "{name}: a rope went slack");
        assert!(drift <= 1e-8, "{name}: relative energy drift {drift}");
    }
    // Through slack phases (20°/−15° rope, −10°/25° sling): information, not a limit.
    let p = rig(m_h, m_l, ls, elastic(ea_hoist), elastic(ea_sling));
    let s0 = RiggingState {
        hoist: chord(20.0 * DEG, -15.0 * DEG, 1.05),
        sling: chord(-10.0 * DEG, 25.0 * DEG, 0.6),
        ..rigid
    };
    let (drift, _, _, snap) = energy_drift(&p, s0, lp);
    println!(
        "energy drift over 60 s through slack phases (both elastic): {drift:.2e} relative; peak snap loads {:.1} N \
         (rope), {:.1} N (sling)",
        snap.hoist_peak, snap.sling_peak
    );
}

/// The vertical bounce of hook and load on an elastic hoist rope has ω = √(EA/(l·m)) with m the
/// whole mass the rope carries (hook + load on a rigid sling), at test scale and at full scale (a
/// 40 mm steel wire rope, 5 t on 20 m, which also needs the substeps shortened), and on a soft
/// cord stretched 10 % by its load. Fails on the wrong mass (the hook alone) or on the wrong spring
/// rate (EA/r instead of EA/l₀ moves the soft cord's frequency by 9 %).
#[test]
fn elastic_rope_bounce_frequency_is_the_spring_mass_frequency() {
    let cases = [
        ("test scale, 0.1 + 0.2 kg on 0.7 m, rigid sling 0.2 m", 0.1, 0.2, 0.2, 0.7, 300.0),
        ("test scale, 0.3 kg on 0.7 m, no sling", 0.1, 0.2, 0.0, 0.7, 300.0),
        ("soft cord, 0.1 + 0.2 kg on 0.7 m, 10 % static stretch", 0.1, 0.2, 0.2, 0.7, 30.0),
        ("full scale, 0.3 + 5 t on 20 m, rigid sling 3 m", 300.0, 5000.0, 3.0, 20.0, ElasticRope::steel_wire(0.04).ea),
    ];
    for (name, m_h, m_l, ls, lp, ea) in cases {
        let p = rig(m_h, m_l, ls, elastic(ea), RopeLaw::Rigid);
        let u = fixed_tip(lp);
        let mut s0 = RiggingState::hanging(&p, &u);
        let z_eq = s0.hoist.z;
        s0.hoist.z += 1e-3;
        let expected = (ea / (lp * (m_h + m_l))).sqrt();
        let seconds = 10.0 * 2.0 * std::f64::consts::PI / expected;
        let trace = free_run(&p, s0, lp, seconds, 1e-3);
        let signal: Vec<(f64, f64)> = trace.iter().map(|(t, s)| (*t, s.hoist.z - z_eq)).collect();
        let measured = crossing_frequency(&signal);
        let error = measured / expected - 1.0;
        println!("bounce, {name}: {measured:.4} vs √(EA/(l m)) = {expected:.4} rad/s ({error:+.1e}; limit 1e-2)");
        assert!(error.abs() < 1e-2, "{name}: {measured} vs {expected}");
    }
}

/// A full-scale lump (1 t on 10 m, k = 10⁵ N/m) thrown up from its rest: the rope goes slack, the
/// lump flies free, and the rope catches it again. Returns the 1 ms samples (t, state).
fn thrown(p: &RiggingParams, lp: f64, v0: Vec3, seconds: f64) -> Vec<(f64, RiggingState)> {
    let mut s0 = RiggingState::hanging(p, &fixed_tip(lp));
    s0.hoist_rate = v0;
    free_run(p, s0, lp, seconds, 1e-3)
}

/// While the hoist rope is slack the lump follows the ballistic parabola x₀ + v₀ t + ½ g ẑ t² to
/// 1e-9 m (RK4 integrates a quadratic exactly), and the peak rope tension after the re-catch
/// matches the energy balance of the catch (`snap_load_estimate`) within 5 %, undamped and with
/// rope damping (ζ = 2 %). Fails if a slack rope still pushes or pulls, if the free flight is
/// not free, or if the catch is too soft or too hard.
#[test]
fn slack_flight_is_ballistic_and_the_snap_load_matches_the_energy_balance() {
    let (m, lp) = (1000.0, 10.0);
    let k: f64 = 1e5;
    let omega = (k / m).sqrt();
    let cases = [
        ("vertical, undamped", Vec3::new(0.0, 0.0, -2.0), 0.0, 1e-3),
        ("oblique, undamped", Vec3::new(0.3, -0.2, -2.0), 0.0, 1e-2),
        ("vertical, ζ = 2 %", Vec3::new(0.0, 0.0, -2.0), 2.0 * 0.02 / omega, 5e-2),
    ];
    for (name, v0, beta, limit) in cases {
        let rope = ElasticRope { ea: k * lp, damping_time: beta };
        let p = rig(0.0, m, 0.0, RopeLaw::Elastic(rope), RopeLaw::Rigid);
        let u = fixed_tip(lp);
        let trace = thrown(&p, lp, v0, 1.5);
        let slack: Vec<bool> = trace.iter().map(|(_, s)| rigging_motion(&p, s, &u).unwrap().hoist_slack).collect();
        let first = slack.iter().position(|s| *s).unwrap();
        let last = first + slack[first..].iter().position(|s| !*s).unwrap() - 1;
        // Free flight from the first slack sample: every later slack sample on the parabola.
        let (t0, s0) = trace[first];
        let mut worst: f64 = 0.0;
        for (t, s) in &trace[first..=last] {
            let tau = t - t0;
            let ballistic = s0.hoist + s0.hoist_rate * tau + Vec3::new(0.0, 0.0, 0.5 * G * tau * tau);
            worst = worst.max((s.hoist - ballistic).norm());
        }
        // The catch: where the parabola reaches the rope length (Newton on |x(τ)| = l_p).
        let at = |tau: f64| s0.hoist + s0.hoist_rate * tau + Vec3::new(0.0, 0.0, 0.5 * G * tau * tau);
        let vel = |tau: f64| s0.hoist_rate + Vec3::new(0.0, 0.0, G * tau);
        let mut tau = trace[last].0 - t0;
        for _ in 0..20 {
            tau -= (at(tau).norm() - lp) / (at(tau).normalize().dot(&vel(tau)));
        }
        let v_catch = at(tau).normalize().dot(&vel(tau));
        let peak = trace.last().unwrap().1.snap.hoist_peak;
        let estimate = snap_load_estimate(m, v_catch, k, G);
        let error = peak / estimate - 1.0;
        let flight = trace[last].0 - t0;
        println!(
            "slack, {name}: free flight {flight:.3} s off the parabola by ≤ {worst:.1e} m; catch at {v_catch:.4} m/s; \
             peak snap {peak:.1} N vs energy balance {estimate:.1} N ({error:+.2e}; limit {limit:.0e})"
        );
        assert!(flight > 0.2, "{name}: the rope was slack for {flight} s only");
        assert!(worst < 1e-9, "{name}: free flight off the ballistic trajectory by {worst} m");
        assert!(error.abs() < limit, "{name}: peak {peak} N vs estimate {estimate} N");
        assert!(trace[first..=last].iter().all(|(_, s)| s.snap.hoist_peak == 0.0), "no snap before the catch");
    }
    // For the vertical undamped throw the catch speed has a closed form too: the taut phase is a
    // harmonic oscillator about the static stretch g/ω², so v² = v₀² − (g/ω)².
    let v_closed = (4.0 - (G / omega).powi(2)).sqrt();
    println!(
        "vertical throw: closed-form catch speed {v_closed:.4} m/s, snap {:.1} N",
        snap_load_estimate(m, v_closed, k, G)
    );
}

/// As l_s → 0 (rigid rope and sling, the sling starting along the rope), hook and load converge to
/// the single pendulum of `pendulum.rs` with the lumped mass, the error shrinking in proportion
/// to l_s. Fails on a double pendulum that does not reduce to the thesis' pendulum.
#[test]
fn a_vanishing_sling_converges_to_the_single_pendulum() {
    let (m_h, m_l, lp) = (0.1, 0.2018, 0.7);
    let seconds = 10.0;
    let (theta_x, theta_y) = (15.0 * DEG, -10.0 * DEG);
    let single_params = rig(m_h, m_l, 0.0, RopeLaw::Rigid, RopeLaw::Rigid);
    let swing = Swing { theta_x, theta_y, ..Swing::default() };
    let single = free_run(&single_params, RiggingState::from_swing(&swing), lp, seconds, 0.01);
    let u = fixed_tip(lp);
    let mut errors = Vec::new();
    for ls in [0.1, 0.01, 0.001] {
        let p = rig(m_h, m_l, ls, RopeLaw::Rigid, RopeLaw::Rigid);
        let s0 = RiggingState {
            hoist: Vec3::new(theta_x, theta_y, 0.0),
            sling: Vec3::new(theta_x, theta_y, 0.0),
            ..RiggingState::default()
        };
        let double = free_run(&p, s0, lp, seconds, 0.01);
        let (mut hook, mut load, mut tension): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for ((_, a), (_, b)) in single.iter().zip(&double) {
            let (ma, mb) = (rigging_motion(&single_params, a, &u).unwrap(), rigging_motion(&p, b, &u).unwrap());
            hook = hook.max((ma.load.pos - mb.hook.pos).norm());
            load = load.max((ma.load.pos - mb.load.pos).norm());
            tension = tension.max((ma.hoist_tension - mb.hoist_tension).abs());
        }
        println!(
            "l_s = {ls:>5} m: max |hook − single| {hook:.3e} m, max |load − single| {load:.3e} m, \
             max |T − T_single| {tension:.3e} N over {seconds} s"
        );
        errors.push((hook, load, tension));
    }
    for pair in errors.windows(2) {
        let ratio = pair[0].1 / pair[1].1;
        println!("load error ratio per decade of l_s: {ratio:.2}");
        assert!((5.0..20.0).contains(&ratio), "not first-order convergence: ratio {ratio}");
    }
    assert!(errors[2].1 < 1e-2 && errors[2].2 < 1e-2, "l_s = 1 mm still far: {:?}", errors[2]);
}

/// The secant rates of the inputs over [t, t + h] (what an importer hands a step).
fn secant(t: f64, h: f64) -> TipMotion {
    moving_tip(t).secant(&moving_tip(t + h), h)
}

/// The default (no sling, rigid rope) is the thesis' pendulum to the bit, states and outputs,
/// with a moving tip and a changing hoist length.
#[test]
fn the_default_is_the_single_pendulum_to_the_bit() {
    let (p, q) = (RiggingParams::default(), PendulumParams::default());
    assert_eq!(p.lumped(), q);
    let h = 0.01;
    let mut swing = Swing { theta_x: 0.2, theta_y: -0.1, omega_x: 0.3, omega_y: 0.1 };
    let mut state = RiggingState::from_swing(&swing);
    for k in 0..2000 {
        let t = k as f64 * h;
        let (u, rate) = (moving_tip(t), secant(t, h));
        swing = crate::pendulum::advance(&q, &swing, &u, &rate, h).unwrap();
        state = advance(&p, &state, &u, &rate, h).unwrap();
        assert_eq!(state.swing(), swing, "step {k}");
        let (a, b) = (crate::pendulum::load_motion(&q, &swing, &u), rigging_motion(&p, &state, &u).unwrap());
        assert_eq!(
            (a.pos, a.vel, a.acc, a.tension, a.cable_force),
            (b.load.pos, b.load.vel, b.load.acc, b.hoist_tension, b.tip_force)
        );
    }
    println!("default rigging = pendulum.rs bit for bit over 2000 steps of 10 ms");
}

/// The general equations, given no sling and a rigid rope (which `advance` hands to the pendulum
/// instead), reproduce the pendulum's angular accelerations and tension within round-off, with
/// hook mass and drag lumped: the two formulations agree, measured here.
#[test]
fn the_general_equations_reduce_to_the_pendulum_within_round_off() {
    let p = RiggingParams { hook_mass: 0.12, hook_drag: 0.05, ..RiggingParams::default() };
    let q = p.lumped();
    let (mut worst_acc, mut worst_tension): (f64, f64) = (0.0, 0.0);
    for k in 0..50 {
        let t = 0.37 * k as f64;
        let s = Swing {
            theta_x: 0.5 * (1.1 * t).sin(),
            theta_y: 0.4 * (0.7 * t).cos(),
            omega_x: 0.8 * (1.3 * t).cos(),
            omega_y: -0.6 * (0.9 * t).sin(),
        };
        let u = moving_tip(t);
        let e = evaluate(&p, &RiggingState::from_swing(&s), &u).unwrap();
        let (ax, ay) = crate::pendulum::angular_acceleration(&q, &s, &u);
        let scale = ax.abs().max(ay.abs()).max(1.0);
        worst_acc = worst_acc.max((e.hoist_acc.x - ax).abs().max((e.hoist_acc.y - ay).abs()) / scale);
        let tension = crate::pendulum::tension(&q, &s, &u);
        worst_tension = worst_tension.max((e.hoist_tension - tension).abs() / tension.abs());
    }
    println!(
        "general equations vs pendulum.rs: angular acceleration {worst_acc:.1e}, tension {worst_tension:.1e} relative"
    );
    assert!(worst_acc < 1e-12 && worst_tension < 1e-12);
}

/// Hanging at rest the ropes carry the weight below them; with motion, hook and load velocities
/// and accelerations are the derivatives of their positions (finite differences along a driven
/// run), for each rope combination.
#[test]
fn outputs_are_consistent_at_rest_and_in_motion() {
    let (m_h, m_l, ls) = (0.1, 0.2, 0.25);
    let combos = [
        ("rigid/rigid", RopeLaw::Rigid, RopeLaw::Rigid),
        ("elastic/rigid", elastic(2000.0), RopeLaw::Rigid),
        ("rigid/elastic", RopeLaw::Rigid, elastic(500.0)),
        ("elastic/elastic", elastic(2000.0), elastic(500.0)),
    ];
    for (name, hoist, sling) in combos {
        let p = rig(m_h, m_l, ls, hoist, sling);
        let u = fixed_tip(0.7);
        let rest = rigging_motion(&p, &RiggingState::hanging(&p, &u), &u).unwrap();
        assert!((rest.hoist_tension - (m_h + m_l) * G).abs() < 1e-12, "{name}: {}", rest.hoist_tension);
        assert!((rest.sling_tension - m_l * G).abs() < 1e-12, "{name}: {}", rest.sling_tension);
        assert!(rest.hook.acc.norm() < 1e-12 && rest.load.acc.norm() < 1e-12, "{name}: at rest");
        // Driven run with exact inputs per 0.1 ms step.
        let dt = 1e-4;
        let mut s = RiggingState {
            hoist: if hoist == RopeLaw::Rigid {
                Vec3::new(0.2, -0.1, 0.0)
            } else {
                chord(0.2, -0.1, 0.7 * (1.0 + 0.3 * G / 2000.0))
            },
            sling: if sling == RopeLaw::Rigid {
                Vec3::new(-0.1, 0.15, 0.0)
            } else {
                chord(-0.1, 0.15, 0.25 * (1.0 + 0.2 * G / 500.0))
            },
            ..RiggingState::default()
        };
        let mut motions = Vec::new();
        for k in 0..20000 {
            let t = k as f64 * dt;
            motions.push(rigging_motion(&p, &s, &moving_tip(t)).unwrap());
            s = advance(&p, &s, &moving_tip(t), &secant(t, dt), dt).unwrap();
        }
        let (mut wv, mut wa): (f64, f64) = (0.0, 0.0);
        for k in (1..motions.len() - 1).step_by(97) {
            for (prev, here, next) in [
                (&motions[k - 1].hook, &motions[k].hook, &motions[k + 1].hook),
                (&motions[k - 1].load, &motions[k].load, &motions[k + 1].load),
            ] {
                wv = wv.max(((next.pos - prev.pos) / (2.0 * dt) - here.vel).norm());
                wa = wa.max(((next.vel - prev.vel) / (2.0 * dt) - here.acc).norm());
            }
        }
        println!("{name}: velocity vs finite difference {wv:.1e} m/s, acceleration {wa:.1e} m/s²");
        assert!(wv < 1e-5 && wa < 1e-3, "{name}: {wv} {wa}");
    }
}

#[test]
fn invalid_parameters_and_configurations_are_errors() {
    let p = rig(1.0, 1.0, 0.5, RopeLaw::Rigid, RopeLaw::Rigid);
    assert!(p.validate().is_ok());
    assert!(RiggingParams { hook_mass: 0.0, ..p }.validate().is_err(), "a sling needs a hook mass");
    assert!(RiggingParams { sling_length: -1.0, ..p }.validate().is_err());
    assert!(RiggingParams { sling_length: 0.0, sling: elastic(1.0), ..p }.validate().is_err());
    assert!(RiggingParams { hoist: elastic(0.0), ..p }.validate().is_err());
    assert!(RiggingParams { hoist: elastic(f64::NAN), ..p }.validate().is_err());
    let damped = RopeLaw::Elastic(ElasticRope { ea: 1.0, damping_time: -1.0 });
    assert!(RiggingParams { hoist: damped, ..p }.validate().is_err());
    assert!(RiggingParams::default().validate().is_ok());
    for q in [p, RiggingParams::default()] {
        assert!(rigging_motion(&q, &RiggingState::default(), &fixed_tip(0.0)).is_err());
    }
    let zero = TipMotion::default();
    assert!(advance(&p, &RiggingState::default(), &fixed_tip(0.0), &zero, 0.01).is_err());
    let sideways = RiggingState { sling: Vec3::new(0.0, 89.99999 * DEG, 0.0), ..RiggingState::default() };
    let message = advance(&p, &sideways, &fixed_tip(1.0), &zero, 0.01).unwrap_err();
    assert!(message.contains("singularity"), "{message}");
}

/// Hook on an elastic rope and load on an elastic sling, vertical: the two axial modes of the
/// spring chain, m_h m_l ω⁴ − (m_l (k₁ + k₂) + m_h k₂) ω² + k₁ k₂ = 0 (M = diag(m_h, m_l),
/// K = [[k₁ + k₂, −k₂], [−k₂, k₂]]), within 1 %. Fails on a sling force applied to one body only
/// or with the wrong sign.
#[test]
fn elastic_rope_and_sling_have_the_spring_chain_frequencies() {
    let (m_h, m_l, lp, ls) = (300.0, 2000.0, 20.0, 3.0);
    let (ea1, ea2) = (ElasticRope::steel_wire(0.04).ea, ElasticRope::steel_wire(0.03).ea);
    let (k1, k2) = (ea1 / lp, ea2 / ls);
    let p = rig(m_h, m_l, ls, elastic(ea1), elastic(ea2));
    let (a, b, c) = (m_h * m_l, m_l * (k1 + k2) + m_h * k2, k1 * k2);
    let root = (b * b - 4.0 * a * c).sqrt();
    let modes = [((b - root) / (2.0 * a)).sqrt(), ((b + root) / (2.0 * a)).sqrt()];
    let u = fixed_tip(lp);
    let rest = RiggingState::hanging(&p, &u);
    for omega in modes {
        // Mode shape from the first row of (K − ω² M) x = 0: x_l/x_h = (k₁ + k₂ − ω² m_h)/k₂, with
        // x_l = x_h + (sling stretch change).
        let ratio = (k1 + k2 - omega * omega * m_h) / k2;
        let amplitude = 1e-4 / ratio.abs().max(1.0);
        let mut s0 = rest;
        s0.hoist.z += amplitude;
        s0.sling.z += amplitude * (ratio - 1.0);
        let seconds = 10.0 * 2.0 * std::f64::consts::PI / omega;
        let trace = free_run(&p, s0, lp, seconds, 1e-3);
        let signal: Vec<(f64, f64)> = trace.iter().map(|(t, s)| (*t, s.hoist.z - rest.hoist.z)).collect();
        let measured = crossing_frequency(&signal);
        let error = measured / omega - 1.0;
        println!("axial chain mode (300 kg hook, 2 t load, 20 m rope, 3 m sling): {measured:.4} vs {omega:.4} rad/s ({error:+.1e}; limit 1e-2)");
        assert!(error.abs() < 1e-2, "{measured} vs {omega}");
    }
}

/// A tip heaving faster than gravity can follow (1 m at 3.5 rad/s: 12.3 m/s² peak) throws hook
/// and load up: both ropes go slack and snap taut again, repeatedly, for 60 s in 10 ms steps with
/// the inputs ramped, drag and rope damping on — and the run ends normally with the peaks in the
/// record.
#[test]
fn heave_driven_slack_and_snap_run_to_the_end() {
    let damped = |ea: f64, zeta_time: f64| RopeLaw::Elastic(ElasticRope { ea, damping_time: zeta_time });
    let p = RiggingParams {
        load: PendulumParams { mass: 2000.0, ..PendulumParams::default() },
        hook_mass: 300.0,
        sling_length: 3.0,
        hoist: damped(ElasticRope::steel_wire(0.04).ea, 1e-3),
        sling: damped(ElasticRope::steel_wire(0.03).ea, 1e-3),
        ..RiggingParams::default()
    };
    p.validate().unwrap();
    let (amplitude, w, lp) = (1.0, 3.5, 20.0);
    let tip = |t: f64| TipMotion {
        pos: Vec3::new(0.3 * (0.4 * t).sin(), 0.0, amplitude * (w * t).sin()),
        vel: Vec3::new(0.12 * (0.4 * t).cos(), 0.0, amplitude * w * (w * t).cos()),
        acc: Vec3::new(-0.048 * (0.4 * t).sin(), 0.0, -amplitude * w * w * (w * t).sin()),
        lp,
        ..TipMotion::default()
    };
    let h = 0.01;
    let mut s = RiggingState::hanging(&p, &tip(0.0));
    let mut slack_steps = 0;
    for k in 0..6000 {
        let t = k as f64 * h;
        let (a, b) = (tip(t), tip(t + h));
        s = advance(&p, &s, &a, &a.secant(&b, h), h).unwrap();
        let m = rigging_motion(&p, &s, &b).unwrap();
        slack_steps += usize::from(m.hoist_slack);
        assert!(m.hoist_tension >= 0.0 && m.sling_tension >= 0.0 && m.load.pos.iter().all(|c| c.is_finite()));
    }
    let weight = (p.hook_mass + p.load.mass) * G;
    println!(
        "heave 1 m at 3.5 rad/s, 300 kg hook + 2 t load on 20 m / 3 m steel ropes: hoist slack in {slack_steps} of \
         6000 steps; peak snap loads {:.0} kN (rope), {:.0} kN (sling); static weight {:.1} kN",
        s.snap.hoist_peak / 1e3,
        s.snap.sling_peak / 1e3,
        weight / 1e3
    );
    assert!(s.snap.hoist_was_slack && slack_steps > 0 && s.snap.hoist_peak > 2.0 * weight);
}

/// The tip force is affine in the tip's and the hoist length's accelerations: F₀ + A a_t + b l̈
/// reproduces the force at other accelerations to round-off, for the double pendulum and the
/// single one, whose A = −m e eᵀ, b = −m e and F₀ the pendulum's free cable force.
#[test]
fn the_tip_force_is_affine_in_the_tip_and_length_accelerations() {
    let double = rig(0.1, 0.2, 0.25, RopeLaw::Rigid, RopeLaw::Rigid);
    let s = RiggingState {
        hoist: Vec3::new(0.3, -0.2, 0.0),
        sling: Vec3::new(-0.1, 0.25, 0.0),
        hoist_rate: Vec3::new(0.4, 0.1, 0.0),
        sling_rate: Vec3::new(-0.7, 0.3, 0.0),
        ..RiggingState::default()
    };
    let mut worst: f64 = 0.0;
    for k in 0..20 {
        let u = moving_tip(0.41 * k as f64);
        let c = tip_coupling(&double, &s, &u).unwrap();
        let predicted = c.free_force + c.per_tip_acc * u.acc + c.per_lp_acc * u.lp_ddot;
        let actual = rigging_motion(&double, &s, &u).unwrap().tip_force;
        worst = worst.max((predicted - actual).norm() / actual.norm());
    }
    let p = RiggingParams::default();
    let swing = Swing { theta_x: 0.3, theta_y: -0.2, omega_x: 0.4, omega_y: 0.1 };
    let u = moving_tip(0.8);
    let c = tip_coupling(&p, &RiggingState::from_swing(&swing), &u).unwrap();
    let m = crate::pendulum::load_motion(&p.load, &swing, &u);
    let e = (m.pos - u.pos) / u.lp;
    let single = (c.per_tip_acc + e * e.transpose() * p.load.mass).norm()
        + (c.per_lp_acc + e * p.load.mass).norm()
        + (c.free_force - m.free_cable_force).norm();
    println!("tip coupling: affine to {worst:.1e} relative (double pendulum); single pendulum off by {single:.1e}");
    assert!(worst < 1e-12 && single < 1e-12, "{worst} {single}");
}

/// Hook and load on a rigid sling thrown up on a slack elastic rope: a tumbling dumbbell whose
/// centre of mass follows the ballistic parabola to 1e-9 m while the rope is slack (the sling's
/// forces are internal). Fails if the mixed Cartesian–angle equations leak a force into the free
/// flight.
#[test]
fn a_tumbling_hook_and_load_fly_free_on_a_slack_rope() {
    let (m_h, m_l, ls, lp) = (300.0, 1000.0, 3.0, 10.0);
    let p = rig(m_h, m_l, ls, elastic(1e6), RopeLaw::Rigid);
    let u = fixed_tip(lp);
    let mut s0 = RiggingState::hanging(&p, &u);
    s0.hoist_rate = Vec3::new(0.4, -0.3, -4.0);
    s0.sling_rate = Vec3::new(0.8, -0.5, 0.0);
    let trace = free_run(&p, s0, lp, 3.0, 1e-3);
    let motions: Vec<RiggingMotion> = trace.iter().map(|(_, s)| rigging_motion(&p, s, &u).unwrap()).collect();
    let first = motions.iter().position(|m| m.hoist_slack).unwrap();
    let last = first + motions[first..].iter().position(|m| !m.hoist_slack).unwrap() - 1;
    let centre = |m: &RiggingMotion| (m.hook.pos * m_h + m.load.pos * m_l) / (m_h + m_l);
    let centre_vel = |m: &RiggingMotion| (m.hook.vel * m_h + m.load.vel * m_l) / (m_h + m_l);
    let (t0, c0, v0) = (trace[first].0, centre(&motions[first]), centre_vel(&motions[first]));
    let mut worst: f64 = 0.0;
    for k in first..=last {
        let tau = trace[k].0 - t0;
        worst = worst.max((centre(&motions[k]) - (c0 + v0 * tau + Vec3::new(0.0, 0.0, 0.5 * G * tau * tau))).norm());
    }
    let sling_turn = (motions[last].sling_angles.0 - motions[first].sling_angles.0).abs()
        + (motions[last].sling_angles.1 - motions[first].sling_angles.1).abs();
    println!(
        "tumbling hook and load: {:.3} s slack, the sling turning {:.1}°, centre of mass off the parabola by ≤ {worst:.1e} m",
        trace[last].0 - t0,
        sling_turn / DEG
    );
    assert!(trace[last].0 - t0 > 0.3 && sling_turn > 5.0 * DEG);
    assert!(worst < 1e-9, "centre of mass off the ballistic trajectory by {worst} m");
}

/// `RiggingState::at_angles` puts both ropes at the angles asked for, whatever their laws, and the
/// outputs report them back.
#[test]
fn start_angles_are_the_reported_angles() {
    let (hoist, sling) = ((0.2, -0.15), (-0.1, 0.3));
    let u = fixed_tip(0.7);
    for (h, l) in [
        (RopeLaw::Rigid, RopeLaw::Rigid),
        (elastic(2000.0), RopeLaw::Rigid),
        (RopeLaw::Rigid, elastic(500.0)),
        (elastic(2000.0), elastic(500.0)),
    ] {
        let p = rig(0.1, 0.2, 0.25, h, l);
        let m = rigging_motion(&p, &RiggingState::at_angles(&p, &u, hoist, sling), &u).unwrap();
        let off = (m.hoist_angles.0 - hoist.0).abs()
            + (m.hoist_angles.1 - hoist.1).abs()
            + (m.sling_angles.0 - sling.0).abs()
            + (m.sling_angles.1 - sling.1).abs();
        assert!(off < 1e-15, "{h:?} {l:?}: {m:?}");
        assert!(m.hook.vel.norm() == 0.0 && m.load.vel.norm() == 0.0);
    }
}

/// A pendulum released from rest at θ carries m g cos θ (the rate terms vanish at zero rate), so
/// an elastic hoist rope started there is stretched by m g cos θ / k: the closed form, against the
/// m g / k of hanging straight that the start used before (1/cos θ − 1 = 14 % too long at 0.5 rad,
/// an axial oscillation and, with a sling, slack and spurious snap loads).
#[test]
fn an_elastic_rope_starts_with_the_tension_of_its_start_state() {
    let (lp, ea, theta) = (10.0, 4e7, 0.5);
    let p = rig(300.0, 5000.0, 0.0, elastic(ea), RopeLaw::Rigid);
    let u = fixed_tip(lp);
    let at_rest = Swing { theta_x: theta, ..Swing::default() };
    let s = start_state(&p, &u, &at_rest, &Swing::default()).unwrap();
    let tension = 5300.0 * G * theta.cos();
    let chord = lp * (1.0 + tension / ea);
    assert!((s.hoist.norm() - chord).abs() <= 1e-12 * chord, "{} against {chord}", s.hoist.norm());
    assert_eq!(s.hoist_rate, Vec3::zeros());
    let m = rigging_motion(&p, &s, &u).unwrap();
    assert!((m.hoist_tension - tension).abs() <= 1e-9 * tension, "{} against {tension}", m.hoist_tension);
    assert!((m.hoist_angles.0 - theta).abs() < 1e-15);

    // With a sling, both ropes elastic and swinging: each starts with the tension the rigid rigging
    // has in the same state, and the chords turn at the start rates with their lengths held.
    let hoist = Swing { theta_x: 0.3, theta_y: -0.1, omega_x: 0.2, omega_y: 0.05 };
    let sling = Swing { theta_x: 0.4, theta_y: 0.1, omega_x: -0.3, omega_y: 0.1 };
    let elastic_rig = rig(300.0, 5000.0, 3.0, elastic(ea), elastic(2e7));
    let rigid_rig = rig(300.0, 5000.0, 3.0, RopeLaw::Rigid, RopeLaw::Rigid);
    let s = start_state(&elastic_rig, &u, &hoist, &sling).unwrap();
    let rigid = rigging_motion(&rigid_rig, &start_state(&rigid_rig, &u, &hoist, &sling).unwrap(), &u).unwrap();
    let m = rigging_motion(&elastic_rig, &s, &u).unwrap();
    for (what, got, want) in
        [("hoist", m.hoist_tension, rigid.hoist_tension), ("sling", m.sling_tension, rigid.sling_tension)]
    {
        assert!((got - want).abs() <= 1e-9 * want, "{what}: {got} N against the rigid rigging's {want} N");
    }
    assert!(s.hoist.dot(&s.hoist_rate).abs() < 1e-9 && s.sling.dot(&s.sling_rate).abs() < 1e-9, "no stretch rate");
}

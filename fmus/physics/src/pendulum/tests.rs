use super::*;

const DEG: f64 = std::f64::consts::PI / 180.0;

fn fixed_tip(lp: f64) -> TipMotion {
    TipMotion { lp, ..TipMotion::default() }
}

fn undamped() -> PendulumParams {
    PendulumParams { kappa_x: 0.0, kappa_y: 0.0, ..PendulumParams::default() }
}

fn swing(theta_x_deg: f64, theta_y_deg: f64) -> Swing {
    Swing { theta_x: theta_x_deg * DEG, theta_y: theta_y_deg * DEG, ..Swing::default() }
}

/// Simulates `seconds` at 10 ms communication steps with the tip fixed; returns (t, swing) samples.
fn free_response(p: &PendulumParams, s0: Swing, lp: f64, seconds: f64) -> Vec<(f64, Swing)> {
    let u = fixed_tip(lp);
    let zero = TipMotion::default();
    let h = 0.01;
    let n = (seconds / h).round() as usize;
    let mut s = s0;
    let mut out = vec![(0.0, s)];
    for k in 0..n {
        s = advance(p, &s, &u, &zero, h).unwrap();
        out.push(((k + 1) as f64 * h, s));
    }
    out
}

/// Time constant of the exponential envelope through the local extrema of `signal` on the side
/// opposite to its initial value (least squares on ln|peak|).
fn decay_time_constant(samples: &[(f64, f64)]) -> f64 {
    let sign = -samples[0].1.signum();
    let peaks: Vec<(f64, f64)> = samples
        .windows(3)
        .filter(|w| {
            let (a, b, c) = (w[0].1 * sign, w[1].1 * sign, w[2].1 * sign);
            b > a && b >= c && b > 0.0
        })
        .map(|w| (w[1].0, (w[1].1 * sign).ln()))
        .collect();
    let n = peaks.len() as f64;
    let (st, sy) = peaks.iter().fold((0.0, 0.0), |(a, b), (t, y)| (a + t, b + y));
    let (mt, my) = (st / n, sy / n);
    let slope = peaks.iter().map(|(t, y)| (t - mt) * (y - my)).sum::<f64>()
        / peaks.iter().map(|(t, _)| (t - mt) * (t - mt)).sum::<f64>();
    -1.0 / slope
}

#[test]
fn energy_is_conserved_without_damping_for_a_fixed_tip() {
    let p = undamped();
    let lp = 0.7;
    let trace = free_response(&p, swing(20.0, -15.0), lp, 60.0);
    let e0 = energy(&p, &trace[0].1, lp);
    let drift = trace.iter().map(|(_, s)| (energy(&p, s, lp) - e0).abs()).fold(0.0, f64::max) / e0.abs();
    println!("pendulum energy drift over 60 s (20°, −15°, l = 0.7 m, 10 ms sixth-order steps): {drift:.3e} relative");
    assert!(drift < 1e-10, "relative energy drift {drift}");
}

#[test]
fn free_decay_time_constants_match_the_identified_damping() {
    let p = PendulumParams::default();
    let lp = 0.7;
    let tx = free_response(&p, swing(-10.0, 0.0), lp, 120.0);
    let ty = free_response(&p, swing(0.0, 10.0), lp, 120.0);
    let tau_x = decay_time_constant(&tx.iter().map(|(t, s)| (*t, s.theta_x)).collect::<Vec<_>>());
    let tau_y = decay_time_constant(&ty.iter().map(|(t, s)| (*t, s.theta_y)).collect::<Vec<_>>());
    println!(
        "free-decay time constants: tau_theta_x = {tau_x:.2} s (expected 73.5), tau_theta_y = {tau_y:.2} \
        s (expected 111.1)"
    );
    assert!((tau_x / 73.5 - 1.0).abs() < 0.05, "tau_x {tau_x}");
    assert!((tau_y / 111.1 - 1.0).abs() < 0.05, "tau_y {tau_y}");
}

#[test]
fn drag_adds_exactly_minus_kappa_times_rate_for_a_fixed_tip() {
    let p = PendulumParams::default();
    let s = Swing { theta_x: 0.3, theta_y: 0.0, omega_x: 0.7, omega_y: 0.0 };
    let u = fixed_tip(0.55);
    let (with, _) = angular_acceleration(&p, &s, &u);
    let (without, _) = angular_acceleration(&undamped(), &s, &u);
    assert!((with - without + p.kappa_x * 0.7).abs() < 1e-15);
    let s = Swing { theta_x: 0.0, theta_y: -0.2, omega_x: 0.0, omega_y: 0.4 };
    let (_, with) = angular_acceleration(&p, &s, &u);
    let (_, without) = angular_acceleration(&undamped(), &s, &u);
    assert!((with - without + p.kappa_y * 0.4).abs() < 1e-15);
}

/// RMSD (m) of the Euclidean distance between linearised and nonlinear load positions over 60 s,
/// 10 ms logging, l_p = 0.25 m, tip fixed, no damping (the comparison of §4.3.2, Fig. 4.15b).
fn linearisation_rmsd(theta_x_deg: f64, theta_y_deg: f64) -> f64 {
    let p = undamped();
    let lp = 0.25;
    let u = fixed_tip(lp);
    let nonlinear = free_response(&p, swing(theta_x_deg, theta_y_deg), lp, 60.0);
    let mut lin = swing(theta_x_deg, theta_y_deg).to_vector();
    let h = 0.01;
    let mut sum = 0.0;
    for (k, (_, s)) in nonlinear.iter().enumerate() {
        if k > 0 {
            for _ in 0..10 {
                lin = crate::integrate::rk4(&lin, 0.0, h / 10.0, |_, x| {
                    let (ax, ay) = linear_angular_acceleration(p.g, lp, &Swing::from_vector(x), &Vec3::zeros());
                    SVector::<f64, 4>::new(x[2], x[3], ax, ay)
                });
            }
        }
        let exact = load_motion(&p, s, &u).pos;
        let approx = linear_load_position(lp, &Swing::from_vector(&lin), &u.pos, lp);
        sum += (exact - approx).norm_squared();
    }
    (sum / nonlinear.len() as f64).sqrt()
}

#[test]
fn linearised_model_error_grows_with_the_initial_angle_as_in_fig_4_15b() {
    let small = [(5.0, 5.0), (-5.0, 5.0), (5.0, -5.0), (-5.0, -5.0), (5.0, 0.0), (0.0, -5.0)]
        .map(|(a, b)| linearisation_rmsd(a, b));
    let large = [(20.0, 20.0), (-20.0, -20.0), (20.0, -20.0)].map(|(a, b)| linearisation_rmsd(a, b));
    println!(
        "linearised-model RMSD (l = 0.25 m): ±5° corners {:.2?} mm; ±20° corners {:.1?} mm",
        small.map(|r| r * 1e3),
        large.map(|r| r * 1e3)
    );
    assert!(small.iter().all(|r| *r < 5e-3), "±5° RMSD {small:?}");
    assert!(large.iter().all(|r| (0.08..0.17).contains(r)), "±20° RMSD {large:?}");
}

/// A smooth, fully consistent tip and length trajectory for derivative checks (the rigging's
/// tests drive their hook and load with it too).
pub(crate) fn moving_tip(t: f64) -> TipMotion {
    let w = 2.3;
    TipMotion {
        pos: Vec3::new(0.05 * (w * t).sin(), -0.03 * (1.7 * t).cos(), 0.02 * (0.9 * t).sin()),
        vel: Vec3::new(0.05 * w * (w * t).cos(), 0.03 * 1.7 * (1.7 * t).sin(), 0.02 * 0.9 * (0.9 * t).cos()),
        acc: Vec3::new(
            -0.05 * w * w * (w * t).sin(),
            0.03 * 1.7 * 1.7 * (1.7 * t).cos(),
            -0.02 * 0.81 * (0.9 * t).sin(),
        ),
        lp: 0.7 + 0.1 * (0.5 * t).sin(),
        lp_dot: 0.05 * (0.5 * t).cos(),
        lp_ddot: -0.025 * (0.5 * t).sin(),
    }
}

/// Integrates with a moving tip using exact inputs at every substep (1e-4 s steps).
fn driven_trace(p: &PendulumParams, seconds: f64, dt: f64) -> Vec<(f64, Swing)> {
    let mut s = Swing { theta_x: 0.2, theta_y: -0.1, omega_x: 0.3, omega_y: 0.1 };
    let n = (seconds / dt).round() as usize;
    let mut out = vec![(0.0, s)];
    for k in 0..n {
        let t = k as f64 * dt;
        let x = crate::integrate::rk4(&s.to_vector(), t, dt, |t, x| swing_rate(p, x, &moving_tip(t)));
        s = Swing::from_vector(&x);
        out.push(((k + 1) as f64 * dt, s));
    }
    out
}

#[test]
fn load_velocity_and_acceleration_match_finite_differences() {
    let p = PendulumParams::default();
    let dt = 1e-4;
    let trace = driven_trace(&p, 3.0, dt);
    let motion: Vec<LoadMotion> = trace.iter().map(|(t, s)| load_motion(&p, s, &moving_tip(*t))).collect();
    let mut worst_v: f64 = 0.0;
    let mut worst_a: f64 = 0.0;
    for k in (1..motion.len() - 1).step_by(97) {
        let fd_v = (motion[k + 1].pos - motion[k - 1].pos) / (2.0 * dt);
        let fd_a = (motion[k + 1].vel - motion[k - 1].vel) / (2.0 * dt);
        worst_v = worst_v.max((fd_v - motion[k].vel).norm());
        worst_a = worst_a.max((fd_a - motion[k].acc).norm());
    }
    assert!(worst_v < 1e-6, "velocity vs finite difference: {worst_v}");
    assert!(worst_a < 1e-5, "acceleration vs finite difference: {worst_a}");
}

#[test]
fn angular_velocity_matches_the_orientation_derivative() {
    let p = PendulumParams::default();
    let dt = 1e-4;
    let trace = driven_trace(&p, 1.0, dt);
    for k in (1..trace.len() - 1).step_by(333) {
        let m = load_motion(&p, &trace[k].1, &moving_tip(trace[k].0));
        let q_prev = load_motion(&p, &trace[k - 1].1, &moving_tip(trace[k - 1].0)).orientation;
        let q_next = load_motion(&p, &trace[k + 1].1, &moving_tip(trace[k + 1].0)).orientation;
        // Body rate from q⁻¹ q̇ = ½ (0, ω_body).
        let rotation = q_prev.inverse() * q_next;
        let fd = rotation.scaled_axis() / (2.0 * dt);
        assert!((fd - m.angular_velocity).norm() < 1e-6, "{fd} vs {}", m.angular_velocity);
    }
}

#[test]
fn tension_is_the_radial_force_balance() {
    let p = PendulumParams::default();
    let at_rest = tension(&p, &Swing::default(), &fixed_tip(0.7));
    assert!((at_rest - p.mass * p.g).abs() < 1e-12, "tension at rest {at_rest}");
    for (t, s) in driven_trace(&p, 1.0, 1e-3).iter().step_by(50) {
        let u = moving_tip(*t);
        let m = load_motion(&p, s, &u);
        let e_r = (m.pos - u.pos) / u.lp;
        // m a = m g ẑ − T e_r + drag (drag ⟂ e_r)  ⇒  T = m (g ẑ − a)·e_r.
        let expected = p.mass * (Vec3::new(0.0, 0.0, p.g) - m.acc).dot(&e_r);
        assert!((m.tension - expected).abs() < 1e-12, "{} vs {expected}", m.tension);
    }
}

#[test]
fn invalid_configurations_are_errors_not_nan() {
    let p = PendulumParams::default();
    let zero = TipMotion::default();
    assert!(advance(&p, &Swing::default(), &fixed_tip(0.0), &zero, 0.01).is_err());
    let shrinking = TipMotion { lp: -1.0, ..TipMotion::default() };
    assert!(advance(&p, &Swing::default(), &fixed_tip(0.005), &shrinking, 0.01).is_err());
    assert!(PendulumParams { mass: 0.0, ..p }.validate().is_err());
    assert!(PendulumParams { g: f64::NAN, ..p }.validate().is_err());
}

/// A swing fast enough to cross θy = 90° between two substep checks (1.5 rad at 30 rad/s: past
/// 1.8 rad after 10 ms) is an error, not a state beyond the singularity with |cos θy| = 0.02.
#[test]
fn a_swing_that_steps_over_90_degrees_is_an_error() {
    let p = undamped();
    let fast = Swing { theta_y: 1.5, omega_y: 30.0, ..Swing::default() };
    let message = advance(&p, &fast, &fixed_tip(0.7), &TipMotion::default(), 0.01).unwrap_err();
    assert!(message.contains("singularity"), "{message}");
}

#[test]
fn reconciled_ramp_recovers_an_acceleration_that_jumped_at_the_step_start() {
    // Over [0, h] the true acceleration is a0 + c·τ; the sample at 0 is the left limit of the
    // previous step (a_prev), as a sampled crane command produces.
    let (h, a_prev, a0, c) = (0.01, 0.8, -0.5, 12.0);
    let end = a0 + c * h;
    let mut u = TipMotion { lp: 0.7, ..TipMotion::default() };
    let mut rate = TipMotion::default();
    u.acc.y = a_prev;
    rate.acc.y = (end - a_prev) / h;
    rate.vel.y = a0 + c * h / 2.0; // exact mean acceleration = velocity secant
    u.lp_ddot = a_prev;
    rate.lp_ddot = (end - a_prev) / h;
    rate.lp_dot = rate.vel.y;
    let all = VelocitySlopes { tip: [true; 3], lp: true };
    let (start, ramp) = u.reconciled(&rate, &all, h);
    assert!((start.acc.y - a0).abs() < 1e-12 && (ramp.acc.y - c).abs() < 1e-9, "{start:?} {ramp:?}");
    assert!((start.lp_ddot - a0).abs() < 1e-12 && (ramp.lp_ddot - c).abs() < 1e-9);
    assert!((start.ramp(&ramp, h).acc.y - end).abs() < 1e-12, "the end value is kept");
    // Without velocity derivatives (held inputs) the plain ramp is kept.
    let (held, held_rate) = u.reconciled(&rate, &VelocitySlopes::default(), h);
    assert_eq!((held, held_rate), (u, rate));
}

#[test]
fn reconciled_ramp_of_a_smooth_trajectory_differs_from_the_plain_one_at_second_order() {
    let all = VelocitySlopes { tip: [true; 3], lp: true };
    let deviation = |h: f64| {
        let (a, b) = (moving_tip(1.3), moving_tip(1.3 + h));
        let rate = a.secant(&b, h);
        let (start, _) = a.reconciled(&rate, &all, h);
        (start.acc - a.acc).norm()
    };
    let (coarse, fine) = (deviation(0.02), deviation(0.01));
    assert!(coarse < 1e-3 && (coarse / fine - 4.0).abs() < 0.2, "deviation {coarse:e} -> {fine:e}");
}

#[test]
fn drag_opposes_the_load_velocity_along_the_swing_directions_with_a_moving_tip() {
    let p = PendulumParams::default();
    let s = Swing { theta_x: 0.35, theta_y: -0.25, omega_x: -0.6, omega_y: 0.45 };
    let u = moving_tip(0.4);
    let v = load_motion(&p, &s, &u).vel;
    let (sx, cx, sy, cy) = (s.theta_x.sin(), s.theta_x.cos(), s.theta_y.sin(), s.theta_y.cos());
    let (e_x, e_y) = (Vec3::new(0.0, -cx, -sx), Vec3::new(cy, sy * sx, -sy * cx));
    let (with_x, with_y) = angular_acceleration(&p, &s, &u);
    let (without_x, without_y) = angular_acceleration(&undamped(), &s, &u);
    let expected_x = -p.kappa_x * v.dot(&e_x) / (u.lp * cy);
    let expected_y = -p.kappa_y * v.dot(&e_y) / u.lp;
    assert!(((with_x - without_x) - expected_x).abs() < 1e-12, "{} vs {expected_x}", with_x - without_x);
    assert!(((with_y - without_y) - expected_y).abs() < 1e-12, "{} vs {expected_y}", with_y - without_y);
    assert!(expected_x.abs() > 1e-3 && expected_y.abs() > 1e-3);
}

/// A full-scale offshore load (SPEC: 2–10 t on 5–30 m of cable): 5 t on 20 m.
fn full_scale_load() -> PendulumParams {
    PendulumParams { mass: 5000.0, ..PendulumParams::default() }
}

#[test]
fn a_load_hanging_at_rest_pulls_the_tip_straight_down_with_its_weight() {
    for p in [PendulumParams::default(), full_scale_load()] {
        for lp in [0.7, 5.0, 20.0, 30.0] {
            let f = load_motion(&p, &Swing::default(), &fixed_tip(lp)).cable_force;
            let weight = p.mass * p.g;
            // North-East-Down: the load below the tip pulls it along +z with m g (Newton's third law).
            assert_eq!((f.x, f.y), (0.0, 0.0), "m = {} kg, lp = {lp} m: {f}", p.mass);
            assert!((f.z - weight).abs() <= 1e-12 * weight, "m = {} kg, lp = {lp} m: {} vs {weight}", p.mass, f.z);
        }
    }
}

#[test]
fn the_cable_force_on_the_tip_has_the_tension_as_magnitude_and_points_to_the_load() {
    let p = full_scale_load();
    let mut worst_norm: f64 = 0.0;
    let mut worst_direction: f64 = 0.0;
    for (t, s) in driven_trace(&p, 2.0, 1e-3).iter().step_by(40) {
        let u = TipMotion { lp: 20.0 * moving_tip(*t).lp, ..moving_tip(*t) };
        let m = load_motion(&p, s, &u);
        let f = m.cable_force;
        let towards_load = (m.pos - u.pos).normalize();
        assert!(m.tension > 0.0 && s.theta_x != 0.0 && s.theta_y != 0.0, "a taut swinging cable at t = {t}");
        worst_norm = worst_norm.max((f.norm() - m.tension).abs() / m.tension);
        // Parallel and the same way: the component across the load direction vanishes, along it is +T.
        worst_direction = worst_direction.max((f - towards_load * f.dot(&towards_load)).norm() / m.tension);
        assert!(f.dot(&towards_load) > 0.0, "t = {t}: {f} points away from the load");
    }
    println!("5 t on ~20 m, swinging: ||F| − T|/T ≤ {worst_norm:.1e}, F across the cable ≤ {worst_direction:.1e} T");
    assert!(worst_norm < 1e-12 && worst_direction < 1e-12);
}

/// Without drag the only forces on the load are gravity and the cable, so the force on the tip is
/// Newton's second law of the load, F = −F_load = m (g ẑ − a_load), with a_load the kinematic
/// acceleration (eqs. 4.94–4.96 differentiated twice), which does not use the tension formula.
#[test]
fn without_drag_the_cable_force_is_the_load_inertia_and_weight() {
    let p = PendulumParams { kappa_x: 0.0, kappa_y: 0.0, ..full_scale_load() };
    for (t, s) in driven_trace(&p, 2.0, 1e-3).iter().step_by(100) {
        let u = TipMotion { lp: 20.0 * moving_tip(*t).lp, ..moving_tip(*t) };
        let m = load_motion(&p, s, &u);
        let expected = (Vec3::new(0.0, 0.0, p.g) - m.acc) * p.mass;
        assert!((m.cable_force - expected).norm() < 1e-9 * expected.norm(), "t = {t}: {} vs {expected}", m.cable_force);
    }
}

/// The pendulum's accuracy rule (docs/specification.md, §4) on the Rust side: over 60 s of 10 ms
/// steps with a moving tip and a changing length (inputs ramped linearly between the samples),
/// the load position of [`advance`] within 1e-7 m RMSD of classical RK4 at 0.1 ms substeps of the
/// same ramps, whose own error is some 10⁻¹³ m. tests/test_pendulum.py checks the same bound
/// against SciPy through the FMU.
#[test]
fn ten_millisecond_steps_keep_the_load_within_1e_7_m_rmsd_of_a_fine_reference() {
    let p = PendulumParams::default();
    let h = 0.01;
    let fine = 100;
    let dt = h / fine as f64;
    let mut s = Swing { theta_x: -15.0 * DEG, theta_y: 10.0 * DEG, omega_x: 0.3, omega_y: -0.2 };
    let mut reference = s.to_vector();
    let mut sum_sq = 0.0;
    let steps = 6000;
    for k in 0..steps {
        let (u, u_next) = (moving_tip(k as f64 * h), moving_tip((k + 1) as f64 * h));
        let rate = u.secant(&u_next, h);
        s = advance(&p, &s, &u, &rate, h).unwrap();
        for i in 0..fine {
            let tau = i as f64 * dt;
            reference = crate::integrate::rk4(&reference, tau, dt, |t, x| swing_rate(&p, x, &u.ramp(&rate, t)));
        }
        let end = u.ramp(&rate, h);
        let got = load_motion(&p, &s, &end).pos;
        let expected = load_motion(&p, &Swing::from_vector(&reference), &end).pos;
        sum_sq += (got - expected).norm_squared();
    }
    let rmsd = (sum_sq / steps as f64).sqrt();
    println!("pendulum, 10 ms steps vs RK4 at 0.1 ms, moving tip and length, 60 s: load RMSD {rmsd:.3e} m");
    assert!(rmsd < 1e-7, "load-position RMSD {rmsd:e} m");
}

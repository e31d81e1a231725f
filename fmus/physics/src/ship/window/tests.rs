use super::*;
use crate::platform::kinematics::PlatformGeometry;
use crate::ship::profiles::ProfileId;
use crate::ship::rao::Hull;
use crate::ship::source::{SourceConfig, SourceKind};

/// Central-difference step (s) and the relative tolerance of the derivative checks.
const H: f64 = 1e-5;
const TOL: f64 = 1e-6;

fn profile_1() -> MotionSource {
    let config = SourceConfig { kind: SourceKind::Sea(ProfileId::One), ..SourceConfig::default() };
    MotionSource::build(&config, None, &Hull::default(), &PlatformGeometry::default()).unwrap()
}

/// An analytic motion that moves every degree of freedom, with offsets (a motion file need not be
/// zero-mean) so that the ẇ x and ẅ x terms matter: x_j = c_j + A_j sin(ω_j τ + φ_j).
fn analytic(tau: f64) -> DeckMotion {
    let mut m = DeckMotion::default();
    for (j, axis) in m.dof.iter_mut().enumerate() {
        let k = j as f64;
        let (a, omega, phi, c) = (0.01 + 0.002 * k, 0.5 + 0.6 * k, 0.3 * k, 0.004 * (k - 2.5));
        let (s, co) = (omega * tau + phi).sin_cos();
        *axis = AxisMotion { pos: c + a * s, vel: a * omega * co, acc: -a * omega * omega * s };
    }
    m
}

fn all_bits_zero(m: &DeckMotion) -> bool {
    m.dof.iter().all(|a| a.pos.to_bits() == 0 && a.vel.to_bits() == 0 && a.acc.to_bits() == 0)
}

#[test]
fn the_deck_rests_exactly_until_the_start() {
    let window = MotionWindow { start: 10.0, fade_in: 5.0 };
    let mut source = profile_1();
    for t in [-3.0, 0.0, 5.0, 9.99, 10.0 - 1e-12, 10.0] {
        for offset in [0.0, -2.5, 7.0] {
            let m = window.sample(&mut source, t, offset);
            assert!(all_bits_zero(&m), "t = {t}, offset = {offset}: {m:?}");
            assert!(all_bits_zero(&window.apply(t, &analytic(t))), "t = {t}");
        }
    }
    // Without a fade the motion switches on at the start itself.
    let step = MotionWindow { start: 10.0, fade_in: 0.0 };
    assert!(all_bits_zero(&step.sample(&mut source, 10.0 - 1e-9, 0.0)));
    assert_eq!(step.sample(&mut source, 10.0, 0.0), source.sample(0.0));
    assert_ne!(step.sample(&mut source, 10.0, 0.0), DeckMotion::default());
}

#[test]
fn after_the_fade_the_motion_is_the_source_at_profile_time() {
    let window = MotionWindow { start: 10.0, fade_in: 5.0 };
    let mut source = profile_1();
    for t in [15.0, 15.0 + 1e-9, 17.3, 60.0, 130.0] {
        for offset in [0.0, -2.5, 7.0] {
            let tau = t - 10.0 + offset;
            assert_eq!(window.profile_time(t, offset), tau);
            assert_eq!(window.sample(&mut source, t, offset), source.sample(tau), "t = {t}, offset = {offset}");
        }
        assert_eq!(window.apply(t, &analytic(t)), analytic(t));
    }
}

#[test]
fn the_default_window_is_the_bare_source_bit_for_bit() {
    let window = MotionWindow::default();
    assert_eq!(window, MotionWindow { start: 0.0, fade_in: 0.0 });
    let mut source = profile_1();
    for k in 0..2_000 {
        let t = k as f64 * 0.0613;
        for offset in [0.0, -2.5, -10.0, 3.25] {
            assert_eq!(window.profile_time(t, offset).to_bits(), (t + offset).to_bits());
            let (windowed, bare) = (window.sample(&mut source, t, offset), source.sample(t + offset));
            let bits = |m: &DeckMotion| m.dof.map(|a| [a.pos.to_bits(), a.vel.to_bits(), a.acc.to_bits()]);
            assert_eq!(bits(&windowed), bits(&bare), "t = {t}, offset = {offset}");
        }
    }
}

#[test]
fn the_weight_is_the_smootherstep_with_chain_rule_derivatives() {
    for fade in [0.3, 5.0] {
        let window = MotionWindow { start: 2.0, fade_in: fade };
        // Midpoint: w = 1/2, ẇ = w'(1/2)/T = 1.875/T, ẅ = 0.
        let mid = window.weight(2.0 + fade / 2.0);
        assert!(
            (mid.pos - 0.5).abs() < 1e-15 && (mid.vel - 1.875 / fade).abs() < 1e-12 / fade && mid.acc.abs() < 1e-12
        );
        // Quarter: w = 10/64 − 15/256 + 6/1024, ẅ = 60 (1/4)(3/4)(1/2)/T².
        let quarter = window.weight(2.0 + fade / 4.0);
        assert!((quarter.pos - (10.0 / 64.0 - 15.0 / 256.0 + 6.0 / 1024.0)).abs() < 1e-15);
        assert!((quarter.acc - 5.625 / (fade * fade)).abs() < 1e-12 / (fade * fade));
        // ẇ and ẅ are the time derivatives of w and ẇ.
        let mut worst: f64 = 0.0;
        for k in 1..200 {
            let t = 2.0 + fade * k as f64 / 200.0;
            let (plus, minus, w) = (window.weight(t + H * fade), window.weight(t - H * fade), window.weight(t));
            let fd_vel = (plus.pos - minus.pos) / (2.0 * H * fade);
            let fd_acc = (plus.vel - minus.vel) / (2.0 * H * fade);
            worst = worst.max((fd_vel - w.vel).abs() * fade / 1.875).max((fd_acc - w.acc).abs() * fade * fade / 5.8);
        }
        println!("fade {fade} s: weight derivatives vs central differences, worst error {worst:.1e} of the peak");
        assert!(worst < TOL);
    }
}

#[test]
fn the_weight_and_its_derivatives_are_continuous_at_both_ends() {
    let window = MotionWindow { start: 10.0, fade_in: 5.0 };
    assert_eq!(window.weight(10.0), AxisMotion { pos: 0.0, vel: 0.0, acc: 0.0 });
    assert_eq!(window.weight(15.0), AxisMotion { pos: 1.0, vel: 0.0, acc: 0.0 });
    let mut worst: f64 = 0.0;
    for end in [10.0, 15.0] {
        for delta in [1e-6, 1e-9] {
            let (before, after) = (window.weight(end - delta), window.weight(end + delta));
            worst = worst
                .max((after.pos - before.pos).abs())
                .max((after.vel - before.vel).abs())
                .max((after.acc - before.acc).abs());
        }
    }
    println!("jump of (w, ẇ, ẅ) across the ends of a 5 s fade within ±1 µs: {worst:.1e}");
    assert!(worst < 1e-5, "ẅ ≈ 60 δ/T² = 2.4e-6 at δ = 1 µs");
    // w rises monotonically from 0 to 1.
    let w: Vec<f64> = (0..=1000).map(|k| window.weight(10.0 + 5.0 * k as f64 / 1000.0).pos).collect();
    assert!(w.windows(2).all(|p| p[1] > p[0]) && w[0] == 0.0 && w[1000] == 1.0);
}

/// Central differences of the weighted position and velocity against the weighted velocity and
/// acceleration over the fade, every degree of freedom; the error relative to the larger of the
/// value and 1e-3 of the quantity's peak over the fade (zero crossings). Returns the worst, and
/// the worst the velocity would be off without the ẇ x term (to show the check would see it).
fn derivative_check(window: &MotionWindow, offset: f64, sample: impl Fn(f64) -> DeckMotion) -> (f64, f64) {
    let at = |t: f64| window.apply(t, &sample(window.profile_time(t, offset)));
    let times: Vec<f64> = (1..500).map(|k| window.start + window.fade_in * k as f64 / 500.0).collect();
    let rows: Vec<_> = times.iter().map(|&t| (at(t - H), at(t), at(t + H))).collect();
    let (mut worst, mut missing_term): (f64, f64) = (0.0, 0.0);
    for j in 0..6 {
        let peak_vel = rows.iter().fold(0.0f64, |p, r| p.max(r.1.dof[j].vel.abs()));
        let peak_acc = rows.iter().fold(0.0f64, |p, r| p.max(r.1.dof[j].acc.abs()));
        if peak_vel == 0.0 {
            continue; // a degree of freedom that does not move (yaw of the profiles)
        }
        for (&t, (minus, m, plus)) in times.iter().zip(&rows) {
            let fd_vel = (plus.dof[j].pos - minus.dof[j].pos) / (2.0 * H);
            let fd_acc = (plus.dof[j].vel - minus.dof[j].vel) / (2.0 * H);
            let (vel, acc) = (m.dof[j].vel, m.dof[j].acc);
            worst = worst.max((fd_vel - vel).abs() / vel.abs().max(1e-3 * peak_vel));
            worst = worst.max((fd_acc - acc).abs() / acc.abs().max(1e-3 * peak_acc));
            let w = window.weight(t);
            let unweighted = sample(window.profile_time(t, offset)).dof[j];
            missing_term = missing_term.max((fd_vel - w.pos * unweighted.vel).abs() / vel.abs().max(1e-3 * peak_vel));
        }
    }
    (worst, missing_term)
}

#[test]
fn during_the_fade_velocity_and_acceleration_are_the_derivatives() {
    let source = std::cell::RefCell::new(profile_1());
    for (window, offset) in [
        (MotionWindow { start: 10.0, fade_in: 5.0 }, 0.0),
        (MotionWindow { start: 10.0, fade_in: 2.0 }, -2.5),
        (MotionWindow { start: 3.0, fade_in: 20.0 }, 40.0),
    ] {
        let (profile, profile_naive) = derivative_check(&window, offset, |tau| source.borrow_mut().sample(tau));
        let (synthetic, synthetic_naive) = derivative_check(&window, offset, analytic);
        println!(
            "{window:?}, offset {offset}: worst relative derivative error {profile:.1e} (profile 1), \
             {synthetic:.1e} (six-DOF sines); \
             without ẇx the velocity would be off by {profile_naive:.1e}, {synthetic_naive:.1e}"
        );
        assert!(profile < TOL && synthetic < TOL);
        assert!(profile_naive > 1e3 * TOL && synthetic_naive > 1e3 * TOL);
    }
}

#[test]
fn invalid_windows_are_rejected() {
    assert!(MotionWindow::default().validate().is_ok());
    assert!(MotionWindow { start: -4.0, fade_in: 2.0 }.validate().is_ok());
    for (start, fade_in) in
        [(0.0, -1.0), (0.0, f64::NAN), (0.0, f64::INFINITY), (f64::NAN, 1.0), (f64::NEG_INFINITY, 0.0)]
    {
        assert!(MotionWindow { start, fade_in }.validate().is_err(), "{start}, {fade_in}");
    }
}

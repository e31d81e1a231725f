use super::*;
use crate::integrate::rk4;
use nalgebra::SVector;

const ALL: [(&str, Actuator); 4] =
    [("base", Actuator::BASE), ("boom", Actuator::BOOM), ("jib", Actuator::JIB), ("winch", Actuator::WINCH)];

/// Runs `seconds` at communication steps `h` with the command held; returns the states.
fn run(a: &Actuator, start: AxisState, u: f64, h: f64, seconds: f64) -> Vec<AxisState> {
    let n = (seconds / h).round() as usize;
    let mut s = start;
    let mut out = vec![s];
    for _ in 0..n {
        s = a.advance(&s, u, h);
        out.push(s);
    }
    out
}

fn mid(a: &Actuator) -> AxisState {
    AxisState { pos: if a.stroke.is_some() { 25.0 } else { 1000.0 }, vel: 0.0 }
}

#[test]
fn deadband_removes_the_jump() {
    let band = Deadband { lower: -0.145, upper: 0.525 };
    assert_eq!(band.apply(0.0), 0.0);
    assert_eq!(band.apply(0.525), 0.0);
    assert_eq!(band.apply(-0.145), 0.0);
    assert!((band.apply(0.625) - 0.1).abs() < 1e-15);
    assert!((band.apply(-0.245) + 0.1).abs() < 1e-15);
    // Step 1 saturates the hardware command before the neutral is removed.
    assert_eq!(Actuator::BOOM.linearise(5.0), Actuator::BOOM.linearise(3.3));
    assert_eq!(Actuator::WINCH.linearise(-1.0), -0.5 - (-0.0165));
    for (_, a) in ALL {
        a.validate().unwrap();
    }
}

#[test]
fn constant_command_reaches_the_steady_velocity() {
    for (name, a) in ALL {
        let span = a.input_max - a.neutral;
        for frac in [0.5, -0.5] {
            let u = a.neutral + frac * span;
            let crossed = if frac > 0.0 { a.deadband.upper } else { a.deadband.lower };
            let expected = a.plant.gain / a.plant.pole * (u - a.neutral - crossed);
            // 30 time constants (e^-30 ≈ 1e-13), starting far enough from the stroke end.
            let seconds = 30.0 / a.plant.pole;
            let start = match a.stroke {
                Some(_) => AxisState { pos: if frac > 0.0 { 10.0 } else { 40.0 }, vel: 0.0 },
                None => AxisState::default(),
            };
            let end = *run(&a, start, u, 0.01, seconds).last().unwrap();
            let rel = (end.vel - expected).abs() / expected.abs();
            println!(
                "{name:5} u = {u:.4}: steady velocity {:.9} vs K/a·(u − neutral − deadband) = \
                {expected:.9} ({rel:.1e})",
                end.vel
            );
            assert!(rel < 1e-10, "{name}: {} vs {expected}", end.vel);
        }
    }
}

/// Unit-step response of K/(s(s + a)) from rest: x(t) = (K/a)(t − (1 − e^(−at))/a).
fn step_response(a: &Actuator, c_per_gain: f64, t: f64) -> (f64, f64) {
    let (k, p) = (a.plant.gain * c_per_gain, a.plant.pole);
    (k / p * (t - (1.0 - (-p * t).exp()) / p), k / p * (1.0 - (-p * t).exp()))
}

#[test]
fn step_response_matches_the_transfer_function() {
    for (name, a) in ALL {
        for frac in [0.6, -0.6] {
            let u = a.neutral + frac * (a.input_max - a.neutral);
            let lin = a.linearise(u);
            assert!(lin != 0.0);
            let start = AxisState {
                pos: if a.stroke.is_none() {
                    0.0
                } else if frac > 0.0 {
                    5.0
                } else {
                    45.0
                },
                vel: 0.0,
            };
            let seconds = if a.stroke.is_some() { 1.0 } else { 2.0 };
            let trace = run(&a, start, u, 0.01, seconds);
            // An independent integration: RK4 with 0.1 ms steps of ẍ = −a ẋ + K u_lin.
            let mut x = SVector::<f64, 2>::new(start.pos, 0.0);
            let f =
                |_t: f64, x: &SVector<f64, 2>| SVector::<f64, 2>::new(x[1], -a.plant.pole * x[1] + a.plant.gain * lin);
            let (mut max_exact, mut max_rk4) = (0.0f64, 0.0f64);
            for (k, s) in trace.iter().enumerate() {
                let t = k as f64 * 0.01;
                let (pos, vel) = step_response(&a, lin, t);
                max_exact = max_exact.max((s.pos - start.pos - pos).abs()).max((s.vel - vel).abs());
                max_rk4 = max_rk4.max((s.pos - x[0]).abs());
                for i in 0..100 {
                    x = rk4(&x, t + i as f64 * 1e-4, 1e-4, f);
                }
            }
            let travel = trace.last().unwrap().pos - start.pos;
            let unit = if a.stroke.is_some() { "mm" } else { "deg" };
            println!(
                "{name:5} u = {u:.3}: step response at 10 ms steps over {seconds} s ({travel:+.2} {unit}): \
                 max error vs analytic {max_exact:.2e} {unit}, vs RK4 at 0.1 ms {max_rk4:.2e} {unit}"
            );
            assert!(max_exact < 1e-12 * (1.0 + travel.abs()), "{name}: {max_exact}");
            assert!(max_rk4 < 1e-10 * (1.0 + travel.abs()), "{name}: {max_rk4}");
        }
    }
}

#[test]
fn step_size_does_not_change_the_result() {
    let a = Actuator::JIB;
    let start = AxisState { pos: 10.0, vel: 3.0 };
    let one = a.advance(&start, 2.4, 0.5);
    let many = run(&a, start, 2.4, 0.001, 0.5).pop().unwrap();
    assert!((one.pos - many.pos).abs() < 1e-11 && (one.vel - many.vel).abs() < 1e-10, "{one:?} vs {many:?}");
}

#[test]
fn nothing_moves_inside_the_deadband() {
    for (name, a) in ALL {
        let inside =
            [0.999 * a.deadband.lower, 0.5 * a.deadband.lower, 0.0, 0.5 * a.deadband.upper, 0.999 * a.deadband.upper];
        for u in inside.map(|x| a.neutral + x) {
            let start = mid(&a);
            let end = *run(&a, start, u, 0.01, 5.0).last().unwrap();
            assert_eq!(end, start, "{name} at u = {u}");
            assert_eq!(a.acceleration(&end, u), 0.0);
        }
    }
}

#[test]
fn positions_saturate_at_the_stroke_ends() {
    let a = Actuator::BASE;
    // Full extension command from 45 mm: the stroke end is reached inside a step and held.
    let c = a.plant.gain * a.linearise(3.3);
    let trace = run(&a, AxisState { pos: 45.0, vel: 0.0 }, 3.3, 0.01, 2.0);
    let end = trace.last().unwrap();
    assert_eq!(*end, AxisState { pos: 50.0, vel: 0.0 });
    assert_eq!(a.acceleration(end, 3.3), 0.0);
    assert!(trace.iter().all(|s| s.pos <= 50.0));
    // The arrival time agrees with the analytic step response reaching 5 mm.
    let arrival = trace.iter().position(|s| s.pos == 50.0).unwrap() as f64 * 0.01;
    let (mut lo, mut hi) = (0.0, 2.0);
    for _ in 0..60 {
        let t = 0.5 * (lo + hi);
        if step_response(&a, c / a.plant.gain, t).0 < 5.0 {
            lo = t;
        } else {
            hi = t;
        }
    }
    println!(
        "base: 45 → 50 mm at full command, stroke end reached at {hi:.4} s (first sample at the end: {arrival:.2} s)"
    );
    assert!(arrival >= hi && arrival < hi + 0.01);
    // A single long step lands on the same state.
    assert_eq!(a.advance(&AxisState { pos: 45.0, vel: 0.0 }, 3.3, 2.0), AxisState { pos: 50.0, vel: 0.0 });
    // Reversing the command leaves the stroke end at once, and the retracted end holds too.
    let back = a.advance(end, 0.0, 0.01);
    assert!(back.pos < 50.0 && back.vel < 0.0);
    let bottom = run(&a, back, 0.0, 0.01, 5.0).pop().unwrap();
    assert_eq!(bottom, AxisState { pos: 0.0, vel: 0.0 });
    // Arriving at speed with the command at neutral: it coasts into the end and stays there.
    let fast = a.advance(&AxisState { pos: 49.9, vel: 15.0 }, 1.65, 0.05);
    assert_eq!(fast, AxisState { pos: 50.0, vel: 0.0 });
    // A motion that would overshoot the end and come back inside one step stops at the end
    // first: one long step equals many short ones.
    let start = AxisState { pos: 49.99, vel: 15.0 };
    let touch = a.advance(&start, 0.0, 0.5);
    let fine = run(&a, start, 0.0, 1e-4, 0.5);
    let last = fine.last().unwrap();
    assert!(touch.pos < 50.0 && touch.vel < 0.0, "{touch:?}");
    assert!((touch.pos - last.pos).abs() < 1e-9 && (touch.vel - last.vel).abs() < 1e-9, "{touch:?} vs {last:?}");
    assert!(fine.iter().all(|s| s.pos <= 50.0));
}

#[test]
fn the_winch_turns_without_limit() {
    let a = Actuator::WINCH;
    let end = run(&a, AxisState::default(), 1.0, 0.01, 3.0).pop().unwrap();
    println!("winch at full duty for 3 s: {:.1} deg, {:.1} deg/s", end.pos, end.vel);
    assert!(end.pos > 2000.0);
    let reverse = run(&a, AxisState::default(), 0.0, 0.01, 3.0).pop().unwrap();
    assert!(reverse.pos < -2000.0);
}

#[test]
fn the_series_and_closed_form_of_phi2_agree() {
    let a = 10.0;
    let below = phi2(a, 0.0499999999);
    let closed = (0.0499999999 - phi1(a, 0.0499999999)) / a;
    assert!((below - closed).abs() < 1e-16, "{below} vs {closed}");
    assert_eq!(phi2(a, 0.0), 0.0);
}

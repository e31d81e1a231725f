use super::*;
use crate::crane::plant::{Commands, CraneConfig};
use crate::crane::sensors::{NoiseDraw, Potentiometer, POT_CHANNELS};
use crate::crane::MM_PER_M;
use crate::noise::NoiseStream;

const DT: f64 = 0.01;

#[test]
fn the_table_6_1_limits_add_up_to_the_hardware_range() {
    // Saturation plus the jumped deadband spans exactly 0-3.3 V (duty 0.33-0.67 for the winch).
    for p in [PidParams::BASE, PidParams::BOOM, PidParams::JIB] {
        p.validate().unwrap();
        assert!((p.neutral + p.sat_upper + p.deadband_upper - 3.3).abs() < 1e-12);
        assert!((p.neutral + p.sat_lower + p.deadband_lower).abs() < 1e-12);
    }
    let w = PidParams::WINCH;
    w.validate().unwrap();
    assert!((w.neutral + w.sat_upper + w.deadband_upper - 0.67).abs() < 1e-12);
    assert!((w.neutral + w.sat_lower + w.deadband_lower - 0.33).abs() < 1e-12);
}

#[test]
fn the_first_sample_is_proportional_only() {
    let mut pid = Pid::new(PidParams::WINCH);
    let out = pid.step(10.0, 0.0, DT);
    assert_eq!((out.proportional, out.integral, out.derivative), (0.15, 0.0, 0.0));
    // Second sample: trapezoid of the two errors, derivative of the measurement.
    let out = pid.step(10.0, 1.0, DT);
    assert!((out.integral - 0.2 * DT * 0.5 * (9.0 + 10.0)).abs() < 1e-15);
    assert!((out.derivative - (-0.00075 * 1.0 / DT)).abs() < 1e-15);
}

#[test]
fn saturation_limits_the_action() {
    let mut pid = Pid::new(PidParams::BOOM);
    let up = pid.step(100.0, 0.0, DT);
    assert_eq!(up.saturated, 1.125);
    assert_eq!(up.command, 1.65 + 1.125 + 0.525);
    let down = pid.step(-100.0, 0.0, DT);
    assert_eq!(down.saturated, -1.505);
    assert!((down.command - 0.0).abs() < 1e-15);
}

#[test]
fn the_integral_does_not_wind_up_while_saturated() {
    // A winch held far from its set-point: the P action alone (0.015 · 50) saturates.
    let mut pid = Pid::new(PidParams::WINCH);
    let outputs: Vec<PidOutput> = (0..500).map(|_| pid.step(50.0, 0.0, DT)).collect();
    for o in &outputs[1..] {
        // Each sample's integral is one trapezoid step, K_i Δt e = 0.1, never more.
        assert!((o.integral - 0.2 * DT * 50.0).abs() < 1e-15, "the integral moved: {}", o.integral);
        assert_eq!(o.saturated, 0.17);
    }
    // Without anti-windup it would be 0.2 · 50 · 5 s = 50 duty after 5 s. When the error
    // reverses, the action leaves saturation at once.
    let back = pid.step(-20.0, 0.0, DT);
    assert!(back.saturated < 0.0, "reversed action {}", back.saturated);
}

#[test]
fn anti_windup_removes_the_excess_from_the_integral_but_never_reverses_it() {
    let p = PidParams::WINCH;
    // Within the limits: the integral as it is (eq. 6.9 reduces to u_aw = u_i).
    assert_eq!(p.anti_windup(0.05, 0.1), 0.1);
    // PI action 0.25 above the 0.17 limit by 0.08: the integral gives up the excess.
    assert!((p.anti_windup(0.05, 0.2) - 0.12).abs() < 1e-15);
    assert!((p.anti_windup(-0.05, -0.2) - (-0.1035)).abs() < 1e-15);
    // The proportional action alone saturates: the integral goes to zero, not to sat − u_p.
    assert_eq!(p.anti_windup(0.5, 0.1), 0.0);
    assert_eq!(p.anti_windup(0.5, -0.1), -0.1);
    assert_eq!(p.anti_windup(-0.5, 0.1), 0.1);
    // A P-only actuator that saturates keeps no integral.
    let mut pid = Pid::new(PidParams::BASE);
    for _ in 0..10 {
        assert_eq!(pid.step(30.0, 0.0, DT).integral, 0.0);
    }
    assert_eq!(pid.step(0.5, 0.0, DT).saturated, 0.3);
}

#[test]
fn the_deadband_jump_follows_eq_6_11() {
    let p = PidParams::BOOM;
    assert_eq!(p.jump(0.005), 0.005 + 0.525);
    assert_eq!(p.jump(0.0049), 0.0);
    assert_eq!(p.jump(-0.0049), 0.0);
    assert_eq!(p.jump(0.0), 0.0);
    assert_eq!(p.jump(-0.005), -0.005 - 0.145);
    assert_eq!(p.jump(1.125), 1.65);
    let w = PidParams::WINCH;
    assert_eq!(w.jump(0.0035), 0.0035);
    assert_eq!(w.jump(-0.0035), -0.0035 - 0.0165);
    assert_eq!(w.jump(0.003), 0.0);
}

#[test]
fn the_error_deadband_zeroes_small_errors() {
    let mut pid = Pid::new(PidParams::BASE);
    let inside = pid.step(10.0, 9.76, DT);
    assert_eq!((inside.error, inside.command), (0.0, 1.65));
    let outside = pid.step(10.0, 9.74, DT);
    assert!((outside.error - 0.26).abs() < 1e-12);
    assert!((outside.command - (1.65 + 0.6 * 0.26 + 0.145)).abs() < 1e-12);
}

#[test]
fn the_derivative_acts_on_the_measurement_only() {
    // A reference step gives no derivative kick.
    let mut pid = Pid::new(PidParams::WINCH);
    pid.step(0.0, 0.0, DT);
    let out = pid.step(30.0, 0.0, DT);
    assert_eq!(out.derivative, 0.0);
}

/// Closed loop on the crane plant (actuator transfer function, deadband, stroke) with the
/// potentiometer as feedback: each actuator steps by `step_mm` from mid-stroke.
fn step_response(axis: usize, step_mm: f64, seconds: f64) -> Vec<f64> {
    let config = CraneConfig::default();
    let start = [0.025, 0.025, 0.025];
    let mut state = config.initial_state(start, 0.7).unwrap();
    let params = [PidParams::BASE, PidParams::BOOM, PidParams::JIB][axis];
    let mut pid = Pid::new(params);
    let pot = Potentiometer::default();
    let target = start[axis] * MM_PER_M + step_mm;
    let mut trace = Vec::new();
    for _ in 0..(seconds / DT).round() as usize {
        let measured = pot.extension(pot.read(
            state.extensions()[axis],
            POT_CHANNELS[axis],
            NoiseDraw::Off,
            &mut NoiseStream::default(),
        )) * MM_PER_M;
        let mut cmd = Commands::default();
        cmd.volts[axis] = pid.step(target, measured, DT).command;
        state = config.advance(&state, &cmd, DT);
        trace.push(state.actuators[axis].pos);
    }
    trace
}

#[test]
fn each_actuator_tracks_a_step_without_overshoot_beyond_the_deadband() {
    // Bound: the error deadband (0.25 mm) plus one potentiometer count (0.012 mm). The base
    // actuator, the slowest (a = 13.8 1/s), coasts a little past it on steps of 5 mm and more
    // with the Table 6.1 gain: its bound there is the deadband plus 0.1 mm.
    for (axis, name) in ["base", "boom", "jib"].iter().enumerate() {
        for step in [-20.0, -10.0, -5.0, -2.0, -0.5, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0] {
            let trace = step_response(axis, step, 5.0);
            let target = 25.0 + step;
            let overshoot = if step > 0.0 {
                trace.iter().cloned().fold(f64::MIN, f64::max) - target
            } else {
                target - trace.iter().cloned().fold(f64::MAX, f64::min)
            };
            let settled = trace.iter().rposition(|x| (x - target).abs() > 0.3).map_or(0.0, |i| (i + 1) as f64 * DT);
            let last = trace.last().unwrap();
            println!(
                "{name} step {step:+} mm: final error {:+.3} mm, overshoot {overshoot:+.3} mm, within 0.3 mm \
                    after {settled:.2} s",
                last - target
            );
            let bound = if axis == 0 && step.abs() >= 5.0 { 0.35 } else { 0.25 + 0.0125 };
            assert!(overshoot <= bound, "{name} step {step}: overshoot {overshoot} mm");
            assert!((last - target).abs() <= 0.25 + 0.0125, "{name} step {step}: final {last} mm");
            assert!(settled < 1.5, "{name} step {step}: settles after {settled} s");
        }
    }
}

//! The delta law's angle gain over the measured length: fixed (the thesis' 0.1 m/rad at every
//! length) or scheduled with the LQR's angle coupling ([`super::super::compensation`]).

use super::*;
use crate::control::lqr::{lqr, pendulum_model};
use crate::math::STANDARD_GRAVITY;
use nalgebra::DMatrix;

/// The load swung to θx = −0.1 rad: e_θx = 0.1 rad, out of the deadband.
const THETA_X: f64 = -0.1;
/// Samples before the controller becomes active.
const LEARNING: usize = 3;
const DT: f64 = 0.01;

/// The angle gain (m/rad) a compensating controller with truth feedback and `schedule` used at
/// each sample, the measured length running through `lengths` (m) from the start, active from
/// the fourth sample; each checked against the tip set-point it commanded.
fn angle_gains(schedule: GainSchedule, lengths: &[f64]) -> Vec<f64> {
    let mut config =
        ControllerConfig { feedback: Feedback::Truth, active_from: LEARNING as f64 * DT, ..ControllerConfig::DEFAULT };
    config.compensation.schedule = schedule;
    let mut controller = Controller::new(config).unwrap();
    lengths
        .iter()
        .enumerate()
        .map(|(n, &lp)| {
            let mut u = Inputs::AT_REST;
            u.truth.lp = lp;
            u.truth.theta_x = THETA_X;
            let out = controller.step(n as f64 * DT, DT, &u).unwrap();
            let gain = controller.angle_gain();
            // Δy_t = e_y + k_θ e_θx with the tip on its set-point (eq. 6.29).
            let delta = out.commanded.tip.y - u.truth.tip.y;
            assert!((delta - gain * -THETA_X).abs() < 1e-15, "{lp} m: Δy_t {delta} is not k_θ = {gain}'s");
            gain
        })
        .collect()
}

/// K_θ(l) from the 12-state design of §6.2 (Q = 10·I12, R = I6): the entry (ÿ_t, θx).
fn full_design(lp: f64) -> f64 {
    let (a, b) = pendulum_model(lp, STANDARD_GRAVITY);
    lqr(&a, &b, &(DMatrix::identity(12, 12) * 10.0), &DMatrix::identity(6, 6)).unwrap().k[(1, 3)]
}

#[test]
fn a_scheduled_angle_gain_is_the_tuned_one_scaled_by_a_fresh_design() {
    // Before activation the tuned gain; from then on l_d = the set-point's 0.7 m although the
    // cable measures 0.4 m. Steps below 1 % of the last design's length (0.402 after 0.4, 0.995
    // after 1.0) keep that design.
    let lengths = [0.4, 0.4, 0.4, 0.4, 0.402, 0.55, 0.7, 0.85, 1.0, 0.995, 1.3, 0.25, 0.7];
    let designed_at = [0.4, 0.4, 0.4, 0.4, 0.4, 0.55, 0.7, 0.85, 1.0, 1.0, 1.3, 0.25, 0.7];
    let gains = angle_gains(GainSchedule::Length, &lengths);
    let tuned = CompensationGains::DEFAULT.angle;
    let design = full_design(Setpoint::FIXED.lp);
    for (n, ((gain, lp), at)) in gains.iter().zip(lengths).zip(designed_at).enumerate() {
        let expected = if n < LEARNING { tuned } else { tuned * full_design(at) / design };
        assert!((gain - expected).abs() < 1e-12, "sample {n}, {lp} m: k_θ {gain}, the design at {at} m {expected}");
    }
    // At the design length the tuned gain exactly; 6 % more at 0.4 m, 5 % less at 1.0 m.
    assert_eq!(gains[6], tuned);
    assert!(gains[3] > 1.05 * tuned && gains[8] < 0.96 * tuned, "{gains:?}");
}

#[test]
fn a_fixed_angle_gain_holds_while_the_length_changes() {
    let gains = angle_gains(GainSchedule::Fixed, &[0.4, 0.4, 0.4, 0.4, 0.7, 1.0, 1.3, 0.25]);
    assert!(gains.iter().all(|&k| k == CompensationGains::DEFAULT.angle), "{gains:?}");
}

#[test]
fn the_schedule_is_in_the_state_and_a_bad_one_is_refused() {
    let mut config = ControllerConfig { feedback: Feedback::Truth, ..ControllerConfig::DEFAULT };
    config.compensation.schedule = GainSchedule::Length;
    let mut controller = Controller::new(config).unwrap();
    let mut u = Inputs::AT_REST;
    u.truth.lp = 1.0;
    controller.step(0.0, DT, &u).unwrap();
    let copy = controller.clone();
    assert_eq!(copy.angle_gain(), controller.angle_gain());
    assert!(copy.angle_gain() < 0.96 * CompensationGains::DEFAULT.angle);
    let mut bad = controller;
    bad.angle_schedule.as_mut().unwrap().design.gain = 0.0;
    assert!(bad.validate().unwrap_err().contains("schedule"));
}

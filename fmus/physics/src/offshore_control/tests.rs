//! One sample of [`super::controller`] against closed forms: the anti-sway law's tip velocity
//! through the Jacobian, the saturation that keeps the direction, the winch's feedforward and the
//! arm's tip holding in W.

use super::antisway::{AntiSway, AntiSwayWeights};
use super::controller::{Heave, Measured, Mode, OffshoreConfig, OffshoreController};
use super::setpoint::SetpointSource;
use crate::control::controller::SlingConfig;
use crate::control::lqr::GainSchedule;
use crate::hydraulic_crane::plant::{DEFAULT_JOINTS, JIB, SLEW, WINCH};
use crate::math::{Vec3, STANDARD_GRAVITY};
use crate::motion::ShipMotion;

const LP: f64 = 10.0;
/// Samples 1 s apart: the spool ramp (5 1/s) does not bind, the commands are the law's.
const DT: f64 = 1.0;

/// The crane at its default start on a still deck, the load hanging at rest under the tip.
fn at_rest() -> Measured {
    let arm = &OffshoreConfig::DEFAULT.crane.arm;
    let tip = arm.tip_in_world(&ShipMotion::AT_REST, &DEFAULT_JOINTS, &[0.0; 3], &[0.0; 3]);
    Measured {
        joints: DEFAULT_JOINTS,
        lp: LP,
        ship: ShipMotion::AT_REST,
        load: tip.pos + Vec3::new(0.0, 0.0, LP),
        load_velocity: Vec3::zeros(),
        residual: Vec3::zeros(),
    }
}

/// A controller in `mode` and `heave` that has latched its references at rest.
fn latched(mode: Mode, heave: Heave) -> OffshoreController {
    let mut c = OffshoreController::new(OffshoreConfig { mode, heave, ..OffshoreConfig::DEFAULT });
    let out = c.step(&at_rest(), DT).unwrap();
    assert_eq!(out.spools, [0.0; 4], "at rest on its references nothing moves");
    c
}

#[test]
fn a_load_swung_out_draws_the_tip_after_it_at_the_lqr_gain() {
    let mut c = latched(Mode::Compensated, Heave::Winch);
    let mut m = at_rest();
    m.load.x += 0.05;
    let out = c.step(&m, DT).unwrap();
    let (law, _) = AntiSway::design(LP, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).unwrap();
    let expected = law.velocity(0.0, 0.05, 0.0);
    println!("load 50 mm out in x: tip command {:.6?} m/s, law {expected:.6} m/s", out.tip_command);
    // The Jacobian solve gives the law's horizontal velocity; vertically the tip holds in K.
    assert!((out.tip_command.x - expected).abs() < 1e-12, "{:?}", out.tip_command);
    assert!(out.tip_command.y.abs() < 1e-12 && out.tip_command.z.abs() < 1e-12, "{:?}", out.tip_command);
    assert!(!out.saturated);
    // The next sample's tip velocity (the commanded rates through the kinematics) is the command.
    let next = c.step(&m, DT).unwrap();
    assert!((next.tip_velocity - out.tip_command).norm() < 1e-12, "{:?}", next.tip_velocity);
}

#[test]
fn a_residual_adds_to_the_laws_tip_velocity_in_the_world() {
    let mut m = at_rest();
    m.load.x += 0.05;
    m.ship.vel = Vec3::new(0.1, 0.0, -0.2);
    let law_only = latched(Mode::Compensated, Heave::Arm).step(&m, DT).unwrap();
    // Heave by the arm: the tip's W velocity is commanded in all three axes.
    m.residual = Vec3::new(0.03, -0.02, 0.01);
    let with_residual = latched(Mode::Compensated, Heave::Arm).step(&m, DT).unwrap();
    let added = with_residual.tip_command - law_only.tip_command;
    println!("residual {:?} m/s: the tip command moved by {added:.6?} m/s", m.residual);
    assert!((added - m.residual).norm() < 1e-12, "{added:?}");
    // Heave by the winch: x and y in W, z in K (the deck level here, so W's z as well).
    let law_only = latched(Mode::Compensated, Heave::Winch).step(&at_rest(), DT).unwrap();
    let mut m = at_rest();
    m.residual = Vec3::new(0.03, -0.02, 0.01);
    let added = latched(Mode::Compensated, Heave::Winch).step(&m, DT).unwrap().tip_command - law_only.tip_command;
    assert!((added - m.residual).norm() < 1e-12, "{added:?}");
    // Beyond ±10 m/s (or not finite) it is refused.
    let mut c = latched(Mode::Compensated, Heave::Winch);
    for bad in [10.5, f64::NAN] {
        m.residual = Vec3::new(0.0, bad, 0.0);
        let error = c.step(&m, DT).unwrap_err();
        assert!(error.contains("residual.tip.v"), "{error}");
    }
}

/// The anti-sway gain a compensating controller with `schedule` uses as the measured hoist
/// length runs through `lengths` (the load 50 mm out in x, at rest, so the tip's command is the
/// law's k_d·0.05), each checked against the command it gave.
fn gains_along(schedule: GainSchedule, lengths: &[f64]) -> Vec<[f64; 3]> {
    let config = OffshoreConfig { mode: Mode::Compensated, schedule, ..OffshoreConfig::DEFAULT };
    let mut c = OffshoreController::new(config);
    c.step(&at_rest(), DT).unwrap();
    lengths
        .iter()
        .map(|&lp| {
            let mut m = at_rest();
            m.lp = lp;
            m.load.x += 0.05;
            let out = c.step(&m, DT).unwrap();
            let law = c.antisway().unwrap();
            let expected = law.velocity(0.0, 0.05, 0.0);
            assert!((out.tip_command.x - expected).abs() < 1e-12, "{lp} m: {:?} is not this gain's", out.tip_command);
            law.gain
        })
        .collect()
}

#[test]
fn a_scheduled_gain_is_a_fresh_design_at_the_measured_length() {
    // Paying out 10 → 30 m, hauling in to 5 m and back to 10 m; steps below 1 % of the last
    // design's length (10.05 after 10, 29.8 after 30) keep that design.
    let lengths = [10.0, 10.05, 12.0, 20.0, 30.0, 29.8, 17.3, 5.0, 5.04, 7.5, 10.0];
    let designed_at = [10.0, 10.0, 12.0, 20.0, 30.0, 30.0, 17.3, 5.0, 5.0, 7.5, 10.0];
    let gains = gains_along(GainSchedule::Length, &lengths);
    for ((gain, lp), at) in gains.iter().zip(lengths).zip(designed_at) {
        let (fresh, _) = AntiSway::design(at, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).unwrap();
        for (k, f) in gain.iter().zip(fresh.gain) {
            assert!((k - f).abs() < 1e-12, "measured {lp} m: {gain:?}, the design at {at} m {:?}", fresh.gain);
        }
    }
    // The gain does change with the length: k_w is 2.01 s at 10 m, 2.86 s at 30 m.
    assert!(gains[4][2] - gains[0][2] > 0.8, "{gains:?}");
}

#[test]
fn a_fixed_gain_keeps_the_latched_design_while_the_length_changes() {
    let (latched, _) = AntiSway::design(LP, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).unwrap();
    for gain in gains_along(GainSchedule::Fixed, &[10.0, 12.0, 30.0, 5.0]) {
        assert_eq!(gain, latched.gain);
    }
}

#[test]
fn a_saturated_arm_keeps_the_direction_of_its_tip() {
    let openings = |offset: Vec3| {
        let mut c = latched(Mode::Compensated, Heave::Winch);
        let mut m = at_rest();
        m.load += offset;
        c.step(&m, DT).unwrap()
    };
    let small = openings(Vec3::new(0.02, -0.01, 0.0));
    let large = openings(Vec3::new(2.0, -1.0, 0.0));
    assert!(!small.saturated && large.saturated);
    let largest = large.openings[..3].iter().fold(0.0f64, |m, o| m.max(o.abs()));
    assert!((largest - 1.0).abs() < 1e-12, "{:?}", large.openings);
    // The saturated openings are the small ones scaled by one factor.
    let scale = large.openings[SLEW] / small.openings[SLEW];
    for drive in [SLEW, 1, JIB] {
        let ratio = large.openings[drive] / small.openings[drive];
        assert!((ratio / scale - 1.0).abs() < 1e-9, "drive {drive}: {:?} vs {:?}", large.openings, small.openings);
    }
}

#[test]
fn the_winch_pays_out_what_the_deck_lifts_the_tip() {
    let mut c = latched(Mode::Positioning, Heave::Winch);
    let mut m = at_rest();
    // The deck rolling at 0.05 rad/s and heaving up at 0.3 m/s: the tip's W velocity is the
    // rigid body's at the tip, the rope rate its negative z (the load keeps its height).
    m.ship.vel = Vec3::new(0.0, 0.0, -0.3);
    m.ship.omega = Vec3::new(0.05, 0.0, 0.0);
    let out = c.step(&m, DT).unwrap();
    let arm = &OffshoreConfig::DEFAULT.crane.arm;
    let tip = arm.tip_in_world(&m.ship, &m.joints, &[0.0; 3], &[0.0; 3]);
    assert!((out.rope_rate + tip.vel.z).abs() < 1e-12, "rope {} m/s, tip ż {} m/s", out.rope_rate, tip.vel.z);
    assert!((out.rope_rate - 0.3).abs() > 0.05, "the roll moves the tip as well: {}", out.rope_rate);
    // Feedback: a load 0.1 m low (z down) is hoisted at k_z · 0.1 m.
    let mut low = at_rest();
    low.lp += 0.1;
    let out = c.step(&low, DT).unwrap();
    assert!((out.rope_rate + OffshoreConfig::DEFAULT.heave_gain * 0.1).abs() < 1e-12, "{}", out.rope_rate);
    assert!(out.spools[WINCH] < 0.0, "hoisting is a negative winch spool");
}

#[test]
fn the_arm_holds_the_tip_in_the_world_against_the_heave() {
    let mut c = latched(Mode::Compensated, Heave::Arm);
    let mut m = at_rest();
    m.ship.vel = Vec3::new(0.0, 0.0, -0.2);
    let out = c.step(&m, DT).unwrap();
    // On its reference the tip is commanded to stand still in W: the arm moves down at 0.2 m/s
    // in K; the winch holds its length.
    assert!(out.tip_command.norm() < 1e-12, "{:?}", out.tip_command);
    assert_eq!(out.rope_rate, 0.0);
    let next = c.step(&m, DT).unwrap();
    assert!(next.tip_velocity.norm() < 1e-12, "the deck's 0.2 m/s and the arm's cancel: {:?}", next.tip_velocity);
}

/// A controller in `mode` and `heave` on the pick-and-place profile, latched at rest, and the
/// measurements of a crane exactly on the profile `t` s after the latch (the joints the moved
/// tip's inverse kinematics, the load hanging under it and moving with it).
fn on_the_profile(mode: Mode, heave: Heave) -> (OffshoreController, impl Fn(f64) -> Measured) {
    let config = OffshoreConfig { mode, heave, setpoint: SetpointSource::PickAndPlace, ..OffshoreConfig::DEFAULT };
    let mut c = OffshoreController::new(config);
    c.step(&at_rest(), DT).unwrap();
    let arm = OffshoreConfig::DEFAULT.crane.arm;
    let tip = arm.tip_in_base(&DEFAULT_JOINTS, &[0.0; 3], &[0.0; 3]).pos;
    let measured = move |t: f64| {
        let d = SetpointSource::PickAndPlace.displacement(t).unwrap();
        let joints = arm.inverse_kinematics(&(tip + d.tip)).unwrap();
        let lp = LP + d.lp;
        let tip = arm.tip_in_world(&ShipMotion::AT_REST, &joints, &[0.0; 3], &[0.0; 3]);
        Measured { joints, lp, load: tip.pos + Vec3::new(0.0, 0.0, lp), load_velocity: d.tip_rate, ..at_rest() }
    };
    (c, measured)
}

#[test]
fn on_the_pick_and_place_profile_the_joints_and_the_winch_follow_it_with_its_rates_fed_forward() {
    let (mut c, measured) = on_the_profile(Mode::Positioning, Heave::None);
    let start = c.clone().step(&at_rest(), DT).unwrap().load_setpoint;
    // One sample a second: τ = 1 … 300 s, through the pick (50–125 s) to the middle of the move.
    for k in 1..=300 {
        let t = k as f64 * DT;
        let (m, d) = (measured(t), SetpointSource::PickAndPlace.displacement(t).unwrap());
        let out = c.step(&m, DT).unwrap();
        // On its references the winch pays out at the profile's rate, the set-point moves by Δ.
        assert!((out.rope_rate - d.lp_rate).abs() < 1e-12, "t = {t}: {} vs {}", out.rope_rate, d.lp_rate);
        let moved = out.load_setpoint - start;
        assert!((moved - Vec3::new(d.tip.x, 0.0, d.lp)).norm() < 1e-12, "t = {t}: {moved:?}");
    }
    // Half way through the move the tip runs at the profile's peak, −1.875 · 5 m / 150 s.
    let m = measured(300.0);
    let next = c.step(&m, DT).unwrap();
    assert!((next.tip_velocity - Vec3::new(-0.0625, 0.0, 0.0)).norm() < 1e-12, "{:?}", next.tip_velocity);
}

#[test]
fn on_the_pick_and_place_profile_the_compensating_tip_runs_at_the_profiles_velocity() {
    let (mut c, measured) = on_the_profile(Mode::Compensated, Heave::Winch);
    for k in 1..300 {
        c.step(&measured(k as f64 * DT), DT).unwrap();
    }
    // On the reference, the load under the tip and moving with it: the anti-sway law adds nothing
    // (it regulates the load's velocity relative to the set-point's).
    let out = c.step(&measured(300.0), DT).unwrap();
    assert!((out.tip_command - Vec3::new(-0.0625, 0.0, 0.0)).norm() < 1e-12, "{:?}", out.tip_command);
}

#[test]
fn the_modes_are_checked_and_bad_measurements_refused() {
    let config = OffshoreConfig { heave: Heave::Arm, ..OffshoreConfig::DEFAULT };
    assert!(config.validate().unwrap_err().contains("needs mode = 2"));
    let mut c = OffshoreController::new(OffshoreConfig::DEFAULT);
    let mut m = at_rest();
    m.ship.omega.y = f64::INFINITY;
    assert!(c.step(&m, DT).unwrap_err().contains("ship.w"));
    m = at_rest();
    m.lp = 0.0;
    assert!(c.step(&m, DT).unwrap_err().contains("lp must be > 0"));
    let config = OffshoreConfig { heave_gain: -1.0, ..OffshoreConfig::DEFAULT };
    assert!(config.validate().unwrap_err().contains("heave_gain"));
}

#[test]
fn the_spools_ramp_at_the_amplifiers_rate() {
    let mut c = latched(Mode::Compensated, Heave::Winch);
    let mut m = at_rest();
    m.load.x += 2.0;
    let dt = 0.01;
    let limit = OffshoreConfig::DEFAULT.spool_rate * dt;
    let target = latched(Mode::Compensated, Heave::Winch).step(&m, DT).unwrap().spools;
    let mut last = [0.0; 4];
    for k in 1..=100 {
        let spools = c.step(&m, dt).unwrap().spools;
        for drive in 0..4 {
            let change = spools[drive] - last[drive];
            assert!(change.abs() <= limit + 1e-15, "sample {k}, drive {drive}: {change}");
            let expected = (k as f64 * limit).min(target[drive].abs()) * target[drive].signum();
            assert!(
                (spools[drive] - expected).abs() < 1e-12,
                "sample {k}, drive {drive}: {spools:?} toward {target:?}"
            );
        }
        last = spools;
    }
}

/// The amplitude (m/s) of the tip's x command over the last `tail` samples when the load swings
/// 1 mm in x at `omega` (rad/s) about its rest under the tip, with the controller knowing a
/// `sling` (m) of the full-scale rigging (300 kg hook, 5 t load).
fn tip_command_amplitude(omega: f64, sling: f64) -> f64 {
    let config = OffshoreConfig {
        mode: Mode::Compensated,
        sling: SlingConfig { length: sling, ..OffshoreConfig::DEFAULT.sling },
        ..OffshoreConfig::DEFAULT
    };
    let mut c = OffshoreController::new(config);
    let dt = 0.01;
    let (samples, tail) = (6000, 1000);
    let mut peak: f64 = 0.0;
    for k in 0..samples {
        let t = k as f64 * dt;
        let mut m = at_rest();
        m.load.x += 1e-3 * (omega * t).sin();
        m.load_velocity.x = 1e-3 * omega * (omega * t).cos();
        let out = c.step(&m, dt).unwrap();
        if k >= samples - tail {
            peak = peak.max(out.tip_command.x.abs());
        }
    }
    peak
}

#[test]
fn with_a_sling_the_law_ignores_the_hook_load_mode_and_still_acts_on_the_swing() {
    let sling = SlingConfig { length: 3.0, ..OffshoreConfig::DEFAULT.sling };
    let second = sling.hook_load_mode(LP, STANDARD_GRAVITY);
    let swing = (STANDARD_GRAVITY / (LP + 3.0)).sqrt();
    // The double pendulum's modes for 300 kg over 5 t on 10 m + 3 m (Landau & Lifshitz §23).
    println!("hook-load mode {second:.3} rad/s, swing about {swing:.3} rad/s");
    assert!((7.0..10.0).contains(&second), "{second}");
    let [mode_off, mode_on] = [0.0, 3.0].map(|s| tip_command_amplitude(second, s));
    let [swing_off, swing_on] = [0.0, 3.0].map(|s| tip_command_amplitude(swing, s));
    println!("tip command at the mode {mode_off:.3e} -> {mode_on:.3e} m/s, at the swing {swing_off:.3e} -> {swing_on:.3e} m/s");
    // Without the sling the law feeds the mode back in full; the notch takes out 99 % of it and
    // passes the swing, 12 times lower in frequency, within 2 %.
    assert!(mode_on < 0.01 * mode_off, "{mode_on} vs {mode_off}");
    assert!((swing_on / swing_off - 1.0).abs() < 0.02, "{swing_on} vs {swing_off}");
    let bad = OffshoreConfig { sling: SlingConfig { hook_fraction: 1.5, ..sling }, ..OffshoreConfig::DEFAULT };
    assert!(bad.validate().unwrap_err().contains("sling: the hook's share"));
}

//! The controller in a closed loop with the crane plant, the pendulum and two IMUs (the physics
//! models, no FMUs), stepped in the order of the co-simulation: ship, crane, pendulum, IMUs,
//! controller; the commands act over the next step.

use super::*;
use crate::crane::motion::tip_in_world;
use crate::crane::plant::{CraneConfig, CraneState, DEFAULT_POSE};
use crate::crane::sensors::{Encoder, NoiseDraw, POT_CHANNELS};
use crate::imu::{readings, ImuMotion, ImuParams};
use crate::motion::ShipMotion;
use crate::noise::NoiseStream;
use crate::pendulum::{self, PendulumParams, Swing, TipMotion};
use crate::platform::kinematics::PlatformGeometry;
use crate::ship::profiles::{test_scale, ProfileId};
use crate::ship::rao::Hull;

const H: f64 = 0.01;
const DEG: f64 = std::f64::consts::PI / 180.0;

/// The test rig: every model's state and the commands in force.
struct Rig {
    crane: CraneConfig,
    crane_state: CraneState,
    pendulum: PendulumParams,
    swing: Swing,
    /// The load is held at its initial angles until this time (s).
    release: f64,
    /// Ship roll amplitude (rad) and angular frequency (rad/s): roll = A sin ωt.
    roll: (f64, f64),
    imu1: ImuParams,
    imu2: ImuParams,
    noise: bool,
    commands: Commands,
    controller: Controller,
}

/// Per-sample record: time, true load position and angles, and the controller's outputs.
struct Sample {
    t: f64,
    load: Vec3,
    tip: Vec3,
    swing: Swing,
    out: Outputs,
}

impl Rig {
    fn new(config: ControllerConfig, theta_x0: f64, theta_y0: f64, noise: bool) -> Rig {
        let crane = CraneConfig::default();
        Rig {
            crane,
            crane_state: crane.initial_state(DEFAULT_POSE.extensions, DEFAULT_POSE.lp).unwrap(),
            pendulum: PendulumParams::default(),
            swing: Swing { theta_x: theta_x0, theta_y: theta_y0, ..Swing::default() },
            release: config.active_from,
            roll: (0.0, 0.0),
            imu1: ImuParams { seed: 1, noise, ..ImuParams::default() },
            imu2: ImuParams { seed: 2, noise, ..ImuParams::default() },
            noise,
            commands: Commands::default(),
            controller: Controller::new(config).unwrap(),
        }
    }

    fn ship(&self, t: f64) -> ShipMotion {
        let (a, w) = self.roll;
        ShipMotion {
            roll: a * (w * t).sin(),
            omega: Vec3::new(a * w * (w * t).cos(), 0.0, 0.0),
            alpha: Vec3::new(-a * w * w * (w * t).sin(), 0.0, 0.0),
            ..ShipMotion::default()
        }
    }

    fn run(&mut self, seconds: f64) -> Vec<Sample> {
        let n = (seconds / H).round() as u64;
        let mut samples = Vec::new();
        for k in 0..=n {
            let t = k as f64 * H;
            let ship = self.ship(t);
            let chain = self.crane.motion(&self.crane_state, &self.commands).unwrap();
            let tip = tip_in_world(&ship, &chain);
            let u = TipMotion {
                pos: tip.pos,
                vel: tip.vel,
                acc: tip.acc,
                lp: chain.lp.pos,
                lp_dot: chain.lp.vel,
                lp_ddot: chain.lp.acc,
            };
            let held = t < self.release;
            let load = if held {
                pendulum::load_kinematics(&self.pendulum, &self.swing, &u, (0.0, 0.0))
            } else {
                pendulum::load_motion(&self.pendulum, &self.swing, &u)
            };
            let imu1 = readings(
                &self.imu1,
                &ImuMotion { orientation: ship.attitude(), angular_velocity: ship.omega, acceleration: ship.acc },
                k,
            );
            let imu2 = readings(
                &self.imu2,
                &ImuMotion {
                    orientation: load.orientation,
                    angular_velocity: load.angular_velocity,
                    acceleration: load.acc,
                },
                k,
            );
            let draw = if self.noise { NoiseDraw::On { seed: 3, k } } else { NoiseDraw::Off };
            let d = self.crane_state.extensions();
            let inputs = Inputs {
                pots: [0, 1, 2].map(|i| {
                    self.controller.config.potentiometer.read(d[i], POT_CHANNELS[i], draw, &mut NoiseStream::default())
                }),
                encoder: Encoder::default().read(self.crane_state.winch.pos, draw, &mut NoiseStream::default()),
                imu1,
                imu2,
                ship_position: ship.pos,
                truth: Truth {
                    tip: tip.pos,
                    lp: chain.lp.pos,
                    theta_x: self.swing.theta_x,
                    theta_y: self.swing.theta_y,
                    ship: [ship.roll, ship.pitch, ship.yaw],
                },
                external: Setpoint::FIXED,
                residual: Vec3::zeros(),
            };
            let out = self.controller.step(t, H, &inputs).unwrap();
            samples.push(Sample { t, load: load.pos, tip: tip.pos, swing: self.swing, out });
            // Advance every model over [t, t + h] with the new commands.
            self.commands = out.commands;
            if !held {
                self.swing = pendulum::advance(&self.pendulum, &self.swing, &u, &TipMotion::default(), H).unwrap();
            }
            self.crane_state = self.crane.advance(&self.crane_state, &self.commands, H);
        }
        samples
    }
}

fn config(mode: Mode, feedback: Feedback, active_from: f64) -> ControllerConfig {
    ControllerConfig { mode, feedback, active_from, ..ControllerConfig::default() }
}

/// Largest |θx| and |θy| over the samples after `from` seconds.
fn peak_angles(samples: &[Sample], from: f64) -> (f64, f64) {
    samples
        .iter()
        .filter(|s| s.t >= from)
        .fold((0.0, 0.0), |(x, y), s| (f64::max(x, s.swing.theta_x.abs()), f64::max(y, s.swing.theta_y.abs())))
}

#[test]
fn hold_mode_and_the_initialisation_period_issue_neutral_commands() {
    let mut rig = Rig::new(config(Mode::Hold, Feedback::Sensors, 0.0), -13.0 * DEG, 0.0, true);
    assert!(rig.run(3.0).iter().all(|s| s.out.commands == Commands::default() && !s.out.active));
    let mut rig = Rig::new(config(Mode::Compensated, Feedback::Sensors, 2.0), -13.0 * DEG, 0.0, true);
    let samples = rig.run(2.5);
    assert!(samples
        .iter()
        .filter(|s| s.t < 2.0 - 1e-9)
        .all(|s| s.out.commands == Commands::default() && !s.out.active));
    assert!(samples.iter().filter(|s| s.t >= 2.0 - 1e-9).all(|s| s.out.active));
}

#[test]
fn at_rest_at_the_set_point_the_actuators_stay_still() {
    let mut rig = Rig::new(config(Mode::Compensated, Feedback::Sensors, 0.0), 0.0, 0.0, false);
    let samples = rig.run(5.0);
    let last = samples.last().unwrap();
    let drift = (last.tip - Setpoint::FIXED.tip).norm();
    println!(
        "compensated, load hanging still: tip {:.3} mm from the set-point after 5 s, length {:.4} m \
            (controller drum 41.32 mm, plant 41.26 mm)",
        drift * 1000.0,
        last.out.lp
    );
    for s in &samples {
        assert_eq!(s.out.commands.volts, [1.65; 3], "t = {}: {:?}", s.t, s.out.commands);
    }
    assert!(drift < 1e-4);
}

#[test]
fn the_estimates_follow_a_swinging_load() {
    // Sensor feedback, §8.1 noise, the load held at θx = −13° for 10 s, then released; the
    // controller in hold mode only estimates.
    let mut rig = Rig::new(config(Mode::Hold, Feedback::Sensors, 10.0), -13.0 * DEG, 0.0, true);
    let samples = rig.run(40.0);
    let after: Vec<&Sample> = samples.iter().filter(|s| s.t >= 10.0).collect();
    let rms =
        |f: &dyn Fn(&Sample) -> f64| (after.iter().map(|s| f(s).powi(2)).sum::<f64>() / after.len() as f64).sqrt();
    let theta = rms(&|s| (s.out.theta_x - s.swing.theta_x).hypot(s.out.theta_y - s.swing.theta_y));
    let load = rms(&|s| (s.out.load - s.load).norm());
    let held = &samples[999];
    println!(
        "hold, sensors, 30 s after release from θx = −13°: angle error RMS {:.2}° (1 Hz low-pass lag \
            included), load position error RMS {:.1} mm; before release θx = {:.2}°",
        theta / DEG,
        load * 1000.0,
        held.out.theta_x / DEG
    );
    assert!((held.out.theta_x + 13.0 * DEG).abs() < 0.5 * DEG, "aligned on the held load");
    assert!(theta < 6.0 * DEG && load < 0.06);
}

#[test]
fn compensation_damps_the_swing() {
    // Test 060-like: l_p = 0.7 m, θx0 = −13° (and θy0 = 13°), 10 s initialisation, 30 s after
    // release. Compensated runs must end with a fraction of the uncompensated swing.
    for (name, theta_x0, theta_y0) in [("θx", -13.0 * DEG, 0.0), ("θy", 0.0, 13.0 * DEG)] {
        let mut off = Rig::new(config(Mode::Hold, Feedback::Truth, 10.0), theta_x0, theta_y0, false);
        let (off_x, off_y) = peak_angles(&off.run(40.0), 35.0);
        for feedback in [Feedback::Truth, Feedback::Sensors] {
            let mut on =
                Rig::new(config(Mode::Compensated, feedback, 10.0), theta_x0, theta_y0, feedback == Feedback::Sensors);
            let samples = on.run(40.0);
            let (x, y) = peak_angles(&samples, 35.0);
            let limited = samples.iter().filter(|s| s.out.limited).count();
            println!(
                "{name}0 = 13°, {feedback:?} feedback: peak |θx|, |θy| over 35-40 s {:.2}°, {:.2}° (crane \
                    off: {:.2}°, {:.2}°); {limited} limited samples",
                x / DEG,
                y / DEG,
                off_x / DEG,
                off_y / DEG
            );
            assert!(x.hypot(y) < 0.3 * off_x.hypot(off_y), "{name}, {feedback:?}: no damping");
        }
    }
}

#[test]
fn inverse_kinematic_control_holds_the_tip_in_the_world_while_the_ship_rolls() {
    // Roll ±3° at 0.8 rad/s: the tip (0.5 m from the roll axis, 0.15 m above it) moves by
    // several mm with the crane off; world-frame IK tracking keeps it near the set-point.
    let mut deviation = Vec::new();
    for (mode, feedback) in [
        (Mode::Hold, Feedback::Truth),
        (Mode::InverseKinematics, Feedback::Truth),
        (Mode::InverseKinematics, Feedback::Sensors),
    ] {
        let mut rig = Rig::new(config(mode, feedback, 0.0), 0.0, 0.0, feedback == Feedback::Sensors);
        rig.roll = (3.0 * DEG, 0.8);
        let samples = rig.run(30.0);
        let rms = (samples[1000..].iter().map(|s| (s.tip - Setpoint::FIXED.tip).norm_squared()).sum::<f64>()
            / (samples.len() - 1000) as f64)
            .sqrt();
        let roll_error =
            samples[1000..].iter().map(|s| (s.out.ship[0] - 3.0 * DEG * (0.8 * s.t).sin()).abs()).fold(0.0, f64::max);
        println!(
            "ship rolling ±3°: {mode:?}/{feedback:?} tip RMS deviation from the set-point {:.2} mm (roll \
            estimate max error {:.2}°)",
            rms * 1000.0,
            roll_error / DEG
        );
        deviation.push(rms);
    }
    assert!(deviation[1] < 0.3 * deviation[0] && deviation[2] < 0.5 * deviation[0], "{deviation:?}");
}

#[test]
fn an_unreachable_set_point_keeps_the_previous_references() {
    let mut c = config(Mode::InverseKinematics, Feedback::Truth, 0.0);
    c.setpoint = SetpointSource::External;
    let mut controller = Controller::new(c).unwrap();
    let mut inputs = Inputs { encoder: 0.0, ..Inputs::AT_REST };
    let reachable = controller.step(0.0, H, &inputs).unwrap();
    assert!(!reachable.limited);
    inputs.external.tip = Vec3::new(0.0, -3.0, 0.0);
    let out = controller.step(H, H, &inputs).unwrap();
    assert!(out.limited);
    assert_eq!(out.extensions, reachable.extensions);
    inputs.pots[0] = f64::NAN;
    assert!(controller.step(2.0 * H, H, &inputs).unwrap_err().contains("not finite"));
}

#[test]
fn a_residual_moves_the_commanded_tip_by_itself_on_top_of_the_law() {
    // Two compensated controllers fed the same swinging-load truth; one also gets a residual.
    let c = config(Mode::Compensated, Feedback::Truth, 0.0);
    let (mut plain, mut corrected) = (Controller::new(c).unwrap(), Controller::new(c).unwrap());
    let mut inputs = Inputs { encoder: 0.0, ..Inputs::AT_REST };
    inputs.truth.theta_x = 0.1;
    let law = plain.step(0.0, H, &inputs).unwrap();
    inputs.residual = Vec3::new(0.01, -0.02, 0.005);
    let out = corrected.step(0.0, H, &inputs).unwrap();
    // The law moved the tip off the set-point (eqs. 6.28-6.30); the residual adds to that.
    assert!((law.commanded.tip - law.desired.tip).norm() > 1e-3);
    assert_eq!(out.commanded.tip, law.commanded.tip + inputs.residual);
    assert_eq!(out.desired, law.desired);
    assert_ne!(out.extensions, law.extensions);
    inputs.residual.x = f64::NAN;
    assert!(corrected.step(H, H, &inputs).unwrap_err().contains("not finite"));
}

#[test]
fn a_gyro_reading_beyond_any_sensor_is_refused_not_integrated_into_a_nan() {
    let mut controller = Controller::new(config(Mode::Hold, Feedback::Sensors, 0.0)).unwrap();
    let mut inputs = Inputs { encoder: 0.0, ..Inputs::AT_REST };
    controller.step(0.0, H, &inputs).unwrap();
    inputs.imu2.gyro = Vec3::new(f64::MAX, f64::MAX, 0.0);
    let error = controller.step(H, H, &inputs).unwrap_err();
    assert!(error.contains("beyond ±1e6"), "{error}");
    // A reading just inside the bound is taken, and the attitude stays finite.
    inputs.imu2.gyro = Vec3::new(1e6, -1e6, 1e6);
    controller.step(2.0 * H, H, &inputs).unwrap();
}

#[test]
fn pick_and_place_tracks_the_profile() {
    let mut c = config(Mode::Compensated, Feedback::Truth, 1.0);
    c.setpoint = SetpointSource::PickAndPlace;
    let mut rig = Rig::new(c, 0.0, 0.0, false);
    let samples = rig.run(121.0);
    let errors: Vec<f64> =
        samples.iter().filter(|s| s.t >= 1.0).map(|s| (s.load - s.out.desired.load()).norm()).collect();
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    let worst = errors.iter().cloned().fold(0.0, f64::max);
    println!(
        "pick and place, compensated, truth feedback: load tracking RMS {:.1} mm, max {:.1} mm",
        rms * 1000.0,
        worst * 1000.0
    );
    assert!(samples.iter().all(|s| !s.out.limited));
    assert!(rms < 0.02);
}

/// A state decoded from bytes may carry joint limits no configuration allowed (the PIDs keep a
/// copy of theirs); `validate` finds them before `step` would clamp with min > max and panic.
#[test]
fn validate_checks_the_copies_of_the_pid_limits() {
    let mut c = Controller::new(ControllerConfig::DEFAULT).unwrap();
    c.validate().unwrap();
    c.pids[2].params.sat_lower = 1.0;
    assert_eq!(c.validate().unwrap_err(), "jib PID: saturation limits must bracket 0, got 1 and 1.475");
}

/// RMS errors of the controller's surge/sway/heave (EKF, [`Feedback::Estimated`]) and their
/// rates against the truth of the test-scale profile `id`, relative to the motion's RMS, over
/// [`EKF_FROM`]–[`EKF_TO`] s: `[positions, rates]`, x, y, z; NaN on an axis the profile leaves
/// still. The deck IMU (SPEC §8.1 noise, seed 1) moves with the profile from t = 0; the crane
/// is off; the truth positions' mean over the span is removed (the EKF estimates the oscillating
/// part, eq. 5.46 without v(t)).
fn ekf_errors(id: ProfileId, attitude: AttitudeFilterKind) -> [[f64; 3]; 2] {
    let full = id.profile().full_scale(&Hull::default(), id.profile().seed);
    let motion = test_scale(&full, &PlatformGeometry::default()).unwrap().motion;
    let imu = ImuParams { seed: 1, ..ImuParams::default() };
    let config = ControllerConfig { attitude, ..config(Mode::Hold, Feedback::Estimated, 10.0) };
    let mut controller = Controller::new(config).unwrap();
    let mut samples = Vec::new();
    for k in 0..=(EKF_TO / H).round() as u64 {
        let t = k as f64 * H;
        let ship = motion.sample(t).to_ship_motion();
        let truth = ImuMotion { orientation: ship.attitude(), angular_velocity: ship.omega, acceleration: ship.acc };
        let inputs = Inputs { imu1: readings(&imu, &truth, k), ..Inputs::AT_REST };
        let out = controller.step(t, H, &inputs).unwrap();
        if t >= EKF_FROM {
            samples.push((out, ship));
        }
    }
    let rms = |values: &mut dyn Iterator<Item = f64>| {
        let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
        (sum / n as f64).sqrt()
    };
    // Error RMS over motion RMS on axis i, the truth less `offset`; NaN where the motion's RMS is
    // below `still` (m or m/s).
    let relative =
        |i: usize, estimate: fn(&Outputs) -> Vec3, truth: fn(&ShipMotion) -> Vec3, offset: f64, still: f64| {
            let motion = rms(&mut samples.iter().map(|(_, s)| truth(s)[i] - offset));
            let error = rms(&mut samples.iter().map(|(o, s)| estimate(o)[i] - (truth(s)[i] - offset)));
            if motion > still {
                error / motion
            } else {
                f64::NAN
            }
        };
    let mean = |i: usize| samples.iter().map(|(_, s)| s.pos[i]).sum::<f64>() / samples.len() as f64;
    [
        [0, 1, 2].map(|i| relative(i, |o| o.ship_position, |s| s.pos, mean(i), 1e-4)),
        [0, 1, 2].map(|i| relative(i, |o| o.ship_rate, |s| s.vel, 0.0, 1e-5)),
    ]
}

/// The span of the EKF statistics (s): from 20 s after the first window's identification.
const EKF_FROM: f64 = 40.0;
const EKF_TO: f64 = 130.0;

#[test]
fn at_test_scale_the_ekf_follows_part_of_the_heave_and_none_of_surge_and_sway() {
    // Largest heave position and rate errors relative to the motion, profiles 1–3 (measured with
    // either attitude filter: 72, 58, 90 % and 82, 57, 87 %). An estimate of zero scores 100 %,
    // so a filter that does not follow the heave fails these.
    let limits = [(0.8, 0.9), (0.65, 0.65), (0.95, 0.95)];
    for (id, (pos_limit, rate_limit)) in ProfileId::ALL.into_iter().zip(limits) {
        for attitude in [AttitudeFilterKind::Complementary, AttitudeFilterKind::Madgwick] {
            let [pos, rate] = ekf_errors(id, attitude);
            println!(
                "profile {} {attitude:?}: RMS error / motion: surge {:.0} %, sway {:.0} %, heave {:.0} %; \
                    rates {:.0} %, {:.0} %, {:.0} %",
                id.profile().number,
                100.0 * pos[0],
                100.0 * pos[1],
                100.0 * pos[2],
                100.0 * rate[0],
                100.0 * rate[1],
                100.0 * rate[2]
            );
            assert!(pos[2] < pos_limit && rate[2] < rate_limit, "{id:?} {attitude:?}: {pos:?} {rate:?}");
            // Surge and sway: the test-scale accelerations (≈ 0.002 m/s² RMS) are below what an
            // attitude error of 0.01° leaks from gravity, with either filter: no better than zero.
            for i in (0..2).filter(|&i| !pos[i].is_nan()) {
                assert!(pos[i] > 0.9, "{id:?} {attitude:?} axis {i}: {pos:?}");
            }
        }
    }
}

/// A decoded state is checked down to the EKF's own copy of its settings (a NaN window would
/// never close and the window would grow without bound).
#[test]
fn a_state_with_a_broken_ekf_is_refused() {
    let mut controller = Controller::new(config(Mode::Hold, Feedback::Estimated, 0.0)).unwrap();
    controller.step(0.0, H, &Inputs::AT_REST).unwrap();
    assert_eq!(controller.validate(), Ok(()));
    let broken = EstimatorParams { window: f64::NAN, ..EstimatorParams::TEST_SCALE };
    controller.linear = Some(LinearMotionEstimator::new(broken, H));
    assert_eq!(
        controller.validate().unwrap_err(),
        "surge/sway/heave EKF: the identification window must be > 0 s, got NaN"
    );
}

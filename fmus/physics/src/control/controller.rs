//! The myRIO software as one sampled controller (thesis Chapters 5–6, Figs. 6.1–6.2): estimation,
//! world-frame compensation, inverse kinematics and joint PID, once per sample.
//!
//! Each sample, from what the myRIO saw (Table 3.1):
//!
//! 1. Estimation (always, from the first sample): the complementary filters of §5.1.1 on IMU1
//!    (ship, Table 5.1) and IMU2 (load, Table 5.2) — or, as an alternative, Madgwick's filter —
//!    started at the identity or aligned on the
//!    first sample. The ship's yaw is learnt by a 0.005 Hz low-pass until the controller becomes
//!    active and then removed from both estimates (an artificial northern heading, §5.3/§7.2.1);
//!    optionally the load angles' offsets are learnt and removed the same way, the gyro biases
//!    are learnt at rest and removed, and the load is referenced to IMU2's own mean yaw
//!    ([`crate::estimation::calibration`]). Ship Z–Y–X and load
//!    X–Y angles (eqs. 5.35–5.37, 5.59–5.60) pass a 1 Hz low-pass.
//!    With [`Feedback::Estimated`], the deck IMU's specific force turned into W with the ship's
//!    attitude estimate (eq. 5.40) feeds the §5.1.3 EKF of surge, sway and heave
//!    ([`LinearMotionEstimator`]).
//! 2. The measured state: with sensor feedback, the tip from the potentiometers through the
//!    mechanism and crane forward kinematics, placed in W with the ship's surge/sway/heave (the
//!    truth input, as the thesis did, or the EKF's estimate) and estimated attitude (eq. 5.65),
//!    the length from the encoder (optionally counted from the initial length, §6.1) and the jib
//!    potentiometer (eqs. 3.1–3.4, controller drum 41.32 mm), the angles from the filters; with
//!    truth feedback,
//!    tip, length, angles and ship attitude from the truth inputs. The load position follows
//!    from eqs. 5.62–5.64.
//! 3. The desired set-point (fixed, pick-and-place timed from `active_from`, or external), and
//!    the commanded one: the desired itself (inverse-kinematic control) or the delta law of §6.2
//!    (compensation), its angle gain fixed or, with [`GainSchedule::Length`], scheduled over the
//!    measured length from the first active sample on ([`super::compensation`]: the LQR's angle
//!    coupling designed again whenever the length has moved by more than 1 %,
//!    [`crate::control::lqr::Scheduled`]).
//! 4. Joint references: the commanded tip through the ship pose into J12 and the inverse
//!    kinematics (clamped to the stroke; a target out of reach keeps the previous references),
//!    the length to a winch angle at the measured jib extension.
//! 5. From `active_from` on (and not in hold mode): the four PIDs of §6.1 on potentiometer
//!    millimetres and encoder degrees give the voltages and the duty; before that, or in hold
//!    mode, the commands are neutral (1.65 V, 0.5) and the PIDs start afresh when activated.

use super::compensation::{CompensationGains, Measured};
use super::joints::{extensions_for_tip, CONTROLLER_CABLE};
use super::lqr::{angle_coupling, GainSchedule, Scheduled};
use super::pid::{Pid, PidParams};
use super::setpoint::{pick_and_place, Setpoint};
use crate::crane::kinematics::tip_from_actuators;
use crate::crane::motion::CRANE_BASE;
use crate::crane::plant::{Commands, DEFAULT_POSE};
use crate::crane::sensors::Potentiometer;
use crate::crane::winch::CableModel;
use crate::crane::MM_PER_M;
use crate::estimation::attitude::{AttitudeFilter, AttitudeFilterKind};
use crate::estimation::calibration::{GyroBias, MeanAngle};
use crate::estimation::complementary::FilterParams;
use crate::estimation::euler::{cable_angles, ship_angles, ship_yaw};
use crate::estimation::filters::LowPass;
use crate::estimation::linear_motion::{world_acceleration, EstimatorParams, LinearEstimate, LinearMotionEstimator};
use crate::estimation::madgwick::MadgwickParams;
use crate::estimation::notch::Notch;
use crate::estimation::pose::{load_position, BaseFrame};
use crate::imu::ImuReadings;
use crate::math::{euler_zyx, rot_z, Quat, Vec3};
use crate::rigging::normal_modes;
use serde::{Deserialize, Serialize};

/// What the controller does with the crane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mode {
    /// Crane off: neutral commands, the actuators stay still (estimation still runs).
    Hold,
    /// World-frame inverse-kinematic tracking of the set-point, no anti-pendulum action.
    InverseKinematics,
    /// World-frame compensation with the delta law of §6.2.
    Compensated,
}

/// Where the controller's state comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Feedback {
    /// Tip, length, pendulum angles and ship attitude from the truth inputs.
    Truth,
    /// Potentiometers, encoder and the attitude filters; surge, sway and heave from the truth
    /// input (the thesis' sensor variant, §7.3).
    Sensors,
    /// As [`Feedback::Sensors`], with surge, sway and heave from the EKF of §5.1.3: no truth
    /// input is read at all.
    Estimated,
}

/// Where the desired set-point comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SetpointSource {
    Fixed,
    PickAndPlace,
    External,
}

/// Configuration (not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ControllerConfig {
    pub mode: Mode,
    pub feedback: Feedback,
    pub setpoint: SetpointSource,
    /// Time (s) from which commands are issued; the pick-and-place profile starts then.
    pub active_from: f64,
    /// The fixed set-point.
    pub fixed: Setpoint,
    /// Start the filters from the first accelerometer and magnetometer sample (true) or from
    /// the identity (false, the thesis' behaviour).
    pub align: bool,
    /// The attitude estimator of both IMUs.
    pub attitude: AttitudeFilterKind,
    /// Complementary filter parameters (ship, load).
    pub ship_filter: FilterParams,
    pub load_filter: FilterParams,
    /// Madgwick filter parameters (ship, load).
    pub ship_madgwick: MadgwickParams,
    pub load_madgwick: MadgwickParams,
    /// The surge/sway/heave EKF's settings (used with [`Feedback::Estimated`]).
    pub linear: EstimatorParams,
    /// Cut-off of the bias low-pass (Hz), §5.3.
    pub bias_cutoff: f64,
    /// Cut-off of the output-angle low-pass (Hz), §5.3; 0 = none.
    pub angle_cutoff: f64,
    /// Also learn and remove offsets of the load angles during initialisation.
    pub load_bias: bool,
    /// Learn both IMUs' gyro biases at rest during initialisation and remove them
    /// ([`crate::estimation::calibration`]).
    pub gyro_bias: bool,
    /// Turn the load estimate by IMU2's own mean yaw before `active_from` instead of IMU1's learnt
    /// yaw (assumes the load faces the deck's heading then; removes a difference between the two
    /// fields).
    pub load_heading: bool,
    /// Count the winch encoder from its first sample, offset by the angle of the initial length
    /// at the controller's nominal drum (§6.1: "the measured angle from the encoder is offset by
    /// an angle corresponding to both the initial length and the increase in length caused by
    /// extending the jib"), as the thesis' controller does (the default); false reads it as the
    /// angle from the winch home, which puts the drum mismatch's 0.145 % of the whole cable into
    /// every reading. Relative, the mismatch scales only changes of the length.
    pub relative_encoder: bool,
    /// The initial cable length (m) the relative encoder starts from; `None` takes the fixed
    /// set-point's length, which equals the initial one in every thesis test.
    pub initial_length: Option<f64>,
    pub compensation: CompensationGains,
    /// Base, boom, jib (mm → V) and winch (deg → duty) controllers.
    pub pid: [PidParams; 4],
    /// The controller's cable model (drum 41.32 mm).
    pub cable: CableModel,
    /// Origin of the crane base frame J12 in the ship frame B (m).
    pub crane_base: Vec3,
    pub potentiometer: Potentiometer,
    /// The rigging below the hook (none by default: the thesis' load on the hook).
    pub sling: SlingConfig,
}

/// A sling from the hook to the load that the controller accounts for (beyond the thesis,
/// docs/rigging.md, "A controller setting for the second mode"). The set-point's length `lp`
/// stays the hoist rope's (what the winch pays out); the load hangs `length` further down.
///
/// Why: with the load IMU on the load, a sling adds the hook–load mode (the double pendulum's
/// second normal mode, 13–14 rad/s on the thesis rig against the swing's 3–4 rad/s) to the angles
/// the delta law feeds back; the arm then drives that mode until the hook leaves its rope. The
/// notch removes it from the load angles before the §5.3 smoothing, at the mode's frequency for
/// the measured hoist length ([`crate::rigging::normal_modes`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SlingConfig {
    /// Sling length from the hook to the load (m); 0: the load on the hook, nothing changes.
    pub length: f64,
    /// The hook's share of the hanging mass, m_h/(m_h + m_l) (1); with the lengths it places the
    /// hook–load mode.
    pub hook_fraction: f64,
    /// ζ of the notch at the hook–load mode on the load IMU's angles (1); 0: no notch.
    pub notch_damping: f64,
}

impl SlingConfig {
    /// No sling. The hook fraction is the rigging FMU's default hook (0.1006 kg) under its load
    /// (0.2012 kg), the thesis' 0.3018 kg split one to two. The notch's ζ = 0.2 is the best of the
    /// sweep 0.1–1.0 over the sensor-feedback campaign with that rigging (docs/rigging.md): it turns
    /// the swing (2.9–4.2 rad/s against the mode's 13.0–14.2 rad/s) by 5–7° and keeps 99 % of it.
    pub const NONE: SlingConfig = SlingConfig { length: 0.0, hook_fraction: 1.0 / 3.0, notch_damping: 0.2 };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.length.is_finite() && self.length >= 0.0) {
            return Err(format!("the sling length must be ≥ 0 m, got {}", self.length));
        }
        if !(self.hook_fraction > 0.0 && self.hook_fraction < 1.0) {
            return Err(format!("the hook's share of the hanging mass must be in (0, 1), got {}", self.hook_fraction));
        }
        if !(self.notch_damping.is_finite() && self.notch_damping >= 0.0) {
            return Err(format!("the notch damping must be ≥ 0, got {}", self.notch_damping));
        }
        Ok(())
    }

    /// The hook–load mode's angular frequency (rad/s) below a hoist rope of `hoist` (m), gravity
    /// `g` (m/s²).
    pub fn hook_load_mode(&self, hoist: f64, g: f64) -> f64 {
        normal_modes(self.hook_fraction, 1.0 - self.hook_fraction, hoist, self.length, g).1
    }
}

default_is_const!(ControllerConfig);

impl ControllerConfig {
    /// Compensation with sensor feedback at the fixed set-point from t = 0; the thesis' filter
    /// (Tables 5.1–5.2), low-pass (§5.3), compensation (§6.2) and PID (Table 6.1) parameters; the
    /// nominal drum (§6.1); filters aligned on the first sample.
    pub const DEFAULT: ControllerConfig = ControllerConfig {
        mode: Mode::Compensated,
        feedback: Feedback::Sensors,
        setpoint: SetpointSource::Fixed,
        active_from: 0.0,
        fixed: Setpoint::FIXED,
        align: true,
        attitude: AttitudeFilterKind::Complementary,
        ship_filter: FilterParams::SHIP,
        load_filter: FilterParams::LOAD,
        ship_madgwick: MadgwickParams::SPEC_NOISE,
        load_madgwick: MadgwickParams::SPEC_NOISE,
        linear: EstimatorParams::TEST_SCALE,
        bias_cutoff: 0.005,
        angle_cutoff: 1.0,
        load_bias: false,
        gyro_bias: false,
        load_heading: false,
        relative_encoder: true,
        initial_length: None,
        compensation: CompensationGains::DEFAULT,
        pid: [PidParams::BASE, PidParams::BOOM, PidParams::JIB, PidParams::WINCH],
        cable: CONTROLLER_CABLE,
        crane_base: CRANE_BASE,
        potentiometer: Potentiometer::DEFAULT,
        sling: SlingConfig::NONE,
    };

    pub fn validate(&self) -> Result<(), String> {
        self.ship_filter.validate().map_err(|e| format!("ship filter: {e}"))?;
        self.load_filter.validate().map_err(|e| format!("load filter: {e}"))?;
        self.ship_madgwick.validate().map_err(|e| format!("ship Madgwick filter: {e}"))?;
        self.load_madgwick.validate().map_err(|e| format!("load Madgwick filter: {e}"))?;
        self.linear.validate().map_err(|e| format!("surge/sway/heave EKF: {e}"))?;
        for (name, p) in ["base", "boom", "jib", "winch"].iter().zip(&self.pid) {
            p.validate().map_err(|e| format!("{name} PID: {e}"))?;
        }
        self.cable.validate()?;
        self.sling.validate().map_err(|e| format!("sling: {e}"))?;
        if !(self.bias_cutoff >= 0.0 && self.angle_cutoff >= 0.0) {
            return Err("low-pass cut-off frequencies must be ≥ 0 Hz".into());
        }
        let c = &self.compensation;
        if ![c.position, c.angle, c.position_deadband, c.angle_deadband].iter().all(|v| v.is_finite()) {
            return Err("compensation gains must be finite".into());
        }
        if !(self.fixed.tip.iter().all(|v| v.is_finite()) && self.fixed.lp > 0.0) {
            return Err(format!("the fixed set-point needs a finite tip and a length > 0, got {:?}", self.fixed));
        }
        if let Some(l) = self.initial_length {
            if !(l.is_finite() && l > 0.0) {
                return Err(format!("the encoder's initial cable length must be > 0 m, got {l}"));
            }
        }
        if !(self.active_from.is_finite() && self.crane_base.iter().all(|v| v.is_finite())) {
            return Err("active_from and the crane base offset must be finite".into());
        }
        Ok(())
    }
}

/// The truth supplied for the truth-feedback variant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    /// Tip position (m, W).
    pub tip: Vec3,
    pub lp: f64,
    pub theta_x: f64,
    pub theta_y: f64,
    /// Ship roll, pitch, yaw (rad, Z–Y–X).
    pub ship: [f64; 3],
}

/// One sample of everything the controller reads.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Inputs {
    /// Base, boom and jib potentiometers (V).
    pub pots: [f64; 3],
    /// Winch encoder, multi-turn (deg).
    pub encoder: f64,
    /// Deck IMU1 and load IMU2, sensor frames.
    pub imu1: ImuReadings,
    pub imu2: ImuReadings,
    /// Ship surge, sway, heave (m, W): truth, as in the thesis (§7.3).
    pub ship_position: Vec3,
    pub truth: Truth,
    /// The external set-point.
    pub external: Setpoint,
    /// A correction (m, W) added to the commanded tip after the delta law, e.g. a learning
    /// agent's residual on top of the thesis' law; zero leaves the law's command as it is.
    pub residual: Vec3,
}

impl Inputs {
    /// What a crane at rest in its default pose ([`DEFAULT_POSE`]) on a still, level deck at the
    /// origin presents to a controller with the default configuration, as that controller models
    /// its sensors: the potentiometers' true outputs (V); the encoder angle (deg) that the
    /// controller's own cable model (eqs. 3.1–3.4 with its nominal drum, [`CONTROLLER_CABLE`])
    /// gives for the pose's length at the jib extension it measures; level IMUs at rest; truth
    /// and the external set-point at the fixed set-point. The tip (within 0.05 mm) and the length
    /// are on the set-point, so such a controller holds the crane still (neutral commands).
    ///
    /// (The plant's encoder reads more for the same length, because its drum is smaller: 41.26
    /// against the nominal 41.32 mm, the thesis' mismatch, which a connected controller corrects.)
    pub const AT_REST: Inputs = {
        let config = ControllerConfig::DEFAULT;
        let pot = config.potentiometer;
        let pots = [
            pot.volts(DEFAULT_POSE.extensions[0]),
            pot.volts(DEFAULT_POSE.extensions[1]),
            pot.volts(DEFAULT_POSE.extensions[2]),
        ];
        let fixed = config.fixed;
        Inputs {
            pots,
            encoder: config.cable.winch_angle(DEFAULT_POSE.lp, pot.extension(pots[2])),
            imu1: ImuReadings::LEVEL,
            imu2: ImuReadings::LEVEL,
            ship_position: Vec3::new(0.0, 0.0, 0.0),
            truth: Truth { tip: fixed.tip, lp: fixed.lp, theta_x: 0.0, theta_y: 0.0, ship: [0.0; 3] },
            external: fixed,
            residual: Vec3::new(0.0, 0.0, 0.0),
        }
    };
}

/// What the controller estimated and decided at one sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Outputs {
    /// Hardware commands: V for base, boom, jib; winch duty.
    pub commands: Commands,
    /// The state the controller acts on (estimates, or truth with truth feedback).
    pub tip: Vec3,
    pub lp: f64,
    pub theta_x: f64,
    pub theta_y: f64,
    /// Ship roll, pitch, yaw (rad).
    pub ship: [f64; 3],
    /// Ship surge, sway, heave (m, W) the controller placed the crane with (the truth input, or
    /// the EKF's estimate with [`Feedback::Estimated`]) and the EKF's rates (m/s; zero when it
    /// does not run).
    pub ship_position: Vec3,
    pub ship_rate: Vec3,
    /// Load position (m, W).
    pub load: Vec3,
    /// The desired set-point and the commanded one (after the delta law).
    pub desired: Setpoint,
    /// Where the load hangs at the desired set-point (m, W): the sling's length below
    /// [`Setpoint::load`].
    pub desired_load: Vec3,
    pub commanded: Setpoint,
    /// Actuator extension references (m) and the winch angle reference (deg).
    pub extensions: [f64; 3],
    pub winch: f64,
    /// Whether the commanded tip needed a stroke limit or was out of reach.
    pub limited: bool,
    /// Whether commands are being issued.
    pub active: bool,
}

/// The controller's state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Controller {
    pub config: ControllerConfig,
    ship_filter: AttitudeFilter,
    load_filter: AttitudeFilter,
    /// The surge/sway/heave EKF, with [`Feedback::Estimated`] only: made at the first sample,
    /// whose interval it assumes for every later one (the controller samples at a fixed period).
    linear: Option<LinearMotionEstimator>,
    /// Learnt ship yaw, then load θx and θy offsets (rad).
    yaw_bias: LowPass,
    load_bias: [LowPass; 2],
    /// Mean load yaw (rad) before `active_from`, used with `load_heading`.
    load_yaw: MeanAngle,
    /// Learnt gyro biases of IMU1 and IMU2, used with `gyro_bias`.
    gyro_bias: [GyroBias; 2],
    /// Added to the encoder reading (deg), set at the first sample with `relative_encoder`.
    encoder_offset: f64,
    /// Output smoothing of roll, pitch, yaw, θx, θy.
    smoothing: [LowPass; 5],
    /// The hook–load notch on the load's θx, θy (used with a sling).
    notch: [Notch; 2],
    pids: [Pid; 4],
    /// Samples processed.
    samples: u64,
    /// The last outputs (the previous joint references are kept when a target is out of reach).
    last: Option<Outputs>,
    /// The angle gain's schedule (with [`GainSchedule::Length`], from the first active sample of
    /// the delta law).
    angle_schedule: Option<AngleSchedule>,
}

/// The LQR angle couplings the scheduled angle gain is the ratio of ([`super::compensation`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct AngleSchedule {
    /// K_θ(l_d) at the design length l_d (m): the desired length at the first active sample.
    design: Scheduled<f64>,
    /// K_θ at the length (m) of the last design, which follows the measured length.
    current: Scheduled<f64>,
}

/// Tolerance (s) on the activation time, for times accumulated from steps.
const TIME_TOLERANCE: f64 = 1e-9;

impl Controller {
    pub fn new(config: ControllerConfig) -> Result<Self, String> {
        config.validate()?;
        let angle = LowPass::new(config.angle_cutoff);
        Ok(Controller {
            config,
            ship_filter: AttitudeFilter::new(config.attitude, config.ship_filter, config.ship_madgwick),
            load_filter: AttitudeFilter::new(config.attitude, config.load_filter, config.load_madgwick),
            linear: None,
            yaw_bias: LowPass::new(config.bias_cutoff),
            load_bias: [LowPass::new(config.bias_cutoff); 2],
            load_yaw: MeanAngle::default(),
            gyro_bias: [GyroBias::default(); 2],
            encoder_offset: 0.0,
            smoothing: [angle; 5],
            notch: [Notch::new(config.sling.notch_damping); 2],
            pids: config.pid.map(Pid::new),
            samples: 0,
            last: None,
            angle_schedule: None,
        })
    }

    /// Checks a controller state that did not come from [`Controller::new`] (decoded from bytes):
    /// its configuration and the parameters each joint controller and the EKF keep a copy of.
    pub fn validate(&self) -> Result<(), String> {
        self.config.validate()?;
        if let Some(linear) = &self.linear {
            linear.validate().map_err(|e| format!("surge/sway/heave EKF: {e}"))?;
        }
        for (name, pid) in ["base", "boom", "jib", "winch"].iter().zip(&self.pids) {
            pid.params.validate().map_err(|e| format!("{name} PID: {e}"))?;
        }
        if let Some(s) = &self.angle_schedule {
            let values = [s.design.length, s.design.gain, s.current.length, s.current.gain];
            if !values.iter().all(|v| v.is_finite() && *v > 0.0) {
                return Err(format!("the angle gain's schedule needs lengths and couplings > 0, got {s:?}"));
            }
        }
        Ok(())
    }

    /// The delta law's angle gain k_θ (m/rad) that the last sample used (with the delta law): the
    /// configured one, or the scheduled one once the schedule has started.
    pub fn angle_gain(&self) -> f64 {
        let gains = &self.config.compensation;
        self.angle_schedule.map_or(gains.angle, |s| gains.scheduled_angle(s.current.gain, s.design.gain))
    }

    /// The delta law's gains for this sample: the configured ones, or with [`GainSchedule::Length`]
    /// and from the first active sample on, the angle gain scheduled at the measured length `lp`
    /// (m), the design length being `desired_lp` (m) at that first sample.
    fn compensation(&mut self, active: bool, desired_lp: f64, lp: f64) -> Result<CompensationGains, String> {
        let gains = self.config.compensation;
        if gains.schedule == GainSchedule::Fixed {
            return Ok(gains);
        }
        let g = self.config.load_filter.g;
        let schedule = match (&mut self.angle_schedule, active) {
            (Some(schedule), _) => schedule,
            (None, false) => return Ok(gains),
            (None, true) => {
                let coupling = angle_coupling(desired_lp, g).map_err(|e| format!("at the desired length: {e}"))?;
                let design = Scheduled { length: desired_lp, gain: coupling };
                self.angle_schedule.insert(AngleSchedule { design, current: design })
            }
        };
        let coupling =
            schedule.current.at(lp, |lp| angle_coupling(lp, g)).map_err(|e| format!("at the measured length: {e}"))?;
        Ok(CompensationGains { angle: gains.scheduled_angle(coupling, schedule.design.gain), ..gains })
    }

    /// Whether commands are issued at time `t` (s).
    pub fn is_active(&self, t: f64) -> bool {
        self.config.mode != Mode::Hold && t + TIME_TOLERANCE >= self.config.active_from
    }

    /// Processes the sample taken at time `t` (s), `dt` (s) after the previous one.
    pub fn step(&mut self, t: f64, dt: f64, u: &Inputs) -> Result<Outputs, String> {
        check_inputs(u)?;
        let c = self.config;
        let first = self.samples == 0;
        let learning = first || t + TIME_TOLERANCE < c.active_from;
        self.samples += 1;

        // The crane sensors (read first: the hook–load notch follows the hoist length).
        let extensions = u.pots.map(|v| c.potentiometer.extension(v));
        if first && c.relative_encoder {
            let initial = c.initial_length.unwrap_or(c.fixed.lp);
            self.encoder_offset = c.cable.winch_angle(initial, extensions[2]) - u.encoder;
        }
        let encoder = u.encoder + self.encoder_offset;
        let sensed_lp = c.cable.length(encoder, extensions[2]);

        // 1. Estimation.
        if first && c.align {
            self.ship_filter.align(&u.imu1.acc, &u.imu1.mag);
            self.load_filter.align(&u.imu2.acc, &u.imu2.mag);
        }
        let [gyro1, gyro2] = if c.gyro_bias {
            [self.gyro_bias[0].correct(&u.imu1.gyro, learning), self.gyro_bias[1].correct(&u.imu2.gyro, learning)]
        } else {
            [u.imu1.gyro, u.imu2.gyro]
        };
        let q_ship = self.ship_filter.update(&gyro1, &u.imu1.acc, &u.imu1.mag, dt);
        let q_load = self.load_filter.update(&gyro2, &u.imu2.acc, &u.imu2.mag, dt);
        // Finite inputs far beyond any sensor's range (a gyro reading of 1e300 rad/s) overflow the
        // filters' integration: refuse the step rather than go on with a NaN attitude.
        if !q_ship.coords.iter().chain(q_load.coords.iter()).all(|c| c.is_finite()) {
            return Err("an attitude estimate is not finite: an IMU input is beyond any sensor's range".into());
        }
        if learning {
            self.yaw_bias.update(ship_yaw(&q_ship), dt);
            if c.load_heading {
                // The Z–Y–X yaw of eq. 5.37, of the load's orientation.
                self.load_yaw.learn(ship_yaw(&q_load));
            }
        }
        let north = rot_z(-self.yaw_bias.value());
        let load_north = if c.load_heading { rot_z(-self.load_yaw.value()) } else { north };
        let ship_raw = ship_angles(&(north * q_ship));
        let [mut theta_x, mut theta_y] = cable_angles(&(load_north * q_load));
        if c.load_bias {
            if learning {
                self.load_bias[0].update(theta_x, dt);
                self.load_bias[1].update(theta_y, dt);
            }
            theta_x -= self.load_bias[0].value();
            theta_y -= self.load_bias[1].value();
        }
        if c.sling.length > 0.0 {
            [theta_x, theta_y] = self.notch_hook_load_mode([theta_x, theta_y], sensed_lp, dt);
        }
        let linear = self.linear_motion(&(north * q_ship), &u.imu1.acc, dt);
        let raw = [ship_raw[0], ship_raw[1], ship_raw[2], theta_x, theta_y];
        // The five smoothing filters share one cut-off (`Controller::new`), hence one gain.
        let gain = self.smoothing[0].gain(dt);
        let smooth: [f64; 5] = std::array::from_fn(|i| self.smoothing[i].update_with_gain(raw[i], gain));

        // 2. The measured state.
        let (ship, theta_x, theta_y) = match c.feedback {
            Feedback::Truth => (u.truth.ship, u.truth.theta_x, u.truth.theta_y),
            Feedback::Sensors | Feedback::Estimated => ([smooth[0], smooth[1], smooth[2]], smooth[3], smooth[4]),
        };
        let ship_position = linear.map_or(u.ship_position, |e| e.position);
        let frame = BaseFrame::new(&ship_position, &euler_zyx(ship[0], ship[1], ship[2]), &c.crane_base);
        let (tip, lp) = match c.feedback {
            Feedback::Truth => (u.truth.tip, u.truth.lp),
            Feedback::Sensors | Feedback::Estimated => {
                let tip_base = tip_from_actuators(&extensions).map_err(|e| format!("measured tip: {e}"))?;
                (frame.to_world(&tip_base), sensed_lp)
            }
        };
        let measured = Measured { tip, theta_x, theta_y, lp };

        // 3. Set-points.
        let desired = match c.setpoint {
            SetpointSource::Fixed => c.fixed,
            SetpointSource::PickAndPlace => pick_and_place(t - c.active_from),
            SetpointSource::External => u.external,
        };
        let active = self.is_active(t);
        let mut commanded = match c.mode {
            Mode::Compensated => self.compensation(active, desired.lp, lp)?.setpoint(&desired, &measured),
            Mode::Hold | Mode::InverseKinematics => desired,
        };
        // Skipped when zero, so that the law's command keeps its bits (a −0.0 stays −0.0).
        if u.residual != Vec3::zeros() {
            commanded.tip += u.residual;
        }

        // 4. Joint references.
        let (references, limited) = match extensions_for_tip(&frame, &commanded.tip) {
            Ok(result) => result,
            Err(_) => (self.last.map_or(extensions, |o| o.extensions), true),
        };
        let winch = c.cable.winch_angle(commanded.lp, extensions[2]);

        // 5. Joint control.
        let was_active = self.last.is_some_and(|o| o.active);
        let commands = if active {
            if !was_active {
                self.pids.iter_mut().for_each(Pid::reset);
            }
            let volts =
                [0, 1, 2].map(|i| self.pids[i].step(references[i] * MM_PER_M, extensions[i] * MM_PER_M, dt).command);
            let duty = self.pids[3].step(winch, encoder, dt).command;
            Commands { volts, duty }
        } else {
            Commands::default()
        };

        let out = Outputs {
            commands,
            tip,
            lp,
            theta_x,
            theta_y,
            ship,
            ship_position,
            ship_rate: linear.map_or(Vec3::zeros(), |e| e.rate),
            load: load_position(&tip, lp + c.sling.length, theta_x, theta_y),
            desired,
            desired_load: desired.load() + Vec3::new(0.0, 0.0, c.sling.length),
            commanded,
            extensions: references,
            winch,
            limited,
            active,
        };
        self.last = Some(out);
        Ok(out)
    }

    /// The load angles `theta` (rad) with the hook–load mode below a hoist rope of `hoist` (m)
    /// notched out ([`SlingConfig`]).
    fn notch_hook_load_mode(&mut self, theta: [f64; 2], hoist: f64, dt: f64) -> [f64; 2] {
        let omega = self.config.sling.hook_load_mode(hoist, self.config.load_filter.g);
        [self.notch[0].update(theta[0], omega, dt), self.notch[1].update(theta[1], omega, dt)]
    }

    /// With [`Feedback::Estimated`], one sample of the surge/sway/heave EKF: the deck IMU's
    /// specific force `acc` (m/s²) turned into the controller's world frame with the ship's
    /// attitude estimate `q_ship` (W←S, the learnt yaw removed, so that the estimate is in the
    /// frame the crane is placed in) by eq. 5.40, the gravity of the filters' `g`.
    fn linear_motion(&mut self, q_ship: &Quat, acc: &Vec3, dt: f64) -> Option<LinearEstimate> {
        if self.config.feedback != Feedback::Estimated {
            return None;
        }
        let (params, g) = (self.config.linear, self.config.ship_filter.g);
        let estimator = self.linear.get_or_insert_with(|| LinearMotionEstimator::new(params, dt));
        Some(estimator.update(&world_acceleration(q_ship, acc, g)))
    }
}

/// The largest magnitude any input may have: far beyond every sensor's range (volts, degrees,
/// rad/s, m/s², metres), and small enough that the estimators' products and integrals of such
/// values cannot overflow into a NaN state.
const MAX_INPUT: f64 = 1e6;

fn check_inputs(u: &Inputs) -> Result<(), String> {
    let scalars = [u.encoder, u.truth.lp, u.truth.theta_x, u.truth.theta_y, u.external.lp];
    let vectors = [
        u.imu1.gyro,
        u.imu1.acc,
        u.imu1.mag,
        u.imu2.gyro,
        u.imu2.acc,
        u.imu2.mag,
        u.ship_position,
        u.truth.tip,
        u.external.tip,
        u.residual,
    ];
    let mut values = scalars.iter().chain(&u.pots).chain(&u.truth.ship).chain(vectors.iter().flat_map(|v| v.iter()));
    if values.all(|v| v.is_finite() && v.abs() <= MAX_INPUT) {
        Ok(())
    } else {
        Err(format!("an input is not finite or beyond ±{MAX_INPUT:e} (no sensor reads that much)"))
    }
}

#[cfg(test)]
mod calibration_tests;
#[cfg(test)]
mod schedule_tests;
#[cfg(test)]
mod sling_tests;
#[cfg(test)]
mod tests;

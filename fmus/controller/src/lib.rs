//! FMU `controller`: the crane's myRIO software (SPEC §4.5; thesis Chapters 5–6).
//!
//! A sampled controller: every communication step it reads the crane sensors (potentiometer
//! volts, encoder degrees), the two IMUs' nine channels, the ship's surge/sway/heave and, for the
//! truth-feedback variant, truth values; it estimates the ship attitude and the pendulum angles
//! (complementary filters, or Madgwick's filter with `attitude_filter` = 1) and, with
//! `feedback` = 2, the ship's surge, sway and heave (the EKF of §5.1.3), computes the
//! world-frame set-point (inverse kinematics only, or the LQR-based delta law), converts it to
//! actuator and winch references, and runs the four joint PIDs. The physics and the algorithm live in `physics::control::controller`; this crate is the
//! variable table.
//!
//! Timing: the controller samples at its own period `sample_period` (100 Hz, §6.1), whatever the
//! communication step: `fmi2ExitInitializationMode` processes the sample at the start time, and
//! `fmi2DoStep(t, h)` processes every sample time start + n·period in (t, t + h] with the inputs
//! set before it. The outputs are held between samples (a zero-order hold, like the myRIO's).
//! At the default 10 ms step this is one sample per step; at 1 ms, one every tenth step, so the
//! closed loop's co-simulation error can be measured without changing the controller.

use fmi2::{Model, ModelInfo, Variable};
use physics::control::controller::{Controller, ControllerConfig, Feedback, Inputs, Mode, Outputs, SetpointSource};
use physics::crane::MM_PER_M;
use physics::estimation::attitude::AttitudeFilterKind;
use physics::estimation::linear_motion::MAX_MODES;
use physics::math::components;
use serde::{Deserialize, Serialize};

/// Instance data: configuration, inputs, the controller and its last outputs.
#[derive(Clone, Serialize, Deserialize)]
pub struct CraneController {
    config: ControllerConfig,
    inputs: Inputs,
    controller: Controller,
    out: Outputs,
    /// Sample period (s) and the samples taken since the one at `start_time`.
    sample_period: f64,
    start_time: f64,
    samples: u64,
}

/// The myRIO's control and sampling period (s), §6.1.
const DEFAULT_SAMPLE_PERIOD: f64 = 0.01;

/// Largest communication step (s): 100,000 samples at the default period.
const MAX_STEP_SIZE: f64 = 1000.0;
/// Most samples one `fmi2DoStep` processes (about half a second of work); more, e.g. a 1000 s
/// step at the shortest period of 0.1 ms, are refused with `fmi2Error`.
const MAX_SAMPLES_PER_STEP: u64 = 100_000;

impl CraneController {
    fn sample(&mut self, t: f64, dt: f64) -> Result<(), String> {
        self.out = self.controller.step(t, dt, &self.inputs)?;
        Ok(())
    }
}

impl Model for CraneController {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "controller",
        description: "Crane controller (the myRIO software): complementary-filter estimation of the ship attitude and the pendulum angles, LQR-based world-frame compensation, crane inverse kinematics and PID joint control (thesis chapters 5-6)",
        default_stop_time: 10.0,
        default_step_size: 0.01,
        can_interpolate_inputs: false,
        max_step_size: MAX_STEP_SIZE,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(_env: &fmi2::Environment) -> Self {
        let controller = Controller::new(CONFIG).expect("the default configuration is valid");
        CraneController {
            config: CONFIG,
            inputs: INPUTS,
            out: placeholder_outputs(),
            controller,
            sample_period: DEFAULT_SAMPLE_PERIOD,
            start_time: 0.0,
            samples: 0,
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.controller = Controller::new(self.config)?;
        self.start_time = start_time;
        self.samples = 0;
        self.sample(start_time, self.sample_period)
    }

    /// The controller built at initialization (the configuration as set may be inconsistent
    /// until then, one parameter at a time: initialization checks it).
    fn validate_state(&self) -> Result<(), String> {
        self.controller.validate()
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        let end = t + h;
        // Sample times are start + n·period (an integer count, so nothing drifts); one that
        // lands on the step's end up to rounding belongs to this step.
        let tolerance = fmi2::time_tolerance(end);
        // The samples due, counted before taking any: the work of one step is bounded, and at a
        // large t, where the period is below the resolution of t, the count is refused instead
        // of sampling forever at the same instant.
        let due = ((end + tolerance - self.start_time) / self.sample_period).floor() - self.samples as f64;
        if !(due <= MAX_SAMPLES_PER_STEP as f64) {
            return Err(format!(
                "a step to t = {end} s spans {due} samples of {} s; at most {MAX_SAMPLES_PER_STEP} per fmi2DoStep",
                self.sample_period
            ));
        }
        // One more than counted, in case the count rounded down; the loop ends at the step's end.
        for _ in 0..=due as u64 + 1 {
            let next = self.start_time + (self.samples + 1) as f64 * self.sample_period;
            if next > end + tolerance {
                break;
            }
            self.sample(next, self.sample_period)?;
            self.samples += 1;
        }
        Ok(())
    }
}

/// The outputs until the first sample (initialization computes them before any is read).
fn placeholder_outputs() -> Outputs {
    let fixed = CONFIG.fixed;
    Outputs {
        commands: Default::default(),
        tip: fixed.tip,
        lp: fixed.lp,
        theta_x: 0.0,
        theta_y: 0.0,
        ship: [0.0; 3],
        ship_position: INPUTS.ship_position,
        ship_rate: Default::default(),
        load: fixed.load(),
        desired: fixed,
        commanded: fixed,
        extensions: [0.0; 3],
        winch: 0.0,
        limited: false,
        active: false,
    }
}

/// The default configuration and inputs: the start values of the table and of [`Model::new`].
const CONFIG: ControllerConfig = ControllerConfig::DEFAULT;
const INPUTS: Inputs = Inputs::AT_REST;

// Integer codes of the enumerations, converted here and nowhere else. Each parameter's declared
// range is exactly its codes, so `fmi2SetInteger` refuses any other code ("'mode' = 3 is outside
// its range [0, 2]") before a setter sees it.

/// `mode`: 0 hold, 1 inverse-kinematic control only, 2 world-frame compensation.
const fn mode_code(mode: Mode) -> i32 {
    match mode {
        Mode::Hold => 0,
        Mode::InverseKinematics => 1,
        Mode::Compensated => 2,
    }
}

fn mode(code: i32) -> Option<Mode> {
    match code {
        0 => Some(Mode::Hold),
        1 => Some(Mode::InverseKinematics),
        2 => Some(Mode::Compensated),
        _ => None,
    }
}

/// `feedback`: 0 truth, 1 sensors, 2 sensors and the surge/sway/heave EKF (no truth).
const fn feedback_code(feedback: Feedback) -> i32 {
    match feedback {
        Feedback::Truth => 0,
        Feedback::Sensors => 1,
        Feedback::Estimated => 2,
    }
}

fn feedback(code: i32) -> Option<Feedback> {
    match code {
        0 => Some(Feedback::Truth),
        1 => Some(Feedback::Sensors),
        2 => Some(Feedback::Estimated),
        _ => None,
    }
}

/// `setpoint`: 0 fixed, 1 pick-and-place profile, 2 external inputs.
const fn setpoint_code(source: SetpointSource) -> i32 {
    match source {
        SetpointSource::Fixed => 0,
        SetpointSource::PickAndPlace => 1,
        SetpointSource::External => 2,
    }
}

fn setpoint(code: i32) -> Option<SetpointSource> {
    match code {
        0 => Some(SetpointSource::Fixed),
        1 => Some(SetpointSource::PickAndPlace),
        2 => Some(SetpointSource::External),
        _ => None,
    }
}

/// `cf_init`: 0 identity, 1 aligned on the first sample.
const fn align_code(align: bool) -> i32 {
    align as i32
}

fn align(code: i32) -> Option<bool> {
    match code {
        0 => Some(false),
        1 => Some(true),
        _ => None,
    }
}

/// `attitude_filter`: 0 complementary (the thesis' filter), 1 Madgwick.
const fn attitude_code(kind: AttitudeFilterKind) -> i32 {
    match kind {
        AttitudeFilterKind::Complementary => 0,
        AttitudeFilterKind::Madgwick => 1,
    }
}

fn attitude(code: i32) -> Option<AttitudeFilterKind> {
    match code {
        0 => Some(AttitudeFilterKind::Complementary),
        1 => Some(AttitudeFilterKind::Madgwick),
        _ => None,
    }
}

/// The message of a setter that meets a code outside the declared range (which `fmi2SetInteger`
/// refuses first).
const REFUSED: &str = "fmi2SetInteger refuses a code outside the declared range";

fn set_g(m: &mut CraneController, g: f64) {
    m.config.ship_filter.g = g;
    m.config.load_filter.g = g;
}

type V = Variable<CraneController>;

/// Millimetres per metre, for the linear actuators' PID parameters (the controller works in mm,
/// the ports in m).
const MM: f64 = MM_PER_M;

/// The variable table (value references: parameters 0–99, inputs 200–259, outputs 260–269 and 300+).
static VARIABLES: &[V] = &[
    // Parameters: operation.
    V { variability: fmi2::variables::Variability::Tunable, ..V::integer_parameter(0, "mode", mode_code(CONFIG.mode), 0, 2, "0 hold (crane off, neutral commands), 1 inverse-kinematic control only (uncompensated), 2 world-frame compensation (section 6.2); tunable, so an operator can switch compensation on and off between steps", |m| mode_code(m.config.mode), |m, v| m.config.mode = mode(v).expect(REFUSED)) },
    V::integer_parameter(1, "feedback", feedback_code(CONFIG.feedback), 0, 2, "0 truth (tip, length, pendulum angles and ship attitude from the truth inputs), 1 sensors (potentiometers, encoder, attitude filters; surge/sway/heave from the ship.* truth inputs, as the thesis), 2 sensors with surge/sway/heave from the EKF of section 5.1.3 (ekf.*): no truth input is read", |m| feedback_code(m.config.feedback), |m, v| m.config.feedback = feedback(v).expect(REFUSED)),
    V::integer_parameter(2, "setpoint", setpoint_code(CONFIG.setpoint), 0, 2, "0 fixed (sp.tip.*, sp.lp), 1 pick-and-place profile from active_from, 2 external inputs sp_in.*", |m| setpoint_code(m.config.setpoint), |m, v| m.config.setpoint = setpoint(v).expect(REFUSED)),
    V::integer_parameter(3, "cf_init", align_code(CONFIG.align), 0, 1, "Complementary filter start: 0 identity (thesis behaviour, initial estimation kick), 1 aligned on the first accelerometer and magnetometer sample", |m| align_code(m.config.align), |m, v| m.config.align = align(v).expect(REFUSED)),
    V::integer_parameter(22, "attitude_filter", attitude_code(CONFIG.attitude), 0, 1, "Attitude estimator of both IMUs: 0 the complementary filter (section 5.1.1, cf1.*/cf2.*), 1 Madgwick's gradient-descent filter (mw1.beta/mw2.beta)", |m| attitude_code(m.config.attitude), |m, v| m.config.attitude = attitude(v).expect(REFUSED)),
    V::parameter(21, "sample_period", "s", DEFAULT_SAMPLE_PERIOD, "Control and sampling period (100 Hz, section 6.1); independent of the communication step", |m| m.sample_period, |m, v| m.sample_period = v).range(1e-4, 1.0),
    V::parameter(4, "active_from", "s", CONFIG.active_from, "Time from which commands are issued (estimation runs from the start); the pick-and-place profile starts here", |m| m.config.active_from, |m, v| m.config.active_from = v),
    V::parameter(5, "sp.tip.x", "m", components(&CONFIG.fixed.tip)[0], "Fixed set-point: tip position, W x", |m| m.config.fixed.tip.x, |m, v| m.config.fixed.tip.x = v),
    V::parameter(6, "sp.tip.y", "m", components(&CONFIG.fixed.tip)[1], "Fixed set-point: tip position, W y", |m| m.config.fixed.tip.y, |m, v| m.config.fixed.tip.y = v),
    V::parameter(7, "sp.tip.z", "m", components(&CONFIG.fixed.tip)[2], "Fixed set-point: tip position, W z (down)", |m| m.config.fixed.tip.z, |m, v| m.config.fixed.tip.z = v),
    V::parameter(8, "sp.lp", "m", CONFIG.fixed.lp, "Fixed set-point: pendulum length", |m| m.config.fixed.lp, |m, v| m.config.fixed.lp = v).range(0.01, 10.0),
    V::parameter(9, "r_base.x", "m", components(&CONFIG.crane_base)[0], "Crane base frame J12 origin in the ship frame B, x", |m| m.config.crane_base.x, |m, v| m.config.crane_base.x = v),
    V::parameter(10, "r_base.y", "m", components(&CONFIG.crane_base)[1], "Crane base frame J12 origin in B, y (crane on the port side)", |m| m.config.crane_base.y, |m, v| m.config.crane_base.y = v),
    V::parameter(11, "r_base.z", "m", components(&CONFIG.crane_base)[2], "Crane base frame J12 origin in B, z", |m| m.config.crane_base.z, |m, v| m.config.crane_base.z = v),
    V::parameter(12, "winch.diameter", "m", CONFIG.cable.drum_diameter / MM, "Nominal winch drum diameter the controller converts lengths with (section 6.1; the plant's is 0.04126 m)", |m| m.config.cable.drum_diameter / MM, |m, v| m.config.cable.drum_diameter = v * MM).range(0.001, 1.0),
    V::parameter(13, "g", "m/s2", CONFIG.ship_filter.g, "Gravitational acceleration the accelerometer magnitude is compared with (eq. 5.20)", |m| m.config.ship_filter.g, set_g).range(0.1, 100.0),
    V::parameter(14, "lowpass.bias", "Hz", CONFIG.bias_cutoff, "Cut-off of the low-pass that learns the ship yaw (and optionally the load angle offsets) before active_from (section 5.3); 0 learns the first sample only", |m| m.config.bias_cutoff, |m, v| m.config.bias_cutoff = v).range(0.0, 1000.0),
    V::parameter(15, "lowpass.angles", "Hz", CONFIG.angle_cutoff, "Cut-off of the low-pass on the estimated angles (section 5.3); 0 = none", |m| m.config.angle_cutoff, |m, v| m.config.angle_cutoff = v).range(0.0, 1000.0),
    V::boolean_parameter(16, "bias.load", CONFIG.load_bias, "Also learn the load angles before active_from and remove them as IMU mounting offsets (section 5.3); off by default because the load is held displaced during initialisation", |m| m.config.load_bias, |m, v| m.config.load_bias = v),
    // Parameters: compensation (section 6.2).
    V::parameter(17, "k.position", "1", CONFIG.compensation.position, "Delta-law gain K_P on the tip position and length errors", |m| m.config.compensation.position, |m, v| m.config.compensation.position = v),
    V::parameter(18, "k.angle", "m/rad", CONFIG.compensation.angle, "Delta-law gain K_P on the pendulum angle errors (dy_t = e_y + k e_thx, dx_t = e_x - k e_thy)", |m| m.config.compensation.angle, |m, v| m.config.compensation.angle = v),
    V::parameter(19, "deadband.position", "m", CONFIG.compensation.position_deadband, "Error deadband on the tip position and length", |m| m.config.compensation.position_deadband, |m, v| m.config.compensation.position_deadband = v).range(0.0, 1.0),
    V::parameter(20, "deadband.angle", "rad", CONFIG.compensation.angle_deadband, "Error deadband on the pendulum angles", |m| m.config.compensation.angle_deadband, |m, v| m.config.compensation.angle_deadband = v).range(0.0, 1.0),
    // Parameters: the surge/sway/heave EKF (section 5.1.3; feedback = 2).
    V::parameter(37, "ekf.window", "s", CONFIG.linear.window, "EKF identification window: every window's FFT and peak detection starts the filter of each axis that shows modes (20 s: the first window of a campaign run holds 8-10 s of ship motion)", |m| m.config.linear.window, |m, v| m.config.linear.window = v).range(1.0, 600.0),
    V::integer_parameter(38, "ekf.modes", CONFIG.linear.search.modes as i32, 1, MAX_MODES as i32, "EKF oscillator modes per axis, N_m (section 5.1.3)", |m| m.config.linear.search.modes as i32, |m, v| m.config.linear.search.modes = v as usize),
    V::parameter(39, "ekf.floor", "m/s2", CONFIG.linear.search.floor, "Smallest acceleration amplitude of an identified mode: a still deck's noise maxima stay below it, so a still axis estimates zero", |m| m.config.linear.search.floor, |m, v| m.config.linear.search.floor = v).range(0.0, 10.0),
    // Parameters: complementary filters (Table 5.1 ship, Table 5.2 load).
    V::parameter(30, "cf1.beta", "1", CONFIG.ship_filter.beta, "Ship filter: LERP above, SLERP below this delta-quaternion scalar part (eqs. 5.19, 5.26)", |m| m.config.ship_filter.beta, |m, v| m.config.ship_filter.beta = v).range(-1.0, 1.0),
    V::parameter(31, "cf1.alpha_a", "1", CONFIG.ship_filter.alpha_a, "Ship filter: accelerometer gain (eq. 5.21)", |m| m.config.ship_filter.alpha_a, |m, v| m.config.ship_filter.alpha_a = v).range(0.0, 1.0),
    V::parameter(32, "cf1.beta_a_ll", "1", CONFIG.ship_filter.beta_a_ll, "Ship filter: magnitude error up to which the full accelerometer gain applies (eq. 5.21)", |m| m.config.ship_filter.beta_a_ll, |m, v| m.config.ship_filter.beta_a_ll = v),
    V::parameter(33, "cf1.beta_a_ul", "1", CONFIG.ship_filter.beta_a_ul, "Ship filter: magnitude error from which the accelerometer is ignored (eq. 5.21)", |m| m.config.ship_filter.beta_a_ul, |m, v| m.config.ship_filter.beta_a_ul = v),
    V::parameter(34, "cf1.alpha_m", "1", CONFIG.ship_filter.alpha_m, "Ship filter: magnetometer gain (eq. 5.27)", |m| m.config.ship_filter.alpha_m, |m, v| m.config.ship_filter.alpha_m = v).range(0.0, 1.0),
    V::parameter(35, "cf1.beta_m", "1", CONFIG.ship_filter.beta_m, "Ship filter: exponential rejection of large magnetic corrections (eq. 5.27)", |m| m.config.ship_filter.beta_m, |m, v| m.config.ship_filter.beta_m = v),
    V::parameter(36, "mw1.beta", "rad/s", CONFIG.ship_madgwick.beta, "Ship Madgwick filter: gain beta = sqrt(3/4) times the gyro error (Madgwick 2010, eqs. 43, 50); default from the 0.0035 rad/s gyro noise", |m| m.config.ship_madgwick.beta, |m, v| m.config.ship_madgwick.beta = v).range(0.0, 10.0),
    V::parameter(40, "cf2.beta", "1", CONFIG.load_filter.beta, "Load filter: LERP/SLERP threshold (eqs. 5.19, 5.26)", |m| m.config.load_filter.beta, |m, v| m.config.load_filter.beta = v).range(-1.0, 1.0),
    V::parameter(41, "cf2.alpha_a", "1", CONFIG.load_filter.alpha_a, "Load filter: accelerometer gain (eq. 5.21)", |m| m.config.load_filter.alpha_a, |m, v| m.config.load_filter.alpha_a = v).range(0.0, 1.0),
    V::parameter(42, "cf2.beta_a_ll", "1", CONFIG.load_filter.beta_a_ll, "Load filter: magnitude error up to which the full accelerometer gain applies", |m| m.config.load_filter.beta_a_ll, |m, v| m.config.load_filter.beta_a_ll = v),
    V::parameter(43, "cf2.beta_a_ul", "1", CONFIG.load_filter.beta_a_ul, "Load filter: magnitude error from which the accelerometer is ignored", |m| m.config.load_filter.beta_a_ul, |m, v| m.config.load_filter.beta_a_ul = v),
    V::parameter(44, "cf2.alpha_m", "1", CONFIG.load_filter.alpha_m, "Load filter: magnetometer gain (eq. 5.27)", |m| m.config.load_filter.alpha_m, |m, v| m.config.load_filter.alpha_m = v).range(0.0, 1.0),
    V::parameter(45, "cf2.beta_m", "1", CONFIG.load_filter.beta_m, "Load filter: exponential rejection of large magnetic corrections (eq. 5.27)", |m| m.config.load_filter.beta_m, |m, v| m.config.load_filter.beta_m = v),
    V::parameter(46, "mw2.beta", "rad/s", CONFIG.load_madgwick.beta, "Load Madgwick filter: gain beta (Madgwick 2010, eqs. 43, 50)", |m| m.config.load_madgwick.beta, |m, v| m.config.load_madgwick.beta = v).range(0.0, 10.0),
    V::boolean_parameter(47, "bias.gyro", CONFIG.gyro_bias, "Learn both IMUs' gyro biases as the mean reading before active_from (both IMUs assumed at rest) and subtract them; off by default (the simulated biases are 0)", |m| m.config.gyro_bias, |m, v| m.config.gyro_bias = v),
    V::boolean_parameter(48, "bias.load_heading", CONFIG.load_heading, "Turn the load estimate by IMU2's own mean yaw before active_from instead of IMU1's learnt yaw (removes a difference between the fields the two IMUs see; assumes the load faces the deck's heading then)", |m| m.config.load_heading, |m, v| m.config.load_heading = v),
    V::boolean_parameter(49, "encoder.relative", CONFIG.relative_encoder, "Count the encoder from its first sample, offset by the winch angle of the initial length (encoder.lp0) at winch.diameter, as the thesis' controller does (section 6.1); false reads it as the angle from the winch home, so the drum mismatch offsets every length reading", |m| m.config.relative_encoder, |m, v| m.config.relative_encoder = v),
    V::parameter(23, "encoder.lp0", "m", 0.0, "Initial cable length the relative encoder starts from; 0 takes sp.lp (the initial length in every thesis test); set it when sp.lp commands a new length", |m| m.config.initial_length.unwrap_or(0.0), |m, v| m.config.initial_length = (v != 0.0).then_some(v)).range(0.0, 10.0),
    // Parameters: joint PIDs (Table 6.1), linear actuators in SI (0.6 V/mm = 600 V/m).
    V::parameter(50, "pid.base.kp", "V/m", CONFIG.pid[0].kp * MM, "Base actuator proportional gain (0.6 V/mm)", |m| m.config.pid[0].kp * MM, |m, v| m.config.pid[0].kp = v / MM),
    V::parameter(51, "pid.base.ki", "V/(m.s)", CONFIG.pid[0].ki * MM, "Base actuator integral gain", |m| m.config.pid[0].ki * MM, |m, v| m.config.pid[0].ki = v / MM),
    V::parameter(52, "pid.base.kd", "V.s/m", CONFIG.pid[0].kd * MM, "Base actuator derivative gain (on the measurement)", |m| m.config.pid[0].kd * MM, |m, v| m.config.pid[0].kd = v / MM),
    V::parameter(53, "pid.base.e_db", "m", CONFIG.pid[0].error_deadband / MM, "Base actuator error deadband (eq. 6.10)", |m| m.config.pid[0].error_deadband / MM, |m, v| m.config.pid[0].error_deadband = v * MM).range(0.0, 0.05),
    V::parameter(54, "pid.base.sat_ll", "V", CONFIG.pid[0].sat_lower, "Base actuator lower saturation (eq. 6.4)", |m| m.config.pid[0].sat_lower, |m, v| m.config.pid[0].sat_lower = v),
    V::parameter(55, "pid.base.sat_ul", "V", CONFIG.pid[0].sat_upper, "Base actuator upper saturation (eq. 6.4)", |m| m.config.pid[0].sat_upper, |m, v| m.config.pid[0].sat_upper = v),
    V::parameter(56, "pid.base.db_ll", "V", CONFIG.pid[0].deadband_lower, "Base actuator lower deadband to jump (eq. 6.11)", |m| m.config.pid[0].deadband_lower, |m, v| m.config.pid[0].deadband_lower = v),
    V::parameter(57, "pid.base.db_ul", "V", CONFIG.pid[0].deadband_upper, "Base actuator upper deadband to jump (eq. 6.11)", |m| m.config.pid[0].deadband_upper, |m, v| m.config.pid[0].deadband_upper = v),
    V::parameter(58, "pid.base.u_db", "V", CONFIG.pid[0].jump_threshold, "Base actuator minimum action for a deadband jump (eq. 6.11)", |m| m.config.pid[0].jump_threshold, |m, v| m.config.pid[0].jump_threshold = v),
    V::parameter(60, "pid.boom.kp", "V/m", CONFIG.pid[1].kp * MM, "Boom actuator proportional gain (0.45 V/mm)", |m| m.config.pid[1].kp * MM, |m, v| m.config.pid[1].kp = v / MM),
    V::parameter(61, "pid.boom.ki", "V/(m.s)", CONFIG.pid[1].ki * MM, "Boom actuator integral gain", |m| m.config.pid[1].ki * MM, |m, v| m.config.pid[1].ki = v / MM),
    V::parameter(62, "pid.boom.kd", "V.s/m", CONFIG.pid[1].kd * MM, "Boom actuator derivative gain", |m| m.config.pid[1].kd * MM, |m, v| m.config.pid[1].kd = v / MM),
    V::parameter(63, "pid.boom.e_db", "m", CONFIG.pid[1].error_deadband / MM, "Boom actuator error deadband", |m| m.config.pid[1].error_deadband / MM, |m, v| m.config.pid[1].error_deadband = v * MM).range(0.0, 0.05),
    V::parameter(64, "pid.boom.sat_ll", "V", CONFIG.pid[1].sat_lower, "Boom actuator lower saturation", |m| m.config.pid[1].sat_lower, |m, v| m.config.pid[1].sat_lower = v),
    V::parameter(65, "pid.boom.sat_ul", "V", CONFIG.pid[1].sat_upper, "Boom actuator upper saturation", |m| m.config.pid[1].sat_upper, |m, v| m.config.pid[1].sat_upper = v),
    V::parameter(66, "pid.boom.db_ll", "V", CONFIG.pid[1].deadband_lower, "Boom actuator lower deadband to jump", |m| m.config.pid[1].deadband_lower, |m, v| m.config.pid[1].deadband_lower = v),
    V::parameter(67, "pid.boom.db_ul", "V", CONFIG.pid[1].deadband_upper, "Boom actuator upper deadband to jump", |m| m.config.pid[1].deadband_upper, |m, v| m.config.pid[1].deadband_upper = v),
    V::parameter(68, "pid.boom.u_db", "V", CONFIG.pid[1].jump_threshold, "Boom actuator minimum action for a deadband jump", |m| m.config.pid[1].jump_threshold, |m, v| m.config.pid[1].jump_threshold = v),
    V::parameter(70, "pid.jib.kp", "V/m", CONFIG.pid[2].kp * MM, "Jib actuator proportional gain (0.59 V/mm)", |m| m.config.pid[2].kp * MM, |m, v| m.config.pid[2].kp = v / MM),
    V::parameter(71, "pid.jib.ki", "V/(m.s)", CONFIG.pid[2].ki * MM, "Jib actuator integral gain", |m| m.config.pid[2].ki * MM, |m, v| m.config.pid[2].ki = v / MM),
    V::parameter(72, "pid.jib.kd", "V.s/m", CONFIG.pid[2].kd * MM, "Jib actuator derivative gain", |m| m.config.pid[2].kd * MM, |m, v| m.config.pid[2].kd = v / MM),
    V::parameter(73, "pid.jib.e_db", "m", CONFIG.pid[2].error_deadband / MM, "Jib actuator error deadband", |m| m.config.pid[2].error_deadband / MM, |m, v| m.config.pid[2].error_deadband = v * MM).range(0.0, 0.05),
    V::parameter(74, "pid.jib.sat_ll", "V", CONFIG.pid[2].sat_lower, "Jib actuator lower saturation", |m| m.config.pid[2].sat_lower, |m, v| m.config.pid[2].sat_lower = v),
    V::parameter(75, "pid.jib.sat_ul", "V", CONFIG.pid[2].sat_upper, "Jib actuator upper saturation", |m| m.config.pid[2].sat_upper, |m, v| m.config.pid[2].sat_upper = v),
    V::parameter(76, "pid.jib.db_ll", "V", CONFIG.pid[2].deadband_lower, "Jib actuator lower deadband to jump", |m| m.config.pid[2].deadband_lower, |m, v| m.config.pid[2].deadband_lower = v),
    V::parameter(77, "pid.jib.db_ul", "V", CONFIG.pid[2].deadband_upper, "Jib actuator upper deadband to jump", |m| m.config.pid[2].deadband_upper, |m, v| m.config.pid[2].deadband_upper = v),
    V::parameter(78, "pid.jib.u_db", "V", CONFIG.pid[2].jump_threshold, "Jib actuator minimum action for a deadband jump", |m| m.config.pid[2].jump_threshold, |m, v| m.config.pid[2].jump_threshold = v),
    V::parameter(80, "pid.winch.kp", "1/deg", CONFIG.pid[3].kp, "Winch proportional gain (duty per degree)", |m| m.config.pid[3].kp, |m, v| m.config.pid[3].kp = v),
    V::parameter(81, "pid.winch.ki", "1/(deg.s)", CONFIG.pid[3].ki, "Winch integral gain (trapezoidal, anti-windup eq. 6.9)", |m| m.config.pid[3].ki, |m, v| m.config.pid[3].ki = v),
    V::parameter(82, "pid.winch.kd", "s/deg", CONFIG.pid[3].kd, "Winch derivative gain (on the measurement, eq. 6.8)", |m| m.config.pid[3].kd, |m, v| m.config.pid[3].kd = v),
    V::parameter(83, "pid.winch.e_db", "deg", CONFIG.pid[3].error_deadband, "Winch error deadband", |m| m.config.pid[3].error_deadband, |m, v| m.config.pid[3].error_deadband = v).range(0.0, 360.0),
    V::parameter(84, "pid.winch.sat_ll", "1", CONFIG.pid[3].sat_lower, "Winch lower saturation (duty)", |m| m.config.pid[3].sat_lower, |m, v| m.config.pid[3].sat_lower = v),
    V::parameter(85, "pid.winch.sat_ul", "1", CONFIG.pid[3].sat_upper, "Winch upper saturation (duty)", |m| m.config.pid[3].sat_upper, |m, v| m.config.pid[3].sat_upper = v),
    V::parameter(86, "pid.winch.db_ll", "1", CONFIG.pid[3].deadband_lower, "Winch lower deadband to jump (duty)", |m| m.config.pid[3].deadband_lower, |m, v| m.config.pid[3].deadband_lower = v),
    V::parameter(87, "pid.winch.db_ul", "1", CONFIG.pid[3].deadband_upper, "Winch upper deadband to jump (duty)", |m| m.config.pid[3].deadband_upper, |m, v| m.config.pid[3].deadband_upper = v),
    V::parameter(88, "pid.winch.u_db", "1", CONFIG.pid[3].jump_threshold, "Winch minimum action for a deadband jump (duty)", |m| m.config.pid[3].jump_threshold, |m, v| m.config.pid[3].jump_threshold = v),
    // Inputs: crane sensors (the crane's outputs).
    V::held_input(200, "pot.base", "V", INPUTS.pots[0], "Base potentiometer, 0-5 V over 0-50 mm", |m| m.inputs.pots[0], |m, v| m.inputs.pots[0] = v),
    V::held_input(201, "pot.boom", "V", INPUTS.pots[1], "Boom potentiometer", |m| m.inputs.pots[1], |m, v| m.inputs.pots[1] = v),
    V::held_input(202, "pot.jib", "V", INPUTS.pots[2], "Jib potentiometer", |m| m.inputs.pots[2], |m, v| m.inputs.pots[2] = v),
    V::held_input(203, "encoder", "deg", INPUTS.encoder, "Winch encoder, multi-turn, from the winch home (the default is the fixed set-point's l_p in the controller's cable model, so a bare instance holds the winch still)", |m| m.inputs.encoder, |m, v| m.inputs.encoder = v),
    // Inputs: IMU1 (deck) and IMU2 (load), sensor frames.
    V::held_input(210, "imu1.gyro.x", "rad/s", components(&INPUTS.imu1.gyro)[0], "Deck IMU gyroscope x", |m| m.inputs.imu1.gyro.x, |m, v| m.inputs.imu1.gyro.x = v),
    V::held_input(211, "imu1.gyro.y", "rad/s", components(&INPUTS.imu1.gyro)[1], "Deck IMU gyroscope y", |m| m.inputs.imu1.gyro.y, |m, v| m.inputs.imu1.gyro.y = v),
    V::held_input(212, "imu1.gyro.z", "rad/s", components(&INPUTS.imu1.gyro)[2], "Deck IMU gyroscope z", |m| m.inputs.imu1.gyro.z, |m, v| m.inputs.imu1.gyro.z = v),
    V::held_input(213, "imu1.acc.x", "m/s2", components(&INPUTS.imu1.acc)[0], "Deck IMU specific force x", |m| m.inputs.imu1.acc.x, |m, v| m.inputs.imu1.acc.x = v),
    V::held_input(214, "imu1.acc.y", "m/s2", components(&INPUTS.imu1.acc)[1], "Deck IMU specific force y", |m| m.inputs.imu1.acc.y, |m, v| m.inputs.imu1.acc.y = v),
    V::held_input(215, "imu1.acc.z", "m/s2", components(&INPUTS.imu1.acc)[2], "Deck IMU specific force z (-g at rest, level)", |m| m.inputs.imu1.acc.z, |m, v| m.inputs.imu1.acc.z = v),
    V::held_input(216, "imu1.mag.x", "1", components(&INPUTS.imu1.mag)[0], "Deck IMU magnetometer x (unit field vector)", |m| m.inputs.imu1.mag.x, |m, v| m.inputs.imu1.mag.x = v),
    V::held_input(217, "imu1.mag.y", "1", components(&INPUTS.imu1.mag)[1], "Deck IMU magnetometer y", |m| m.inputs.imu1.mag.y, |m, v| m.inputs.imu1.mag.y = v),
    V::held_input(218, "imu1.mag.z", "1", components(&INPUTS.imu1.mag)[2], "Deck IMU magnetometer z", |m| m.inputs.imu1.mag.z, |m, v| m.inputs.imu1.mag.z = v),
    V::held_input(220, "imu2.gyro.x", "rad/s", components(&INPUTS.imu2.gyro)[0], "Load IMU gyroscope x", |m| m.inputs.imu2.gyro.x, |m, v| m.inputs.imu2.gyro.x = v),
    V::held_input(221, "imu2.gyro.y", "rad/s", components(&INPUTS.imu2.gyro)[1], "Load IMU gyroscope y", |m| m.inputs.imu2.gyro.y, |m, v| m.inputs.imu2.gyro.y = v),
    V::held_input(222, "imu2.gyro.z", "rad/s", components(&INPUTS.imu2.gyro)[2], "Load IMU gyroscope z", |m| m.inputs.imu2.gyro.z, |m, v| m.inputs.imu2.gyro.z = v),
    V::held_input(223, "imu2.acc.x", "m/s2", components(&INPUTS.imu2.acc)[0], "Load IMU specific force x", |m| m.inputs.imu2.acc.x, |m, v| m.inputs.imu2.acc.x = v),
    V::held_input(224, "imu2.acc.y", "m/s2", components(&INPUTS.imu2.acc)[1], "Load IMU specific force y", |m| m.inputs.imu2.acc.y, |m, v| m.inputs.imu2.acc.y = v),
    V::held_input(225, "imu2.acc.z", "m/s2", components(&INPUTS.imu2.acc)[2], "Load IMU specific force z", |m| m.inputs.imu2.acc.z, |m, v| m.inputs.imu2.acc.z = v),
    V::held_input(226, "imu2.mag.x", "1", components(&INPUTS.imu2.mag)[0], "Load IMU magnetometer x", |m| m.inputs.imu2.mag.x, |m, v| m.inputs.imu2.mag.x = v),
    V::held_input(227, "imu2.mag.y", "1", components(&INPUTS.imu2.mag)[1], "Load IMU magnetometer y", |m| m.inputs.imu2.mag.y, |m, v| m.inputs.imu2.mag.y = v),
    V::held_input(228, "imu2.mag.z", "1", components(&INPUTS.imu2.mag)[2], "Load IMU magnetometer z", |m| m.inputs.imu2.mag.z, |m, v| m.inputs.imu2.mag.z = v),
    // Inputs: ship position (truth, as the thesis supplied it) and the truth-feedback variant.
    V::held_input(230, "ship.x", "m", components(&INPUTS.ship_position)[0], "Ship surge, W x (truth)", |m| m.inputs.ship_position.x, |m, v| m.inputs.ship_position.x = v),
    V::held_input(231, "ship.y", "m", components(&INPUTS.ship_position)[1], "Ship sway, W y (truth)", |m| m.inputs.ship_position.y, |m, v| m.inputs.ship_position.y = v),
    V::held_input(232, "ship.z", "m", components(&INPUTS.ship_position)[2], "Ship heave, W z (truth)", |m| m.inputs.ship_position.z, |m, v| m.inputs.ship_position.z = v),
    V::held_input(240, "truth.tip.x", "m", components(&INPUTS.truth.tip)[0], "Truth feedback: tip position, W x (the crane's tip.x)", |m| m.inputs.truth.tip.x, |m, v| m.inputs.truth.tip.x = v),
    V::held_input(241, "truth.tip.y", "m", components(&INPUTS.truth.tip)[1], "Truth feedback: tip position, W y", |m| m.inputs.truth.tip.y, |m, v| m.inputs.truth.tip.y = v),
    V::held_input(242, "truth.tip.z", "m", components(&INPUTS.truth.tip)[2], "Truth feedback: tip position, W z", |m| m.inputs.truth.tip.z, |m, v| m.inputs.truth.tip.z = v),
    V::held_input(243, "truth.lp", "m", INPUTS.truth.lp, "Truth feedback: pendulum length (the crane's lp)", |m| m.inputs.truth.lp, |m, v| m.inputs.truth.lp = v),
    V::held_input(244, "truth.theta_x", "rad", INPUTS.truth.theta_x, "Truth feedback: pendulum angle theta_x (the pendulum's theta_x)", |m| m.inputs.truth.theta_x, |m, v| m.inputs.truth.theta_x = v),
    V::held_input(245, "truth.theta_y", "rad", INPUTS.truth.theta_y, "Truth feedback: pendulum angle theta_y", |m| m.inputs.truth.theta_y, |m, v| m.inputs.truth.theta_y = v),
    V::held_input(246, "truth.ship.roll", "rad", INPUTS.truth.ship[0], "Truth feedback: ship roll (Z-Y-X)", |m| m.inputs.truth.ship[0], |m, v| m.inputs.truth.ship[0] = v),
    V::held_input(247, "truth.ship.pitch", "rad", INPUTS.truth.ship[1], "Truth feedback: ship pitch", |m| m.inputs.truth.ship[1], |m, v| m.inputs.truth.ship[1] = v),
    V::held_input(248, "truth.ship.yaw", "rad", INPUTS.truth.ship[2], "Truth feedback: ship yaw", |m| m.inputs.truth.ship[2], |m, v| m.inputs.truth.ship[2] = v),
    // Inputs: external set-point (setpoint = 2).
    V::held_input(250, "sp_in.tip.x", "m", components(&INPUTS.external.tip)[0], "External set-point: tip position, W x", |m| m.inputs.external.tip.x, |m, v| m.inputs.external.tip.x = v),
    V::held_input(251, "sp_in.tip.y", "m", components(&INPUTS.external.tip)[1], "External set-point: tip position, W y", |m| m.inputs.external.tip.y, |m, v| m.inputs.external.tip.y = v),
    V::held_input(252, "sp_in.tip.z", "m", components(&INPUTS.external.tip)[2], "External set-point: tip position, W z", |m| m.inputs.external.tip.z, |m, v| m.inputs.external.tip.z = v),
    V::held_input(253, "sp_in.lp", "m", INPUTS.external.lp, "External set-point: pendulum length", |m| m.inputs.external.lp, |m, v| m.inputs.external.lp = v),
    // Outputs: surge, sway and heave the crane is placed with, and the EKF's rates.
    V::output(260, "est.ship.x", "m", "Ship surge, W x, the controller uses: the ship.x input, or the EKF's estimate with feedback = 2 (0 until an identification window shows modes)", |m| m.out.ship_position.x),
    V::output(261, "est.ship.y", "m", "Ship sway, W y, the controller uses", |m| m.out.ship_position.y),
    V::output(262, "est.ship.z", "m", "Ship heave, W z (down), the controller uses", |m| m.out.ship_position.z),
    V::output(263, "est.ship.vx", "m/s", "EKF surge rate, W x (feedback = 2; 0 otherwise)", |m| m.out.ship_rate.x),
    V::output(264, "est.ship.vy", "m/s", "EKF sway rate, W y", |m| m.out.ship_rate.y),
    V::output(265, "est.ship.vz", "m/s", "EKF heave rate, W z", |m| m.out.ship_rate.z),
    // Outputs: hardware commands (the crane's inputs).
    V::output(300, "u.base", "V", "Base actuator command, 0-3.3 V, neutral 1.65 V", |m| m.out.commands.volts[0]),
    V::output(301, "u.boom", "V", "Boom actuator command", |m| m.out.commands.volts[1]),
    V::output(302, "u.jib", "V", "Jib actuator command", |m| m.out.commands.volts[2]),
    V::output(303, "u.winch", "1", "Winch PWM duty, neutral 0.5", |m| m.out.commands.duty),
    // Outputs: the state the controller acts on (estimates; truth with truth feedback).
    V::output(310, "est.load.x", "m", "Load position, W x (eqs. 5.62-5.65)", |m| m.out.load.x),
    V::output(311, "est.load.y", "m", "Load position, W y", |m| m.out.load.y),
    V::output(312, "est.load.z", "m", "Load position, W z", |m| m.out.load.z),
    V::output(313, "est.theta_x", "rad", "Pendulum angle theta_x (eq. 5.59, low-passed)", |m| m.out.theta_x),
    V::output(314, "est.theta_y", "rad", "Pendulum angle theta_y (eq. 5.60, low-passed)", |m| m.out.theta_y),
    V::output(315, "est.ship.roll", "rad", "Ship roll (eq. 5.35, low-passed)", |m| m.out.ship[0]),
    V::output(316, "est.ship.pitch", "rad", "Ship pitch (eq. 5.36, low-passed)", |m| m.out.ship[1]),
    V::output(317, "est.ship.yaw", "rad", "Ship yaw less the yaw learnt before active_from (eq. 5.37, low-passed)", |m| m.out.ship[2]),
    V::output(318, "est.tip.x", "m", "Tip position, W x (potentiometers, forward kinematics, eq. 5.65)", |m| m.out.tip.x),
    V::output(319, "est.tip.y", "m", "Tip position, W y", |m| m.out.tip.y),
    V::output(320, "est.tip.z", "m", "Tip position, W z", |m| m.out.tip.z),
    V::output(321, "est.lp", "m", "Pendulum length (encoder and jib potentiometer, eqs. 3.1-3.4 with the controller's drum)", |m| m.out.lp),
    // Outputs: set-points.
    V::output(330, "sp.load.x", "m", "Desired load position, W x (below the desired tip)", |m| m.out.desired.load().x),
    V::output(331, "sp.load.y", "m", "Desired load position, W y", |m| m.out.desired.load().y),
    V::output(332, "sp.load.z", "m", "Desired load position, W z (desired tip z + desired length)", |m| m.out.desired.load().z),
    V::output(333, "sp.ref.tip.x", "m", "Desired tip position in force (fixed, pick-and-place or external), W x", |m| m.out.desired.tip.x),
    V::output(334, "sp.ref.tip.y", "m", "Desired tip position, W y", |m| m.out.desired.tip.y),
    V::output(335, "sp.ref.tip.z", "m", "Desired tip position, W z", |m| m.out.desired.tip.z),
    V::output(336, "sp.ref.lp", "m", "Desired pendulum length", |m| m.out.desired.lp),
    V::output(337, "sp.cmd.tip.x", "m", "Commanded tip set-point after the delta law (eqs. 6.28-6.30), W x", |m| m.out.commanded.tip.x),
    V::output(338, "sp.cmd.tip.y", "m", "Commanded tip set-point, W y", |m| m.out.commanded.tip.y),
    V::output(339, "sp.cmd.tip.z", "m", "Commanded tip set-point, W z", |m| m.out.commanded.tip.z),
    V::output(340, "sp.cmd.lp", "m", "Commanded pendulum length after the delta law (eq. 6.31)", |m| m.out.commanded.lp),
    V::output(341, "sp.d.base", "m", "Base actuator extension reference (inverse kinematics, clamped to 0-0.05 m)", |m| m.out.extensions[0]),
    V::output(342, "sp.d.boom", "m", "Boom actuator extension reference", |m| m.out.extensions[1]),
    V::output(343, "sp.d.jib", "m", "Jib actuator extension reference", |m| m.out.extensions[2]),
    V::output(344, "sp.winch", "deg", "Winch angle reference from home (controller drum, measured jib)", |m| m.out.winch),
    V::boolean_output(350, "active", "Commands are being issued (mode > 0 and t >= active_from)", |m| m.out.active),
    V::boolean_output(351, "sp.limited", "The commanded tip needed a stroke limit or was out of reach (previous references kept)", |m| m.out.limited),
];

fmi2::export_fmu!(CraneController);

#[cfg(test)]
mod tests;

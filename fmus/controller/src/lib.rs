//! FMU `controller`: the crane's myRIO software (SPEC §4.5; thesis Chapters 5–6).
//!
//! A sampled controller: every communication step it reads the crane sensors (potentiometer
//! volts, encoder degrees), the two IMUs' nine channels, the ship's surge/sway/heave and, for the
//! truth-feedback variant, truth values; it estimates the ship attitude and the pendulum angles
//! (complementary filters, or Madgwick's filter with `attitude_filter` = 1) and, with
//! `feedback` = 2, the ship's surge, sway and heave (the EKF of §5.1.3), computes the
//! world-frame set-point (inverse kinematics only, or the LQR-based delta law), converts it to
//! actuator and winch references, and runs the four joint PIDs. The physics and the algorithm
//! live in `physics::control::controller`; this crate is the variable table.
//!
//! Timing: the controller samples at its own period `sample_period` (100 Hz, §6.1), whatever the
//! communication step: `fmi2ExitInitializationMode` processes the sample at the start time, and
//! `fmi2DoStep(t, h)` processes every sample time start + n·period in (t, t + h] with the inputs
//! set before it. The outputs are held between samples (a zero-order hold, like the myRIO's).
//! At the default 10 ms step this is one sample per step; at 1 ms, one every tenth step, so the
//! closed loop's co-simulation error can be measured without changing the controller.

use fmu_model::{sling_parameters, xyz, Environment, Model, ModelInfo, SampleClock, Variable};
use physics::control::controller::{Controller, ControllerConfig, Feedback, Inputs, Mode, Outputs, SetpointSource};
use physics::control::lqr::GainSchedule;
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
    /// The sample times (the period is the `sample_period` parameter).
    clock: SampleClock,
}

impl CraneController {
    fn sample(&mut self, t: f64, dt: f64) -> Result<(), String> {
        self.out = self.controller.step(t, dt, &self.inputs)?;
        Ok(())
    }
}

impl Model for CraneController {
    const INFO: ModelInfo = ModelInfo::new(
        "controller",
        concat!(
            "Crane controller (the myRIO software): complementary-filter estimation of the ship attitude and the ",
            "pendulum angles, LQR-based world-frame compensation, crane inverse kinematics and PID joint control ",
            "(thesis chapters 5-6)"
        ),
    )
    .max_step(SampleClock::MAX_STEP_SIZE);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(_env: &Environment) -> Self {
        let controller = Controller::new(CONFIG).expect("the default configuration is valid");
        CraneController {
            config: CONFIG,
            inputs: INPUTS,
            out: placeholder_outputs(),
            controller,
            clock: SampleClock::new(SampleClock::DEFAULT_PERIOD),
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.controller = Controller::new(self.config)?;
        self.clock.restart(start_time);
        self.sample(start_time, self.clock.period)
    }

    /// The controller built at initialization (the configuration as set may be inconsistent
    /// until then, one parameter at a time: initialization checks it).
    fn validate_state(&self) -> Result<(), String> {
        self.controller.validate()
    }

    /// Its sample period: it reads its inputs once per communication step.
    fn largest_sensible_step(&self) -> Option<f64> {
        Some(self.clock.period)
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        let mut clock = self.clock;
        let period = clock.period;
        let result = clock.step(t, h, SampleClock::MAX_SAMPLES_PER_STEP, |time| self.sample(time, period));
        self.clock = clock;
        result
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
        desired_load: fixed.load(),
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

fmu_model::codes! {
    /// `mode`: 0 hold, 1 inverse-kinematic control only, 2 world-frame compensation.
    ModeCodes: Mode { Mode::Hold => 0, Mode::InverseKinematics => 1, Mode::Compensated => 2 }
}

fmu_model::codes! {
    /// `feedback`: 0 truth, 1 sensors, 2 sensors and the surge/sway/heave EKF (no truth).
    FeedbackCodes: Feedback { Feedback::Truth => 0, Feedback::Sensors => 1, Feedback::Estimated => 2 }
}

fmu_model::codes! {
    /// `setpoint`: 0 fixed, 1 pick-and-place profile, 2 external inputs.
    SetpointCodes: SetpointSource {
        SetpointSource::Fixed => 0,
        SetpointSource::PickAndPlace => 1,
        SetpointSource::External => 2,
    }
}

fmu_model::codes! {
    /// `cf_init`: 0 identity, 1 aligned on the first sample.
    AlignCodes: bool { false => 0, true => 1 }
}

fmu_model::codes! {
    /// `attitude_filter`: 0 complementary (the thesis' filter), 1 Madgwick.
    AttitudeCodes: AttitudeFilterKind { AttitudeFilterKind::Complementary => 0, AttitudeFilterKind::Madgwick => 1 }
}

fmu_model::codes! {
    /// `k.schedule`: 0 the angle gain fixed (the thesis), 1 scheduled over the measured length.
    ScheduleCodes: GainSchedule { GainSchedule::Fixed => 0, GainSchedule::Length => 1 }
}

fn set_g(m: &mut CraneController, g: f64) {
    m.config.ship_filter.g = g;
    m.config.load_filter.g = g;
}

type V = Variable<CraneController>;
type Real = fmu_model::Real<CraneController>;
type Integer = fmu_model::Integer<CraneController>;
type Boolean = fmu_model::Boolean<CraneController>;

/// Millimetres per metre, for the linear actuators' PID parameters (the controller works in mm,
/// the ports in m).
const MM: f64 = MM_PER_M;

/// The units of one joint PID's parameters at the ports.
struct PidUnits {
    kp: &'static str,
    ki: &'static str,
    kd: &'static str,
    e_db: &'static str,
    /// The actions: saturation, deadband and jump limits.
    u: &'static str,
}

/// The linear actuators: lengths in m at the ports (the PIDs work in mm), actions in V.
const ACTUATOR: PidUnits = PidUnits { kp: "V/m", ki: "V/(m.s)", kd: "V.s/m", e_db: "m", u: "V" };
/// The winch: angles in degrees, actions as PWM duty.
const WINCH: PidUnits = PidUnits { kp: "1/deg", ki: "1/(deg.s)", kd: "s/deg", e_db: "deg", u: "1" };

/// The nine parameter rows of joint PID `pid` (`m.config.pid[pid]`, Table 6.1) at value
/// references `vr`..`vr + 8`, named after `prefix`. A port value is the PID's value times `scale`
/// for the gains (and divided by it for the error deadband): millimetres per metre for the
/// linear actuators, 1 for the winch, whose PID works in the port units. The descriptions are
/// per parameter, since the joints cite different equations.
macro_rules! pid {
    ($vr:literal, $prefix:literal, $pid:literal, scale: $scale:expr, units: $units:expr, e_db_max: $e_db_max:expr,
     kp: $kp:literal, ki: $ki:literal, kd: $kd:literal, e_db: $e_db:literal, sat_ll: $sat_ll:literal,
     sat_ul: $sat_ul:literal, db_ll: $db_ll:literal, db_ul: $db_ul:literal, u_db: $u_db:literal) => {
        [
            pid!(@gain $vr, $prefix, "kp", $pid, kp, $scale, $units.kp, $kp),
            pid!(@gain $vr + 1, $prefix, "ki", $pid, ki, $scale, $units.ki, $ki),
            pid!(@gain $vr + 2, $prefix, "kd", $pid, kd, $scale, $units.kd, $kd),
            Real::parameter($vr + 3, concat!($prefix, "e_db"))
                .unit($units.e_db)
                .start(CONFIG.pid[$pid].error_deadband / $scale)
                .range(0.0, $e_db_max)
                .doc($e_db)
                .get(|m| m.config.pid[$pid].error_deadband / $scale)
                .set(|m, v| m.config.pid[$pid].error_deadband = v * $scale),
            pid!(@action $vr + 4, $prefix, "sat_ll", $pid, sat_lower, $units.u, $sat_ll),
            pid!(@action $vr + 5, $prefix, "sat_ul", $pid, sat_upper, $units.u, $sat_ul),
            pid!(@action $vr + 6, $prefix, "db_ll", $pid, deadband_lower, $units.u, $db_ll),
            pid!(@action $vr + 7, $prefix, "db_ul", $pid, deadband_upper, $units.u, $db_ul),
            pid!(@action $vr + 8, $prefix, "u_db", $pid, jump_threshold, $units.u, $u_db),
        ]
    };
    (@gain $vr:expr, $prefix:literal, $name:literal, $pid:literal, $field:ident, $scale:expr, $unit:expr,
     $doc:literal) => {
        Real::parameter($vr, concat!($prefix, $name))
            .unit($unit)
            .start(CONFIG.pid[$pid].$field * $scale)
            .doc($doc)
            .get(|m| m.config.pid[$pid].$field * $scale)
            .set(|m, v| m.config.pid[$pid].$field = v / $scale)
    };
    (@action $vr:expr, $prefix:literal, $name:literal, $pid:literal, $field:ident, $unit:expr, $doc:literal) => {
        fmu_model::field!(Real::parameter($vr, concat!($prefix, $name)), unit: $unit, doc: $doc,
            field: (m.config, CONFIG).pid[$pid].$field)
    };
}

/// The variable table in sections (value references: parameters 0–99, inputs 200–259, outputs
/// 260–269 and 300+).
const GROUPS: &[&[V]] = &[
    &[
        // Parameters: operation.
        fmu_model::coded!(Integer::tunable(0, "mode"), ModeCodes, start: CONFIG.mode,
            doc: concat!(
                "0 hold (crane off, neutral commands), 1 inverse-kinematic control only (uncompensated), 2 ",
                "world-frame compensation (section 6.2); tunable, so an operator can switch compensation on and ",
                "off between steps"
            ),
            value: |m| m.config.mode),
        fmu_model::coded!(Integer::parameter(1, "feedback"), FeedbackCodes, start: CONFIG.feedback,
            doc: concat!(
                "0 truth (tip, length, pendulum angles and ship attitude from the truth inputs), 1 sensors ",
                "(potentiometers, encoder, attitude filters; surge/sway/heave from the ship.* truth inputs, as the ",
                "thesis), 2 sensors with surge/sway/heave from the EKF of section 5.1.3 (ekf.*): no truth input is ",
                "read"
            ),
            value: |m| m.config.feedback),
        fmu_model::coded!(Integer::parameter(2, "setpoint"), SetpointCodes, start: CONFIG.setpoint,
            doc: "0 fixed (sp.tip.*, sp.lp), 1 pick-and-place profile from active_from, 2 external inputs sp_in.*",
            value: |m| m.config.setpoint),
        fmu_model::coded!(Integer::parameter(3, "cf_init"), AlignCodes, start: CONFIG.align,
            doc: concat!(
                "Complementary filter start: 0 identity (thesis behaviour, initial estimation kick), 1 aligned on ",
                "the first accelerometer and magnetometer sample"
            ),
            value: |m| m.config.align),
        fmu_model::coded!(Integer::parameter(22, "attitude_filter"), AttitudeCodes, start: CONFIG.attitude,
            doc: concat!(
                "Attitude estimator of both IMUs: 0 the complementary filter (section 5.1.1, cf1.*/cf2.*), 1 ",
                "Madgwick's gradient-descent filter (mw1.beta/mw2.beta)"
            ),
            value: |m| m.config.attitude),
        fmu_model::sample_period!(21, m => m.clock,
            doc: "Control and sampling period (100 Hz, section 6.1); independent of the communication step"),
        fmu_model::field!(Real::parameter(4, "active_from"), unit: "s",
            doc: concat!(
                "Time from which commands are issued (estimation runs from the start); the pick-and-place profile ",
                "starts here"
            ),
            field: (m.config, CONFIG).active_from),
    ],
    &xyz!(Real::parameter(5, "sp.tip."),
        unit: "m",
        doc: [
            "Fixed set-point: tip position, W x",
            "Fixed set-point: tip position, W y",
            "Fixed set-point: tip position, W z (down)",
        ],
        field: (m.config, CONFIG).fixed.tip),
    &[fmu_model::field!(Real::parameter(8, "sp.lp"), unit: "m", range: (0.01, 10.0),
        doc: "Fixed set-point: pendulum length",
        field: (m.config, CONFIG).fixed.lp)],
    &xyz!(Real::parameter(9, "r_base."),
        unit: "m",
        doc: [
            "Crane base frame J12 origin in the ship frame B, x",
            "Crane base frame J12 origin in B, y (crane on the port side)",
            "Crane base frame J12 origin in B, z",
        ],
        field: (m.config, CONFIG).crane_base),
    &[
        Real::parameter(12, "winch.diameter")
            .unit("m")
            .start(CONFIG.cable.drum_diameter / MM)
            .range(0.001, 1.0)
            .doc(concat!(
                "Nominal winch drum diameter the controller converts lengths with (section 6.1; the plant's is ",
                "0.04126 m)"
            ))
            .get(|m| m.config.cable.drum_diameter / MM)
            .set(|m, v| m.config.cable.drum_diameter = v * MM),
        Real::parameter(13, "g")
            .unit("m/s2")
            .start(CONFIG.ship_filter.g)
            .range(0.1, 100.0)
            .doc("Gravitational acceleration the accelerometer magnitude is compared with (eq. 5.20)")
            .get(|m| m.config.ship_filter.g)
            .set(set_g),
        fmu_model::field!(Real::parameter(14, "lowpass.bias"), unit: "Hz", range: (0.0, 1000.0),
            doc: concat!(
                "Cut-off of the low-pass that learns the ship yaw (and optionally the load angle offsets) before ",
                "active_from (section 5.3); 0 learns the first sample only"
            ),
            field: (m.config, CONFIG).bias_cutoff),
        fmu_model::field!(Real::parameter(15, "lowpass.angles"), unit: "Hz", range: (0.0, 1000.0),
            doc: "Cut-off of the low-pass on the estimated angles (section 5.3); 0 = none",
            field: (m.config, CONFIG).angle_cutoff),
        fmu_model::field!(Boolean::parameter(16, "bias.load"),
            doc: concat!(
                "Also learn the load angles before active_from and remove them as IMU mounting offsets (section ",
                "5.3); off by default because the load is held displaced during initialisation"
            ),
            field: (m.config, CONFIG).load_bias),
        // Parameters: compensation (section 6.2).
        fmu_model::field!(Real::parameter(17, "k.position"), unit: "1",
            doc: "Delta-law gain K_P on the tip position and length errors",
            field: (m.config, CONFIG).compensation.position),
        fmu_model::field!(Real::parameter(18, "k.angle"), unit: "m/rad",
            doc: "Delta-law gain K_P on the pendulum angle errors (dy_t = e_y + k e_thx, dx_t = e_x - k e_thy)",
            field: (m.config, CONFIG).compensation.angle),
        fmu_model::coded!(Integer::parameter(27, "k.schedule"), ScheduleCodes, start: CONFIG.compensation.schedule,
            doc: concat!(
                "Angle gain over the cable length: 0 fixed at k.angle (the thesis), 1 scheduled from the first ",
                "active sample, k.angle * K(l)/K(l_d) with K(l) the section 6.2 LQR's angle-to-tip-acceleration ",
                "gain (Q = 10 I, R = I) redesigned at the measured length l whenever it moved by more than 1 %, ",
                "l_d the desired length at activation (docs/tuning.md)"
            ),
            value: |m| m.config.compensation.schedule),
        fmu_model::field!(Real::parameter(19, "deadband.position"), unit: "m", range: (0.0, 1.0),
            doc: "Error deadband on the tip position and length",
            field: (m.config, CONFIG).compensation.position_deadband),
        fmu_model::field!(Real::parameter(20, "deadband.angle"), unit: "rad", range: (0.0, 1.0),
            doc: "Error deadband on the pendulum angles",
            field: (m.config, CONFIG).compensation.angle_deadband),
        // Parameters: the surge/sway/heave EKF (section 5.1.3; feedback = 2).
        fmu_model::field!(Real::parameter(37, "ekf.window"), unit: "s", range: (1.0, 600.0),
            doc: concat!(
                "EKF identification window: every window's FFT and peak detection starts the filter of each axis ",
                "that shows modes (20 s: the first window of a campaign run holds 8-10 s of ship motion)"
            ),
            field: (m.config, CONFIG).linear.window),
        Integer::parameter(38, "ekf.modes")
            .start(CONFIG.linear.search.modes as i32)
            .range(1, MAX_MODES as i32)
            .doc("EKF oscillator modes per axis, N_m (section 5.1.3)")
            .get(|m| m.config.linear.search.modes as i32)
            .set(|m, v| m.config.linear.search.modes = v as usize),
        fmu_model::field!(Real::parameter(39, "ekf.floor"), unit: "m/s2", range: (0.0, 10.0),
            doc: concat!(
                "Smallest acceleration amplitude of an identified mode: a still deck's noise maxima stay below it, ",
                "so a still axis estimates zero"
            ),
            field: (m.config, CONFIG).linear.search.floor),
        // Parameters: complementary filters (Table 5.1 ship, Table 5.2 load).
        fmu_model::field!(Real::parameter(30, "cf1.beta"), unit: "1", range: (-1.0, 1.0),
            doc: "Ship filter: LERP above, SLERP below this delta-quaternion scalar part (eqs. 5.19, 5.26)",
            field: (m.config, CONFIG).ship_filter.beta),
        fmu_model::field!(Real::parameter(31, "cf1.alpha_a"), unit: "1", range: (0.0, 1.0),
            doc: "Ship filter: accelerometer gain (eq. 5.21)",
            field: (m.config, CONFIG).ship_filter.alpha_a),
        fmu_model::field!(Real::parameter(32, "cf1.beta_a_ll"), unit: "1",
            doc: "Ship filter: magnitude error up to which the full accelerometer gain applies (eq. 5.21)",
            field: (m.config, CONFIG).ship_filter.beta_a_ll),
        fmu_model::field!(Real::parameter(33, "cf1.beta_a_ul"), unit: "1",
            doc: "Ship filter: magnitude error from which the accelerometer is ignored (eq. 5.21)",
            field: (m.config, CONFIG).ship_filter.beta_a_ul),
        fmu_model::field!(Real::parameter(34, "cf1.alpha_m"), unit: "1", range: (0.0, 1.0),
            doc: "Ship filter: magnetometer gain (eq. 5.27)",
            field: (m.config, CONFIG).ship_filter.alpha_m),
        fmu_model::field!(Real::parameter(35, "cf1.beta_m"), unit: "1",
            doc: "Ship filter: exponential rejection of large magnetic corrections (eq. 5.27)",
            field: (m.config, CONFIG).ship_filter.beta_m),
        fmu_model::field!(Real::parameter(36, "mw1.beta"), unit: "rad/s", range: (0.0, 10.0),
            doc: concat!(
                "Ship Madgwick filter: gain beta = sqrt(3/4) times the gyro error (Madgwick 2010, eqs. 43, 50); ",
                "default from the 0.0035 rad/s gyro noise"
            ),
            field: (m.config, CONFIG).ship_madgwick.beta),
        fmu_model::field!(Real::parameter(40, "cf2.beta"), unit: "1", range: (-1.0, 1.0),
            doc: "Load filter: LERP/SLERP threshold (eqs. 5.19, 5.26)",
            field: (m.config, CONFIG).load_filter.beta),
        fmu_model::field!(Real::parameter(41, "cf2.alpha_a"), unit: "1", range: (0.0, 1.0),
            doc: "Load filter: accelerometer gain (eq. 5.21)",
            field: (m.config, CONFIG).load_filter.alpha_a),
        fmu_model::field!(Real::parameter(42, "cf2.beta_a_ll"), unit: "1",
            doc: "Load filter: magnitude error up to which the full accelerometer gain applies",
            field: (m.config, CONFIG).load_filter.beta_a_ll),
        fmu_model::field!(Real::parameter(43, "cf2.beta_a_ul"), unit: "1",
            doc: "Load filter: magnitude error from which the accelerometer is ignored",
            field: (m.config, CONFIG).load_filter.beta_a_ul),
        fmu_model::field!(Real::parameter(44, "cf2.alpha_m"), unit: "1", range: (0.0, 1.0),
            doc: "Load filter: magnetometer gain (eq. 5.27)",
            field: (m.config, CONFIG).load_filter.alpha_m),
        fmu_model::field!(Real::parameter(45, "cf2.beta_m"), unit: "1",
            doc: "Load filter: exponential rejection of large magnetic corrections (eq. 5.27)",
            field: (m.config, CONFIG).load_filter.beta_m),
        fmu_model::field!(Real::parameter(46, "mw2.beta"), unit: "rad/s", range: (0.0, 10.0),
            doc: "Load Madgwick filter: gain beta (Madgwick 2010, eqs. 43, 50)",
            field: (m.config, CONFIG).load_madgwick.beta),
        fmu_model::field!(Boolean::parameter(47, "bias.gyro"),
            doc: concat!(
                "Learn both IMUs' gyro biases as the mean reading before active_from (both IMUs assumed at rest) ",
                "and subtract them; off by default (the simulated biases are 0)"
            ),
            field: (m.config, CONFIG).gyro_bias),
        fmu_model::field!(Boolean::parameter(48, "bias.load_heading"),
            doc: concat!(
                "Turn the load estimate by IMU2's own mean yaw before active_from instead of IMU1's learnt yaw ",
                "(removes a difference between the fields the two IMUs see; assumes the load faces the deck's ",
                "heading then)"
            ),
            field: (m.config, CONFIG).load_heading),
        fmu_model::field!(Boolean::parameter(49, "encoder.relative"),
            doc: concat!(
                "Count the encoder from its first sample, offset by the winch angle of the initial length ",
                "(encoder.lp0) at winch.diameter, as the thesis' controller does (section 6.1); false reads it as ",
                "the angle from the winch home, so the drum mismatch offsets every length reading"
            ),
            field: (m.config, CONFIG).relative_encoder),
        Real::parameter(23, "encoder.lp0")
            .unit("m")
            .start(0.0)
            .range(0.0, 10.0)
            .doc(concat!(
                "Initial cable length the relative encoder starts from; 0 takes sp.lp (the initial length in every ",
                "thesis test); set it when sp.lp commands a new length"
            ))
            .get(|m| m.config.initial_length.unwrap_or(0.0))
            .set(|m, v| m.config.initial_length = (v != 0.0).then_some(v)),
    ],
    // Parameters: a sling below the hook (docs/rigging.md), beyond the thesis.
    &sling_parameters!(24, m => m.config.sling, start: CONFIG.sling, notch_on: "the load IMU's angles"),
    // Parameters: joint PIDs (Table 6.1), linear actuators in SI (0.6 V/mm = 600 V/m).
    &pid!(50, "pid.base.", 0, scale: MM, units: ACTUATOR, e_db_max: 0.05,
        kp: "Base actuator proportional gain (0.6 V/mm)",
        ki: "Base actuator integral gain",
        kd: "Base actuator derivative gain (on the measurement)",
        e_db: "Base actuator error deadband (eq. 6.10)",
        sat_ll: "Base actuator lower saturation (eq. 6.4)",
        sat_ul: "Base actuator upper saturation (eq. 6.4)",
        db_ll: "Base actuator lower deadband to jump (eq. 6.11)",
        db_ul: "Base actuator upper deadband to jump (eq. 6.11)",
        u_db: "Base actuator minimum action for a deadband jump (eq. 6.11)"),
    &pid!(60, "pid.boom.", 1, scale: MM, units: ACTUATOR, e_db_max: 0.05,
        kp: "Boom actuator proportional gain (0.45 V/mm)",
        ki: "Boom actuator integral gain",
        kd: "Boom actuator derivative gain",
        e_db: "Boom actuator error deadband",
        sat_ll: "Boom actuator lower saturation",
        sat_ul: "Boom actuator upper saturation",
        db_ll: "Boom actuator lower deadband to jump",
        db_ul: "Boom actuator upper deadband to jump",
        u_db: "Boom actuator minimum action for a deadband jump"),
    &pid!(70, "pid.jib.", 2, scale: MM, units: ACTUATOR, e_db_max: 0.05,
        kp: "Jib actuator proportional gain (0.59 V/mm)",
        ki: "Jib actuator integral gain",
        kd: "Jib actuator derivative gain",
        e_db: "Jib actuator error deadband",
        sat_ll: "Jib actuator lower saturation",
        sat_ul: "Jib actuator upper saturation",
        db_ll: "Jib actuator lower deadband to jump",
        db_ul: "Jib actuator upper deadband to jump",
        u_db: "Jib actuator minimum action for a deadband jump"),
    &pid!(80, "pid.winch.", 3, scale: 1.0, units: WINCH, e_db_max: 360.0,
        kp: "Winch proportional gain (duty per degree)",
        ki: "Winch integral gain (trapezoidal, anti-windup eq. 6.9)",
        kd: "Winch derivative gain (on the measurement, eq. 6.8)",
        e_db: "Winch error deadband",
        sat_ll: "Winch lower saturation (duty)",
        sat_ul: "Winch upper saturation (duty)",
        db_ll: "Winch lower deadband to jump (duty)",
        db_ul: "Winch upper deadband to jump (duty)",
        u_db: "Winch minimum action for a deadband jump (duty)"),
    &[
        // Inputs: crane sensors (the crane's outputs).
        fmu_model::field!(Real::held_input(200, "pot.base"), unit: "V",
            doc: "Base potentiometer, 0-5 V over 0-50 mm",
            field: (m.inputs, INPUTS).pots[0]),
        fmu_model::field!(Real::held_input(201, "pot.boom"), unit: "V",
            doc: "Boom potentiometer",
            field: (m.inputs, INPUTS).pots[1]),
        fmu_model::field!(Real::held_input(202, "pot.jib"), unit: "V",
            doc: "Jib potentiometer",
            field: (m.inputs, INPUTS).pots[2]),
        fmu_model::field!(Real::held_input(203, "encoder"), unit: "deg",
            doc: concat!(
                "Winch encoder, multi-turn, from the winch home (the default is the fixed set-point's l_p in the ",
                "controller's cable model, so a bare instance holds the winch still)"
            ),
            field: (m.inputs, INPUTS).encoder),
    ],
    // Inputs: IMU1 (deck) and IMU2 (load), sensor frames.
    &xyz!(Real::held_input(210, "imu1.gyro."),
        unit: "rad/s",
        doc: ("Deck IMU gyroscope " + axis),
        field: (m.inputs, INPUTS).imu1.gyro),
    &xyz!(Real::held_input(213, "imu1.acc."),
        unit: "m/s2",
        doc: [
            "Deck IMU specific force x",
            "Deck IMU specific force y",
            "Deck IMU specific force z (-g at rest, level)",
        ],
        field: (m.inputs, INPUTS).imu1.acc),
    &xyz!(Real::held_input(216, "imu1.mag."),
        unit: "1",
        doc: ["Deck IMU magnetometer x (unit field vector)", "Deck IMU magnetometer y", "Deck IMU magnetometer z"],
        field: (m.inputs, INPUTS).imu1.mag),
    &xyz!(Real::held_input(220, "imu2.gyro."),
        unit: "rad/s",
        doc: ("Load IMU gyroscope " + axis),
        field: (m.inputs, INPUTS).imu2.gyro),
    &xyz!(Real::held_input(223, "imu2.acc."),
        unit: "m/s2",
        doc: ("Load IMU specific force " + axis),
        field: (m.inputs, INPUTS).imu2.acc),
    &xyz!(Real::held_input(226, "imu2.mag."),
        unit: "1",
        doc: ("Load IMU magnetometer " + axis),
        field: (m.inputs, INPUTS).imu2.mag),
    // Inputs: ship position (truth, as the thesis supplied it) and the truth-feedback variant.
    &xyz!(Real::held_input(230, "ship."),
        unit: "m",
        doc: ["Ship surge, W x (truth)", "Ship sway, W y (truth)", "Ship heave, W z (truth)"],
        field: (m.inputs, INPUTS).ship_position),
    &xyz!(Real::held_input(240, "truth.tip."),
        unit: "m",
        doc: [
            "Truth feedback: tip position, W x (the crane's tip.x)",
            "Truth feedback: tip position, W y",
            "Truth feedback: tip position, W z",
        ],
        field: (m.inputs, INPUTS).truth.tip),
    &[
        fmu_model::field!(Real::held_input(243, "truth.lp"), unit: "m",
            doc: "Truth feedback: pendulum length (the crane's lp)",
            field: (m.inputs, INPUTS).truth.lp),
        fmu_model::field!(Real::held_input(244, "truth.theta_x"), unit: "rad",
            doc: "Truth feedback: pendulum angle theta_x (the pendulum's theta_x)",
            field: (m.inputs, INPUTS).truth.theta_x),
        fmu_model::field!(Real::held_input(245, "truth.theta_y"), unit: "rad",
            doc: "Truth feedback: pendulum angle theta_y",
            field: (m.inputs, INPUTS).truth.theta_y),
        fmu_model::field!(Real::held_input(246, "truth.ship.roll"), unit: "rad",
            doc: "Truth feedback: ship roll (Z-Y-X)",
            field: (m.inputs, INPUTS).truth.ship[0]),
        fmu_model::field!(Real::held_input(247, "truth.ship.pitch"), unit: "rad",
            doc: "Truth feedback: ship pitch",
            field: (m.inputs, INPUTS).truth.ship[1]),
        fmu_model::field!(Real::held_input(248, "truth.ship.yaw"), unit: "rad",
            doc: "Truth feedback: ship yaw",
            field: (m.inputs, INPUTS).truth.ship[2]),
    ],
    // Inputs: external set-point (setpoint = 2).
    &xyz!(Real::held_input(250, "sp_in.tip."),
        unit: "m",
        doc: ("External set-point: tip position, W " + axis),
        field: (m.inputs, INPUTS).external.tip),
    &[fmu_model::field!(Real::held_input(253, "sp_in.lp"), unit: "m",
        doc: "External set-point: pendulum length",
        field: (m.inputs, INPUTS).external.lp)],
    // Inputs: a correction of the commanded tip (an agent's residual on top of the law).
    &xyz!(Real::held_input(254, "residual.tip."),
        unit: "m",
        doc: ("Added to the commanded tip after the delta law (0: the law's command), W " + axis),
        field: (m.inputs, INPUTS).residual),
    // Outputs: surge, sway and heave the crane is placed with, and the EKF's rates.
    &xyz!(Real::output(260, "est.ship."),
        unit: "m",
        doc: [
            concat!(
                "Ship surge, W x, the controller uses: the ship.x input, or the EKF's estimate with feedback = 2 ",
                "(0 until an identification window shows modes)"
            ),
            "Ship sway, W y, the controller uses",
            "Ship heave, W z (down), the controller uses",
        ],
        get: |m| m.out.ship_position),
    &xyz!(Real::output(263, "est.ship.v"),
        unit: "m/s",
        doc: ["EKF surge rate, W x (feedback = 2; 0 otherwise)", "EKF sway rate, W y", "EKF heave rate, W z"],
        get: |m| m.out.ship_rate),
    &[
        // Outputs: hardware commands (the crane's inputs).
        Real::output(300, "u.base")
            .unit("V")
            .doc("Base actuator command, 0-3.3 V, neutral 1.65 V")
            .get(|m| m.out.commands.volts[0]),
        Real::output(301, "u.boom").unit("V").doc("Boom actuator command").get(|m| m.out.commands.volts[1]),
        Real::output(302, "u.jib").unit("V").doc("Jib actuator command").get(|m| m.out.commands.volts[2]),
        Real::output(303, "u.winch").unit("1").doc("Winch PWM duty, neutral 0.5").get(|m| m.out.commands.duty),
    ],
    // Outputs: the state the controller acts on (estimates; truth with truth feedback).
    &xyz!(Real::output(310, "est.load."),
        unit: "m",
        doc: ["Load position, W x (eqs. 5.62-5.65, at est.lp + sling.length)", "Load position, W y", "Load position, W z"],
        get: |m| m.out.load),
    &[
        Real::output(313, "est.theta_x")
            .unit("rad")
            .doc("Pendulum angle theta_x (eq. 5.59, low-passed)")
            .get(|m| m.out.theta_x),
        Real::output(314, "est.theta_y")
            .unit("rad")
            .doc("Pendulum angle theta_y (eq. 5.60, low-passed)")
            .get(|m| m.out.theta_y),
        Real::output(315, "est.ship.roll").unit("rad").doc("Ship roll (eq. 5.35, low-passed)").get(|m| m.out.ship[0]),
        Real::output(316, "est.ship.pitch").unit("rad").doc("Ship pitch (eq. 5.36, low-passed)").get(|m| m.out.ship[1]),
        Real::output(317, "est.ship.yaw")
            .unit("rad")
            .doc("Ship yaw less the yaw learnt before active_from (eq. 5.37, low-passed)")
            .get(|m| m.out.ship[2]),
    ],
    &xyz!(Real::output(318, "est.tip."),
        unit: "m",
        doc: [
            "Tip position, W x (potentiometers, forward kinematics, eq. 5.65)",
            "Tip position, W y",
            "Tip position, W z",
        ],
        get: |m| m.out.tip),
    &[Real::output(321, "est.lp")
        .unit("m")
        .doc("Pendulum length (encoder and jib potentiometer, eqs. 3.1-3.4 with the controller's drum)")
        .get(|m| m.out.lp)],
    // Outputs: set-points.
    &xyz!(Real::output(330, "sp.load."),
        unit: "m",
        doc: [
            "Desired load position, W x (below the desired tip)",
            "Desired load position, W y",
            "Desired load position, W z (desired tip z + desired length + sling.length)",
        ],
        get: |m| m.out.desired_load),
    &xyz!(Real::output(333, "sp.ref.tip."),
        unit: "m",
        doc: [
            "Desired tip position in force (fixed, pick-and-place or external), W x",
            "Desired tip position, W y",
            "Desired tip position, W z",
        ],
        get: |m| m.out.desired.tip),
    &[Real::output(336, "sp.ref.lp").unit("m").doc("Desired pendulum length").get(|m| m.out.desired.lp)],
    &xyz!(Real::output(337, "sp.cmd.tip."),
        unit: "m",
        doc: [
            "Commanded tip set-point after the delta law (eqs. 6.28-6.30), W x",
            "Commanded tip set-point, W y",
            "Commanded tip set-point, W z",
        ],
        get: |m| m.out.commanded.tip),
    &[
        Real::output(340, "sp.cmd.lp")
            .unit("m")
            .doc("Commanded pendulum length after the delta law (eq. 6.31)")
            .get(|m| m.out.commanded.lp),
        Real::output(341, "sp.d.base")
            .unit("m")
            .doc("Base actuator extension reference (inverse kinematics, clamped to 0-0.05 m)")
            .get(|m| m.out.extensions[0]),
        Real::output(342, "sp.d.boom").unit("m").doc("Boom actuator extension reference").get(|m| m.out.extensions[1]),
        Real::output(343, "sp.d.jib").unit("m").doc("Jib actuator extension reference").get(|m| m.out.extensions[2]),
        Real::output(344, "sp.winch")
            .unit("deg")
            .doc("Winch angle reference from home (controller drum, measured jib)")
            .get(|m| m.out.winch),
        Boolean::output(350, "active")
            .doc("Commands are being issued (mode > 0 and t >= active_from)")
            .get(|m| m.out.active),
        Boolean::output(351, "sp.limited")
            .doc("The commanded tip needed a stroke limit or was out of reach (previous references kept)")
            .get(|m| m.out.limited),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(CraneController);

#[cfg(test)]
mod tests;

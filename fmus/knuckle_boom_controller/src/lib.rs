//! FMU `knuckle_boom_controller`: the control software of the full-scale offshore crane
//! (`knuckle_boom`; docs/full-scale.md).
//!
//! A sampled controller ([`physics::offshore_control::controller`]): at every sample time
//! start + n·`sample_period`, n ≥ 1, it reads the crane's joint angles and hoist length, the
//! deck's motion (a motion reference unit) and the load's position and velocity, and sets the
//! four valve spools: the arm holds its start (mode 1) or compensates in the world frame with the
//! anti-sway law (mode 2), and the winch compensates the heave (heave 1), or holds its length
//! while the arm holds the tip's height (heave 2) or nobody compensates (heave 0). The
//! references are latched at the first sample; until then the spools are centred. They hold
//! (setpoint 0), or follow the thesis' pick-and-place profile Froude-scaled to this crane
//! (setpoint 1: lengths ×25, times ×5, 600 s from the latch). The outputs
//! are held between samples (a zero-order hold), so the result does not depend on how the
//! master divides the steps.

use fmu_model::{ship_inputs, sling_parameters, xyz, Environment, Model, ModelInfo, SampleClock, Variable};
use physics::control::lqr::GainSchedule;
use physics::hydraulic_crane::plant::{BOOM, JIB, SLEW, WINCH};
use physics::math::components;
use physics::motion::ShipMotion;
use physics::offshore_control::controller::{Commands, Heave, Measured, Mode, OffshoreConfig, OffshoreController};
use physics::offshore_control::drives::RatedSpeeds;
use physics::offshore_control::setpoint::SetpointSource;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// Instance data: the configuration as set, the controller built from it at initialization, the
/// inputs as last set and the last sample's commands.
#[derive(Clone, Serialize, Deserialize)]
pub struct KnuckleBoomController {
    /// The crane description as set (`crane`) and the one `config.crane` was last loaded from.
    crane: String,
    loaded: Option<String>,
    resource_dir: Option<PathBuf>,
    /// The crane's fingerprint and rated speeds as connected ([`CRANE_INTERFACE`]; 0 = not
    /// connected, nothing to compare).
    crane_interface: [f64; 7],
    /// The same values for the controller's own crane, computed at initialization (the
    /// fingerprint hashes every parameter: too much work for every sample).
    own_interface: [f64; 7],
    config: OffshoreConfig,
    controller: OffshoreController,
    inputs: Measured,
    out: Commands,
    clock: SampleClock,
    /// No sample acts before this time (s): the spools stay centred, nothing is latched.
    active_from: f64,
}

const CONFIG: OffshoreConfig = OffshoreConfig::DEFAULT;

/// The crane's outputs the controller compares with its own crane: name, unit and what the
/// controller's description gives (in the order of `crane_interface`).
const CRANE_INTERFACE: [(&str, &str); 7] = [
    ("crane.fingerprint", "1"),
    ("rated.boom.extend", "m/s"),
    ("rated.boom.retract", "m/s"),
    ("rated.jib.extend", "m/s"),
    ("rated.jib.retract", "m/s"),
    ("rated.slew", "rad/s"),
    ("rated.rope", "m/s"),
];

impl KnuckleBoomController {
    /// The values of [`CRANE_INTERFACE`] for the controller's own crane.
    fn interface_of(&self) -> [f64; 7] {
        let crane = &self.config.crane;
        let r = RatedSpeeds::of(crane);
        let [(be, br), (je, jr)] = r.cylinders;
        [crane_description::fingerprint(crane), be, br, je, jr, r.slew, r.rope]
    }

    /// Refuses a connected crane that is not the controller's: the named values first (they say
    /// what differs), then the fingerprint (everything else, the mounting point included).
    fn check_crane(&self) -> Result<(), String> {
        let own = self.own_interface;
        let order = [1, 2, 3, 4, 5, 6, 0];
        for i in order {
            let (crane, mine) = (self.crane_interface[i], own[i]);
            if crane != 0.0 && (crane - mine).abs() > 1e-12 * mine.abs() {
                let (name, unit) = CRANE_INTERFACE[i];
                let unit = if unit == "1" { String::new() } else { format!(" {unit}") };
                return Err(format!(
                    "the crane is not the controller's: {name} is {crane}{unit} at the crane and {mine}{unit} \
                     here (crane description '{}'); give both FMUs the same `crane` and `base.*`",
                    self.crane
                ));
            }
        }
        Ok(())
    }

    /// Loads the description `crane` names into the controller's crane, once per name; the
    /// mounting point stays the controller's `base.*`.
    fn configure(&mut self) -> Result<(), String> {
        if self.loaded.as_deref() != Some(self.crane.as_str()) {
            let d = crane_description::load(&self.crane, self.resource_dir.as_deref())?;
            self.config.crane = d.params(self.config.crane.arm.base);
            self.loaded = Some(self.crane.clone());
        }
        Ok(())
    }

    fn sample(&mut self, time: f64) -> Result<(), String> {
        if time < self.active_from - fmu_model::time_tolerance(time) {
            return Ok(());
        }
        self.check_crane()?;
        self.out = self.controller.step(&self.inputs, self.clock.period)?;
        Ok(())
    }

    fn set_ship(&mut self, set: impl FnOnce(&mut ShipMotion)) {
        set(&mut self.inputs.ship);
    }
}

impl Model for KnuckleBoomController {
    const INFO: ModelInfo = ModelInfo::new(
        "knuckle_boom_controller",
        concat!(
            "Control of the full-scale offshore knuckle-boom crane: joint loops on the valve spools through the ",
            "cylinder mechanisms, world-frame anti-sway (LQR at the full-scale hoist length) and active heave ",
            "compensation by the winch"
        ),
    )
    .max_step(SampleClock::MAX_STEP_SIZE);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(env: &Environment) -> Self {
        KnuckleBoomController {
            crane: String::new(),
            // CONFIG's crane is the default description's (crane-description's tests).
            loaded: Some(crane_description::catalogue::DEFAULT_CRANE.to_string()),
            resource_dir: env.resource_dir.clone(),
            crane_interface: [0.0; 7],
            own_interface: [0.0; 7],
            config: CONFIG,
            controller: OffshoreController::new(CONFIG),
            inputs: INPUTS,
            out: Commands::default(),
            clock: SampleClock::new(SampleClock::DEFAULT_PERIOD),
            active_from: 0.0,
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.configure()?;
        self.config.validate()?;
        self.own_interface = self.interface_of();
        self.controller = OffshoreController::new(self.config);
        self.clock.restart(start_time);
        self.out = Commands::default();
        Ok(())
    }

    /// Its sample period: it reads its inputs once per communication step.
    fn largest_sensible_step(&self) -> Option<f64> {
        Some(self.clock.period)
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        // Tunable: the operating modes as set now.
        self.controller.config.mode = self.config.mode;
        self.controller.config.heave = self.config.heave;
        let mut clock = self.clock;
        let result = clock.step(t, h, SampleClock::MAX_SAMPLES_PER_STEP, |time| {
            self.sample(time).map_err(|e| format!("sample at t = {time} s: {e}"))
        });
        self.clock = clock;
        result
    }
}

type V = Variable<KnuckleBoomController>;
type Real = fmu_model::Real<KnuckleBoomController>;
type Integer = fmu_model::Integer<KnuckleBoomController>;
type Boolean = fmu_model::Boolean<KnuckleBoomController>;
type Text = fmu_model::Text<KnuckleBoomController>;

/// The inputs' start values: the crane's default start (`knuckle_boom`'s q0.* and lp0) on a
/// still deck; the load's start values are zero (a system connects them: mode 2 needs them).
const INPUTS: Measured = Measured {
    joints: physics::hydraulic_crane::plant::DEFAULT_JOINTS,
    lp: 10.0,
    ship: ShipMotion::AT_REST,
    load: physics::math::Vec3::new(0.0, 0.0, 0.0),
    load_velocity: physics::math::Vec3::new(0.0, 0.0, 0.0),
    residual: physics::math::Vec3::new(0.0, 0.0, 0.0),
};

// Integer codes of the enumerations, converted here and nowhere else; each parameter's declared
// range is exactly its codes, so the export layer refuses any other code before a setter sees it.

fmu_model::codes! {
    /// `mode`: 0 off, 1 positioning, 2 world-frame compensation with anti-sway.
    ModeCodes: Mode { Mode::Off => 0, Mode::Positioning => 1, Mode::Compensated => 2 }
}

fmu_model::codes! {
    /// `heave`: 0 none, 1 by the winch, 2 by the arm.
    HeaveCodes: Heave { Heave::None => 0, Heave::Winch => 1, Heave::Arm => 2 }
}

fmu_model::codes! {
    /// `setpoint`: 0 fixed, 1 pick-and-place profile (the test-scale controller's codes).
    SetpointCodes: SetpointSource { SetpointSource::Fixed => 0, SetpointSource::PickAndPlace => 1 }
}

fmu_model::codes! {
    /// `lqr.schedule`: 0 the gain of the latched hoist length, 1 scheduled over the measured one.
    ScheduleCodes: GainSchedule { GainSchedule::Fixed => 0, GainSchedule::Length => 1 }
}

/// The crane's interface values (the crane's outputs of the same names; 0, the start, when not
/// connected: nothing to compare).
const CRANE_INPUTS: [V; 7] = {
    let mut rows = [crane_input(150, 0); 7];
    let mut i = 1;
    while i < 7 {
        rows[i] = crane_input(150 + i as u32, i);
        i += 1;
    }
    rows
};

const fn crane_input(vr: u32, i: usize) -> V {
    let (name, unit) = CRANE_INTERFACE[i];
    let getters: [fn(&KnuckleBoomController) -> f64; 7] = [
        |m| m.crane_interface[0],
        |m| m.crane_interface[1],
        |m| m.crane_interface[2],
        |m| m.crane_interface[3],
        |m| m.crane_interface[4],
        |m| m.crane_interface[5],
        |m| m.crane_interface[6],
    ];
    let setters: [fn(&mut KnuckleBoomController, f64); 7] = [
        |m, v| m.crane_interface[0] = v,
        |m, v| m.crane_interface[1] = v,
        |m, v| m.crane_interface[2] = v,
        |m, v| m.crane_interface[3] = v,
        |m, v| m.crane_interface[4] = v,
        |m, v| m.crane_interface[5] = v,
        |m, v| m.crane_interface[6] = v,
    ];
    // The fingerprint's 52 bits (crane_description::fingerprint); a drive's speed in m/s or rad/s.
    let max = if i == 0 { 4_503_599_627_370_496.0 } else { 1e3 };
    Real::held_input(vr, name)
        .unit(unit)
        .start(0.0)
        .range(0.0, max)
        .doc("The crane's output of this name (0: not connected); the controller refuses a crane whose value differs from its own")
        .get(getters[i])
        .set(setters[i])
}

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
const GROUPS: &[&[V]] = &[
    &[Text::parameter(9, "crane")
        .start(crane_description::catalogue::DEFAULT_CRANE)
        .doc(concat!(
            "Crane description, as the crane's `crane` parameter (a catalogue name or a JSON file's path): the ",
            "inverse kinematics, valve deadbands and drive speeds come from it; a connected crane that differs ",
            "is refused"
        ))
        .get(|m| &m.crane)
        .set(|m, v| m.crane = v.to_string())],
    &CRANE_INPUTS,
    &[
        fmu_model::coded!(Integer::tunable(0, "mode"), ModeCodes, start: CONFIG.mode,
            doc: concat!(
                "The arm: 0 off (every spool centred, the counterbalance valves hold), 1 positioning (the joints ",
                "hold their start angles), 2 world-frame compensation with anti-sway; tunable"
            ),
            value: |m| m.config.mode),
        fmu_model::coded!(Integer::tunable(1, "heave"), HeaveCodes, start: CONFIG.heave,
            doc: concat!(
                "Heave compensation: 0 none (the winch holds its length), 1 by the winch (active heave ",
                "compensation), 2 by the arm (the tip holds its world height; needs mode 2); tunable"
            ),
            value: |m| m.config.heave),
        fmu_model::sample_period!(2, m => m.clock, doc: "Sample period of the control software"),
        fmu_model::field!(Real::parameter(3, "active_from"), unit: "s", start: 0.0, range: (0.0, 1e9),
            doc: "The control acts from this time on; before it the spools are centred and nothing is latched",
            field: m => m.active_from),
        fmu_model::field!(Real::parameter(4, "spool_rate"), unit: "1/s", range: (0.01, 1000.0),
            doc: "Largest rate of change of a spool command (the valve amplifier's ramp)",
            field: (m.config, CONFIG).spool_rate),
        fmu_model::coded!(Integer::parameter(5, "setpoint"), SetpointCodes, start: CONFIG.setpoint,
            doc: concat!(
                "0 fixed (the references latched at the first active sample hold), 1 pick-and-place: the ",
                "test-scale profile Froude-scaled by 25 (lengths x25, times x5: the tip 5 m towards -x, the rope ",
                "17.5 <-> 25 m, 600 s) as displacements of the latched tip and hoist length"
            ),
            value: |m| m.config.setpoint),
        fmu_model::field!(Real::parameter(10, "gain.slew"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_q of the slew joint loop (mode 1)",
            field: (m.config, CONFIG).joint_gain[0]),
        fmu_model::field!(Real::parameter(11, "gain.boom"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_q of the boom joint loop (mode 1)",
            field: (m.config, CONFIG).joint_gain[1]),
        fmu_model::field!(Real::parameter(12, "gain.jib"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_q of the jib joint loop (mode 1)",
            field: (m.config, CONFIG).joint_gain[2]),
        fmu_model::field!(Real::parameter(13, "gain.height"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_h of the tip's height loop in mode 2 (in the base frame, or the world with heave 2)",
            field: (m.config, CONFIG).height_gain),
        fmu_model::field!(Real::parameter(14, "gain.heave"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_z of the load-height feedback of the heave compensation by the winch",
            field: (m.config, CONFIG).heave_gain),
        fmu_model::field!(Real::parameter(15, "gain.length"), unit: "1/s", range: (0.0, 100.0),
            doc: "k_l of the winch's length loop (heave 0 and 2)",
            field: (m.config, CONFIG).length_gain),
        fmu_model::field!(Real::parameter(16, "lqr.q_position"), unit: "1/m2", range: (1e-9, 1e9),
            doc: "Anti-sway LQR weight on the tip's position error",
            field: (m.config, CONFIG).weights.position),
        fmu_model::field!(Real::parameter(17, "lqr.q_offset"), unit: "1/m2", range: (1e-9, 1e9),
            doc: "Anti-sway LQR weight on the load's horizontal offset from the tip",
            field: (m.config, CONFIG).weights.offset),
        fmu_model::field!(Real::parameter(18, "lqr.q_velocity"), unit: "s2/m2", range: (1e-9, 1e9),
            doc: "Anti-sway LQR weight on the load's horizontal velocity",
            field: (m.config, CONFIG).weights.velocity),
        fmu_model::field!(Real::parameter(19, "lqr.r"), unit: "s2/m2", range: (1e-9, 1e9),
            doc: "Anti-sway LQR weight on the tip's velocity command",
            field: (m.config, CONFIG).weights.effort),
        fmu_model::coded!(Integer::parameter(6, "lqr.schedule"), ScheduleCodes, start: CONFIG.schedule,
            doc: concat!(
                "Anti-sway gain over the hoist length: 0 the LQR designed once at the latched length, 1 designed ",
                "again at the measured length whenever it moved by more than 1 % since the last design ",
                "(docs/tuning.md)"
            ),
            value: |m| m.config.schedule),
    ],
    // A sling below the hook (docs/rigging.md), as the test-scale controller's.
    &sling_parameters!(20, m => m.config.sling, start: CONFIG.sling, notch_on: "the load's offset and velocity before the anti-sway law (mode 2)"),
    &xyz!(Real::parameter(24, "base."),
        unit: "m",
        range: (-200.0, 200.0),
        doc: ("The crane's pedestal foot in the ship frame B (as the crane's base.*), " + axis),
        field: (m.config, CONFIG).crane.arm.base),
    // Inputs: the crane's encoders and the drum.
    &[
        fmu_model::field!(Real::held_input(100, "joint.slew"), unit: "rad",
            doc: "Slew angle (the crane's joint.slew or sensor.joint.slew)",
            field: (m.inputs, INPUTS).joints[0]),
        fmu_model::field!(Real::held_input(101, "joint.boom"), unit: "rad",
            doc: "Boom elevation",
            field: (m.inputs, INPUTS).joints[1]),
        fmu_model::field!(Real::held_input(102, "joint.jib"), unit: "rad",
            doc: "Jib angle relative to the boom",
            field: (m.inputs, INPUTS).joints[2]),
        fmu_model::field!(Real::held_input(103, "lp"), unit: "m",
            doc: "Hoist length (the drum's payout)",
            field: (m.inputs, INPUTS).lp),
    ],
    // Inputs: the motion reference unit (the platform's outputs).
    &ship_inputs!(m => m.inputs.ship),
    // Inputs: the load (the pendulum's outputs).
    &xyz!(Real::held_input(130, "load."),
        unit: "m",
        start: [0.0; 3],
        doc: ("Load position, W " + axis),
        get: |m| m.inputs.load,
        set: |m, v| m.inputs.load),
    &xyz!(Real::held_input(133, "load.v"),
        unit: "m/s",
        start: [0.0; 3],
        doc: ("Load velocity, W " + axis),
        get: |m| m.inputs.load_velocity,
        set: |m, v| m.inputs.load_velocity),
    // Inputs: a correction of the commanded tip velocity (an agent's residual on top of the law).
    &xyz!(Real::held_input(140, "residual.tip.v"),
        unit: "m/s",
        start: [0.0; 3],
        range: (-10.0, 10.0),
        doc: ("Added to the anti-sway law's tip velocity in mode 2 (0: the law's command), W " + axis),
        get: |m| m.inputs.residual,
        set: |m, v| m.inputs.residual),
    // Outputs: the commands.
    &[
        Real::output(200, "spool.slew")
            .unit("1")
            .doc("Slew valve spool command (the crane's spool.slew)")
            .get(|m| m.out.spools[SLEW]),
        Real::output(201, "spool.boom").unit("1").doc("Boom valve spool command").get(|m| m.out.spools[BOOM]),
        Real::output(202, "spool.jib").unit("1").doc("Jib valve spool command").get(|m| m.out.spools[JIB]),
        Real::output(203, "spool.winch").unit("1").doc("Winch valve spool command").get(|m| m.out.spools[WINCH]),
        Real::output(204, "opening.slew")
            .unit("1")
            .doc("Effective valve opening the slew spool gives (-1..1; 1 is the rated flow)")
            .get(|m| m.out.openings[SLEW]),
        Real::output(205, "opening.boom").unit("1").doc("Effective boom valve opening").get(|m| m.out.openings[BOOM]),
        Real::output(206, "opening.jib").unit("1").doc("Effective jib valve opening").get(|m| m.out.openings[JIB]),
        Real::output(207, "opening.winch")
            .unit("1")
            .doc("Effective winch valve opening")
            .get(|m| m.out.openings[WINCH]),
        Boolean::output(208, "saturated")
            .doc("A drive was asked for more than its rated speed in the last sample")
            .get(|m| m.out.saturated),
    ],
    &xyz!(Real::output(210, "tip."),
        unit: "m",
        doc: ("Tip position from the measurements (deck motion and joints), W " + axis),
        get: |m| m.out.tip),
    &xyz!(Real::output(213, "tip.v"),
        unit: "m/s",
        doc: ("Tip velocity from the measurements and the commanded arm rates, W " + axis),
        get: |m| m.out.tip_velocity),
    &xyz!(Real::output(216, "command.v"),
        unit: "m/s",
        doc: ("Commanded tip velocity (mode 2), W " + axis),
        get: |m| m.out.tip_command),
    &[
        Real::output(219, "command.lp_dot")
            .unit("m/s")
            .doc("Commanded rope rate, positive paying out")
            .get(|m| m.out.rope_rate),
        Real::output(220, "load_height.ref")
            .unit("m")
            .doc("Load height reference, W z (down), latched at the first sample")
            .get(|m| m.out.load_height_ref),
        Real::output(221, "load_height")
            .unit("m")
            .doc("Load height estimate tip z + lp, W z (down)")
            .get(|m| m.out.load_height),
    ],
    &xyz!(Real::output(222, "setpoint."),
        unit: "m",
        doc: ("The load's set-point: under the tip's reference at the load's height reference (plus sling.length), W " + axis),
        get: |m| m.out.load_setpoint),
    &xyz!(Real::output(225, "tip.ref."),
        unit: "m",
        doc: ("The tip's reference: latched at the first active sample, moved by the set-point profile, W " + axis),
        get: |m| m.out.tip_ref),
    &[Real::output(228, "lp.ref")
        .unit("m")
        .doc("The hoist length's reference: latched at the first active sample, moved by the set-point profile")
        .get(|m| m.out.lp_ref)],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(KnuckleBoomController);

#[cfg(test)]
mod tests;

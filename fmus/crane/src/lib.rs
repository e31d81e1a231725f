//! FMU `crane`: the test-scale knuckle-boom crane (SPEC §4.2; thesis §3.4.2–3.5.4 and §4.2).
//!
//! States: the three linear actuators and the winch, each a double integrator with a pole
//! (G(s) = K/(s(s + a))) behind input saturation and a deadband, integrated exactly over each
//! communication step with the commands held (zero-order hold); the linear actuators stop at the
//! ends of their 0–50 mm stroke. The kinematic chain (actuator mechanisms, serial FK, pendulum
//! length) is evaluated with exact first and second time derivatives.
//!
//! The ship motion inputs act directly on the world-frame tip outputs (direct feedthrough): the
//! tip in W is always computed from the ship motion currently set and the crane state at the
//! current communication point. Accelerations are those under the commands applied over the step
//! just taken. Sensor readings at communication point k (= completed steps) use noise sample k.
//! Ports are SI except the hardware signals (V, duty, deg); W is North-East-Down, the ship frame
//! B and the crane base frame J12 are aligned (x bow, y starboard, z down).

use fmu_model::{noise_parameters, ship_inputs, xyz, Environment, Model, ModelInfo, Variable};
use physics::crane::motion::{tip_in_world, ChainMotion};
use physics::crane::plant::{Commands, CraneConfig, CranePose, CraneState, StepPropagators, DEFAULT_POSE};
use physics::crane::sensors::{Encoder, NoiseDraw, Potentiometer, POT_CHANNELS};
use physics::crane::MM_PER_M;
use physics::motion::{PointMotion, ShipMotion};
use physics::noise::NoiseStream;
use serde::{Deserialize, Serialize};
use std::cell::OnceCell;

/// Instance data: configuration, inputs, continuous state and the outputs last computed.
#[derive(Clone, Serialize, Deserialize)]
pub struct Crane {
    config: CraneConfig,
    /// Initial actuator extensions (m) and pendulum length (m).
    initial: CranePose,
    potentiometer: Potentiometer,
    encoder: Encoder,
    noise: bool,
    seed: u64,
    /// Inputs as last set (held over a step).
    commands: Commands,
    ship: ShipMotion,
    state: CraneState,
    /// Sample index k of the current outputs: steps completed since initialization.
    k: u64,
    /// The chain at the current communication point (J12).
    chain: ChainMotion,
    pots: [f64; 3],
    encoder_reading: f64,
    /// Noise memos of the three potentiometers and the encoder (a cache: rebuilt after
    /// deserialization, never changes a value).
    #[serde(skip)]
    streams: [NoiseStream; 4],
    /// The tip in W for the chain and the ship motion currently set, once computed, so that each
    /// tip getter does not transform it again; emptied whenever either changes.
    #[serde(skip)]
    tip: OnceCell<PointMotion>,
    /// The plant's propagators for the two step sizes last used (a cache: every step of one
    /// size shares them; rebuilt after deserialization and initialization).
    #[serde(skip)]
    propagators: [Option<StepPropagators>; 2],
}

impl Crane {
    fn update_outputs(&mut self) -> Result<(), String> {
        self.tip = OnceCell::new();
        self.chain = self.config.motion(&self.state, &self.commands).map_err(|e| e.to_string())?;
        let draw = if self.noise { NoiseDraw::On { seed: self.seed, k: self.k } } else { NoiseDraw::Off };
        let d = self.state.extensions();
        let (pot_streams, encoder_stream) = self.streams.split_at_mut(3);
        self.pots = [0, 1, 2].map(|i| self.potentiometer.read(d[i], POT_CHANNELS[i], draw, &mut pot_streams[i]));
        self.encoder_reading = self.encoder.read(self.state.winch.pos, draw, &mut encoder_stream[0]);
        Ok(())
    }

    /// The plant's propagators over a step of `h` seconds. Two sizes are kept because an importer's
    /// steps t_{k+1} − t_k of one nominal size differ in their last bits, mostly alternating
    /// between two values for a while.
    fn propagators(&mut self, h: f64) -> StepPropagators {
        if let Some(step) = self.propagators.iter().flatten().find(|step| step.h == h) {
            return *step;
        }
        let step = self.config.propagators(h);
        self.propagators = [Some(step), self.propagators[0]];
        step
    }

    /// Applies `set` to the ship motion input; the tip in W depends on it directly (direct
    /// feedthrough).
    fn set_ship(&mut self, set: impl FnOnce(&mut ShipMotion)) {
        set(&mut self.ship);
        self.tip = OnceCell::new();
    }

    /// The tip in W for the ship motion currently set.
    fn tip(&self) -> &PointMotion {
        // A reference, not a copy: each getter reads one component.
        self.tip.get_or_init(|| tip_in_world(&self.ship, &self.chain))
    }
}

impl Model for Crane {
    const INFO: ModelInfo = ModelInfo::new(
        "crane",
        concat!(
            "Knuckle-boom crane: actuator transfer functions with deadbands and saturation, winch, actuator ",
            "mechanisms and crane kinematics, tip motion in the world frame, potentiometer and encoder sensors ",
            "(thesis sections 3.4-3.5, 4.2)",
        ),
    );

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(_env: &Environment) -> Self {
        Crane {
            config: CraneConfig::DEFAULT,
            initial: DEFAULT_POSE,
            potentiometer: Potentiometer::DEFAULT,
            encoder: Encoder::DEFAULT,
            noise: NOISE,
            seed: SEED as u64,
            commands: Commands::NEUTRAL,
            ship: ShipMotion::default(),
            state: CraneState::default(),
            k: 0,
            chain: ChainMotion::default(),
            pots: [0.0; 3],
            encoder_reading: 0.0,
            streams: Default::default(),
            tip: OnceCell::new(),
            propagators: [None; 2],
        }
    }

    fn initialize(&mut self, _start_time: f64) -> Result<(), String> {
        self.config.validate()?;
        // The configuration may have changed since the last step.
        self.propagators = [None; 2];
        self.state = self.config.initial_state(self.initial.extensions, self.initial.lp)?;
        self.k = 0;
        self.update_outputs()
    }

    fn do_step(&mut self, _t: f64, h: f64) -> Result<(), String> {
        let step = self.propagators(h);
        self.state = self.config.advance_with(&self.state, &self.commands, &step);
        self.k += 1;
        self.update_outputs()
    }
}

type V = Variable<Crane>;
type Real = fmu_model::Real<Crane>;
type Integer = fmu_model::Integer<Crane>;
type Boolean = fmu_model::Boolean<Crane>;

/// Default of `noise`: the sensors are noisy.
const NOISE: bool = true;
/// Default noise seed.
const SEED: i32 = 3;
/// The plant's defaults, for the start values.
const CONFIG: CraneConfig = CraneConfig::DEFAULT;
const NEUTRAL: Commands = Commands::NEUTRAL;
/// The sensors' defaults (SPEC §8.1), for the start values.
const POT: Potentiometer = Potentiometer::DEFAULT;
const ENCODER: Encoder = Encoder::DEFAULT;

/// A parameter row of a field of actuator `I`'s configuration (`deadband.lower`, `plant.gain`, …):
/// its start is the default configuration's, and it reads and writes the same field, so that the
/// three actuators' rows differ only in what the caller names.
macro_rules! actuator_parameter {
    ($i:ident, $vr:expr, $name:expr, $unit:literal, ($lo:expr, $hi:expr), $doc:expr, $($field:ident).+) => {
        fmu_model::field!(Real::parameter($vr, $name), unit: $unit, range: ($lo, $hi), doc: $doc,
            field: (m.config, CONFIG).actuators[$i].$($field).+)
    };
}

/// The two parameter rows of actuator `I`'s deadband, lower and upper (V, relative to the 1.65 V
/// neutral), value references `vr` and `vr + 1`: one place for the three actuators, so that their
/// ranges cannot drift apart. The names and descriptions are the caller's.
const fn deadband<const I: usize>(vr: u32, names: [&'static str; 2], docs: [&'static str; 2]) -> [V; 2] {
    [
        actuator_parameter!(I, vr, names[0], "V", (-1.65, 0.0), docs[0], deadband.lower),
        actuator_parameter!(I, vr + 1, names[1], "V", (0.0, 1.65), docs[1], deadband.upper),
    ]
}

/// The two parameter rows of actuator `I`'s transfer function G(s) = K/(s(s + a)), its gain K and
/// pole a, value references `vr` and `vr + 1`, like [`deadband`] one place for the three actuators.
const fn plant<const I: usize>(vr: u32, names: [&'static str; 2], docs: [&'static str; 2]) -> [V; 2] {
    [
        actuator_parameter!(I, vr, names[0], "mm/(V.s2)", (0.0, 1.0e6), docs[0], plant.gain),
        actuator_parameter!(I, vr + 1, names[1], "1/s", (0.0, 1.0e4), docs[1], plant.pole),
    ]
}

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
const GROUPS: &[&[V]] = &[
    &[
        // Parameters.
        fmu_model::field!(Real::parameter(0, "d0.base"), unit: "m", range: (0.0, 0.05),
            doc: concat!(
                "Initial base actuator extension (0-0.05 m); the defaults put the tip within 0.05 mm of (3, -277, ",
                "-153) mm in J12, the controller's fixed set-point (3, -502, -153) mm in W"
            ),
            field: (m.initial, DEFAULT_POSE).extensions[0]),
        fmu_model::field!(Real::parameter(1, "d0.boom"), unit: "m", range: (0.0, 0.05),
            doc: "Initial boom actuator extension",
            field: (m.initial, DEFAULT_POSE).extensions[1]),
        fmu_model::field!(Real::parameter(2, "d0.jib"), unit: "m", range: (0.0, 0.05),
            doc: "Initial jib actuator extension",
            field: (m.initial, DEFAULT_POSE).extensions[2]),
        fmu_model::field!(Real::parameter(3, "lp0"), unit: "m", range: (0.01, 10.0),
            doc: "Initial pendulum length; sets the winch start angle (eqs. 3.1-3.4)",
            field: (m.initial, DEFAULT_POSE).lp),
        Real::parameter(4, "winch.diameter")
            .unit("m")
            .start(CONFIG.cable.drum_diameter / MM_PER_M)
            .range(0.001, 1.0)
            .doc("Mean diameter of the cable wrapped on the winch drum (eq. 3.3)")
            .get(|m| m.config.cable.drum_diameter / MM_PER_M)
            .set(|m, v| m.config.cable.drum_diameter = v * MM_PER_M),
    ],
    &deadband::<0>(
        5,
        ["deadband.base.lower", "deadband.base.upper"],
        ["Base actuator lower deadband relative to 1.65 V (Table 3.2)", "Base actuator upper deadband (Table 3.2)"],
    ),
    &deadband::<1>(
        7,
        ["deadband.boom.lower", "deadband.boom.upper"],
        ["Boom actuator lower deadband (Table 3.2)", "Boom actuator upper deadband (Table 3.2)"],
    ),
    &deadband::<2>(
        9,
        ["deadband.jib.lower", "deadband.jib.upper"],
        ["Jib actuator lower deadband (Table 3.2)", "Jib actuator upper deadband (Table 3.2)"],
    ),
    &[
        fmu_model::field!(Real::parameter(11, "deadband.winch.lower"), unit: "1", range: (-0.5, 0.0),
            doc: "Winch lower deadband relative to duty 0.5 (Table 3.2)",
            field: (m.config, CONFIG).winch.deadband.lower),
        fmu_model::field!(Real::parameter(12, "deadband.winch.upper"), unit: "1", range: (0.0, 0.5),
            doc: "Winch upper deadband (Table 3.2)",
            field: (m.config, CONFIG).winch.deadband.upper),
    ],
    &noise_parameters!(13, m => m.noise, m.seed, start: (NOISE, SEED),
        noise: "Add Gaussian noise to the potentiometer and encoder readings (quantisation applies regardless)",
        seed: "Noise seed; give every noisy instance of the system its own"),
    // Parameters: the identified actuator transfer functions G(s) = K/(s(s + a)) (eqs. 3.5-3.8) in
    // the thesis' units, in which they were identified (a conversion would change their bits).
    &plant::<0>(
        20,
        ["gain.base", "pole.base"],
        [
            "Base actuator gain K of G(s) = K/(s(s + a)) (eq. 3.5)",
            "Base actuator pole a of G(s) = K/(s(s + a)) (eq. 3.5); > 0",
        ],
    ),
    &plant::<1>(
        22,
        ["gain.boom", "pole.boom"],
        ["Boom actuator gain K (eq. 3.6)", "Boom actuator pole a (eq. 3.6); > 0"],
    ),
    &plant::<2>(24, ["gain.jib", "pole.jib"], ["Jib actuator gain K (eq. 3.7)", "Jib actuator pole a (eq. 3.7); > 0"]),
    &[
        fmu_model::field!(Real::parameter(26, "gain.winch"), unit: "deg/s2", range: (0.0, 1.0e7),
            doc: "Winch gain K per unit duty (eq. 3.8)",
            field: (m.config, CONFIG).winch.plant.gain),
        fmu_model::field!(Real::parameter(27, "pole.winch"), unit: "1/s", range: (0.0, 1.0e4),
            doc: "Winch pole a (eq. 3.8); > 0",
            field: (m.config, CONFIG).winch.plant.pole),
        // Parameters: sensor noise (SPEC §8.1).
        fmu_model::field!(Real::parameter(28, "pot.sigma"), unit: "V", range: (0.0, 1.0),
            doc: "Standard deviation of the potentiometers' noise (before the 12-bit converter)",
            field: (m.potentiometer, POT).sigma),
        fmu_model::field!(Real::parameter(29, "encoder.sigma"), unit: "deg", range: (0.0, 360.0),
            doc: "Standard deviation of the winch encoder's noise (before the 12-bit per turn quantisation)",
            field: (m.encoder, ENCODER).sigma),
        // Inputs: hardware commands.
        fmu_model::field!(Real::held_input(100, "u.base"), unit: "V",
            doc: "Base actuator command, 0-3.3 V (saturated), neutral 1.65 V",
            field: (m.commands, NEUTRAL).volts[0]),
        fmu_model::field!(Real::held_input(101, "u.boom"), unit: "V",
            doc: "Boom actuator command, 0-3.3 V (saturated), neutral 1.65 V",
            field: (m.commands, NEUTRAL).volts[1]),
        fmu_model::field!(Real::held_input(102, "u.jib"), unit: "V",
            doc: "Jib actuator command, 0-3.3 V (saturated), neutral 1.65 V",
            field: (m.commands, NEUTRAL).volts[2]),
        fmu_model::field!(Real::held_input(103, "u.winch"), unit: "1",
            doc: "Winch PWM duty cycle, 0-1 (saturated), neutral 0.5; above 0.5 pays cable out",
            field: (m.commands, NEUTRAL).duty),
    ],
    // Inputs: ship (deck) motion, the platform's outputs.
    &ship_inputs!(accelerations, m => m.ship),
    // Outputs: the tip in W.
    &xyz!(Real::output(200, "tip."),
        unit: "m",
        doc: [
            "Crane tip position, W x: p_ship + R (r_base + p_tip/J12)",
            "Crane tip position, W y",
            "Crane tip position, W z",
        ],
        get: |m| m.tip().pos),
    &xyz!(Real::output(203, "tip.v"),
        unit: "m/s",
        doc: ["Crane tip velocity, W x (rigid-body kinematics)", "Crane tip velocity, W y", "Crane tip velocity, W z"],
        get: |m| m.tip().vel),
    &xyz!(Real::output(206, "tip.a"),
        unit: "m/s2",
        doc: [
            "Crane tip acceleration, W x (with transport, centripetal and Coriolis terms)",
            "Crane tip acceleration, W y",
            "Crane tip acceleration, W z",
        ],
        get: |m| m.tip().acc),
    // Outputs: the tip in the crane base frame, the pendulum length.
    &xyz!(Real::output(210, "tip_base."),
        unit: "m",
        doc: [
            "Crane tip position in the base frame J12, x (eq. 4.73)",
            "Crane tip position in J12, y (eq. 4.74)",
            "Crane tip position in J12, z (eq. 4.75)",
        ],
        get: |m| m.chain.tip.pos),
    &[
        Real::output(213, "lp")
            .unit("m")
            .doc("Pendulum (cable) length, tip to load (eqs. 3.1-3.4)")
            .get(|m| m.chain.lp.pos),
        Real::output(214, "lp_dot").unit("m/s").doc("Pendulum length rate").get(|m| m.chain.lp.vel),
        Real::output(215, "lp_ddot").unit("m/s2").doc("Pendulum length acceleration").get(|m| m.chain.lp.acc),
        // Outputs: actuator and joint truth.
        Real::output(220, "d.base")
            .unit("m")
            .doc("Base actuator extension (0-0.05 m)")
            .get(|m| m.state.actuators[0].pos / MM_PER_M),
        Real::output(221, "d.boom")
            .unit("m")
            .doc("Boom actuator extension")
            .get(|m| m.state.actuators[1].pos / MM_PER_M),
        Real::output(222, "d.jib").unit("m").doc("Jib actuator extension").get(|m| m.state.actuators[2].pos / MM_PER_M),
        Real::output(223, "joint.theta2z")
            .unit("rad")
            .doc("Base (slewing) joint angle, eqs. 4.33-4.39")
            .get(|m| m.chain.joints[0].pos),
        Real::output(224, "joint.theta3x")
            .unit("rad")
            .doc("Boom joint angle, eqs. 4.46-4.52")
            .get(|m| m.chain.joints[1].pos),
        Real::output(225, "joint.theta4x")
            .unit("rad")
            .doc("Jib joint angle, eqs. 4.59-4.65")
            .get(|m| m.chain.joints[2].pos),
        Real::output(226, "winch.angle")
            .unit("deg")
            .doc("Winch rotation from its home position (multi-turn)")
            .get(|m| m.state.winch.pos),
        // Outputs: sensors.
        Real::output(230, "pot.base")
            .unit("V")
            .doc("Base potentiometer: 0-5 V over 0-50 mm, 12-bit, noise 1.2 mV")
            .get(|m| m.pots[0]),
        Real::output(231, "pot.boom").unit("V").doc("Boom potentiometer").get(|m| m.pots[1]),
        Real::output(232, "pot.jib").unit("V").doc("Jib potentiometer").get(|m| m.pots[2]),
        Real::output(233, "encoder")
            .unit("deg")
            .doc("Winch encoder, multi-turn: 12-bit per turn (360/4096 deg), noise 0.06 deg")
            .get(|m| m.encoder_reading),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(Crane);

#[cfg(test)]
mod tests;

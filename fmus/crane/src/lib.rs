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

use fmi2::{Model, ModelInfo, Variable};
use physics::crane::motion::{tip_in_world, ChainMotion};
use physics::crane::plant::{Commands, CraneConfig, CranePose, CraneState, StepPropagators, DEFAULT_POSE};
use physics::crane::sensors::{Encoder, NoiseDraw, Potentiometer, POT_CHANNELS};
use physics::crane::MM_PER_M;
use physics::motion::{PointMotion, ShipMotion};
use physics::noise::NoiseStream;
use serde::{Deserialize, Serialize};
use std::cell::Cell;

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
    tip: Cell<Option<PointMotion>>,
    /// The plant's propagators for the two step sizes last used (a cache: every step of one
    /// size shares them; rebuilt after deserialization and initialization).
    #[serde(skip)]
    propagators: [Option<StepPropagators>; 2],
}

impl Crane {
    fn update_outputs(&mut self) -> Result<(), String> {
        self.tip.set(None);
        self.chain = self.config.motion(&self.state, &self.commands).map_err(|e| e.to_string())?;
        let draw = if self.noise { NoiseDraw::On { seed: self.seed, k: self.k } } else { NoiseDraw::Off };
        let d = self.state.extensions();
        let (pot_streams, encoder_stream) = self.streams.split_at_mut(3);
        self.pots = [0, 1, 2].map(|i| self.potentiometer.read(d[i], POT_CHANNELS[i], draw, &mut pot_streams[i]));
        self.encoder_reading = self.encoder.read(self.state.winch.pos, draw, &mut encoder_stream[0]);
        Ok(())
    }

    /// The plant's propagators over a step of `h` seconds. Two sizes are kept because a master's
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
        self.tip.set(None);
    }

    /// The tip in W for the ship motion currently set.
    fn tip(&self) -> PointMotion {
        if let Some(tip) = self.tip.get() {
            return tip;
        }
        let tip = tip_in_world(&self.ship, &self.chain);
        self.tip.set(Some(tip));
        tip
    }
}

impl Model for Crane {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "crane",
        description: "Knuckle-boom crane: actuator transfer functions with deadbands and saturation, winch, actuator mechanisms and crane kinematics, tip motion in the world frame, potentiometer and encoder sensors (thesis sections 3.4-3.5, 4.2)",
        default_stop_time: 10.0,
        default_step_size: 0.01,
        can_interpolate_inputs: false,
        max_step_size: f64::MAX,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(_env: &fmi2::Environment) -> Self {
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
            tip: Cell::new(None),
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

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
static VARIABLES: &[V] = &[
    // Parameters.
    V::parameter(0, "d0.base", "m", DEFAULT_POSE.extensions[0], "Initial base actuator extension (0-0.05 m); the defaults put the tip within 0.05 mm of (3, -277, -153) mm in J12, the controller's fixed set-point (3, -502, -153) mm in W", |m| m.initial.extensions[0], |m, v| m.initial.extensions[0] = v).range(0.0, 0.05),
    V::parameter(1, "d0.boom", "m", DEFAULT_POSE.extensions[1], "Initial boom actuator extension", |m| m.initial.extensions[1], |m, v| m.initial.extensions[1] = v).range(0.0, 0.05),
    V::parameter(2, "d0.jib", "m", DEFAULT_POSE.extensions[2], "Initial jib actuator extension", |m| m.initial.extensions[2], |m, v| m.initial.extensions[2] = v).range(0.0, 0.05),
    V::parameter(3, "lp0", "m", DEFAULT_POSE.lp, "Initial pendulum length; sets the winch start angle (eqs. 3.1-3.4)", |m| m.initial.lp, |m, v| m.initial.lp = v).range(0.01, 10.0),
    V::parameter(4, "winch.diameter", "m", CONFIG.cable.drum_diameter / MM_PER_M, "Mean diameter of the cable wrapped on the winch drum (eq. 3.3)", |m| m.config.cable.drum_diameter / MM_PER_M, |m, v| m.config.cable.drum_diameter = v * MM_PER_M).range(0.001, 1.0),
    V::parameter(5, "deadband.base.lower", "V", CONFIG.actuators[0].deadband.lower, "Base actuator lower deadband relative to 1.65 V (Table 3.2)", |m| m.config.actuators[0].deadband.lower, |m, v| m.config.actuators[0].deadband.lower = v).range(-1.65, 0.0),
    V::parameter(6, "deadband.base.upper", "V", CONFIG.actuators[0].deadband.upper, "Base actuator upper deadband (Table 3.2)", |m| m.config.actuators[0].deadband.upper, |m, v| m.config.actuators[0].deadband.upper = v).range(0.0, 1.65),
    V::parameter(7, "deadband.boom.lower", "V", CONFIG.actuators[1].deadband.lower, "Boom actuator lower deadband (Table 3.2)", |m| m.config.actuators[1].deadband.lower, |m, v| m.config.actuators[1].deadband.lower = v).range(-1.65, 0.0),
    V::parameter(8, "deadband.boom.upper", "V", CONFIG.actuators[1].deadband.upper, "Boom actuator upper deadband (Table 3.2)", |m| m.config.actuators[1].deadband.upper, |m, v| m.config.actuators[1].deadband.upper = v).range(0.0, 1.65),
    V::parameter(9, "deadband.jib.lower", "V", CONFIG.actuators[2].deadband.lower, "Jib actuator lower deadband (Table 3.2)", |m| m.config.actuators[2].deadband.lower, |m, v| m.config.actuators[2].deadband.lower = v).range(-1.65, 0.0),
    V::parameter(10, "deadband.jib.upper", "V", CONFIG.actuators[2].deadband.upper, "Jib actuator upper deadband (Table 3.2)", |m| m.config.actuators[2].deadband.upper, |m, v| m.config.actuators[2].deadband.upper = v).range(0.0, 1.65),
    V::parameter(11, "deadband.winch.lower", "1", CONFIG.winch.deadband.lower, "Winch lower deadband relative to duty 0.5 (Table 3.2)", |m| m.config.winch.deadband.lower, |m, v| m.config.winch.deadband.lower = v).range(-0.5, 0.0),
    V::parameter(12, "deadband.winch.upper", "1", CONFIG.winch.deadband.upper, "Winch upper deadband (Table 3.2)", |m| m.config.winch.deadband.upper, |m, v| m.config.winch.deadband.upper = v).range(0.0, 0.5),
    V::boolean_parameter(13, "noise", NOISE, "Add Gaussian noise to the potentiometer and encoder readings (quantisation applies regardless)", |m| m.noise, |m, v| m.noise = v),
    V::integer_parameter(14, "seed", SEED, 0, i32::MAX, "Noise seed; give every noisy instance of the system its own", |m| m.seed as i32, |m, v| m.seed = v as u64),
    // Parameters: the identified actuator transfer functions G(s) = K/(s(s + a)) (eqs. 3.5-3.8) in
    // the thesis' units, in which they were identified (a conversion would change their bits).
    V::parameter(20, "gain.base", "mm/(V.s2)", CONFIG.actuators[0].plant.gain, "Base actuator gain K of G(s) = K/(s(s + a)) (eq. 3.5)", |m| m.config.actuators[0].plant.gain, |m, v| m.config.actuators[0].plant.gain = v).range(0.0, 1.0e6),
    V::parameter(21, "pole.base", "1/s", CONFIG.actuators[0].plant.pole, "Base actuator pole a of G(s) = K/(s(s + a)) (eq. 3.5); > 0", |m| m.config.actuators[0].plant.pole, |m, v| m.config.actuators[0].plant.pole = v).range(0.0, 1.0e4),
    V::parameter(22, "gain.boom", "mm/(V.s2)", CONFIG.actuators[1].plant.gain, "Boom actuator gain K (eq. 3.6)", |m| m.config.actuators[1].plant.gain, |m, v| m.config.actuators[1].plant.gain = v).range(0.0, 1.0e6),
    V::parameter(23, "pole.boom", "1/s", CONFIG.actuators[1].plant.pole, "Boom actuator pole a (eq. 3.6); > 0", |m| m.config.actuators[1].plant.pole, |m, v| m.config.actuators[1].plant.pole = v).range(0.0, 1.0e4),
    V::parameter(24, "gain.jib", "mm/(V.s2)", CONFIG.actuators[2].plant.gain, "Jib actuator gain K (eq. 3.7)", |m| m.config.actuators[2].plant.gain, |m, v| m.config.actuators[2].plant.gain = v).range(0.0, 1.0e6),
    V::parameter(25, "pole.jib", "1/s", CONFIG.actuators[2].plant.pole, "Jib actuator pole a (eq. 3.7); > 0", |m| m.config.actuators[2].plant.pole, |m, v| m.config.actuators[2].plant.pole = v).range(0.0, 1.0e4),
    V::parameter(26, "gain.winch", "deg/s2", CONFIG.winch.plant.gain, "Winch gain K per unit duty (eq. 3.8)", |m| m.config.winch.plant.gain, |m, v| m.config.winch.plant.gain = v).range(0.0, 1.0e7),
    V::parameter(27, "pole.winch", "1/s", CONFIG.winch.plant.pole, "Winch pole a (eq. 3.8); > 0", |m| m.config.winch.plant.pole, |m, v| m.config.winch.plant.pole = v).range(0.0, 1.0e4),
    // Parameters: sensor noise (SPEC §8.1).
    V::parameter(28, "pot.sigma", "V", POT.sigma, "Standard deviation of the potentiometers' noise (before the 12-bit converter)", |m| m.potentiometer.sigma, |m, v| m.potentiometer.sigma = v).range(0.0, 1.0),
    V::parameter(29, "encoder.sigma", "deg", ENCODER.sigma, "Standard deviation of the winch encoder's noise (before the 12-bit per turn quantisation)", |m| m.encoder.sigma, |m, v| m.encoder.sigma = v).range(0.0, 360.0),
    // Inputs: hardware commands.
    V::held_input(100, "u.base", "V", NEUTRAL.volts[0], "Base actuator command, 0-3.3 V (saturated), neutral 1.65 V", |m| m.commands.volts[0], |m, v| m.commands.volts[0] = v),
    V::held_input(101, "u.boom", "V", NEUTRAL.volts[1], "Boom actuator command, 0-3.3 V (saturated), neutral 1.65 V", |m| m.commands.volts[1], |m, v| m.commands.volts[1] = v),
    V::held_input(102, "u.jib", "V", NEUTRAL.volts[2], "Jib actuator command, 0-3.3 V (saturated), neutral 1.65 V", |m| m.commands.volts[2], |m, v| m.commands.volts[2] = v),
    V::held_input(103, "u.winch", "1", NEUTRAL.duty, "Winch PWM duty cycle, 0-1 (saturated), neutral 0.5; above 0.5 pays cable out", |m| m.commands.duty, |m, v| m.commands.duty = v),
    // Inputs: ship (deck) motion, the platform's outputs.
    V::held_input(110, "ship.x", "m", 0.0, "Ship frame origin, W x (surge)", |m| m.ship.pos.x, |m, v| m.set_ship(|s| s.pos.x = v)),
    V::held_input(111, "ship.y", "m", 0.0, "Ship frame origin, W y (sway)", |m| m.ship.pos.y, |m, v| m.set_ship(|s| s.pos.y = v)),
    V::held_input(112, "ship.z", "m", 0.0, "Ship frame origin, W z (heave, down)", |m| m.ship.pos.z, |m, v| m.set_ship(|s| s.pos.z = v)),
    V::held_input(113, "ship.roll", "rad", 0.0, "Ship roll (Z-Y-X sequence, applied last)", |m| m.ship.roll, |m, v| m.set_ship(|s| s.roll = v)),
    V::held_input(114, "ship.pitch", "rad", 0.0, "Ship pitch (Z-Y-X sequence)", |m| m.ship.pitch, |m, v| m.set_ship(|s| s.pitch = v)),
    V::held_input(115, "ship.yaw", "rad", 0.0, "Ship yaw (Z-Y-X sequence, applied first)", |m| m.ship.yaw, |m, v| m.set_ship(|s| s.yaw = v)),
    V::held_input(116, "ship.vx", "m/s", 0.0, "Ship frame origin velocity, W x", |m| m.ship.vel.x, |m, v| m.set_ship(|s| s.vel.x = v)),
    V::held_input(117, "ship.vy", "m/s", 0.0, "Ship frame origin velocity, W y", |m| m.ship.vel.y, |m, v| m.set_ship(|s| s.vel.y = v)),
    V::held_input(118, "ship.vz", "m/s", 0.0, "Ship frame origin velocity, W z", |m| m.ship.vel.z, |m, v| m.set_ship(|s| s.vel.z = v)),
    V::held_input(119, "ship.ax", "m/s2", 0.0, "Ship frame origin acceleration, W x", |m| m.ship.acc.x, |m, v| m.set_ship(|s| s.acc.x = v)),
    V::held_input(120, "ship.ay", "m/s2", 0.0, "Ship frame origin acceleration, W y", |m| m.ship.acc.y, |m, v| m.set_ship(|s| s.acc.y = v)),
    V::held_input(121, "ship.az", "m/s2", 0.0, "Ship frame origin acceleration, W z", |m| m.ship.acc.z, |m, v| m.set_ship(|s| s.acc.z = v)),
    V::held_input(122, "ship.wx", "rad/s", 0.0, "Ship angular velocity, ship frame B x", |m| m.ship.omega.x, |m, v| m.set_ship(|s| s.omega.x = v)),
    V::held_input(123, "ship.wy", "rad/s", 0.0, "Ship angular velocity, B y", |m| m.ship.omega.y, |m, v| m.set_ship(|s| s.omega.y = v)),
    V::held_input(124, "ship.wz", "rad/s", 0.0, "Ship angular velocity, B z", |m| m.ship.omega.z, |m, v| m.set_ship(|s| s.omega.z = v)),
    V::held_input(125, "ship.alphax", "rad/s2", 0.0, "Ship angular acceleration, B x", |m| m.ship.alpha.x, |m, v| m.set_ship(|s| s.alpha.x = v)),
    V::held_input(126, "ship.alphay", "rad/s2", 0.0, "Ship angular acceleration, B y", |m| m.ship.alpha.y, |m, v| m.set_ship(|s| s.alpha.y = v)),
    V::held_input(127, "ship.alphaz", "rad/s2", 0.0, "Ship angular acceleration, B z", |m| m.ship.alpha.z, |m, v| m.set_ship(|s| s.alpha.z = v)),
    // Outputs: the tip in W.
    V::output(200, "tip.x", "m", "Crane tip position, W x: p_ship + R (r_base + p_tip/J12)", |m| m.tip().pos.x),
    V::output(201, "tip.y", "m", "Crane tip position, W y", |m| m.tip().pos.y),
    V::output(202, "tip.z", "m", "Crane tip position, W z", |m| m.tip().pos.z),
    V::output(203, "tip.vx", "m/s", "Crane tip velocity, W x (rigid-body kinematics)", |m| m.tip().vel.x),
    V::output(204, "tip.vy", "m/s", "Crane tip velocity, W y", |m| m.tip().vel.y),
    V::output(205, "tip.vz", "m/s", "Crane tip velocity, W z", |m| m.tip().vel.z),
    V::output(206, "tip.ax", "m/s2", "Crane tip acceleration, W x (with transport, centripetal and Coriolis terms)", |m| m.tip().acc.x),
    V::output(207, "tip.ay", "m/s2", "Crane tip acceleration, W y", |m| m.tip().acc.y),
    V::output(208, "tip.az", "m/s2", "Crane tip acceleration, W z", |m| m.tip().acc.z),
    // Outputs: the tip in the crane base frame, the pendulum length.
    V::output(210, "tip_base.x", "m", "Crane tip position in the base frame J12, x (eq. 4.73)", |m| m.chain.tip.pos.x),
    V::output(211, "tip_base.y", "m", "Crane tip position in J12, y (eq. 4.74)", |m| m.chain.tip.pos.y),
    V::output(212, "tip_base.z", "m", "Crane tip position in J12, z (eq. 4.75)", |m| m.chain.tip.pos.z),
    V::output(213, "lp", "m", "Pendulum (cable) length, tip to load (eqs. 3.1-3.4)", |m| m.chain.lp.pos),
    V::output(214, "lp_dot", "m/s", "Pendulum length rate", |m| m.chain.lp.vel),
    V::output(215, "lp_ddot", "m/s2", "Pendulum length acceleration", |m| m.chain.lp.acc),
    // Outputs: actuator and joint truth.
    V::output(220, "d.base", "m", "Base actuator extension (0-0.05 m)", |m| m.state.actuators[0].pos / MM_PER_M),
    V::output(221, "d.boom", "m", "Boom actuator extension", |m| m.state.actuators[1].pos / MM_PER_M),
    V::output(222, "d.jib", "m", "Jib actuator extension", |m| m.state.actuators[2].pos / MM_PER_M),
    V::output(223, "joint.theta2z", "rad", "Base (slewing) joint angle, eqs. 4.33-4.39", |m| m.chain.joints[0].pos),
    V::output(224, "joint.theta3x", "rad", "Boom joint angle, eqs. 4.46-4.52", |m| m.chain.joints[1].pos),
    V::output(225, "joint.theta4x", "rad", "Jib joint angle, eqs. 4.59-4.65", |m| m.chain.joints[2].pos),
    V::output(226, "winch.angle", "deg", "Winch rotation from its home position (multi-turn)", |m| m.state.winch.pos),
    // Outputs: sensors.
    V::output(230, "pot.base", "V", "Base potentiometer: 0-5 V over 0-50 mm, 12-bit, noise 1.2 mV", |m| m.pots[0]),
    V::output(231, "pot.boom", "V", "Boom potentiometer", |m| m.pots[1]),
    V::output(232, "pot.jib", "V", "Jib potentiometer", |m| m.pots[2]),
    V::output(233, "encoder", "deg", "Winch encoder, multi-turn: 12-bit per turn (360/4096 deg), noise 0.06 deg", |m| m.encoder_reading),
];

fmi2::export_fmu!(Crane);

#[cfg(test)]
mod tests;

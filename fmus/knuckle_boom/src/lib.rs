//! FMU `knuckle_boom`: the full-scale offshore knuckle-boom crane (docs/full-scale.md; the
//! thesis' future work 4, §8.3).
//!
//! A rigid three-joint arm (slew, boom, jib) with masses and inertias on the moving deck, driven
//! by hydraulics: boom and jib by double-acting cylinders through their mechanisms, the slew by
//! a motor and gear, the winch by a motor and drum whose payout is the hoist length. Each drive
//! has a proportional directional valve, chamber pressure dynamics, port relief valves and (the
//! cylinders and the winch) a counterbalance valve that holds the load with the valve centred
//! ([`physics::hydraulic_crane`], [`physics::hydraulics`], [`physics::knuckle_boom`]).
//!
//! Inputs: the four spool commands (−1…1), the deck motion (the platform's outputs) and the
//! force of the cable on the tip (the pendulum's `cable.*` outputs), all held over a step. The
//! state is integrated with RK4 at substeps ≤ 1 ms. Outputs at communication point k: the tip in
//! W with its velocity and its acceleration under the inputs currently set (direct feedthrough
//! from every input), the hoist length with its rates, joints, strokes, pressures, flows,
//! forces, hydraulic power, and the sensor readings (noise sample k).
//!
//! Frames: W North-East-Down; the ship frame B and the crane base frame K are aligned (x bow,
//! y starboard, z down); K's origin is the pedestal foot on deck, at `base.*` in B.

use crane_description::{CraneDescription, Rating, Rope};
use fmu_model::{noise_parameters, ship_inputs, xyz, Environment, Model, ModelInfo, Variable};
use physics::hydraulic_crane::plant::{CraneParams, Evaluation, Loads, PlantState, Spools, BOOM, JIB, SLEW, WINCH};
use physics::hydraulic_crane::sensors::{Readings, SensorSet, CHANNELS};
use physics::hydraulics::WinchCircuit;
use physics::knuckle_boom::Joints;
use physics::math::components;
use physics::motion::{PointMotion, ShipMotion};
use physics::noise::{NoiseDraw, NoiseStream};
use physics::offshore_control::drives::RatedSpeeds;
use serde::{Deserialize, Serialize};
use std::cell::OnceCell;
use std::path::PathBuf;

/// Instance data: configuration, inputs, continuous state and the outputs last computed.
#[derive(Clone, Serialize, Deserialize)]
pub struct KnuckleBoom {
    /// The crane description as set (`crane`: a catalogue name or a file's path), the one it was
    /// last loaded from, and what only the description holds.
    crane: String,
    loaded: Option<String>,
    rating: Rating,
    rope: Rope,
    /// `winch.circuit`: −1 as the description says, else the circuit's code.
    circuit: i32,
    described_circuit: WinchCircuit,
    /// The fingerprint of `params` (crane_description::fingerprint).
    fingerprint: f64,
    resource_dir: Option<PathBuf>,
    params: CraneParams,
    sensors: SensorSet,
    /// Initial joint angles (rad) and hoist length (m).
    initial: Joints,
    lp0: f64,
    noise: bool,
    seed: u64,
    /// Inputs as last set (held over a step).
    spools: Spools,
    loads: Loads,
    state: PlantState,
    /// Sample index k of the current outputs: steps completed since initialization.
    k: u64,
    /// Whether the tip was below the deck plane at the last communication point (a warning is
    /// logged on each crossing into it).
    below_deck: bool,
    /// Warnings of the last step for the host ([`Model::take_warnings`]).
    #[serde(skip)]
    warnings: Vec<String>,
    readings: Readings,
    /// Noise memos of the sensor channels (a cache: rebuilt after deserialization).
    #[serde(skip)]
    streams: [NoiseStream; CHANNELS],
    /// The plant's derivatives at the current state under the inputs currently set, once
    /// computed; emptied whenever the state or an input changes.
    #[serde(skip)]
    evaluation: OnceCell<Evaluation>,
    /// The tip in W under the same, once computed.
    #[serde(skip)]
    tip: OnceCell<PointMotion>,
}

impl KnuckleBoom {
    /// Applies `set` to the inputs; every output that depends on them is recomputed on demand.
    fn set_input(&mut self, set: impl FnOnce(&mut Self)) {
        set(self);
        self.evaluation = OnceCell::new();
        self.tip = OnceCell::new();
    }

    fn set_ship(&mut self, set: impl FnOnce(&mut ShipMotion)) {
        self.set_input(|m| set(&mut m.loads.ship));
    }

    /// The evaluation for the state and the inputs currently set, computed once; a reference,
    /// so that each getter reads one field instead of copying the whole evaluation.
    fn evaluation(&self) -> &Evaluation {
        self.evaluation.get_or_init(|| self.params.evaluate(&self.state, &self.spools, &self.loads))
    }

    /// The tip in W for the state and the inputs currently set.
    fn tip(&self) -> &PointMotion {
        self.tip.get_or_init(|| self.params.tip_in_world(&self.state, self.evaluation(), &self.loads.ship))
    }

    fn tip_base(&self) -> PointMotion {
        let zero = [0.0; 3];
        self.params.arm.tip_in_base(&self.state.q, &self.state.qd, &zero)
    }

    /// Loads the description `crane` names (once per name) and applies the mounting point and
    /// the circuit's override.
    fn configure(&mut self) -> Result<(), String> {
        if self.loaded.as_deref() != Some(self.crane.as_str()) {
            let d = crane_description::load(&self.crane, self.resource_dir.as_deref())?;
            self.described(&d);
            self.loaded = Some(self.crane.clone());
        }
        self.params.winch_circuit = match self.circuit {
            -1 => self.described_circuit,
            code => {
                CircuitCodes::decode(code).ok_or_else(|| format!("winch.circuit {code} is not a circuit's code"))?
            }
        };
        // The description's crane at this mounting point: the circuit override is the crane's
        // own run-time choice, which the controller's drive model does not depend on (both
        // circuits give the winch's rated flow, crane-description's checks).
        let described = CraneParams { winch_circuit: self.described_circuit, ..self.params };
        self.fingerprint = crane_description::fingerprint(&described);
        Ok(())
    }

    fn described(&mut self, d: &CraneDescription) {
        // The mounting point is the FMU's own parameter (base.*), kept across descriptions.
        self.params = d.params(self.params.arm.base);
        self.described_circuit = d.winch.circuit;
        self.sensors = d.sensors;
        self.rating = d.rating;
        self.rope = d.rope;
    }

    /// winch.line_pull (N).
    fn line_pull(&self) -> f64 {
        use crane_description::checks::{line_pull, working_winch_pressure};
        line_pull(&self.params, working_winch_pressure(&self.params))
    }

    fn rated(&self) -> RatedSpeeds {
        RatedSpeeds::of(&self.params)
    }

    /// The tip's height above the deck plane (m): the plane of the pedestal foot, K's z = 0
    /// (K's z points down).
    fn tip_clearance(&self) -> f64 {
        -self.tip_base().pos.z
    }

    /// Notes a crossing of the tip below the deck plane at time `t` (s): the arm would strike
    /// the deck or the vessel's structure, which the model does not stop.
    fn watch_deck(&mut self, t: f64) {
        let clearance = self.tip_clearance();
        if clearance < 0.0 && !self.below_deck {
            self.warnings.push(format!(
                "the crane tip went {:.3} m below the deck plane at t = {t} s (joints slew {:.4}, boom {:.4}, jib \
                 {:.4} rad): the arm would strike the deck",
                -clearance, self.state.q[0], self.state.q[1], self.state.q[2]
            ));
        }
        self.below_deck = clearance < 0.0;
    }

    fn lp(&self) -> f64 {
        self.lp0 + self.params.drum_radius * self.state.drum
    }

    fn update_outputs(&mut self) -> Result<(), String> {
        self.evaluation = OnceCell::new();
        self.tip = OnceCell::new();
        if !(self.lp() > 0.0) {
            return Err(format!(
                "the hoist rope is fully wound in (length {:.3} m): the hook reached the tip",
                self.lp()
            ));
        }
        let draw = if self.noise { NoiseDraw::On { seed: self.seed, k: self.k } } else { NoiseDraw::Off };
        let d = self.evaluation().drives;
        self.readings = self.sensors.read(&self.state, [d[BOOM].pos, d[JIB].pos], draw, &mut self.streams);
        Ok(())
    }
}

impl Model for KnuckleBoom {
    const INFO: ModelInfo = ModelInfo::new(
        "knuckle_boom",
        concat!(
            "Full-scale offshore knuckle-boom crane: rigid slew-boom-jib arm on the moving deck, hydraulic ",
            "cylinders, slew motor and winch with proportional valves, counterbalance and relief valves and ",
            "chamber pressure dynamics, cable force at the tip, joint encoders, stroke and pressure transducers",
        ),
    )
    .stop_time(20.0)
    // 1 ms RK4 substeps: a step of 10 s is 10,000 substeps, a fraction of a second.
    .max_step(10.0);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(env: &Environment) -> Self {
        let default = crane_description::load(crane_description::catalogue::DEFAULT_CRANE, None).ok();
        let mut m = KnuckleBoom {
            crane: String::new(),
            loaded: None,
            rating: Rating { safe_working_load: 0.0, outreach: 0.0 },
            rope: Rope { diameter: 0.0, axial_stiffness: 0.0, damping_time: 0.0, minimum_breaking_load: 0.0 },
            circuit: CIRCUIT_AS_DESCRIBED,
            described_circuit: PARAMS.winch_circuit,
            fingerprint: 0.0,
            resource_dir: env.resource_dir.clone(),
            params: PARAMS,
            sensors: SENSORS,
            initial: INITIAL_JOINTS,
            lp0: LP0,
            noise: NOISE,
            seed: SEED as u64,
            spools: Spools::default(),
            loads: Loads::default(),
            state: PlantState::default(),
            k: 0,
            below_deck: false,
            warnings: Vec::new(),
            readings: Readings::default(),
            streams: Default::default(),
            evaluation: OnceCell::new(),
            tip: OnceCell::new(),
        };
        // The shipped default is checked by the crate's tests; the start values name it.
        if let Some(d) = default {
            m.described(&d);
            m.loaded = Some(crane_description::catalogue::DEFAULT_CRANE.to_string());
        }
        m
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.configure()?;
        self.params.validate()?;
        self.state = self.params.initial_state(self.initial, &self.loads)?;
        self.k = 0;
        self.below_deck = false;
        self.update_outputs()?;
        self.watch_deck(start_time);
        Ok(())
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        let next = self.params.advance(&self.state, &self.spools, &self.loads, h);
        if !next.is_finite() {
            return Err(format!("the crane's state became non-finite in the step from t = {t} s"));
        }
        self.state = next;
        self.k += 1;
        self.update_outputs()?;
        self.watch_deck(t + h);
        Ok(())
    }

    fn take_warnings(&mut self) -> Vec<String> {
        std::mem::take(&mut self.warnings)
    }
}

type V = Variable<KnuckleBoom>;
type Real = fmu_model::Real<KnuckleBoom>;
type Integer = fmu_model::Integer<KnuckleBoom>;
type Boolean = fmu_model::Boolean<KnuckleBoom>;
type Text = fmu_model::Text<KnuckleBoom>;

/// Default of `noise`: the sensors are noisy.
const NOISE: bool = true;
/// Default noise seed.
const SEED: i32 = 5;
/// The plant's defaults (docs/full-scale.md), for the start values.
const PARAMS: CraneParams = CraneParams::DEFAULT;
const SENSORS: SensorSet = SensorSet::DEFAULT;
/// The default start: reaching to port with the jib folded down (docs/full-scale.md).
const INITIAL_JOINTS: Joints = physics::hydraulic_crane::plant::DEFAULT_JOINTS;
/// Default initial hoist length (m).
const LP0: f64 = 10.0;

/// Getter and setter of one drive's pressures in the state (for the table's rows).
fn pressure(m: &KnuckleBoom, drive: usize, chamber: usize) -> f64 {
    m.state.pressures[drive][chamber]
}

fn reading(m: &KnuckleBoom, drive: usize, chamber: usize) -> f64 {
    m.readings.pressures[drive][chamber]
}

fmu_model::codes! {
    /// `winch.circuit`'s circuits: 0 open circuit, 1 closed circuit (−1, the start, keeps the
    /// description's; the declared range −1…1 is exactly these codes).
    CircuitCodes: WinchCircuit { WinchCircuit::Open => 0, WinchCircuit::Closed => 1 }
}

/// `winch.circuit`'s start: the circuit the crane description gives.
const CIRCUIT_AS_DESCRIBED: i32 = -1;

/// Largest `cable.mass` (kg): a rigging's hook and load, each up to 1e6 kg.
const CABLE_MASS_MAX: f64 = 2e6;

/// The values in force, from the crane description (calculated parameters: the host reads them
/// after initialization; docs/crane-description.md names each field).
const CALCULATED: [V; 37] = [
    Real::calculated(10, "supply.pressure")
        .unit("Pa")
        .doc("Supply pressure of the pressure-compensated pump (description: supply.pressure)")
        .get(|m| m.params.supply.pressure),
    Real::calculated(11, "oil.bulk_modulus")
        .unit("Pa")
        .doc("Effective bulk modulus of the oil (oil.bulk_modulus)")
        .get(|m| m.params.oil.bulk_modulus),
    Real::calculated(12, "drum.radius")
        .unit("m")
        .doc("Pitch radius of the hoist rope on the winch drum (winch.drum_radius)")
        .get(|m| m.params.drum_radius),
    Real::calculated(13, "winch.inertia")
        .unit("kg.m2")
        .doc("Inertia of the drum with the gear-reflected motor (winch.inertia)")
        .get(|m| m.params.winch_inertia),
    Real::calculated(20, "sigma.joint")
        .unit("rad")
        .doc("Standard deviation of the joint encoders' noise (sensors.joint.sigma)")
        .get(|m| m.sensors.joint.sigma),
    Real::calculated(21, "sigma.stroke")
        .unit("m")
        .doc("Standard deviation of the stroke transducers' noise (sensors.stroke.sigma)")
        .get(|m| m.sensors.stroke.sigma),
    Real::calculated(22, "sigma.pressure")
        .unit("Pa")
        .doc("Standard deviation of the pressure transducers' noise (sensors.pressure.sigma)")
        .get(|m| m.sensors.pressure.sigma),
    Real::calculated(23, "sigma.drum")
        .unit("rad")
        .doc("Standard deviation of the drum encoder's noise (sensors.drum.sigma)")
        .get(|m| m.sensors.drum.sigma),
    Real::calculated(300, "crane.swl")
        .unit("kg")
        .doc("Safe working load (rating.safe_working_load)")
        .get(|m| m.rating.safe_working_load),
    Real::calculated(301, "crane.outreach")
        .unit("m")
        .doc("Outreach of the rating (rating.outreach)")
        .get(|m| m.rating.outreach),
    Real::calculated(302, "crane.pedestal")
        .unit("m")
        .doc("Boom pivot above the deck (arm.pedestal_height)")
        .get(|m| m.params.arm.pedestal_height),
    Real::calculated(303, "crane.boom_length")
        .unit("m")
        .doc("Boom pivot to knuckle (arm.boom_length)")
        .get(|m| m.params.arm.boom_length),
    Real::calculated(304, "crane.jib_length")
        .unit("m")
        .doc("Knuckle to tip (arm.jib_length)")
        .get(|m| m.params.arm.jib_length),
    Real::calculated(305, "crane.mass.column")
        .unit("kg")
        .doc("Slewing column mass (arm.links[0].mass)")
        .get(|m| m.params.arm.links[0].mass),
    Real::calculated(306, "crane.mass.boom")
        .unit("kg")
        .doc("Boom mass (arm.links[1].mass)")
        .get(|m| m.params.arm.links[1].mass),
    Real::calculated(307, "crane.mass.jib")
        .unit("kg")
        .doc("Jib mass (arm.links[2].mass)")
        .get(|m| m.params.arm.links[2].mass),
    Real::calculated(308, "crane.boom.bore")
        .unit("m")
        .doc("Boom cylinder bore (boom.cylinder.bore)")
        .get(|m| m.params.boom.cylinder.bore),
    Real::calculated(309, "crane.boom.rod")
        .unit("m")
        .doc("Boom cylinder rod (boom.cylinder.rod)")
        .get(|m| m.params.boom.cylinder.rod),
    Real::calculated(310, "crane.boom.count")
        .unit("1")
        .doc("Boom cylinders on the joint (boom.cylinder.count)")
        .get(|m| m.params.boom.cylinder.count),
    Real::calculated(311, "crane.boom.stroke")
        .unit("m")
        .doc("Boom cylinder stroke (boom.cylinder.stroke)")
        .get(|m| m.params.boom.cylinder.stroke),
    Real::calculated(312, "crane.jib.bore")
        .unit("m")
        .doc("Jib cylinder bore (jib.cylinder.bore)")
        .get(|m| m.params.jib.cylinder.bore),
    Real::calculated(313, "crane.jib.rod")
        .unit("m")
        .doc("Jib cylinder rod (jib.cylinder.rod)")
        .get(|m| m.params.jib.cylinder.rod),
    Real::calculated(314, "crane.jib.count")
        .unit("1")
        .doc("Jib cylinders on the joint (jib.cylinder.count)")
        .get(|m| m.params.jib.cylinder.count),
    Real::calculated(315, "crane.jib.stroke")
        .unit("m")
        .doc("Jib cylinder stroke (jib.cylinder.stroke)")
        .get(|m| m.params.jib.cylinder.stroke),
    Real::calculated(316, "crane.valve.boom")
        .unit("m3/s")
        .doc("Boom valve's meter-in flow at full spool (boom.valve.max_flow)")
        .get(|m| m.params.boom.valve.max_flow),
    Real::calculated(317, "crane.valve.jib")
        .unit("m3/s")
        .doc("Jib valve's meter-in flow at full spool (jib.valve.max_flow)")
        .get(|m| m.params.jib.valve.max_flow),
    Real::calculated(318, "crane.valve.slew")
        .unit("m3/s")
        .doc("Slew valve's meter-in flow at full spool (slew.valve.max_flow)")
        .get(|m| m.params.slew.valve.max_flow),
    Real::calculated(319, "crane.valve.winch")
        .unit("m3/s")
        .doc(
            "Winch valve's flow at full spool, the pump's full flow in the closed circuit (winch.drive.valve.max_flow)",
        )
        .get(|m| m.params.winch.valve.max_flow),
    Real::calculated(320, "slew.displacement")
        .unit("m3/rad")
        .doc("Slew motor displacement (slew.displacement)")
        .get(|m| m.params.slew.displacement),
    Real::calculated(321, "slew.gear").unit("1").doc("Slew gear ratio (slew.gear)").get(|m| m.params.slew.gear),
    Real::calculated(322, "winch.displacement")
        .unit("m3/rad")
        .doc("Winch motor displacement (winch.drive.displacement)")
        .get(|m| m.params.winch.displacement),
    Real::calculated(323, "winch.gear")
        .unit("1")
        .doc("Winch gear ratio (winch.drive.gear)")
        .get(|m| m.params.winch.gear),
    Real::calculated(324, "winch.line_pull")
        .unit("N")
        .doc("Line pull at the working pressure: the supply's (open circuit) or the cross-port relief's (closed)")
        .get(|m| m.line_pull()),
    Real::calculated(325, "crane.relief.boom")
        .unit("Pa")
        .doc("Boom port relief setting (boom.relief.pressure)")
        .get(|m| m.params.boom.relief.pressure),
    Real::calculated(326, "rope.diameter")
        .unit("m")
        .doc("Hoist rope diameter (rope.diameter)")
        .get(|m| m.rope.diameter),
    Real::calculated(327, "rope.ea")
        .unit("N")
        .doc("Hoist rope EA (rope.axial_stiffness)")
        .get(|m| m.rope.axial_stiffness),
    Real::calculated(328, "rope.mbl")
        .unit("N")
        .doc("Hoist rope minimum breaking load (rope.minimum_breaking_load)")
        .get(|m| m.rope.minimum_breaking_load),
];

/// What the controller compares with its own crane (outputs, so a system connects them).
const INTERFACE: [V; 7] = [
    Real::output(280, "crane.fingerprint").unit("1").doc("Fingerprint of every crane parameter in force and the mounting point: the controller refuses a crane whose fingerprint differs from its own").get(|m| m.fingerprint),
    Real::output(281, "rated.boom.extend").unit("m/s").doc("Boom cylinder speed at full spool, extending (valve flow over piston area)").get(|m| m.rated().cylinders[0].0),
    Real::output(282, "rated.boom.retract").unit("m/s").doc("Boom cylinder speed at full spool, retracting (valve flow over annulus area)").get(|m| m.rated().cylinders[0].1),
    Real::output(283, "rated.jib.extend").unit("m/s").doc("Jib cylinder speed at full spool, extending").get(|m| m.rated().cylinders[1].0),
    Real::output(284, "rated.jib.retract").unit("m/s").doc("Jib cylinder speed at full spool, retracting").get(|m| m.rated().cylinders[1].1),
    Real::output(285, "rated.slew").unit("rad/s").doc("Slew rate at full spool").get(|m| m.rated().slew),
    Real::output(286, "rated.rope").unit("m/s").doc("Rope speed at full spool (full pump displacement in the closed circuit)").get(|m| m.rated().rope),
];

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
const GROUPS: &[&[V]] = &[
    &[
        // Parameters: the start.
        fmu_model::field!(Real::parameter(0, "q0.slew"), unit: "rad", range: (-7.0, 7.0),
            doc: "Initial slew angle about the base z axis (down); -pi/2 reaches to port (-y)",
            field: (m.initial, INITIAL_JOINTS)[0]),
        fmu_model::field!(Real::parameter(1, "q0.boom"), unit: "rad", range: (-1.6, 1.6),
            doc: "Initial boom elevation above the horizontal (the boom cylinder's stroke must lie in 0-1.6 m)",
            field: (m.initial, INITIAL_JOINTS)[1]),
        fmu_model::field!(Real::parameter(2, "q0.jib"), unit: "rad", range: (-3.2, 3.2),
            doc: "Initial jib angle relative to the boom, positive up (the jib cylinder's stroke must lie in 0-1.6 m)",
            field: (m.initial, INITIAL_JOINTS)[2]),
        fmu_model::field!(Real::parameter(3, "lp0"), unit: "m", start: LP0, range: (0.5, 200.0),
            doc: "Initial hoist length, tip to load (the pendulum length)",
            field: m => m.lp0),
    ],
    &noise_parameters!(4, m => m.noise, m.seed, start: (NOISE, SEED),
        noise: "Add Gaussian noise to the encoder, stroke and pressure readings (quantisation applies regardless)",
        seed: "Noise seed; give every noisy instance of the system its own"),
    &[
        // Parameters: the crane (docs/crane-description.md).
        Text::parameter(9, "crane")
            .start(crane_description::catalogue::DEFAULT_CRANE)
            .doc(concat!(
                "Crane description: a catalogue name (osp_derived, osp_test_crane, ahc_10t) or a JSON file's path ",
                "(a relative one from the working directory, else from the FMU's resources folder); every crane ",
                "parameter comes from it and the crane.* and other calculated parameters show the values in force"
            ))
            .get(|m| &m.crane)
            .set(|m, v| m.crane = v.to_string()),
        Integer::parameter(14, "winch.circuit")
            .start(CIRCUIT_AS_DESCRIBED)
            .range(-1, 1)
            .doc(concat!(
                "Winch drive: -1 as the crane description says, 0 open circuit (proportional valve, counterbalance ",
                "valve, port reliefs on the supply), 1 closed circuit (over-centre pump driving the motor, charge ",
                "checks, cross-port reliefs; the spool.winch input commands the pump's displacement)"
            ))
            .get(|m| m.circuit)
            .set(|m, v| m.circuit = v),
    ],
    &CALCULATED,
    &xyz!(Real::parameter(24, "base."),
        unit: "m",
        range: (-200.0, 200.0),
        doc: ("Pedestal foot on deck, ship frame B " + axis + "; the controller's base.* must be the same"),
        field: (m.params, PARAMS).arm.base),
    // Inputs: valve spools.
    &[
        Real::held_input(100, "spool.slew")
            .unit("1")
            .start(0.0)
            .doc("Slew valve spool command, -1..1 (clamped); positive turns clockwise seen from above")
            .get(|m| m.spools.0[SLEW])
            .set(|m, v| m.set_input(|m| m.spools.0[SLEW] = v)),
        Real::held_input(101, "spool.boom")
            .unit("1")
            .start(0.0)
            .doc("Boom valve spool command, -1..1 (clamped); positive extends the cylinder (raises the boom)")
            .get(|m| m.spools.0[BOOM])
            .set(|m, v| m.set_input(|m| m.spools.0[BOOM] = v)),
        Real::held_input(102, "spool.jib")
            .unit("1")
            .start(0.0)
            .doc("Jib valve spool command, -1..1 (clamped); positive extends the cylinder (raises the jib)")
            .get(|m| m.spools.0[JIB])
            .set(|m, v| m.set_input(|m| m.spools.0[JIB] = v)),
        Real::held_input(103, "spool.winch")
            .unit("1")
            .start(0.0)
            .doc("Winch valve spool command (closed circuit: pump displacement command), -1..1 (clamped); positive pays rope out (lowers the load)")
            .get(|m| m.spools.0[WINCH])
            .set(|m, v| m.set_input(|m| m.spools.0[WINCH] = v)),
    ],
    // Inputs: ship (deck) motion, the platform's outputs.
    &ship_inputs!(accelerations, m => m.loads.ship),
    // Inputs: the hoist rope's load, the pendulum's outputs (physics::hydraulic_crane::plant::Loads).
    &xyz!(Real::held_input(130, "cable.f0"),
        unit: "N",
        start: [0.0; 3],
        doc: ("Rope force on the tip for an unaccelerated tip and a steady length, W " + axis
            + ": toward the load, at rest (0, 0, m g); the crane adds the load's inertia along the rope"),
        get: |m| m.loads.cable,
        set: |m, v| m.set_input(|m| m.loads.cable)),
    &[Real::held_input(133, "cable.mass")
        .unit("kg")
        .start(0.0)
        // A negative mass would turn the rope's inertia into a push and the tension into nonsense;
        // the bound is the rigging's (hook and load masses up to 1e6 kg each).
        .range(0.0, CABLE_MASS_MAX)
        .doc("Mass hanging in the rope, whose inertia along the rope the crane integrates; 0: cable.f0 is the whole force")
        .get(|m| m.loads.load_mass)
        .set(|m, v| m.set_input(|m| m.loads.load_mass = v))],
    // Outputs: the tip in W.
    &xyz!(Real::output(200, "tip."),
        unit: "m",
        doc: ("Crane tip (rope sheave) position, W " + axis),
        get: |m| m.tip().pos),
    &xyz!(Real::output(203, "tip.v"),
        unit: "m/s",
        doc: ("Crane tip velocity, W " + axis),
        get: |m| m.tip().vel),
    &xyz!(Real::output(206, "tip.a"),
        unit: "m/s2",
        doc: ("Crane tip acceleration, W " + axis + " (under the inputs currently set)"),
        get: |m| m.tip().acc),
    &[
        Real::output(288, "brake.slew")
            .unit("N.m")
            .doc("Slew brake torque against the slew's motion (0 released or not fitted)")
            .get(|m| m.evaluation().brake_torques[0]),
        Real::output(289, "brake.winch")
            .unit("N.m")
            .doc("Drum brake torque against the drum's motion (0 released or not fitted)")
            .get(|m| m.evaluation().brake_torques[1]),
    ],
    &[Real::output(287, "clearance.tip")
        .unit("m")
        .doc("Height of the tip above the deck plane (the pedestal foot's); a warning is logged whenever it goes below 0")
        .get(|m| m.tip_clearance())],
    &xyz!(Real::output(210, "tip_base."),
        unit: "m",
        doc: ("Crane tip position in the base frame K (from the pedestal foot), " + axis),
        get: |m| m.tip_base().pos),
    &[
        Real::output(213, "lp").unit("m").doc("Hoist length, tip to load (drum payout)").get(|m| m.lp()),
        Real::output(214, "lp_dot")
            .unit("m/s")
            .doc("Hoist length rate")
            .get(|m| m.params.drum_radius * m.state.drum_rate),
        Real::output(215, "lp_ddot")
            .unit("m/s2")
            .doc("Hoist length acceleration (under the inputs currently set)")
            .get(|m| m.params.drum_radius * m.evaluation().drum_acc),
        // Outputs: joints and actuators.
        Real::output(220, "joint.slew").unit("rad").doc("Slew angle").get(|m| m.state.q[0]),
        Real::output(221, "joint.boom").unit("rad").doc("Boom elevation").get(|m| m.state.q[1]),
        Real::output(222, "joint.jib").unit("rad").doc("Jib angle relative to the boom").get(|m| m.state.q[2]),
        Real::output(223, "joint.slew_dot").unit("rad/s").doc("Slew rate").get(|m| m.state.qd[0]),
        Real::output(224, "joint.boom_dot").unit("rad/s").doc("Boom elevation rate").get(|m| m.state.qd[1]),
        Real::output(225, "joint.jib_dot").unit("rad/s").doc("Jib angle rate").get(|m| m.state.qd[2]),
        Real::output(226, "stroke.boom")
            .unit("m")
            .doc("Boom cylinder stroke (0-1.6 m)")
            .get(|m| m.evaluation().drives[BOOM].pos),
        Real::output(227, "stroke.jib")
            .unit("m")
            .doc("Jib cylinder stroke (0-1.6 m)")
            .get(|m| m.evaluation().drives[JIB].pos),
        Real::output(228, "stroke.boom_dot")
            .unit("m/s")
            .doc("Boom cylinder speed")
            .get(|m| m.evaluation().drives[BOOM].vel),
        Real::output(229, "stroke.jib_dot")
            .unit("m/s")
            .doc("Jib cylinder speed")
            .get(|m| m.evaluation().drives[JIB].vel),
        Real::output(230, "p.slew.a").unit("Pa").doc("Slew motor, chamber A pressure").get(|m| pressure(m, SLEW, 0)),
        Real::output(231, "p.slew.b").unit("Pa").doc("Slew motor, chamber B pressure").get(|m| pressure(m, SLEW, 1)),
        Real::output(232, "p.boom.a")
            .unit("Pa")
            .doc("Boom cylinder, piston (load-holding) chamber pressure")
            .get(|m| pressure(m, BOOM, 0)),
        Real::output(233, "p.boom.b")
            .unit("Pa")
            .doc("Boom cylinder, rod chamber pressure")
            .get(|m| pressure(m, BOOM, 1)),
        Real::output(234, "p.jib.a")
            .unit("Pa")
            .doc("Jib cylinder, piston (load-holding) chamber pressure")
            .get(|m| pressure(m, JIB, 0)),
        Real::output(235, "p.jib.b").unit("Pa").doc("Jib cylinder, rod chamber pressure").get(|m| pressure(m, JIB, 1)),
        Real::output(236, "p.winch.a").unit("Pa").doc("Winch motor, chamber A pressure").get(|m| pressure(m, WINCH, 0)),
        Real::output(237, "p.winch.b").unit("Pa").doc("Winch motor, chamber B pressure").get(|m| pressure(m, WINCH, 1)),
        Real::output(240, "flow.slew")
            .unit("m3/s")
            .doc("Flow the slew valve draws from the pump")
            .get(|m| m.evaluation().rates[SLEW].q_supply),
        Real::output(241, "flow.boom")
            .unit("m3/s")
            .doc("Flow the boom valve draws from the pump")
            .get(|m| m.evaluation().rates[BOOM].q_supply),
        Real::output(242, "flow.jib")
            .unit("m3/s")
            .doc("Flow the jib valve draws from the pump")
            .get(|m| m.evaluation().rates[JIB].q_supply),
        Real::output(243, "flow.winch")
            .unit("m3/s")
            .doc("Flow the winch valve draws from the pump (closed circuit: the charge pump's flow into the winch's loop)")
            .get(|m| m.evaluation().rates[WINCH].q_supply),
        Real::output(244, "flow.pump")
            .unit("m3/s")
            .doc("Total pump flow (the four valves)")
            .get(|m| m.evaluation().rates.iter().map(|r| r.q_supply).sum()),
        Real::output(245, "power.hydraulic")
            .unit("W")
            .doc("Hydraulic power drawn from the pump")
            .get(|m| CraneParams::pump_power(m.evaluation())),
        Real::output(246, "force.boom")
            .unit("N")
            .doc("Boom cylinder force on the rod, extending positive (pressures, friction, end stops)")
            .get(|m| m.evaluation().rates[BOOM].force),
        Real::output(247, "force.jib")
            .unit("N")
            .doc("Jib cylinder force on the rod, extending positive")
            .get(|m| m.evaluation().rates[JIB].force),
        Real::output(248, "torque.slew")
            .unit("N.m")
            .doc("Slew drive torque at the slewing ring (after the gear)")
            .get(|m| m.evaluation().rates[SLEW].force),
        Real::output(249, "torque.winch")
            .unit("N.m")
            .doc("Winch drive torque at the drum (after the gear), positive hoisting")
            .get(|m| m.evaluation().rates[WINCH].force),
        Real::output(250, "drum.angle")
            .unit("rad")
            .doc("Winch drum angle from the start, positive paying out")
            .get(|m| m.state.drum),
        Real::output(251, "drum.rate").unit("rad/s").doc("Winch drum rate").get(|m| m.state.drum_rate),
        Real::output(238, "swash.winch")
            .unit("1")
            .doc("Closed-circuit winch pump's displacement fraction (swash-plate angle), -1..1, positive hoisting; 0 in the open circuit")
            .get(|m| m.state.swash),
        Real::output(252, "tension")
            .unit("N")
            .doc("Hoist rope tension at the tip (0 when slack)")
            .get(|m| m.evaluation().tension),
    ],
    &INTERFACE,
    &xyz!(Real::output(253, "cable."),
        unit: "N",
        doc: ("Rope force on the tip, W " + axis + " (the tension along the rope)"),
        get: |m| m.evaluation().cable_force),
    &[
        // Outputs: sensors.
        Real::output(260, "sensor.joint.slew")
            .unit("rad")
            .doc("Slew encoder: 17-bit absolute, noise sigma.joint")
            .get(|m| m.readings.joints[0]),
        Real::output(261, "sensor.joint.boom").unit("rad").doc("Boom encoder").get(|m| m.readings.joints[1]),
        Real::output(262, "sensor.joint.jib").unit("rad").doc("Jib encoder").get(|m| m.readings.joints[2]),
        Real::output(263, "sensor.stroke.boom")
            .unit("m")
            .doc("Boom cylinder stroke transducer: 10 um resolution, noise sigma.stroke")
            .get(|m| m.readings.strokes[0]),
        Real::output(264, "sensor.stroke.jib")
            .unit("m")
            .doc("Jib cylinder stroke transducer")
            .get(|m| m.readings.strokes[1]),
        Real::output(265, "sensor.p.slew.a")
            .unit("Pa")
            .doc("Pressure transducer, slew motor A: 0-40 MPa, 12-bit, noise sigma.pressure")
            .get(|m| reading(m, SLEW, 0)),
        Real::output(266, "sensor.p.slew.b").unit("Pa").doc("Pressure transducer, slew motor B").get(|m| reading(m, SLEW, 1)),
        Real::output(267, "sensor.p.boom.a")
            .unit("Pa")
            .doc("Pressure transducer, boom cylinder piston side")
            .get(|m| reading(m, BOOM, 0)),
        Real::output(268, "sensor.p.boom.b")
            .unit("Pa")
            .doc("Pressure transducer, boom cylinder rod side")
            .get(|m| reading(m, BOOM, 1)),
        Real::output(269, "sensor.p.jib.a")
            .unit("Pa")
            .doc("Pressure transducer, jib cylinder piston side")
            .get(|m| reading(m, JIB, 0)),
        Real::output(270, "sensor.p.jib.b")
            .unit("Pa")
            .doc("Pressure transducer, jib cylinder rod side")
            .get(|m| reading(m, JIB, 1)),
        Real::output(271, "sensor.p.winch.a").unit("Pa").doc("Pressure transducer, winch motor A").get(|m| reading(m, WINCH, 0)),
        Real::output(272, "sensor.p.winch.b").unit("Pa").doc("Pressure transducer, winch motor B").get(|m| reading(m, WINCH, 1)),
        Real::output(273, "sensor.drum")
            .unit("rad")
            .doc("Winch drum encoder: 12 bits per turn, multi-turn, noise sigma.drum")
            .get(|m| m.readings.drum),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(KnuckleBoom);

#[cfg(test)]
mod tests;

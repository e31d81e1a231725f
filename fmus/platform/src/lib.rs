//! FMU `platform`: the ship motion source and the motion platform (SPEC §4.1; thesis §3.3, §4.1).
//!
//! No continuous state: every output at a communication point t is a function of the
//! parameters and t. The motion source is built at initialization (the test-scale conversion of
//! profiles 1–3 and the motion file happen there); each step samples it at profile time
//! τ = t − `motion_start` + `time_offset`, weights it by the motion window (rest before
//! `motion_start`, C² fade-in over `fade_in`; [`MotionWindow`]), resolves it in the platform frame
//! for the crane's location, runs the inverse kinematics and publishes the deck motion and the
//! actuator set-points. Ports are SI; positions, velocities and accelerations in W
//! (North-East-Down), angular velocity and acceleration in the deck frame B.

use fmi2::{Model, ModelInfo, Variable};
use physics::motion::{DeckMotion, ShipMotion};
use physics::platform::kinematics::PlatformGeometry;
use physics::platform::{drive, CraneLocation, InverseModel, PlatformState};
use physics::ship::profiles::ProfileId;
use physics::ship::rao::Hull;
use physics::ship::source::{MotionSource, SourceConfig, SourceKind, SINE_AMPLITUDE, SINE_OMEGA};
use physics::ship::window::MotionWindow;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// Instance data: parameters, the source built from them and the outputs last computed.
#[derive(Clone, Serialize, Deserialize)]
pub struct Platform {
    config: SourceConfig,
    crane_location: CraneLocation,
    ik_model: InverseModel,
    mechanism_yaw: bool,
    time_offset: f64,
    /// `motion_start` and `fade_in`: rest, then fade the motion in.
    window: MotionWindow,
    resource_dir: Option<PathBuf>,
    hull: Hull,
    geometry: PlatformGeometry,
    /// The source and the configuration it was built for (initialization is idempotent).
    source: Option<(SourceConfig, MotionSource)>,
    /// What `state` was driven from: the requested deck motion (bits), the inverse model and the
    /// mechanism-yaw switch. A deck that does not move (still water, before `motion_start`, past
    /// the end of a motion file) asks for the same again, and the outputs are already there.
    driven: Option<(DeckMotion, InverseModel, bool)>,
    state: PlatformState,
    ship: ShipMotion,
    /// Orientation W←B, scalar first.
    q: [f64; 4],
}

impl Platform {
    /// Samples the source at communication point `t` and updates every output.
    fn update(&mut self, t: f64) -> Result<(), String> {
        let Some((_, source)) = &mut self.source else { return Err("the motion source was not built".into()) };
        let requested = self.crane_location.resolve(&self.window.sample(source, t, self.time_offset));
        let (model, yaw) = (self.ik_model, self.mechanism_yaw);
        if self.driven.as_ref().is_some_and(|(r, m, y)| r.same_bits(&requested) && (*m, *y) == (model, yaw)) {
            return Ok(());
        }
        self.state = drive(&self.geometry, &requested, model, yaw).map_err(|e| format!("at t = {t} s: {e}"))?;
        self.ship = self.state.deck.to_ship_motion();
        let q = self.ship.attitude();
        self.q = [q.w, q.i, q.j, q.k];
        self.driven = Some((requested, model, yaw));
        Ok(())
    }
}

impl Model for Platform {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "platform",
        description: "Ship motion source (still water, synthesized sea-state profiles 1-3 at test scale, sine, CSV file) and motion-platform inverse kinematics with actuator set-points (thesis sections 3.3, 4.1)",
        default_stop_time: 120.0,
        default_step_size: 0.01,
        can_interpolate_inputs: false,
        max_step_size: f64::MAX,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(env: &fmi2::Environment) -> Self {
        Platform {
            config: SourceConfig::default(),
            crane_location: CraneLocation::DEFAULT,
            ik_model: InverseModel::DEFAULT,
            mechanism_yaw: MECHANISM_YAW,
            time_offset: TIME_OFFSET,
            window: MotionWindow::DEFAULT,
            resource_dir: env.resource_dir.clone(),
            hull: Hull::default(),
            geometry: PlatformGeometry::default(),
            source: None,
            driven: None,
            state: PlatformState::default(),
            ship: ShipMotion::default(),
            q: [1.0, 0.0, 0.0, 0.0],
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.window.validate()?;
        if !self.source.as_ref().is_some_and(|(built_for, _)| *built_for == self.config) {
            let source = MotionSource::build(&self.config, self.resource_dir.as_deref(), &self.hull, &self.geometry)?;
            self.source = Some((self.config.clone(), source));
        }
        self.update(start_time)
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        self.update(t + h)
    }
}

/// Default of `mechanism_yaw`: the deck follows the requested motion alone.
const MECHANISM_YAW: bool = false;
/// Default of `time_offset` (s).
const TIME_OFFSET: f64 = 0.0;
/// The `seed` that keeps each profile's own seed.
const OWN_SEED: i32 = 0;

// Integer codes of the enumerations, converted here and nowhere else. Each parameter's declared
// range is exactly its codes, so `fmi2SetInteger` refuses any other code ("'profile' = 6 is outside
// its range [0, 5]") before a setter sees it.

/// `profile`: 0 still water, 1–3 the test-scale profiles, 4 sine, 5 CSV file.
const fn source_code(kind: SourceKind) -> i32 {
    match kind {
        SourceKind::Still => 0,
        SourceKind::Sea(ProfileId::One) => 1,
        SourceKind::Sea(ProfileId::Two) => 2,
        SourceKind::Sea(ProfileId::Three) => 3,
        SourceKind::Sine => 4,
        SourceKind::File => 5,
    }
}

fn source_kind(code: i32) -> Option<SourceKind> {
    Some(match code {
        0 => SourceKind::Still,
        1 => SourceKind::Sea(ProfileId::One),
        2 => SourceKind::Sea(ProfileId::Two),
        3 => SourceKind::Sea(ProfileId::Three),
        4 => SourceKind::Sine,
        5 => SourceKind::File,
        _ => return None,
    })
}

fn source_from_code(code: i32) -> SourceKind {
    source_kind(code).expect("fmi2SetInteger refuses a profile outside its range")
}

/// `crane_location`: 0 port side, 1 stern.
const fn location_code(location: CraneLocation) -> i32 {
    match location {
        CraneLocation::Port => 0,
        CraneLocation::Stern => 1,
    }
}

fn location(code: i32) -> Option<CraneLocation> {
    match code {
        0 => Some(CraneLocation::Port),
        1 => Some(CraneLocation::Stern),
        _ => None,
    }
}

fn location_from_code(code: i32) -> CraneLocation {
    location(code).expect("fmi2SetInteger refuses a crane_location outside its range")
}

/// `ik_model`: 0 exact closed chain, 1 simplified eqs. 4.1–4.5.
const fn model_code(model: InverseModel) -> i32 {
    match model {
        InverseModel::Exact => 0,
        InverseModel::Simplified => 1,
    }
}

fn inverse_model(code: i32) -> Option<InverseModel> {
    match code {
        0 => Some(InverseModel::Exact),
        1 => Some(InverseModel::Simplified),
        _ => None,
    }
}

fn model_from_code(code: i32) -> InverseModel {
    inverse_model(code).expect("fmi2SetInteger refuses an ik_model outside its range")
}

type V = Variable<Platform>;

/// The variable table (value references: parameters 0–99, outputs 200+).
static VARIABLES: &[V] = &[
    // Parameters.
    V::integer_parameter(0, "profile", source_code(SourceConfig::DEFAULT_KIND), 0, 5, "Ship motion: 0 still water, 1-3 test-scale profiles (1 sea state 4 bow-quartering, 2 sea state 5 beam seas, 3 sea state 5 head seas), 4 sine in surge and sway, 5 CSV file", |m| source_code(m.config.kind), |m, v| m.config.kind = source_from_code(v)),
    V::parameter(1, "sine_omega", "rad/s", SINE_OMEGA, "Profile 4: sine frequency (default sqrt(g/0.7 m), the pendulum's natural frequency at 0.7 m)", |m| m.config.sine_omega, |m, v| m.config.sine_omega = v).range(0.0, 100.0),
    V::parameter(2, "sine_amplitude", "m", SINE_AMPLITUDE, "Profile 4: amplitude of surge and sway (in phase)", |m| m.config.sine_amplitude, |m, v| m.config.sine_amplitude = v).range(0.0, 1.0),
    V::string_parameter(3, "motion_file", "", "Profile 5: CSV file with columns time, surge, sway, heave, roll, pitch, yaw (SI); a relative path is resolved in the FMU's resources folder", |m| &m.config.motion_file, |m, v| m.config.motion_file = v.to_string()),
    V::integer_parameter(4, "crane_location", location_code(CraneLocation::DEFAULT), 0, 1, "Crane on the ship: 0 port side (platform frame = ship frame), 1 stern (ship motion resolved in a frame turned -90 deg about z)", |m| location_code(m.crane_location), |m, v| m.crane_location = location_from_code(v)),
    V::boolean_parameter(5, "mechanism_yaw", MECHANISM_YAW, "Add the yaw the platform mechanism takes (dependent on heave, roll and pitch) to the deck motion", |m| m.mechanism_yaw, |m, v| m.mechanism_yaw = v),
    V::integer_parameter(6, "seed", OWN_SEED, 0, i32::MAX, "Profiles 1-3: seed of the random wave phases and frequencies; 0 keeps the profile's own (1, 2, 3)", |m| m.config.seed.map_or(OWN_SEED, |s| s as i32), |m, v| m.config.seed = (v != OWN_SEED).then_some(v as u64)),
    V::parameter(7, "time_offset", "s", TIME_OFFSET, "Added to the profile time: the motion is sampled at t - motion_start + time_offset (with the default motion_start = 0 at t + time_offset; -10 puts profile time 0 at t = 10 s, but the deck then moves before too: use motion_start to rest until then)", |m| m.time_offset, |m, v| m.time_offset = v).range(-1e6, 1e6),
    V::integer_parameter(8, "ik_model", model_code(InverseModel::DEFAULT), 0, 1, "Actuator set-points from 0 the exact closed-chain inverse kinematics, 1 the simplified eqs. 4.1-4.5", |m| model_code(m.ik_model), |m, v| m.ik_model = model_from_code(v)),
    V::parameter(9, "motion_start", "s", MotionWindow::DEFAULT.start, "The deck rests at the zero pose (the mean pose of profiles 1-4) while t < motion_start and moves from then on; profile time 0 is at t = motion_start (+ time_offset shifts it)", |m| m.window.start, |m, v| m.window.start = v).range(-1e6, 1e6),
    V::parameter(10, "fade_in", "s", MotionWindow::DEFAULT.fade_in, "Duration of the fade-in after motion_start: the motion is multiplied by w = 10s^3 - 15s^4 + 6s^5, s = (t - motion_start)/fade_in, with exact velocity and acceleration (continuous up to acceleration); 0 switches the motion on at once", |m| m.window.fade_in, |m, v| m.window.fade_in = v).range(0.0, 1e6),
    // Outputs: deck pose.
    V::output(200, "ship.x", "m", "Deck (ship frame) origin, W x: surge", |m| m.ship.pos.x),
    V::output(201, "ship.y", "m", "Deck origin, W y: sway", |m| m.ship.pos.y),
    V::output(202, "ship.z", "m", "Deck origin, W z: heave (down)", |m| m.ship.pos.z),
    V::output(203, "ship.roll", "rad", "Roll (Z-Y-X sequence, applied last)", |m| m.ship.roll),
    V::output(204, "ship.pitch", "rad", "Pitch (Z-Y-X sequence)", |m| m.ship.pitch),
    V::output(205, "ship.yaw", "rad", "Yaw (Z-Y-X sequence, applied first); zero at test scale unless mechanism_yaw", |m| m.ship.yaw),
    V::output(206, "ship.q0", "1", "Orientation W<-B, quaternion scalar part", |m| m.q[0]),
    V::output(207, "ship.q1", "1", "Orientation W<-B, quaternion x part", |m| m.q[1]),
    V::output(208, "ship.q2", "1", "Orientation W<-B, quaternion y part", |m| m.q[2]),
    V::output(209, "ship.q3", "1", "Orientation W<-B, quaternion z part", |m| m.q[3]),
    // Outputs: deck velocity and acceleration.
    V::output(210, "ship.vx", "m/s", "Deck origin velocity, W x", |m| m.ship.vel.x),
    V::output(211, "ship.vy", "m/s", "Deck origin velocity, W y", |m| m.ship.vel.y),
    V::output(212, "ship.vz", "m/s", "Deck origin velocity, W z", |m| m.ship.vel.z),
    V::output(213, "ship.ax", "m/s2", "Deck origin acceleration, W x", |m| m.ship.acc.x),
    V::output(214, "ship.ay", "m/s2", "Deck origin acceleration, W y", |m| m.ship.acc.y),
    V::output(215, "ship.az", "m/s2", "Deck origin acceleration, W z", |m| m.ship.acc.z),
    V::output(216, "ship.wx", "rad/s", "Deck angular velocity, B x", |m| m.ship.omega.x),
    V::output(217, "ship.wy", "rad/s", "Deck angular velocity, B y", |m| m.ship.omega.y),
    V::output(218, "ship.wz", "rad/s", "Deck angular velocity, B z", |m| m.ship.omega.z),
    V::output(219, "ship.alphax", "rad/s2", "Deck angular acceleration, B x", |m| m.ship.alpha.x),
    V::output(220, "ship.alphay", "rad/s2", "Deck angular acceleration, B y", |m| m.ship.alpha.y),
    V::output(221, "ship.alphaz", "rad/s2", "Deck angular acceleration, B z", |m| m.ship.alpha.z),
    // Outputs: actuator set-points.
    V::output(230, "la1", "m", "LA1 set-point (sway gantry), extension 0-0.2 m, nominal 0.1 m", |m| m.state.la[0].pos),
    V::output(231, "la2", "m", "LA2 set-point (surge gantry)", |m| m.state.la[1].pos),
    V::output(232, "la3", "m", "LA3 set-point (leg at 90 deg)", |m| m.state.la[2].pos),
    V::output(233, "la4", "m", "LA4 set-point (leg at 210 deg)", |m| m.state.la[3].pos),
    V::output(234, "la5", "m", "LA5 set-point (leg at 330 deg)", |m| m.state.la[4].pos),
    V::boolean_output(240, "la_limit", "A set-point is outside 0-0.2 m or moves faster than 20 mm/s", |m| m.state.la_limit),
];

fmi2::export_fmu!(Platform);

#[cfg(test)]
mod tests;

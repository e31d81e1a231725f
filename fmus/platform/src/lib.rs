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
//!
//! `scale = 1` (full scale) publishes the vessel's own motion instead (profiles 1–3 unscaled,
//! uncentred, yaw included; [`MotionScale::Full`]) for a full-scale crane, and drives no platform:
//! the set-points rest at the neutral extension with the limit flag false
//! ([`PlatformState::unactuated`]); `ik_model` and `mechanism_yaw` then have no effect.

use fmu_model::{xyz, Environment, Model, ModelInfo, Variable};
use physics::motion::{DeckMotion, ShipMotion};
use physics::platform::kinematics::PlatformGeometry;
use physics::platform::{drive, CraneLocation, InverseModel, PlatformState};
use physics::ship::profiles::ProfileId;
use physics::ship::rao::Hull;
use physics::ship::source::{MotionScale, MotionSource, SourceConfig, SourceKind, SINE_AMPLITUDE, SINE_OMEGA};
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
    /// What `state` was driven from: the requested deck motion (bits), the inverse model, the
    /// mechanism-yaw switch and the scale. A deck that does not move (still water, before
    /// `motion_start`, past the end of a motion file) asks for the same again, and the outputs are
    /// already there.
    driven: Option<(DeckMotion, InverseModel, bool, MotionScale)>,
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
        let (model, yaw, scale) = (self.ik_model, self.mechanism_yaw, self.config.scale);
        if self
            .driven
            .as_ref()
            .is_some_and(|(r, m, y, s)| r.same_bits(&requested) && (*m, *y, *s) == (model, yaw, scale))
        {
            return Ok(());
        }
        self.state = match scale {
            MotionScale::Test => {
                drive(&self.geometry, &requested, model, yaw).map_err(|e| format!("at t = {t} s: {e}"))?
            }
            // The test-scale platform cannot follow the vessel's motion: it is not driven.
            MotionScale::Full => PlatformState::unactuated(&self.geometry, &requested),
        };
        self.ship = self.state.deck.to_ship_motion();
        let q = self.ship.attitude();
        self.q = [q.w, q.i, q.j, q.k];
        self.driven = Some((requested, model, yaw, scale));
        Ok(())
    }
}

impl Model for Platform {
    const INFO: ModelInfo = ModelInfo::new(
        "platform",
        concat!(
            "Ship motion source (still water, synthesized sea-state profiles 1-3 at test or full scale, sine, CSV ",
            "file) and motion-platform inverse kinematics with actuator set-points (thesis sections 3.3, 4.1)",
        ),
    )
    .stop_time(120.0);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(env: &Environment) -> Self {
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

fmu_model::codes! {
    /// `profile`: 0 still water, 1–3 the test-scale profiles, 4 sine, 5 CSV file.
    SourceCodes: SourceKind {
        SourceKind::Still => 0,
        SourceKind::Sea(ProfileId::One) => 1,
        SourceKind::Sea(ProfileId::Two) => 2,
        SourceKind::Sea(ProfileId::Three) => 3,
        SourceKind::Sine => 4,
        SourceKind::File => 5,
    }
}

fmu_model::codes! {
    /// `scale`: 0 test scale, 1 full scale.
    ScaleCodes: MotionScale { MotionScale::Test => 0, MotionScale::Full => 1 }
}

fmu_model::codes! {
    /// `crane_location`: 0 port side, 1 stern.
    LocationCodes: CraneLocation { CraneLocation::Port => 0, CraneLocation::Stern => 1 }
}

fmu_model::codes! {
    /// `ik_model`: 0 exact closed chain, 1 simplified eqs. 4.1–4.5.
    ModelCodes: InverseModel { InverseModel::Exact => 0, InverseModel::Simplified => 1 }
}

type V = Variable<Platform>;
type Real = fmu_model::Real<Platform>;
type Integer = fmu_model::Integer<Platform>;
type Boolean = fmu_model::Boolean<Platform>;
type Text = fmu_model::Text<Platform>;

/// The variable table (value references: parameters 0–99, outputs 200+).
const GROUPS: &[&[V]] = &[
    &[
        // Parameters.
        fmu_model::coded!(Integer::parameter(0, "profile"), SourceCodes, start: SourceConfig::DEFAULT_KIND,
            doc: concat!(
                "Ship motion: 0 still water, 1-3 profiles at test or full scale (parameter scale; 1 sea state 4 ",
                "bow-quartering, 2 sea state 5 beam seas, 3 sea state 5 head seas), 4 sine in surge and sway, ",
                "5 CSV file"
            ),
            value: |m| m.config.kind),
        fmu_model::field!(Real::parameter(1, "sine_omega"), unit: "rad/s", start: SINE_OMEGA, range: (0.0, 100.0),
            doc: "Profile 4: sine frequency (default sqrt(g/0.7 m), the pendulum's natural frequency at 0.7 m)",
            field: m => m.config.sine_omega),
        fmu_model::field!(Real::parameter(2, "sine_amplitude"), unit: "m", start: SINE_AMPLITUDE, range: (0.0, 1.0),
            doc: "Profile 4: amplitude of surge and sway (in phase)",
            field: m => m.config.sine_amplitude),
        Text::parameter(3, "motion_file")
            .start("")
            .doc(concat!(
                "Profile 5: CSV file with columns time, surge, sway, heave, roll, pitch, yaw (SI); a relative path ",
                "is resolved in the FMU's resources folder"
            ))
            .get(|m| &m.config.motion_file)
            .set(|m, v| m.config.motion_file = v.to_string()),
        fmu_model::coded!(Integer::parameter(4, "crane_location"), LocationCodes, start: CraneLocation::DEFAULT,
            doc: concat!(
                "Crane on the ship: 0 port side (platform frame = ship frame), 1 stern (ship motion resolved in a ",
                "frame turned -90 deg about z)"
            ),
            value: |m| m.crane_location),
        fmu_model::field!(Boolean::parameter(5, "mechanism_yaw"), start: MECHANISM_YAW,
            doc: "Add the yaw the platform mechanism takes (dependent on heave, roll and pitch) to the deck motion",
            field: m => m.mechanism_yaw),
        Integer::parameter(6, "seed")
            .start(OWN_SEED)
            .range(0, i32::MAX)
            .doc("Profiles 1-3: seed of the random wave phases and frequencies; 0 keeps the profile's own (1, 2, 3)")
            .get(|m| m.config.seed.map_or(OWN_SEED, |s| s as i32))
            .set(|m, v| m.config.seed = (v != OWN_SEED).then_some(v as u64)),
        fmu_model::field!(Real::parameter(7, "time_offset"), unit: "s", start: TIME_OFFSET, range: (-1e6, 1e6),
            doc: concat!(
                "Added to the profile time: the motion is sampled at t - motion_start + time_offset (with the ",
                "default motion_start = 0 at t + time_offset; -10 puts profile time 0 at t = 10 s, but the deck ",
                "then moves before too: use motion_start to rest until then)"
            ),
            field: m => m.time_offset),
        fmu_model::coded!(Integer::parameter(8, "ik_model"), ModelCodes, start: InverseModel::DEFAULT,
            doc: "Actuator set-points from 0 the exact closed-chain inverse kinematics, 1 the simplified eqs. 4.1-4.5",
            value: |m| m.ik_model),
        fmu_model::field!(Real::parameter(9, "motion_start"), unit: "s", range: (-1e6, 1e6),
            doc: concat!(
                "The deck rests at the zero pose (the mean pose of profiles 1-4) while t < motion_start and moves ",
                "from then on; profile time 0 is at t = motion_start (+ time_offset shifts it)"
            ),
            field: (m.window, MotionWindow::DEFAULT).start),
        fmu_model::field!(Real::parameter(10, "fade_in"), unit: "s", range: (0.0, 1e6),
            doc: concat!(
                "Duration of the fade-in after motion_start: the motion is multiplied by w = 10s^3 - 15s^4 + 6s^5, ",
                "s = (t - motion_start)/fade_in, with exact velocity and acceleration (continuous up to ",
                "acceleration); 0 switches the motion on at once"
            ),
            field: (m.window, MotionWindow::DEFAULT).fade_in),
        fmu_model::coded!(Integer::parameter(11, "scale"), ScaleCodes, start: MotionScale::Test,
            doc: concat!(
                "0 test scale (profiles 1-3 scaled to the platform, section 3.3), 1 full scale: the 120 m vessel's ",
                "own motion (profiles 1-3 unscaled and uncentred, yaw included; sine and file as given at both), ",
                "the platform not driven (la1-la5 held at 0.1 m, la_limit false; ik_model and mechanism_yaw unused)"
            ),
            value: |m| m.config.scale),
    ],
    // Outputs: deck pose.
    &xyz!(Real::output(200, "ship."),
        unit: "m",
        doc: ["Deck (ship frame) origin, W x: surge", "Deck origin, W y: sway", "Deck origin, W z: heave (down)"],
        get: |m| m.ship.pos),
    &[
        Real::output(203, "ship.roll").unit("rad").doc("Roll (Z-Y-X sequence, applied last)").get(|m| m.ship.roll),
        Real::output(204, "ship.pitch").unit("rad").doc("Pitch (Z-Y-X sequence)").get(|m| m.ship.pitch),
        Real::output(205, "ship.yaw")
            .unit("rad")
            .doc("Yaw (Z-Y-X sequence, applied first); profiles 1-3: zero at test scale unless mechanism_yaw")
            .get(|m| m.ship.yaw),
        Real::output(206, "ship.q0").unit("1").doc("Orientation W<-B, quaternion scalar part").get(|m| m.q[0]),
        Real::output(207, "ship.q1").unit("1").doc("Orientation W<-B, quaternion x part").get(|m| m.q[1]),
        Real::output(208, "ship.q2").unit("1").doc("Orientation W<-B, quaternion y part").get(|m| m.q[2]),
        Real::output(209, "ship.q3").unit("1").doc("Orientation W<-B, quaternion z part").get(|m| m.q[3]),
    ],
    // Outputs: deck velocity and acceleration.
    &xyz!(Real::output(210, "ship.v"),
        unit: "m/s",
        doc: ("Deck origin velocity, W " + axis),
        get: |m| m.ship.vel),
    &xyz!(Real::output(213, "ship.a"),
        unit: "m/s2",
        doc: ("Deck origin acceleration, W " + axis),
        get: |m| m.ship.acc),
    &xyz!(Real::output(216, "ship.w"),
        unit: "rad/s",
        doc: ("Deck angular velocity, B " + axis),
        get: |m| m.ship.omega),
    &xyz!(Real::output(219, "ship.alpha"),
        unit: "rad/s2",
        doc: ("Deck angular acceleration, B " + axis),
        get: |m| m.ship.alpha),
    &[
        // Outputs: actuator set-points.
        Real::output(230, "la1")
            .unit("m")
            .doc("LA1 set-point (sway gantry), extension 0-0.2 m, nominal 0.1 m; held at 0.1 m at full scale")
            .get(|m| m.state.la[0].pos),
        Real::output(231, "la2").unit("m").doc("LA2 set-point (surge gantry)").get(|m| m.state.la[1].pos),
        Real::output(232, "la3").unit("m").doc("LA3 set-point (leg at 90 deg)").get(|m| m.state.la[2].pos),
        Real::output(233, "la4").unit("m").doc("LA4 set-point (leg at 210 deg)").get(|m| m.state.la[3].pos),
        Real::output(234, "la5").unit("m").doc("LA5 set-point (leg at 330 deg)").get(|m| m.state.la[4].pos),
        Boolean::output(240, "la_limit")
            .doc("A set-point is outside 0-0.2 m or moves faster than 20 mm/s; false at full scale (not driven)")
            .get(|m| m.state.la_limit),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(Platform);

#[cfg(test)]
mod tests;

//! The full-scale crane's control software, one sample at a time: the arm's joint loops on the
//! valve spools, the world-frame anti-sway law and heave compensation by the winch or the arm.
//!
//! What it measures (what an offshore crane has): the joint encoders, the hoist length from the
//! drum encoder, the deck's motion from a motion reference unit (position, attitude, velocity and
//! angular velocity, the platform's outputs), and, for the anti-sway law, the load's position
//! and velocity in W (the truth here; a load IMU and an estimator on a real crane). The tip's
//! position and velocity in W follow from these by the crane's kinematics
//! ([`ArmParams::tip_in_world`](crate::knuckle_boom::ArmParams::tip_in_world)), the arm's rates taken as the ones the controller commanded in
//! the previous sample (the joint encoders' 17 bits differentiated over 10 ms would put
//! centimetres per second of noise on the tip).
//!
//! At the first sample the controller latches its references: the joints and the tip in K, the
//! tip in W, the hoist length and the load's height estimate z_t + l (W, z down), and designs
//! the anti-sway gain at that hoist length ([`super::antisway`]). That gain holds
//! ([`GainSchedule::Fixed`], the default), or is designed again at the measured hoist length
//! whenever that has moved by more than 1 % since the last design ([`GainSchedule::Length`],
//! [`crate::control::lqr::Scheduled`]; thesis §4.3.2: a model linearised at another cable length
//! loses accuracy, so its matrices should be updated as the length changes). The references hold, or the set-point
//! profile ([`super::setpoint`], `OffshoreConfig::setpoint`) moves them by a displacement Δ(τ),
//! τ the time since the latch: the tip in W and in K by Δ_tip, the hoist length and the load's
//! height by Δ_l; each loop below then also feeds the displacement's rate forward.
//!
//! The arm (drives slew, boom, jib):
//! - [`Mode::Positioning`]: the joints hold their start angles, q̇_c = k_q ∘ (q_ref − q) (a P
//!   loop on a velocity-source actuator: first order with time constant 1/k_q); under a moving
//!   set-point q_ref is the inverse kinematics of the moved tip in K
//!   ([`crate::knuckle_boom::params::ArmParams::inverse_kinematics`]) and q̇_c gains the
//!   feedforward J_K(q_ref)⁻¹ Δ̇_tip;
//! - [`Mode::Compensated`]: the tip's horizontal velocity in W is the anti-sway law's,
//!   v_x,y = Δ̇_tip − K (e, d, w), w then the load's velocity less Δ̇_tip; vertically the tip
//!   holds its height in K (heave by the winch), or in W ([`Heave::Arm`], the thesis' tip
//!   holding, §6.2): v_z = k_h (z_ref − z_t). The velocity relative to the deck is
//!   v_K = Rᵀ (v_W − v_deck(tip)) (rigid-body kinematics, [`crate::motion`]), with the
//!   height-in-K constraint replacing the W z row when the winch takes the heave; the joint rates
//!   solve J_K q̇ = v_K (J_K the tip Jacobian in K, [`ArmParams::tip_jacobian_in_world`](crate::knuckle_boom::ArmParams::tip_jacobian_in_world) at rest,
//!   Siciliano et al. 2009, eq. 3.30) — the inverse kinematics at velocity level, closed on the
//!   measured tip through the law's error terms.
//!
//! The winch:
//! - [`Heave::Winch`] (active heave compensation, as offshore cranes do it): the rope pays out
//!   as the tip rises, l̇_c = −ż_t + k_z (z_L,ref − (z_t + l)) — the feedforward keeps the load's
//!   height z_t + l constant, the feedback removes the drift; ż_t is the deck's motion at the
//!   tip plus the commanded arm motion; a moving set-point adds Δ̇_l;
//! - otherwise the winch holds its length, l̇_c = Δ̇_l + k_l (l_ref − l).
//!
//! Each rate goes to its valve through [`super::drives`]: the cylinder speed ẋ = (dL/dθ)·θ̇
//! (the mechanism's lever arm, [`crate::knuckle_boom::mechanism`]), the opening from the rated
//! speeds, the spool through the deadband. The arm's three openings are scaled together when
//! one saturates, so that the tip keeps its direction of motion. Last, every spool command is
//! rate limited (the ramp of a proportional valve's amplifier): a saturated arm reversing from
//! one full opening to the other in one sample would hit the oil columns of a tonnes-heavy arm
//! with a step of the full flow, and the load's rope with a jerk that can slacken it.

use super::antisway::{AntiSway, AntiSwayWeights};
use super::drives::{cylinder_opening, spool_for, RatedSpeeds};
use super::setpoint::{Displacement, SetpointSource};
use crate::control::controller::SlingConfig;
use crate::control::lqr::{GainSchedule, Scheduled};
use crate::estimation::notch::Notch;
use crate::hydraulic_crane::plant::{CraneParams, BOOM, JIB, SLEW, WINCH};
use crate::knuckle_boom::Joints;
use crate::math::{Matrix3, Vec3, STANDARD_GRAVITY};
use crate::motion::{PointMotion, ShipMotion};
use serde::{Deserialize, Serialize};

/// What the arm does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mode {
    /// Every spool centred: the counterbalance valves hold arm and load.
    Off,
    /// The joints hold their start angles (the tip is fixed relative to the deck).
    Positioning,
    /// World-frame compensation: the tip holds its W position horizontally and damps the swing.
    Compensated,
}

/// Who compensates the deck's heave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Heave {
    /// Nobody: the winch holds its length.
    None,
    /// The winch (active heave compensation).
    Winch,
    /// The arm holds the tip's W height (needs [`Mode::Compensated`]); the winch holds its length.
    Arm,
}

/// The controller's configuration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OffshoreConfig {
    pub mode: Mode,
    pub heave: Heave,
    /// What the references do after the latch.
    pub setpoint: SetpointSource,
    /// The crane as the controller knows it: geometry, base, valves, drives and drum.
    pub crane: CraneParams,
    /// k_q (1/s) of the joint loops (slew, boom, jib).
    pub joint_gain: Joints,
    /// k_h (1/s): the tip's height loop (in K, or in W with [`Heave::Arm`]).
    pub height_gain: f64,
    /// k_z (1/s): the load-height feedback of the heave compensation.
    pub heave_gain: f64,
    /// k_l (1/s): the winch's length loop.
    pub length_gain: f64,
    pub weights: AntiSwayWeights,
    /// Whether the anti-sway gain is the one designed at the latched hoist length or follows the
    /// measured one.
    pub schedule: GainSchedule,
    /// g (m/s²) of the anti-sway design.
    pub gravity: f64,
    /// Largest rate of change of a spool command (1/s): the valve amplifier's ramp.
    pub spool_rate: f64,
    /// The sling below the hook that the anti-sway law accounts for: with a length > 0 the
    /// load's measured offset and velocity pass a notch at the hook–load mode before the law
    /// (docs/rigging.md, "At full scale").
    pub sling: SlingConfig,
}

impl OffshoreConfig {
    /// The gains: the valve-driven actuators are velocity sources whose hydraulic modes lie at
    /// 20–50 rad/s under load (docs/full-scale.md), so the position loops stay an order below
    /// them: k_q = 1 1/s on the slew (the slowest drive, 0.18 rad/s), 2 1/s on boom and jib;
    /// k_h = 2 1/s; k_z = k_l = 1 1/s on the winch (its feedforward does the work). The spool
    /// ramp of 5 1/s moves a spool across its stroke (−1 to 1) in 0.4 s, within the 0.1–2 s an
    /// amplifier's ramp is set to, and over the deadband (±0.1) in 40 ms.
    pub const DEFAULT: OffshoreConfig = OffshoreConfig {
        mode: Mode::Positioning,
        heave: Heave::Winch,
        setpoint: SetpointSource::Fixed,
        crane: CraneParams::DEFAULT,
        joint_gain: [1.0, 2.0, 2.0],
        height_gain: 2.0,
        heave_gain: 1.0,
        length_gain: 1.0,
        weights: AntiSwayWeights::DEFAULT,
        schedule: GainSchedule::Fixed,
        gravity: STANDARD_GRAVITY,
        spool_rate: 5.0,
        // No sling; the hook's share is the full-scale rigging's 300 kg hook block above a 5 t
        // load (systems/full_scale_ahc_rigging.json), used once a length is set.
        sling: SlingConfig { hook_fraction: 300.0 / 5300.0, ..SlingConfig::NONE },
    };

    /// Checks the mode combination (heave by the arm needs compensation).
    pub fn check_modes(&self) -> Result<(), String> {
        if self.heave == Heave::Arm && self.mode != Mode::Compensated {
            return Err("heave = 2 (the arm holds the tip's height) needs mode = 2 (compensated)".into());
        }
        Ok(())
    }

    pub fn validate(&self) -> Result<(), String> {
        self.check_modes()?;
        let gains = [
            ("joint_gain.slew", self.joint_gain[0]),
            ("joint_gain.boom", self.joint_gain[1]),
            ("joint_gain.jib", self.joint_gain[2]),
            ("height_gain", self.height_gain),
            ("heave_gain", self.heave_gain),
            ("length_gain", self.length_gain),
            ("gravity", self.gravity),
            ("spool_rate", self.spool_rate),
        ];
        for (name, value) in gains {
            if !(value >= 0.0 && value.is_finite()) {
                return Err(format!("{name} must be finite and ≥ 0, got {value}"));
            }
        }
        self.weights.validate()?;
        self.sling.validate().map_err(|e| format!("sling: {e}"))?;
        self.crane.validate()
    }
}

default_is_const!(OffshoreConfig);

/// One sample's measurements.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Measured {
    /// Joint angles (rad): slew, boom, jib.
    pub joints: Joints,
    /// Hoist length (m).
    pub lp: f64,
    /// The deck's motion (acceleration terms unused).
    pub ship: ShipMotion,
    /// The load's position and velocity in W (m, m/s).
    pub load: Vec3,
    pub load_velocity: Vec3,
    /// Not a measurement but an input sampled with them: a correction of the commanded tip
    /// velocity in W (m/s), added to the anti-sway law's in [`Mode::Compensated`] (an agent's
    /// residual on top of the law; zero leaves the law's command bit for bit).
    pub residual: Vec3,
}

/// One sample's commands and what they came from.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Commands {
    /// Spool commands (−1…1), index [`SLEW`] … [`WINCH`].
    pub spools: [f64; 4],
    /// The effective openings they give (H1), saturated at ±1.
    pub openings: [f64; 4],
    /// Whether a drive asked for more than its rated speed in this sample.
    pub saturated: bool,
    /// The tip in W from the measurements (m, m/s).
    pub tip: Vec3,
    pub tip_velocity: Vec3,
    /// The commanded tip velocity in W (m/s; zero with the arm off or positioning).
    pub tip_command: Vec3,
    /// The commanded rope rate (m/s, positive paying out).
    pub rope_rate: f64,
    /// The load's height reference and its estimate z_t + l (W z, down, m).
    pub load_height_ref: f64,
    pub load_height: f64,
    /// The load's set-point in W (m): under the tip's reference, at the load's height reference
    /// and the sling's length below it.
    pub load_setpoint: Vec3,
    /// The tip's reference in W (m) and the hoist length's (m): latched, moved by the set-point
    /// profile.
    pub tip_ref: Vec3,
    pub lp_ref: f64,
}

/// What the first sample latched.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Reference {
    joints: Joints,
    /// The tip's position in K (m, relative to K's origin) and in W (m).
    tip_base: Vec3,
    tip: Vec3,
    lp: f64,
    load_height: f64,
    antisway: AntiSway,
}

/// The controller's state: its configuration, the references once latched, the arm rates it
/// last commanded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OffshoreController {
    pub config: OffshoreConfig,
    reference: Option<Reference>,
    joint_rates: Joints,
    /// The spool commands of the last sample (the ramp's start).
    spools: [f64; 4],
    /// Samples since the latch: the set-point profile's clock τ = n·dt.
    samples: u64,
    /// The hook–load notch on the load's offset (x, y) and velocity (x, y), used with a sling.
    notch: [Notch; 4],
    /// With [`GainSchedule::Length`], the anti-sway gain of the last design and the hoist length
    /// (m) it was designed at; set at the latch, then moved in the samples of [`Mode::Compensated`].
    scheduled: Option<Scheduled<AntiSway>>,
}

/// This sample's references: the latched ones, moved by the set-point profile.
#[derive(Debug, Clone, Copy)]
struct Target {
    reference: Reference,
    moved: Option<Displacement>,
}

impl Target {
    /// The tip's reference in W (m).
    fn tip(&self) -> Vec3 {
        match self.moved {
            None => self.reference.tip,
            Some(d) => self.reference.tip + d.tip,
        }
    }

    /// The tip's reference in K (m, relative to K's origin).
    fn tip_base(&self) -> Vec3 {
        self.reference.tip_base + self.moved.map_or(Vec3::zeros(), |d| d.tip)
    }

    /// The hoist length's reference (m) and the load height's (W z, down, m).
    fn lengths(&self) -> (f64, f64) {
        let r = &self.reference;
        match self.moved {
            None => (r.lp, r.load_height),
            Some(d) => (r.lp + d.lp, r.load_height + d.lp),
        }
    }
}

/// `feedback` plus the set-point's rate when the set-point moves; a fixed one adds nothing, not
/// even a zero (which would turn a −0 into a +0).
fn fed_forward<T: std::ops::Add<Output = T>>(feedback: T, rate: Option<T>) -> T {
    match rate {
        Some(rate) => feedback + rate,
        None => feedback,
    }
}

impl OffshoreController {
    /// A controller that has not sampled yet (check the configuration with
    /// [`OffshoreConfig::validate`] first).
    pub const fn new(config: OffshoreConfig) -> OffshoreController {
        let notch = Notch::new(config.sling.notch_damping);
        OffshoreController {
            config,
            reference: None,
            joint_rates: [0.0; 3],
            spools: [0.0; 4],
            samples: 0,
            notch: [notch; 4],
            scheduled: None,
        }
    }

    /// The anti-sway gain the last sample used: the latched one, or with [`GainSchedule::Length`]
    /// the last design; `None` before the latch.
    pub fn antisway(&self) -> Option<AntiSway> {
        self.scheduled.map(|s| s.gain).or(self.reference.map(|r| r.antisway))
    }

    /// One sample, `dt` (s) after the last: the commands for the measurements `m`. Err if a
    /// measurement is not finite or beyond ±1e6 or the anti-sway design fails at the latched (or, scheduled,
    /// the measured) length.
    pub fn step(&mut self, m: &Measured, dt: f64) -> Result<Commands, String> {
        self.config.check_modes()?;
        check_inputs(m)?;
        let tip = self.config.crane.arm.tip_in_world(&m.ship, &m.joints, &self.joint_rates, &[0.0; 3]);
        let reference = match self.reference {
            Some(r) => r,
            None => self.latch(m, &tip)?,
        };
        let target = Target { reference, moved: self.config.setpoint.displacement(self.samples as f64 * dt) };
        self.samples += 1;
        let load_height = tip.pos.z + m.lp;
        let (tip_ref, (lp_ref, load_height_ref)) = (target.tip(), target.lengths());
        let mut out = Commands {
            tip: tip.pos,
            tip_ref,
            lp_ref,
            tip_velocity: tip.vel,
            load_height_ref,
            load_height,
            // The load hangs the sling's length below the hook (0 without one).
            load_setpoint: Vec3::new(tip_ref.x, tip_ref.y, load_height_ref + self.config.sling.length),
            ..Commands::default()
        };
        if self.config.mode == Mode::Off {
            self.joint_rates = [0.0; 3];
            self.ramp(&mut out, [0.0; 4], dt);
            return Ok(out);
        }
        let (rates, tip_command) = match self.config.mode {
            Mode::Compensated => {
                let law = self.law(m.lp, &reference)?;
                self.compensating_rates(m, &tip, &target, &law, dt)
            }
            _ => (self.positioning_rates(m, &target)?, Vec3::zeros()),
        };
        let (openings, scale) = self.arm_openings(&m.joints, &rates);
        let saturated = scale < 1.0;
        // The rates the arm will move at: the commanded ones, scaled like their openings.
        self.joint_rates = rates.map(|r| r * scale);
        let rope_rate = self.rope_rate(m, &target, load_height);
        let crane = &self.config.crane;
        let rated = RatedSpeeds::of(crane).rope;
        let winch = (rope_rate / rated).clamp(-1.0, 1.0);
        let wanted = [openings[0], openings[1], openings[2], winch];
        out.saturated = saturated || (rope_rate / rated).abs() > 1.0;
        let valves = self.valves();
        let spools = [SLEW, BOOM, JIB, WINCH].map(|drive| spool_for(valves[drive], wanted[drive]));
        self.ramp(&mut out, spools, dt);
        out.tip_command = tip_command;
        out.rope_rate = rope_rate;
        Ok(out)
    }

    fn valves(&self) -> [&crate::hydraulics::Valve; 4] {
        let crane = &self.config.crane;
        [&crane.slew.valve, &crane.boom.valve, &crane.jib.valve, &crane.winch.valve]
    }

    /// Moves the spools toward `spools` by at most `spool_rate`·`dt` each; the openings are
    /// what the ramped spools give (H1).
    fn ramp(&mut self, out: &mut Commands, spools: [f64; 4], dt: f64) {
        let limit = self.config.spool_rate * dt;
        for drive in [SLEW, BOOM, JIB, WINCH] {
            let last = self.spools[drive];
            out.spools[drive] = last + (spools[drive] - last).clamp(-limit, limit);
            out.openings[drive] = self.valves()[drive].opening(out.spools[drive]);
        }
        self.spools = out.spools;
    }

    fn latch(&mut self, m: &Measured, tip: &PointMotion) -> Result<Reference, String> {
        let tip_base = self.config.crane.arm.tip_in_base(&m.joints, &[0.0; 3], &[0.0; 3]);
        let (antisway, _) = AntiSway::design(m.lp, self.config.gravity, &self.config.weights)
            .map_err(|e| format!("at the latched hoist length {} m: {e}", m.lp))?;
        let reference = Reference {
            joints: m.joints,
            tip_base: tip_base.pos,
            tip: tip.pos,
            lp: m.lp,
            load_height: tip.pos.z + m.lp,
            antisway,
        };
        self.reference = Some(reference);
        if self.config.schedule == GainSchedule::Length {
            self.scheduled = Some(Scheduled { length: m.lp, gain: antisway });
        }
        Ok(reference)
    }

    /// The anti-sway gain for the measured hoist length `lp` (m): the latched one
    /// ([`GainSchedule::Fixed`]), or the design at `lp` (eqs. 6.17–6.18 on the model of
    /// [`super::antisway`] at l = `lp`), redone whenever `lp` has moved by more than
    /// [`crate::control::lqr::RESCHEDULE_STEP`] since the last design ([`GainSchedule::Length`]).
    fn law(&mut self, lp: f64, reference: &Reference) -> Result<AntiSway, String> {
        let Some(scheduled) = &mut self.scheduled else {
            return Ok(reference.antisway);
        };
        let (g, weights) = (self.config.gravity, self.config.weights);
        scheduled
            .at(lp, |lp| AntiSway::design(lp, g, &weights).map(|(law, _)| law))
            .map_err(|e| format!("at the measured hoist length {lp} m: {e}"))
    }

    /// [`Mode::Positioning`]: q̇_c = k_q ∘ (q_ref − q), plus J_K(q_ref)⁻¹ Δ̇_tip under a moving
    /// set-point, q_ref then the inverse kinematics of the moved tip in K. Err if that tip is out
    /// of the arm's reach or strokes.
    fn positioning_rates(&self, m: &Measured, target: &Target) -> Result<Joints, String> {
        let k = self.config.joint_gain;
        let Some(moved) = target.moved else {
            let r = &target.reference;
            return Ok([0, 1, 2].map(|j| k[j] * (r.joints[j] - m.joints[j])));
        };
        let arm = &self.config.crane.arm;
        let joints = arm.inverse_kinematics(&target.tip_base()).map_err(|e| format!("the set-point profile: {e}"))?;
        let (jacobian, _) = arm.tip_jacobian_in_world(&ShipMotion::default(), &joints, &[0.0; 3]);
        let feedforward = solve(&jacobian, &moved.tip_rate);
        Ok([0, 1, 2].map(|j| fed_forward(k[j] * (joints[j] - m.joints[j]), Some(feedforward[j]))))
    }

    /// [`Mode::Compensated`]: the joint rates for the anti-sway law's tip velocity, and that
    /// velocity in W (the module documentation).
    fn compensating_rates(
        &mut self,
        m: &Measured,
        tip: &PointMotion,
        target: &Target,
        law: &AntiSway,
        dt: f64,
    ) -> (Joints, Vec3) {
        let tip_ref = target.tip();
        let rate = target.moved.map(|d| d.tip_rate);
        let mut offset = m.load - tip.pos;
        let error = tip.pos - tip_ref;
        // Along a moving set-point the law regulates the load's velocity relative to it (its model
        // ė = v − ṙ, ḋ = w − v, ẇ = −(g/l)·d holds for w = ẋ_L − ṙ at a constant ṙ); the
        // absolute velocity would hold the tip back by K_w ṙ / K_e.
        let mut load_velocity = match rate {
            Some(rate) => m.load_velocity - rate,
            None => m.load_velocity,
        };
        if self.config.sling.length > 0.0 {
            self.notch_hook_load_mode(&mut offset, &mut load_velocity, m.lp, dt);
        }
        let axis = |i: usize| law.velocity(error[i], offset[i], load_velocity[i]);
        let arm = &self.config.crane.arm;
        let tip_base = arm.tip_in_base(&m.joints, &[0.0; 3], &[0.0; 3]);
        // The deck's motion at the tip with the arm at rest.
        let deck = m.ship.point_in_world(&PointMotion { pos: arm.base + tip_base.pos, ..PointMotion::default() });
        let rotation = m.ship.attitude().to_rotation_matrix().into_inner();
        // An agent's residual adds to the law's velocity; a zero one adds nothing (not even a
        // zero, which would turn a −0 into a +0 and move the law's bits).
        let residual = (m.residual != Vec3::zeros()).then_some(m.residual);
        let horizontal = fed_forward(Vec3::new(axis(0), axis(1), 0.0), rate.map(|v| Vec3::new(v.x, v.y, 0.0)));
        let horizontal = fed_forward(horizontal, residual.map(|r| Vec3::new(r.x, r.y, 0.0)));
        let relative = if self.config.heave == Heave::Arm {
            let v_z = fed_forward(self.config.height_gain * (tip_ref.z - tip.pos.z), rate.map(|v| v.z));
            let v_z = fed_forward(v_z, residual.map(|r| r.z));
            rotation.transpose() * (horizontal + Vec3::new(0.0, 0.0, v_z) - deck.vel)
        } else {
            // Rows x and y of v_W = v_deck + R v_K, and v_K,z from the height loop in K (the
            // residual's z taken as K's: the deck's roll and pitch are a few degrees).
            let v_kz = fed_forward(self.config.height_gain * (target.tip_base().z - tip_base.pos.z), rate.map(|v| v.z));
            let v_kz = fed_forward(v_kz, residual.map(|r| r.z));
            let mut rows = rotation;
            rows.set_row(2, &nalgebra::RowVector3::new(0.0, 0.0, 1.0));
            let rhs = Vec3::new(horizontal.x - deck.vel.x, horizontal.y - deck.vel.y, v_kz);
            rows.lu().solve(&rhs).unwrap_or_else(Vec3::zeros)
        };
        let (jacobian, _) = arm.tip_jacobian_in_world(&ShipMotion::default(), &m.joints, &[0.0; 3]);
        let rates = solve(&jacobian, &relative);
        let command = deck.vel + rotation * (jacobian * Vec3::from(rates));
        (rates, command)
    }

    /// Takes the hook–load mode (the double pendulum's second normal mode at the measured hoist
    /// length, [`SlingConfig::hook_load_mode`]) out of the horizontal offset and velocity the
    /// law feeds back. Why: the law was designed on the single pendulum (its model has no second
    /// mode); fed that mode, the arm drives it until the hoist rope's tension reaches zero.
    fn notch_hook_load_mode(&mut self, offset: &mut Vec3, velocity: &mut Vec3, hoist: f64, dt: f64) {
        let omega = self.config.sling.hook_load_mode(hoist, self.config.gravity);
        let [ox, oy, vx, vy] = &mut self.notch;
        offset.x = ox.update(offset.x, omega, dt);
        offset.y = oy.update(offset.y, omega, dt);
        velocity.x = vx.update(velocity.x, omega, dt);
        velocity.y = vy.update(velocity.y, omega, dt);
    }

    /// The openings of slew, boom and jib for the joint rates `rates` at `joints`, scaled
    /// together by the returned factor (≤ 1) so that none exceeds 1.
    fn arm_openings(&self, joints: &Joints, rates: &Joints) -> ([f64; 3], f64) {
        let crane = &self.config.crane;
        let rated = RatedSpeeds::of(crane);
        let [(_, boom_lever), (_, jib_lever)] = crane.arm.cylinders(joints);
        let wanted = [
            rates[0] / rated.slew,
            cylinder_opening(boom_lever * rates[1], rated.cylinders[0]),
            cylinder_opening(jib_lever * rates[2], rated.cylinders[1]),
        ];
        let scale = 1.0 / max_abs(&wanted).max(1.0);
        (wanted.map(|o| o * scale), scale)
    }

    /// The winch's rope rate (m/s, positive paying out).
    fn rope_rate(&self, m: &Measured, target: &Target, load_height: f64) -> f64 {
        let (lp_ref, load_height_ref) = target.lengths();
        let feedback = match self.config.heave {
            Heave::Winch => {
                let tip = self.config.crane.arm.tip_in_world(&m.ship, &m.joints, &self.joint_rates, &[0.0; 3]);
                -tip.vel.z + self.config.heave_gain * (load_height_ref - load_height)
            }
            Heave::None | Heave::Arm => self.config.length_gain * (lp_ref - m.lp),
        };
        fed_forward(feedback, target.moved.map(|d| d.lp_rate))
    }
}

/// J q̇ = v for q̇; zero rates where J is singular (the tip on the slew axis or the arm
/// stretched), which the joint limits keep away from.
fn solve(jacobian: &Matrix3<f64>, v: &Vec3) -> Joints {
    jacobian.lu().solve(v).map(|q| [q.x, q.y, q.z]).unwrap_or([0.0; 3])
}

fn max_abs(values: &[f64; 3]) -> f64 {
    values.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// The largest residual tip velocity (m/s): far beyond what the drives can give (the arm's rated
/// cylinder speeds move the tip well under 1 m/s; the winch's rope speed is 0.524 m/s), and small
/// enough that the joint rates it asks for stay finite.
const MAX_RESIDUAL: f64 = 10.0;

/// The largest magnitude any other input may have (the test-scale controller's bound): far beyond
/// every sensor's range (radians, metres, m/s, rad/s), and small enough that the kinematics and
/// the latched references built from such values stay finite instead of passing an absurd
/// measurement straight through to the outputs (`tip.*`, `setpoint.*`). A NaN fails the
/// comparison too.
const MAX_INPUT: f64 = 1e6;

fn check_inputs(m: &Measured) -> Result<(), String> {
    let s = &m.ship;
    let values = [
        ("joint.slew", m.joints[0]),
        ("joint.boom", m.joints[1]),
        ("joint.jib", m.joints[2]),
        ("lp", m.lp),
        ("ship.roll", s.roll),
        ("ship.pitch", s.pitch),
        ("ship.yaw", s.yaw),
    ];
    for (name, value) in values {
        if !(value.abs() <= MAX_INPUT) {
            return Err(format!("input {name} is not finite or beyond ±{MAX_INPUT:e} ({value})"));
        }
    }
    let vectors =
        [("ship.", s.pos), ("ship.v", s.vel), ("ship.w", s.omega), ("load.", m.load), ("load.v", m.load_velocity)];
    for (name, v) in vectors {
        if !v.iter().all(|x| x.abs() <= MAX_INPUT) {
            return Err(format!("input {name}x|y|z is not finite or beyond ±{MAX_INPUT:e} ({v:?})"));
        }
    }
    if !m.residual.iter().all(|x| x.abs() <= MAX_RESIDUAL) {
        return Err(format!(
            "input residual.tip.vx|y|z must be finite and within ±{MAX_RESIDUAL} m/s ({:?})",
            m.residual
        ));
    }
    if !(m.lp > 0.0) {
        return Err(format!("input lp must be > 0 m, got {}", m.lp));
    }
    Ok(())
}

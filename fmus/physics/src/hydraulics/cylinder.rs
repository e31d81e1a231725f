//! The double-acting luffing cylinder and its drive (H4, H7).

use super::counterbalance::Counterbalance;
use super::drive::{friction, Circuit, DriveRates, DriveState};
use super::oil::{Oil, Supply};
use super::relief::Relief;
use super::valve::Valve;
use crate::check::check_fields;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A double-acting differential cylinder, or `count` equal ones side by side on one joint, fed
/// in parallel by one valve. Stroke x from 0 (fully retracted) to `stroke`, positive extending;
/// chamber A is the piston side, B the rod side.
///
/// `count` equal cylinders in parallel act as one cylinder of `count` times the areas, chamber
/// volumes, friction and end-stop stiffness and damping: every chamber sees the same pressure
/// and the same stroke, so flows and forces add (the OSP test crane drives each luffing joint
/// with two; its 20-sim model doubles the actuator's transformer ratio, which is the same).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Cylinder {
    /// Piston diameter (m). 0.4 m (OSP data).
    pub bore: f64,
    /// Rod diameter (m). 0.3 m (OSP data).
    pub rod: f64,
    /// Stroke s (m). 1.6 m (OSP data: 2.1–3.7 m pin to pin).
    pub stroke: f64,
    /// V_dead per chamber of one cylinder, lines included (m³). 0.01 m³ (OSP data).
    pub dead_volume: f64,
    /// Viscous friction b (N·s/m). 1e5 N·s/m: 3 kN at full extending speed (32 mm/s), a
    /// representative share of seal friction (Jelali & Kroll 2003 ch. 3).
    pub viscous: f64,
    /// Coulomb friction F_c (N). 30 kN ≈ 0.8 % of the 3.77 MN force at 30 MPa, the usual
    /// 0.5–1 % of a large cylinder's seals.
    pub coulomb: f64,
    /// v_s of tanh(v/v_s) (m/s). 10 mm/s: the regularisation slope F_c/v_s = 3e6 N·s/m stays
    /// below 0.03 per 1 ms step on a 100 t equivalent mass (and 0.17 on 1.8e4 kg).
    pub coulomb_speed: f64,
    /// End-stop stiffness (N/m) beyond 0 and s. 1e9 N/m: 3.8 mm penetration at the 3.77 MN
    /// relief force, contact frequency √(k/m) = 100 rad/s on 1e5 kg and 237 rad/s on 1.8e4 kg
    /// (ω·dt = 0.1–0.24 at 1 ms, far below RK4's limit 2.8).
    pub stop_stiffness: f64,
    /// End-stop damping (N·s/m). 5e6 N·s/m: damping ratio 0.25 on 1e5 kg.
    pub stop_damping: f64,
    /// Number of equal cylinders on the joint (≥ 1). 1 unless a crane description says otherwise.
    pub count: f64,
}

impl Cylinder {
    /// The OSP luffing cylinder (bore, rod, stroke, dead volume) with the choices above.
    pub const DEFAULT: Cylinder = Cylinder {
        bore: 0.4,
        rod: 0.3,
        stroke: 1.6,
        dead_volume: 0.01,
        viscous: 1e5,
        coulomb: 3e4,
        coulomb_speed: 0.01,
        stop_stiffness: 1e9,
        stop_damping: 5e6,
        count: 1.0,
    };

    pub fn validate(&self) -> Result<(), String> {
        check_fields!("cylinder", self;
            bore > 0, rod > 0, stroke > 0, dead_volume > 0,
            viscous >= 0, coulomb >= 0, coulomb_speed > 0,
            stop_stiffness > 0, stop_damping >= 0, count > 0,
        )?;
        if self.count.fract() != 0.0 || self.count < 1.0 {
            return Err(format!("cylinder count {} must be a whole number ≥ 1", self.count));
        }
        if !(self.rod < self.bore) {
            return Err(format!("cylinder rod ({} m) must be thinner than its bore ({} m)", self.rod, self.bore));
        }
        Ok(())
    }

    /// H4's areas (m²) of all `count` cylinders: A_A = n·π·bore²/4, A_B = A_A − n·π·rod²/4.
    pub fn areas(&self) -> (f64, f64) {
        let a = PI * self.bore * self.bore / 4.0;
        let (a_a, a_b) = (a, a - PI * self.rod * self.rod / 4.0);
        (self.count * a_a, self.count * a_b)
    }

    /// H4's volumes (m³): V_A = V_dead + A_A·x, V_B = V_dead + A_B·(s − x), each floored at 1 %
    /// of V_dead so the rates stay finite in states the end stops should never allow.
    pub fn volumes(&self, x: f64) -> (f64, f64) {
        let (a_a, a_b) = self.areas();
        let dead = self.count * self.dead_volume;
        let floor = 0.01 * dead;
        ((dead + a_a * x).max(floor), (dead + a_b * (self.stroke - x)).max(floor))
    }

    /// H7's end stops: force on the rod (N, positive extending) of a spring-damper that acts
    /// beyond x = 0 and x = s and only pushes back into the stroke.
    pub fn stop_force(&self, x: f64, v: f64) -> f64 {
        let (k, c) = (self.count * self.stop_stiffness, self.count * self.stop_damping);
        if x < 0.0 {
            (-k * x - c * v).max(0.0)
        } else if x > self.stroke {
            (-k * (x - self.stroke) - c * v).min(0.0)
        } else {
            0.0
        }
    }

    /// H7's friction force opposing v (N), of all `count` cylinders.
    pub fn friction(&self, v: f64) -> f64 {
        self.count * friction(self.viscous, self.coulomb, self.coulomb_speed, v)
    }
}

default_is_const!(Cylinder);

/// A luffing drive: directional valve, cylinder, counterbalance valve on the piston side (it
/// holds the boom up), port reliefs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CylinderDrive {
    pub valve: Valve,
    pub cylinder: Cylinder,
    pub holding: Option<Counterbalance>,
    pub relief: Relief,
}

impl CylinderDrive {
    /// The OSP boom/jib drive with the default valve, counterbalance valve and reliefs.
    pub const DEFAULT: CylinderDrive = CylinderDrive {
        valve: Valve::DEFAULT,
        cylinder: Cylinder::DEFAULT,
        holding: Some(Counterbalance::PILOT_OPERATED),
        relief: Relief::DEFAULT,
    };

    fn circuit(&self) -> Circuit<'_> {
        Circuit { valve: &self.valve, holding: self.holding.as_ref(), relief: &self.relief }
    }

    pub fn validate(&self, supply: &Supply) -> Result<(), String> {
        self.circuit().validate_drive(supply, || self.cylinder.validate())
    }

    pub fn areas(&self) -> (f64, f64) {
        self.cylinder.areas()
    }

    pub fn volumes(&self, x: f64) -> (f64, f64) {
        self.cylinder.volumes(x)
    }

    /// The rates of the drive at state `s` and spool command `spool` ∈ [−1, 1] (clamped):
    /// H4 for both chambers, H7 for the rod force, the flows of H3, H5, H6 and H12's powers.
    pub fn rates(&self, oil: &Oil, supply: &Supply, spool: f64, s: &DriveState) -> DriveRates {
        let (a_a, a_b) = self.areas();
        let (v_a, v_b) = self.volumes(s.pos);
        let mut rates = self.circuit().rates(supply, spool, s);
        let (dv_a, dv_b) = (a_a * s.vel, -a_b * s.vel);
        rates.dp_a = oil.pressure_rate(v_a, rates.q_a, dv_a);
        rates.dp_b = oil.pressure_rate(v_b, rates.q_b, dv_b);
        let friction = self.cylinder.friction(s.vel);
        // H7: F = p_A·A_A − p_B·A_B − F_friction + F_stop (the stop force already points back
        // into the stroke).
        rates.force = s.p_a * a_a - s.p_b * a_b - friction + self.cylinder.stop_force(s.pos, s.vel);
        rates.friction_loss = friction * s.vel;
        rates.compression_power = s.p_a * (rates.q_a - dv_a) + s.p_b * (rates.q_b - dv_b);
        rates
    }

    /// Static equilibrium for an initial state: the chamber pressures (p_A, p_B) that carry the
    /// rod force `force` (N, positive extending: the load's weight on a luffing cylinder) for a
    /// given p_B (H7 with v = 0: p_A = (F + p_B·A_B)/A_A).
    pub fn holding_pressures(&self, force: f64, p_b: f64) -> (f64, f64) {
        let (a_a, a_b) = self.areas();
        ((force + p_b * a_b) / a_a, p_b)
    }

    /// H10 over both chambers (J).
    pub fn stored_energy(&self, oil: &Oil, s: &DriveState) -> f64 {
        let (v_a, v_b) = self.volumes(s.pos);
        oil.stored_energy(s.p_a, v_a) + oil.stored_energy(s.p_b, v_b)
    }

    /// H13, the hydraulic natural frequency with closed chambers at stroke x and moving mass m
    /// (rad/s): ω_h = √(β·(A_A²/V_A + A_B²/V_B)/m) (Merritt 1967 ch. 5; Jelali & Kroll 2003 ch. 4).
    pub fn hydraulic_frequency(&self, oil: &Oil, x: f64, mass: f64) -> f64 {
        let (a_a, a_b) = self.areas();
        let (v_a, v_b) = self.volumes(x);
        (oil.bulk_modulus * (a_a * a_a / v_a + a_b * a_b / v_b) / mass).sqrt()
    }
}

default_is_const!(CylinderDrive);

//! The hydraulic motor with its gear: slew and winch drives (H8, H9).

use super::brake::Brake;
use super::counterbalance::Counterbalance;
use super::drive::{friction, Circuit, DriveRates, DriveState};
use super::oil::{Oil, Supply};
use super::relief::Relief;
use super::valve::Valve;
use crate::check::check_fields;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A motor drive: directional valve, fixed-displacement motor, gear, line volumes, optional
/// counterbalance valve on port A (the winch's hoisting side), port reliefs.
///
/// Signs: u > 0 feeds port A and turns the motor positive (ω_m > 0 takes D·ω_m from A to B);
/// `DriveState::pos`/`vel` are the gear output's angle and speed, ω_m = n·vel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MotorDrive {
    pub valve: Valve,
    /// D (m³/rad).
    pub displacement: f64,
    /// Gear ratio n = motor speed / output speed (output torque n·τ_m).
    pub gear: f64,
    /// V_A = V_B: oil volume of each motor line, motor chamber included (m³).
    pub line_volume: f64,
    /// Viscous friction at the motor shaft (N·m·s/rad).
    pub viscous: f64,
    /// Coulomb friction at the motor shaft (N·m).
    pub coulomb: f64,
    /// ω_s of tanh(ω_m/ω_s) at the motor shaft (rad/s).
    pub coulomb_speed: f64,
    /// Internal cross-port leakage A→B, C_m (m³/(s·Pa)).
    pub leakage: f64,
    pub holding: Option<Counterbalance>,
    pub relief: Relief,
    /// The spring-applied brake at the gear output (H18), if fitted.
    #[serde(default)]
    pub brake: Option<Brake>,
}

/// 1 L/rev in m³/rad.
const LITRE_PER_REV: f64 = 1e-3 / (2.0 * PI);

impl MotorDrive {
    /// Slew: 0.7 L/rev through 200:1 (OSP data), no counterbalance valve (the slew is not
    /// loaded by gravity; its port reliefs with make-up act as the cross-port relief: what one
    /// port relieves the other takes from the tank line). Chosen: 10 L per line (hoses from the
    /// valve block in the king to the slew motors, 20 m of 25 mm bore), friction 50 N·m
    /// Coulomb (1.5 % of the 3.3 kN·m at 30 MPa) + 0.5 N·m·s/rad, ω_s = 0.5 rad/s, leakage
    /// 2e-13 m³/(s·Pa) (0.12 L/min at 10 MPa, a volumetric efficiency above 99 % at rated flow).
    pub const SLEW_DEFAULT: MotorDrive = MotorDrive {
        valve: Valve::DEFAULT,
        displacement: 0.7 * LITRE_PER_REV,
        gear: 200.0,
        line_volume: 0.01,
        viscous: 0.5,
        coulomb: 50.0,
        coulomb_speed: 0.5,
        leakage: 2e-13,
        holding: None,
        relief: Relief::DEFAULT,
        brake: None,
    };

    /// Winch: chosen for a Palfinger PK 65002 M class offshore crane: 0.4 L/rev (offshore winch
    /// motors 0.25–0.5 L/rev) through 30:1 onto a 0.5 m drum, which gives 214 kN line pull at
    /// 28 MPa and 0.52 m/s at the valve's 240 L/min; 10 L per line; friction 30 N·m Coulomb
    /// (1.5 % of 1.9 kN·m) + 0.3 N·m·s/rad, ω_s = 0.5 rad/s, leakage as the slew motor;
    /// on the hoisting port A the third wave's pilot-operated lowering valve
    /// ([`Counterbalance::PILOT_OPERATED`]), kept so that the default crane's figures stay bit for
    /// bit: lowering under load it oscillates (docs/full-scale.md); the catalogue's other cranes
    /// have the counterbalance valve [`Counterbalance::WINCH`], which does not.
    pub const WINCH_DEFAULT: MotorDrive = MotorDrive {
        valve: Valve::DEFAULT,
        displacement: 0.4 * LITRE_PER_REV,
        gear: 30.0,
        line_volume: 0.01,
        viscous: 0.3,
        coulomb: 30.0,
        coulomb_speed: 0.5,
        leakage: 2e-13,
        holding: Some(Counterbalance::PILOT_OPERATED),
        relief: Relief::DEFAULT,
        brake: None,
    };

    fn circuit(&self) -> Circuit<'_> {
        Circuit { valve: &self.valve, holding: self.holding.as_ref(), relief: &self.relief }
    }

    pub fn validate(&self, supply: &Supply) -> Result<(), String> {
        if let Some(brake) = &self.brake {
            brake.validate()?;
        }
        self.circuit().validate_drive(supply, || {
            check_fields!("motor", self;
                displacement > 0, gear > 0, line_volume > 0,
                viscous >= 0, coulomb >= 0, coulomb_speed > 0,
                leakage >= 0,
            )
        })
    }

    /// (D, D): the displacement seen by each port (m³/rad), the motor's counterpart of
    /// [`super::CylinderDrive::areas`].
    pub fn areas(&self) -> (f64, f64) {
        (self.displacement, self.displacement)
    }

    /// (V_A, V_B) = (V_line, V_line) (m³), independent of the angle.
    pub fn volumes(&self, _angle: f64) -> (f64, f64) {
        (self.line_volume, self.line_volume)
    }

    /// The rates at state `s` (output angle and speed) and spool `spool`: H9 for the chambers,
    /// H8 for the output torque, the flows of H3, H5, H6 and H12's powers.
    pub fn rates(&self, oil: &Oil, supply: &Supply, spool: f64, s: &DriveState) -> DriveRates {
        let mut rates = self.circuit().rates(supply, spool, s);
        self.motor_rates(oil, s, &mut rates);
        rates
    }

    /// H8 and H9 for the port flows `rates.q_a`, `rates.q_b` already in `rates` (whatever feeds
    /// the lines: the valve section here, the pump of [`super::ClosedCircuit`]): fills the
    /// pressure rates, the output torque, the friction and compression powers, and adds the
    /// motor's leakage loss to `throttle_loss`.
    pub(crate) fn motor_rates(&self, oil: &Oil, s: &DriveState, rates: &mut DriveRates) {
        let motor_speed = self.gear * s.vel;
        // H9: the motor takes D·ω_m from A to B, the leakage C_m·(p_A − p_B) as well.
        let through = self.displacement * motor_speed + self.leakage * (s.p_a - s.p_b);
        rates.dp_a = oil.pressure_rate(self.line_volume, rates.q_a - through, 0.0);
        rates.dp_b = oil.pressure_rate(self.line_volume, rates.q_b + through, 0.0);
        let friction = friction(self.viscous, self.coulomb, self.coulomb_speed, motor_speed);
        // H8: τ_m = D·(p_A − p_B) − τ_friction at the motor, n·τ_m at the gear output.
        rates.force = self.gear * (self.displacement * (s.p_a - s.p_b) - friction);
        rates.friction_loss = friction * motor_speed;
        rates.throttle_loss += self.leakage * (s.p_a - s.p_b).powi(2);
        rates.compression_power = s.p_a * (rates.q_a - through) + s.p_b * (rates.q_b + through);
    }

    /// Static equilibrium: (p_A, p_B) that carry the output torque `torque` (N·m, positive in
    /// the direction of `pos`, e.g. the load's torque on the drum) for a given p_B (H8 with ω = 0):
    /// p_A = p_B + torque/(n·D).
    pub fn holding_pressures(&self, torque: f64, p_b: f64) -> (f64, f64) {
        (p_b + torque / (self.gear * self.displacement), p_b)
    }

    /// H10 over both lines (J).
    pub fn stored_energy(&self, oil: &Oil, s: &DriveState) -> f64 {
        oil.stored_energy(s.p_a, self.line_volume) + oil.stored_energy(s.p_b, self.line_volume)
    }

    /// H14, the hydraulic natural frequency of the closed motor on an inertia J at the gear
    /// output (rad/s): ω_h = n·D·√(β·(1/V_A + 1/V_B)/J) (Merritt 1967 ch. 5, the motor's
    /// hydraulic spring β·D²·(1/V_A + 1/V_B), reflected through the gear by n²).
    pub fn hydraulic_frequency(&self, oil: &Oil, inertia: f64) -> f64 {
        let stiffness = oil.bulk_modulus * self.displacement.powi(2) * 2.0 / self.line_volume;
        self.gear * (stiffness / inertia).sqrt()
    }
}

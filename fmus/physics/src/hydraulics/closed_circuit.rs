//! The closed-circuit (hydrostatic) winch drive: a variable-displacement over-centre pump
//! feeding the winch motor directly, with its swash-plate servo (H15), pump flow (H16), charge
//! circuit and cross-port reliefs (H17). No directional valve and no counterbalance valve: the
//! pump's displacement holds and lowers the load.

use super::drive::{DriveRates, DriveState};
use super::motor::MotorDrive;
use super::oil::Oil;
use super::relief::Relief;
use super::valve::effective_opening;
use crate::check::check_fields;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The pump side of a hydrostatic transmission; the motor, gear and lines are a [`MotorDrive`]
/// (its H8, H9, without its valve section).
///
/// Signs as the motor's: ε > 0 pumps from line B into line A, which turns the motor positive
/// (the winch hoisting). Pressures gauge (Pa), the charge pump's suction at tank pressure 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ClosedCircuit {
    /// D_p (m³/rad), the pump's displacement at ε = 1. 240 L/min / 1,776 rpm = 135.1 cm³/rev:
    /// the open circuit's rated valve flow at the OSP pump's 1,776 rpm drive speed, so the
    /// controller's rated rope speed is the same in both circuits; a 140 cm³/rev swash-plate
    /// pump for closed circuits (the Bosch Rexroth A4VG 140 size) with its swivel angle set to
    /// that displacement by a mechanical stroke limiter (an option of that series).
    pub displacement: f64,
    /// ω_p (rad/s): the pump's constant drive speed. 1,776 rpm, as the open circuit's pump.
    pub speed: f64,
    /// C_p (m³/(s·Pa)): the pump's volumetric loss as laminar leakage from the high to the low
    /// line (H16). 2 % of the full flow at 28 MPa: a volumetric efficiency of 98 % at full flow
    /// and the highest load pressure (our choice within the 95–98 % usual for axial-piston
    /// units).
    pub leakage: f64,
    /// τ_sw (s), the swash-plate servo's time constant (H15). 0.05 s: a servo-valve-controlled
    /// swash plate as used for heave compensation, 95 % of a step in 0.15 s, a tenth of the
    /// shortest wave period of the profiles (our choice; it is short against the 5–12 s of the
    /// sea states and slow against the oil column's 6 Hz).
    pub swash_lag: f64,
    /// d: deadband of the swash-plate control as a fraction of the command. 0.1, the open
    /// circuit valve's: the controller jumps the winch valve's deadband (its spool inverse), so
    /// the same d keeps that inverse exact; an electro-proportional pump control also has a
    /// start-of-control threshold below which the swash plate stays at zero.
    pub deadband: f64,
    /// p_c (Pa): the charge (boost) pressure, set by the charge pump's relief. 2.5 MPa, the
    /// middle of the 2–3 MPa of closed-circuit pumps' boost circuits.
    pub charge_pressure: f64,
    /// The cross-port (high-pressure) reliefs (H17), one each way between the lines, set as a
    /// pressure difference, and the charge check valves' slope (`makeup_gain`). 28 MPa: the
    /// open circuit's supply pressure, so the largest line pull is the same; slope as the
    /// port reliefs ([`Relief::DEFAULT`]: the pump's full 240 L/min at 1 MPa override).
    pub relief: Relief,
    /// The flushing valve (H17b) that drains the low line to tank, or none: the default circuit
    /// has none, so its low line floats wherever compression and leakage leave it.
    pub flushing: Option<Flushing>,
}

/// A flushing (hot-oil shuttle) valve: a shuttle spool that, once the lines differ by more than
/// `shift`, connects the lower-pressure line to tank through a relief set at `pressure`, below
/// the charge pressure, so that the charge pump's oil flows through the loop and the low line
/// sits at the charge pressure (Rexroth's A4VG closed-circuit pumps and their flushing-and-boost
/// valve blocks work this way; the flushing flow is typically 10–20 % of the pump's, our choice).
///
/// H17b: Q_f = s·min(G_f·max(0, p_low − p_f), Q_f,max), p_low = min(p_A, p_B), the shuttle's
/// opening s = clamp((|p_A − p_B| − Δp_shift)/Δp_range, 0, 1) (a linear stroke, so the flow is
/// continuous for the integrator).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Flushing {
    /// p_f (Pa): the flushing relief's setting.
    pub pressure: f64,
    /// G_f (m³/(s·Pa)): its slope above the setting.
    pub gain: f64,
    /// Q_f,max (m³/s): the flushing orifice's flow limit.
    pub max_flow: f64,
    /// Δp_shift (Pa): the line pressure difference at which the shuttle starts to open.
    pub shift: f64,
    /// Δp_range (Pa): the further difference over which it opens fully.
    pub shift_range: f64,
}

impl Flushing {
    pub fn validate(&self, charge_pressure: f64) -> Result<(), String> {
        check_fields!("flushing valve", self;
            pressure > 0, gain > 0, max_flow > 0, shift >= 0, shift_range > 0,
        )?;
        if !(self.pressure < charge_pressure) {
            return Err(format!(
                "flushing valve pressure {} Pa must lie below the charge pressure {charge_pressure} Pa, or the \
                 charge pump's oil could not flow through the loop",
                self.pressure
            ));
        }
        Ok(())
    }

    /// H17b, the flows out of lines A and B to tank (m³/s), one of them 0.
    pub fn flows(&self, p_a: f64, p_b: f64) -> (f64, f64) {
        let shuttle = (((p_a - p_b).abs() - self.shift) / self.shift_range).clamp(0.0, 1.0);
        let low = p_a.min(p_b);
        let flow = shuttle * (self.gain * (low - self.pressure).max(0.0)).min(self.max_flow);
        if p_a < p_b {
            (flow, 0.0)
        } else {
            (0.0, flow)
        }
    }
}

/// 1 rpm in rad/s.
const RPM: f64 = 2.0 * PI / 60.0;
/// The pump's drive speed (rpm), the open circuit's.
const PUMP_RPM: f64 = 1776.0;
/// The open circuit's rated valve flow, 240 L/min (m³/s).
const RATED_FLOW: f64 = 240e-3 / 60.0;

impl ClosedCircuit {
    /// The values above.
    pub const DEFAULT: ClosedCircuit = ClosedCircuit {
        displacement: RATED_FLOW / (PUMP_RPM * RPM),
        speed: PUMP_RPM * RPM,
        leakage: 0.02 * RATED_FLOW / 28e6,
        swash_lag: 0.05,
        deadband: 0.1,
        charge_pressure: 2.5e6,
        relief: Relief { pressure: 28e6, ..Relief::DEFAULT },
        flushing: None,
    };

    pub fn validate(&self) -> Result<(), String> {
        check_fields!("closed circuit", self;
            displacement > 0, speed > 0, leakage >= 0, swash_lag > 0, charge_pressure > 0,
        )?;
        if !(self.deadband >= 0.0 && self.deadband < 1.0) {
            return Err(format!("closed circuit deadband must be in [0, 1), got {}", self.deadband));
        }
        if let Some(flushing) = &self.flushing {
            flushing.validate(self.charge_pressure)?;
        }
        self.relief.validate()
    }

    /// H17b's flows out of lines A and B to tank (m³/s); 0 without a flushing valve.
    pub fn flushing_flows(&self, p_a: f64, p_b: f64) -> (f64, f64) {
        self.flushing.map_or((0.0, 0.0), |f| f.flows(p_a, p_b))
    }

    /// H15's target: the command u after H1's clamp and deadband (u_eff ∈ [−1, 1]).
    pub fn command(&self, spool: f64) -> f64 {
        effective_opening(spool, self.deadband)
    }

    /// H15, the swash-plate servo: dε/dt = (u_eff − ε)/τ_sw (1/s). ε stays in [−1, 1] because
    /// u_eff does.
    pub fn swash_rate(&self, spool: f64, swash: f64) -> f64 {
        (self.command(spool) - swash) / self.swash_lag
    }

    /// H16's ideal flow ε·D_p·ω_p from line B into line A (m³/s).
    pub fn ideal_flow(&self, swash: f64) -> f64 {
        swash * self.displacement * self.speed
    }

    /// H16, the pump's delivered flow from B into A (m³/s): ε·D_p·ω_p − C_p·(p_A − p_B).
    pub fn pump_flow(&self, swash: f64, p_a: f64, p_b: f64) -> f64 {
        self.ideal_flow(swash) - self.leakage * (p_a - p_b)
    }

    /// H17, the cross-port relief flows (m³/s): (A→B, B→A), H5's finite-capacity law of ±(p_A − p_B)
    /// (G·max(0, ±(p_A − p_B) − Δp_relief) up to the rated flow).
    pub fn cross_relief(&self, p_a: f64, p_b: f64) -> (f64, f64) {
        (self.relief.relief_flow(p_a - p_b), self.relief.relief_flow(p_b - p_a))
    }

    /// H17, the charge check valves' flows into A and B (m³/s): G_c·max(0, p_c − p).
    pub fn charge(&self, p_a: f64, p_b: f64) -> (f64, f64) {
        let p_c = self.charge_pressure;
        (self.relief.makeup_flow(p_a, p_c), self.relief.makeup_flow(p_b, p_c))
    }

    /// The rates of the pump-and-motor drive at state `s` (the motor's output angle and speed and
    /// the line pressures), swash-plate angle `swash` (ε) and command `spool`: H15–H17 for the
    /// pump side, H8/H9 of `motor` for the motor and lines, and the power terms of H12 with the
    /// pump in place of the supply.
    ///
    /// Powers: `power_in` = ε·D_p·ω_p·(p_A − p_B) + p_c·Q_charge, the hydraulic power of the
    /// pump's ideal flow plus the charge pump's; `throttle_loss` adds the pump leakage
    /// C_p·(p_A − p_B)², the reliefs |p_A − p_B|·Q_relief, the charge checks
    /// (p_c − p)·Q_charge and the flushing valve p_low·Q_f (H17b, to tank at 0) to the motor's
    /// leakage. `q_supply` is the charge flow (what the loop takes from outside), `q_tank` the
    /// flushing flow, `relief_flow` the cross-port flow, `makeup_flow` the
    /// charge flow, `opening` the swash-plate angle ε; no counterbalance valve (`cbv_opening`
    /// 0, `dpilot` 0).
    pub fn rates(&self, motor: &MotorDrive, oil: &Oil, spool: f64, swash: f64, s: &DriveState) -> DriveRates {
        let (p_a, p_b) = (s.p_a, s.p_b);
        let pumped = self.pump_flow(swash, p_a, p_b);
        let (relief_ab, relief_ba) = self.cross_relief(p_a, p_b);
        let (charge_a, charge_b) = self.charge(p_a, p_b);
        let (flush_a, flush_b) = self.flushing_flows(p_a, p_b);
        let p_c = self.charge_pressure;
        let charge_flow = charge_a + charge_b;
        let mut rates = DriveRates {
            q_a: pumped - relief_ab + relief_ba + charge_a - flush_a,
            q_b: -pumped + relief_ab - relief_ba + charge_b - flush_b,
            q_supply: charge_flow,
            q_tank: flush_a + flush_b,
            power_in: self.ideal_flow(swash) * (p_a - p_b) + p_c * charge_flow,
            relief_flow: relief_ab + relief_ba,
            makeup_flow: charge_flow,
            throttle_loss: self.leakage * (p_a - p_b).powi(2)
                + (p_a - p_b) * (relief_ab - relief_ba)
                + (p_c - p_a) * charge_a
                + (p_c - p_b) * charge_b
                + p_a * flush_a
                + p_b * flush_b,
            p_line_a: p_a,
            p_line_b: p_b,
            opening: swash,
            dswash: self.swash_rate(spool, swash),
            ..DriveRates::default()
        };
        motor.motor_rates(oil, s, &mut rates);
        rates
    }

    /// Static equilibrium at ε = 0 with the low line B at the charge pressure: (p_A, p_B) that
    /// carry the output torque `torque` (N·m, positive hoisting) through `motor`:
    /// p_A = p_c + torque/(n·D).
    pub fn holding_pressures(&self, motor: &MotorDrive, torque: f64) -> (f64, f64) {
        motor.holding_pressures(torque, self.charge_pressure)
    }
}

default_is_const!(ClosedCircuit);

/// Which drive turns the winch: [`crate::hydraulic_crane::plant::CraneParams::winch_circuit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum WinchCircuit {
    /// The open circuit: proportional valve, counterbalance valve and port reliefs on the
    /// constant-pressure supply (H1–H9).
    #[default]
    Open,
    /// The closed circuit: the over-centre pump of [`ClosedCircuit`] (H15–H17 with H8, H9).
    Closed,
}

//! What every drive shares: its state, its rates, and the two service ports with their valve,
//! counterbalance valve and reliefs (H3, H5, H6) and the power bookkeeping (H12).

use super::counterbalance::Counterbalance;
use super::oil::Supply;
use super::orifice::{port_flow, PortFlow};
use super::relief::Relief;
use super::valve::Valve;
use serde::{Deserialize, Serialize};

/// The state of a drive that the model integrates.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DriveState {
    /// Cylinder: stroke x (m, 0 = fully retracted, positive extending). Motor: output angle
    /// after the gear (rad, positive = the direction u > 0 drives).
    pub pos: f64,
    /// Its rate (m/s or rad/s at the gear output).
    pub vel: f64,
    /// Gauge pressure of chamber A (cylinder piston side; motor port A, the hoisting side of a
    /// winch) (Pa).
    pub p_a: f64,
    /// Gauge pressure of chamber B (rod side; motor port B) (Pa).
    pub p_b: f64,
    /// π, the counterbalance valve's lagged pilot pressure (H6b) (Pa); follows its target (p_B,
    /// or H6c's commanded pressure) with the lag τ_pilot. Constant in a drive without a
    /// counterbalance valve or without a lag.
    pub pilot: f64,
}

/// What a drive gives the mechanics and the outputs at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DriveRates {
    /// dp_A/dt, dp_B/dt (Pa/s), H4 (cylinder) or H9 (motor).
    pub dp_a: f64,
    pub dp_b: f64,
    /// dπ/dt, the pilot pressure's rate (Pa/s), H6b.
    pub dpilot: f64,
    /// Force on the rod, positive extending (N), or torque at the gear output, positive in the
    /// direction of `pos` (N·m); includes friction and (cylinder) the end stops.
    pub force: f64,
    /// Net flow into chamber A and B through their ports (valve, counterbalance valve, relief,
    /// make-up) (m³/s); the motor's own flows and leakage are not part of it.
    pub q_a: f64,
    pub q_b: f64,
    /// Flow from the pump and to the tank (m³/s).
    pub q_supply: f64,
    pub q_tank: f64,
    /// Hydraulic power from the supply p_S·q_supply − p_T·q_tank (W).
    pub power_in: f64,
    /// Flow out through both port reliefs, and in through both make-up checks (m³/s).
    pub relief_flow: f64,
    pub makeup_flow: f64,
    /// Power lost by throttling: every orifice's Δp·Q (valve edges and leakage, counterbalance
    /// poppet, reliefs, make-up, motor leakage) (W, ≥ 0).
    pub throttle_loss: f64,
    /// Power lost to friction (W, ≥ 0).
    pub friction_loss: f64,
    /// Power compressing the oil: Σ p·(Q_net − dV/dt) over both chambers (W), H12.
    pub compression_power: f64,
    /// Pressures of the lines between the valve and the chambers (Pa): the chamber pressure
    /// unless a closed or throttling counterbalance valve separates them.
    pub p_line_a: f64,
    pub p_line_b: f64,
    /// The valve's effective opening u_eff (H1) and the counterbalance poppet's opening (H6).
    pub opening: f64,
    pub cbv_opening: f64,
    /// dε/dt, the closed-circuit pump's swash-plate rate (1/s), H15; 0 in a valve-fed drive.
    pub dswash: f64,
}

/// The flows of both ports of a drive at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Ports {
    pub a: PortFlow,
    pub b: PortFlow,
    pub relief_a: f64,
    pub relief_b: f64,
    pub makeup_a: f64,
    pub makeup_b: f64,
    pub opening: f64,
    pub cbv_opening: f64,
    pub dpilot: f64,
}

/// The valve section of a drive: directional valve, optional counterbalance valve on port A,
/// port reliefs on both chambers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Circuit<'a> {
    pub valve: &'a Valve,
    pub holding: Option<&'a Counterbalance>,
    pub relief: &'a Relief,
}

impl Circuit<'_> {
    /// H3 (valve), H6 (counterbalance on A, piloted by p_B or the command through the lag of H6b
    /// and H6c) and H5 (reliefs, make-up) at the chamber pressures and pilot pressure of `s` and
    /// spool command `spool`.
    pub fn ports(&self, supply: &Supply, spool: f64, s: &DriveState) -> Ports {
        let (p_a, p_b) = (s.p_a, s.p_b);
        let opening = self.valve.opening(spool);
        let [supply_a, tank_a, supply_b, tank_b] = self.valve.edges(opening);
        let (p_s, p_t, dp_t) = (supply.pressure, supply.tank, self.valve.transition);
        let target = self.holding.map(|cbv| cbv.pilot_target(p_b, spool));
        let pilot = self.holding.zip(target).map(|(cbv, target)| cbv.pilot(target, s.pilot));
        let poppet = self.holding.zip(pilot).map(|(cbv, pilot)| cbv.conductance(p_a, pilot));
        Ports {
            a: port_flow(&supply_a, &tank_a, p_s, p_t, poppet, p_a, dp_t),
            b: port_flow(&supply_b, &tank_b, p_s, p_t, None, p_b, dp_t),
            relief_a: self.relief.relief_flow(p_a),
            relief_b: self.relief.relief_flow(p_b),
            makeup_a: self.relief.makeup_flow(p_a, p_t),
            makeup_b: self.relief.makeup_flow(p_b, p_t),
            opening,
            cbv_opening: self.holding.zip(pilot).map_or(0.0, |(cbv, pilot)| cbv.opening(p_a, pilot)),
            dpilot: self.holding.zip(target).map_or(0.0, |(cbv, target)| cbv.pilot_rate(target, s.pilot)),
        }
    }

    /// The rates of the port flows alone (H3, H5, H6 and H12's throttling terms, [`Ports::account`])
    /// at state `s` and spool command `spool`: what a drive completes with its chambers' rates.
    pub fn rates(&self, supply: &Supply, spool: f64, s: &DriveState) -> DriveRates {
        let ports = self.ports(supply, spool, s);
        let mut rates = DriveRates::default();
        ports.account(supply, s.p_a, s.p_b, &mut rates);
        rates
    }

    /// Checks a drive in this order: the supply, the drive's own values (`own`), this section.
    pub fn validate_drive(&self, supply: &Supply, own: impl FnOnce() -> Result<(), String>) -> Result<(), String> {
        supply.validate()?;
        own()?;
        self.validate(supply)
    }

    fn validate(&self, supply: &Supply) -> Result<(), String> {
        self.valve.validate()?;
        self.relief.validate()?;
        if let Some(cbv) = self.holding {
            cbv.validate()?;
            // A commanded pilot (H6c) does not see the ports' neutral pressure.
            let neutral = self.valve.neutral_pressure(supply.pressure, supply.tank);
            if !cbv.is_commanded() && cbv.pilot_ratio * neutral >= cbv.setting {
                return Err(format!(
                    "the centred valve's leakage holds its ports at {neutral} Pa, at or above the counterbalance \
                     valve's cracking pilot with no load, setting/pilot_ratio = {} Pa: the valve would open it \
                     (lower leak_supply/leak_tank)",
                    cbv.setting / cbv.pilot_ratio
                ));
            }
        }
        Ok(())
    }
}

impl Ports {
    /// Net port flows into A and B (m³/s).
    pub fn net(&self) -> (f64, f64) {
        (self.a.into_chamber - self.relief_a + self.makeup_a, self.b.into_chamber - self.relief_b + self.makeup_b)
    }

    /// Fills the hydraulic fields of `rates` (flows, supply power, throttling losses) for chamber
    /// pressures `p_a`, `p_b`: H12's terms Δp·Q of every orifice.
    pub fn account(&self, supply: &Supply, p_a: f64, p_b: f64, rates: &mut DriveRates) {
        let (p_s, p_t) = (supply.pressure, supply.tank);
        let port_loss = |port: &PortFlow, p_chamber: f64| {
            (p_s - port.line_pressure) * port.from_supply
                + (port.line_pressure - p_t) * port.to_tank
                + (port.line_pressure - p_chamber) * port.into_chamber
        };
        let relief_loss = (p_a - p_t) * self.relief_a + (p_b - p_t) * self.relief_b;
        let makeup_loss = (p_t - p_a) * self.makeup_a + (p_t - p_b) * self.makeup_b;
        (rates.q_a, rates.q_b) = self.net();
        rates.q_supply = self.a.from_supply + self.b.from_supply;
        rates.relief_flow = self.relief_a + self.relief_b;
        rates.makeup_flow = self.makeup_a + self.makeup_b;
        rates.q_tank = self.a.to_tank + self.b.to_tank + rates.relief_flow - rates.makeup_flow;
        rates.power_in = p_s * rates.q_supply - p_t * rates.q_tank;
        rates.throttle_loss = port_loss(&self.a, p_a) + port_loss(&self.b, p_b) + relief_loss + makeup_loss;
        rates.p_line_a = self.a.line_pressure;
        rates.p_line_b = self.b.line_pressure;
        rates.opening = self.opening;
        rates.cbv_opening = self.cbv_opening;
        rates.dpilot = self.dpilot;
    }
}

/// H7/H8's regularised friction: viscous plus Coulomb, b·v + F_c·tanh(v/v_s) (Jelali & Kroll
/// 2003 ch. 3, Coulomb and viscous friction; tanh in place of sign so the force is smooth in v).
pub fn friction(viscous: f64, coulomb: f64, coulomb_speed: f64, speed: f64) -> f64 {
    viscous * speed + coulomb * (speed / coulomb_speed).tanh()
}

//! The 4/3 critical-centre directional valve with pressure-compensated meter-in (H1–H3).

use super::orifice::Edge;
use crate::check::check_fields;
use serde::{Deserialize, Serialize};

/// A proportional 4/3 directional valve section, critical centre, with internal spool leakage.
///
/// Ports P (supply), T (tank), A and B (service). u > 0 opens P→A and B→T, u < 0 opens P→B and
/// A→T, both edges by the same opening o = |u_eff| (H1, H3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Valve {
    /// Q_rated (m³/s): flow of one fully open metering edge at `rated_drop`. 240 L/min (OSP data).
    pub rated_flow: f64,
    /// Δp_rated (Pa): the pressure drop of the rating. 1 MPa (OSP data).
    pub rated_drop: f64,
    /// d: deadband as a fraction of the spool command. 0.1 (OSP data).
    pub deadband: f64,
    /// Δp_t (Pa): laminar transition of the orifice law (H2). 0.1 MPa: a tenth of the rated drop,
    /// small against working pressures (the flow differs from √Δp by < 1 % above 0.7 MPa) and
    /// large enough that dQ/dp stays moderate for RK4 at 1 ms.
    pub transition: f64,
    /// Q_max (m³/s): cap of the meter-in edges (P→A, P→B) at full opening; the cap at opening
    /// o is o·Q_max. 240 L/min = Q_rated: a load-sensing section's compensator holds the meter-in
    /// drop at the rated 1 MPa, so its flow follows the spool, not the load (what crane operators
    /// and their control systems expect), whenever the supply can give more than that drop.
    pub max_flow: f64,
    /// C_P (m³/(s·Pa)): laminar spool leakage P→A and P→B. 1/20 of `leak_tank`, so the
    /// service lines of a centred spool float at p_S·C_P/(C_P + C_T) = 1.33 MPa, below the
    /// counterbalance valves' 2 MPa cracking pilot (a valve for counterbalance circuits vents its
    /// service ports towards tank in neutral; otherwise the leakage would open the CBVs).
    pub leak_supply: f64,
    /// C_T (m³/(s·Pa)): laminar spool leakage A→T and B→T. 1 L/min at 10 MPa, a generous figure
    /// for a worn 240 L/min section plus the neutral A/B→T bleed (why a centred spool alone
    /// does not hold a load).
    pub leak_tank: f64,
}

impl Valve {
    /// The OSP crane data (240 L/min at 1 MPa per edge, deadband 0.1) with the choices above.
    pub const DEFAULT: Valve = Valve {
        rated_flow: 240e-3 / 60.0,
        rated_drop: 1e6,
        deadband: 0.1,
        transition: 1e5,
        max_flow: 240e-3 / 60.0,
        leak_supply: 1e-3 / 60.0 / 1e7 / 20.0,
        leak_tank: 1e-3 / 60.0 / 1e7,
    };

    pub fn validate(&self) -> Result<(), String> {
        check_fields!("valve", self; rated_flow > 0, rated_drop > 0, transition > 0, max_flow > 0)?;
        if !(self.deadband >= 0.0 && self.deadband < 1.0) {
            return Err(format!("valve deadband must be in [0, 1), got {}", self.deadband));
        }
        for (name, value) in [("leak_supply", self.leak_supply), ("leak_tank", self.leak_tank)] {
            if !(value >= 0.0 && value.is_finite()) {
                return Err(format!("valve {name} must be a finite value ≥ 0 m³/(s·Pa), got {value}"));
            }
        }
        Ok(())
    }

    /// H2's coefficient K = Q_rated/√Δp_rated (m³/(s·Pa^½)).
    pub fn coefficient(&self) -> f64 {
        self.rated_flow / self.rated_drop.sqrt()
    }

    /// H1, the effective opening of a spool command u (clamped to [−1, 1]; NaN counts as 0):
    /// u_eff = sign(u)·max(0, |u| − d)/(1 − d).
    pub fn opening(&self, spool: f64) -> f64 {
        effective_opening(spool, self.deadband)
    }

    /// Pressure at which a centred spool's leakage balances in a port with no other flow (Pa):
    /// p_T + (p_S − p_T)·C_P/(C_P + C_T) (H3 with o = 0); p_T without leakage.
    pub fn neutral_pressure(&self, p_supply: f64, p_tank: f64) -> f64 {
        let total = self.leak_supply + self.leak_tank;
        if total > 0.0 {
            p_tank + (p_supply - p_tank) * self.leak_supply / total
        } else {
            p_tank
        }
    }

    /// H3, the edges of port A and port B at effective opening `o` (H1): (supply→A, A→tank,
    /// supply→B, B→tank).
    pub(crate) fn edges(&self, opening: f64) -> [Edge; 4] {
        let k = self.coefficient();
        let meter_in =
            |o: f64| Edge { turbulent: k * o, cap: o * self.max_flow, one_way: true, laminar: self.leak_supply };
        let meter_out = |o: f64| Edge { turbulent: k * o, cap: f64::INFINITY, one_way: false, laminar: self.leak_tank };
        let (a, b) = (opening.max(0.0), (-opening).max(0.0));
        [meter_in(a), meter_out(b), meter_in(b), meter_out(a)]
    }
}

/// H1 for a command u and deadband d: u clamped to [−1, 1] (NaN counts as 0),
/// u_eff = sign(u)·max(0, |u| − d)/(1 − d). The valve's spool and the closed circuit's
/// swash-plate control (H15) share it.
pub fn effective_opening(spool: f64, deadband: f64) -> f64 {
    let u = if spool.is_nan() { 0.0 } else { spool.clamp(-1.0, 1.0) };
    u.signum() * (u.abs() - deadband).max(0.0) / (1.0 - deadband)
}

default_is_const!(Valve);

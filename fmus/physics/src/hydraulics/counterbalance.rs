//! The counterbalance (load-holding) valve (H6).

use serde::{Deserialize, Serialize};

/// A pilot-operated counterbalance valve on the load-holding port (A): a free check valve for
/// flow into the chamber, and a poppet for flow out of it, opened by the pilot pressure of the
/// opposite line (p_B). Leak-free when closed. The load-pressure term p_A/ψ of a real valve's
/// area ratio ψ is left out (ψ → ∞: the valve opens on the pilot alone), so overloads are taken
/// by the port relief on the chamber side, not by the poppet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Counterbalance {
    /// Pilot pressure at which the poppet starts to open (Pa). 2 MPa (OSP data).
    pub crack_pilot: f64,
    /// Pilot pressure at which it is fully open (Pa). 20 MPa (OSP data).
    pub full_pilot: f64,
    /// Flow through the fully open poppet at `rated_drop` (m³/s). 480 L/min, twice the
    /// directional valve: it passes the piston side's outflow, A_A/A_B = 2.29 times the rod
    /// side's inflow, when lowering (a choice; the OSP data gives no size).
    pub rated_flow: f64,
    /// Pressure drop of that rating (Pa). 1 MPa.
    pub rated_drop: f64,
}

impl Counterbalance {
    pub const DEFAULT: Counterbalance =
        Counterbalance { crack_pilot: 2e6, full_pilot: 20e6, rated_flow: 480e-3 / 60.0, rated_drop: 1e6 };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.crack_pilot.is_finite() && self.full_pilot.is_finite() && self.full_pilot > self.crack_pilot) {
            return Err(format!(
                "counterbalance full_pilot ({} Pa) must be finite and above crack_pilot ({} Pa)",
                self.full_pilot, self.crack_pilot
            ));
        }
        for (name, value) in [("rated_flow", self.rated_flow), ("rated_drop", self.rated_drop)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("counterbalance {name} must be a finite value > 0, got {value}"));
            }
        }
        Ok(())
    }

    /// H6, the poppet opening from the pilot pressure:
    /// o_cb = clamp((p_pilot − p_crack)/(p_full − p_crack), 0, 1).
    pub fn opening(&self, pilot: f64) -> f64 {
        ((pilot - self.crack_pilot) / (self.full_pilot - self.crack_pilot)).clamp(0.0, 1.0)
    }

    /// The poppet's turbulent conductance K_cb·o_cb (m³/(s·Pa^½)), K_cb = Q_rated/√Δp_rated (H2).
    pub fn conductance(&self, pilot: f64) -> f64 {
        self.rated_flow / self.rated_drop.sqrt() * self.opening(pilot)
    }
}

impl Default for Counterbalance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

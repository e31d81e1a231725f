//! The counterbalance (load-holding) valve (H6) and its pilot lag (H6b).

use serde::{Deserialize, Serialize};

/// A pilot-operated counterbalance valve on the load-holding port (A): a free check valve for
/// flow into the chamber, and a poppet for flow out of it, opened by the pilot pressure of the
/// opposite line (p_B). Leak-free when closed. The load-pressure term p_A/ψ of a real valve's
/// area ratio ψ is left out (ψ → ∞: the valve opens on the pilot alone), so overloads are taken
/// by the port relief on the chamber side, not by the poppet.
///
/// The poppet does not see p_B itself but the pressure π of its pilot chamber, which fills
/// through the pilot line's damping orifice: H6b, dπ/dt = (p_B − π)/τ_pilot, a first-order lag
/// (the linearised orifice-plus-pilot-volume filter; pilot-operated spools are modelled the same
/// way, with a time constant, in the Modelica hydraulic libraries, e.g. Wolfram SystemModeler's
/// `Hydraulic.Utilities.SpoolHPilotOperated`). Without it a loaded, lowering cylinder chatters:
/// p_B opens the poppet, the load drops, p_B falls, the poppet closes — a limit cycle at the
/// hydraulic frequency that pilot orifices are fitted to damp (docs/hydraulics.md, H6b).
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
    /// τ_pilot of H6b (s). 0.05 s: the shortest lag that stops the boom's chatter in every
    /// full-scale campaign run that chattered without it (a sweep of 0.02–0.1 s in
    /// docs/hydraulics.md, H6b); the 0.01–0.1 s of pilot-operated valve models. 0 = no lag (the
    /// poppet follows p_B; the pilot state is then not integrated).
    pub pilot_lag: f64,
}

impl Counterbalance {
    pub const DEFAULT: Counterbalance = Counterbalance {
        crack_pilot: 2e6,
        full_pilot: 20e6,
        rated_flow: 480e-3 / 60.0,
        rated_drop: 1e6,
        pilot_lag: 0.05,
    };

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
        if !(self.pilot_lag >= 0.0 && self.pilot_lag.is_finite()) {
            return Err(format!("counterbalance pilot_lag must be a finite value ≥ 0 s, got {}", self.pilot_lag));
        }
        Ok(())
    }

    /// The pilot pressure the poppet sees (Pa): the lagged π of H6b, or p_B itself when
    /// `pilot_lag` is 0.
    pub fn pilot(&self, p_b: f64, lagged: f64) -> f64 {
        if self.pilot_lag > 0.0 {
            lagged
        } else {
            p_b
        }
    }

    /// H6b, dπ/dt = (p_B − π)/τ_pilot (Pa/s); 0 without a lag.
    pub fn pilot_rate(&self, p_b: f64, lagged: f64) -> f64 {
        if self.pilot_lag > 0.0 {
            (p_b - lagged) / self.pilot_lag
        } else {
            0.0
        }
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

default_is_const!(Counterbalance);

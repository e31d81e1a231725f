//! The oil and the supply: compressibility (H4), the energy stored by compression (H10, H11) and
//! the constant-pressure supply.

use crate::check::check_positive;
use serde::{Deserialize, Serialize};

/// Hydraulic oil (constant properties).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Oil {
    /// Effective bulk modulus β (Pa).
    pub bulk_modulus: f64,
    /// Density ρ (kg/m³); kept for documentation and for users of the flows (the turbulent
    /// orifices are rated by flow and pressure drop, so ρ is already inside their coefficients).
    pub density: f64,
}

impl Oil {
    /// β = 1.6 GPa, ρ = 900 kg/m³: the Open Simulation Platform's crane test data (MPL-2.0).
    pub const DEFAULT: Oil = Oil { bulk_modulus: 1.6e9, density: 900.0 };

    pub fn validate(&self) -> Result<(), String> {
        check_positive("oil bulk_modulus", self.bulk_modulus, "Pa")?;
        check_positive("oil density", self.density, "kg/m³")
    }

    /// H4, chamber continuity with compressibility (Merritt 1967 ch. 3, the continuity equation; Jelali & Kroll
    /// 2003 ch. 3): dp/dt = β/V·(Q_in − dV/dt), for a chamber of volume `volume` (m³) whose
    /// boundary moves at `volume_rate` (m³/s) and receives the net flow `inflow` (m³/s).
    pub fn pressure_rate(&self, volume: f64, inflow: f64, volume_rate: f64) -> f64 {
        self.bulk_modulus / volume * (inflow - volume_rate)
    }

    /// H10, energy stored by compressing the oil of a chamber from 0 to gauge pressure p in a
    /// volume V with a constant compressibility 1/β (Merritt 1967 ch. 2, bulk modulus): E = p²·V/(2β) (J).
    /// First order in p/β (≤ 2 % at 30 MPa and 1.6 GPa); the exact form for a closed chamber is
    /// [`Oil::closed_chamber_work`].
    pub fn stored_energy(&self, pressure: f64, volume: f64) -> f64 {
        pressure * pressure * volume / (2.0 * self.bulk_modulus)
    }

    /// H11, the work −∫p dV done on the oil of a closed chamber (no flow) while its volume goes
    /// from V0 (at pressure p0) to V (J). H4 with Q = 0 integrates exactly to
    /// p = p0 − β·ln(V/V0), so with s = (p − p0)/β (V = V0·e^(−s)):
    /// −∫p dV = V0·[p0·(1 − e^(−s)) + β·(1 − (1 + s)·e^(−s))].
    /// Exact for H4 with constant β and Q = 0, hence the form of the energy-conservation test.
    pub fn closed_chamber_work(&self, p0: f64, v0: f64, volume: f64) -> f64 {
        let beta = self.bulk_modulus;
        let s = -(volume / v0).ln();
        let decay = (-s).exp();
        v0 * (p0 * (1.0 - decay) + beta * (1.0 - (1.0 + s) * decay))
    }
}

default_is_const!(Oil);

/// The constant-pressure supply and the tank (gauge pressures, Pa).
///
/// A pressure-compensated pump (1 L/rev at 1,776 rpm = 29.6 L/s, OSP data) holds its compensator
/// setting p_S as long as the drives draw less than its flow: four valve sections of 240 L/min
/// take at most 16 L/s, so the supply is modelled as an ideal pressure source.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Supply {
    /// p_S (Pa): the pump's pressure compensator, set 2 MPa below the 30 MPa system relief
    /// (the usual margin so the relief does not open in normal work).
    pub pressure: f64,
    /// p_T (Pa): the tank (return line), atmospheric.
    pub tank: f64,
}

impl Supply {
    /// p_S = 28 MPa (30 MPa system relief of the OSP data minus a 2 MPa compensator margin), p_T = 0.
    pub const DEFAULT: Supply = Supply { pressure: 28e6, tank: 0.0 };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.pressure.is_finite() && self.tank.is_finite() && self.pressure > self.tank) {
            return Err(format!(
                "supply pressure ({} Pa) must be finite and above the tank pressure ({} Pa)",
                self.pressure, self.tank
            ));
        }
        Ok(())
    }
}

default_is_const!(Supply);

//! Port relief and anti-cavitation make-up (H5).

use serde::{Deserialize, Serialize};

/// A port relief valve to tank and an anti-cavitation check from tank, on each chamber (the
/// chamber side of a counterbalance valve, as a cylinder- or motor-mounted shock valve).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Relief {
    /// p_relief (Pa): 30 MPa, the system pressure of the OSP data.
    pub pressure: f64,
    /// G (m³/(s·Pa)): slope of the relief characteristic. 240 L/min (the valve's rated flow) at
    /// 1 MPa override, a steep but RK4-friendly characteristic: β·G/V = 640 s⁻¹ at V = 0.01 m³
    /// (0.64 per 1 ms step, below RK4's stability limit of 2.78).
    pub gain: f64,
    /// G_mu (m³/(s·Pa)): slope of the make-up check below p_T. The same as `gain`: a steeper
    /// check would pass β·G_mu·dt/V_dead > 0.64 per 1 ms step; the price is that a chamber
    /// refilled at the full 240 L/min sits 1 MPa below tank (gauge), beyond what real oil does
    /// (it cavitates at about −0.1 MPa), so the gauge pressure of a cavitating chamber is a
    /// numerical figure.
    pub makeup_gain: f64,
}

impl Relief {
    pub const DEFAULT: Relief = Relief { pressure: 30e6, gain: 240e-3 / 60.0 / 1e6, makeup_gain: 240e-3 / 60.0 / 1e6 };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.pressure > 0.0 && self.pressure.is_finite()) {
            return Err(format!("relief pressure must be a finite value > 0 Pa, got {}", self.pressure));
        }
        for (name, value) in [("gain", self.gain), ("makeup_gain", self.makeup_gain)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("relief {name} must be a finite value > 0 m³/(s·Pa), got {value}"));
            }
        }
        Ok(())
    }

    /// H5, relief flow out of a chamber at pressure p (m³/s): G·max(0, p − p_relief).
    pub fn relief_flow(&self, pressure: f64) -> f64 {
        self.gain * (pressure - self.pressure).max(0.0)
    }

    /// H5, make-up flow into a chamber at pressure p from the tank at p_T (m³/s):
    /// G_mu·max(0, p_T − p).
    pub fn makeup_flow(&self, pressure: f64, tank: f64) -> f64 {
        self.makeup_gain * (tank - pressure).max(0.0)
    }

    /// The pressure drop over the relief at flow q (Pa): q/G, the override of the documented
    /// characteristic (1 MPa at 240 L/min with the default).
    pub fn override_at(&self, flow: f64) -> f64 {
        flow / self.gain
    }
}

default_is_const!(Relief);

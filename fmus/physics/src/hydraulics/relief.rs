//! Port relief and anti-cavitation make-up (H5).

use serde::{Deserialize, Serialize};

/// A port relief valve to tank and an anti-cavitation check from tank, on each chamber (the
/// chamber side of a counterbalance valve, as a cylinder- or motor-mounted shock valve).
///
/// The relief has a finite capacity (H5): it cracks at `pressure`, opens along the override
/// slope `gain` until it passes its `rated_flow` at the full-open pressure
/// p_full = p_relief + Q_r/G, and beyond that is a fully open orifice, Q = Q_r·√(p/p_full), so
/// the pressure rises with the square of the flow (the linear opening between a set and a
/// full-open pressure, then an orifice of maximum area, of the relief valves of the Simscape
/// Fluids library, MathWorks "Pressure Relief Valve (IL)", and of the Modelica hydraulic
/// library, Wolfram SystemModeler `Hydraulic.Valves.PressureControl.PressureReliefValve` with its
/// pMin, pMax and AMax).
///
/// Stiffness at the 1 ms RK4 substep: dQ/dp is at most G (on the override slope; the orifice's
/// Q_r/(2·√(p·p_full)) is below Q_r/(2·p_full), far less), so β·(dQ/dp)·dt/V ≤ β·G·dt/V =
/// 0.64 at V = 0.01 m³, below RK4's limit of 2.78. The flow is continuous, non-decreasing and
/// Lipschitz in p (a kink at p_relief and at p_full, no jump).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Relief {
    /// p_relief (Pa): 30 MPa, the system pressure of the OSP data.
    pub pressure: f64,
    /// G (m³/(s·Pa)): slope of the relief characteristic. 240 L/min (the valve's rated flow) at
    /// 1 MPa override, a steep but RK4-friendly characteristic: β·G/V = 640 s⁻¹ at V = 0.01 m³
    /// (0.64 per 1 ms step, below RK4's stability limit of 2.78).
    pub gain: f64,
    /// Q_r (m³/s): the flow at which the relief is fully open, at p_full = p_relief + Q_r/G.
    /// 240 L/min, the valve section's rated flow (a relief sized for the pump flow it may have
    /// to pass), so the default opens fully at 1 MPa override, 3.3 % of its setting (the
    /// few-percent override of a pilot-operated relief).
    pub rated_flow: f64,
    /// G_mu (m³/(s·Pa)): slope of the make-up check below p_T. The same as `gain`: a steeper
    /// check would pass β·G_mu·dt/V_dead > 0.64 per 1 ms step; the price is that a chamber
    /// refilled at the full 240 L/min sits 1 MPa below tank (gauge), beyond what real oil does
    /// (it cavitates at about −0.1 MPa), so the gauge pressure of a cavitating chamber is a
    /// numerical figure.
    pub makeup_gain: f64,
}

impl Relief {
    pub const DEFAULT: Relief = Relief {
        pressure: 30e6,
        gain: 240e-3 / 60.0 / 1e6,
        rated_flow: 240e-3 / 60.0,
        makeup_gain: 240e-3 / 60.0 / 1e6,
    };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.pressure > 0.0 && self.pressure.is_finite()) {
            return Err(format!("relief pressure must be a finite value > 0 Pa, got {}", self.pressure));
        }
        for (name, value) in [("gain", self.gain), ("makeup_gain", self.makeup_gain)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("relief {name} must be a finite value > 0 m³/(s·Pa), got {value}"));
            }
        }
        if !(self.rated_flow > 0.0 && self.rated_flow.is_finite()) {
            return Err(format!("relief rated_flow must be a finite value > 0 m³/s, got {}", self.rated_flow));
        }
        Ok(())
    }

    /// p_full (Pa): the pressure at which the relief is fully open and passes its rated flow,
    /// p_relief + Q_r/G.
    pub fn full_open_pressure(&self) -> f64 {
        self.pressure + self.rated_flow / self.gain
    }

    /// H5, relief flow out of a chamber at pressure p (m³/s, gauge, the outlet at 0): 0 up to
    /// p_relief, G·(p − p_relief) up to p_full, Q_r·√(p/p_full) above (the fully open orifice).
    pub fn relief_flow(&self, pressure: f64) -> f64 {
        let full = self.full_open_pressure();
        if pressure <= full {
            self.gain * (pressure - self.pressure).max(0.0)
        } else {
            self.rated_flow * (pressure / full).sqrt()
        }
    }

    /// H5, make-up flow into a chamber at pressure p from the tank at p_T (m³/s):
    /// G_mu·max(0, p_T − p).
    pub fn makeup_flow(&self, pressure: f64, tank: f64) -> f64 {
        self.makeup_gain * (tank - pressure).max(0.0)
    }

    /// The override p − p_relief at which the relief passes flow q ≥ 0 (Pa), the inverse of
    /// [`Relief::relief_flow`]: q/G up to the rated flow (1 MPa at 240 L/min with the default),
    /// p_full·(q/Q_r)² − p_relief beyond it.
    pub fn override_at(&self, flow: f64) -> f64 {
        if flow <= self.rated_flow {
            flow / self.gain
        } else {
            self.full_open_pressure() * (flow / self.rated_flow).powi(2) - self.pressure
        }
    }
}

default_is_const!(Relief);

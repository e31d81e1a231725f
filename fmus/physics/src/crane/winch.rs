//! The pendulum (cable) length from the winch rotation and the jib actuator (thesis §3.4.2,
//! eqs. 3.1–3.4).
//!
//! ```text
//! l_p = l_p,0 + Δl_p,wm + Δl_p,jib                                     (3.1)
//! l_p,0 = 325 mm                                                        (3.2)
//! Δl_p,wm = (Δθ_wm / 360) · π · 41.26 mm                               (3.3)
//! Δl_p,jib = 0.010668 d_jib² + 0.5327 d_jib + 0.59982 mm, d_jib in mm  (3.4)
//! ```
//!
//! Δθ_wm is the winch angle (deg) from its home position; paying cable out (positive angle)
//! lengthens the pendulum, and so does extending the jib, which shortens the cable path inside
//! the crane. Units: lengths in m and the jib extension in m at the API, the winch angle in deg;
//! the thesis' mm are converted at the boundary.

use super::MM_PER_M;
use crate::math::Scalar;
use serde::{Deserialize, Serialize};

/// The cable-length model (mm, as in the thesis).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CableModel {
    /// l_p,0 (mm): length with the winch at home and the jib retracted (eq. 3.2).
    pub base_length: f64,
    /// Mean diameter of the wrapped cable on the winch drum (mm), eq. 3.3.
    pub drum_diameter: f64,
    /// Δl_p,jib = q2 d² + q1 d + q0 (mm, d in mm), eq. 3.4: [q2, q1, q0].
    pub jib_fit: [f64; 3],
}

default_is_const!(CableModel, THESIS);

impl CableModel {
    /// The thesis' values (the plant's): l_p,0 = 325 mm (eq. 3.2), 41.26 mm drum (eq. 3.3), the
    /// quadratic fit of Fig. 3.15 (eq. 3.4).
    pub const THESIS: CableModel =
        CableModel { base_length: 325.0, drum_diameter: 41.26, jib_fit: [0.010668, 0.5327, 0.59982] };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.drum_diameter > 0.0) {
            return Err(format!("winch drum diameter must be > 0, got {} mm", self.drum_diameter));
        }
        if !(self.base_length.is_finite() && self.jib_fit.iter().all(|q| q.is_finite())) {
            return Err("cable model constants must be finite".into());
        }
        Ok(())
    }

    /// Cable paid out per degree of winch rotation (mm/deg), eq. 3.3.
    pub const fn mm_per_degree(&self) -> f64 {
        std::f64::consts::PI * self.drum_diameter / 360.0
    }

    /// Pendulum length l_p (m) for the winch angle Δθ_wm (deg) and the jib extension (m),
    /// eqs. 3.1–3.4.
    pub fn length<D: Scalar>(&self, winch_deg: D, jib: D) -> D {
        let d = jib * MM_PER_M;
        let [q2, q1, q0] = self.jib_fit;
        let jib_term = d * d * q2 + d * q1 + q0;
        (winch_deg * self.mm_per_degree() + jib_term + self.base_length) / MM_PER_M
    }

    /// The winch angle Δθ_wm (deg) that gives the pendulum length `lp` (m) at the jib extension
    /// `jib` (m): eqs. 3.1–3.4 solved for Δθ_wm. A `const fn`, so default inputs can be derived from
    /// it; the operations are those of [`Self::length`] at Δθ_wm = 0, in the same order.
    pub const fn winch_angle(&self, lp: f64, jib: f64) -> f64 {
        let d = jib * MM_PER_M;
        let [q2, q1, q0] = self.jib_fit;
        let at_home = (d * d * q2 + d * q1 + q0 + self.base_length) / MM_PER_M;
        (lp * MM_PER_M - at_home * MM_PER_M) / self.mm_per_degree()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_length_model_follows_eqs_3_1_to_3_4() {
        let cable = CableModel::default();
        // Winch at home, jib retracted: 325 mm plus the fit's constant.
        assert!((cable.length(0.0f64, 0.0) - 0.32559982).abs() < 1e-15);
        // One winch turn pays out π·41.26 mm; the full jib stroke adds 53.9 mm.
        let turn = cable.length(360.0f64, 0.0) - cable.length(0.0, 0.0);
        assert!((turn - std::f64::consts::PI * 0.04126).abs() < 1e-15);
        let jib = cable.length(0.0f64, 0.05) - cable.length(0.0, 0.0);
        assert!((jib - (0.010668 * 2500.0 + 0.5327 * 50.0) / 1000.0).abs() < 1e-15);
        // The inverse gives back the length.
        let angle = cable.winch_angle(0.7, 0.0237);
        assert!((cable.length(angle, 0.0237) - 0.7).abs() < 1e-15);
        println!("winch angle for l_p = 0.700 m at d_jib = 23.7 mm: {angle:.3} deg");
    }
}

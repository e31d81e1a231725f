//! The world-frame anti-sway law for the full-scale crane: the LQR design of thesis §6.2
//! (eqs. 6.12–6.19, [`crate::control::lqr`]) redone at the full-scale hoist length, on a model
//! whose input is the tip's velocity — what a hydraulic arm driven by pressure-compensated valves
//! delivers (the valve sets the flow, so the actuator speed, [`super::drives`]).
//!
//! One horizontal W axis (x and y alike, decoupled for small angles), states
//! s = (e, d, w): e = x_t − x_t* the tip's error from its set-point, d = x_L − x_t the load's
//! horizontal offset from the tip, w = ẋ_L the load's velocity; input v = ẋ_t. The hanging load
//! linearised about the vertical (thesis §4.3, eqs. 4.138–4.144: θ̈ = −(g/l)θ − ẍ_t/l with the
//! offset d = l·θ, so ẍ_L = ẍ_t + l θ̈ = −(g/l)·d):
//!
//! ```text
//! ė = v,   ḋ = w − v,   ẇ = −(g/l)·d
//! ```
//!
//! (controllable: [B, AB, A²B] has rank 3 for every l > 0). The law v = −K s with
//! K = R⁻¹BᵀS (eq. 6.17) from the CARE (eq. 6.18) for Q = diag(q_e, q_d, q_w), R = r.
//! [`AntiSwayWeights::DEFAULT`] gives closed-loop damping ratios of 0.67–0.97 over 5–30 m of rope
//! (0.97 at 10 m, poles −1.30 and −0.85 ± 0.20i 1/s).

use crate::check::check_fields;
use crate::control::lqr::lqr;
use nalgebra::{Complex, DMatrix};
use serde::{Deserialize, Serialize};

/// The LQR weights of the anti-sway design (config).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AntiSwayWeights {
    /// q_e on the tip's position error (1/m²).
    pub position: f64,
    /// q_d on the load's offset from the tip (1/m²).
    pub offset: f64,
    /// q_w on the load's velocity (s²/m²).
    pub velocity: f64,
    /// r on the tip's velocity command (s²/m²).
    pub effort: f64,
}

impl AntiSwayWeights {
    /// Q = diag(1, 4, 4), R = 1: Bryson's rule for a 1 m tip error and 0.5 m, 0.5 m/s of swing
    /// against 1 m/s of tip speed, chosen for damping ratios above 0.65 from 5 to 30 m.
    pub const DEFAULT: AntiSwayWeights = AntiSwayWeights { position: 1.0, offset: 4.0, velocity: 4.0, effort: 1.0 };

    /// Checks that every weight is finite and positive.
    pub fn validate(&self) -> Result<(), String> {
        check_fields!("anti-sway weight", self; position > 0, offset > 0, velocity > 0, effort > 0)
    }
}

default_is_const!(AntiSwayWeights);

/// The anti-sway gain at one hoist length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AntiSway {
    /// K = (k_e, k_d, k_w): v = −(k_e e + k_d d + k_w w).
    pub gain: [f64; 3],
}

/// The per-axis model's A and B at hoist length `lp` (m) and gravity `g` (m/s²).
pub fn swing_model(lp: f64, g: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let a = DMatrix::from_row_slice(3, 3, &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -g / lp, 0.0]);
    let b = DMatrix::from_column_slice(3, 1, &[1.0, -1.0, 0.0]);
    (a, b)
}

impl AntiSway {
    /// The LQR gain at hoist length `lp` (m) and gravity `g` (m/s²), and the closed-loop poles.
    pub fn design(lp: f64, g: f64, weights: &AntiSwayWeights) -> Result<(AntiSway, Vec<Complex<f64>>), String> {
        if !(lp > 0.0 && lp.is_finite() && g > 0.0 && g.is_finite()) {
            return Err(format!("anti-sway design needs a finite hoist length > 0 and g > 0, got {lp} m, {g} m/s²"));
        }
        weights.validate()?;
        let (a, b) = swing_model(lp, g);
        let q = DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&[
            weights.position,
            weights.offset,
            weights.velocity,
        ]));
        let r = DMatrix::from_element(1, 1, weights.effort);
        let design = lqr(&a, &b, &q, &r)?;
        let k = &design.k;
        Ok((AntiSway { gain: [k[(0, 0)], k[(0, 1)], k[(0, 2)]] }, design.poles))
    }

    /// The tip's velocity command (m/s) along one axis for the tip error `error` (m), the
    /// load's offset from the tip `offset` (m) and the load's velocity `velocity` (m/s).
    pub fn velocity(&self, error: f64, offset: f64, velocity: f64) -> f64 {
        let [k_e, k_d, k_w] = self.gain;
        -(k_e * error + k_d * offset + k_w * velocity)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::STANDARD_GRAVITY;

    #[test]
    fn the_design_damps_the_swing_at_every_full_scale_length() {
        for lp in [5.0, 10.0, 20.0, 30.0] {
            let (law, poles) = AntiSway::design(lp, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).unwrap();
            // The closed loop's poles are those of A − B K with this gain (an independent check
            // of the returned gain against the model).
            let (a, b) = swing_model(lp, STANDARD_GRAVITY);
            let k = DMatrix::from_row_slice(1, 3, &law.gain);
            let closed = (a - b * k).complex_eigenvalues();
            for p in closed.iter() {
                assert!(poles.iter().any(|q| (q - p).norm() < 1e-9), "{lp} m: pole {p} not in {poles:?}");
                let damping = -p.re / p.norm();
                assert!(damping > 0.65, "{lp} m: pole {p}, damping ratio {damping:.3}");
            }
        }
    }

    #[test]
    fn the_tip_moves_toward_a_displaced_load_and_back_to_its_set_point() {
        let (law, _) = AntiSway::design(10.0, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).unwrap();
        assert!(law.velocity(0.0, 1.0, 0.0) > 0.0, "load 1 m ahead: the tip follows it");
        assert!(law.velocity(1.0, 0.0, 0.0) < 0.0, "tip 1 m past its set-point: it returns");
        // Reference values of the CARE at 10 m (SciPy's solve_continuous_are, the same Q and R).
        let [k_e, k_d, k_w] = law.gain;
        let reference = [0.9999999999999991, -1.9903089633709996, 2.0098339883736775];
        for (k, r) in [k_e, k_d, k_w].iter().zip(reference) {
            assert!((k - r).abs() < 1e-9, "{:?} against {reference:?}", law.gain);
        }
    }

    #[test]
    fn bad_lengths_and_weights_are_refused() {
        assert!(AntiSway::design(0.0, STANDARD_GRAVITY, &AntiSwayWeights::DEFAULT).is_err());
        let weights = AntiSwayWeights { effort: 0.0, ..AntiSwayWeights::DEFAULT };
        assert!(AntiSway::design(10.0, STANDARD_GRAVITY, &weights).unwrap_err().contains("effort"));
    }
}

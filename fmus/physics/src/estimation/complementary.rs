//! The quaternion complementary filter of thesis §5.1.1 (adapted from Valenti et al.), used for
//! the ship (IMU1, Table 5.1) and for the load (IMU2, Table 5.2).
//!
//! Each sample k runs three steps on the orientation estimate q = ^W q_S (W←S, scalar first):
//!
//! 1. Prediction by the gyro, eqs. 5.13–5.14: q ← q ⊗ exp(Δt ω̄ / 2) with the rate averaged over
//!    the step, ω̄ = (ω_{k−1} + ω_k)/2, and exp(Δt ω/2) = cos(Δt‖ω‖/2) + (ω/‖ω‖) sin(Δt‖ω‖/2).
//! 2. Accelerometer (roll/pitch) correction, eqs. 5.16–5.22: the measured direction â rotated
//!    into W predicts gravity, ĝ_P = q â q*; the delta quaternion Δq_a with
//!    Δq_a ĝ Δq_a* = ĝ_P, ĝ = (0, 0, −1), is eq. 5.18; it is interpolated toward the identity
//!    with the adaptive gain α_a(e_a) of eqs. 5.20–5.21, e_a = |‖a‖ − g|/g (eq. 5.19: LERP with
//!    normalisation when Δq_a,0 > β, SLERP otherwise); then q' = Δq̂_a* ⊗ q (eq. 5.22).
//! 3. Magnetometer (yaw-only) correction, eqs. 5.23–5.28: η̂_P = q' m̂ q'*; Δq_m, a rotation about
//!    z only, turns η̂ = (√(η_x² + η_y²), 0, η_z) into η̂_P (eq. 5.25); it is interpolated with
//!    α_m = ᾱ_m exp(−β_m |1 − Δq_m,0|) (eq. 5.27, eq. 5.26 as 5.19), and q'' = Δq̂_m* ⊗ q'
//!    (eq. 5.28).
//!
//! With full gains (α = 1) the two corrections rotate any estimate so that it maps the measured
//! gravity onto ĝ and the measured field into the xz-plane: [`ComplementaryFilter::align`] uses
//! this to start from the first sample instead of the identity.
//!
//! Notes on the printed equations: the text after eq. 5.24 writes the magnetic delta quaternion
//! as Δq_η,0 + 0î + 0ĵ + Δq_η,0 k̂; its k̂ component is Δq_η,3 (eq. 5.25 gives both). Where the
//! predicted field is vertical (η_x = η_y = 0) eq. 5.25 would return a 90° turn; the heading is
//! undefined there and no magnetic correction is applied.

use crate::math::{Quat, Vec3, STANDARD_GRAVITY};
use nalgebra::Quaternion;
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_1_SQRT_2;

/// Tuning of one filter (thesis symbols; config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilterParams {
    /// β: LERP when the delta quaternion's scalar part exceeds it, SLERP otherwise (5.19, 5.26).
    pub beta: f64,
    /// ᾱ_a: accelerometer gain while the measured magnitude is close to g (5.21).
    pub alpha_a: f64,
    /// β_a,ll: magnitude error e_a up to which the full gain ᾱ_a applies (5.21).
    pub beta_a_ll: f64,
    /// β_a,ul: magnitude error from which the accelerometer is ignored (5.21).
    pub beta_a_ul: f64,
    /// ᾱ_m: magnetometer gain (5.27).
    pub alpha_m: f64,
    /// β_m: exponential rejection of large magnetic deltas (5.27).
    pub beta_m: f64,
    /// g (m/s²), the magnitude the accelerometer reads at rest (5.20).
    pub g: f64,
}

impl FilterParams {
    /// Table 5.1, the ship (IMU1): β = 0.9, ᾱ_a = 0.05, β_a,ll = 0.1, β_a,ul = 0.2, ᾱ_m = 1,
    /// β_m = 1.
    pub const SHIP: FilterParams = FilterParams {
        beta: 0.9,
        alpha_a: 0.05,
        beta_a_ll: 0.1,
        beta_a_ul: 0.2,
        alpha_m: 1.0,
        beta_m: 1.0,
        g: STANDARD_GRAVITY,
    };
    /// Table 5.2, the load (IMU2): β = 0.9, ᾱ_a = 0.005, β_a,ll = 0.05, β_a,ul = 0.2, ᾱ_m = 1,
    /// β_m = 1.
    pub const LOAD: FilterParams = FilterParams {
        beta: 0.9,
        alpha_a: 0.005,
        beta_a_ll: 0.05,
        beta_a_ul: 0.2,
        alpha_m: 1.0,
        beta_m: 1.0,
        g: STANDARD_GRAVITY,
    };

    pub fn validate(&self) -> Result<(), String> {
        let unit = |name: &str, v: f64| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(format!("{name} must be within 0-1, got {v}"))
            }
        };
        unit("alpha_a", self.alpha_a)?;
        unit("alpha_m", self.alpha_m)?;
        if !(self.beta.abs() <= 1.0) {
            return Err(format!("beta must be within -1 to 1, got {}", self.beta));
        }
        if !(self.beta_a_ll > 0.0 && self.beta_a_ul > self.beta_a_ll && self.beta_a_ul.is_finite()) {
            return Err(format!(
                "the accelerometer limits need 0 < beta_a_ll < beta_a_ul, got {} and {}",
                self.beta_a_ll, self.beta_a_ul
            ));
        }
        if !(self.beta_m > 0.0 && self.beta_m.is_finite()) {
            return Err(format!("beta_m must be > 0, got {}", self.beta_m));
        }
        if !(self.g > 0.0 && self.g.is_finite()) {
            return Err(format!("g must be > 0 m/s², got {}", self.g));
        }
        Ok(())
    }

    /// The adaptive accelerometer gain α_a(e_a), eq. 5.21.
    pub fn accelerometer_gain(&self, e_a: f64) -> f64 {
        if e_a <= self.beta_a_ll {
            self.alpha_a
        } else if e_a < self.beta_a_ul {
            self.alpha_a * (self.beta_a_ul - e_a) / (self.beta_a_ul - self.beta_a_ll)
        } else {
            0.0
        }
    }

    /// The magnetometer gain α_m = ᾱ_m exp(−β_m |1 − Δq_m · q_I|), eq. 5.27.
    pub fn magnetometer_gain(&self, delta: &Quaternion<f64>) -> f64 {
        self.alpha_m * (-self.beta_m * (1.0 - delta.w).abs()).exp()
    }
}

/// One gyro step, eqs. 5.13–5.14: q ⊗ exp(Δt ω/2) for the body rate ω (rad/s) held over `dt` (s).
pub fn integrate(q: &Quat, omega: &Vec3, dt: f64) -> Quat {
    let rate = omega.norm();
    let half = 0.5 * dt * rate;
    let exp = if rate > 0.0 {
        Quaternion::from_parts(half.cos(), omega * (half.sin() / rate))
    } else {
        Quaternion::identity()
    };
    Quat::new_normalize(q.quaternion() * exp)
}

/// The accelerometer's delta quaternion Δq_a for the predicted gravity direction ĝ_P (unit), eq.
/// 5.18: Δq_a (0, 0, −1) Δq_a* = ĝ_P.
pub fn gravity_delta(g_p: &Vec3) -> Quaternion<f64> {
    let (gx, gy, gz) = (g_p.x, g_p.y, g_p.z);
    if gz > 0.0 {
        let s = (2.0 * (1.0 + gz)).sqrt();
        Quaternion::new(gy / s, ((1.0 + gz) / 2.0).sqrt(), 0.0, -gx / s)
    } else {
        let s = (2.0 * (1.0 - gz)).sqrt();
        Quaternion::new(((1.0 - gz) / 2.0).sqrt(), gy / s, -gx / s, 0.0)
    }
}

/// The magnetometer's delta quaternion Δq_m for the predicted field direction η̂_P, eq. 5.25: the
/// rotation about z with Δq_m (√(η_x² + η_y²), 0, η_z) Δq_m* = η̂_P. Defined for a field with a
/// horizontal component.
pub fn magnetic_delta(eta_p: &Vec3) -> Quaternion<f64> {
    let (ex, ey) = (eta_p.x, eta_p.y);
    let gamma = ex * ex + ey * ey;
    if ex > 0.0 {
        let r = (gamma + ex * gamma.sqrt()).sqrt();
        Quaternion::new(r / (2.0 * gamma).sqrt(), 0.0, 0.0, ey / (std::f64::consts::SQRT_2 * r))
    } else if ex < 0.0 {
        let r = (gamma - ex * gamma.sqrt()).sqrt();
        Quaternion::new(ey / (std::f64::consts::SQRT_2 * r), 0.0, 0.0, r / (2.0 * gamma).sqrt())
    } else if ey >= ex {
        Quaternion::new(FRAC_1_SQRT_2, 0.0, 0.0, FRAC_1_SQRT_2)
    } else {
        Quaternion::new(FRAC_1_SQRT_2, 0.0, 0.0, -FRAC_1_SQRT_2)
    }
}

/// Interpolation of a delta quaternion toward the identity with weight `alpha` on the delta,
/// eqs. 5.19 / 5.26: LERP with normalisation when its scalar part exceeds `beta`, SLERP otherwise.
pub fn interpolate(delta: &Quaternion<f64>, alpha: f64, beta: f64) -> Quat {
    if delta.w > beta {
        return Quat::new_normalize(Quaternion::identity() * (1.0 - alpha) + delta * alpha);
    }
    // Ω = acos(Δq · q_I); the SLERP branch has Δq_0 ≤ β < 1, so Ω > 0.
    let omega = delta.w.clamp(-1.0, 1.0).acos();
    let sin = omega.sin();
    if sin < 1e-12 {
        // Δq = −1: the identity rotation.
        return Quat::identity();
    }
    let q =
        Quaternion::identity() * (((1.0 - alpha).abs() * omega).sin() / sin) + delta * ((alpha * omega).sin() / sin);
    Quat::new_normalize(q)
}

/// The accelerometer correction, eqs. 5.16–5.19 and 5.22, with the weight `alpha`: the estimate
/// `q` rotated toward the orientation in which the measured specific force `acc` points along
/// (0, 0, −1). A zero reading carries no direction and leaves `q` unchanged.
pub fn gravity_correction(q: &Quat, acc: &Vec3, alpha: f64, beta: f64) -> Quat {
    let Some(a_hat) = acc.try_normalize(0.0) else { return *q };
    let g_p = q * a_hat;
    let delta = interpolate(&gravity_delta(&g_p), alpha, beta);
    delta.inverse() * q
}

/// The magnetometer correction, eqs. 5.23–5.28, with the weight `alpha(Δq_m)`: the estimate `q`
/// turned about the world z axis toward the heading in which the measured field `mag` lies in the
/// xz-plane (points north). Unchanged when the field has no horizontal part in the estimate.
pub fn heading_correction(q: &Quat, mag: &Vec3, alpha: impl Fn(&Quaternion<f64>) -> f64, beta: f64) -> Quat {
    let Some(m_hat) = mag.try_normalize(0.0) else { return *q };
    let eta_p = q * m_hat;
    if eta_p.x.hypot(eta_p.y) < 1e-9 {
        return *q;
    }
    let delta = magnetic_delta(&eta_p);
    let corrected = interpolate(&delta, alpha(&delta), beta);
    corrected.inverse() * q
}

/// The filter's state: the orientation estimate W←S and the previous gyro reading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ComplementaryFilter {
    pub params: FilterParams,
    orientation: Quat,
    previous_gyro: Option<Vec3>,
}

impl ComplementaryFilter {
    /// A filter at the identity, q_I at t_0 (the thesis' initial condition, §5.1.1).
    pub fn new(params: FilterParams) -> Self {
        ComplementaryFilter { params, orientation: Quat::identity(), previous_gyro: None }
    }

    /// The current estimate W←S.
    pub fn orientation(&self) -> Quat {
        self.orientation
    }

    /// Starts the estimate from one accelerometer and magnetometer sample: both corrections with
    /// full weight applied to the identity (roll and pitch from gravity, then yaw from the field).
    pub fn align(&mut self, acc: &Vec3, mag: &Vec3) {
        let q = gravity_correction(&Quat::identity(), acc, 1.0, self.params.beta);
        self.orientation = heading_correction(&q, mag, |_| 1.0, self.params.beta);
    }

    /// Processes one sample taken `dt` seconds after the previous one (eqs. 5.13–5.28): gyro
    /// (rad/s), accelerometer (m/s²) and magnetometer (any scale), all in the sensor frame.
    /// The first sample has no previous rate, so it only corrects. Returns the new estimate.
    pub fn update(&mut self, gyro: &Vec3, acc: &Vec3, mag: &Vec3, dt: f64) -> Quat {
        let p = self.params;
        let mut q = self.orientation;
        if let Some(previous) = self.previous_gyro {
            q = integrate(&q, &((previous + gyro) * 0.5), dt);
        }
        self.previous_gyro = Some(*gyro);
        let e_a = (acc.norm() - p.g).abs() / p.g;
        q = gravity_correction(&q, acc, p.accelerometer_gain(e_a), p.beta);
        q = heading_correction(&q, mag, |delta| p.magnetometer_gain(delta), p.beta);
        self.orientation = q;
        q
    }
}

#[cfg(test)]
mod tests;

//! The gradient-descent MARG orientation filter of Madgwick, "An efficient orientation filter for
//! inertial and inertial/magnetic sensor arrays" (2010 report), as a second attitude estimator
//! next to the thesis' complementary filter. Each step names the report's section as well as its
//! equation numbers: the numbers could be checked only against a secondary source, which agrees
//! on eqs. 25, 26, 34, 45 and 46 and numbers the gyro rate 12 and the fusion 33
//! (`docs/estimation.md`).
//!
//! The estimate q = ^W q_S (W←S, scalar first) is the report's ^S_E q̂: both rotate a sensor-frame
//! vector v into the reference frame as q v q*, and both integrate q̇ = ½ q ⊗ (0, ω). Each
//! sample k:
//!
//! 1. Rate of change from the gyro ("orientation from angular rate"), eq. 11:
//!    q̇_ω = ½ q̂_{k−1} ⊗ (0, ω_k).
//! 2. Direction of the error from the accelerometer and magnetometer ("orientation from vector
//!    observations"), eqs. 25–34: the objective
//!    f(q) = q* d q − s stacks the gravity direction (d = (0, 0, 1) in W, the measurement ŝ = â
//!    the *negated* specific force, which in NED points down at rest) and the Earth field
//!    (d = b̂ = (b_x, 0, b_z), eq. 46, from the measured field rotated into W, ĥ = q m̂ q*,
//!    eq. 45, "magnetic distortion compensation"); its gradient ∇f = Jᵀ f (eq. 34) with the
//!    Jacobians of eqs. 26 and 30.
//! 3. Fusion ("filter fusion algorithm"), eqs. 42–44: q̇_est = q̇_ω − β ∇f/‖∇f‖, q̂_k = q̂_{k−1} + q̇_est Δt,
//!    normalised.
//!
//! Negating the specific force makes the report's gravity row apply unchanged: in NED the measured
//! specific force of a level IMU at rest is (0, 0, −g), so −â = (0, 0, 1) = d, the report's own
//! reference direction. Without a usable field (zero, or vertical in the estimate) the gravity
//! rows alone are used (the report's IMU form, eqs. 25–26); without an accelerometer reading the
//! gyro alone. The gyro bias compensation of eqs. 47–49 ("gyroscope bias drift compensation") is
//! not used (ζ = 0): the simulated IMUs'
//! gyro biases are zero by default (SPEC §8.1).

use crate::estimation::complementary::{gravity_correction, heading_correction};
use crate::math::{Quat, Vec3};
use nalgebra::{Matrix3x4, Quaternion, SVector, Vector4};
use serde::{Deserialize, Serialize};

/// Tuning of one filter (config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MadgwickParams {
    /// β (rad/s): the magnitude of the quaternion rate the accelerometer and magnetometer may
    /// correct, eq. 43.
    pub beta: f64,
}

/// √(3/4), eqs. 50–51.
const SQRT_3_4: f64 = 0.866_025_403_784_438_6;

/// The SPEC §8.1 gyro noise, 0.0035 rad/s standard deviation per axis at 100 Hz.
const SPEC_GYRO_NOISE: f64 = 0.0035;

impl MadgwickParams {
    /// β = √(3/4) ω̃_β (eq. 50), with ω̃_β, the report's "estimated mean zero gyroscope measurement
    /// error of each axis", taken as the SPEC §8.1 gyro noise (0.0035 rad/s): β = 0.00303 rad/s.
    /// The same value serves the ship and the load IMU, which have the same noise.
    pub const SPEC_NOISE: MadgwickParams = MadgwickParams { beta: SQRT_3_4 * SPEC_GYRO_NOISE };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.beta >= 0.0 && self.beta <= 10.0) {
            return Err(format!("beta must be within 0-10 rad/s, got {}", self.beta));
        }
        Ok(())
    }
}

/// The filter's state: the orientation estimate W←S.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MadgwickFilter {
    pub params: MadgwickParams,
    orientation: Quat,
}

impl MadgwickFilter {
    /// A filter at the identity.
    pub fn new(params: MadgwickParams) -> Self {
        MadgwickFilter { params, orientation: Quat::identity() }
    }

    /// The current estimate W←S.
    pub fn orientation(&self) -> Quat {
        self.orientation
    }

    /// Starts the estimate from one accelerometer and magnetometer sample with the complementary
    /// filter's two corrections at full weight (roll and pitch from gravity, then yaw from the
    /// field), so that both filters start from the same estimate.
    pub fn align(&mut self, acc: &Vec3, mag: &Vec3) {
        let q = gravity_correction(&Quat::identity(), acc, 1.0, 0.0);
        self.orientation = heading_correction(&q, mag, |_| 1.0, 0.0);
    }

    /// Processes one sample taken `dt` seconds after the previous one (eqs. 11, 25–34, 42–44):
    /// gyro (rad/s), accelerometer (m/s², specific force) and magnetometer (any scale), all in the
    /// sensor frame. Returns the new estimate.
    pub fn update(&mut self, gyro: &Vec3, acc: &Vec3, mag: &Vec3, dt: f64) -> Quat {
        let q = self.orientation.into_inner();
        // Eq. 11.
        let rate = q * Quaternion::from_imag(*gyro) * 0.5;
        let direction = error_gradient(&self.orientation, acc, mag).try_normalize(0.0).unwrap_or_default();
        let correction = Quaternion::from_vector(direction) * self.params.beta;
        // Eqs. 42–44.
        self.orientation = Quat::new_normalize(q + (rate - correction) * dt);
        self.orientation
    }
}

/// ∇f = Jᵀ f (eq. 34) for the accelerometer (the negated specific force, eqs. 25–26) and, when
/// the field has a horizontal part in the estimate, the magnetometer (eqs. 29–30, 45–46); zero
/// without an accelerometer reading. Computed in the report's component order (q0, q1, q2, q3),
/// returned in nalgebra's storage order (i, j, k, w).
fn error_gradient(q: &Quat, acc: &Vec3, mag: &Vec3) -> Vector4<f64> {
    let Some(down) = (-acc).try_normalize(0.0) else { return Vector4::zeros() };
    let q_components = scalar_first(q);
    let (f_g, j_g) = gravity_objective(q_components, &down);
    let field = mag.try_normalize(0.0).and_then(|m| {
        // Eqs. 45–46: the measured field in W, turned into the xz-plane.
        let h = q * m;
        let horizontal = h.x.hypot(h.y);
        (horizontal > 1e-9).then(|| (m, horizontal, h.z))
    });
    let mut gradient = j_g.transpose() * f_g;
    if let Some((m, bx, bz)) = field {
        let (f_b, j_b) = field_objective(q_components, &m, bx, bz);
        gradient += j_b.transpose() * f_b;
    }
    // Back to nalgebra's (i, j, k, w) order for `Quaternion::from_vector`.
    Vector4::new(gradient[1], gradient[2], gradient[3], gradient[0])
}

/// The components in the report's order, scalar first.
fn scalar_first(q: &Quat) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}

/// Eqs. 25–26 with d = (0, 0, 1) and the measured direction `a` (unit): f_g = q* d q − a and its
/// Jacobian with respect to (q0, q1, q2, q3). The report's q1…q4 are q0…q3 here.
fn gravity_objective(q: [f64; 4], a: &Vec3) -> (SVector<f64, 3>, Matrix3x4<f64>) {
    let [q0, q1, q2, q3] = q;
    let f = SVector::<f64, 3>::new(
        2.0 * (q1 * q3 - q0 * q2) - a.x,
        2.0 * (q0 * q1 + q2 * q3) - a.y,
        2.0 * (0.5 - q1 * q1 - q2 * q2) - a.z,
    );
    #[rustfmt::skip]
    let j = Matrix3x4::new(
        -2.0 * q2, 2.0 * q3, -2.0 * q0, 2.0 * q1,
        2.0 * q1, 2.0 * q0, 2.0 * q3, 2.0 * q2,
        0.0, -4.0 * q1, -4.0 * q2, 0.0,
    );
    (f, j)
}

/// Eqs. 29–30 with d = b̂ = (b_x, 0, b_z) and the measured direction `m` (unit): f_b = q* b̂ q − m
/// and its Jacobian with respect to (q0, q1, q2, q3).
fn field_objective(q: [f64; 4], m: &Vec3, bx: f64, bz: f64) -> (SVector<f64, 3>, Matrix3x4<f64>) {
    let [q0, q1, q2, q3] = q;
    let (bx2, bz2) = (2.0 * bx, 2.0 * bz);
    let f = SVector::<f64, 3>::new(
        bx2 * (0.5 - q2 * q2 - q3 * q3) + bz2 * (q1 * q3 - q0 * q2) - m.x,
        bx2 * (q1 * q2 - q0 * q3) + bz2 * (q0 * q1 + q2 * q3) - m.y,
        bx2 * (q0 * q2 + q1 * q3) + bz2 * (0.5 - q1 * q1 - q2 * q2) - m.z,
    );
    #[rustfmt::skip]
    let j = Matrix3x4::new(
        -bz2 * q2, bz2 * q3, -2.0 * bx2 * q2 - bz2 * q0, -2.0 * bx2 * q3 + bz2 * q1,
        -bx2 * q3 + bz2 * q1, bx2 * q2 + bz2 * q0, bx2 * q1 + bz2 * q3, -bx2 * q0 + bz2 * q2,
        bx2 * q2, bx2 * q3 - 2.0 * bz2 * q1, bx2 * q0 - 2.0 * bz2 * q2, bx2 * q1,
    );
    (f, j)
}

#[cfg(test)]
mod tests;

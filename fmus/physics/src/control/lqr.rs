//! The LQR design tool of thesis §6.2 (eqs. 6.12–6.25): a continuous algebraic Riccati equation
//! (CARE) solver, `lqr(A, B, Q, R)`, and the linearised tip–pendulum model it is applied to.
//!
//! With N = 0 (eq. 6.24) the gain K = R⁻¹ Bᵀ S (eq. 6.17) comes from the stabilising solution S
//! of (eq. 6.18)
//!
//! ```text
//! Aᵀ S + S A − S B R⁻¹ Bᵀ S + Q = 0,
//! ```
//!
//! and A − B K is Hurwitz (eq. 6.19). The solver:
//!
//! 1. the matrix sign function of the Hamiltonian H = [A, −G; −Q, −Aᵀ], G = B R⁻¹ Bᵀ, by the
//!    Newton iteration Z ← (c Z + (c Z)⁻¹)/2 with determinant scaling c = |det Z|^(−1/2n); the
//!    stable invariant subspace [I; S] is the null space of sign(H) + I, so S solves the
//!    overdetermined system [W12; W22 + I] S = −[W11 + I; W21] (least squares);
//! 2. Newton–Kleinman refinement from that stabilising S: K = R⁻¹ Bᵀ S, then the Lyapunov
//!    equation (A − BK)ᵀ S' + S' (A − BK) = −(Q + Kᵀ R K), solved through its Kronecker form,
//!    until S stops changing.
//!
//! Both steps need only inverses and linear solves (nalgebra has no ordered Schur form).
//!
//! The model (§4.3 linearisation, eqs. 4.138–4.144; Appendix D `PendLinearDynamics`), states
//! x = (x_t, y_t, z_t, θx, θy, l_p, ẋ_t, ẏ_t, ż_t, θ̇x, θ̇y, l̇_p) (eq. 6.14) and inputs
//! ũ = (ẍ_t, ÿ_t, z̈_t, 0, 0, l̈_p) (eq. 6.26), about the hanging equilibrium with length l_p*:
//!
//! ```text
//! θ̈x = −(g/l_p*) θx + ÿ_t / l_p*,   θ̈y = −(g/l_p*) θy − ẍ_t / l_p*,
//! ```
//!
//! the tip and the length being double integrators of their inputs.

use nalgebra::{Complex, DMatrix};
use serde::{Deserialize, Serialize};

/// Names of the model's states, in order (eq. 6.14).
pub const STATES: [&str; 12] =
    ["x_t", "y_t", "z_t", "theta_x", "theta_y", "l_p", "vx_t", "vy_t", "vz_t", "omega_x", "omega_y", "vl_p"];
/// Names of the model's inputs, in order (eq. 6.26); the two angle inputs are always zero.
pub const INPUTS: [&str; 6] = ["ax_t", "ay_t", "az_t", "-", "-", "al_p"];

/// The linearised model's A (12×12) and B (12×6) at the pendulum length `lp` (m) and gravity
/// `g` (m/s²).
pub fn pendulum_model(lp: f64, g: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let mut a = DMatrix::zeros(12, 12);
    for i in 0..6 {
        a[(i, i + 6)] = 1.0;
    }
    a[(9, 3)] = -g / lp;
    a[(10, 4)] = -g / lp;
    let mut b = DMatrix::zeros(12, 6);
    b[(6, 0)] = 1.0;
    b[(7, 1)] = 1.0;
    b[(8, 2)] = 1.0;
    b[(9, 1)] = 1.0 / lp;
    b[(10, 0)] = -1.0 / lp;
    b[(11, 5)] = 1.0;
    (a, b)
}

/// The thesis' weights of §6.2 (eqs. 6.22–6.23): every Q_ii = 10, every R_ii = 1.
pub const THESIS_Q: f64 = 10.0;
pub const THESIS_R: f64 = 1.0;

/// The y axis of [`pendulum_model`] alone: states (y_t, θx, ẏ_t, θ̇x) and input ÿ_t, rows and
/// columns 1, 3, 7, 9 of A and row 1's input of B. With Q and R diagonal (eqs. 6.22–6.23) the
/// 12-state problem splits into this axis, the x axis (its mirror image: θy enters with −1/l_p)
/// and the double integrators of z_t and l_p; the Riccati solution is block diagonal, so this
/// axis' gain is the full design's row ÿ_t restricted to its states.
pub fn swing_axis_model(lp: f64, g: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let (a, b) = pendulum_model(lp, g);
    let states = [1, 3, 7, 9];
    let a = DMatrix::from_fn(4, 4, |i, j| a[(states[i], states[j])]);
    let b = DMatrix::from_fn(4, 1, |i, _| b[(states[i], 1)]);
    (a, b)
}

/// K_θ(l_p): the LQR gain of §6.2 from the angle error e_θx to the tip acceleration ÿ_t
/// (1/s² per rad · m, the entry (ÿ_t, θx) of eq. 6.25; the x axis has −K_θ on e_θy) at the
/// pendulum length `lp` (m) and gravity `g` (m/s²), with the thesis' weights Q = 10·I, R = I.
/// Solved on the y axis alone ([`swing_axis_model`]): a 4-state CARE instead of the 12-state one,
/// the same number (`the_angle_coupling_is_the_full_designs` checks it to 1e-12).
pub fn angle_coupling(lp: f64, g: f64) -> Result<f64, String> {
    if !(lp > 0.0 && lp.is_finite() && g > 0.0 && g.is_finite()) {
        return Err(format!("the LQR design needs a finite pendulum length > 0 and g > 0, got {lp} m, {g} m/s²"));
    }
    let (a, b) = swing_axis_model(lp, g);
    let q = DMatrix::identity(4, 4) * THESIS_Q;
    let r = DMatrix::from_element(1, 1, THESIS_R);
    Ok(lqr(&a, &b, &q, &r)?.k[(0, 1)])
}

/// How a controller's anti-sway gain follows the cable length (issue 32; thesis §4.3.2, Fig. 4.16:
/// a model linearised at another length loses accuracy, so "the system matrices should be updated
/// periodically").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GainSchedule {
    /// The gain of one length, held (the thesis' controller and the default).
    Fixed,
    /// Re-designed at the measured length whenever it has moved by more than
    /// [`RESCHEDULE_STEP`] of the length of the last design ([`Scheduled`]).
    Length,
}

/// The relative change of the measured length (1 %) beyond which a scheduled gain is designed
/// again. Why 1 %: the gains' sensitivity to the length, |d ln K / d ln l|, is at most 0.20 for
/// the test scale's K_θ over 0.05–1.3 m and at most 0.39 for the full scale's K over 5–30 m, so a
/// gain lags its fresh design by at most 0.2 % and 0.4 %; a design costs 2.0·10⁵ and 1.1·10⁵
/// instructions (a 4- and a 3-state CARE; both numbers from `cargo run --release -p physics
/// --example gain_schedule_cost`), five times a whole test-scale co-simulation step and a quarter
/// of a full-scale one: every sample would multiply the test scale's cost, once per 1 % of length
/// is a fraction of a per cent of a run's (docs/tuning.md).
pub const RESCHEDULE_STEP: f64 = 0.01;

/// A gain and the length (m) it was designed at, re-designed as the length moves
/// ([`GainSchedule::Length`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Scheduled<T> {
    /// The length of the last design (m).
    pub length: f64,
    pub gain: T,
}

impl<T: Copy> Scheduled<T> {
    /// The gain for the measured length `lp` (m): the last design while `lp` is within
    /// [`RESCHEDULE_STEP`] of its length, else `design(lp)`, which becomes the last design.
    pub fn at(&mut self, lp: f64, design: impl FnOnce(f64) -> Result<T, String>) -> Result<T, String> {
        if (lp - self.length).abs() > RESCHEDULE_STEP * self.length {
            *self = Scheduled { length: lp, gain: design(lp)? };
        }
        Ok(self.gain)
    }
}

/// A linear-quadratic regulator: the gain, the Riccati solution and the closed-loop poles.
#[derive(Debug, Clone)]
pub struct Lqr {
    /// K (m×n), the state feedback ũ = −K x (or ũ = K e for the error e = x_d − x, eq. 6.21).
    pub k: DMatrix<f64>,
    /// S_R (n×n), the stabilising solution of eq. 6.18.
    pub s: DMatrix<f64>,
    /// Eigenvalues of A − B K.
    pub poles: Vec<Complex<f64>>,
}

/// `[K, S, eig] = lqr(A, B, Q, R)` with N = 0 (eqs. 6.16–6.19).
pub fn lqr(a: &DMatrix<f64>, b: &DMatrix<f64>, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr, String> {
    let s = care(a, b, q, r)?;
    let k = gain(b, r, &s)?;
    let poles = (a - b * &k).complex_eigenvalues().iter().cloned().collect();
    Ok(Lqr { k, s, poles })
}

/// The stabilising solution S of Aᵀ S + S A − S B R⁻¹ Bᵀ S + Q = 0 (eq. 6.18 with N = 0), for
/// (A, B) stabilisable, Q symmetric positive semi-definite with (Q, A) detectable, and R
/// symmetric positive definite.
pub fn care(a: &DMatrix<f64>, b: &DMatrix<f64>, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<DMatrix<f64>, String> {
    let n = a.nrows();
    let m = b.ncols();
    if a.ncols() != n || b.nrows() != n || q.shape() != (n, n) || r.shape() != (m, m) {
        return Err(format!(
            "care: inconsistent shapes A {:?}, B {:?}, Q {:?}, R {:?}",
            a.shape(),
            b.shape(),
            q.shape(),
            r.shape()
        ));
    }
    if [a, b, q, r].iter().any(|x| x.iter().any(|v| !v.is_finite())) {
        return Err("care: the matrices must be finite".into());
    }
    let r_inv = r.clone().cholesky().ok_or("care: R must be symmetric positive definite")?.inverse();
    let g = b * &r_inv * b.transpose();
    let mut h = DMatrix::zeros(2 * n, 2 * n);
    h.view_mut((0, 0), (n, n)).copy_from(a);
    h.view_mut((0, n), (n, n)).copy_from(&(-&g));
    h.view_mut((n, 0), (n, n)).copy_from(&(-q));
    h.view_mut((n, n), (n, n)).copy_from(&(-a.transpose()));
    let w = sign(&h)?;
    let identity = DMatrix::<f64>::identity(n, n);
    let mut lhs = DMatrix::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n)).copy_from(&w.view((0, n), (n, n)));
    lhs.view_mut((n, 0), (n, n)).copy_from(&(w.view((n, n), (n, n)) + &identity));
    let mut rhs = DMatrix::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n)).copy_from(&(-(w.view((0, 0), (n, n)) + &identity)));
    rhs.view_mut((n, 0), (n, n)).copy_from(&(-w.view((n, 0), (n, n))));
    let mut s = lhs.svd(true, true).solve(&rhs, 1e-14).map_err(|e| format!("care: {e}"))?;
    s = symmetric(&s);
    // Newton–Kleinman refinement.
    for _ in 0..20 {
        let k = gain(b, r, &s)?;
        let closed = a - b * &k;
        let next = symmetric(&lyapunov(&closed, &(q + k.transpose() * r * &k))?);
        let change = (&next - &s).norm();
        s = next;
        if change <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    let residual = (a.transpose() * &s + &s * a - &s * &g * &s + q).norm();
    let scale = (a.norm() * s.norm() + s.norm() * g.norm() * s.norm() + q.norm()).max(f64::MIN_POSITIVE);
    if !(residual <= 1e-10 * scale) {
        return Err(format!("care: no stabilising solution found (relative residual {:.2e})", residual / scale));
    }
    Ok(s)
}

/// K = R⁻¹ Bᵀ S (eq. 6.17 with N = 0).
fn gain(b: &DMatrix<f64>, r: &DMatrix<f64>, s: &DMatrix<f64>) -> Result<DMatrix<f64>, String> {
    r.clone().lu().solve(&(b.transpose() * s)).ok_or_else(|| "lqr: R is singular".to_string())
}

fn symmetric(s: &DMatrix<f64>) -> DMatrix<f64> {
    (s + s.transpose()) * 0.5
}

/// The matrix sign function by the scaled Newton iteration.
fn sign(h: &DMatrix<f64>) -> Result<DMatrix<f64>, String> {
    let dim = h.nrows() as f64;
    let mut z = h.clone();
    for _ in 0..100 {
        let lu = z.clone().lu();
        let log_det: f64 = lu.u().diagonal().iter().map(|d| d.abs().ln()).sum();
        let inverse = lu
            .try_inverse()
            .ok_or("care: the Hamiltonian has eigenvalues on the imaginary axis (no stabilising solution)")?;
        let c = (-log_det / dim).exp();
        let next = (&z * c + inverse / c) * 0.5;
        let change = (&next - &z).norm();
        z = next;
        if change <= 1e-13 * z.norm() {
            return Ok(z);
        }
    }
    Err("care: the sign-function iteration did not converge".into())
}

/// X with Aᵀ X + X A = −C, through (I ⊗ Aᵀ + Aᵀ ⊗ I) vec X = −vec C (column-major vec).
fn lyapunov(a: &DMatrix<f64>, c: &DMatrix<f64>) -> Result<DMatrix<f64>, String> {
    let n = a.nrows();
    let identity = DMatrix::<f64>::identity(n, n);
    let at = a.transpose();
    let system = identity.kronecker(&at) + at.kronecker(&identity);
    let rhs = -DMatrix::from_column_slice(n * n, 1, c.as_slice());
    let x = system.lu().solve(&rhs).ok_or("care: the closed loop has eigenvalues ±λ (Lyapunov equation singular)")?;
    Ok(DMatrix::from_column_slice(n, n, x.as_slice()))
}

#[cfg(test)]
mod tests;

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

//! Fixed-step integration shared by every model with continuous states.

use nalgebra::SVector;

/// Largest internal step of any model (s): FMUs integrate with RK4 substeps no longer than this.
pub const MAX_SUBSTEP: f64 = 1e-3;

/// Number of equal substeps that split `h` into pieces no longer than [`MAX_SUBSTEP`]. The small
/// tolerance keeps h = 10 ms at exactly 10 substeps despite rounding in h.
pub fn substeps(h: f64) -> usize {
    ((h / MAX_SUBSTEP) * (1.0 - 1e-12)).ceil().max(1.0) as usize
}

/// One classical fourth-order Runge–Kutta step of dx/dt = f(t, x) from `t` over `dt`.
pub fn rk4<const N: usize>(
    x: &SVector<f64, N>,
    t: f64,
    dt: f64,
    f: impl Fn(f64, &SVector<f64, N>) -> SVector<f64, N>,
) -> SVector<f64, N> {
    rk4_from(x, f(t, x), dt, |x| f(t + 0.5 * dt, x), |x| f(t + dt, x))
}

/// [`rk4`] from its first stage k1 = f(t, x), which the caller has already evaluated (with
/// quantities it also needs for checking the state), and the right-hand side at the stage times:
/// `f_mid(x) = f(t + dt/2, x)` (stages 2 and 3, so inputs of that time are prepared once) and
/// `f_end(x) = f(t + dt, x)` (stage 4).
pub fn rk4_from<const N: usize>(
    x: &SVector<f64, N>,
    k1: SVector<f64, N>,
    dt: f64,
    f_mid: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
    f_end: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
) -> SVector<f64, N> {
    let k2 = f_mid(&(x + k1 * (0.5 * dt)));
    let k3 = f_mid(&(x + k2 * (0.5 * dt)));
    let k4 = f_end(&(x + k3 * dt));
    x + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0)
}

/// One step of Butcher's explicit seven-stage Runge–Kutta method of order six (the tableau with
/// rational coefficients in J. C. Butcher, Numerical Methods for Ordinary Differential Equations)
/// for dx/dt = f(t, x), from its first stage k1 = f(t, x), which the caller has already
/// evaluated. Seven evaluations per step against RK4's four, but its error falls as dt⁶: where a
/// model is smooth within a step, one step of it replaces many RK4 substeps.
///
/// The stages sit at the fractions 0, 1/3, 2/3, 1/3, 1/2, 1/2, 1 of the step: `f_at(c, x)` is
/// the right-hand side at t + c·dt, with `c` one of [`RK6_NODES`] (so that inputs can be
/// prepared once per distinct fraction).
pub fn rk6_from<const N: usize>(
    x: &SVector<f64, N>,
    k1: SVector<f64, N>,
    dt: f64,
    f_at: impl Fn(usize, &SVector<f64, N>) -> SVector<f64, N>,
) -> SVector<f64, N> {
    // Butcher's tableau: rows a_i1..a_i(i-1), weights b.
    let k2 = f_at(1, &(x + k1 * (dt / 3.0)));
    let k3 = f_at(2, &(x + k2 * (2.0 * dt / 3.0)));
    let k4 = f_at(1, &(x + (k1 + k2 * 4.0 - k3) * (dt / 12.0)));
    let k5 = f_at(3, &(x + (-k1 + k2 * 18.0 - k3 * 3.0 - k4 * 6.0) * (dt / 16.0)));
    let k6 = f_at(3, &(x + (k2 * 9.0 - k3 * 3.0 - k4 * 6.0 + k5 * 4.0) * (dt / 8.0)));
    let k7 = f_at(4, &(x + (k1 * 9.0 - k2 * 36.0 + k3 * 63.0 + k4 * 72.0 - k6 * 64.0) * (dt / 44.0)));
    x + ((k1 + k7) * 11.0 + (k3 + k4) * 81.0 - (k5 + k6) * 32.0) * (dt / 120.0)
}

/// The distinct stage times of [`rk6_from`] as fractions of the step, indexed as `f_at` receives
/// them: 0 (k1), 1/3 (k2, k4), 2/3 (k3), 1/2 (k5, k6), 1 (k7).
pub const RK6_NODES: [f64; 5] = [0.0, 1.0 / 3.0, 2.0 / 3.0, 0.5, 1.0];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn substeps_cover_the_step_without_exceeding_the_limit() {
        assert_eq!(substeps(0.01), 10);
        assert_eq!(substeps(0.010000000000000002), 10);
        assert_eq!(substeps(0.0005), 1);
        assert_eq!(substeps(0.0015), 2);
        assert_eq!(substeps(1.0), 1000);
    }

    #[test]
    fn rk4_is_fourth_order_on_exponential_decay() {
        let exact = (-1.0f64).exp();
        let error = |n: usize| {
            let mut x = SVector::<f64, 1>::new(1.0);
            let dt = 1.0 / n as f64;
            for i in 0..n {
                x = rk4(&x, i as f64 * dt, dt, |_, x| -x);
            }
            (x[0] - exact).abs()
        };
        let ratio = error(10) / error(20);
        assert!((ratio - 16.0).abs() < 1.0, "error ratio {ratio} is not ~16");
    }

    /// Order six on a nonlinear, non-autonomous problem (every elementary differential of
    /// order ≤ 6 enters): dx/dt = −x² + cos t, integrated over 1 s and compared with a run at
    /// 64 times the steps.
    #[test]
    fn rk6_is_sixth_order_on_a_nonlinear_time_dependent_problem() {
        let f = |t: f64, x: &SVector<f64, 1>| SVector::<f64, 1>::new(-x[0] * x[0] + t.cos());
        let run = |n: usize| {
            let mut x = SVector::<f64, 1>::new(1.0);
            let dt = 1.0 / n as f64;
            for i in 0..n {
                let t = i as f64 * dt;
                x = rk6_from(&x, f(t, &x), dt, |c, x| f(t + RK6_NODES[c] * dt, x));
            }
            x[0]
        };
        let exact = run(1024);
        let ratio = (run(4) - exact).abs() / (run(8) - exact).abs();
        assert!((ratio / 64.0 - 1.0).abs() < 0.15, "error ratio {ratio} is not ~64");
    }
}

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
}

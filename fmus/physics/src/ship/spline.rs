//! Natural cubic spline interpolation with exact first and second derivatives.
//!
//! The interpolating spline of a motion file's samples (profile 5): it passes through every
//! sample. (The thesis fits a MATLAB smoothing spline to recorded, noisy actuator feedback, §3.3 and
//! Appendix A; a motion file is taken as the motion itself.)
//!
//! The spline in its second-derivative ("moment") form, as in Press et al., *Numerical Recipes*,
//! 3rd ed. 2007, §3.3 (de Boor, *A Practical Guide to Splines*, 1978, ch. IV, for the theory).
//! Through samples (t_i, y_i) with strictly increasing t, the spline is a cubic on each interval,
//! twice continuously differentiable, with zero second derivative at both ends. Its second
//! derivatives M_i solve the tridiagonal system
//! h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1} = 6 ((y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1}),
//! M_0 = M_{n−1} = 0, h_i = t_{i+1} − t_i. Outside [t_0, t_{n−1}] the end value is held with zero
//! derivatives.

use crate::motion::AxisMotion;
use serde::{Deserialize, Serialize};

/// A natural cubic spline y(t).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CubicSpline {
    t: Vec<f64>,
    y: Vec<f64>,
    /// Second derivatives at the knots.
    m: Vec<f64>,
}

impl CubicSpline {
    /// The natural spline through (t_i, y_i). Needs at least two samples, finite values and
    /// strictly increasing t.
    pub fn natural(t: Vec<f64>, y: Vec<f64>) -> Result<CubicSpline, String> {
        let n = t.len();
        if n != y.len() {
            return Err(format!("{} times but {} values", n, y.len()));
        }
        if n < 2 {
            return Err(format!("a spline needs at least 2 samples, got {n}"));
        }
        if !t.iter().chain(&y).all(|v| v.is_finite()) {
            return Err("a sample is not finite".into());
        }
        if let Some(i) = t.windows(2).position(|w| !(w[1] > w[0])) {
            return Err(format!("times must increase strictly: t[{}] = {} is followed by {}", i, t[i], t[i + 1]));
        }
        let mut m = vec![0.0; n];
        if n > 2 {
            // Thomas algorithm (Gaussian elimination without pivoting, Numerical Recipes §2.4) on the
            // interior knots 1 … n−2: the system is diagonally dominant, so it needs no pivoting.
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let k = n - 2;
            let mut diag = vec![0.0; k];
            let mut rhs = vec![0.0; k];
            for j in 0..k {
                let i = j + 1;
                diag[j] = 2.0 * (h[i - 1] + h[i]);
                rhs[j] = 6.0 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]);
            }
            for j in 1..k {
                let w = h[j] / diag[j - 1];
                diag[j] -= w * h[j];
                rhs[j] -= w * rhs[j - 1];
            }
            m[k] = rhs[k - 1] / diag[k - 1];
            for j in (0..k - 1).rev() {
                m[j + 1] = (rhs[j] - h[j + 1] * m[j + 2]) / diag[j];
            }
        }
        Ok(CubicSpline { t, y, m })
    }

    /// The time span [t_0, t_{n−1}] of the samples.
    pub fn span(&self) -> (f64, f64) {
        (self.t[0], self.t[self.t.len() - 1])
    }

    /// Value, first and second derivative at `x`: with h = t_{i+1} − t_i, a = (t_{i+1} − x)/h and
    /// b = (x − t_i)/h, y = a y_i + b y_{i+1} + ((a³ − a) M_i + (b³ − b) M_{i+1}) h²/6 and its
    /// derivatives (Numerical Recipes §3.3).
    pub fn eval(&self, x: f64) -> AxisMotion {
        let (t, y, m) = (&self.t, &self.y, &self.m);
        let last = t.len() - 1;
        if !(x > t[0]) {
            return AxisMotion { pos: y[0], vel: 0.0, acc: 0.0 };
        }
        if x >= t[last] {
            return AxisMotion { pos: y[last], vel: 0.0, acc: 0.0 };
        }
        let i = t.partition_point(|&ti| ti <= x) - 1;
        let h = t[i + 1] - t[i];
        let a = (t[i + 1] - x) / h;
        let b = (x - t[i]) / h;
        AxisMotion {
            pos: a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0,
            vel: (y[i + 1] - y[i]) / h + ((3.0 * b * b - 1.0) * m[i + 1] - (3.0 * a * a - 1.0) * m[i]) * h / 6.0,
            acc: a * m[i] + b * m[i + 1],
        }
    }
}

#[cfg(test)]
mod tests;

//! The Extended Kalman Filter of §5.1.3 for one linear coordinate ζ (surge, sway or heave), after
//! Küchler et al. \[35\]: N_m undamped oscillators whose eigenfrequencies are states (a random walk,
//! eq. 5.49), plus an offset state, observed through the measured acceleration (eq. 5.52).
//!
//! State x = [ζ_1, ζ̇_1, w_1, …, ζ_Nm, ζ̇_Nm, w_Nm, x_off] (m, m/s, rad/s per mode; m/s²). The
//! thesis names an offset x_off in the state (5.51) and y_off in the output (5.52) without
//! equations; here they are one random walk: x_off is the bias of the world-frame acceleration
//! (accelerometer bias and the gravity leak of the attitude error) and y_off = x_off. A position
//! offset would not be observable from accelerations (the slow offset v(t) of eq. 5.46 is
//! neglected, as in \[35\]), so the estimate is the oscillating part of ζ.

use super::peaks::Mode;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Noise of the filter (where the thesis gives no values; the choices are explained on
/// [`super::EstimatorParams::FULL_SCALE`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Noise {
    /// κ: the velocity of mode i receives white acceleration noise of spectral density
    /// κ² a_i² / w_i ((m/s²)²·s), a_i the mode's acceleration amplitude from the FFT: relative
    /// to its own size, a higher mode may change less (the thesis' "penalty on higher frequency
    /// components").
    pub kappa: f64,
    /// Spectral density of the eigenfrequencies' random walk ((rad/s)²/s).
    pub frequency: f64,
    /// Spectral density of the offset's random walk ((m/s²)²/s).
    pub offset: f64,
    /// Variance of the measured acceleration (m²/s⁴), the sensor's noise (§5.1.3).
    pub measurement: f64,
    /// Standard deviation of the initial offset (m/s²).
    pub initial_offset: f64,
}

impl Noise {
    pub fn validate(&self) -> Result<(), String> {
        let values = [self.kappa, self.frequency, self.offset, self.initial_offset];
        if !(values.iter().all(|v| *v >= 0.0 && v.is_finite())
            && self.measurement > 0.0
            && self.measurement.is_finite())
        {
            return Err(format!("EKF noises must be finite and ≥ 0 (measurement variance > 0), got {self:?}"));
        }
        Ok(())
    }
}

/// The filter of one coordinate: state, covariance and per-step process noise intensities.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OscillatorEkf {
    x: DVector<f64>,
    p: DMatrix<f64>,
    /// Diagonal of the process noise covariance per unit time (its units follow the state's).
    q_rate: DVector<f64>,
    measurement: f64,
    /// Limits the eigenfrequencies are kept within (rad/s): the identification band.
    band: (f64, f64),
}

/// Rows of mode i in the state.
const fn mode_rows(i: usize) -> (usize, usize, usize) {
    (3 * i, 3 * i + 1, 3 * i + 2)
}

impl OscillatorEkf {
    /// A filter started from the FFT modes `modes` of a window, at its last sample, taken `elapsed`
    /// s after its first (x_t0 from the FFT, §5.1.3): each oscillator is set to the position and
    /// velocity whose acceleration −w² ζ_i continues the mode's a_i cos(w t + φ_i). The initial
    /// position and velocity standard deviations are the mode's own amplitudes (the FFT phase is
    /// rough), the frequency's is `resolution` (rad/s), the offset's `noise.initial_offset`.
    pub fn from_modes(modes: &[Mode], elapsed: f64, resolution: f64, band: (f64, f64), noise: &Noise) -> Self {
        let n = 3 * modes.len() + 1;
        let (mut x, mut p0, mut q_rate) = (DVector::zeros(n), DVector::zeros(n), DVector::zeros(n));
        for (i, m) in modes.iter().enumerate() {
            let (r_pos, r_vel, r_w) = mode_rows(i);
            let (w, angle) = (m.omega, m.omega * elapsed + m.phase);
            // ζ_i = −a_i/w² cos(w t + φ), ζ̇_i = a_i/w sin(w t + φ) (eqs. 5.46–5.48 per mode).
            x[r_pos] = -m.amplitude / (w * w) * angle.cos();
            x[r_vel] = m.amplitude / w * angle.sin();
            x[r_w] = w;
            p0[r_pos] = (m.amplitude / (w * w)).powi(2);
            p0[r_vel] = (m.amplitude / w).powi(2);
            p0[r_w] = resolution * resolution;
            q_rate[r_vel] = (noise.kappa * m.amplitude).powi(2) / w;
            q_rate[r_w] = noise.frequency;
        }
        p0[n - 1] = noise.initial_offset.powi(2);
        q_rate[n - 1] = noise.offset;
        OscillatorEkf { x, p: DMatrix::from_diagonal(&p0), q_rate, measurement: noise.measurement, band }
    }

    fn modes(&self) -> usize {
        (self.x.len() - 1) / 3
    }

    /// Estimated position ζ = Σ ζ_i (m; eq. 5.46 without v(t)).
    pub fn position(&self) -> f64 {
        (0..self.modes()).map(|i| self.x[mode_rows(i).0]).sum()
    }

    /// Estimated rate ζ̇ = Σ ζ̇_i (m/s; eq. 5.47 without v̇(t)).
    pub fn rate(&self) -> f64 {
        (0..self.modes()).map(|i| self.x[mode_rows(i).1]).sum()
    }

    /// Estimated eigenfrequencies w_i (rad/s).
    pub fn frequencies(&self) -> Vec<f64> {
        (0..self.modes()).map(|i| self.x[mode_rows(i).2]).collect()
    }

    /// One predict/update cycle with the world-frame acceleration `acc` (m/s²) measured `dt` s
    /// after the previous one.
    pub fn step(&mut self, acc: f64, dt: f64) {
        self.predict(dt);
        self.update(acc);
    }

    /// Prediction x ← Φ(x, Δt) (eq. 5.51), P ← F P Fᵀ + Q Δt with F = ∂Φ/∂x.
    fn predict(&mut self, dt: f64) {
        let n = self.x.len();
        let mut f = DMatrix::identity(n, n);
        for i in 0..self.modes() {
            let (r_pos, r_vel, r_w) = mode_rows(i);
            let (z, v, w) = (self.x[r_pos], self.x[r_vel], self.x[r_w]);
            let (s, c) = (w * dt).sin_cos();
            // Φ_i: the matrix exponential of eq. 5.49 over Δt with w_i frozen (exact for the
            // undamped oscillator), w_i and x_off kept (random walks).
            self.x[r_pos] = c * z + s / w * v;
            self.x[r_vel] = -w * s * z + c * v;
            f[(r_pos, r_pos)] = c;
            f[(r_pos, r_vel)] = s / w;
            f[(r_pos, r_w)] = -dt * s * z + (dt * c / w - s / (w * w)) * v;
            f[(r_vel, r_pos)] = -w * s;
            f[(r_vel, r_vel)] = c;
            f[(r_vel, r_w)] = -(s + w * dt * c) * z - dt * s * v;
        }
        self.p = &f * &self.p * f.transpose() + DMatrix::from_diagonal(&(&self.q_rate * dt));
    }

    /// Measurement update with y = Σ −w_i² ζ_i + x_off (eqs. 5.50, 5.52), in Joseph form (the
    /// covariance stays symmetric and positive over hours of 100 Hz steps).
    fn update(&mut self, acc: f64) {
        let n = self.x.len();
        let mut h = DVector::zeros(n);
        let mut predicted = self.x[n - 1];
        h[n - 1] = 1.0;
        for i in 0..self.modes() {
            let (r_pos, _, r_w) = mode_rows(i);
            let (z, w) = (self.x[r_pos], self.x[r_w]);
            predicted -= w * w * z;
            h[r_pos] = -w * w;
            h[r_w] = -2.0 * w * z;
        }
        let ph = &self.p * &h;
        let innovation_variance = h.dot(&ph) + self.measurement;
        let gain = ph / innovation_variance;
        self.x += &gain * (acc - predicted);
        let a = DMatrix::identity(n, n) - &gain * h.transpose();
        self.p = &a * &self.p * a.transpose() + &gain * gain.transpose() * self.measurement;
        // The frequencies stay in the identification band: outside it a mode is no longer the
        // wave motion it was started on (and w → 0 would turn bias into unbounded position).
        for i in 0..self.modes() {
            let r_w = mode_rows(i).2;
            self.x[r_w] = self.x[r_w].clamp(self.band.0, self.band.1);
        }
    }
}

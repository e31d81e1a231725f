//! The low-pass filters of thesis §5.3: bias removal and output smoothing of the estimated
//! angles.
//!
//! - Bias removal: a very slow low-pass (0.005 Hz) follows an angle during the initialisation
//!   period before a test and is no longer updated when the test starts; the value it holds is
//!   the bias, subtracted from then on. The ship's yaw is removed this way, which turns the world
//!   frame to an artificial northern heading (applied to the ship and the load estimates alike, §7.2.1); the same
//!   mechanism can remove mounting offsets of the load IMU.
//! - Smoothing: a 1 Hz low-pass on every output angle.
//!
//! Each is the first-order filter y' = 2π f_c (x − y), discretised exactly for an input held over
//! the sample period Δt: y_k = y_{k−1} + a (x_k − y_{k−1}), a = 1 − exp(−2π f_c Δt). The thesis
//! gives only the cut-off frequencies; the first sample initialises the state (no start-up
//! transient from zero), and f_c = 0 turns a filter into a pass-through.

use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// A first-order low-pass filter (cut-off in Hz) and its state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LowPass {
    /// Cut-off frequency f_c (Hz); 0 passes the input through.
    pub cutoff: f64,
    state: Option<f64>,
}

impl LowPass {
    pub fn new(cutoff: f64) -> Self {
        LowPass { cutoff, state: None }
    }

    /// The filtered value after the sample `x` taken `dt` seconds after the previous one.
    pub fn update(&mut self, x: f64, dt: f64) -> f64 {
        self.update_with_gain(x, self.gain(dt))
    }

    /// The gain a = 1 − exp(−2π f_c Δt) of a sample `dt` seconds after the previous one: filters
    /// with one cut-off share it.
    pub fn gain(&self, dt: f64) -> f64 {
        1.0 - (-TAU * self.cutoff * dt).exp()
    }

    /// [`LowPass::update`] with the sample's gain ([`LowPass::gain`]) already computed.
    pub fn update_with_gain(&mut self, x: f64, gain: f64) -> f64 {
        let y = match self.state {
            Some(y) if self.cutoff > 0.0 => y + gain * (x - y),
            _ => x,
        };
        self.state = Some(y);
        y
    }

    /// The last output (0 before the first sample).
    pub fn value(&self) -> f64 {
        self.state.unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_step_response_is_the_exponential_of_the_cut_off() {
        // After a unit step, y(t) = 1 − exp(−2π f_c t) at every sample, exactly.
        let mut f = LowPass::new(1.0);
        assert_eq!(f.update(0.0, 0.01), 0.0);
        for k in 1..=100 {
            let y = f.update(1.0, 0.01);
            let expected = 1.0 - (-TAU * 0.01 * k as f64).exp();
            assert!((y - expected).abs() < 1e-14, "k = {k}: {y} vs {expected}");
        }
    }

    #[test]
    fn the_first_sample_initialises_and_zero_cut_off_passes_through() {
        let mut f = LowPass::new(0.005);
        assert_eq!(f.value(), 0.0);
        assert_eq!(f.update(0.3, 0.01), 0.3);
        let mut through = LowPass::new(0.0);
        for x in [1.0, -2.0, 5.0] {
            assert_eq!(through.update(x, 0.01), x);
        }
    }

    #[test]
    fn a_sine_at_the_cut_off_is_attenuated_to_one_over_root_two() {
        let (fc, dt) = (1.0, 0.001);
        let mut f = LowPass::new(fc);
        let mut peak: f64 = 0.0;
        for k in 0..20_000 {
            let t = k as f64 * dt;
            let y = f.update((TAU * fc * t).sin(), dt);
            if t > 10.0 {
                peak = peak.max(y.abs());
            }
        }
        assert!((peak - std::f64::consts::FRAC_1_SQRT_2).abs() < 5e-3, "peak {peak}");
    }
}

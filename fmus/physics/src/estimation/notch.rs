//! A notch filter that removes one frequency from a sampled signal and passes the rest: the
//! controller takes the hook–load mode out of the load IMU's angles with it (docs/rigging.md,
//! "A controller setting for the second mode").
//!
//! The continuous notch H(s) = (s² + ω₀²)/(s² + 2ζ ω₀ s + ω₀²) (unit gain at 0 and ∞, zero gain at
//! ω₀, −3 dB band 2ζ ω₀ wide) is discretised by the bilinear transform with the centre prewarped,
//! K = tan(ω₀ Δt/2), so that the discrete notch sits exactly at ω₀ (Oppenheim & Schafer,
//! Discrete-Time Signal Processing, 3rd ed., §7.2.2; the notch biquad of R. Bristow-Johnson's
//! "Audio EQ Cookbook"): with a₀ = 1 + 2ζK + K²,
//!
//! ```text
//! b₀ = b₂ = (1 + K²)/a₀,   b₁ = a₁ = 2(K² − 1)/a₀,   a₂ = (1 − 2ζK + K²)/a₀,
//! y_k = b₀ x_k + s₁,   s₁ ← b₁ x_k − a₁ y_k + s₂,   s₂ ← b₂ x_k − a₂ y_k
//! ```
//!
//! (direct form II transposed). The centre may change from sample to sample (it follows the hoist
//! length); the coefficients are recomputed each sample. As [`super::filters::LowPass`], the first
//! sample initialises the state at rest on that sample (for a constant input x the steady state is
//! s₁ = s₂ = (b₂ − a₂) x), and ζ = 0 passes the input through.

use serde::{Deserialize, Serialize};

/// A notch filter of damping ζ (the band's half-width per centre frequency) and its state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Notch {
    /// ζ of the continuous notch; 0 passes the input through.
    pub damping: f64,
    state: Option<[f64; 2]>,
}

/// The biquad's coefficients (b₀ = b₂, b₁ = a₁) for one sample.
struct Coefficients {
    b0: f64,
    a1: f64,
    a2: f64,
}

impl Coefficients {
    /// The prewarped bilinear transform of the notch at `omega` (rad/s) for the sample period `dt`.
    fn new(damping: f64, omega: f64, dt: f64) -> Self {
        let k = (0.5 * omega * dt).tan();
        let k2 = k * k;
        let a0 = 1.0 + 2.0 * damping * k + k2;
        Coefficients { b0: (1.0 + k2) / a0, a1: 2.0 * (k2 - 1.0) / a0, a2: (1.0 - 2.0 * damping * k + k2) / a0 }
    }
}

impl Notch {
    pub const fn new(damping: f64) -> Self {
        Notch { damping, state: None }
    }

    /// The filtered value of the sample `x` taken `dt` seconds after the previous one, with the
    /// notch at `omega` (rad/s; below the Nyquist frequency π/Δt, else the input passes).
    pub fn update(&mut self, x: f64, omega: f64, dt: f64) -> f64 {
        if !(self.damping > 0.0 && omega > 0.0 && omega * dt < std::f64::consts::PI) {
            self.state = None;
            return x;
        }
        let c = Coefficients::new(self.damping, omega, dt);
        let [s1, s2] = self.state.unwrap_or([(c.b0 - c.a2) * x; 2]);
        let y = c.b0 * x + s1;
        self.state = Some([c.a1 * (x - y) + s2, c.b0 * x - c.a2 * y]);
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The steady amplitude of the notch's response to a unit sine at `omega` (rad/s), notch at
    /// `centre`, 1 ms samples.
    fn gain(damping: f64, centre: f64, omega: f64) -> f64 {
        let dt = 1e-3;
        let mut f = Notch::new(damping);
        let mut peak: f64 = 0.0;
        for k in 0..60_000 {
            let t = k as f64 * dt;
            let y = f.update((omega * t).sin(), centre, dt);
            if t > 40.0 {
                peak = peak.max(y.abs());
            }
        }
        peak
    }

    /// |H(jω)| of the continuous notch.
    fn continuous_gain(damping: f64, centre: f64, omega: f64) -> f64 {
        let re = centre * centre - omega * omega;
        re.abs() / (re * re + (2.0 * damping * centre * omega).powi(2)).sqrt()
    }

    #[test]
    fn the_centre_is_removed_and_the_rest_passes_as_the_continuous_notch() {
        let (zeta, centre) = (0.5, 13.5);
        assert!(gain(zeta, centre, centre) < 1e-3, "at the centre: {}", gain(zeta, centre, centre));
        // Prewarping puts the zero exactly at ω₀; away from it the bilinear map moves the response
        // by (ωΔt)²/12, well below a percent at these frequencies.
        for omega in [2.0, 4.0, 8.0, 20.0, 40.0] {
            let (discrete, continuous) = (gain(zeta, centre, omega), continuous_gain(zeta, centre, omega));
            assert!((discrete - continuous).abs() < 5e-3, "ω = {omega}: {discrete} vs {continuous}");
        }
    }

    #[test]
    fn a_constant_passes_from_the_first_sample_and_zero_damping_passes_everything() {
        let mut f = Notch::new(0.3);
        for _ in 0..100 {
            let y = f.update(0.25, 13.0, 0.01);
            assert!((y - 0.25).abs() < 1e-14, "{y}");
        }
        let mut through = Notch::new(0.0);
        for x in [1.0, -2.0, 5.0] {
            assert_eq!(through.update(x, 13.0, 0.01), x);
        }
        // A centre at or above Nyquist (π/Δt = 314 rad/s at 10 ms) passes the input too.
        assert_eq!(Notch::new(0.3).update(0.7, 400.0, 0.01), 0.7);
    }
}

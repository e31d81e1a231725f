//! The JONSWAP wave spectrum in the DNV form (DNV-RP-C205, *Environmental Conditions and
//! Environmental Loads*, §3.5.5) and its seeded discretisation into harmonic wave components
//! (SPEC §8.2; the random-phase sum of Faltinsen 1990, *Sea Loads on Ships and Offshore
//! Structures*, ch. 2).
//!
//! Units: wave frequency ω in rad/s, spectral density S(ω) in m²·s/rad, heights in m. The
//! spectrum is one-sided, so the variance of the wave elevation is m0 = ∫ S(ω) dω and the
//! significant wave height Hs ≈ 4 √m0.

use crate::check::check_positive;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Number of harmonic components of a synthesized sea.
pub const COMPONENTS: usize = 200;
/// Frequency band of the components as multiples of the peak frequency ωp: [0.6 ωp, 3 ωp].
pub const BAND: (f64, f64) = (0.6, 3.0);

/// ChaCha stream that holds the draws of the wave components (kept apart from the sensor-noise
/// channels, which use small stream numbers).
const WAVE_STREAM: u64 = 0x5741_5645; // "WAVE"

/// A short-crested sea state described by its significant wave height and peak period.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SeaState {
    /// Significant wave height Hs (m).
    pub hs: f64,
    /// Peak period Tp (s).
    pub tp: f64,
}

impl SeaState {
    pub fn validate(&self) -> Result<(), String> {
        check_positive("significant wave height", self.hs, "m")?;
        check_positive("peak period", self.tp, "s")
    }

    /// Peak frequency ωp = 2π/Tp (rad/s).
    pub fn peak_frequency(&self) -> f64 {
        TAU / self.tp
    }

    /// Peak enhancement factor γ by the DNV rule: with k = Tp/√Hs (Tp in s, Hs in m), γ = 5 for
    /// k ≤ 3.6, exp(5.75 − 1.15 k) for 3.6 < k < 5 and 1 for k ≥ 5 (Pierson–Moskowitz).
    pub fn gamma(&self) -> f64 {
        let k = self.tp / self.hs.sqrt();
        if k <= 3.6 {
            5.0
        } else if k < 5.0 {
            (5.75 - 1.15 * k).exp()
        } else {
            1.0
        }
    }

    /// JONSWAP spectral density in the DNV form (m²·s/rad):
    /// S(ω) = (1 − 0.287 ln γ) (5/16) Hs² ωp⁴ ω⁻⁵ exp(−1.25 (ωp/ω)⁴) γ^exp(−(ω − ωp)²/(2 σ² ωp²)),
    /// σ = 0.07 for ω ≤ ωp and 0.09 above.
    pub fn density(&self, omega: f64) -> f64 {
        if !(omega > 0.0) {
            return 0.0;
        }
        let wp = self.peak_frequency();
        let gamma = self.gamma();
        let sigma = if omega <= wp { 0.07 } else { 0.09 };
        let normalisation = 1.0 - 0.287 * gamma.ln();
        let pierson_moskowitz =
            5.0 / 16.0 * self.hs.powi(2) * wp.powi(4) * omega.powi(-5) * (-1.25 * (wp / omega).powi(4)).exp();
        let peak = gamma.powf((-(omega - wp).powi(2) / (2.0 * sigma * sigma * wp * wp)).exp());
        normalisation * pierson_moskowitz * peak
    }
}

/// One harmonic wave: elevation ζ(t) = a cos(ω t + φ) at the origin of the ship frame (m, up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WaveComponent {
    /// Frequency ω (rad/s).
    pub omega: f64,
    /// Amplitude a = √(2 S(ω) Δω) (m).
    pub amplitude: f64,
    /// Phase φ (rad), in [0, 2π).
    pub phase: f64,
}

/// The sea state as a sum of `n` random-phase harmonics: the band [0.6 ωp, 3 ωp] is cut into `n`
/// equal bins of width Δω, one frequency is drawn uniformly inside each bin (so no two
/// components share a frequency and the sum does not repeat), its amplitude is √(2 S(ω) Δω) and
/// its phase is uniform in [0, 2π).
///
/// The draws are a deterministic function of `seed`: a ChaCha8 stream keyed by the seed
/// (`seed_from_u64`, as [`crate::noise`] does) on its own stream number, two 53-bit uniforms per
/// component in order (frequency offset, phase).
pub fn components(sea: &SeaState, n: usize, seed: u64) -> Vec<WaveComponent> {
    let wp = sea.peak_frequency();
    let (lo, hi) = (BAND.0 * wp, BAND.1 * wp);
    let d_omega = (hi - lo) / n as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(WAVE_STREAM);
    let mut uniform = move || common::unit::closed_open(rng.next_u64());
    (0..n)
        .map(|i| {
            let omega = lo + (i as f64 + uniform()) * d_omega;
            let phase = TAU * uniform();
            WaveComponent { omega, amplitude: (2.0 * sea.density(omega) * d_omega).sqrt(), phase }
        })
        .collect()
}

#[cfg(test)]
mod tests;

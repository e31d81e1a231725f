//! The harmonic-sum generator of six-degree-of-freedom deck motion with exact derivatives.
//!
//! Linear superposition (SPEC §8.2; Faltinsen 1990, *Sea Loads on Ships and Offshore Structures*,
//! ch. 2 for the irregular sea as a sum of harmonics, ch. 3 for the response to it): a wave
//! component a cos(ωt + φ) moves degree of freedom j as Re(H_j(ω, β) a e^{i(ωt + φ)}), H_j the
//! hull's RAO ([`Hull::response`]), and the responses to all components add.
//!
//! The sum yields a [`DeckMotion`] (surge, sway, heave in m, W, heave positive down; roll, pitch,
//! yaw in rad, Z–Y–X; indices and names in [`crate::motion`]), which
//! [`DeckMotion::to_ship_motion`] turns into what the crane and the deck IMU consume.

use super::rao::Hull;
use super::spectrum::WaveComponent;
use crate::motion::{AxisMotion, DeckMotion};
use nalgebra::Complex;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One harmonic of the motion: every degree of freedom j moves as Re(c_j e^{i(ωt + φ)}).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Harmonic {
    /// Frequency ω (rad/s).
    pub omega: f64,
    /// Phase φ (rad), shared by every degree of freedom.
    pub phase: f64,
    /// Complex amplitudes c_j (m or rad): RAO × wave amplitude.
    pub amplitude: [Complex<f64>; 6],
}

/// A sum of harmonics per degree of freedom, x_j(t) = g_j Σ Re(c_j e^{i(ωt + φ)}) − o_j, with gains
/// g_j and offsets o_j (a scaled and centred copy of the same sea keeps the same harmonics).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HarmonicMotion {
    pub harmonics: Vec<Harmonic>,
    pub gains: [f64; 6],
    pub offsets: [f64; 6],
}

impl HarmonicMotion {
    /// The response of `hull` to the waves `waves` arriving at heading `heading` (rad): one
    /// harmonic per wave component, the component's phase shared by every degree of freedom.
    pub fn from_waves(hull: &Hull, waves: &[WaveComponent], heading: f64) -> HarmonicMotion {
        let harmonics = waves
            .iter()
            .map(|w| Harmonic {
                omega: w.omega,
                phase: w.phase,
                amplitude: hull.response(w.omega, heading).map(|h| h * w.amplitude),
            })
            .collect();
        HarmonicMotion { harmonics, gains: [1.0; 6], offsets: [0.0; 6] }
    }

    /// Position, velocity and acceleration of every degree of freedom at time `t` (s): exact
    /// derivatives of the sum (×iω, ×−ω²).
    pub fn sample(&self, t: f64) -> DeckMotion {
        let mut dof = [AxisMotion::default(); 6];
        for h in &self.harmonics {
            let (s, c) = (h.omega * t + h.phase).sin_cos();
            let rotor = Complex::new(c, s);
            for (j, axis) in dof.iter_mut().enumerate() {
                let z = h.amplitude[j] * rotor;
                axis.pos += z.re;
                axis.vel -= h.omega * z.im;
                axis.acc -= h.omega * h.omega * z.re;
            }
        }
        for (j, axis) in dof.iter_mut().enumerate() {
            let g = self.gains[j];
            *axis = AxisMotion { pos: g * axis.pos - self.offsets[j], vel: g * axis.vel, acc: g * axis.acc };
        }
        DeckMotion { dof }
    }

    /// The mean of each degree of freedom over [t0, t1] (s), exact: the mean of cos(ωt + φ) is
    /// (sin(ωt1 + φ) − sin(ωt0 + φ))/(ω (t1 − t0)).
    pub fn window_mean(&self, t0: f64, t1: f64) -> [f64; 6] {
        let mut mean = [0.0; 6];
        for h in &self.harmonics {
            // ∫ e^{i(ωt + φ)} dt / (t1 − t0) = (e^{i(ωt1 + φ)} − e^{i(ωt0 + φ)}) / (iω (t1 − t0)).
            let end = Complex::from_polar(1.0, h.omega * t1 + h.phase);
            let start = Complex::from_polar(1.0, h.omega * t0 + h.phase);
            let average = (end - start) / Complex::new(0.0, h.omega * (t1 - t0));
            for (j, m) in mean.iter_mut().enumerate() {
                *m += (h.amplitude[j] * average).re;
            }
        }
        for (j, m) in mean.iter_mut().enumerate() {
            *m = self.gains[j] * *m - self.offsets[j];
        }
        mean
    }

    /// Spectral moment m_n = Σ ωⁿ |g c|²/2 of degree of freedom `j` (the variance for n = 0): the
    /// discrete form of m_n = ∫ ωⁿ S_j(ω) dω with the response spectrum S_j = |H_j|² S (Faltinsen
    /// 1990, ch. 3), each harmonic contributing its variance |g c|²/2.
    pub fn spectral_moment(&self, j: usize, n: i32) -> f64 {
        let g2 = self.gains[j] * self.gains[j];
        self.harmonics.iter().map(|h| h.omega.powi(n) * g2 * h.amplitude[j].norm_sqr() / 2.0).sum()
    }

    /// Significant single amplitude 2√m0 of degree of freedom `j` (m or rad): half the significant
    /// height 4√m0 of a narrow-banded Gaussian process (Faltinsen 1990, ch. 2).
    pub fn significant_amplitude(&self, j: usize) -> f64 {
        2.0 * self.spectral_moment(j, 0).sqrt()
    }

    /// Mean zero-crossing period T_z = 2π √(m0/m2) of degree of freedom `j` (s); 0 without motion.
    /// Rice's rate of zero up-crossings of a Gaussian process, √(m2/m0)/2π (Rice 1944, *Bell System
    /// Technical Journal* 23; Faltinsen 1990, ch. 2, where it is the period T_2).
    pub fn zero_crossing_period(&self, j: usize) -> f64 {
        let (m0, m2) = (self.spectral_moment(j, 0), self.spectral_moment(j, 2));
        if m2 > 0.0 {
            TAU * (m0 / m2).sqrt()
        } else {
            0.0
        }
    }

    /// Period 2π/ω (s) of the harmonic with the largest amplitude in degree of freedom `j`: the
    /// dominant period of the realisation; 0 without motion.
    pub fn dominant_period(&self, j: usize) -> f64 {
        self.harmonics
            .iter()
            .filter(|h| h.amplitude[j].norm() > 0.0)
            .max_by(|a, b| a.amplitude[j].norm().total_cmp(&b.amplitude[j].norm()))
            .map_or(0.0, |h| TAU / h.omega)
    }
}

#[cfg(test)]
mod tests;

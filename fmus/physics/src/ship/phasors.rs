//! The harmonic sum on the communication grid by phasor rotation: the same deck motion as
//! [`HarmonicMotion::sample`] (to rounding), without a sine per harmonic and sample.
//!
//! On the grid τ_k = k Δ (Δ = [`GRID_STEP`]) each harmonic's unit phasor e^{i(ω τ_k + φ)} advances by
//! the fixed rotation e^{iωΔ}: e^{i(ω τ_{k+1} + φ)} = e^{i(ω τ_k + φ)} e^{iωΔ}, the angle-addition
//! formulas of sine and cosine as one complex product (the trigonometric recurrence of Press et
//! al., *Numerical Recipes*, 3rd ed. 2007, ch. 5, "Recurrence relations"). That is one complex
//! multiplication instead of a `sin_cos`. Rounding grows with the number of rotations, so the
//! phasors are re-anchored every [`ANCHOR_INTERVAL`] grid points to the exact value, computed as
//! the direct sum computes it: the phasors at k are always those of the anchor k0 = k − (k mod K)
//! rotated k − k0 times. The deck motion is therefore a pure function of τ, whatever order and
//! however often it is asked for; the cursor that remembers the last grid point only saves the
//! repeated rotations.
//!
//! A time within [`GRID_TOLERANCE`] of a grid point (an importer's t_k + h differs from (k + 1) Δ
//! by rounding) is reached from the grid point by a first-order Taylor step of each signal,
//! x(τ_k + δ) = x(τ_k) + δ ẋ(τ_k), exact to (ωδ)²/2 < 10⁻¹⁷ of its amplitude (Taylor's remainder
//! δ² ẍ/2, with |ẍ| ≤ ω² a for a harmonic of amplitude a); the acceleration's step needs the jerk,
//! summed alongside only then (on the grid itself δ = 0 and the sums leave it out, the same bits).
//! Any other time (another step size, an arbitrary t) takes the direct sum.
//! Positions, velocities and accelerations then agree with the direct sum to about 10⁻¹⁴ of each
//! degree of freedom's amplitude.

use super::motion::HarmonicMotion;
use crate::motion::{AxisMotion, DeckMotion};
use nalgebra::Complex;
use serde::{Deserialize, Serialize};

/// Spacing Δ of the grid the phasors rotate on (s): the platform's default communication step.
pub const GRID_STEP: f64 = 0.01;
/// Grid points between two exact anchors (K): 1 s of profile time on the 10 ms grid.
pub const ANCHOR_INTERVAL: i64 = 100;
/// Largest distance from a grid point (s) still served by the rotation.
pub const GRID_TOLERANCE: f64 = 1e-9;
/// Largest |τ| (s) served by the rotation: beyond it the grid index would lose integer precision.
const GRID_REACH: f64 = 1e12;

/// One harmonic as the rotation needs it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Term {
    /// Frequency ω (rad/s), its square and cube, and the phase φ (rad).
    omega: f64,
    omega_sq: f64,
    omega_cube: f64,
    phase: f64,
    /// e^{iωΔ}: the phasor's advance per grid step.
    rotation: Complex<f64>,
    /// Gain × complex amplitude g_j c_j per degree of freedom (m or rad), split for the inner loop.
    amplitude_re: [f64; 6],
    amplitude_im: [f64; 6],
}

/// The phasors e^{i(ω τ_k + φ)} of every harmonic at grid point `index`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Cursor {
    index: i64,
    phasors: Vec<Complex<f64>>,
}

/// A [`HarmonicMotion`] sampled by phasor rotation on the grid, directly elsewhere.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhasorSum {
    motion: HarmonicMotion,
    terms: Vec<Term>,
    cursor: Option<Cursor>,
}

impl PhasorSum {
    pub fn new(motion: HarmonicMotion) -> PhasorSum {
        let terms = terms(&motion, GRID_STEP);
        PhasorSum { motion, terms, cursor: None }
    }

    /// The motion this sum evaluates.
    pub fn motion(&self) -> &HarmonicMotion {
        &self.motion
    }

    /// Position, velocity and acceleration of every degree of freedom at time `tau` (s).
    pub fn sample(&mut self, tau: f64) -> DeckMotion {
        let Some((k, delta)) = grid_point(tau) else { return self.motion.sample(tau) };
        // The jerk only serves the step off the grid: on it (δ = 0, what an importer stepping
        // from a grid point asks for) the acceleration below is acc + 0·0 instead of acc + 0·jerk,
        // the same bits (a sum of harmonics is exactly zero only when it started at +0 and only
        // zeros were subtracted from it, and +0 + ±0 = +0).
        let [pos, vel, acc, jerk] = if delta == 0.0 { self.sums::<false>(k) } else { self.sums::<true>(k) };
        let offsets = &self.motion.offsets;
        DeckMotion {
            dof: std::array::from_fn(|j| AxisMotion {
                pos: pos[j] + delta * vel[j] - offsets[j],
                vel: vel[j] + delta * acc[j],
                acc: acc[j] + delta * jerk[j],
            }),
        }
    }

    /// The sums of [`accumulate`] at grid point `k`, the jerk's only with `JERK`.
    fn sums<const JERK: bool>(&mut self, k: i64) -> [[f64; 6]; 4] {
        match &mut self.cursor {
            // The next grid point of the same block, as an importer stepping on the grid asks for:
            // the one rotation move_cursor would make, fused with the sum (one pass over the
            // phasors instead of two, the same operations in the same order).
            Some(c) if c.index + 1 == k && k.rem_euclid(ANCHOR_INTERVAL) != 0 => {
                c.index = k;
                rotate_accumulate::<JERK>(&self.terms, &mut c.phasors)
            }
            _ => {
                self.move_cursor(k);
                let phasors = self.cursor.as_ref().map_or(&[][..], |c| &c.phasors);
                accumulate::<JERK>(&self.terms, phasors)
            }
        }
    }

    /// Puts the cursor on grid point `k`: from the cursor if it lies between k's anchor and k, else
    /// from the anchor, so the phasors at k always come from the same rotations.
    fn move_cursor(&mut self, k: i64) {
        let anchor = k - k.rem_euclid(ANCHOR_INTERVAL);
        let terms = &self.terms;
        let cursor = match &mut self.cursor {
            Some(c) if (anchor..=k).contains(&c.index) => c,
            slot => slot.insert(Cursor { index: anchor, phasors: anchor_phasors(terms, anchor as f64 * GRID_STEP) }),
        };
        for _ in cursor.index..k {
            for (phasor, term) in cursor.phasors.iter_mut().zip(terms) {
                *phasor *= term.rotation;
            }
        }
        cursor.index = k;
    }
}

/// The deck motion at τ_k = k `step` for k = 0 … `last`, by the same rotation with the step
/// `step` and the same re-anchoring every [`ANCHOR_INTERVAL`] points: within about 1e-14 of each
/// signal's amplitude of [`HarmonicMotion::sample`] for steps up to some 0.1 s (each rotation
/// rounds to about 1e-16 whatever its angle), at one complex product per harmonic and point
/// whatever the step. For uses that need the motion on a coarser uniform grid than the
/// communication grid, approximately (the test-scale search screens its window with it).
pub fn uniform_samples(motion: &HarmonicMotion, step: f64, last: usize) -> Vec<DeckMotion> {
    let terms = terms(motion, step);
    let mut phasors = Vec::new();
    (0..=last)
        .map(|k| {
            if k as i64 % ANCHOR_INTERVAL == 0 {
                phasors = anchor_phasors(&terms, k as f64 * step);
            } else {
                for (phasor, term) in phasors.iter_mut().zip(&terms) {
                    *phasor *= term.rotation;
                }
            }
            let [pos, vel, acc, _] = accumulate::<false>(&terms, &phasors);
            DeckMotion {
                dof: std::array::from_fn(|j| AxisMotion { pos: pos[j] - motion.offsets[j], vel: vel[j], acc: acc[j] }),
            }
        })
        .collect()
}

/// The harmonics of `motion` as the rotation by `step` (s) needs them.
fn terms(motion: &HarmonicMotion, step: f64) -> Vec<Term> {
    motion
        .harmonics
        .iter()
        .map(|h| {
            let (s, c) = (h.omega * step).sin_cos();
            let scaled = |j: usize| motion.gains[j] * h.amplitude[j];
            Term {
                omega: h.omega,
                omega_sq: h.omega * h.omega,
                omega_cube: h.omega * h.omega * h.omega,
                phase: h.phase,
                rotation: Complex::new(c, s),
                amplitude_re: std::array::from_fn(|j| scaled(j).re),
                amplitude_im: std::array::from_fn(|j| scaled(j).im),
            }
        })
        .collect()
}

/// The exact unit phasors e^{i(ω τ + φ)} of `terms` at time `tau` (s), computed as the direct sum
/// computes them.
fn anchor_phasors(terms: &[Term], tau: f64) -> Vec<Complex<f64>> {
    terms
        .iter()
        .map(|t| {
            let (s, c) = (t.omega * tau + t.phase).sin_cos();
            Complex::new(c, s)
        })
        .collect()
}

/// Σ Re z, Σ −ω Im z, Σ −ω² Re z and Σ ω³ Im z (position, velocity, acceleration, jerk) per
/// degree of freedom, z = g c_j e^{i(ωτ_k + φ)}, over the harmonics with their phasors at τ_k: the
/// harmonic sum of [`HarmonicMotion::sample`] and its time derivatives (d/dt multiplies z by iω).
///
/// The six degrees of freedom are independent lanes of the same operations, so the compiler
/// vectorizes across them; with AVX four lanes at a time instead of two. Either way each lane
/// performs the same IEEE operations in the same order (no fused multiply-add), so the result is
/// bit for bit the same on every x86-64 processor.
fn accumulate<const JERK: bool>(terms: &[Term], phasors: &[Complex<f64>]) -> [[f64; 6]; 4] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the processor supports AVX, checked just above.
        return unsafe { accumulate_avx::<JERK>(terms, phasors) };
    }
    accumulate_lanes::<JERK>(terms, phasors)
}

/// [`accumulate_lanes`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn accumulate_avx<const JERK: bool>(terms: &[Term], phasors: &[Complex<f64>]) -> [[f64; 6]; 4] {
    accumulate_lanes::<JERK>(terms, phasors)
}

#[inline(always)] // compiled into each caller, with the caller's instruction set
fn accumulate_lanes<const JERK: bool>(terms: &[Term], phasors: &[Complex<f64>]) -> [[f64; 6]; 4] {
    let mut sums = [[0.0; 6]; 4];
    for (term, phasor) in terms.iter().zip(phasors) {
        add_term::<JERK>(&mut sums, term, *phasor);
    }
    sums
}

/// Advances every phasor by its rotation e^{iωΔ} (one grid step, as [`PhasorSum::move_cursor`]
/// does) and returns [`accumulate`] of the rotated phasors, in one pass: the same bits as the
/// rotation followed by the sum.
fn rotate_accumulate<const JERK: bool>(terms: &[Term], phasors: &mut [Complex<f64>]) -> [[f64; 6]; 4] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the processor supports AVX, checked just above.
        return unsafe { rotate_accumulate_avx::<JERK>(terms, phasors) };
    }
    rotate_accumulate_lanes::<JERK>(terms, phasors)
}

/// [`rotate_accumulate_lanes`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn rotate_accumulate_avx<const JERK: bool>(terms: &[Term], phasors: &mut [Complex<f64>]) -> [[f64; 6]; 4] {
    rotate_accumulate_lanes::<JERK>(terms, phasors)
}

#[inline(always)] // compiled into each caller, with the caller's instruction set
fn rotate_accumulate_lanes<const JERK: bool>(terms: &[Term], phasors: &mut [Complex<f64>]) -> [[f64; 6]; 4] {
    let mut sums = [[0.0; 6]; 4];
    for (term, phasor) in terms.iter().zip(phasors) {
        // e^{i(ω τ_{k+1} + φ)} = e^{i(ω τ_k + φ)} e^{iωΔ} (the recurrence in the module comment).
        *phasor *= term.rotation;
        add_term::<JERK>(&mut sums, term, *phasor);
    }
    sums
}

/// Adds one harmonic's z = g c_j e^{i(ωτ_k + φ)} to the sums of [`accumulate`]: Re z, −ω Im z,
/// −ω² Re z and, with `JERK`, ω³ Im z per degree of freedom (d/dt multiplies z by iω); without
/// it the jerk's sums stay 0.
#[inline(always)] // compiled into each caller, with the caller's instruction set
fn add_term<const JERK: bool>(sums: &mut [[f64; 6]; 4], term: &Term, phasor: Complex<f64>) {
    let [pos, vel, acc, jerk] = sums;
    let (c, s) = (phasor.re, phasor.im);
    for j in 0..6 {
        let re = term.amplitude_re[j] * c - term.amplitude_im[j] * s;
        let im = term.amplitude_re[j] * s + term.amplitude_im[j] * c;
        pos[j] += re;
        vel[j] -= term.omega * im;
        acc[j] -= term.omega_sq * re;
        if JERK {
            jerk[j] += term.omega_cube * im;
        }
    }
}

/// The grid point k nearest to `tau` (s) and the offset δ = τ − k Δ (s), if within
/// [`GRID_TOLERANCE`].
fn grid_point(tau: f64) -> Option<(i64, f64)> {
    if !(tau.abs() < GRID_REACH) {
        return None;
    }
    let k = (tau / GRID_STEP).round();
    let delta = tau - k * GRID_STEP;
    (delta.abs() <= GRID_TOLERANCE).then_some((k as i64, delta))
}

#[cfg(test)]
mod tests;

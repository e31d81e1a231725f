//! Identification of the dominant modes of one acceleration signal (thesis §5.1.3: "an FFT and
//! peak detection are applied to identify the dominant modes and initialise the filter").
//!
//! The window is multiplied by a Hann taper (its side lobes fall off fast, so a strong wave peak
//! does not raise spurious maxima next to it), zero-padded to [`PADDING`] times its length (the
//! padded spectrum samples the same peaks on a finer grid, so a peak is located to a fraction of
//! the window's resolution 1/T) and transformed. Only the bins of the band (and one on either
//! side) are needed, a few dozen of thousands, so they are summed directly (a discrete Fourier
//! transform with exact twiddle factors from one table) rather than by a full FFT — which would
//! also bring a planner whose hash map needs the operating system's random generator, a
//! dependency older Windows emulators cannot resolve. A mode is a local maximum of the
//! magnitude inside the band [`Band`], at least [`PeakSearch::threshold`] times the largest one
//! and with an amplitude of at least [`PeakSearch::floor`]; modes are returned strongest first.

use nalgebra::Complex;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Zero-padding factor of the transform.
pub const PADDING: usize = 4;

/// The frequency band searched for modes (rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    pub min: f64,
    pub max: f64,
}

/// How modes are picked from the spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PeakSearch {
    /// Number of modes N_m wanted (at most this many are returned).
    pub modes: usize,
    /// Smallest magnitude of a mode relative to the largest peak in the band (0–1).
    pub threshold: f64,
    /// Smallest amplitude of a mode (the signal's unit, m/s² for accelerations): a window of
    /// sensor noise alone has spectral maxima too, and they must not become modes.
    pub floor: f64,
    pub band: Band,
}

/// One dominant mode of the window: a(t) ≈ amplitude · cos(ω t + phase), t from the window's
/// first sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Eigenfrequency w (rad/s).
    pub omega: f64,
    /// Amplitude of the signal at this frequency (the signal's unit; Hann coherent gain removed).
    pub amplitude: f64,
    /// Phase at the window's first sample (rad).
    pub phase: f64,
}

/// The dominant modes of `signal`, sampled every `dt` s, strongest first (see the module
/// documentation). An empty window, or one without a peak in the band, gives no modes.
pub fn dominant_modes(signal: &[f64], dt: f64, search: &PeakSearch) -> Vec<Mode> {
    let length = PADDING * signal.len();
    let bin = TAU / (length as f64 * dt);
    // Candidate bins: the band widened by one bin against round-off in k·bin, below N/2.
    let first = ((search.band.min / bin).ceil() as usize).saturating_sub(1).max(1);
    let last = ((search.band.max / bin).floor() as usize + 1).min((length / 2).saturating_sub(1));
    let spectrum = hann_spectrum(signal, first - 1..=last + 1);
    let magnitude: Vec<f64> = spectrum.iter().map(|c| c.norm()).collect();
    let in_band = |k: usize| (search.band.min..=search.band.max).contains(&(k as f64 * bin));
    let mut peaks: Vec<usize> = (first..=last)
        .filter(|&k| in_band(k) && magnitude[k] > magnitude[k - 1] && magnitude[k] >= magnitude[k + 1])
        .collect();
    peaks.sort_by(|&a, &b| magnitude[b].total_cmp(&magnitude[a]));
    let Some(&strongest) = peaks.first() else { return Vec::new() };
    // Sum of the Hann weights: the coherent gain that scales a sinusoid's bin magnitude.
    let gain: f64 = hann(signal.len()).sum();
    let floor = (search.threshold * magnitude[strongest]).max(search.floor * gain / 2.0);
    peaks
        .into_iter()
        .filter(|&k| magnitude[k] >= floor)
        .take(search.modes)
        .map(|k| Mode { omega: k as f64 * bin, amplitude: 2.0 * magnitude[k] / gain, phase: spectrum[k].arg() })
        .collect()
}

/// The Hann window of length n.
fn hann(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| 0.5 - 0.5 * (TAU * i as f64 / n as f64).cos())
}

/// The bins `bins` of the transform of the Hann-tapered `signal` zero-padded to [`PADDING`]
/// times its length, X_k = Σ_n x_n w_n e^(−2πi k n / N); the other bins of the returned
/// spectrum (N/2 + 1 long) are zero. The twiddle factor of k·n is looked up at k·n mod N, so it
/// is exact to the last bit of one `sin_cos` whatever k and n are.
fn hann_spectrum(signal: &[f64], bins: std::ops::RangeInclusive<usize>) -> Vec<Complex<f64>> {
    let length = PADDING * signal.len();
    let mut spectrum = vec![Complex::new(0.0, 0.0); length / 2 + 1];
    if signal.is_empty() {
        return spectrum;
    }
    let twiddles: Vec<Complex<f64>> = (0..length)
        .map(|j| {
            let (sin, cos) = (TAU * j as f64 / length as f64).sin_cos();
            Complex::new(cos, -sin)
        })
        .collect();
    let tapered: Vec<f64> = signal.iter().zip(hann(signal.len())).map(|(x, w)| x * w).collect();
    for k in bins {
        spectrum[k] = tapered.iter().enumerate().map(|(n, x)| twiddles[k * n % length] * *x).sum();
    }
    spectrum
}

//! Surge, sway and heave of the ship from the deck IMU (thesis §5.1.3, after Küchler et al. [35]):
//! the specific force turned into the world frame with the attitude estimate (eqs. 5.38–5.43),
//! the dominant frequencies of each axis found by FFT and peak detection over an initialisation
//! window, then one Extended Kalman Filter of undamped oscillators per axis (eqs. 5.46–5.52).
//!
//! Frames and units: world frame W North-East-Down (x north, y east, z down, gravity along +z), so
//! surge, sway and heave are the x, y and z of the ship frame's origin in W (m; heave positive
//! down) and their rates in m/s. The sensor frame S is aligned with the ship frame B
//! (^S q_B = q_I) and IMU1 sits at the deck centre (s1 = 0, SPEC §3), so the lever-arm terms of
//! eq. 5.42 vanish and the sensor's acceleration is the ship's.
//!
//! The thesis does not apply the filter at test scale: "the test-scale acceleration measurements
//! have poor signal-to-noise ratios" (§5.1.3). Measured (`cargo test -p physics --release
//! linear_motion -- --show-output`; set-up in `linear_motion/tests.rs`: profiles 1–3, SPEC §8.1
//! IMU noise at both scales, [`EstimatorParams::FULL_SCALE`], RMS over 90–300 s), RMS position
//! error relative to the motion's RMS:
//!
//! | attitude of eq. 5.40       | scale | surge     | sway      | heave     |
//! |----------------------------|-------|-----------|-----------|-----------|
//! | true                       | full  | 42–44 %   | 42–49 %   | 31–43 %   |
//! | true                       | test  | 71–79 %   | 64–80 %   | 50–72 %   |
//! | complementary filter (5.1) | full  | 100–103 % | 99–101 %  | 31–43 %   |
//! | complementary filter (5.1) | test  | 96–100 %  | 99 %      | 50–72 %   |
//!
//! (rates alike: 27–40 % at full scale with the true attitude, 55–87 % at test scale). In metres:
//! full-scale heave 0.12–0.94 m RMS is estimated to 0.04–0.33 m; test-scale heave 9–14 mm RMS to
//! 4–10 mm. So: heave is usable as a full-scale feed-forward estimate (errors a third of the
//! motion), not at test scale, where the error is half to three quarters of the motion, as the
//! thesis predicted. Surge and sway are unusable at both scales with the Table 5.1 attitude: its
//! accelerometer gain (ᾱ_a = 0.05 per 10 ms) makes the estimated vertical follow the specific
//! force within ~0.2 s, so eq. 5.40 cancels the horizontal wave accelerations (an error of ~100 %
//! is what an estimate of zero scores); they need an attitude that ignores the accelerometer over
//! wave periods.
//!
//! Not done here (the thesis' [35] behaviour, later work): periodic re-identification and
//! re-initialisation as modes appear or disappear.

pub mod ekf;
pub mod peaks;

use crate::math::{Quat, Vec3};
use ekf::{Noise, OscillatorEkf};
use peaks::{dominant_modes, Band, PeakSearch};
use std::f64::consts::TAU;

/// The ship's linear acceleration in W (m/s²) from the specific force `f_s` (m/s², sensor frame)
/// and the attitude estimate `q` (W←S): eq. 5.40 rearranged,
/// ^W a_S/W = ^W q_S (^S a) ^W q_S* − ^W g. This crate's IMU senses gravity as (0, 0, −g) in W
/// (a level sensor at rest reads (0, 0, −g), §3.5.4), so ^W g = (0, 0, −g) and
/// a_W = R(q) f_S + (0, 0, g).
pub fn world_acceleration(q: &Quat, f_s: &Vec3, g: f64) -> Vec3 {
    q * f_s + Vec3::new(0.0, 0.0, g)
}

/// Settings of the estimator where the thesis gives none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimatorParams {
    /// Length of the initialisation window (s).
    pub window: f64,
    pub search: PeakSearch,
    pub noise: Noise,
}

impl EstimatorParams {
    /// The choices for a full-scale ship with the deck IMU of SPEC §8.1:
    /// - window 60 s: six to eight wave periods of the profiles (T_p 8.8–9.7 s) and a resolution
    ///   2π/60 = 0.105 rad/s, a sixth of the peak frequency;
    /// - N_m = 3 modes per axis: the profiles' spectra are single-peaked (JONSWAP) with the roll
    ///   resonance (11 s) beside the wave peak in sway; three oscillators cover the peak and its
    ///   flanks. With the 0.2 threshold no profile has more than three peaks; six modes with a
    ///   0.05 threshold gave 39 % instead of 42 % surge/sway error (profile 1, true attitude) and
    ///   the same heave error, not worth twice the states;
    /// - band 0.3–2.0 rad/s (periods 3–21 s): the sea's energy lies within 0.6–3 ω_p of the
    ///   profiles (0.39–2.1 rad/s); a lower bound keeps noise and bias, which −a/w² amplifies at
    ///   low frequency, out of the modes;
    /// - peak threshold 0.2 of the strongest peak: lower picks leakage and noise maxima;
    /// - κ = 0.1, frequency walk 10⁻⁶ (rad/s)²/s, offset walk 10⁻⁶ (m/s²)²/s, initial offset
    ///   0.05 m/s²: a mode's velocity may drift by a quarter of its amplitude a_i/w_i per period, its
    ///   frequency by 0.03 rad/s in 15 min, the offset (bias, attitude gravity leak) by 1 mm/s² in
    ///   1 s. κ and the frequency walk were tuned on profile 1 at full scale with the true
    ///   attitude (κ 0.01–1 and 10⁻⁴–10⁻⁶ tried: heave error 31 % of its motion at κ 0.1,
    ///   35–64 % below, 95–200 % above, where −a/w² amplifies the admitted noise) and are kept
    ///   for the other profiles and for test scale;
    /// - measurement variance: the accelerometer's σ = 0.01 m/s² (§8.1; "the measurement
    ///   covariance is taken from the sensor noise", §5.1.3).
    pub const FULL_SCALE: EstimatorParams = EstimatorParams {
        window: 60.0,
        search: PeakSearch { modes: 3, threshold: 0.2, band: Band { min: 0.3, max: 2.0 } },
        noise: Noise { kappa: 0.1, frequency: 1e-6, offset: 1e-6, measurement: 1e-4, initial_offset: 0.05 },
    };
}

/// Estimated surge, sway and heave (m, W) and their rates (m/s), indexed x, y, z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearEstimate {
    pub position: Vec3,
    pub rate: Vec3,
}

/// The estimator: collects the initialisation window, then filters.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearMotionEstimator {
    params: EstimatorParams,
    /// Sampling period (s).
    dt: f64,
    window: [Vec<f64>; 3],
    filters: Option<[OscillatorEkf; 3]>,
}

impl LinearMotionEstimator {
    /// An estimator for world-frame accelerations sampled every `dt` s.
    pub fn new(params: EstimatorParams, dt: f64) -> Self {
        LinearMotionEstimator { params, dt, window: Default::default(), filters: None }
    }

    /// Processes one world-frame acceleration (m/s², [`world_acceleration`]). Returns the
    /// estimate once the window is complete, `Ok(None)` while it fills, and an error when an axis
    /// has no mode in the band at the end of the window.
    pub fn update(&mut self, a_w: &Vec3) -> Result<Option<LinearEstimate>, String> {
        if let Some(filters) = &mut self.filters {
            for (filter, a) in filters.iter_mut().zip(a_w.iter()) {
                filter.step(*a, self.dt);
            }
        } else {
            for (samples, a) in self.window.iter_mut().zip(a_w.iter()) {
                samples.push(*a);
            }
            if (self.window[0].len() as f64) * self.dt < self.params.window {
                return Ok(None);
            }
            self.filters = Some(self.identify()?);
        }
        Ok(self.estimate())
    }

    /// The current estimate, once the window is complete.
    pub fn estimate(&self) -> Option<LinearEstimate> {
        let f = self.filters.as_ref()?;
        Some(LinearEstimate {
            position: Vec3::from_fn(|i, _| f[i].position()),
            rate: Vec3::from_fn(|i, _| f[i].rate()),
        })
    }

    /// FFT and peak detection on each axis' window, and its filter started from the modes.
    fn identify(&self) -> Result<[OscillatorEkf; 3], String> {
        let p = &self.params;
        // The filters' state is the one at the window's last sample; the next update predicts on.
        let samples = self.window[0].len();
        let elapsed = (samples - 1) as f64 * self.dt;
        let resolution = TAU / (samples as f64 * self.dt);
        let band = (p.search.band.min, p.search.band.max);
        let filter = |axis: usize| {
            let modes = dominant_modes(&self.window[axis], self.dt, &p.search);
            if modes.is_empty() {
                return Err(format!(
                    "no acceleration peak on axis {} within {}–{} rad/s in the {} s window",
                    ["x", "y", "z"][axis],
                    band.0,
                    band.1,
                    p.window
                ));
            }
            Ok(OscillatorEkf::from_modes(&modes, elapsed, resolution, band, &p.noise))
        };
        Ok([filter(0)?, filter(1)?, filter(2)?])
    }
}

#[cfg(test)]
mod tests;

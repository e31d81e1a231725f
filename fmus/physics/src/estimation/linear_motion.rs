//! Surge, sway and heave of the ship from the deck IMU (thesis §5.1.3, after Küchler et al. \[35\]):
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
//! wave periods. The controller runs the estimator with [`EstimatorParams::TEST_SCALE`] (feedback
//! variant "sensors, no truth"); its test-scale figures in the closed loop, with either attitude
//! filter, are in `docs/estimation.md`.
//!
//! Identification is retried: the samples are cut into consecutive windows, and an axis whose
//! window holds no mode above [`PeakSearch::floor`] (a still sea, the sensor noise alone, or an
//! axis the sea does not move) estimates zero and tries again on the next window. Once an axis
//! has its filter it keeps it: the periodic re-identification and re-initialisation of \[35\], as
//! modes appear or disappear, is not done, because the profiles are stationary and a re-started
//! filter would put a convergence transient into a two-minute test (see `docs/estimation.md`).

pub mod ekf;
pub mod peaks;

use crate::math::{Quat, Vec3};
use ekf::{Noise, OscillatorEkf};
use peaks::{dominant_modes, Band, PeakSearch};
use serde::{Deserialize, Serialize};
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EstimatorParams {
    /// Length of the identification window (s).
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
    /// - no mode floor: the preset is for a moving sea, whose full-scale modes are 0.1–1 m/s²
    ///   (the figures above, also those at test scale, are without one);
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
        search: PeakSearch { modes: 3, threshold: 0.2, floor: 0.0, band: Band { min: 0.3, max: 2.0 } },
        noise: Noise { kappa: 0.1, frequency: 1e-6, offset: 1e-6, measurement: 1e-4, initial_offset: 0.05 },
    };

    /// The choices for the test-scale campaign (the controller's default), where a run is 10 s of
    /// initialisation with the deck at rest, 2 s of fade-in and a 120 s test:
    /// - window 20 s: the first window (0–20 s) holds 8–10 s of motion, so the filters run from
    ///   20 s, 10 s into the test; the 60 s full-scale window would leave half the test without
    ///   an estimate. The resolution 2π/20 = 0.31 rad/s is half the peak frequency, so
    ///   N_m = 2 modes (the peak and one flank; a third would sit within a bin of them) and the
    ///   frequencies, which are states, converge from there;
    /// - floor 0.002 m/s²: the largest noise maximum a still deck's window shows in the band.
    ///   White noise of σ = 0.01 m/s² gives a Hann-window amplitude of RMS σ √(6/N) = 0.0005 m/s²
    ///   per bin at N = 2000 samples, and the largest of the band's padded bins stays below
    ///   four times that (0.0009 m/s² measured, `linear_motion::tests`). The test-scale heave
    ///   modes are 0.005–0.01 m/s², the natural-frequency excitation's 0.04–0.1 m/s², so a moving
    ///   axis passes and a still one is not fitted to noise;
    /// - band 0.3–6 rad/s: the waves' band of [`EstimatorParams::FULL_SCALE`] (the test-scale
    ///   motion keeps the full-scale periods) widened to the campaign's natural-frequency
    ///   excitation, surge and sway at √(g/l_p) = 3.1–5.0 rad/s for l_p = 0.4–1.0 m; above 2 rad/s
    ///   −a/w² no longer amplifies noise and bias;
    /// - threshold and noises as [`EstimatorParams::FULL_SCALE`] (the sensor is the same).
    pub const TEST_SCALE: EstimatorParams = EstimatorParams {
        window: 20.0,
        search: PeakSearch { modes: 2, threshold: 0.2, floor: 0.002, band: Band { min: 0.3, max: 6.0 } },
        noise: EstimatorParams::FULL_SCALE.noise,
    };

    pub fn validate(&self) -> Result<(), String> {
        let s = &self.search;
        if !(self.window > 0.0 && self.window.is_finite()) {
            return Err(format!("the identification window must be > 0 s, got {}", self.window));
        }
        if !(1..=MAX_MODES).contains(&s.modes) {
            return Err(format!("the EKF needs 1-{MAX_MODES} modes per axis, got {}", s.modes));
        }
        if !(s.floor >= 0.0 && s.floor.is_finite() && (0.0..=1.0).contains(&s.threshold)) {
            return Err(format!("the mode floor must be ≥ 0 m/s² and the threshold within 0-1, got {s:?}"));
        }
        if !(s.band.min > 0.0 && s.band.min < s.band.max && s.band.max.is_finite()) {
            return Err(format!("the mode band must satisfy 0 < min < max, got {:?}", s.band));
        }
        self.noise.validate()
    }
}

/// Most modes per axis: the filter's covariance grows as (3 N_m + 1)², and the thesis' profiles
/// show at most three peaks.
pub const MAX_MODES: usize = 6;

/// Estimated surge, sway and heave (m, W) and their rates (m/s), indexed x, y, z.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LinearEstimate {
    pub position: Vec3,
    pub rate: Vec3,
}

/// The estimator: collects an identification window, then filters each axis that has modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinearMotionEstimator {
    params: EstimatorParams,
    /// Sampling period (s).
    dt: f64,
    /// The current window's samples of the axes that have no filter yet.
    window: [Vec<f64>; 3],
    /// Samples in the current window.
    samples: usize,
    filters: [Option<OscillatorEkf>; 3],
}

impl LinearMotionEstimator {
    /// An estimator for world-frame accelerations sampled every `dt` s.
    pub fn new(params: EstimatorParams, dt: f64) -> Self {
        LinearMotionEstimator { params, dt, window: Default::default(), samples: 0, filters: Default::default() }
    }

    /// Processes one world-frame acceleration (m/s², [`world_acceleration`]) and returns the
    /// estimate: each axis' filter once its modes are identified, zero before (and on an axis
    /// whose windows hold no mode).
    pub fn update(&mut self, a_w: &Vec3) -> LinearEstimate {
        for axis in 0..3 {
            match &mut self.filters[axis] {
                Some(filter) => filter.step(a_w[axis], self.dt),
                None => self.window[axis].push(a_w[axis]),
            }
        }
        self.samples += 1;
        if (self.samples as f64) * self.dt >= self.params.window {
            self.identify();
        }
        self.estimate()
    }

    /// The current estimate (zero on an axis without a filter).
    pub fn estimate(&self) -> LinearEstimate {
        let axis = |i: usize, value: fn(&OscillatorEkf) -> f64| self.filters[i].as_ref().map_or(0.0, value);
        LinearEstimate {
            position: Vec3::from_fn(|i, _| axis(i, OscillatorEkf::position)),
            rate: Vec3::from_fn(|i, _| axis(i, OscillatorEkf::rate)),
        }
    }

    /// Checks an estimator that did not come from [`LinearMotionEstimator::new`] (decoded from
    /// bytes): its settings and sampling period.
    pub fn validate(&self) -> Result<(), String> {
        self.params.validate()?;
        if !(self.dt > 0.0 && self.dt.is_finite()) {
            return Err(format!("the sampling period must be > 0 s, got {}", self.dt));
        }
        Ok(())
    }

    /// Whether each axis (x, y, z) has its filter.
    pub fn identified(&self) -> [bool; 3] {
        self.filters.each_ref().map(Option::is_some)
    }

    /// FFT and peak detection on the window of each axis without a filter, which is started from
    /// the modes found (at the window's last sample; the next update predicts on); then a new
    /// window begins.
    fn identify(&mut self) {
        let p = &self.params;
        let elapsed = (self.samples - 1) as f64 * self.dt;
        let resolution = TAU / (self.samples as f64 * self.dt);
        let band = (p.search.band.min, p.search.band.max);
        for (filter, samples) in self.filters.iter_mut().zip(&mut self.window) {
            if filter.is_none() {
                let modes = dominant_modes(samples, self.dt, &p.search);
                if !modes.is_empty() {
                    *filter = Some(OscillatorEkf::from_modes(&modes, elapsed, resolution, band, &p.noise));
                }
            }
            samples.clear();
        }
        self.samples = 0;
    }
}

#[cfg(test)]
mod tests;

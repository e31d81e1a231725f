//! Tests of the §5.1.3 estimator, and its accuracy on profiles 1–3 at full and at test scale.
//!
//! Accuracy set-up: the profile's truth motion (the harmonic sum, [`HarmonicMotion`]) drives the
//! deck IMU (IMU1 at the deck centre) with the SPEC §8.1 noise at 100 Hz, σ = 0.01 m/s² and
//! 0.0035 rad/s, seed 1 — the same Yost sensor at both scales, since a full-scale installation of
//! the thesis' hardware would carry it; the attitude comes from the complementary filter (Table
//! 5.1) aligned on the first sample; the world-frame acceleration of eq. 5.40 feeds the estimator
//! ([`EstimatorParams::FULL_SCALE`] at both scales). Errors are RMS over [`SETTLED`]–[`END`] s
//! against the truth, whose mean over that span is removed from the positions (a constant
//! offset, v(t) of eq. 5.46, is not observable from accelerations). `cargo test -p physics
//! --release linear_motion -- --show-output` prints the table.

use super::*;
use crate::estimation::complementary::{ComplementaryFilter, FilterParams};
use crate::imu::{readings, ImuMotion, ImuParams};
use crate::math::STANDARD_GRAVITY;
use crate::motion::{HEAVE, SURGE, SWAY};
use crate::platform::kinematics::PlatformGeometry;
use crate::ship::motion::HarmonicMotion;
use crate::ship::profiles::{test_scale, ProfileId};
use crate::ship::rao::Hull;
use peaks::Mode;

const DT: f64 = 0.01;
/// Start of the error statistics (s): the 60 s window and 30 s of filter convergence.
const SETTLED: f64 = 90.0;
/// End of each run (s).
const END: f64 = 300.0;

fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    (sum / n as f64).sqrt()
}

fn search(modes: usize) -> PeakSearch {
    PeakSearch { modes, threshold: 0.2, floor: 0.0, band: Band { min: 0.3, max: 2.0 } }
}

#[test]
fn world_acceleration_removes_gravity_and_rotates_to_the_world_frame() {
    // A sensor rolled 90° about x (its y axis pointing down) at rest, accelerating 1 m/s² north:
    // the specific force in S is Rᵀ (a + (0, 0, −g)).
    let q = crate::math::rot_x(std::f64::consts::FRAC_PI_2);
    let a = Vec3::new(1.0, 0.0, 0.0);
    let f_s = q.inverse_transform_vector(&(a + Vec3::new(0.0, 0.0, -STANDARD_GRAVITY)));
    assert!((f_s - Vec3::new(1.0, -STANDARD_GRAVITY, 0.0)).norm() < 1e-12, "{f_s}");
    let back = world_acceleration(&q, &f_s, STANDARD_GRAVITY);
    assert!((back - a).norm() < 1e-12, "{back}");
}

#[test]
fn fft_peak_detection_finds_two_sines_within_one_bin() {
    // 0.11 Hz at 1.0 m/s² and 0.17 Hz at 0.5 m/s² (off the 1/60 Hz bins) over 60 s at 100 Hz.
    let (w1, w2) = (TAU * 0.11, TAU * 0.17);
    let signal: Vec<f64> =
        (0..6000).map(|k| k as f64 * DT).map(|t| (w1 * t + 0.3).cos() + 0.5 * (w2 * t - 1.0).cos()).collect();
    let modes = dominant_modes(&signal, DT, &search(3));
    let bin = TAU / 60.0;
    assert_eq!(modes.len(), 2, "{modes:?}");
    assert!((modes[0].omega - w1).abs() < bin, "{modes:?}");
    assert!((modes[1].omega - w2).abs() < bin, "{modes:?}");
    // The Hann coherent gain is removed: the amplitudes come out within the taper's scalloping
    // loss (at most 15 % for a tone between bins; the padding shrinks it to a few %).
    assert!((modes[0].amplitude - 1.0).abs() < 0.05 && (modes[1].amplitude - 0.5).abs() < 0.03, "{modes:?}");
}

#[test]
fn peak_detection_drops_peaks_below_the_threshold_and_outside_the_band() {
    // 0.11 Hz strong, 0.17 Hz at 10 % (below the 0.2 threshold), 0.4 Hz (2.5 rad/s, out of band).
    let signal: Vec<f64> = (0..6000)
        .map(|k| k as f64 * DT)
        .map(|t| (TAU * 0.11 * t).cos() + 0.1 * (TAU * 0.17 * t).cos() + 2.0 * (TAU * 0.4 * t).cos())
        .collect();
    let modes = dominant_modes(&signal, DT, &search(3));
    assert_eq!(modes.len(), 1, "{modes:?}");
    assert!((modes[0].omega - TAU * 0.11).abs() < TAU / 60.0, "{modes:?}");
}

/// Filter noise for an exact two-mode signal: the model has no error, so a small process noise
/// (κ = 0.01) and a measurement variance far below any sensor's.
const NOISE_FREE: Noise = Noise { kappa: 0.01, measurement: 1e-8, ..EstimatorParams::FULL_SCALE.noise };

#[test]
fn a_window_of_sensor_noise_has_no_mode_above_the_floor() {
    // 20 s of the SPEC §8.1 accelerometer noise (σ = 0.01 m/s²) on a still deck: its spectrum
    // has maxima in the band, which only the floor keeps from becoming modes.
    let imu = ImuParams::DEFAULT;
    let still =
        ImuMotion { orientation: Quat::identity(), angular_velocity: Vec3::zeros(), acceleration: Vec3::zeros() };
    let heave: Vec<f64> =
        (0..2000).map(|k| world_acceleration(&Quat::identity(), &readings(&imu, &still, k).acc, imu.g).z).collect();
    let floor = EstimatorParams::TEST_SCALE.search;
    let largest = dominant_modes(&heave, DT, &PeakSearch { floor: 0.0, ..floor });
    println!("largest noise mode of a still 20 s window: {:.5} m/s²", largest[0].amplitude);
    assert!(largest[0].amplitude > 2e-4 && largest[0].amplitude < 0.5 * floor.floor, "{largest:?}");
    assert_eq!(dominant_modes(&heave, DT, &floor), Vec::new());
}

#[test]
fn an_axis_without_motion_estimates_zero_until_a_window_shows_its_modes() {
    // Heave at rest for the first 20 s window, then a 0.7 rad/s, 1 m/s² oscillation: the first
    // window identifies nothing (estimate zero), the second starts the filter at 40 s, which
    // then tracks the motion; surge and sway, never moving, stay at zero.
    let w = 0.7;
    let acc = |t: f64| if t < 20.0 { 0.0 } else { -(w * (t - 20.0)).sin() };
    let mut estimator =
        LinearMotionEstimator::new(EstimatorParams { noise: NOISE_FREE, ..EstimatorParams::TEST_SCALE }, DT);
    let (mut errors, mut identified_at) = (Vec::new(), None);
    for k in 1..=12000 {
        let t = k as f64 * DT;
        let e = estimator.update(&Vec3::new(0.0, 0.0, acc(t)));
        if identified_at.is_none() && estimator.identified()[2] {
            identified_at = Some(t);
        }
        assert_eq!((e.position.x, e.position.y, e.rate.x), (0.0, 0.0, 0.0));
        if t >= 60.0 {
            errors.push(e.position.z - (w * (t - 20.0)).sin() / (w * w));
        }
        if t < 40.0 - 1e-9 {
            assert_eq!(e.position.z, 0.0, "t = {t}");
        }
    }
    assert_eq!(estimator.identified(), [false, false, true]);
    assert!((identified_at.unwrap() - 40.0).abs() < 1e-9, "{identified_at:?}");
    // The motion's amplitude is 1/w² = 2.04 m; the filter tracks it to a millimetre.
    assert!(rms(errors.into_iter()) < 1e-3);
}

/// Position (m) and rate (m/s) RMS errors of a filter on a noise-free two-mode coordinate.
fn noise_free_errors() -> (f64, f64) {
    let (w1, w2) = (0.7, 1.1);
    let truth = |t: f64| {
        let (p1, p2) = (w1 * t + 0.4, w2 * t - 1.2);
        (
            1.0 * p1.cos() + 0.3 * p2.cos(),
            -w1 * p1.sin() - 0.3 * w2 * p2.sin(),
            -w1 * w1 * p1.cos() - 0.3 * w2 * w2 * p2.cos(),
        )
    };
    let window: Vec<f64> = (0..6000).map(|k| truth(k as f64 * DT).2).collect();
    let modes = dominant_modes(&window, DT, &search(2));
    let mut ekf = OscillatorEkf::from_modes(&modes, 59.99, TAU / 60.0, (0.3, 2.0), &NOISE_FREE);
    let mut errors = Vec::new();
    for k in 6000..=30000 {
        let t = k as f64 * DT;
        let (pos, vel, acc) = truth(t);
        ekf.step(acc, DT);
        if t >= SETTLED {
            errors.push((ekf.position() - pos, ekf.rate() - vel));
        }
    }
    (rms(errors.iter().map(|e| e.0)), rms(errors.iter().map(|e| e.1)))
}

#[test]
fn ekf_tracks_a_noise_free_two_mode_motion() {
    // Amplitudes 1 m and 0.3 m: an error of a millimetre means the oscillators lock on both
    // modes (a wrong sign of w² in the model or Jacobian diverges to metres).
    let (pos, rate) = noise_free_errors();
    println!("noise-free two-mode motion: RMS error {pos:.2e} m, {rate:.2e} m/s");
    assert!(pos < 1e-3 && rate < 1e-3, "position {pos} m, rate {rate} m/s");
}

#[test]
fn ekf_frequencies_converge_to_the_true_eigenfrequencies() {
    let (w1, w2) = (0.7, 1.1);
    let window: Vec<f64> =
        (0..6000).map(|k| k as f64 * DT).map(|t| -w1 * w1 * (w1 * t).cos() - 0.3 * w2 * w2 * (w2 * t).cos()).collect();
    let modes: Vec<Mode> = dominant_modes(&window, DT, &search(2));
    let mut ekf = OscillatorEkf::from_modes(&modes, 59.99, TAU / 60.0, (0.3, 2.0), &NOISE_FREE);
    for k in 6000..=30000 {
        let t = k as f64 * DT;
        ekf.step(-w1 * w1 * (w1 * t).cos() - 0.3 * w2 * w2 * (w2 * t).cos(), DT);
    }
    let w = ekf.frequencies();
    assert!((w[0] - w1).abs() < 1e-3 && (w[1] - w2).abs() < 1e-3, "{w:?}");
}

/// RMS of the truth (mean removed) and of the position and rate errors per axis (x, y, z).
#[derive(Debug, Clone, Copy)]
struct Figures {
    truth_pos: [f64; 3],
    truth_rate: [f64; 3],
    err_pos: [f64; 3],
    err_rate: [f64; 3],
}

impl Figures {
    /// Position error relative to the motion, per axis.
    fn relative_pos(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| self.err_pos[i] / self.truth_pos[i])
    }

    fn relative_rate(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| self.err_rate[i] / self.truth_rate[i])
    }

    fn print(&self, label: &str) {
        let (rp, rr) = (self.relative_pos(), self.relative_rate());
        for (i, name) in ["surge", "sway", "heave"].iter().enumerate().filter(|(i, _)| self.truth_pos[*i] > MOVING) {
            println!(
                "{label:<22} {name:<6} motion {:9.4} m {:9.4} m/s | error {:9.4} m ({:6.1} %) {:9.4} m/s ({:6.1} %)",
                self.truth_pos[i],
                self.truth_rate[i],
                self.err_pos[i],
                100.0 * rp[i],
                self.err_rate[i],
                100.0 * rr[i]
            );
        }
    }
}

/// Where the attitude of eq. 5.40 comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Attitude {
    /// The complementary filter on the IMU (the estimator as the controller would run it).
    Estimated,
    /// The true attitude: isolates the EKF from the attitude error's gravity leak.
    Truth,
}

/// The estimator on `motion` with the SPEC §8.1 deck IMU (see the module documentation).
fn measure(motion: &HarmonicMotion, source: Attitude) -> Figures {
    let imu = ImuParams::DEFAULT;
    let mut attitude = ComplementaryFilter::new(FilterParams::SHIP);
    let mut estimator = LinearMotionEstimator::new(EstimatorParams::FULL_SCALE, DT);
    let mut samples = Vec::new();
    for k in 0..=(END / DT).round() as u64 {
        let t = k as f64 * DT;
        let ship = motion.sample(t).to_ship_motion();
        let truth = ImuMotion { orientation: ship.attitude(), angular_velocity: ship.omega, acceleration: ship.acc };
        let r = readings(&imu, &truth, k);
        if k == 0 {
            attitude.align(&r.acc, &r.mag);
        }
        let estimated = attitude.update(&r.gyro, &r.acc, &r.mag, DT);
        let q = if source == Attitude::Truth { truth.orientation } else { estimated };
        let estimate = estimator.update(&world_acceleration(&q, &r.acc, imu.g));
        if t >= SETTLED {
            samples.push((estimate, ship.pos, ship.vel));
        }
    }
    let mean = |i: usize| samples.iter().map(|s| s.1[i]).sum::<f64>() / samples.len() as f64;
    let mut f = Figures { truth_pos: [0.0; 3], truth_rate: [0.0; 3], err_pos: [0.0; 3], err_rate: [0.0; 3] };
    for i in [SURGE, SWAY, HEAVE] {
        let m = mean(i);
        f.truth_pos[i] = rms(samples.iter().map(|s| s.1[i] - m));
        f.truth_rate[i] = rms(samples.iter().map(|s| s.2[i]));
        f.err_pos[i] = rms(samples.iter().map(|s| s.0.position[i] - (s.1[i] - m)));
        f.err_rate[i] = rms(samples.iter().map(|s| s.0.rate[i] - s.2[i]));
    }
    f
}

fn full_scale(id: ProfileId) -> HarmonicMotion {
    let p = id.profile();
    p.full_scale(&Hull::default(), p.seed)
}

/// Truth position RMS (m) above which an axis counts as moving (beam and head seas leave surge or
/// sway still).
const MOVING: f64 = 1e-4;

#[test]
fn full_scale_profiles_are_estimated_to_their_measured_accuracy() {
    for id in ProfileId::ALL {
        let motion = full_scale(id);
        let truth_attitude = measure(&motion, Attitude::Truth);
        let estimated = measure(&motion, Attitude::Estimated);
        truth_attitude.print(&format!("full scale {}, true q", id.profile().number));
        estimated.print(&format!("full scale {}, CF q", id.profile().number));
        for i in (0..3).filter(|&i| truth_attitude.truth_pos[i] > MOVING) {
            // The EKF alone, against the measured errors with a margin of about 3 % of the bound
            // (the runs are deterministic: seeded noise, fixed profiles): position at most 48.6 %
            // of the motion (profile 2 sway), rate 39.6 % (profile 1 surge); a filter that
            // outputs zero scores 100 %. The errors are this large because each axis carries
            // N_m = 3 undamped oscillators fitted to one 60 s window (eqs. 5.46–5.52), while the
            // sea is 200 components: what the three modes leave out stays in the error. The
            // bounds hold for these seeded realisations, not for the sea state: another draw of
            // the same sea (the two uniforms per component swapped) gives 61 % for profile 2 sway.
            let (pos, rate) = (truth_attitude.relative_pos()[i], truth_attitude.relative_rate()[i]);
            assert!(pos < 0.50 && rate < 0.41, "{id:?} axis {i}, true attitude: {pos} {rate}");
        }
        // Heave with the estimated attitude: a tilt error leaks g(1 − cos ε) ≈ 0 into z, so heave
        // keeps the true attitude's figures (measured at most 43.4 % and 35.9 %, profile 3).
        assert!(estimated.relative_pos()[2] < 0.45 && estimated.relative_rate()[2] < 0.37, "{id:?}: {estimated:?}");
        // Surge and sway with the estimated attitude are unusable: with ᾱ_a = 0.05 per 10 ms
        // sample (Table 5.1) the complementary filter's "down" follows the specific force within
        // ~0.2 s, far faster than the waves, so eq. 5.40 cancels the horizontal acceleration.
        for i in (0..2).filter(|&i| estimated.truth_pos[i] > MOVING) {
            assert!(estimated.relative_pos()[i] > 0.9, "{id:?} axis {i}: {estimated:?}");
        }
    }
}

#[test]
fn test_scale_profiles_are_estimated_worse_than_full_scale() {
    for id in ProfileId::ALL {
        let full = full_scale(id);
        let scaled = test_scale(&full, &PlatformGeometry::default()).unwrap();
        let (at_full, at_test) = (measure(&full, Attitude::Truth), measure(&scaled.motion, Attitude::Truth));
        at_test.print(&format!("test scale {}, true q", id.profile().number));
        measure(&scaled.motion, Attitude::Estimated).print(&format!("test scale {}, CF q", id.profile().number));
        // The thesis' prediction (§5.1.3): the signal shrinks by s (0.01–0.07), the sensor noise
        // does not. Heave, which every profile moves, is estimated clearly worse relative to its
        // motion even with the true attitude (measured: 1.6–1.7 times the full-scale error).
        let (full_heave, test_heave) = (at_full.relative_pos()[2], at_test.relative_pos()[2]);
        assert!(test_heave > 1.3 * full_heave, "{id:?}: heave {test_heave} at test scale, {full_heave} at full scale");
    }
}

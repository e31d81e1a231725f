//! At-rest calibration of the IMUs during the initialisation before `active_from` (beyond the
//! thesis: its §8.3 lists sensor biases as future work, and §3.5.4 assumes that "the effects of
//! sensor biases are effectively removed following an approximation with low-pass filters during
//! an initialization period").
//!
//! - Gyro biases ([`GyroBias`]): an IMU at rest reads its rate bias plus zero-mean noise, so the
//!   mean reading over the initialisation is the bias, to σ/√N (0.0035 rad/s over 1000 samples:
//!   1.1·10⁻⁴ rad/s = 0.006 °/s against data-sheet biases up to 0.3 °/s). The mean learnt so far is
//!   subtracted from every reading, during the initialisation too, so the attitude estimate has
//!   converged on the corrected rates by the time the controller acts; from `active_from` on it is
//!   held. Assumes both IMUs at rest during the initialisation: the deck in still water or on a
//!   motion platform that has not started, the load held (the campaign's 10 s hold). Any rotation
//!   during it is learnt as bias.
//! - Accelerometer biases are not calibrated: at rest a bias b is indistinguishable from a tilt of
//!   about b/g (10 mg ≈ 0.57°) without an independent reference of the true attitude, which neither
//!   the deck (its level is not known, §3.5.4) nor the load (held at an unknown initial angle)
//!   provides. It appears as a constant angle offset, not as swing.
//! - The load's heading: the thesis removes the deck IMU1's mean yaw from both estimates (§7.2.1),
//!   which cannot remove a difference between the fields the two IMUs see. Referencing IMU2 to its
//!   own mean yaw instead ([`MeanAngle`], the controller's `load_heading`) removes such a
//!   difference, assuming the load faces the deck's heading during the initialisation (no twist
//!   about the cable, as in the pendulum model). The mean, not the §5.3 low-pass: at 0.005 Hz
//!   started on the first sample, a low-pass over a 10 s initialisation still holds 73 % of that
//!   one sample's magnetometer noise (the thesis learnt over several minutes).

use crate::math::Vec3;
use serde::{Deserialize, Serialize};

/// The running mean of one IMU's gyro readings (rad/s, sensor frame) over the initialisation.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct GyroBias {
    sum: Vec3,
    samples: u64,
}

impl GyroBias {
    /// The learnt bias (rad/s, sensor frame): the mean of the readings learnt, 0 before any.
    pub fn bias(&self) -> Vec3 {
        if self.samples == 0 {
            Vec3::zeros()
        } else {
            self.sum / self.samples as f64
        }
    }

    /// The reading `gyro` (rad/s) less the bias, after adding it to the mean while `learning`
    /// (the IMU at rest, before `active_from`).
    pub fn correct(&mut self, gyro: &Vec3, learning: bool) -> Vec3 {
        if learning {
            self.sum += gyro;
            self.samples += 1;
        }
        gyro - self.bias()
    }
}

/// The circular mean of an angle (rad) over the initialisation: the direction of the summed unit
/// vectors, so headings either side of ±π average correctly.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct MeanAngle {
    sin: f64,
    cos: f64,
}

impl MeanAngle {
    pub fn learn(&mut self, angle: f64) {
        let (sin, cos) = angle.sin_cos();
        self.sin += sin;
        self.cos += cos;
    }

    /// The mean angle (rad, within ±π); 0 before any sample.
    pub fn value(&self) -> f64 {
        self.sin.atan2(self.cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::noise::standard_normal;

    #[test]
    fn the_mean_of_noisy_readings_at_rest_is_the_bias_within_the_noise_over_root_n() {
        // 0.3 °/s on x (the data-sheet limit), −0.2 °/s on z; noise σ = 0.0035 rad/s; 1000 samples
        // (10 s at 100 Hz): the error is σ/√1000 = 1.1e-4 rad/s per axis, so 4e-4 is > 3.5 σ.
        let bias = Vec3::new(0.3f64.to_radians(), 0.0, (-0.2f64).to_radians());
        let mut calibration = GyroBias::default();
        for k in 0..1000 {
            let noise =
                Vec3::new(standard_normal(7, 0, k), standard_normal(7, 1, k), standard_normal(7, 2, k)) * 0.0035;
            calibration.correct(&(bias + noise), true);
        }
        let error = calibration.bias() - bias;
        assert!(error.amax() < 4e-4, "bias error {error:?} rad/s");
        // Held once learning stops: a rotation after it is not learnt, only corrected.
        let rate = Vec3::new(0.5, -0.1, 0.2);
        let corrected = calibration.correct(&(rate + bias), false);
        assert!((corrected - rate).amax() < 4e-4, "{corrected:?}");
        assert_eq!(calibration.bias(), bias + error);
    }

    #[test]
    fn nothing_learnt_removes_nothing() {
        let mut calibration = GyroBias::default();
        let rate = Vec3::new(0.01, 0.02, 0.03);
        assert_eq!(calibration.correct(&rate, false), rate);
    }

    #[test]
    fn the_mean_heading_averages_across_plus_minus_pi() {
        let mut heading = MeanAngle::default();
        assert_eq!(heading.value(), 0.0);
        // 179° and −177° average to −179°, not to the 1° an arithmetic mean gives.
        heading.learn(179f64.to_radians());
        heading.learn((-177f64).to_radians());
        assert!((heading.value() - (-179f64).to_radians()).abs() < 1e-12, "{}", heading.value().to_degrees());
    }
}

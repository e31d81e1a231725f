//! The attitude estimator a controller holds for each IMU: the thesis' complementary filter
//! (§5.1.1) or Madgwick's gradient-descent filter, behind one interface (same inputs: gyro,
//! specific force, magnetometer and the sample interval; same output: the orientation W←S).

use crate::estimation::complementary::{ComplementaryFilter, FilterParams};
use crate::estimation::madgwick::{MadgwickFilter, MadgwickParams};
use crate::math::{Quat, Vec3};
use serde::{Deserialize, Serialize};

/// Which estimator to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum AttitudeFilterKind {
    /// The thesis' complementary filter (eqs. 5.8–5.28).
    Complementary,
    /// Madgwick's gradient-descent MARG filter (2010 report, eqs. 11–44).
    Madgwick,
}

/// One IMU's attitude estimator and its state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum AttitudeFilter {
    Complementary(ComplementaryFilter),
    Madgwick(MadgwickFilter),
}

impl AttitudeFilter {
    /// A filter of the given kind at the identity, with that kind's parameters.
    pub fn new(kind: AttitudeFilterKind, complementary: FilterParams, madgwick: MadgwickParams) -> Self {
        match kind {
            AttitudeFilterKind::Complementary => AttitudeFilter::Complementary(ComplementaryFilter::new(complementary)),
            AttitudeFilterKind::Madgwick => AttitudeFilter::Madgwick(MadgwickFilter::new(madgwick)),
        }
    }

    /// The current estimate W←S.
    pub fn orientation(&self) -> Quat {
        match self {
            AttitudeFilter::Complementary(f) => f.orientation(),
            AttitudeFilter::Madgwick(f) => f.orientation(),
        }
    }

    /// Starts the estimate from one accelerometer (m/s²) and magnetometer sample.
    pub fn align(&mut self, acc: &Vec3, mag: &Vec3) {
        match self {
            AttitudeFilter::Complementary(f) => f.align(acc, mag),
            AttitudeFilter::Madgwick(f) => f.align(acc, mag),
        }
    }

    /// Processes one sample taken `dt` (s) after the previous one: gyro (rad/s), specific force
    /// (m/s²) and magnetometer, in the sensor frame. Returns the new estimate W←S.
    pub fn update(&mut self, gyro: &Vec3, acc: &Vec3, mag: &Vec3, dt: f64) -> Quat {
        match self {
            AttitudeFilter::Complementary(f) => f.update(gyro, acc, mag, dt),
            AttitudeFilter::Madgwick(f) => f.update(gyro, acc, mag, dt),
        }
    }
}

//! The platform's ship motion sources (SPEC §4.1 `profile`): still water, the test-scale profiles
//! 1–3, a sinusoid in surge and sway, and a motion file.

use super::motion::HarmonicMotion;
use super::profiles::{profile, test_scale};
use super::rao::Hull;
use super::table::{resolve_path, MotionTable};
use crate::motion::{AxisMotion, DeckMotion, SURGE, SWAY};
use crate::platform::kinematics::PlatformGeometry;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Parameters that choose and shape the source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SourceConfig {
    /// 0 still water, 1–3 test-scale profiles, 4 sine, 5 file.
    pub profile: i32,
    /// Seed of the profile's random phases; 0 keeps the profile's own (1, 2, 3).
    pub seed: u64,
    /// Sine frequency (rad/s) and amplitude (m) of profile 4.
    pub sine_omega: f64,
    pub sine_amplitude: f64,
    /// Motion file of profile 5 (relative paths are resolved against the resources folder).
    pub motion_file: String,
}

/// A deck motion as a function of time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum MotionSource {
    Still,
    /// A test-scale profile and its scale factor on the translations.
    Profile {
        motion: HarmonicMotion,
        scale: f64,
    },
    /// Surge = sway = A sin(ω t).
    Sine {
        omega: f64,
        amplitude: f64,
    },
    File(MotionTable),
}

impl MotionSource {
    /// Builds the source `config` describes. The profiles' test scale is computed here (it
    /// needs the platform's kinematics); a motion file is read here.
    pub fn build(
        config: &SourceConfig,
        resource_dir: Option<&Path>,
        hull: &Hull,
        geom: &PlatformGeometry,
    ) -> Result<MotionSource, String> {
        match config.profile {
            0 => Ok(MotionSource::Still),
            n @ 1..=3 => {
                let p = profile(n).expect("profiles 1-3 exist");
                let seed = if config.seed == 0 { p.seed } else { config.seed };
                let scaled = test_scale(&p.full_scale(hull, seed), geom).map_err(|e| format!("profile {n}: {e}"))?;
                Ok(MotionSource::Profile { motion: scaled.motion, scale: scaled.scale })
            }
            4 => {
                if !(config.sine_omega.is_finite() && config.sine_amplitude.is_finite()) {
                    return Err("sine_omega and sine_amplitude must be finite".into());
                }
                Ok(MotionSource::Sine { omega: config.sine_omega, amplitude: config.sine_amplitude })
            }
            5 => {
                if config.motion_file.trim().is_empty() {
                    return Err("profile 5 reads a motion file, but motion_file is empty".into());
                }
                MotionTable::load(&resolve_path(&config.motion_file, resource_dir)).map(MotionSource::File)
            }
            other => Err(format!("profile must be 0-5, got {other}")),
        }
    }

    /// The deck motion at time `t` (s), ship frame heading north.
    pub fn sample(&self, t: f64) -> DeckMotion {
        match self {
            MotionSource::Still => DeckMotion::default(),
            MotionSource::Profile { motion, .. } => motion.sample(t),
            MotionSource::Sine { omega, amplitude } => {
                let (s, c) = (omega * t).sin_cos();
                let axis =
                    AxisMotion { pos: amplitude * s, vel: amplitude * omega * c, acc: -amplitude * omega * omega * s };
                let mut m = DeckMotion::default();
                m.dof[SURGE] = axis;
                m.dof[SWAY] = axis;
                m
            }
            MotionSource::File(table) => table.sample(t),
        }
    }
}

#[cfg(test)]
mod tests;

//! The platform's ship motion sources (SPEC §4.1 `profile`): still water, the profiles 1–3 at
//! test scale (thesis §3.3) or at full scale, a sinusoid in surge and sway, and a motion file.

use super::phasors::PhasorSum;
use super::profiles::{test_scale, ProfileId};
use super::rao::Hull;
use super::table::{resolve_path, MotionTable};
use crate::motion::{AxisMotion, DeckMotion, SURGE, SWAY};
use crate::platform::kinematics::PlatformGeometry;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Which deck motion the source produces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SourceKind {
    /// Still water: the deck rests at the zero pose.
    Still,
    /// A test-scale sea-state profile (thesis §3.3).
    Sea(ProfileId),
    /// Surge = sway = A sin(ω t).
    Sine,
    /// Motion read from a CSV file.
    File,
}

/// Whether the ship motion is brought to the motion platform's test scale or is the vessel's own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum MotionScale {
    /// Profiles 1–3 converted to test scale ([`test_scale`], thesis §3.3): translations scaled so
    /// the platform can follow them, angles unscaled, yaw zero, centred on the 120 s window mean.
    #[default]
    Test,
    /// Profiles 1–3 as the full-scale response of the ~120 m vessel ([`Profile::full_scale`]):
    /// every degree of freedom unscaled and uncentred, yaw included (the hull's yaw response is
    /// zero, see [`super::rao`]). For a crane model at full scale; the platform cannot follow it.
    ///
    /// [`Profile::full_scale`]: super::profiles::Profile::full_scale
    Full,
}

/// Default sine frequency √(g/0.7 m) (rad/s): the pendulum's natural frequency at l_p = 0.7 m
/// (tests 084–088 and 092–096).
pub const SINE_OMEGA: f64 = 3.742926662386;
/// Default sine amplitude (m) of surge and sway (tests 084–096).
pub const SINE_AMPLITUDE: f64 = 0.004;

/// Parameters that choose and shape the source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SourceConfig {
    pub kind: SourceKind,
    /// The scale of profiles 1–3; still water, the sine and the motion file are the same at both
    /// (given as they are, never scaled).
    pub scale: MotionScale,
    /// Seed of the profile's random phases; `None` keeps the profile's own (1, 2, 3).
    pub seed: Option<u64>,
    /// Sine frequency (rad/s) and amplitude (m) of [`SourceKind::Sine`].
    pub sine_omega: f64,
    pub sine_amplitude: f64,
    /// Motion file of [`SourceKind::File`] (relative paths are resolved against the resources
    /// folder).
    pub motion_file: String,
}

impl SourceConfig {
    /// The default source: still water.
    pub const DEFAULT_KIND: SourceKind = SourceKind::Still;
}

impl Default for SourceConfig {
    /// Still water at test scale, the profiles' own seeds, the sine of tests 084–096, no file.
    fn default() -> Self {
        SourceConfig {
            kind: Self::DEFAULT_KIND,
            scale: MotionScale::Test,
            seed: None,
            sine_omega: SINE_OMEGA,
            sine_amplitude: SINE_AMPLITUDE,
            motion_file: String::new(),
        }
    }
}

/// A deck motion as a function of time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum MotionSource {
    Still,
    /// A profile at test or full scale (sampled by phasor rotation on the grid) and its scale
    /// factor on the translations (1 at full scale).
    Profile {
        motion: PhasorSum,
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
    /// needs the platform's kinematics); at full scale the profile is the hull's response itself.
    /// A motion file is read here.
    pub fn build(
        config: &SourceConfig,
        resource_dir: Option<&Path>,
        hull: &Hull,
        geom: &PlatformGeometry,
    ) -> Result<MotionSource, String> {
        match config.kind {
            SourceKind::Still => Ok(MotionSource::Still),
            SourceKind::Sea(id) => {
                let p = id.profile();
                let seed = config.seed.unwrap_or(p.seed);
                let full = p.full_scale(hull, seed);
                if config.scale == MotionScale::Full {
                    return Ok(MotionSource::Profile { motion: PhasorSum::new(full), scale: 1.0 });
                }
                let scaled = test_scale(&full, geom).map_err(|e| format!("profile {}: {e}", p.number))?;
                Ok(MotionSource::Profile { motion: PhasorSum::new(scaled.motion), scale: scaled.scale })
            }
            SourceKind::Sine => {
                if !(config.sine_omega.is_finite() && config.sine_amplitude.is_finite()) {
                    return Err("sine_omega and sine_amplitude must be finite".into());
                }
                Ok(MotionSource::Sine { omega: config.sine_omega, amplitude: config.sine_amplitude })
            }
            SourceKind::File => {
                if config.motion_file.trim().is_empty() {
                    return Err("the source reads a motion file, but motion_file is empty".into());
                }
                MotionTable::load(&resolve_path(&config.motion_file, resource_dir)).map(MotionSource::File)
            }
        }
    }

    /// The deck motion at time `t` (s), ship frame heading north. Mutable only for the profiles'
    /// phasor cursor: the result is a function of `t` alone.
    pub fn sample(&mut self, t: f64) -> DeckMotion {
        match self {
            MotionSource::Still => DeckMotion::default(),
            MotionSource::Profile { motion, .. } => motion.sample(t),
            &mut MotionSource::Sine { omega, amplitude } => {
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

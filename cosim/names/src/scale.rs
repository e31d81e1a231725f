//! The two scales the crane is simulated at.

use serde::Serialize;

use crate::names::{CraneNames, FULL_SCALE, TEST_SCALE};

/// Which crane: the thesis' test-scale rig or the full-scale hydraulic offshore crane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scale {
    /// The thesis' test-scale rig.
    #[default]
    Test,
    /// The full-scale hydraulic knuckle-boom crane.
    Full,
}

impl Scale {
    /// Both scales, test scale first.
    pub const ALL: [Scale; 2] = [Scale::Test, Scale::Full];

    pub fn is_test(&self) -> bool {
        *self == Scale::Test
    }

    /// The closed-loop system file of `systems/` at this scale.
    pub fn system_file(self) -> &'static str {
        match self {
            Scale::Test => "closed_loop.json",
            Scale::Full => "full_scale_ahc.json",
        }
    }

    /// The names of that system's instances and variables.
    pub fn names(self) -> &'static CraneNames {
        match self {
            Scale::Test => &TEST_SCALE,
            Scale::Full => &FULL_SCALE,
        }
    }

    /// "test" or "full", as the command line's `--scale` and Python's `scale=` spell it.
    pub fn key(self) -> &'static str {
        match self {
            Scale::Test => "test",
            Scale::Full => "full",
        }
    }

    /// "test scale" or "full scale", for reports.
    pub fn label(self) -> &'static str {
        match self {
            Scale::Test => "test scale",
            Scale::Full => "full scale",
        }
    }
}

//! The two scales the Chapter 7 matrix runs at: the thesis' test-scale rig
//! (`systems/closed_loop.json`) and the full-scale hydraulic offshore crane under its control
//! software (`systems/full_scale_ahc.json`, docs/full-scale.md).
//!
//! The full-scale matrix maps the thesis' tests by Froude similarity with the length scale
//! λ = [`LENGTH_SCALE`]: rope lengths and the natural-frequency excitation's amplitude ×λ, angles
//! and the ship motion profiles as they are (the platform at full scale gives the 120 m vessel's
//! own motion), the natural frequencies √(g/l) of the scaled lengths. The thesis' 0.40–1.00 m
//! become 10–25 m of rope, inside the 5–30 m a crane of this class lifts on.

use cosim_engine::closed_loop::FullScaleNames;
use crane_metrics::run::{Traces, TEST_SCALE_TRACES};
use serde::Serialize;

/// Full-scale lengths per test-scale length (Froude scaling: times scale by √λ = 5).
pub const LENGTH_SCALE: f64 = 25.0;

/// Which crane a campaign runs.
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
    pub fn is_test(&self) -> bool {
        *self == Scale::Test
    }

    /// The system file of `systems/` the scenarios start from.
    pub fn system_file(self) -> &'static str {
        match self {
            Scale::Test => "closed_loop.json",
            Scale::Full => "full_scale_ahc.json",
        }
    }

    /// A length of the thesis' matrix (m) at this scale.
    pub fn length(self, test_scale: f64) -> f64 {
        match self {
            Scale::Test => test_scale,
            Scale::Full => test_scale * LENGTH_SCALE,
        }
    }

    /// The load, tip and set-point columns.
    pub fn traces(self) -> Traces {
        match self {
            Scale::Test => TEST_SCALE_TRACES,
            Scale::Full => {
                let n = FullScaleNames::FULL_SCALE;
                Traces { load: n.load, tip: n.tip, setpoint: n.setpoint }
            }
        }
    }

    /// The variables a campaign run records: load, tip and set-point.
    pub fn recorded(self) -> [&'static str; 9] {
        let Traces { load, tip, setpoint } = self.traces();
        let [l, t, s] = [load.axes, tip.axes, setpoint.axes];
        [l[0], l[1], l[2], t[0], t[1], t[2], s[0], s[1], s[2]]
    }

    /// "full scale" or "test scale", for reports.
    pub fn label(self) -> &'static str {
        match self {
            Scale::Test => "test scale",
            Scale::Full => "full scale",
        }
    }
}

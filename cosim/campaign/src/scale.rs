//! The two scales the Chapter 7 matrix runs at: the thesis' test-scale rig
//! (`systems/closed_loop.json`) and the full-scale hydraulic offshore crane under its control
//! software (`systems/full_scale_ahc.json`, docs/full-scale.md).
//!
//! The full-scale matrix maps the thesis' tests by Froude similarity with the length scale
//! λ = [`LENGTH_SCALE`]: rope lengths and the natural-frequency excitation's amplitude ×λ, angles
//! and the ship motion profiles as they are (the platform at full scale gives the 120 m vessel's
//! own motion), the natural frequencies √(g/l) of the scaled lengths. The thesis' 0.40–1.00 m
//! become 10–25 m of rope, inside the 5–30 m a crane of this class lifts on.

use crane_metrics::run::Traces;

pub use crane_names::Scale;

/// Full-scale lengths per test-scale length (Froude scaling: times scale by √λ = 5).
pub const LENGTH_SCALE: f64 = 25.0;

/// What the campaign reads of a scale: the matrix's lengths at it and the traces its runs record.
pub trait CampaignScale {
    /// A length of the thesis' matrix (m) at this scale.
    fn length(self, test_scale: f64) -> f64;
    /// The load, tip and set-point columns.
    fn traces(self) -> Traces;
    /// The variables a campaign run records: load, tip and set-point.
    fn recorded(self) -> [&'static str; 9];
}

impl CampaignScale for Scale {
    fn length(self, test_scale: f64) -> f64 {
        match self {
            Scale::Test => test_scale,
            Scale::Full => test_scale * LENGTH_SCALE,
        }
    }

    fn traces(self) -> Traces {
        Traces::of(self.names())
    }

    fn recorded(self) -> [&'static str; 9] {
        self.traces().names()
    }
}

//! The crane systems' vocabulary: the two scales ([`Scale`]), the system file of each, and the
//! instance and variable names that code outside the system files relies on — the campaign's
//! start values and metrics, the viewer's scene and live session, the tuning's seeds, the Python
//! package's Gymnasium environment — in one shape for both scales ([`CraneNames`]).
//!
//! Every name is qualified (`"instance.variable"`). Positions are in the world frame W
//! (North-East-Down, m), angles in rad. The integration test `names_resolve` checks that every
//! name of [`CraneNames::all`] resolves in its scale's system file, so a renamed variable fails
//! there rather than in a campaign. The engine below knows none of these names.

mod names;
mod scale;
mod set;

pub use names::{CraneNames, FullScaleControl, TestScaleControl, FULL_SCALE, RIGGING_HOOK, TEST_SCALE};
pub use scale::Scale;
pub use set::{Instance, NameSet, Xyz};

/// `"instance.variable"` split at the first dot (instance names hold none); `None` without one.
pub fn split(name: &str) -> Option<(&str, &str)> {
    name.split_once('.')
}

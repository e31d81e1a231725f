//! What the full-scale controller's references do after the first active sample latched them:
//! hold ([`SetpointSource::Fixed`]), or follow the thesis' pick-and-place profile (Fig. 3.4, the
//! timing of SPEC §8.4; [`crate::control::setpoint::pick_and_place`]) Froude-scaled to this crane
//! ([`FULL_SCALE`]) as displacements from the latched references.
//!
//! Scaled by λ = 25 in length and √λ = 5 in time, the profile moves the tip 5 m towards −x (the
//! test scale's x +0.10 → −0.10 m) in a 150 s blend and pays out and hauls in 7.5 m of rope
//! (17.5 ↔ 25 m) in 75 s blends, 600 s in all. The quintic's peak slope is 30/16 = 1.875 times
//! its mean: the rope's peak speed 1.875 · 7.5 m / 75 s = 0.1875 m/s, 36 % of the winch's rated
//! 0.524 m/s ([`super::drives::RatedSpeeds`]), the tip's 1.875 · 5 m / 150 s = 0.0625 m/s. At the test scale's 120 s timing the rope would need
//! 0.94 m/s, beyond the winch (docs/full-scale.md).

use crate::control::setpoint::Froude;
use crate::math::Vec3;
use serde::{Deserialize, Serialize};

/// The full-scale crane against the thesis' rig: λ = 25, the thesis' 0.40–1.00 m of rope become
/// 10–25 m, inside the 5–30 m a crane of this class lifts on (docs/full-scale.md).
pub const FULL_SCALE: Froude = Froude { length: 25.0 };

/// Where the references go after they are latched.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SetpointSource {
    /// They hold.
    Fixed,
    /// The pick-and-place profile at [`FULL_SCALE`], from the latch on.
    PickAndPlace,
}

/// How far the references have moved from their latched values, and how fast.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Displacement {
    /// The tip's displacement (m) and velocity (m/s) along the axes of W (compensated) or K
    /// (positioning; the two coincide on a deck at rest).
    pub tip: Vec3,
    pub tip_rate: Vec3,
    /// The hoist length's displacement (m, positive paying out) and its rate (m/s); the load's
    /// height reference moves with it (W z, down).
    pub lp: f64,
    pub lp_rate: f64,
}

impl SetpointSource {
    /// The displacement `t` seconds after the latch; `None` for [`SetpointSource::Fixed`], whose
    /// references hold exactly.
    pub fn displacement(self, t: f64) -> Option<Displacement> {
        match self {
            SetpointSource::Fixed => None,
            SetpointSource::PickAndPlace => {
                let (start, now) = (FULL_SCALE.pick_and_place(0.0), FULL_SCALE.pick_and_place(t));
                let rate = FULL_SCALE.pick_and_place_rate(t);
                Some(Displacement {
                    tip: now.tip - start.tip,
                    tip_rate: rate.tip,
                    lp: now.lp - start.lp,
                    lp_rate: rate.lp,
                })
            }
        }
    }
}

//! The rigging's state: the continuous coordinates of both segments and the snap-load record.

use super::params::{RiggingParams, RopeLaw};
use super::segment::Coordinates;
use crate::math::Vec3;
use crate::pendulum::{Swing, TipMotion};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// Number of continuous states in [`RiggingState::to_vector`].
pub const STATE_LEN: usize = 12;

/// The rigging's state.
///
/// Each segment has three coordinate slots, whose meaning its rope law fixes:
///
/// | rope                          | slots (0, 1, 2)                          | units |
/// |-------------------------------|------------------------------------------|-------|
/// | rigid                         | (θx, θy, 0): the X–Y angles of the rope  | rad   |
/// | elastic                       | end − start in W (hook − tip, load − hook) | m   |
/// | sling of length 0 (no sling)  | (0, 0, 0)                                | —     |
///
/// and the rates in the same slots (rad/s or m/s). Unused slots stay zero. The continuous vector
/// ([`Self::to_vector`]) is `[hoist 0..3, sling 3..6, hoist_rate 6..9, sling_rate 9..12]`.
/// With no sling and a rigid hoist rope, (θx, θy, θ̇x, θ̇y) = slots (0, 1, 6, 7) are the
/// pendulum's [`Swing`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RiggingState {
    pub hoist: Vec3,
    pub sling: Vec3,
    pub hoist_rate: Vec3,
    pub sling_rate: Vec3,
    /// Slack phases and the snap loads after them (not a continuous state: updated at samples).
    pub snap: SnapRecord,
}

/// Slack and snap bookkeeping of both ropes, updated at every integration substep end (at most
/// 1 ms apart, [`crate::integrate::MAX_SUBSTEP`]; the single pendulum's path at the step end).
///
/// A rope is *slack* at a sample when its tension is zero (elastic) or would need to be
/// compressive (rigid: a negative constraint force). The *peak snap load* of a rope is the
/// largest tension sampled at any sample after the first sample at which it was slack — the
/// running maximum of the tension over everything that follows a slack phase, which is the
/// re-catch's snap when one follows; 0 while the rope has never been slack.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct SnapRecord {
    /// The hoist rope was slack at the last sample.
    pub hoist_slack: bool,
    /// The hoist rope has been slack at some sample.
    pub hoist_was_slack: bool,
    /// Peak snap load of the hoist rope (N).
    pub hoist_peak: f64,
    /// The sling was slack at the last sample.
    pub sling_slack: bool,
    pub sling_was_slack: bool,
    /// Peak snap load of the sling (N).
    pub sling_peak: f64,
}

impl SnapRecord {
    /// Takes one sample of both tensions (N) and slack states.
    pub fn sample(&mut self, hoist: (f64, bool), sling: (f64, bool)) {
        record(&mut self.hoist_peak, &mut self.hoist_was_slack, &mut self.hoist_slack, hoist);
        record(&mut self.sling_peak, &mut self.sling_was_slack, &mut self.sling_slack, sling);
    }
}

fn record(peak: &mut f64, was_slack: &mut bool, slack_now: &mut bool, (tension, slack): (f64, bool)) {
    if *was_slack {
        *peak = peak.max(tension);
    }
    *was_slack |= slack;
    *slack_now = slack;
}

impl RiggingState {
    /// The continuous part as a vector (layout in the type's documentation).
    pub fn to_vector(&self) -> SVector<f64, STATE_LEN> {
        let mut x = SVector::<f64, STATE_LEN>::zeros();
        x.fixed_rows_mut::<3>(0).copy_from(&self.hoist);
        x.fixed_rows_mut::<3>(3).copy_from(&self.sling);
        x.fixed_rows_mut::<3>(6).copy_from(&self.hoist_rate);
        x.fixed_rows_mut::<3>(9).copy_from(&self.sling_rate);
        x
    }

    /// The state with the continuous part `x` and the snap record `snap`.
    pub fn from_vector(x: &SVector<f64, STATE_LEN>, snap: SnapRecord) -> RiggingState {
        RiggingState {
            hoist: x.fixed_rows::<3>(0).into_owned(),
            sling: x.fixed_rows::<3>(3).into_owned(),
            hoist_rate: x.fixed_rows::<3>(6).into_owned(),
            sling_rate: x.fixed_rows::<3>(9).into_owned(),
            snap,
        }
    }

    /// The single pendulum's swing as a rigging state (rigid hoist rope, no sling).
    pub fn from_swing(s: &Swing) -> RiggingState {
        RiggingState {
            hoist: Vec3::new(s.theta_x, s.theta_y, 0.0),
            hoist_rate: Vec3::new(s.omega_x, s.omega_y, 0.0),
            ..RiggingState::default()
        }
    }

    /// The hoist rope's angles and rates as the pendulum's swing (meaningful for a rigid rope).
    pub fn swing(&self) -> Swing {
        Swing { theta_x: self.hoist.x, theta_y: self.hoist.y, omega_x: self.hoist_rate.x, omega_y: self.hoist_rate.y }
    }

    /// Hook and load hanging at rest straight below a tip at rest with the hoist length `u.lp`:
    /// the angles zero, an elastic rope stretched by the static weight below it (m g / k).
    pub fn hanging(p: &RiggingParams, u: &TipMotion) -> RiggingState {
        RiggingState::at_angles(p, u, (0.0, 0.0), (0.0, 0.0))
    }

    /// Hook and load at rest with the hoist rope at the X–Y angles `hoist` and the sling at `sling`
    /// (rad; the sling's are ignored without a sling), an elastic rope at its unstretched length
    /// plus the static stretch of the weight below it (exact hanging straight down, a start value
    /// otherwise).
    pub fn at_angles(p: &RiggingParams, u: &TipMotion, hoist: (f64, f64), sling: (f64, f64)) -> RiggingState {
        let g = p.load.g;
        let along = |(theta_x, theta_y): (f64, f64), r: f64| {
            Vec3::new(theta_y.sin(), -theta_y.cos() * theta_x.sin(), theta_y.cos() * theta_x.cos()) * r
        };
        let hoist = match p.hoist {
            RopeLaw::Rigid => Vec3::new(hoist.0, hoist.1, 0.0),
            RopeLaw::Elastic(rope) => {
                let weight = (p.hook_mass + p.load.mass) * g;
                along(hoist, u.lp + weight * u.lp / rope.ea)
            }
        };
        let sling = match (p.has_sling(), p.sling) {
            (false, _) => Vec3::zeros(),
            (true, RopeLaw::Rigid) => Vec3::new(sling.0, sling.1, 0.0),
            (true, RopeLaw::Elastic(rope)) => {
                let weight = p.load.mass * g;
                along(sling, p.sling_length + weight * p.sling_length / rope.ea)
            }
        };
        RiggingState { hoist, sling, ..RiggingState::default() }
    }
}

/// The coordinates of each segment under `p`.
pub(super) fn layout(p: &RiggingParams) -> (Coordinates, Coordinates) {
    let kind = |law: RopeLaw| match law {
        RopeLaw::Rigid => Coordinates::Angles,
        RopeLaw::Elastic(_) => Coordinates::Cartesian,
    };
    let sling = if p.has_sling() { kind(p.sling) } else { Coordinates::Absent };
    (kind(p.hoist), sling)
}

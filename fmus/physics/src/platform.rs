//! The five-actuator ship motion platform (thesis §3.3, §3.4.1 and §4.1; SPEC §4.1, §8.3).
//!
//! - [`kinematics`]: simplified (eqs. 4.1–4.5) and exact closed-chain inverse kinematics, forward
//!   kinematics and the dependent yaw;
//! - this module: the crane's location on the ship (the frame the motion is resolved in) and
//!   [`drive`], which turns a requested deck motion into actuator set-points, the limit flag and
//!   the deck motion the crane feels.
//!
//! Frames: ship frame B and world frame W as everywhere (x bow/north, y starboard/east, z down).
//! The platform frame P carries the crane on its −y side (Fig. 3.7). With the crane at the port
//! side P is aligned with B; with the crane at the stern P is B turned by −90° about z (its −y axis
//! points aft), and the ship motion is resolved in P before the inverse kinematics.

pub mod kinematics;

use crate::motion::{AxisMotion, DeckMotion, HEAVE, PITCH, ROLL, SURGE, SWAY, YAW};
use kinematics::{exact_inverse_motion, simplified_inverse_motion, PlatformError, PlatformGeometry};
use serde::{Deserialize, Serialize};

/// Where the crane stands on the ship (Fig. 3.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum CraneLocation {
    /// Port side (Fig. 3.7b, the thesis' configuration): P = B.
    Port,
    /// Stern (Fig. 3.7a): P is B turned by −90° about z.
    Stern,
}

default_is_const!(CraneLocation);

impl CraneLocation {
    /// The thesis' configuration, the port side.
    pub const DEFAULT: CraneLocation = CraneLocation::Port;

    /// The deck motion resolved in the platform frame P. For the stern, vectors turn by +90°
    /// about z (coordinates in a frame turned by −90°): surge_P = −sway, sway_P = surge, and the
    /// small-angle rotation vector likewise: roll_P = −pitch, pitch_P = roll, yaw unchanged
    /// (exact for a single tilt; the platform reproduces roll and pitch as Z–Y–X angles in P).
    pub fn resolve(&self, motion: &DeckMotion) -> DeckMotion {
        match self {
            CraneLocation::Port => *motion,
            CraneLocation::Stern => {
                let d = &motion.dof;
                let neg = |a: AxisMotion| AxisMotion { pos: -a.pos, vel: -a.vel, acc: -a.acc };
                DeckMotion { dof: [neg(d[SWAY]), d[SURGE], d[HEAVE], neg(d[PITCH]), d[ROLL], d[YAW]] }
            }
        }
    }
}

/// Which inverse kinematics produces the set-points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum InverseModel {
    /// The closed chain (Table 4.1), as the thesis' Simscape model.
    Exact,
    /// Eqs. 4.1–4.5 of the previous work.
    Simplified,
}

impl InverseModel {
    /// The closed chain.
    pub const DEFAULT: InverseModel = InverseModel::Exact;
}

default_is_const!(InverseModel);

/// The platform at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PlatformState {
    /// The deck motion fed to the crane and the deck IMU, in P: the requested motion (ideal
    /// tracking), with the mechanism's dependent yaw added when asked for.
    pub deck: DeckMotion,
    /// Set-points LA1–LA5 (m, m/s, m/s²).
    pub la: [AxisMotion; 5],
    /// The yaw the closed chain takes for this pose (rad); zero when it was not computed.
    pub dependent_yaw: AxisMotion,
    /// A set-point outside 0 … stroke or faster than the speed limit.
    pub la_limit: bool,
}

impl PlatformState {
    /// The deck following `requested` (already resolved in P) without the platform: for ship
    /// motion at full scale, which the test-scale mechanism cannot reproduce (metres of heave
    /// against its 0.2 m stroke), so no inverse kinematics is run. The deck is the requested
    /// motion, the set-points rest at the neutral extension (`geom.nominal`, at rest), no
    /// dependent yaw, and the limit flag is false: it reports a set-point the platform is asked
    /// to follow, and none is.
    pub fn unactuated(geom: &PlatformGeometry, requested: &DeckMotion) -> PlatformState {
        let neutral = AxisMotion { pos: geom.nominal, vel: 0.0, acc: 0.0 };
        PlatformState { deck: *requested, la: [neutral; 5], dependent_yaw: AxisMotion::default(), la_limit: false }
    }
}

/// The platform reproducing `requested` (already resolved in P): set-points by `model`, the
/// dependent yaw from the exact chain (computed for the exact model or when `mechanism_yaw`
/// adds it to the deck's yaw).
pub fn drive(
    geom: &PlatformGeometry,
    requested: &DeckMotion,
    model: InverseModel,
    mechanism_yaw: bool,
) -> Result<PlatformState, PlatformError> {
    let pose: [AxisMotion; 5] = [0, 1, 2, 3, 4].map(|j| requested.dof[j]);
    let exact =
        if model == InverseModel::Exact || mechanism_yaw { Some(exact_inverse_motion(geom, &pose)?) } else { None };
    let la = match (model, &exact) {
        (InverseModel::Exact, Some(e)) => e.la,
        _ => simplified_inverse_motion(geom, &pose),
    };
    let dependent_yaw = exact.map_or(AxisMotion::default(), |e| e.yaw);
    let mut deck = *requested;
    if mechanism_yaw {
        let yaw = &mut deck.dof[YAW];
        yaw.pos += dependent_yaw.pos;
        yaw.vel += dependent_yaw.vel;
        yaw.acc += dependent_yaw.acc;
    }
    Ok(PlatformState { deck, la, dependent_yaw, la_limit: !geom.within_limits(&la) })
}

#[cfg(test)]
mod tests;

//! The test-scale knuckle-boom crane (thesis §3.4.2–3.5.4 and §4.2).
//!
//! - [`mechanisms`]: the three actuator four-bar mechanisms, actuator extension ↔ joint angle
//!   (eqs. 4.30–4.65);
//! - [`kinematics`]: the serial RRR chain, joint angles ↔ tip position in the base frame J12
//!   (eqs. 4.73–4.75 and 4.78–4.88);
//! - [`actuator`]: the actuator and winch plant — input saturation, deadbands (Table 3.2),
//!   G(s) = K/(s(s + a)) (eqs. 3.5–3.8) and stroke saturation (§3.5.3 steps 1–5);
//! - [`winch`]: the pendulum (cable) length from the winch angle and the jib actuator
//!   (eqs. 3.1–3.4);
//! - [`motion`]: exact first and second time derivatives of the chain by forward-mode automatic
//!   differentiation, and the tip's rigid-body motion in the world frame;
//! - [`plant`]: the whole crane — actuator states in, kinematics out;
//! - [`sensors`]: the actuator potentiometers and the winch encoder (§3.4.4, §3.5.4).
//!
//! Units: the API is SI (m, rad, s) except the hardware signals, which keep their hardware units
//! (actuator commands in V, winch command as duty 0–1, winch angle in degrees). The thesis writes
//! every kinematic constant in millimetres; functions take and return metres and convert at their
//! boundary (`mm = m · 1000`). The actuator plant ([`actuator`]) keeps the thesis' units (mm for
//! the linear actuators, degrees for the winch) because its gains are identified in them.
//!
//! Frames: the crane base frame J12 is aligned with the ship (deck) frame B — x bow, y starboard,
//! z down — with its origin at [`motion::CRANE_BASE`] in B (the crane stands on the port side).
//! The crane reaches toward −y; the tip is above the deck (z < 0).

pub mod actuator;
pub mod kinematics;
pub mod mechanisms;
pub mod motion;
pub mod plant;
pub mod sensors;
pub mod winch;

use crate::math::Scalar;
use std::fmt;

/// Millimetres per metre: the thesis' kinematic constants are in mm.
pub const MM_PER_M: f64 = 1000.0;

/// Why a kinematic problem has no (physical) solution.
#[derive(Debug, Clone, PartialEq)]
pub enum KinematicsError {
    /// An argument is NaN or infinite.
    NotFinite,
    /// The mechanism's loop cannot close: no joint angle for this actuator extension (m).
    NoClosure { mechanism: &'static str, extension: f64 },
    /// The target (m, J12) lies on the slewing axis, where the base angle is undefined.
    OnSlewAxis { target: [f64; 3] },
    /// The target (m, J12) is farther from, or closer to, the boom pivot than the boom and jib
    /// can reach.
    OutOfReach { target: [f64; 3], distance: f64, min: f64, max: f64 },
    /// The joint angle needs an actuator extension (m) outside the 0–50 mm stroke.
    OutOfStroke { mechanism: &'static str, extension: f64 },
}

impl fmt::Display for KinematicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KinematicsError::NotFinite => write!(f, "a kinematic argument is not finite"),
            KinematicsError::NoClosure { mechanism, extension } => {
                write!(f, "the {mechanism} actuator mechanism cannot close at an extension of {extension} m")
            }
            KinematicsError::OnSlewAxis { target } => {
                write!(f, "target {target:?} m lies on the slewing axis (base angle undefined)")
            }
            KinematicsError::OutOfReach { target, distance, min, max } => write!(
                f,
                "target {target:?} m is {distance:.4} m from the boom pivot, outside the reach {min:.4}–{max:.4} m"
            ),
            KinematicsError::OutOfStroke { mechanism, extension } => write!(
                f,
                "the {mechanism} actuator would need an extension of {:.3} mm, outside its 0–50 mm stroke",
                extension * MM_PER_M
            ),
        }
    }
}

impl std::error::Error for KinematicsError {}

/// Four-quadrant arctangent of y/x carrying derivatives. Its value is `f64::atan2` of the real
/// parts; its derivatives are those of atan(y/x) or, where |y| > |x|, of −atan(x/y) (the two
/// differ by a constant), so no derivative divides by a vanishing number away from the origin.
fn atan2<D: Scalar>(y: D, x: D) -> D {
    let angle = if x.re().abs() >= y.re().abs() { (y / x).atan() } else { -(x / y).atan() };
    angle + (y.re().atan2(x.re()) - angle.re())
}

#[cfg(test)]
mod tests;

//! The actuator mechanisms of the base, boom and jib joints (thesis §4.2.2–4.2.4).
//!
//! Each linear actuator forms a planar four-bar loop with the revolute joint it drives: a pin on
//! the first body at offset c·,1 from the joint frame, the actuator of pin-to-pin length
//! d + d0, and a pin on the second body at offset c·,2. Closing the loop (eq. 4.29 and its
//! counterparts) gives
//!
//! ```text
//! (d + d0)² = Σc² + K2 sin θ − K3 cos θ
//! ```
//!
//! whose square root is the inverse kinematics (eqs. 4.30, 4.45, 4.58) and whose half-angle
//! substitution t = tan(θ/2) gives the quadratic A t² + B t + C = 0 of the forward kinematics
//! (eqs. 4.33–4.39, 4.46–4.52, 4.59–4.65), θ = 2 atan2(−B + √(B² − 4AC), 2A).
//!
//! Corrections to the thesis: eq. 4.65 prints K3 = 2(−c4y1 c4y2 − + c4z1 c4z2); the loop closure
//! (and Appendix D `FK_LA3_Jib`) gives K3 = 2(−c4y1 c4y2 + c4z1 c4z2). For the jib, 2 atan2(…)
//! lands in (π, 2π) and 2π is subtracted (Appendix D). In Appendix D `IK_LA2_Boom`, `K2 + sin` and
//! `K3 + cos` mean K2·sin and K3·cos.
//!
//! Units: extensions d in m and angles θ in rad at the API; the constants are the thesis' CAD
//! values in mm, and d is converted to mm at the boundary.

use super::{atan2, KinematicsError, MM_PER_M};
use crate::math::Scalar;

/// Usable stroke of each linear actuator (m): extensions run from 0 (fully retracted) to 50 mm.
pub const STROKE: f64 = 0.050;

/// Loop constants of one actuator mechanism (mm, mm²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mechanism {
    /// Which joint it drives ("base", "boom", "jib"), for messages.
    pub name: &'static str,
    /// Fully retracted pin-to-pin length d0 (mm).
    pub retracted: f64,
    /// Σc², the sum of the squared pin offsets (mm²): K1 = −(d + d0)² + Σc².
    pub sum_sq: f64,
    /// K2 (mm²).
    pub k2: f64,
    /// K3 (mm²).
    pub k3: f64,
    /// Added to 2 atan2(…) so the angle is the physical one: 0, or −2π for the jib (rad).
    pub wrap: f64,
}

impl Mechanism {
    /// Base (slewing) actuator LA1 driving θ2z: eqs. 4.30, 4.33–4.39; d2x,0 = 97, c2x,1 = 122,
    /// c2y,1 = 47.825, c2y,2 = 53.975 mm (§4.2.2).
    pub const BASE: Mechanism = Mechanism::base(97.0, 122.0, 47.825, 53.975);
    /// Boom actuator LA2 driving θ3x: eqs. 4.45–4.52; d3z,0 = 97, c3y,1 = 62.865,
    /// c3z,1 = 107.315, c3y,2 = 66.04, c3z,2 = 9.525 mm (§4.2.3).
    pub const BOOM: Mechanism = Mechanism::boom(97.0, 62.865, 107.315, 66.04, 9.525);
    /// Jib actuator LA3 driving θ4x: eqs. 4.58–4.65 (K3 corrected); d4z,0 = 97,
    /// c4y,1 = 120.8532, c4z,1 = 9.525, c4y,2 = 46.99, c4z,2 = 9.525 mm (§4.2.4).
    pub const JIB: Mechanism = Mechanism::jib(97.0, 120.8532, 9.525, 46.99, 9.525);

    /// The mechanism `name` of retracted length `d0` and loop constants Σc², K2, K3, its angle
    /// unwrapped (`wrap` 0; the jib's constructor sets its −2π).
    const fn from_loop(name: &'static str, d0: f64, sum_sq: f64, k2: f64, k3: f64) -> Mechanism {
        Mechanism { name, retracted: d0, sum_sq, k2, k3, wrap: 0.0 }
    }

    /// Eqs. 4.37–4.39.
    const fn base(d0: f64, c2x1: f64, c2y1: f64, c2y2: f64) -> Mechanism {
        let sum_sq = c2x1 * c2x1 + c2y1 * c2y1 + c2y2 * c2y2;
        let (k2, k3) = (2.0 * c2x1 * c2y2, 2.0 * c2y1 * c2y2);
        Mechanism::from_loop("base", d0, sum_sq, k2, k3)
    }

    /// Eqs. 4.50–4.52.
    const fn boom(d0: f64, c3y1: f64, c3z1: f64, c3y2: f64, c3z2: f64) -> Mechanism {
        let sum_sq = c3y1 * c3y1 + c3y2 * c3y2 + c3z1 * c3z1 + c3z2 * c3z2;
        let (k2, k3) = (2.0 * (c3y2 * c3z1 - c3y1 * c3z2), 2.0 * (c3y1 * c3y2 + c3z1 * c3z2));
        Mechanism::from_loop("boom", d0, sum_sq, k2, k3)
    }

    /// Eqs. 4.63–4.65, with K3 = 2(−c4y1 c4y2 + c4z1 c4z2).
    const fn jib(d0: f64, c4y1: f64, c4z1: f64, c4y2: f64, c4z2: f64) -> Mechanism {
        let sum_sq = c4y1 * c4y1 + c4y2 * c4y2 + c4z1 * c4z1 + c4z2 * c4z2;
        let (k2, k3) = (2.0 * (c4y2 * c4z1 + c4y1 * c4z2), 2.0 * (-c4y1 * c4y2 + c4z1 * c4z2));
        Mechanism { wrap: -std::f64::consts::TAU, ..Mechanism::from_loop("jib", d0, sum_sq, k2, k3) }
    }

    /// Inverse kinematics: the actuator extension d (m) that sets the joint angle `theta` (rad),
    /// eqs. 4.30 / 4.45 / 4.58. Defined for every angle; whether it lies inside the stroke is
    /// checked by [`Mechanism::extension_in_stroke`].
    pub fn extension<D: Scalar>(&self, theta: D) -> D {
        let (s, c) = theta.sin_cos();
        let length = (s * self.k2 - c * self.k3 + self.sum_sq).sqrt();
        (length - self.retracted) / MM_PER_M
    }

    /// [`Mechanism::extension`], or an error when it lies outside the 0–50 mm stroke (by more
    /// than 1 nm, to forgive rounding at the ends).
    pub fn extension_in_stroke(&self, theta: f64) -> Result<f64, KinematicsError> {
        if !theta.is_finite() {
            return Err(KinematicsError::NotFinite);
        }
        let d = self.extension(theta);
        if (-1e-9..=STROKE + 1e-9).contains(&d) {
            Ok(d.clamp(0.0, STROKE))
        } else {
            Err(KinematicsError::OutOfStroke { mechanism: self.name, extension: d })
        }
    }

    /// Forward kinematics: the joint angle (rad) for the actuator extension `d` (m),
    /// eqs. 4.33–4.39 / 4.46–4.52 / 4.59–4.65 with the + root, as in Appendix D.
    pub fn angle<D: Scalar>(&self, d: D) -> Result<D, KinematicsError> {
        if !d.re().is_finite() {
            return Err(KinematicsError::NotFinite);
        }
        let length = d * MM_PER_M + self.retracted;
        let k1 = -(length * length) + self.sum_sq;
        let a = k1 + self.k3;
        let b = 2.0 * self.k2;
        let c = k1 - self.k3;
        let discriminant = -(a * c * 4.0) + b * b;
        if !(discriminant.re() >= 0.0) || a.re() == 0.0 {
            return Err(KinematicsError::NoClosure { mechanism: self.name, extension: d.re() });
        }
        Ok(atan2(discriminant.sqrt() - b, a * 2.0) * 2.0 + self.wrap)
    }

    /// The home angle θ0 (rad): the joint angle with the actuator fully retracted (d = 0).
    pub fn home_angle(&self) -> f64 {
        self.angle(0.0).expect("every mechanism closes at d = 0")
    }
}

/// The base, boom and jib mechanisms, in joint order (θ2z, θ3x, θ4x).
pub const MECHANISMS: [Mechanism; 3] = [Mechanism::BASE, Mechanism::BOOM, Mechanism::JIB];

/// Joint angles (θ2z, θ3x, θ4x) (rad) from the three actuator extensions (m).
pub fn joints_from_actuators<D: Scalar>(d: &[D; 3]) -> Result<[D; 3], KinematicsError> {
    Ok([MECHANISMS[0].angle(d[0])?, MECHANISMS[1].angle(d[1])?, MECHANISMS[2].angle(d[2])?])
}

/// Actuator extensions (m) for the joint angles (θ2z, θ3x, θ4x) (rad), each checked against the
/// stroke.
pub fn actuators_from_joints(theta: &[f64; 3]) -> Result<[f64; 3], KinematicsError> {
    Ok([
        MECHANISMS[0].extension_in_stroke(theta[0])?,
        MECHANISMS[1].extension_in_stroke(theta[1])?,
        MECHANISMS[2].extension_in_stroke(theta[2])?,
    ])
}

#[cfg(test)]
mod tests;

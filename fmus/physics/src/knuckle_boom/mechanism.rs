//! A luffing cylinder as a two-pin mechanism: one pin on the lower link, one on the upper link,
//! the joint between them.
//!
//! Plane coordinates: each link carries a plane frame at the joint, x along the link's line
//! (for the slewing column: radially out along e, see the module documentation of
//! [`crate::knuckle_boom`]), y perpendicular to it, up when the link is horizontal. The upper
//! link's frame is the lower link's turned by the joint angle θ. With a the lower pin (lower
//! frame), b the upper pin (upper frame) and R(θ) the planar rotation, the cylinder is the
//! vector v(θ) = R(θ) b − a and (the law of cosines of the triangle joint–pin–pin, Siciliano et
//! al. 2009, §2.9.1 for the planar rotation):
//!
//! ```text
//! L² = |a|² + |b|² − 2 |a| |b| cos ψ,   ψ = θ + ∠b − ∠a
//! dL/dθ = (R'(θ) b) · v / L = |a| |b| sin ψ / L            (the lever arm, m)
//! d²L/dθ² = (|a| |b| cos ψ − (dL/dθ)²) / L
//! ```
//!
//! The working branch is ψ ∈ (0, π): the cylinder extends as the joint angle grows, so it pushes
//! to lift and carries the weight in compression on its piston side. The joint limits are where
//! the cylinder reaches its shortest and longest pin-to-pin length.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A two-pin cylinder across one joint (pins in m, plane coordinates of their links).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Mechanism {
    /// The pin on the lower link, in the lower link's plane frame at the joint (m).
    pub lower_pin: [f64; 2],
    /// The pin on the upper link, in the upper link's plane frame at the joint (m).
    pub upper_pin: [f64; 2],
    /// Pin-to-pin length fully retracted (m): the lower joint limit.
    pub min_length: f64,
    /// Pin-to-pin length fully extended (m): the upper joint limit.
    pub max_length: f64,
}

impl Mechanism {
    /// Pin-to-pin length L(θ) (m), the lever arm dL/dθ (m) and d²L/dθ² (m) at the joint angle
    /// `theta` (rad). Defined for every angle (the stroke limits are not applied).
    pub fn length(&self, theta: f64) -> (f64, f64, f64) {
        let [ax, ay] = self.lower_pin;
        let (s, c) = theta.sin_cos();
        // R(θ) b and its derivative R'(θ) b = (−(Rb)_y, (Rb)_x).
        let (bx, by) = (c * self.upper_pin[0] - s * self.upper_pin[1], s * self.upper_pin[0] + c * self.upper_pin[1]);
        let (vx, vy) = (bx - ax, by - ay);
        let length = vx.hypot(vy);
        let lever = (-by * vx + bx * vy) / length;
        // d/dθ (R'b · v) = −Rb · v + |b|² = |a| |b| cos ψ.
        let curvature = (-(bx * vx + by * vy) + bx * bx + by * by - lever * lever) / length;
        (length, lever, curvature)
    }

    /// The joint angle (rad) at which the pins are `length` (m) apart, on the working branch
    /// ψ ∈ (0, π); Err if `length` is not finite or outside the stroke
    /// [`Self::min_length`]…[`Self::max_length`].
    pub fn angle(&self, length: f64) -> Result<f64, String> {
        if !(length >= self.min_length && length <= self.max_length) {
            return Err(format!(
                "cylinder length {length} m is outside the stroke {}–{} m",
                self.min_length, self.max_length
            ));
        }
        let (a, b) = (self.lower_arm(), self.upper_arm());
        let cos_psi = ((a * a + b * b - length * length) / (2.0 * a * b)).clamp(-1.0, 1.0);
        Ok(wrap(cos_psi.acos() - self.offset()))
    }

    /// The joint limits (rad): the angles at the shortest and the longest length.
    pub fn joint_range(&self) -> Result<(f64, f64), String> {
        Ok((self.angle(self.min_length)?, self.angle(self.max_length)?))
    }

    /// Checks the pins and the stroke: finite, 0 < min < max, and both lengths strictly inside
    /// the triangle inequality ||a| − |b|| < L < |a| + |b| (else the lever arm vanishes at a
    /// limit and the inverse is not unique), and a joint range that does not wrap across ±π.
    /// `name` names the mechanism in the message.
    pub fn validate(&self, name: &str) -> Result<(), String> {
        let values = [self.lower_pin[0], self.lower_pin[1], self.upper_pin[0], self.upper_pin[1]];
        if values.iter().any(|v| !v.is_finite()) {
            return Err(format!("{name}: pins {:?} and {:?} m must be finite", self.lower_pin, self.upper_pin));
        }
        if !(self.min_length > 0.0 && self.max_length > self.min_length && self.max_length.is_finite()) {
            return Err(format!(
                "{name}: stroke {}–{} m needs 0 < min_length < max_length",
                self.min_length, self.max_length
            ));
        }
        let (a, b) = (self.lower_arm(), self.upper_arm());
        if !((a - b).abs() < self.min_length && self.max_length < a + b) {
            return Err(format!(
                "{name}: pins {a:.4} m and {b:.4} m from the joint reach {:.4}–{:.4} m, which must strictly \
                 contain the stroke {}–{} m",
                (a - b).abs(),
                a + b,
                self.min_length,
                self.max_length
            ));
        }
        let (low, high) = self.joint_range()?;
        if !(high > low) {
            return Err(format!("{name}: the joint range {low:.4}…{high:.4} rad wraps across ±π; turn the pins"));
        }
        Ok(())
    }

    /// |a|, the lower pin's distance from the joint (m).
    fn lower_arm(&self) -> f64 {
        self.lower_pin[0].hypot(self.lower_pin[1])
    }

    /// |b|, the upper pin's distance from the joint (m).
    fn upper_arm(&self) -> f64 {
        self.upper_pin[0].hypot(self.upper_pin[1])
    }

    /// ∠b − ∠a (rad): ψ = θ + offset.
    fn offset(&self) -> f64 {
        self.upper_pin[1].atan2(self.upper_pin[0]) - self.lower_pin[1].atan2(self.lower_pin[0])
    }
}

/// `angle` (rad) in (−π, π].
fn wrap(angle: f64) -> f64 {
    let wrapped = (angle + PI).rem_euclid(2.0 * PI) - PI;
    if wrapped == -PI {
        PI
    } else {
        wrapped
    }
}

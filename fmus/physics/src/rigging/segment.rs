//! One rope segment's kinematics: the chord s from its start (the tip, or the hook) to its end
//! (the hook, or the load) in W, and how it depends on the segment's coordinates.
//!
//! A rigid segment has the thesis' X–Y angles as coordinates, w = (θx, θy, unused) and a
//! prescribed length l(t): s = l e(θ) with e = (sin θy, −cos θy sin θx, cos θy cos θx) (eqs.
//! 4.94–4.96). An elastic segment has the chord's Cartesian components in W as coordinates,
//! s = w. A missing segment (no sling) has none, s = 0.
//!
//! For each, with q̇ the coordinates' rates: ṡ = J q̇ + ∂s/∂t and s̈ = J q̈ + b, where J = ∂s/∂q is
//! the Jacobian and b the bias acceleration (the terms without q̈; Meirovitch, Methods of
//! Analytical Dynamics, 1970, on generalised coordinates and velocities).

use super::rope::{direction, swing_directions};
use crate::math::{Matrix3, Vec3};

/// Which coordinates describe a segment (the state layout of [`super::RiggingState`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Coordinates {
    /// Rigid: (θx, θy) (rad) in the first two of the three slots; the third is unused (zero).
    Angles,
    /// Elastic: the chord end − start in W (m).
    Cartesian,
    /// No sling: all three slots unused.
    Absent,
}

impl Coordinates {
    /// Whether slot `i` (0, 1, 2) of the segment's three holds a coordinate.
    pub(super) fn uses(self, i: usize) -> bool {
        match self {
            Coordinates::Angles => i < 2,
            Coordinates::Cartesian => true,
            Coordinates::Absent => false,
        }
    }
}

/// A prescribed segment length with its first two time derivatives (m, m/s, m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Length {
    pub l: f64,
    pub rate: f64,
    pub acc: f64,
}

/// The chord of one segment and its derivatives at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Segment {
    /// Chord s = end − start in W (m).
    pub chord: Vec3,
    /// Its rate ṡ (m/s).
    pub chord_rate: Vec3,
    /// J = ∂ṡ/∂q̇ (unused columns zero).
    pub jacobian: Matrix3<f64>,
    /// b = s̈ − J q̈ (m/s²).
    pub bias: Vec3,
    /// Unit direction e of the chord (straight down for a zero chord).
    pub unit: Vec3,
    /// Unit swing directions (ê_x, ê_y) across the chord ([`swing_directions`]).
    pub swing: (Vec3, Vec3),
    /// cos θy of the chord (1 for an absent segment), for the singularity check.
    pub cos_theta_y: f64,
}

impl Segment {
    /// The segment described by `kind` with coordinates `q`, rates `w` and (for a rigid segment)
    /// the prescribed length `len`.
    pub(super) fn new(kind: Coordinates, q: &Vec3, w: &Vec3, len: &Length) -> Segment {
        match kind {
            Coordinates::Angles => angles(q, w, len),
            Coordinates::Cartesian => {
                let unit = direction(q);
                Segment {
                    chord: *q,
                    chord_rate: *w,
                    jacobian: Matrix3::identity(),
                    bias: Vec3::zeros(),
                    unit,
                    swing: swing_directions(&unit),
                    cos_theta_y: unit.y.hypot(unit.z),
                }
            }
            Coordinates::Absent => Segment {
                chord: Vec3::zeros(),
                chord_rate: Vec3::zeros(),
                jacobian: Matrix3::zeros(),
                bias: Vec3::zeros(),
                unit: Vec3::z(),
                swing: swing_directions(&Vec3::z()),
                cos_theta_y: 1.0,
            },
        }
    }
}

/// A rigid segment: s = l e(θx, θy), the thesis' eqs. 4.94–4.96 (ṡ and s̈ their time derivatives,
/// as `pendulum::load_kinematics` takes them).
fn angles(q: &Vec3, w: &Vec3, len: &Length) -> Segment {
    let (sx, cx) = q.x.sin_cos();
    let (sy, cy) = q.y.sin_cos();
    let (wx, wy) = (w.x, w.y);
    let e = Vec3::new(sy, -cy * sx, cy * cx);
    // First partial derivatives of e: ∂e/∂θx (length cos θy) and ∂e/∂θy (unit), orthogonal.
    let d_x = Vec3::new(0.0, -cy * cx, -cy * sx);
    let d_y = Vec3::new(cy, sy * sx, -sy * cx);
    // Second partial derivatives.
    let d_xx = Vec3::new(0.0, cy * sx, -cy * cx);
    let d_xy = Vec3::new(0.0, sy * cx, sy * sx);
    let d_yy = Vec3::new(-sy, cy * sx, -cy * cx);
    let e_dot = d_x * wx + d_y * wy;
    let jacobian = Matrix3::from_columns(&[d_x * len.l, d_y * len.l, Vec3::zeros()]);
    let bias =
        (d_xx * (wx * wx) + d_xy * (2.0 * wx * wy) + d_yy * (wy * wy)) * len.l + e_dot * (2.0 * len.rate) + e * len.acc;
    Segment {
        chord: e * len.l,
        chord_rate: e_dot * len.l + e * len.rate,
        jacobian,
        bias,
        unit: e,
        swing: (Vec3::new(0.0, -cx, -sx), d_y),
        cos_theta_y: cy,
    }
}

//! Inverse and forward kinematics of the motion platform (thesis §4.1, eqs. 4.1–4.5, Table 4.1;
//! geometry of SPEC §8.3).
//!
//! Structure (Table 4.1): LA1 (prismatic e1) moves the Y-gantry sideways (sway), LA2 (e2) moves
//! the X-gantry fore and aft (surge); the X-gantry carries three legs LA3–LA5, each on a revolute
//! base joint (e3–e5) with a tangential axis, a cylindrical actuator (e6–e8: extension and rotation
//! about its own axis) and a universal joint at the deck (e9–e11). The rotation of the rod and the
//! universal joint together leave the deck free to turn about the leg's top pin, so each leg holds
//! its pin P_i at the pin-to-pin length l_i from the base pin b_i inside the leg's plane (spanned
//! by the radial direction and z, normal to the revolute axis t_i):
//!
//! ```text
//! t_i · (P_i − g − b_i) = 0,     |P_i − g − b_i| = l_i,     P_i = p + R(φ, θ, ψ) d_i
//! ```
//!
//! with p the deck centre, R the Z–Y–X attitude (W←B), d_i the pin in the deck frame B and g the
//! gantry offset. Five actuators fix five degrees of freedom (Kutzbach mobility 5); the three plane
//! conditions make the yaw ψ (and the deck's position on the gantry) depend on heave, roll and
//! pitch.
//!
//! Frames and units: the platform frame P is aligned with the gantry rails (x along LA2, y along
//! LA1, z down); its origin is the deck centre in the neutral position (every actuator at its
//! nominal 0.1 m extension, deck level). Lengths in m, angles in rad. Set-points are actuator
//! extensions in the order LA1–LA5 (0–0.2 m, nominal 0.1 m): LA1 = nominal + gantry y,
//! LA2 = nominal + gantry x, LA3–LA5 = pin-to-pin length − retracted length.
//!
//! - [`simplified_inverse`]: eqs. 4.1–4.5 (previous work): LA1 = sway, LA2 = surge, the legs as
//!   plain distances between base and deck pins for heave, roll and pitch, no yaw;
//! - [`exact_inverse`] / [`exact_inverse_motion`]: the closed chain solved by Newton's method for
//!   the gantry offsets and the dependent yaw, with exact velocities and accelerations;
//! - [`forward`]: the closed chain's forward kinematics (Newton on the six pose coordinates).

use crate::math::{euler_zyx_matrix, Scalar, Vec3};
use crate::motion::AxisMotion;
use nalgebra::{SMatrix, SVector};
use num_dual::{Dual64, HyperDual64};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Index of each actuator in a set-point array.
pub const LA1: usize = 0;
pub const LA2: usize = 1;

/// Newton iterations before a kinematic problem is declared unsolvable.
const MAX_ITERATIONS: usize = 50;
/// Residual (m) below which a Newton solution is accepted.
const TOLERANCE: f64 = 1e-13;

/// The platform's dimensions and actuator limits (config). SPEC §8.3.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlatformGeometry {
    /// Angular positions of the legs LA3, LA4, LA5 about z, from x toward y (rad).
    pub leg_angles: [f64; 3],
    /// Radius of the base revolute joints on the X-gantry (m).
    pub base_radius: f64,
    /// Radius of the deck universal joints (m).
    pub deck_radius: f64,
    /// Depth of the deck universal joints below the deck plane (m).
    pub joint_depth: f64,
    /// Pin-to-pin length of a leg at zero extension (m).
    pub pin_length: f64,
    /// Nominal (neutral) extension of every actuator (m).
    pub nominal: f64,
    /// Stroke of every actuator (m): extensions 0 … stroke.
    pub stroke: f64,
    /// Largest actuator speed (m/s).
    pub max_speed: f64,
}

impl Default for PlatformGeometry {
    /// Legs at 90°, 210° and 330°, pins on radius 0.25 m, deck pins 0.05 m below the deck, legs
    /// 0.35 m + extension, strokes 0–0.2 m with 0.1 m nominal, 20 mm/s.
    fn default() -> Self {
        let deg = std::f64::consts::PI / 180.0;
        PlatformGeometry {
            leg_angles: [90.0 * deg, 210.0 * deg, 330.0 * deg],
            base_radius: 0.25,
            deck_radius: 0.25,
            joint_depth: 0.05,
            pin_length: 0.35,
            nominal: 0.1,
            stroke: 0.2,
            max_speed: 0.02,
        }
    }
}

impl PlatformGeometry {
    /// Depth of the base pins below the deck centre in the neutral position (m).
    pub fn base_depth(&self) -> f64 {
        self.joint_depth + self.pin_length + self.nominal
    }

    /// Base pin b_i of leg `i` (0–2 for LA3–LA5) in the platform frame, gantry at nominal (m).
    pub fn base_pin(&self, i: usize) -> Vec3 {
        let (s, c) = self.leg_angles[i].sin_cos();
        Vec3::new(self.base_radius * c, self.base_radius * s, self.base_depth())
    }

    /// Deck pin d_i of leg `i` in the deck frame B (m).
    pub fn deck_pin(&self, i: usize) -> Vec3 {
        let (s, c) = self.leg_angles[i].sin_cos();
        Vec3::new(self.deck_radius * c, self.deck_radius * s, self.joint_depth)
    }

    /// Axis t_i of leg `i`'s base revolute joint (unit, tangential, horizontal).
    pub fn hinge_axis(&self, i: usize) -> Vec3 {
        let (s, c) = self.leg_angles[i].sin_cos();
        Vec3::new(-s, c, 0.0)
    }

    /// Whether every set-point is inside the stroke and every speed within the limit.
    pub fn within_limits(&self, la: &[AxisMotion; 5]) -> bool {
        la.iter().all(|a| a.pos >= 0.0 && a.pos <= self.stroke && a.vel.abs() <= self.max_speed)
    }

    /// How much of the actuators' range is used: the largest of |extension − mid-stroke| / half
    /// stroke and |speed| / max speed over the five actuators (≤ 1 inside the limits).
    pub fn usage(&self, la: &[AxisMotion; 5]) -> f64 {
        let half = self.stroke / 2.0;
        la.iter().map(|a| ((a.pos - half).abs() / half).max(a.vel.abs() / self.max_speed)).fold(0.0, f64::max)
    }
}

/// Why a platform kinematic problem has no solution.
#[derive(Debug, Clone, PartialEq)]
pub enum PlatformError {
    /// An argument is NaN or infinite.
    NotFinite,
    /// Newton's method did not converge (or met a singular Jacobian).
    NoConvergence { problem: &'static str, iterations: usize, residual: f64 },
}

impl fmt::Display for PlatformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlatformError::NotFinite => write!(f, "a platform kinematic argument is not finite"),
            PlatformError::NoConvergence { problem, iterations, residual } => write!(
                f,
                "the platform {problem} did not converge: residual {residual:.3e} m after {iterations} Newton iterations \
                 (pose outside the mechanism's reach or at a singularity)"
            ),
        }
    }
}

impl std::error::Error for PlatformError {}

/// A constant `D` from an `f64`.
fn c<D: Scalar>(x: f64) -> D {
    D::from(x)
}

/// The three leg vectors P_i − g − b_i, P_i = p + R d_i, for the deck pose (surge, sway, heave,
/// roll, pitch, yaw) and the gantry offset g.
fn leg_vectors<D: Scalar>(geom: &PlatformGeometry, pose: &[D; 6], gantry: [D; 2]) -> [[D; 3]; 3] {
    let r = euler_zyx_matrix(pose[3], pose[4], pose[5]);
    [0, 1, 2].map(|i| {
        let (d, b) = (geom.deck_pin(i), geom.base_pin(i));
        let pin = [0, 1, 2].map(|row| pose[row] + r[row][0] * d.x + r[row][1] * d.y + r[row][2] * d.z);
        [pin[0] - gantry[0] - b.x, pin[1] - gantry[1] - b.y, pin[2] - b.z]
    })
}

fn norm<D: Scalar>(v: &[D; 3]) -> D {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Plane conditions t_i · (P_i − g − b_i) of the three legs.
fn plane_residuals<D: Scalar>(geom: &PlatformGeometry, legs: &[[D; 3]; 3]) -> [D; 3] {
    [0, 1, 2].map(|i| {
        let t = geom.hinge_axis(i);
        legs[i][0] * t.x + legs[i][1] * t.y
    })
}

/// Set-points LA1–LA5 (m) of the gantry offsets and the leg vectors.
fn setpoints<D: Scalar>(geom: &PlatformGeometry, pose: &[D; 6], gantry: [D; 2]) -> [D; 5] {
    let legs = leg_vectors(geom, pose, gantry);
    let leg = |i: usize| norm(&legs[i]) - geom.pin_length;
    [gantry[1] + geom.nominal, gantry[0] + geom.nominal, leg(0), leg(1), leg(2)]
}

/// Simplified inverse kinematics, eqs. 4.1–4.5: LA1 = sway and LA2 = surge (about the nominal
/// extension); LA3–LA5 the distances between the base pins b_i and the deck pins P_i moved by
/// heave, roll and pitch only (no yaw, the deck assumed fixed on the gantry), less the retracted
/// pin-to-pin length. `pose` is (surge, sway, heave, roll, pitch) in the platform frame.
pub fn simplified_inverse<D: Scalar>(geom: &PlatformGeometry, pose: &[D; 5]) -> [D; 5] {
    let [x, y, z, roll, pitch] = *pose;
    let relative = [c(0.0), c(0.0), z, roll, pitch, c(0.0)];
    let legs = setpoints(geom, &relative, [c(0.0), c(0.0)]);
    [y + geom.nominal, x + geom.nominal, legs[2], legs[3], legs[4]]
}

/// Unknowns of the exact inverse problem: gantry offset (x, y) and the dependent yaw.
type Unknowns = SVector<f64, 3>;

fn ik_residuals<D: Scalar>(geom: &PlatformGeometry, pose: &[D; 5], u: &[D; 3]) -> [D; 3] {
    let full = [pose[0], pose[1], pose[2], pose[3], pose[4], u[2]];
    plane_residuals(geom, &leg_vectors(geom, &full, [u[0], u[1]]))
}

/// ∂(plane residuals)/∂(gantry x, gantry y, yaw): −t_ix, −t_iy and t_i · (∂R/∂ψ d_i), where
/// ∂R/∂ψ d = (−(R d)_y, (R d)_x, 0) for the Z–Y–X sequence.
fn ik_jacobian(geom: &PlatformGeometry, pose: &[f64; 5], u: &Unknowns) -> SMatrix<f64, 3, 3> {
    let r = euler_zyx_matrix(pose[3], pose[4], u[2]);
    let mut j = SMatrix::<f64, 3, 3>::zeros();
    for i in 0..3 {
        let (t, d) = (geom.hinge_axis(i), geom.deck_pin(i));
        let rd = [0, 1].map(|row| r[row][0] * d.x + r[row][1] * d.y + r[row][2] * d.z);
        j[(i, 0)] = -t.x;
        j[(i, 1)] = -t.y;
        j[(i, 2)] = -t.x * rd[1] + t.y * rd[0];
    }
    j
}

/// The exact inverse problem's solution: set-points LA1–LA5 (m) and the dependent yaw (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct InverseSolution {
    pub la: [f64; 5],
    pub yaw: f64,
    /// The gantry offset from its nominal position, (x, y) in the platform frame (m).
    pub gantry: [f64; 2],
}

/// Exact inverse kinematics of the closed chain: the set-points that put the deck centre at
/// (surge, sway, heave) with the given roll and pitch (`pose`, platform frame), and the yaw the
/// mechanism then takes. Newton's method from the neutral configuration.
pub fn exact_inverse(geom: &PlatformGeometry, pose: &[f64; 5]) -> Result<InverseSolution, PlatformError> {
    if !pose.iter().all(|v| v.is_finite()) {
        return Err(PlatformError::NotFinite);
    }
    let mut u = Unknowns::zeros();
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let r = Unknowns::from(ik_residuals(geom, pose, &[u[0], u[1], u[2]]));
        residual = r.amax();
        if residual < TOLERANCE {
            let full = [pose[0], pose[1], pose[2], pose[3], pose[4], u[2]];
            return Ok(InverseSolution { la: setpoints(geom, &full, [u[0], u[1]]), yaw: u[2], gantry: [u[0], u[1]] });
        }
        let Some(step) = ik_jacobian(geom, pose, &u).lu().solve(&r) else { break };
        u -= step;
        if !u.iter().all(|v| v.is_finite()) {
            break;
        }
    }
    Err(PlatformError::NoConvergence { problem: "inverse kinematics", iterations: MAX_ITERATIONS, residual })
}

/// Set-points and the dependent yaw with their first and second time derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct InverseMotion {
    pub la: [AxisMotion; 5],
    pub yaw: AxisMotion,
}

/// [`exact_inverse`] along a trajectory: `pose` holds surge, sway, heave, roll and pitch with their
/// time derivatives. The unknowns' derivatives follow from differentiating the plane conditions
/// F(u(t), c(t)) = 0 twice: J u̇ = −F_c ċ and J ü = −(F_c c̈ + second-order terms), both
/// evaluated exactly with dual and hyper-dual numbers; the set-points then carry their exact
/// velocities and accelerations.
pub fn exact_inverse_motion(geom: &PlatformGeometry, pose: &[AxisMotion; 5]) -> Result<InverseMotion, PlatformError> {
    let position = pose.map(|a| a.pos);
    let solution = exact_inverse(geom, &position)?;
    let u = Unknowns::new(solution.gantry[0], solution.gantry[1], solution.yaw);
    let lu = ik_jacobian(geom, &position, &u).lu();
    let singular =
        || PlatformError::NoConvergence { problem: "inverse kinematics (rates)", iterations: 0, residual: f64::NAN };
    // First derivatives: the ε part of F(u, c + ċ ε) is F_c ċ.
    let c1 = pose.map(|a| Dual64::new(a.pos, a.vel));
    let u1 = [0, 1, 2].map(|k| Dual64::from(u[k]));
    let f1 = Unknowns::from(ik_residuals(geom, &c1, &u1).map(|r| r.eps));
    let u_dot = -lu.solve(&f1).ok_or_else(singular)?;
    // Second derivatives: with u̇ in the jets and ü = 0, the ε1ε2 part is everything but J ü.
    let c2 = pose.map(|a| a.jet());
    let u2 = [0, 1, 2].map(|k| HyperDual64::new(u[k], u_dot[k], u_dot[k], 0.0));
    let f2 = Unknowns::from(ik_residuals(geom, &c2, &u2).map(|r| r.eps1eps2));
    let u_ddot = -lu.solve(&f2).ok_or_else(singular)?;
    let u_jet = [0, 1, 2].map(|k| HyperDual64::new(u[k], u_dot[k], u_dot[k], u_ddot[k]));
    let full = [c2[0], c2[1], c2[2], c2[3], c2[4], u_jet[2]];
    let la = setpoints(geom, &full, [u_jet[0], u_jet[1]]);
    Ok(InverseMotion { la: la.map(|x| AxisMotion::from_jet(&x)), yaw: AxisMotion::from_jet(&u_jet[2]) })
}

/// [`exact_inverse`] with the set-points' exact velocities only (accelerations left zero): the
/// cheaper first half of [`exact_inverse_motion`], for limit checks over many samples.
pub fn exact_inverse_rates(geom: &PlatformGeometry, pose: &[AxisMotion; 5]) -> Result<[AxisMotion; 5], PlatformError> {
    let position = pose.map(|a| a.pos);
    let solution = exact_inverse(geom, &position)?;
    let u = Unknowns::new(solution.gantry[0], solution.gantry[1], solution.yaw);
    let c1 = pose.map(|a| Dual64::new(a.pos, a.vel));
    let u1 = [0, 1, 2].map(|k| Dual64::from(u[k]));
    let f1 = Unknowns::from(ik_residuals(geom, &c1, &u1).map(|r| r.eps));
    let u_dot = -ik_jacobian(geom, &position, &u).lu().solve(&f1).ok_or(PlatformError::NoConvergence {
        problem: "inverse kinematics (rates)",
        iterations: 0,
        residual: f64::NAN,
    })?;
    let u_jet = [0, 1, 2].map(|k| Dual64::new(u[k], u_dot[k]));
    let full = [c1[0], c1[1], c1[2], c1[3], c1[4], u_jet[2]];
    Ok(setpoints(geom, &full, [u_jet[0], u_jet[1]]).map(|x| AxisMotion { pos: x.re, vel: x.eps, acc: 0.0 }))
}

/// [`simplified_inverse`] with exact time derivatives.
pub fn simplified_inverse_motion(geom: &PlatformGeometry, pose: &[AxisMotion; 5]) -> [AxisMotion; 5] {
    simplified_inverse(geom, &pose.map(|a| a.jet())).map(|x| AxisMotion::from_jet(&x))
}

fn fk_residuals<D: Scalar>(geom: &PlatformGeometry, la: &[f64; 5], pose: &[D; 6]) -> [D; 6] {
    let gantry = [c(la[LA2] - geom.nominal), c(la[LA1] - geom.nominal)];
    let legs = leg_vectors(geom, pose, gantry);
    let planes = plane_residuals(geom, &legs);
    let lengths = [0, 1, 2].map(|i| norm(&legs[i]) - (geom.pin_length + la[i + 2]));
    [planes[0], planes[1], planes[2], lengths[0], lengths[1], lengths[2]]
}

/// Forward kinematics of the closed chain: the deck pose (surge, sway, heave, roll, pitch, yaw;
/// platform frame) for set-points LA1–LA5 (m). Newton's method from `guess` (the neutral pose
/// when `None`).
pub fn forward(geom: &PlatformGeometry, la: &[f64; 5], guess: Option<&[f64; 6]>) -> Result<[f64; 6], PlatformError> {
    if !la.iter().all(|v| v.is_finite()) || !guess.is_none_or(|g| g.iter().all(|v| v.is_finite())) {
        return Err(PlatformError::NotFinite);
    }
    let mut x = SVector::<f64, 6>::from(guess.copied().unwrap_or([0.0; 6]));
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let pose: [f64; 6] = x.into();
        let r = SVector::<f64, 6>::from(fk_residuals(geom, la, &pose));
        residual = r.amax();
        if residual < TOLERANCE {
            return Ok(pose);
        }
        let mut j = SMatrix::<f64, 6, 6>::zeros();
        for k in 0..6 {
            let seeded: [Dual64; 6] = [0, 1, 2, 3, 4, 5].map(|m| Dual64::new(x[m], if m == k { 1.0 } else { 0.0 }));
            for (row, value) in fk_residuals(geom, la, &seeded).iter().enumerate() {
                j[(row, k)] = value.eps;
            }
        }
        let Some(step) = j.lu().solve(&r) else { break };
        x -= step;
        if !x.iter().all(|v| v.is_finite()) {
            break;
        }
    }
    Err(PlatformError::NoConvergence { problem: "forward kinematics", iterations: MAX_ITERATIONS, residual })
}

#[cfg(test)]
mod tests;

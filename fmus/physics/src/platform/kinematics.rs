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
//!   the gantry offsets and the dependent yaw (roll and pitch applied once, only the yaw turned per
//!   iteration), with exact velocities and accelerations from the deck's rigid-body motion;
//! - [`forward`]: the closed chain's forward kinematics (Newton on the six pose coordinates).

use crate::math::{euler_zyx_matrix, Matrix3, Scalar, Vec3};
use crate::motion::AxisMotion;
use nalgebra::{SMatrix, SVector};
use num_dual::Dual64;
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
        self.leg(i).base
    }

    /// Deck pin d_i of leg `i` in the deck frame B (m).
    pub fn deck_pin(&self, i: usize) -> Vec3 {
        self.leg(i).deck
    }

    /// Axis t_i of leg `i`'s base revolute joint (unit, tangential, horizontal).
    pub fn hinge_axis(&self, i: usize) -> Vec3 {
        self.leg(i).hinge
    }

    /// Leg `i`'s pins and hinge axis, from one sine and cosine of its angle.
    fn leg(&self, i: usize) -> Leg {
        let (s, c) = self.leg_angles[i].sin_cos();
        Leg {
            base: Vec3::new(self.base_radius * c, self.base_radius * s, self.base_depth()),
            deck: Vec3::new(self.deck_radius * c, self.deck_radius * s, self.joint_depth),
            hinge: Vec3::new(-s, c, 0.0),
        }
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
                "the platform {problem} did not converge: residual {residual:.3e} m after {iterations} Newton \
                 iterations (pose outside the mechanism's reach or at a singularity)"
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
        let Leg { deck: d, base: b, .. } = geom.leg(i);
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

/// One leg's fixed geometry, in the platform frame: base pin b_i (gantry at nominal), deck pin d_i
/// (deck frame) and the unit hinge axis t_i (horizontal), all m or 1.
#[derive(Debug, Clone, Copy)]
struct Leg {
    base: Vec3,
    deck: Vec3,
    hinge: Vec3,
}

/// The exact inverse problem's solution: set-points LA1–LA5 (m) and the dependent yaw (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct InverseSolution {
    pub la: [f64; 5],
    pub yaw: f64,
    /// The gantry offset from its nominal position, (x, y) in the platform frame (m).
    pub gantry: [f64; 2],
}

/// The closed chain solved for one pose, with what the time derivatives are made of.
///
/// With R = R_z(ψ) R_y(θ) R_x(φ), roll and pitch are given and ψ is unknown, so the deck pins are
/// tilted once, q_i = R_y R_x d_i, and each Newton iteration only turns them about z: the arms
/// r_i = R d_i = R_z(ψ) q_i. The plane conditions F_i = t_i · (p + r_i − g − b_i) = 0 have the
/// Jacobian ∂F_i/∂(g_x, g_y, ψ) = (−t_ix, −t_iy, t_i · (e_z × r_i)).
struct Chain {
    legs: [Leg; 3],
    /// Gantry offset g = (g_x, g_y) (m) and the dependent yaw ψ (rad).
    gantry: [f64; 2],
    yaw: f64,
    /// Arms r_i (m) and leg vectors v_i = p + r_i − g − b_i (m), platform frame.
    arms: [Vec3; 3],
    legs_now: [Vec3; 3],
    /// The inverse of the Jacobian at the solution.
    inverse: Matrix3<f64>,
    /// Axes of the pitch and roll rates in P (the Z–Y–X sequence): a_θ = R_z e_y,
    /// a_φ = R_z R_y e_x.
    pitch_axis: Vec3,
    roll_axis: Vec3,
}

/// Jacobian ∂F/∂(g_x, g_y, ψ) for the arms `arms`.
fn chain_jacobian(legs: &[Leg; 3], arms: &[Vec3; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, k| {
        let t = legs[i].hinge;
        [-t.x, -t.y, -t.x * arms[i].y + t.y * arms[i].x][k]
    })
}

fn not_converged(residual: f64) -> PlatformError {
    PlatformError::NoConvergence { problem: "inverse kinematics", iterations: MAX_ITERATIONS, residual }
}

/// Newton's method on (g_x, g_y, ψ) from the neutral configuration, for `pose` (surge, sway,
/// heave, roll, pitch; platform frame).
fn solve_chain(geom: &PlatformGeometry, pose: &[f64; 5]) -> Result<Chain, PlatformError> {
    if !pose.iter().all(|v| v.is_finite()) {
        return Err(PlatformError::NotFinite);
    }
    let legs = [0, 1, 2].map(|i| geom.leg(i));
    let p = Vec3::new(pose[0], pose[1], pose[2]);
    let (sf, cf) = pose[3].sin_cos();
    let (st, ct) = pose[4].sin_cos();
    // q_i = R_y(θ) R_x(φ) d_i.
    let tilted = legs.map(|l| {
        let d = l.deck;
        Vec3::new(
            ct * d.x + st * sf * d.y + st * cf * d.z,
            cf * d.y - sf * d.z,
            -st * d.x + ct * sf * d.y + ct * cf * d.z,
        )
    });
    let mut u = Vec3::zeros();
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let (sp, cp) = u.z.sin_cos();
        let arms = tilted.map(|q| Vec3::new(cp * q.x - sp * q.y, sp * q.x + cp * q.y, q.z));
        let gantry = Vec3::new(u.x, u.y, 0.0);
        let legs_now = [0, 1, 2].map(|i| p + arms[i] - gantry - legs[i].base);
        let f = Vec3::from_fn(|i, _| legs_now[i].x * legs[i].hinge.x + legs_now[i].y * legs[i].hinge.y);
        residual = f.amax();
        let inverse = chain_jacobian(&legs, &arms).try_inverse();
        if residual < TOLERANCE {
            let inverse = inverse.ok_or(PlatformError::NoConvergence {
                problem: "inverse kinematics (rates)",
                iterations: 0,
                residual: f64::NAN,
            })?;
            let pitch_axis = Vec3::new(-sp, cp, 0.0);
            let roll_axis = Vec3::new(cp * ct, sp * ct, -st);
            return Ok(Chain { legs, gantry: [u.x, u.y], yaw: u.z, arms, legs_now, inverse, pitch_axis, roll_axis });
        }
        let Some(inverse) = inverse else { break };
        u -= inverse * f;
        if !u.iter().all(|v| v.is_finite()) {
            break;
        }
    }
    Err(not_converged(residual))
}

impl Chain {
    /// Set-point LA1–LA5 positions (m): nominal + gantry y, nominal + gantry x, leg lengths less
    /// the retracted pin-to-pin length.
    fn setpoints(&self, geom: &PlatformGeometry) -> [f64; 5] {
        let leg = |i: usize| {
            let v: &Vec3 = &self.legs_now[i];
            (v.x * v.x + v.y * v.y + v.z * v.z).sqrt() - geom.pin_length
        };
        [self.gantry[1] + geom.nominal, self.gantry[0] + geom.nominal, leg(0), leg(1), leg(2)]
    }

    /// Solves J x = −(t_i · w_i) for the unknowns' rates x, given the known part w_i of each leg
    /// vector's derivative.
    fn unknown_rates(&self, known: [Vec3; 3]) -> Vec3 {
        let b = Vec3::from_fn(|i, _| self.legs[i].hinge.dot(&known[i]));
        -(self.inverse * b)
    }

    /// First time derivatives: the deck's angular velocity ω (P), the unknowns' rates
    /// (ġ_x, ġ_y, ψ̇) and the legs' v̇_i = ṗ + ω × r_i − ġ. With ω = ω_k + ψ̇ e_z,
    /// ω_k = θ̇ a_θ + φ̇ a_φ, the plane conditions t_i · v̇_i = 0 give J u̇ = −t_i · (ṗ + ω_k × r_i).
    fn rates(&self, pose: &[AxisMotion; 5]) -> (Vec3, Vec3, [Vec3; 3]) {
        let p_dot = Vec3::new(pose[0].vel, pose[1].vel, pose[2].vel);
        let omega_known = self.pitch_axis * pose[4].vel + self.roll_axis * pose[3].vel;
        let u_dot = self.unknown_rates(self.arms.map(|r| p_dot + omega_known.cross(&r)));
        let omega = omega_known + Vec3::z() * u_dot.z;
        let g_dot = Vec3::new(u_dot.x, u_dot.y, 0.0);
        (omega, u_dot, self.arms.map(|r| p_dot + omega.cross(&r) - g_dot))
    }

    /// Second time derivatives of the unknowns and of the legs: v̈_i = p̈ + α × r_i + ω × (ω × r_i) − g̈
    /// with α = α_k + ψ̈ e_z, α_k = θ̈ a_θ + θ̇ ȧ_θ + φ̈ a_φ + φ̇ ȧ_φ, ȧ_θ = ψ̇ e_z × a_θ and
    /// ȧ_φ = (ψ̇ e_z + θ̇ a_θ) × a_φ (the axes turn with the outer rotations); the plane conditions
    /// t_i · v̈_i = 0 give J ü = −t_i · (p̈ + α_k × r_i + ω × (ω × r_i)).
    fn accelerations(&self, pose: &[AxisMotion; 5], omega: &Vec3, u_dot: &Vec3) -> (Vec3, [Vec3; 3]) {
        let p_ddot = Vec3::new(pose[0].acc, pose[1].acc, pose[2].acc);
        let (roll, pitch) = (&pose[3], &pose[4]);
        let yaw_rate = Vec3::z() * u_dot.z;
        let pitch_axis_dot = yaw_rate.cross(&self.pitch_axis);
        let roll_axis_dot = (yaw_rate + self.pitch_axis * pitch.vel).cross(&self.roll_axis);
        let alpha_known = self.pitch_axis * pitch.acc
            + pitch_axis_dot * pitch.vel
            + self.roll_axis * roll.acc
            + roll_axis_dot * roll.vel;
        let known = self.arms.map(|r| p_ddot + alpha_known.cross(&r) + omega.cross(&omega.cross(&r)));
        let u_ddot = self.unknown_rates(known);
        let alpha = alpha_known + Vec3::z() * u_ddot.z;
        let g_ddot = Vec3::new(u_ddot.x, u_ddot.y, 0.0);
        (u_ddot, self.arms.map(|r| p_ddot + alpha.cross(&r) + omega.cross(&omega.cross(&r)) - g_ddot))
    }
}

/// Exact inverse kinematics of the closed chain: the set-points that put the deck centre at
/// (surge, sway, heave) with the given roll and pitch (`pose`, platform frame), and the yaw the
/// mechanism then takes. Newton's method from the neutral configuration.
pub fn exact_inverse(geom: &PlatformGeometry, pose: &[f64; 5]) -> Result<InverseSolution, PlatformError> {
    let chain = solve_chain(geom, pose)?;
    Ok(InverseSolution { la: chain.setpoints(geom), yaw: chain.yaw, gantry: chain.gantry })
}

/// Set-points and the dependent yaw with their first and second time derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct InverseMotion {
    pub la: [AxisMotion; 5],
    pub yaw: AxisMotion,
}

/// A leg length's derivatives from its vector's: l = |v|, l̇ = v · v̇/l, l̈ = (v̇ · v̇ + v · v̈ − l̇²)/l.
fn length_rates(v: &Vec3, v_dot: &Vec3, v_ddot: &Vec3, length: f64) -> (f64, f64) {
    let rate = v.dot(v_dot) / length;
    (rate, (v_dot.dot(v_dot) + v.dot(v_ddot) - rate * rate) / length)
}

/// The set-points of `chain` with the velocities `v_dot`/`u_dot` and accelerations
/// `v_ddot`/`u_ddot` of its legs and unknowns.
fn setpoint_motion(
    geom: &PlatformGeometry,
    chain: &Chain,
    (u_dot, v_dot): (&Vec3, &[Vec3; 3]),
    (u_ddot, v_ddot): (&Vec3, &[Vec3; 3]),
) -> [AxisMotion; 5] {
    let la = chain.setpoints(geom);
    let leg = |i: usize| {
        let (vel, acc) = length_rates(&chain.legs_now[i], &v_dot[i], &v_ddot[i], la[i + 2] + geom.pin_length);
        AxisMotion { pos: la[i + 2], vel, acc }
    };
    [
        AxisMotion { pos: la[0], vel: u_dot.y, acc: u_ddot.y },
        AxisMotion { pos: la[1], vel: u_dot.x, acc: u_ddot.x },
        leg(0),
        leg(1),
        leg(2),
    ]
}

/// [`exact_inverse`] along a trajectory: `pose` holds surge, sway, heave, roll and pitch with their
/// time derivatives. The unknowns' derivatives follow from differentiating the plane conditions
/// twice along the rigid-body motion of the deck (see `Chain::rates`, `Chain::accelerations`);
/// the set-points then carry their exact velocities and accelerations.
pub fn exact_inverse_motion(geom: &PlatformGeometry, pose: &[AxisMotion; 5]) -> Result<InverseMotion, PlatformError> {
    let chain = solve_chain(geom, &pose.map(|a| a.pos))?;
    let (omega, u_dot, v_dot) = chain.rates(pose);
    let (u_ddot, v_ddot) = chain.accelerations(pose, &omega, &u_dot);
    let la = setpoint_motion(geom, &chain, (&u_dot, &v_dot), (&u_ddot, &v_ddot));
    Ok(InverseMotion { la, yaw: AxisMotion { pos: chain.yaw, vel: u_dot.z, acc: u_ddot.z } })
}

/// [`exact_inverse`] with the set-points' exact velocities only (accelerations left zero): the
/// cheaper first half of [`exact_inverse_motion`], for limit checks over many samples.
pub fn exact_inverse_rates(geom: &PlatformGeometry, pose: &[AxisMotion; 5]) -> Result<[AxisMotion; 5], PlatformError> {
    let chain = solve_chain(geom, &pose.map(|a| a.pos))?;
    let (_, u_dot, v_dot) = chain.rates(pose);
    let la = setpoint_motion(geom, &chain, (&u_dot, &v_dot), (&Vec3::zeros(), &[Vec3::zeros(); 3]));
    Ok(la.map(|a| AxisMotion { acc: 0.0, ..a }))
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

//! The variable-length spherical pendulum (thesis §4.3, eqs. 4.89–4.137) with the aerodynamic
//! damping of §7.2.3.
//!
//! Conventions: world frame W is North-East-Down, gravity along +z. The cable hangs from the
//! crane tip; θx then θy (X–Y sequence) rotate the cable relative to a frame at the tip aligned
//! with W (eqs. 4.89–4.93), so the unit vector from tip to load is
//! e_r = (sin θy, −cos θy sin θx, cos θy cos θx) (eqs. 4.94–4.96). Angles in rad, rates in rad/s.

use crate::integrate::{rk6_from, RK6_NODES};
use crate::math::{rot_x, rot_y, Quat, Vec3, STANDARD_GRAVITY};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// Physical constants of the load (config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PendulumParams {
    /// Load mass m_p (kg); enters only the cable tension.
    pub mass: f64,
    /// Aerodynamic damping c_θx/m_p (1/s) along the direction θx moves the load (§7.2.3).
    pub kappa_x: f64,
    /// Aerodynamic damping c_θy/m_p (1/s) along the direction θy moves the load.
    pub kappa_y: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

default_is_const!(PendulumParams);

impl PendulumParams {
    /// The thesis' load: m_p = 0.3018 kg, κx = 0.0272 s⁻¹, κy = 0.018 s⁻¹ (§7.2.3), g = 9.80665 m/s².
    pub const DEFAULT: PendulumParams =
        PendulumParams { mass: 0.3018, kappa_x: 0.0272, kappa_y: 0.018, g: STANDARD_GRAVITY };

    pub fn validate(&self) -> Result<(), String> {
        if !(self.mass > 0.0) {
            return Err(format!("mass must be > 0 kg, got {}", self.mass));
        }
        if !(self.g > 0.0) {
            return Err(format!("g must be > 0 m/s², got {}", self.g));
        }
        if !(self.kappa_x >= 0.0 && self.kappa_y >= 0.0) {
            return Err(format!("damping constants must be ≥ 0, got {} and {}", self.kappa_x, self.kappa_y));
        }
        Ok(())
    }
}

/// The kinematic inputs u of eq. 4.112: crane tip motion in W and the cable length with their
/// derivatives (m, m/s, m/s²).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TipMotion {
    pub pos: Vec3,
    pub vel: Vec3,
    pub acc: Vec3,
    pub lp: f64,
    pub lp_dot: f64,
    pub lp_ddot: f64,
}

impl TipMotion {
    /// `self + rate · tau`: the inputs linearly interpolated `tau` seconds into a step, where
    /// `rate` holds their first time derivatives (zero when the inputs are held).
    pub fn ramp(&self, rate: &TipMotion, tau: f64) -> TipMotion {
        TipMotion {
            pos: self.pos + rate.pos * tau,
            vel: self.vel + rate.vel * tau,
            acc: self.acc + rate.acc * tau,
            lp: self.lp + rate.lp * tau,
            lp_dot: self.lp_dot + rate.lp_dot * tau,
            lp_ddot: self.lp_ddot + rate.lp_ddot * tau,
        }
    }

    /// `(end − self) / h` for every input: the rates of the linear ramp from `self` to `end` over
    /// a step of length `h` (what a master's input derivatives give), the inverse of
    /// [`TipMotion::ramp`].
    pub fn secant(&self, end: &TipMotion, h: f64) -> TipMotion {
        TipMotion {
            pos: (end.pos - self.pos) / h,
            vel: (end.vel - self.vel) / h,
            acc: (end.acc - self.acc) / h,
            lp: (end.lp - self.lp) / h,
            lp_dot: (end.lp_dot - self.lp_dot) / h,
            lp_ddot: (end.lp_ddot - self.lp_ddot) / h,
        }
    }

    /// The start values and rates for a step of length `h` in which each acceleration ramp
    /// integrates exactly to the velocity change the importer announced (where `slopes` says the
    /// velocity came with a derivative; elsewhere the plain ramp is kept).
    ///
    /// Why: a crane whose commands are sampled has a tip acceleration that jumps at every
    /// communication point, and the acceleration sample at t_k is its left limit (under the old
    /// command), so the plain ramp drives the whole step with a lagged acceleration. The
    /// velocity's secant (v_k+1 − v_k)/h is the exact mean acceleration over the step. Keeping
    /// the end value a_e = a_k + ȧ·h and choosing the start a_s = 2·v̇ − a_e makes the linear
    /// ramp's mean equal the secant: exact for accelerations linear within the step, second
    /// order for smooth ones (where it equals the plain ramp to O(h²)).
    pub fn reconciled(&self, rate: &TipMotion, slopes: &VelocitySlopes, h: f64) -> (TipMotion, TipMotion) {
        let (mut start, mut ramp) = (*self, *rate);
        for i in 0..3 {
            if slopes.tip[i] {
                (start.acc[i], ramp.acc[i]) = reconcile(self.acc[i], rate.acc[i], rate.vel[i], h);
            }
        }
        if slopes.lp {
            (start.lp_ddot, ramp.lp_ddot) = reconcile(self.lp_ddot, rate.lp_ddot, rate.lp_dot, h);
        }
        (start, ramp)
    }
}

/// (start value, rate) of an acceleration ramp over `h` that ends at `acc + acc_rate·h` and
/// whose mean is `vel_rate`, the velocity's secant slope over the step.
fn reconcile(acc: f64, acc_rate: f64, vel_rate: f64, h: f64) -> (f64, f64) {
    let end = acc + acc_rate * h;
    let start = 2.0 * vel_rate - end;
    (start, (end - start) / h)
}

/// Which velocity-level inputs (tip velocity x/y/z in W, cable length rate) came with a first
/// derivative for the coming step, so that their accelerations can be reconciled with them.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct VelocitySlopes {
    pub tip: [bool; 3],
    pub lp: bool,
}

/// The pendulum's continuous states ξ4, ξ5 and their rates (rad, rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Swing {
    pub theta_x: f64,
    pub theta_y: f64,
    pub omega_x: f64,
    pub omega_y: f64,
}

impl Swing {
    fn to_vector(self) -> SVector<f64, 4> {
        SVector::<f64, 4>::new(self.theta_x, self.theta_y, self.omega_x, self.omega_y)
    }

    fn from_vector(x: &SVector<f64, 4>) -> Swing {
        Swing { theta_x: x[0], theta_y: x[1], omega_x: x[2], omega_y: x[3] }
    }
}

/// Sines and cosines of the two angles and the cable directions they span.
struct Geometry {
    sx: f64,
    cx: f64,
    sy: f64,
    cy: f64,
}

impl Geometry {
    fn new(s: &Swing) -> Geometry {
        let (sx, cx) = s.theta_x.sin_cos();
        let (sy, cy) = s.theta_y.sin_cos();
        Geometry { sx, cx, sy, cy }
    }

    /// Unit vector from tip to load (eqs. 4.94–4.96 divided by l_p).
    fn radial(&self) -> Vec3 {
        Vec3::new(self.sy, -self.cy * self.sx, self.cy * self.cx)
    }

    /// ∂e_r/∂θx (length cos θy).
    fn d_theta_x(&self) -> Vec3 {
        Vec3::new(0.0, -self.cy * self.cx, -self.cy * self.sx)
    }

    /// ∂e_r/∂θy (unit length, orthogonal to ∂e_r/∂θx).
    fn d_theta_y(&self) -> Vec3 {
        Vec3::new(self.cy, self.sy * self.sx, -self.sy * self.cx)
    }
}

/// Below this cos θy the θx coordinate is singular (gimbal lock of the X–Y sequence).
const MIN_COS_THETA_Y: f64 = 1e-6;

/// Checks that the cable length is positive and θy (with cosine `cos_theta_y`, which the caller
/// has already taken) is inside (−90°, 90°), clear of the singularity. The sign matters: a fast
/// swing can step over ±90° between two checks, to where cos θy < 0 but |cos θy| is large.
fn check_configuration(s: &Swing, cos_theta_y: f64, u: &TipMotion) -> Result<(), String> {
    if !(u.lp > 0.0) {
        return Err(format!("cable length lp must be > 0 m, got {}", u.lp));
    }
    if !(cos_theta_y > MIN_COS_THETA_Y && s.theta_y.abs() < std::f64::consts::PI) {
        return Err(format!("theta_y = {} rad reaches the ±90° singularity of the X–Y angles", s.theta_y));
    }
    Ok(())
}

/// Angular accelerations (θ̈x, θ̈y) in rad/s².
///
/// Eqs. 4.131–4.132 (the constrained dynamics 4.119–4.121), plus aerodynamic drag: a force
/// −m κx (v·ê_x) ê_x − m κy (v·ê_y) ê_y on the load opposing its world-frame velocity v along
/// the unit directions ê_x, ê_y in which θx and θy move it (§7.2.3), applied as generalized
/// forces Q = Jᵀ F. With the tip fixed this adds exactly −κx θ̇x and −κy θ̇y, so a free swing
/// decays as e^(−κ t/2): τθx = 2/κx, τθy = 2/κy.
pub fn angular_acceleration(p: &PendulumParams, s: &Swing, u: &TipMotion) -> (f64, f64) {
    angular_acceleration_at(p, s, u, &Geometry::new(s))
}

/// [`angular_acceleration`] with the sines and cosines of the state's angles already taken
/// (every evaluation needs them more than once).
fn angular_acceleration_at(p: &PendulumParams, s: &Swing, u: &TipMotion, geo: &Geometry) -> (f64, f64) {
    let &Geometry { sx, cx, sy, cy } = geo;
    let (l, ld, g) = (u.lp, u.lp_dot, p.g);
    let (wx, wy) = (s.omega_x, s.omega_y);
    let a = &u.acc;
    // Eq. 4.131.
    let thx_dd = (-g * sx - 2.0 * cy * ld * wx + 2.0 * l * sy * wx * wy) / (cy * l) + (a.y * cx + a.z * sx) / (cy * l);
    // Eq. 4.132.
    let thy_dd =
        (-cy * l * sy * wx * wx - 2.0 * ld * wy - cx * sy * g) / l + (-a.x * cy - a.y * sx * sy + a.z * cx * sy) / l;
    let (drag_x, drag_y) = drag_acceleration(p, s, u, geo);
    (thx_dd + drag_x, thy_dd + drag_y)
}

/// The drag term of [`angular_acceleration`]: Q_θ/M_θθ with M_44 = m l² cos²θy, M_55 = m l².
fn drag_acceleration(p: &PendulumParams, s: &Swing, u: &TipMotion, geo: &Geometry) -> (f64, f64) {
    let v = load_velocity(s, u, geo);
    let e_x = geo.d_theta_x() / geo.cy;
    let e_y = geo.d_theta_y();
    let ax = -p.kappa_x * v.dot(&e_x) / (u.lp * geo.cy);
    let ay = -p.kappa_y * v.dot(&e_y) / u.lp;
    (ax, ay)
}

/// Load velocity in W: the time derivative of eqs. 4.94–4.96.
fn load_velocity(s: &Swing, u: &TipMotion, geo: &Geometry) -> Vec3 {
    u.vel + geo.radial() * u.lp_dot + (geo.d_theta_x() * s.omega_x + geo.d_theta_y() * s.omega_y) * u.lp
}

/// State derivative of eq. 4.135 restricted to the unactuated coordinates (θx, θy), for the
/// state x = (θx, θy, θ̇x, θ̇y).
fn swing_rate(p: &PendulumParams, x: &SVector<f64, 4>, u: &TipMotion) -> SVector<f64, 4> {
    let s = Swing::from_vector(x);
    swing_rate_at(p, &s, u, &Geometry::new(&s))
}

/// [`swing_rate`] with the sines and cosines of the state's angles already taken.
fn swing_rate_at(p: &PendulumParams, s: &Swing, u: &TipMotion, geo: &Geometry) -> SVector<f64, 4> {
    let (ax, ay) = angular_acceleration_at(p, s, u, geo);
    SVector::<f64, 4>::new(s.omega_x, s.omega_y, ax, ay)
}

/// Longest internal step of the pendulum (s). Its inputs are linear in time within a
/// communication step, so its right-hand side is smooth there and a sixth-order method holds its
/// order: at 10 ms the load position stays within 1e-7 m RMSD of an adaptive reference over 60 s
/// (tests/test_pendulum.py), where RK4 needed 1 ms substeps.
pub const MAX_SUBSTEP: f64 = 1e-2;

/// Number of equal substeps that split `h` into pieces no longer than [`MAX_SUBSTEP`] (the small
/// tolerance keeps h = 10 ms at one substep despite rounding in h).
pub fn substeps(h: f64) -> usize {
    ((h / MAX_SUBSTEP) * (1.0 - 1e-12)).ceil().max(1.0) as usize
}

/// Advances the swing over one communication step [t, t + h] with substeps of at most
/// [`MAX_SUBSTEP`] of Butcher's sixth-order Runge–Kutta method ([`rk6_from`]). `u` holds the
/// inputs at t and `rate` their time derivatives within the step.
pub fn advance(p: &PendulumParams, s: &Swing, u: &TipMotion, rate: &TipMotion, h: f64) -> Result<Swing, String> {
    let n = substeps(h);
    let dt = h / n as f64;
    let mut x = s.to_vector();
    for i in 0..n {
        let tau = i as f64 * dt;
        let (swing, u_tau) = (Swing::from_vector(&x), u.ramp(rate, tau));
        let geo = Geometry::new(&swing);
        check_configuration(&swing, geo.cy, &u_tau)?;
        let k1 = swing_rate_at(p, &swing, &u_tau, &geo);
        let inputs = RK6_NODES.map(|c| u.ramp(rate, tau + c * dt));
        x = rk6_from(&x, k1, dt, |c, x| swing_rate(p, x, &inputs[c]));
    }
    let end = Swing::from_vector(&x);
    check_configuration(&end, end.theta_y.cos(), &u.ramp(rate, h))?;
    Ok(end)
}

/// Everything observable about the load at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LoadMotion {
    /// Position, velocity and acceleration of the load in W (m, m/s, m/s²).
    pub pos: Vec3,
    pub vel: Vec3,
    pub acc: Vec3,
    /// Orientation W←load, R_x(θx) R_y(θy), no twist about the cable (eqs. 4.89–4.92).
    pub orientation: Quat,
    /// Angular velocity in the load frame (rad/s): Rᵀ ω_W = (θ̇x cos θy, θ̇y, θ̇x sin θy).
    pub angular_velocity: Vec3,
    /// Cable tension (N), positive when the cable pulls the load toward the tip.
    pub tension: f64,
    /// Force the cable exerts on the crane tip, in W (N): F = T e_r ([`cable_force`]).
    pub cable_force: Vec3,
    /// The same for an unaccelerated tip and a steady length: F₀ = T₀ e_r ([`free_tension`]),
    /// what a crane that integrates the load's inertia along the cable itself takes as its load.
    pub free_cable_force: Vec3,
    /// Angular accelerations (θ̈x, θ̈y) (rad/s²).
    pub angular_acceleration: (f64, f64),
}

/// Load kinematics and cable tension for a freely swinging load in state `s` under inputs `u`.
pub fn load_motion(p: &PendulumParams, s: &Swing, u: &TipMotion) -> LoadMotion {
    let geo = Geometry::new(s);
    load_kinematics_at(p, s, u, angular_acceleration_at(p, s, u, &geo), &geo)
}

/// Load kinematics for given angular accelerations (rad/s²); a load held at fixed angles (before
/// release) has zero angular rates and accelerations.
pub fn load_kinematics(p: &PendulumParams, s: &Swing, u: &TipMotion, angular_acc: (f64, f64)) -> LoadMotion {
    load_kinematics_at(p, s, u, angular_acc, &Geometry::new(s))
}

/// [`load_kinematics`] with the sines and cosines of the state's angles already taken.
fn load_kinematics_at(
    p: &PendulumParams,
    s: &Swing,
    u: &TipMotion,
    angular_acc: (f64, f64),
    geo: &Geometry,
) -> LoadMotion {
    let &Geometry { sx, cx, sy, cy } = geo;
    let (thx_dd, thy_dd) = angular_acc;
    let (wx, wy) = (s.omega_x, s.omega_y);
    let (l, ld, ldd) = (u.lp, u.lp_dot, u.lp_ddot);
    let e_r = geo.radial();
    let (d_x, d_y) = (geo.d_theta_x(), geo.d_theta_y());
    // Second partial derivatives of e_r.
    let d_xx = Vec3::new(0.0, cy * sx, -cy * cx);
    let d_xy = Vec3::new(0.0, sy * cx, sy * sx);
    let d_yy = Vec3::new(-sy, cy * sx, -cy * cx);
    let e_r_dot = d_x * wx + d_y * wy;
    let e_r_ddot = d_x * thx_dd + d_y * thy_dd + d_xx * (wx * wx) + d_xy * (2.0 * wx * wy) + d_yy * (wy * wy);
    let tension = tension_at(p, s, u, geo);
    let pos = u.pos + e_r * l; // eqs. 4.94–4.96 / 4.137
    let vel = u.vel + e_r * ld + e_r_dot * l;
    let acc = u.acc + e_r * ldd + e_r_dot * (2.0 * ld) + e_r_ddot * l;
    LoadMotion {
        pos,
        vel,
        acc,
        orientation: rot_x(s.theta_x) * rot_y(s.theta_y),
        angular_velocity: Vec3::new(wx * cy, wy, wx * sy),
        tension,
        cable_force: cable_force(tension, &e_r),
        free_cable_force: cable_force(free_tension_at(p, s, u, geo), &e_r),
        angular_acceleration: (thx_dd, thy_dd),
    }
}

/// The force the cable exerts on the crane tip, in W (N): F = T e_r, with T the tension of
/// eq. 4.127 and e_r the unit vector from tip to load (eqs. 4.94–4.96 divided by l_p).
///
/// Why this sign: a massless taut cable pulls both of its ends toward each other with the same
/// tension (Newton's third law), so the load feels −T e_r (the constraint force of eq. 4.117
/// along the cable) and the tip +T e_r, toward the load. A load hanging at rest below the tip
/// (e_r = (0, 0, 1) in North-East-Down) pulls the tip down with F = (0, 0, m g).
pub fn cable_force(tension: f64, e_r: &Vec3) -> Vec3 {
    e_r * tension
}

/// Cable tension T = −F_c,lp (N), from the constraint force of eq. 4.127 (the Lagrange
/// multiplier of the length constraint, eq. 4.117). Drag acts normal to the cable and does not
/// enter.
pub fn tension(p: &PendulumParams, s: &Swing, u: &TipMotion) -> f64 {
    tension_at(p, s, u, &Geometry::new(s))
}

/// [`tension`] with the sines and cosines of the state's angles already taken.
fn tension_at(p: &PendulumParams, s: &Swing, u: &TipMotion, geo: &Geometry) -> f64 {
    let &Geometry { sx, cx, sy, cy } = geo;
    let (wx, wy) = (s.omega_x, s.omega_y);
    let a = &u.acc;
    let f_c_lp = -p.mass * u.lp * wy * wy + p.mass * u.lp_ddot + p.mass * a.x * sy - p.mass * p.g * cx * cy
        + p.mass * a.z * cx * cy
        - p.mass * a.y * cy * sx
        - p.mass * u.lp * wx * wx * cy * cy;
    -f_c_lp
}

/// The tension T₀ (N) the cable would carry with the same state and length rate but an
/// unaccelerated tip and a steady length (a = 0, l̈ = 0). Eq. 4.127 is affine in both:
/// T = T₀ − m_p (a·e_r + l̈), T₀ = m_p (g cos θx cos θy + l_p (θ̇y² + θ̇x² cos² θy)), so a crane model
/// given T₀, e_r and m_p completes the tension with its own tip acceleration and length
/// acceleration (docs/full-scale.md, the force coupling).
pub fn free_tension(p: &PendulumParams, s: &Swing, u: &TipMotion) -> f64 {
    free_tension_at(p, s, u, &Geometry::new(s))
}

fn free_tension_at(p: &PendulumParams, s: &Swing, u: &TipMotion, geo: &Geometry) -> f64 {
    let steady = TipMotion { acc: Vec3::zeros(), lp_ddot: 0.0, ..*u };
    tension_at(p, s, &steady, geo)
}

/// Mechanical energy of the load relative to the tip (J): kinetic energy of eq. 4.99 (load part,
/// tip at rest) plus the potential of eq. 4.98 with the datum at the tip. Conserved for a fixed
/// tip and length without damping.
pub fn energy(p: &PendulumParams, s: &Swing, lp: f64) -> f64 {
    let Geometry { cx, cy, .. } = Geometry::new(s);
    let kinetic = 0.5 * p.mass * lp * lp * (s.omega_x * s.omega_x * cy * cy + s.omega_y * s.omega_y);
    let potential = -p.mass * p.g * lp * cx * cy;
    kinetic + potential
}

/// Angular accelerations of the linearised model (eqs. 4.138, 4.141–4.142, Appendix D
/// `PendLinearDynamics`) about the hanging equilibrium with length `lp_star`:
/// θ̈x = −(g/l*) θx + ÿt/l*,  θ̈y = −(g/l*) θy − ẍt/l*.
pub fn linear_angular_acceleration(g: f64, lp_star: f64, s: &Swing, tip_acc: &Vec3) -> (f64, f64) {
    (-g / lp_star * s.theta_x + tip_acc.y / lp_star, -g / lp_star * s.theta_y - tip_acc.x / lp_star)
}

/// Load position of the linearised output equation (eqs. 4.139, 4.143):
/// x_p = x_t + l* θy, y_p = y_t − l* θx, z_p = z_t + l_p.
pub fn linear_load_position(lp_star: f64, s: &Swing, tip: &Vec3, lp: f64) -> Vec3 {
    Vec3::new(tip.x + lp_star * s.theta_y, tip.y - lp_star * s.theta_x, tip.z + lp)
}

#[cfg(test)]
pub(crate) mod tests;

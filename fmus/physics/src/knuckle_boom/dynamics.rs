//! Rigid-body dynamics of the three links on the moving deck: recursive Newton–Euler inverse
//! dynamics, the mass matrix, forward dynamics and the energy.
//!
//! Every vector is expressed in K's axes (= B's); velocities and accelerations are inertial
//! (relative to W). The ship's motion enters as the base motion of the recursion: the base's
//! angular velocity ω0 and acceleration α0 (B) and the linear acceleration of K's origin with
//! gravity folded in as an upward acceleration of the base (Featherstone 2008, §5.3, a_0 = −g):
//!
//! ```text
//! a0 = Rᵀ (a_ship − g ẑ_W) + α0 × r_base + ω0 × (ω0 × r_base)
//! ```
//!
//! (the rigid-body acceleration of the point r_base of the deck, [`crate::motion`]).

use super::kinematics::{Chain, UP};
use super::params::{ArmParams, LinkInertia};
use super::Joints;
use crate::math::{Matrix3, Quat, Vec3};
use crate::motion::ShipMotion;
use nalgebra::Vector3;

/// One link's joint and mass geometry at a joint state (K, m).
#[derive(Debug, Clone, Copy)]
struct LinkFrame {
    /// The joint's unit axis, fixed in the link before it.
    axis: Vec3,
    /// A point on the joint's axis (the joint origin).
    origin: Vec3,
    /// The centre of mass.
    com: Vec3,
    /// The link's line, the symmetry axis of its inertia.
    line: Vec3,
}

/// A link's velocity state with the base fixed (K, m, m/s, rad/s).
#[derive(Debug, Clone, Copy)]
pub(super) struct LinkVelocity {
    pub com: Vec3,
    pub com_velocity: Vec3,
    pub omega: Vec3,
}

/// The three links' frames at `chain`: column about +z through K's origin, boom about n through
/// the pivot, jib about n through the knuckle.
fn link_frames(params: &ArmParams, chain: &Chain) -> [LinkFrame; 3] {
    let [column, boom, jib] = &params.links;
    [
        LinkFrame { axis: Vec3::z(), origin: Vec3::zeros(), com: UP * column.com, line: UP },
        LinkFrame {
            axis: chain.axis,
            origin: chain.pivot,
            com: chain.pivot + chain.boom_line * boom.com,
            line: chain.boom_line,
        },
        LinkFrame {
            axis: chain.axis,
            origin: chain.knuckle,
            com: chain.knuckle + chain.jib_line * jib.com,
            line: chain.jib_line,
        },
    ]
}

/// I v for a link's inertia about its centre of mass, axisymmetric about `line`:
/// I = I_t 1 + (I_a − I_t) l lᵀ (the inertia tensor of a body of revolution in any axes).
fn inertia_times(link: &LinkInertia, line: &Vec3, v: &Vec3) -> Vec3 {
    v * link.transverse + line * ((link.axial - link.transverse) * line.dot(v))
}

impl ArmParams {
    /// Inverse dynamics: the joint torques (N·m) that give the accelerations `qdd` at `q`, `qd`
    /// on the deck moving as `ship`, with the cable's force `f_tip` (N, W axes) acting on the jib
    /// at the tip. τ = M(q) q̈ + b(q, q̇, ship) − Jᵀ f_tip (K axes): the torques the actuators
    /// supply against gravity, inertia and the cable.
    ///
    /// Recursive Newton–Euler (Featherstone 2008, ch. 5, Table 5.1; written with 3-vectors as
    /// Siciliano et al. 2009, eqs. 7.107–7.112), forward for i = 1…3 with link i−1's ω, α:
    ///
    /// ```text
    /// a_o,i = a_o,i−1 + α_i−1 × (o_i − o_i−1) + ω_i−1 × (ω_i−1 × (o_i − o_i−1))
    /// ω_i = ω_i−1 + q̇_i z_i,   α_i = α_i−1 + q̈_i z_i + q̇_i ω_i−1 × z_i
    /// a_c,i = a_o,i + α_i × (c_i − o_i) + ω_i × (ω_i × (c_i − o_i))
    /// ```
    ///
    /// and backward from f_4 = −f_tip, n_4 = 0, o_4 = tip (what the jib exerts on the cable):
    ///
    /// ```text
    /// f_i = m_i a_c,i + f_i+1
    /// n_i = n_i+1 + (o_i+1 − o_i) × f_i+1 + (c_i − o_i) × m_i a_c,i + I_i α_i + ω_i × (I_i ω_i)
    /// τ_i = z_i · n_i
    /// ```
    pub fn joint_torques(&self, ship: &ShipMotion, q: &Joints, qd: &Joints, qdd: &Joints, f_tip: &Vec3) -> Joints {
        let chain = Chain::new(self, q);
        self.newton_euler(ship, &chain, qd, qdd, f_tip)
    }

    /// Mass matrix M(q) (kg·m²; symmetric positive definite for valid parameters):
    /// M = Σ_k m_k J_v,kᵀ J_v,k + J_ω,kᵀ I_k J_ω,k with the centre-of-mass Jacobian columns
    /// J_v,k,j = z_j × (c_k − o_j) and J_ω,k,j = z_j for j ≤ k (Siciliano et al. 2009, eq. 7.32).
    pub fn mass_matrix(&self, q: &Joints) -> Matrix3<f64> {
        self.mass_matrix_at(&Chain::new(self, q))
    }

    /// The bias torques b(q, q̇, ship) = [`Self::joint_torques`] at q̈ = 0 without a tip force
    /// (gravity, Coriolis, centripetal, the base's motion) and the mass matrix M(q) = [`Self::mass_matrix`],
    /// on one evaluation of the chain: the two terms of τ = M q̈ + b a forward-dynamics caller
    /// needs (Featherstone 2008, §6.1). Bit for bit the two functions' results.
    pub fn bias_and_mass_matrix(&self, ship: &ShipMotion, q: &Joints, qd: &Joints) -> (Joints, Matrix3<f64>) {
        let chain = Chain::new(self, q);
        (self.newton_euler(ship, &chain, qd, &[0.0; 3], &Vec3::zeros()), self.mass_matrix_at(&chain))
    }

    /// Forward dynamics: q̈ = M⁻¹ (τ − b) with b = [`Self::joint_torques`] at q̈ = 0 (gravity,
    /// Coriolis, centripetal, the base's motion and the tip force; Featherstone 2008, §6.1). Err
    /// if M is not positive definite or the result is not finite.
    pub fn accelerations(
        &self,
        ship: &ShipMotion,
        q: &Joints,
        qd: &Joints,
        tau: &Joints,
        f_tip: &Vec3,
    ) -> Result<Joints, String> {
        let chain = Chain::new(self, q);
        let bias = self.newton_euler(ship, &chain, qd, &[0.0; 3], f_tip);
        let rhs = Vector3::new(tau[0] - bias[0], tau[1] - bias[1], tau[2] - bias[2]);
        let mass = self.mass_matrix_at(&chain);
        let qdd = mass
            .cholesky()
            .ok_or_else(|| format!("the mass matrix at q = {q:?} rad is not positive definite: {mass:?}"))?
            .solve(&rhs);
        if !qdd.iter().all(|v| v.is_finite()) {
            return Err(format!("joint accelerations {qdd:?} at q = {q:?}, q̇ = {qd:?}, τ = {tau:?} are not finite"));
        }
        Ok([qdd.x, qdd.y, qdd.z])
    }

    /// Kinetic and potential energy with the base fixed and the deck level (J):
    /// T = Σ ½ m_k |v_c,k|² + ½ ω_k · I_k ω_k, V = −Σ m_k g z_c,k with z_c,k the centre of mass's
    /// W z (down), so V grows with height (Siciliano et al. 2009, eqs. 7.13–7.14 and 7.28).
    pub fn energy(&self, q: &Joints, qd: &Joints) -> (f64, f64) {
        let velocities = self.link_velocities(q, qd);
        let mut kinetic = 0.0;
        let mut potential = 0.0;
        for ((link, state), line) in self.links.iter().zip(&velocities).zip(self.link_lines(q)) {
            kinetic += 0.5 * link.mass * state.com_velocity.norm_squared()
                + 0.5 * state.omega.dot(&inertia_times(link, &line, &state.omega));
            potential -= link.mass * self.g * (self.base.z + state.com.z);
        }
        (kinetic, potential)
    }

    /// The links' centre-of-mass positions and velocities and angular velocities with the base
    /// fixed, by velocity propagation (v_o,i = v_o,i−1 + ω_i−1 × (o_i − o_i−1),
    /// ω_i = ω_i−1 + q̇_i z_i, v_c,i = v_o,i + ω_i × (c_i − o_i); Siciliano et al. 2009, eq. 3.22).
    pub(super) fn link_velocities(&self, q: &Joints, qd: &Joints) -> [LinkVelocity; 3] {
        let frames = link_frames(self, &Chain::new(self, q));
        let (mut omega, mut origin_velocity, mut previous_origin) = (Vec3::zeros(), Vec3::zeros(), Vec3::zeros());
        let mut out = [LinkVelocity { com: Vec3::zeros(), com_velocity: Vec3::zeros(), omega: Vec3::zeros() }; 3];
        for ((frame, rate), state) in frames.iter().zip(qd).zip(out.iter_mut()) {
            origin_velocity += omega.cross(&(frame.origin - previous_origin));
            omega += frame.axis * *rate;
            *state = LinkVelocity {
                com: frame.com,
                com_velocity: origin_velocity + omega.cross(&(frame.com - frame.origin)),
                omega,
            };
            previous_origin = frame.origin;
        }
        out
    }

    /// The links' lines (the symmetry axes of their inertias) at `q`.
    pub(super) fn link_lines(&self, q: &Joints) -> [Vec3; 3] {
        link_frames(self, &Chain::new(self, q)).map(|frame| frame.line)
    }

    /// The base motion in K's axes: ω0, α0 and a0 (gravity folded in, see the module
    /// documentation), with `to_deck` = Rᵀ (B←W).
    fn base_motion(&self, ship: &ShipMotion, to_deck: &Quat) -> (Vec3, Vec3, Vec3) {
        let (omega, alpha, base) = (ship.omega, ship.alpha, self.base);
        let acc =
            to_deck * (ship.acc - Vec3::new(0.0, 0.0, self.g)) + alpha.cross(&base) + omega.cross(&omega.cross(&base));
        (omega, alpha, acc)
    }

    /// [`Self::joint_torques`] on a chain already evaluated.
    fn newton_euler(&self, ship: &ShipMotion, chain: &Chain, qd: &Joints, qdd: &Joints, f_tip: &Vec3) -> Joints {
        let frames = link_frames(self, chain);
        let to_deck = ship.attitude().inverse();
        let (mut omega, mut alpha, mut origin_acc) = self.base_motion(ship, &to_deck);
        let mut previous_origin = Vec3::zeros();
        // Forward: each link's ω, α and m a_c.
        let mut motion = [(Vec3::zeros(), Vec3::zeros(), Vec3::zeros()); 3];
        for (((frame, link), (rate, acc)), out) in
            frames.iter().zip(&self.links).zip(qd.iter().zip(qdd)).zip(motion.iter_mut())
        {
            let d = frame.origin - previous_origin;
            origin_acc += alpha.cross(&d) + omega.cross(&omega.cross(&d));
            alpha += frame.axis * *acc + omega.cross(&frame.axis) * *rate;
            omega += frame.axis * *rate;
            let r = frame.com - frame.origin;
            let com_acc = origin_acc + alpha.cross(&r) + omega.cross(&omega.cross(&r));
            *out = (omega, alpha, com_acc * link.mass);
            previous_origin = frame.origin;
        }
        // Backward: forces and moments at the joints, from the tip inward.
        let (mut force, mut moment, mut next_origin) = (-(to_deck * f_tip), Vec3::zeros(), chain.tip);
        let mut tau = [0.0; 3];
        for (((frame, link), (omega, alpha, inertial_force)), torque) in
            frames.iter().zip(&self.links).zip(&motion).zip(tau.iter_mut()).rev()
        {
            let angular =
                inertia_times(link, &frame.line, alpha) + omega.cross(&inertia_times(link, &frame.line, omega));
            moment +=
                (next_origin - frame.origin).cross(&force) + (frame.com - frame.origin).cross(inertial_force) + angular;
            force += inertial_force;
            *torque = frame.axis.dot(&moment);
            next_origin = frame.origin;
        }
        tau
    }

    /// [`Self::mass_matrix`] on a chain already evaluated.
    fn mass_matrix_at(&self, chain: &Chain) -> Matrix3<f64> {
        let frames = link_frames(self, chain);
        let mut mass = Matrix3::zeros();
        for (k, (body, link)) in frames.iter().zip(&self.links).enumerate() {
            // Columns of J_v, J_ω and I J_ω of link k; joints beyond k do not move it.
            let mut jv = [Vec3::zeros(); 3];
            let mut jw = [Vec3::zeros(); 3];
            let mut i_jw = [Vec3::zeros(); 3];
            for (((joint, v), w), iw) in
                frames.iter().zip(jv.iter_mut()).zip(jw.iter_mut()).zip(i_jw.iter_mut()).take(k + 1)
            {
                *v = joint.axis.cross(&(body.com - joint.origin));
                *w = joint.axis;
                *iw = inertia_times(link, &body.line, &joint.axis);
            }
            mass += Matrix3::from_fn(|i, j| link.mass * jv[i].dot(&jv[j]) + jw[i].dot(&i_jw[j]));
        }
        mass
    }
}

//! The arm's geometry at a joint state, the tip's motion, inverse kinematics and the viewer's
//! points. Frames and the tip equation: the module documentation of [`crate::knuckle_boom`].

use super::params::ArmParams;
use super::Joints;
use crate::math::{Matrix3, Vec3};
use crate::motion::{PointMotion, ShipMotion};

/// Upward unit vector in K (z points down).
pub(super) const UP: Vec3 = Vec3::new(0.0, 0.0, -1.0);

/// The directions and joint points of the chain at one joint state (K, m).
#[derive(Debug, Clone, Copy)]
pub(super) struct Chain {
    /// e: the boom plane's horizontal direction (cos θ1, sin θ1, 0).
    pub radial: Vec3,
    /// n = e × u: the axis of joints 2 and 3.
    pub axis: Vec3,
    /// The boom's line (cos θ2 e + sin θ2 u) and its in-plane normal n × line.
    pub boom_line: Vec3,
    pub boom_normal: Vec3,
    /// The jib's line (cos(θ2+θ3) e + sin(θ2+θ3) u) and its in-plane normal.
    pub jib_line: Vec3,
    pub jib_normal: Vec3,
    /// Boom pivot, knuckle and tip.
    pub pivot: Vec3,
    pub knuckle: Vec3,
    pub tip: Vec3,
}

impl Chain {
    /// The chain at `q` (the tip equation of the module documentation, as vectors).
    pub fn new(params: &ArmParams, q: &Joints) -> Chain {
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (s23, c23) = (q[1] + q[2]).sin_cos();
        let radial = Vec3::new(c1, s1, 0.0);
        let axis = Vec3::new(-s1, c1, 0.0);
        // A rotation by φ about n turns e into cos φ e + sin φ u and u into −sin φ e + cos φ u.
        let boom_line = radial * c2 + UP * s2;
        let boom_normal = UP * c2 - radial * s2;
        let jib_line = radial * c23 + UP * s23;
        let jib_normal = UP * c23 - radial * s23;
        let pivot = radial * params.pivot_offset + UP * params.pedestal_height;
        let knuckle = pivot + boom_line * params.boom_length;
        let tip = knuckle + jib_line * params.jib_length;
        Chain { radial, axis, boom_line, boom_normal, jib_line, jib_normal, pivot, knuckle, tip }
    }
}

/// A point given in a link's plane frame (origin, x and y directions) in K.
pub(super) fn plane_point(origin: &Vec3, x: &Vec3, y: &Vec3, point: [f64; 2]) -> Vec3 {
    origin + x * point[0] + y * point[1]
}

/// The points a 3D viewer draws (K, relative to K's origin, m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Skeleton {
    pub foot: Vec3,
    pub pivot: Vec3,
    pub knuckle: Vec3,
    pub tip: Vec3,
    /// Boom cylinder: pin on the column, pin on the boom.
    pub boom_cylinder: [Vec3; 2],
    /// Jib cylinder: pin on the boom, pin on the jib.
    pub jib_cylinder: [Vec3; 2],
}

impl ArmParams {
    /// Cylinder pin-to-pin lengths (m) and lever arms dL/dθ (m) of the boom (at θ2) and the jib
    /// (at θ3) cylinders.
    pub fn cylinders(&self, q: &Joints) -> [(f64, f64); 2] {
        let (boom, boom_lever, _) = self.boom_cylinder.length(q[1]);
        let (jib, jib_lever, _) = self.jib_cylinder.length(q[2]);
        [(boom, boom_lever), (jib, jib_lever)]
    }

    /// Tip position, velocity and acceleration in K relative to K's origin (m, m/s, m/s²), from
    /// q, q̇, q̈: the time derivatives of the module documentation's tip equation, with
    /// ė = θ̇1 n and ṅ = −θ̇1 e (Siciliano et al. 2009, §3.1, differentiation of the direct
    /// kinematics).
    pub fn tip_in_base(&self, q: &Joints, qd: &Joints, qdd: &Joints) -> PointMotion {
        self.tip_on_chain(&Chain::new(self, q), q, qd, qdd)
    }

    /// [`Self::tip_in_base`] on the chain at `q`, already evaluated.
    fn tip_on_chain(&self, chain: &Chain, q: &Joints, qd: &Joints, qdd: &Joints) -> PointMotion {
        let (s2, c2) = q[1].sin_cos();
        let (s23, c23) = (q[1] + q[2]).sin_cos();
        let (lb, lj) = (self.boom_length, self.jib_length);
        let (w2, w23) = (qd[1], qd[1] + qd[2]);
        let (a2, a23) = (qdd[1], qdd[1] + qdd[2]);
        // Outreach ρ and height h in the boom plane, with their rates.
        let rho = self.pivot_offset + lb * c2 + lj * c23;
        let rho_d = -lb * s2 * w2 - lj * s23 * w23;
        let rho_dd = -lb * (c2 * w2 * w2 + s2 * a2) - lj * (c23 * w23 * w23 + s23 * a23);
        let h_d = lb * c2 * w2 + lj * c23 * w23;
        let h_dd = lb * (c2 * a2 - s2 * w2 * w2) + lj * (c23 * a23 - s23 * w23 * w23);
        let (e, n) = (chain.radial, chain.axis);
        let (w1, a1) = (qd[0], qdd[0]);
        PointMotion {
            pos: chain.tip,
            vel: e * rho_d + n * (rho * w1) + UP * h_d,
            acc: e * (rho_dd - rho * w1 * w1) + n * (2.0 * rho_d * w1 + rho * a1) + UP * h_dd,
        }
    }

    /// Tip motion in W on the moving deck: [`Self::tip_in_base`] moved to B by the base offset,
    /// then [`ShipMotion::point_in_world`] (rigid-body kinematics with the transport, centripetal
    /// and Coriolis terms).
    pub fn tip_in_world(&self, ship: &ShipMotion, q: &Joints, qd: &Joints, qdd: &Joints) -> PointMotion {
        let tip = self.tip_in_base(q, qd, qdd);
        ship.point_in_world(&PointMotion { pos: self.base + tip.pos, ..tip })
    }

    /// The tip's acceleration in W as an affine function of q̈, a = J q̈ + c, on the moving
    /// deck: returns (J, c), J (m/rad, W axes) the tip's linear Jacobian and c (m/s², W) the
    /// acceleration at q̈ = 0 (velocity product terms and the deck's motion, gravity not
    /// included). One chain and one attitude for what [`Self::tip_in_world`] would give from four
    /// calls (c at q̈ = 0, the columns as the differences at unit q̈).
    ///
    /// The columns are the revolute joints' geometric Jacobian z_j × (p − o_j) (Siciliano et al.
    /// 2009, eq. 3.30), in K: ρ n for the slew (z × (ρ e + h u) = ρ n), L_b b_⊥ + L_j j_⊥ for the
    /// boom and L_j j_⊥ for the jib (b_⊥, j_⊥ the boom's and the jib's in-plane normals n × line),
    /// the derivatives of the tip equation's ρ̈ and ḧ by θ̈; rotated into W by R, since the
    /// rigid-body kinematics of [`crate::motion`] add r̈ as R r̈.
    pub fn tip_jacobian_in_world(&self, ship: &ShipMotion, q: &Joints, qd: &Joints) -> (Matrix3<f64>, Vec3) {
        let chain = Chain::new(self, q);
        let tip = self.tip_on_chain(&chain, q, qd, &[0.0; 3]);
        let rotation = ship.attitude();
        let free = ship.point_in_world_at(&rotation, &PointMotion { pos: self.base + tip.pos, ..tip });
        let outreach = chain.tip.dot(&chain.radial);
        let jib = chain.jib_normal * self.jib_length;
        let columns = [chain.axis * outreach, chain.boom_normal * self.boom_length + jib, jib];
        (Matrix3::from_columns(&columns.map(|column| rotation * column)), free.acc)
    }

    /// The joints that put the tip at `p` (K, relative to K's origin, m), knuckle up (θ3 ≤ 0):
    /// θ1 = atan2(p_y, p_x) (the tip in front of the slew axis), then the planar two-link inverse
    /// (Siciliano et al. 2009, §2.12.1): with r, z the tip's distance from the pivot along e and
    /// up, cos θ3 = (r² + z² − L_b² − L_j²) / (2 L_b L_j), θ3 = −acos(…),
    /// θ2 = atan2(z, r) − atan2(L_j sin θ3, L_b + L_j cos θ3).
    /// Err if `p` is not finite, on the slew axis, out of reach, or needs a cylinder outside its
    /// stroke.
    pub fn inverse_kinematics(&self, p: &Vec3) -> Result<Joints, String> {
        if !p.iter().all(|v| v.is_finite()) {
            return Err(format!("tip target {p:?} m must be finite"));
        }
        let outreach = p.x.hypot(p.y);
        if outreach < 1e-9 {
            return Err(format!("tip target {p:?} m lies on the slew axis (slew angle undefined)"));
        }
        let slew = p.y.atan2(p.x);
        let (r, z) = (outreach - self.pivot_offset, -p.z - self.pedestal_height);
        let (lb, lj) = (self.boom_length, self.jib_length);
        let cos_jib = (r * r + z * z - lb * lb - lj * lj) / (2.0 * lb * lj);
        if !(cos_jib.abs() <= 1.0) {
            return Err(format!(
                "tip target {p:?} m is {:.4} m from the boom pivot, outside the reach {:.4}–{:.4} m",
                r.hypot(z),
                (lb - lj).abs(),
                lb + lj
            ));
        }
        let jib = -cos_jib.acos();
        let boom = z.atan2(r) - (lj * jib.sin()).atan2(lb + lj * jib.cos());
        let [(boom_min, boom_max), (jib_min, jib_max)] = self.joint_limits()?;
        if !(boom >= boom_min && boom <= boom_max && jib >= jib_min && jib <= jib_max) {
            return Err(format!(
                "tip target {p:?} m needs boom {:.3}° (range {:.3}…{:.3}°) and jib {:.3}° (range {:.3}…{:.3}°)",
                boom.to_degrees(),
                boom_min.to_degrees(),
                boom_max.to_degrees(),
                jib.to_degrees(),
                jib_min.to_degrees(),
                jib_max.to_degrees()
            ));
        }
        Ok([slew, boom, jib])
    }

    /// The points the 3D viewer draws at `q` (K, relative to K's origin, m).
    pub fn skeleton(&self, q: &Joints) -> Skeleton {
        let c = Chain::new(self, q);
        let (boom, jib) = (&self.boom_cylinder, &self.jib_cylinder);
        Skeleton {
            foot: Vec3::zeros(),
            pivot: c.pivot,
            knuckle: c.knuckle,
            tip: c.tip,
            boom_cylinder: [
                plane_point(&c.pivot, &c.radial, &UP, boom.lower_pin),
                plane_point(&c.pivot, &c.boom_line, &c.boom_normal, boom.upper_pin),
            ],
            jib_cylinder: [
                plane_point(&c.knuckle, &c.boom_line, &c.boom_normal, jib.lower_pin),
                plane_point(&c.knuckle, &c.jib_line, &c.jib_normal, jib.upper_pin),
            ],
        }
    }
}

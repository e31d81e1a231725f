use super::dynamics::{compare_with_lagrangian, STILL};
use super::{offset_arm, samples, Worst};
use crate::knuckle_boom::{ArmParams, Joints};
use crate::math::{Quat, Vec3};
use crate::motion::{PointMotion, ShipMotion};
use nalgebra::Unit;

/// A deck translating with constant acceleration a (level, not rotating) gives the same joint
/// accelerations as a deck at rest under gravity g ẑ − a (Einstein's equivalence): for a
/// vertical a by a smaller g, for a general a by a fixed deck tilted so that its z axis points
/// along g ẑ − a, with |g ẑ − a| as g (and the tip force turned with the deck).
#[test]
fn a_uniformly_accelerating_deck_is_a_change_of_gravity() {
    let arm = offset_arm();
    let tau = [2.0e4, 1.5e5, 6.0e4];
    let force = Vec3::new(1.0e3, -2.0e3, 2.5e4);
    let mut worst = Worst::new(1e-10);
    for acc in [Vec3::new(0.0, 0.0, 1.2), Vec3::new(0.8, -0.6, -0.9), Vec3::new(-1.5, 0.4, 0.3)] {
        let moving = ShipMotion { vel: Vec3::new(2.0, 0.3, -0.1), acc, ..STILL };
        let gravity = Vec3::new(0.0, 0.0, arm.g) - acc;
        let down = gravity / gravity.norm();
        // R ᵀ ẑ = (−sin θ, cos θ sin φ, cos θ cos φ) for R = R_z R_y(θ) R_x(φ).
        let (pitch, roll) = ((-down.x).asin(), down.y.atan2(down.z));
        let tilted = ShipMotion { roll, pitch, ..STILL };
        let equivalent = ArmParams { g: gravity.norm(), ..arm };
        let turned_force = tilted.attitude() * force;
        for (q, qd, _) in samples() {
            let a = arm.accelerations(&moving, &q, &qd, &tau, &force).unwrap();
            let b = equivalent.accelerations(&tilted, &q, &qd, &tau, &turned_force).unwrap();
            worst.compare(&a, &b, format_args!("a = {acc:?}, q = {q:?}"));
        }
    }
    worst.report("accelerating deck vs changed gravity");
}

/// The deck turning about a fixed body axis k with the angle φ(t) = w t + α t²/2 (constant α, so
/// ω = φ̇ k and α k in B), its origin accelerating uniformly, the whole seen from W: the
/// Euler–Lagrange torques of the world-frame Lagrangian L(q, q̇, t) = T − V, evaluated by finite
/// differences, equal the recursion's. The world energy uses the deck-relative velocities of
/// the links moved through `ShipMotion::point_in_world` and the links' world angular velocity
/// ω_ship + ω_rel, independently of the recursion's acceleration terms.
#[test]
fn a_rotating_deck_matches_the_world_frame_lagrangian() {
    let arm = offset_arm();
    let mut worst = Worst::new(1e-6);
    let cases = [(0.15, 0.0), (0.05, 0.3), (-0.2, -0.1)];
    for (rate, angular_acc) in cases {
        let axis = Unit::new_normalize(Vec3::new(0.3, -0.5, 0.8));
        let start = Quat::from_euler_angles(0.1, -0.05, 0.7);
        let ship_at = |t: f64| {
            let attitude = start * Quat::from_axis_angle(&axis, rate * t + 0.5 * angular_acc * t * t);
            let (roll, pitch, yaw) = attitude.euler_angles();
            let (p0, v0, acc) = (Vec3::new(5.0, 2.0, 0.3), Vec3::new(1.0, -0.4, 0.2), Vec3::new(0.3, 0.1, -0.6));
            ShipMotion {
                pos: p0 + v0 * t + acc * (0.5 * t * t),
                roll,
                pitch,
                yaw,
                vel: v0 + acc * t,
                acc,
                omega: axis.into_inner() * (rate + angular_acc * t),
                alpha: axis.into_inner() * angular_acc,
            }
        };
        let lagrangian = |q: &Joints, qd: &Joints, t: f64| {
            let ship = ship_at(t);
            let mut kinetic = 0.0;
            let mut potential = 0.0;
            let lines = arm.link_lines(q);
            for ((link, state), line) in arm.links.iter().zip(arm.link_velocities(q, qd)).zip(lines) {
                let relative = PointMotion { pos: arm.base + state.com, vel: state.com_velocity, acc: Vec3::zeros() };
                let world = ship.point_in_world(&relative);
                let omega = ship.omega + state.omega;
                let spin = omega * link.transverse + line * ((link.axial - link.transverse) * line.dot(&omega));
                kinetic += 0.5 * link.mass * world.vel.norm_squared() + 0.5 * omega.dot(&spin);
                potential -= link.mass * arm.g * world.pos.z;
            }
            kinetic - potential
        };
        let case = format!("ω {rate}, α {angular_acc}, ");
        compare_with_lagrangian(&mut worst, &arm, &ship_at(0.0), lagrangian, &case);
    }
    worst.report("rotating deck vs world-frame Lagrangian");
}

/// The deck's rotation changes the torques (the check above is not blind to it): a yaw rate of
/// 0.1 rad/s adds the centrifugal term ∂/∂θ2 of ½ ω² I_zz(q).
#[test]
fn deck_rotation_changes_the_torques() {
    let arm = ArmParams::DEFAULT;
    let q = [0.0, 0.4, -0.9];
    let spinning = ShipMotion { omega: Vec3::new(0.0, 0.0, 0.1), ..STILL };
    let still = arm.joint_torques(&STILL, &q, &[0.0; 3], &[0.0; 3], &Vec3::zeros());
    let turning = arm.joint_torques(&spinning, &q, &[0.0; 3], &[0.0; 3], &Vec3::zeros());
    // Base fixed rotation ω about the slew axis: the torque on θ2 falls by ½ ω² ∂M11/∂θ2.
    let h = 1e-6;
    let m11 = |theta2: f64| arm.mass_matrix(&[0.0, theta2, q[2]])[(0, 0)];
    let centrifugal = 0.5 * 0.01 * (m11(q[1] + h) - m11(q[1] - h)) / (2.0 * h);
    assert!((turning[1] - (still[1] - centrifugal)).abs() < 1e-6 * still[1].abs(), "{turning:?} vs {still:?}");
    assert!(centrifugal.abs() > 100.0, "{centrifugal}");
}

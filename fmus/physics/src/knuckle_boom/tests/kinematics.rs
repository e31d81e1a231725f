use super::{arms, offset_arm, samples, Worst};
use crate::knuckle_boom::{ArmParams, Joints};
use crate::math::{euler_zyx, Vec3};
use crate::motion::{PointMotion, ShipMotion};

#[test]
fn tip_is_the_closed_form() {
    for arm in arms() {
        for (q, _, _) in samples() {
            let rho = arm.pivot_offset + arm.boom_length * q[1].cos() + arm.jib_length * (q[1] + q[2]).cos();
            let h = arm.pedestal_height + arm.boom_length * q[1].sin() + arm.jib_length * (q[1] + q[2]).sin();
            let expected = Vec3::new(rho * q[0].cos(), rho * q[0].sin(), -h);
            let tip = arm.tip_in_base(&q, &[0.0; 3], &[0.0; 3]);
            assert!((tip.pos - expected).norm() < 1e-12, "{q:?}");
            assert_eq!(tip.vel, Vec3::zeros());
        }
    }
    // θ1 = −π/2, boom and jib level: the tip 12.2 m to port at the pivot's height.
    let tip = ArmParams::DEFAULT.tip_in_base(&[-std::f64::consts::FRAC_PI_2, 0.0, 0.0], &[0.0; 3], &[0.0; 3]);
    assert!((tip.pos - Vec3::new(0.0, -12.2, -2.2)).norm() < 1e-12, "{:?}", tip.pos);
}

/// Along q(t) = q0 + A sin(w t + φ), the tip's velocity and acceleration are the central
/// differences of its position and velocity.
#[test]
fn tip_velocity_and_acceleration_are_the_derivatives_of_its_position() {
    let amplitude = [0.8, 0.4, 0.6];
    let rate = [0.7, 1.3, 1.9];
    let phase = [0.0, 0.5, 1.0];
    let joints = |t: f64| -> (Joints, Joints, Joints) {
        let mut out = ([0.1, 0.5, -1.0], [0.0; 3], [0.0; 3]);
        for i in 0..3 {
            let arg = rate[i] * t + phase[i];
            out.0[i] += amplitude[i] * arg.sin();
            out.1[i] = amplitude[i] * rate[i] * arg.cos();
            out.2[i] = -amplitude[i] * rate[i] * rate[i] * arg.sin();
        }
        out
    };
    let h = 1e-5;
    let mut worst = Worst::new(1e-8);
    for arm in arms() {
        let at = |t: f64| {
            let (q, qd, qdd) = joints(t);
            arm.tip_in_base(&q, &qd, &qdd)
        };
        for k in 0..20 {
            let t = 0.37 * k as f64;
            let tip = at(t);
            let fd_vel = (at(t + h).pos - at(t - h).pos) / (2.0 * h);
            let fd_acc = (at(t + h).vel - at(t - h).vel) / (2.0 * h);
            let error = ((tip.vel - fd_vel).norm() / tip.vel.norm()).max((tip.acc - fd_acc).norm() / tip.acc.norm());
            worst.record(error, || format!("t = {t}: {tip:?} vs {fd_vel:?}, {fd_acc:?}"));
        }
    }
    worst.report("tip velocity/acceleration vs finite differences");
}

#[test]
fn inverse_kinematics_round_trips_over_the_workspace() {
    let mut worst: f64 = 0.0;
    let mut count = 0;
    for arm in arms() {
        let [(boom_min, boom_max), (jib_min, jib_max)] = arm.joint_limits().unwrap();
        for i in 0..=12 {
            for j in 0..=12 {
                for slew in [-3.0, -std::f64::consts::FRAC_PI_2, 0.4, 2.5] {
                    // Inside the limits, the fully stretched jib (θ3 → 0) excluded by its limit.
                    let boom = boom_min + (boom_max - boom_min) * i as f64 / 12.0;
                    let jib = jib_min + (jib_max - jib_min) * j as f64 / 12.0;
                    let q = [slew, boom, jib];
                    let target = arm.tip_in_base(&q, &[0.0; 3], &[0.0; 3]).pos;
                    let solved = match arm.inverse_kinematics(&target) {
                        Ok(solved) => solved,
                        // The range ends may round just outside their limits.
                        Err(e) if i == 0 || i == 12 || j == 0 || j == 12 => {
                            assert!(e.contains("range"), "{e}");
                            continue;
                        }
                        Err(e) => panic!("{q:?}: {e}"),
                    };
                    let reached = arm.tip_in_base(&solved, &[0.0; 3], &[0.0; 3]).pos;
                    let error = (reached - target).norm();
                    assert!(error < 1e-9, "{q:?} → {solved:?}: {error} m");
                    assert!(q.iter().zip(&solved).all(|(a, b)| (a - b).abs() < 1e-7), "{q:?} → {solved:?}");
                    worst = worst.max(error);
                    count += 1;
                }
            }
        }
    }
    assert!(count > 1200, "{count} round trips");
    println!("inverse kinematics: {count} round trips, largest tip error {worst:.2e} m");
}

#[test]
fn inverse_kinematics_refuses_unreachable_targets() {
    let arm = ArmParams::DEFAULT;
    let cases = [
        (Vec3::new(0.0, 0.0, -5.0), "slew axis"),
        (Vec3::new(0.0, -12.5, -2.2), "outside the reach"),
        (Vec3::new(0.5, 0.0, -2.0), "outside the reach"),
        (Vec3::new(f64::NAN, 1.0, 0.0), "finite"),
        // Straight down from the pivot, 8 m: the boom would have to point below −20°.
        (Vec3::new(1.0, 0.0, 5.0), "range"),
    ];
    for (target, reason) in cases {
        let error = arm.inverse_kinematics(&target).unwrap_err();
        assert!(error.contains(reason), "{target:?}: {error}");
    }
}

#[test]
fn tip_in_world_is_the_deck_point_moved_by_the_ship() {
    let arm = offset_arm();
    let ship = moving_deck();
    for (q, qd, qdd) in samples() {
        let tip = arm.tip_in_base(&q, &qd, &qdd);
        let world = arm.tip_in_world(&ship, &q, &qd, &qdd);
        let r = arm.base + tip.pos;
        let rotation = euler_zyx(ship.roll, ship.pitch, ship.yaw);
        assert!((world.pos - (ship.pos + rotation * r)).norm() < 1e-12);
        let expected = ship.point_in_world(&PointMotion { pos: r, ..tip });
        assert!((world.vel - expected.vel).norm() < 1e-12 && (world.acc - expected.acc).norm() < 1e-12);
    }
}

#[test]
fn skeleton_cylinders_have_the_mechanism_lengths() {
    for arm in arms() {
        for (q, _, _) in samples() {
            let s = arm.skeleton(&q);
            let [(boom, _), (jib, _)] = arm.cylinders(&q);
            assert!(((s.boom_cylinder[1] - s.boom_cylinder[0]).norm() - boom).abs() < 1e-12);
            assert!(((s.jib_cylinder[1] - s.jib_cylinder[0]).norm() - jib).abs() < 1e-12);
            assert!((s.pivot - s.foot).norm() > 2.2 - 1e-12);
            assert!(((s.knuckle - s.pivot).norm() - arm.boom_length).abs() < 1e-12);
            assert!(((s.tip - s.knuckle).norm() - arm.jib_length).abs() < 1e-12);
            assert!((s.tip - arm.tip_in_base(&q, &[0.0; 3], &[0.0; 3]).pos).norm() < 1e-15);
            // The pins lie in the boom plane: vertical plane through the slew axis along e.
            let e = Vec3::new(q[0].cos(), q[0].sin(), 0.0);
            let n = Vec3::new(-q[0].sin(), q[0].cos(), 0.0);
            for pin in s.boom_cylinder.iter().chain(&s.jib_cylinder) {
                assert!(pin.dot(&n).abs() < 1e-12, "{pin:?} off the plane along {e:?}");
            }
        }
    }
}

/// A tilted, moving deck (attitude, velocities and accelerations of every kind).
fn moving_deck() -> ShipMotion {
    ShipMotion {
        pos: Vec3::new(1.0, -2.0, 0.3),
        roll: 0.05,
        pitch: -0.03,
        yaw: 0.4,
        vel: Vec3::new(0.5, 0.1, -0.2),
        acc: Vec3::new(0.02, -0.1, 0.3),
        omega: Vec3::new(0.02, -0.01, 0.03),
        alpha: Vec3::new(-0.01, 0.02, 0.005),
    }
}

/// J is ∂p_W/∂q (central differences of the tip's world position, step 1e-6 rad, truncation
/// O(h²) ≈ 1e-11 m/rad), and J q̈ + c is the acceleration of [`ArmParams::tip_in_world`] on the
/// moving deck.
#[test]
fn tip_jacobian_is_the_derivative_of_the_world_position_and_gives_the_acceleration() {
    let ship = moving_deck();
    let h = 1e-6;
    let (mut worst_jacobian, mut worst_acc) = (0.0f64, 0.0f64);
    for arm in arms() {
        for (q, qd, qdd) in samples() {
            let (jacobian, free) = arm.tip_jacobian_in_world(&ship, &q, &qd);
            for j in 0..3 {
                let at = |delta: f64| {
                    let mut moved = q;
                    moved[j] += delta;
                    arm.tip_in_world(&ship, &moved, &qd, &qdd).pos
                };
                let difference = (at(h) - at(-h)) / (2.0 * h);
                worst_jacobian = worst_jacobian.max((jacobian.column(j) - difference).norm() / difference.norm());
            }
            let acc = arm.tip_in_world(&ship, &q, &qd, &qdd).acc;
            let affine = jacobian * Vec3::new(qdd[0], qdd[1], qdd[2]) + free;
            worst_acc = worst_acc.max((affine - acc).norm() / acc.norm());
        }
    }
    println!("tip Jacobian: central differences {worst_jacobian:.2e}, J q̈ + c against tip_in_world {worst_acc:.2e}");
    assert!(worst_jacobian < 1e-7 && worst_acc < 1e-12);
}

/// On a tilted deck at rest, c is the time derivative of the tip's world velocity along the path
/// q(t) = q + q̇ t with q̈ = 0 (central differences, step 1e-5 s).
#[test]
fn tip_velocity_term_is_the_derivative_of_the_velocity_at_zero_joint_acceleration() {
    let ship =
        ShipMotion { pos: Vec3::new(1.0, -2.0, 0.3), roll: 0.05, pitch: -0.03, yaw: 0.4, ..ShipMotion::default() };
    let h = 1e-5;
    let mut worst = 0.0f64;
    for arm in arms() {
        for (q, qd, _) in samples() {
            let (_, free) = arm.tip_jacobian_in_world(&ship, &q, &qd);
            let velocity = |t: f64| {
                let moved: Joints = std::array::from_fn(|i| q[i] + qd[i] * t);
                arm.tip_in_world(&ship, &moved, &qd, &[0.0; 3]).vel
            };
            let difference = (velocity(h) - velocity(-h)) / (2.0 * h);
            worst = worst.max((free - difference).norm() / difference.norm().max(1e-3));
        }
    }
    println!("tip velocity term c against central differences: {worst:.2e}");
    assert!(worst < 1e-7);
}

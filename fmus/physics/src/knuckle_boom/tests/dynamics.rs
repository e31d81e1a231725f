use super::{arms, offset_arm, relative_error, samples, Worst};
use crate::integrate::rk4;
use crate::knuckle_boom::{ArmParams, Joints, LinkInertia, Mechanism};
use crate::math::{SVector, Vec3};
use crate::motion::ShipMotion;

/// The deck at rest, level (the fixed base).
pub(super) const STILL: ShipMotion = ShipMotion::AT_REST;

fn add(a: &Joints, b: &Joints, scale: f64) -> Joints {
    [a[0] + b[0] * scale, a[1] + b[1] * scale, a[2] + b[2] * scale]
}

fn unit(i: usize) -> Joints {
    let mut e = [0.0; 3];
    e[i] = 1.0;
    e
}

/// The Euler–Lagrange torques d/dt(∂L/∂q̇) − ∂L/∂q of a Lagrangian `lagrangian(q, q̇, t)` at
/// t = 0 along q(t) = q + q̇ t + q̈ t²/2, all by central differences (L is quadratic in q̇, so the
/// q̇ difference is exact up to rounding).
pub(super) fn euler_lagrange(
    lagrangian: impl Fn(&Joints, &Joints, f64) -> f64,
    q: &Joints,
    qd: &Joints,
    qdd: &Joints,
) -> Joints {
    let (hv, ht, hq) = (1e-3, 1e-4, 1e-6);
    let momentum = |i: usize, t: f64| {
        let (qt, qdt) = (add(&add(q, qd, t), qdd, 0.5 * t * t), add(qd, qdd, t));
        (lagrangian(&qt, &add(&qdt, &unit(i), hv), t) - lagrangian(&qt, &add(&qdt, &unit(i), -hv), t)) / (2.0 * hv)
    };
    let mut tau = [0.0; 3];
    for (i, out) in tau.iter_mut().enumerate() {
        let d_momentum = (momentum(i, ht) - momentum(i, -ht)) / (2.0 * ht);
        let d_q =
            (lagrangian(&add(q, &unit(i), hq), qd, 0.0) - lagrangian(&add(q, &unit(i), -hq), qd, 0.0)) / (2.0 * hq);
        *out = d_momentum - d_q;
    }
    tau
}

/// Compares, over [`samples`], the recursion's joint torques on the deck `ship` (no tip force)
/// with the Euler–Lagrange torques of `lagrangian`, into `worst` (`case` leads the message).
pub(super) fn compare_with_lagrangian(
    worst: &mut Worst,
    arm: &ArmParams,
    ship: &ShipMotion,
    lagrangian: impl Fn(&Joints, &Joints, f64) -> f64,
    case: &str,
) {
    for (q, qd, qdd) in samples() {
        let tau = arm.joint_torques(ship, &q, &qd, &qdd, &Vec3::zeros());
        worst.compare(&tau, &euler_lagrange(&lagrangian, &q, &qd, &qdd), format_args!("{case}q = {q:?}"));
    }
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_and_gives_the_kinetic_energy() {
    for arm in arms() {
        for (q, qd, _) in samples() {
            let m = arm.mass_matrix(&q);
            assert!((m - m.transpose()).abs().max() <= 1e-12 * m.abs().max(), "{m}");
            let eigen = m.symmetric_eigen().eigenvalues;
            assert!(eigen.min() > 0.0, "{eigen}");
            let v = SVector::<f64, 3>::from(qd);
            let kinetic = 0.5 * v.dot(&(m * v));
            let (energy, _) = arm.energy(&q, &qd);
            assert!((kinetic - energy).abs() < 1e-11 * energy, "{kinetic} vs {energy}");
        }
    }
    // Slew inertia of the level, straight arm (closed form): column m r²/2, boom and jib as
    // uniform rods about a perpendicular axis at distances 0…7 m and 7…12.2 m, plus their small
    // axial inertia about the vertical (their transverse moment of the box section).
    let arm = ArmParams::DEFAULT;
    let [column, boom, jib] = arm.links;
    let rod = |mass: f64, from: f64, to: f64| mass * (to.powi(3) - from.powi(3)) / (3.0 * (to - from));
    let expected = column.axial
        + rod(boom.mass, 0.0, 7.0)
        + rod(jib.mass, 7.0, 12.2)
        + (boom.transverse - boom.mass * 49.0 / 12.0)
        + (jib.transverse - jib.mass * 5.2 * 5.2 / 12.0);
    let m = arm.mass_matrix(&[0.3, 0.0, 0.0]);
    assert!((m[(0, 0)] - expected).abs() < 1e-9 * expected, "{} vs {expected}", m[(0, 0)]);
}

#[test]
fn joint_torques_are_the_lagrangian_of_the_energy() {
    let mut worst = Worst::new(1e-6);
    for arm in arms() {
        let lagrangian = |q: &Joints, qd: &Joints, _t: f64| {
            let (kinetic, potential) = arm.energy(q, qd);
            kinetic - potential
        };
        compare_with_lagrangian(&mut worst, &arm, &STILL, lagrangian, "");
    }
    worst.report("RNEA vs Lagrangian of the energy");
}

#[test]
fn tip_force_torques_are_the_jacobian_transpose() {
    let mut worst = Worst::new(1e-8);
    let force = Vec3::new(3.0e3, -1.5e3, 4.0e4);
    for arm in arms() {
        for (q, qd, qdd) in samples() {
            let with = arm.joint_torques(&STILL, &q, &qd, &qdd, &force);
            let without = arm.joint_torques(&STILL, &q, &qd, &qdd, &Vec3::zeros());
            let h = 1e-6;
            let tip = |q: &Joints| arm.tip_in_base(q, &[0.0; 3], &[0.0; 3]).pos;
            let mut expected = [0.0; 3];
            for (i, out) in expected.iter_mut().enumerate() {
                let column = (tip(&add(&q, &unit(i), h)) - tip(&add(&q, &unit(i), -h))) / (2.0 * h);
                // The actuators hold against the cable: τ = … − Jᵀ f.
                *out = -column.dot(&force);
            }
            let difference = [with[0] - without[0], with[1] - without[1], with[2] - without[2]];
            worst.compare(&difference, &expected, format_args!("{q:?}"));
        }
    }
    worst.report("tip force vs −Jᵀ f");
}

#[test]
fn accelerations_invert_joint_torques() {
    let arm = offset_arm();
    let ship = ShipMotion { omega: Vec3::new(0.02, -0.03, 0.01), acc: Vec3::new(0.1, 0.2, -0.5), ..STILL };
    let force = Vec3::new(0.0, 2.0e3, 3.0e4);
    for (q, qd, qdd) in samples() {
        let tau = arm.joint_torques(&ship, &q, &qd, &qdd, &force);
        let back = arm.accelerations(&ship, &q, &qd, &tau, &force).unwrap();
        assert!(relative_error(&back, &qdd) < 1e-9, "{back:?} vs {qdd:?}");
    }
    let error = arm.accelerations(&ship, &[0.0, f64::NAN, 0.0], &[0.0; 3], &[0.0; 3], &force).unwrap_err();
    assert!(error.contains("not"), "{error}");
}

/// τ = 0, no tip force, fixed base, RK4 at 1 ms for 60 s from a swinging, slewing start: the
/// total energy is an invariant of the exact motion, so its drift is the dynamics' and the
/// integrator's consistency.
#[test]
fn free_motion_conserves_energy() {
    let arm = ArmParams::DEFAULT;
    let mut x = SVector::<f64, 6>::from([0.2, 0.6, -1.0, 0.3, 0.5, -0.8]);
    let split = |x: &SVector<f64, 6>| ([x[0], x[1], x[2]], [x[3], x[4], x[5]]);
    let total = |x: &SVector<f64, 6>| {
        let (q, qd) = split(x);
        let (kinetic, potential) = arm.energy(&q, &qd);
        kinetic + potential
    };
    let start = total(&x);
    let rhs = |_t: f64, x: &SVector<f64, 6>| {
        let (q, qd) = split(x);
        let qdd = arm.accelerations(&STILL, &q, &qd, &[0.0; 3], &Vec3::zeros()).unwrap();
        SVector::<f64, 6>::from([qd[0], qd[1], qd[2], qdd[0], qdd[1], qdd[2]])
    };
    let dt = 1e-3;
    let mut worst: f64 = 0.0;
    for step in 0..60_000 {
        x = rk4(&x, step as f64 * dt, dt, rhs);
        worst = worst.max((total(&x) - start).abs() / start.abs());
    }
    assert!(worst < 1e-8, "energy drift {worst:.3e} of {start} J");
    println!("energy over 60 s: start {start:.3} J, largest relative drift {worst:.2e}");
}

/// ns per `accelerations` call (run with `--release --ignored --nocapture`).
#[test]
#[ignore]
fn accelerations_timing() {
    let arm = ArmParams::DEFAULT;
    let ship = ShipMotion { omega: Vec3::new(0.02, -0.03, 0.01), acc: Vec3::new(0.1, 0.2, -0.5), ..STILL };
    let n = 2_000_000;
    let start = std::time::Instant::now();
    let mut sum = 0.0;
    for i in 0..n {
        let s = i as f64 * 1e-6;
        let q = [s, 0.5 + s, -1.0 - s];
        let qdd = arm.accelerations(&ship, &q, &[0.1, 0.2, 0.3], &[1e4, 2e5, 1e5], &Vec3::new(0.0, 0.0, 3e4));
        sum += std::hint::black_box(qdd).map(|a| a[1]).unwrap_or(0.0);
    }
    let ns = start.elapsed().as_nanos() as f64 / n as f64;
    println!("accelerations: {ns:.1} ns per call (checksum {sum:.3})");
}

/// Holding the arm still: τ2 and τ3 are the links' weights times their horizontal lever arms
/// about the pivot and the knuckle, and on a deck rolled by φ the slew holds the sideways weight
/// component m g sin φ at each centre of mass's outreach (statics, closed form).
#[test]
fn static_torques_are_the_weights_times_their_lever_arms() {
    let arm = offset_arm();
    let [_, boom, jib] = arm.links;
    let (lb, g) = (arm.boom_length, arm.g);
    for (q, _, _) in samples() {
        let (c2, c23) = (q[1].cos(), (q[1] + q[2]).cos());
        let tau = arm.joint_torques(&STILL, &q, &[0.0; 3], &[0.0; 3], &Vec3::zeros());
        let jib_torque = g * jib.mass * jib.com * c23;
        let boom_torque = g * (boom.mass * boom.com * c2 + jib.mass * (lb * c2 + jib.com * c23));
        assert!(tau[0].abs() < 1e-9 && (tau[1] - boom_torque).abs() < 1e-9 * boom_torque.abs(), "{tau:?}");
        assert!((tau[2] - jib_torque).abs() < 1e-9 * jib_torque.abs().max(1.0), "{tau:?} vs {jib_torque}");
    }
    let roll: f64 = 0.08;
    let rolled = ShipMotion { roll, ..STILL };
    let q: Joints = [0.0, 0.5, -1.2];
    let outreach = |com: f64, along: f64| arm.pivot_offset + along + com;
    let moment = boom.mass * outreach(boom.com * q[1].cos(), 0.0)
        + jib.mass * outreach(jib.com * (q[1] + q[2]).cos(), arm.boom_length * q[1].cos());
    let tau = arm.joint_torques(&rolled, &q, &[0.0; 3], &[0.0; 3], &Vec3::zeros());
    let expected = -g * roll.sin() * moment;
    assert!((tau[0] - expected).abs() < 1e-9 * expected.abs(), "{} vs {expected}", tau[0]);
    // The level straight arm: 195.7 kN·m on the boom (the documented cylinder load).
    let level = ArmParams::DEFAULT.joint_torques(&STILL, &[0.0; 3], &[0.0; 3], &[0.0; 3], &Vec3::zeros());
    assert!((level[1] - 195_744.656_66).abs() < 1e-3, "{level:?}");
}

#[test]
fn invalid_parameters_are_refused_by_name() {
    assert_eq!(ArmParams::DEFAULT.validate(), Ok(()));
    assert_eq!(offset_arm().validate(), Ok(()));
    let d = ArmParams::DEFAULT;
    let [column, boom, jib] = d.links;
    let cases = [
        (ArmParams { boom_length: 0.0, ..d }, "boom_length 0"),
        (ArmParams { jib_length: f64::NAN, ..d }, "jib_length NaN"),
        (ArmParams { pedestal_height: -2.2, ..d }, "pedestal_height -2.2"),
        (ArmParams { pivot_offset: f64::INFINITY, ..d }, "pivot_offset inf"),
        (ArmParams { base: Vec3::new(0.0, f64::NAN, 0.0), ..d }, "base"),
        (ArmParams { g: -9.8, ..d }, "g -9.8"),
        (ArmParams { links: [LinkInertia { mass: 0.0, ..column }, boom, jib], ..d }, "column mass 0"),
        (ArmParams { links: [column, LinkInertia { axial: 1e5, ..boom }, jib], ..d }, "boom axial inertia 100000"),
        (
            ArmParams { links: [column, boom, LinkInertia { transverse: -1.0, ..jib }], ..d },
            "jib transverse inertia -1",
        ),
        (ArmParams { links: [column, boom, LinkInertia { com: f64::NAN, ..jib }], ..d }, "jib centre of mass NaN"),
        (ArmParams { jib_cylinder: Mechanism { max_length: 9.0, ..d.jib_cylinder }, ..d }, "jib_cylinder: pins"),
    ];
    for (params, expected) in cases {
        let error = params.validate().unwrap_err();
        assert!(error.contains(expected), "{error} does not name {expected}");
    }
}

/// The shared evaluation gives the bias torques and the mass matrix of the two separate
/// functions, bit for bit, on a moving, tilted deck.
#[test]
fn bias_and_mass_matrix_are_joint_torques_and_mass_matrix() {
    let ship = ShipMotion {
        roll: 0.05,
        pitch: -0.03,
        yaw: 0.4,
        omega: Vec3::new(0.02, -0.03, 0.01),
        alpha: Vec3::new(-0.01, 0.02, 0.005),
        acc: Vec3::new(0.1, 0.2, -0.5),
        ..STILL
    };
    for arm in arms() {
        for (q, qd, _) in samples() {
            let (bias, mass) = arm.bias_and_mass_matrix(&ship, &q, &qd);
            assert_eq!(bias, arm.joint_torques(&ship, &q, &qd, &[0.0; 3], &Vec3::zeros()));
            assert_eq!(mass, arm.mass_matrix(&q));
        }
    }
}

use super::*;
use crate::crane::mechanisms::{MECHANISMS, STROKE};
use crate::math::{rot_x, rot_z, Vec3};

const DEG: f64 = std::f64::consts::PI / 180.0;

/// The 11³ actuator set-points of §4.2.7 (0–50 mm, 5 mm steps), in m.
fn actuator_grid() -> Vec<[f64; 3]> {
    let steps: Vec<f64> = (0..=10).map(|i| i as f64 * 0.005).collect();
    let mut grid = Vec::new();
    for &a in &steps {
        for &b in &steps {
            for &c in &steps {
                grid.push([a, b, c]);
            }
        }
    }
    grid
}

fn rmsd(errors: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = errors.fold((0.0, 0usize), |(s, n), e| (s + e * e, n + 1));
    (sum / n as f64).sqrt()
}

/// The tip by composing the joint transformations of eqs. 4.14–4.16 and 4.67–4.69 (mm).
fn tip_by_composition(theta: &[f64; 3]) -> Vec3 {
    let jib = rot_x(theta[2]) * Vec3::new(0.0, -L4Y, 0.0);
    let boom = rot_x(theta[1]) * (Vec3::new(0.0, -L3Y, 0.0) + jib);
    rot_z(theta[0]) * (Vec3::new(0.0, 0.0, -L2Z) + boom)
}

#[test]
fn forward_kinematics_equals_the_composed_chain() {
    let worst = actuator_grid()
        .iter()
        .map(|d| {
            let theta = joints_from_actuators(d).unwrap();
            let [x, y, z] = forward(&theta);
            (Vec3::new(x, y, z) * 1000.0 - tip_by_composition(&theta)).amax()
        })
        .fold(0.0, f64::max);
    println!("eqs. 4.73–4.75 vs the composed joint transformations over 11³ set-points: max {worst:.3e} mm");
    assert!(worst < 1e-12);
}

#[test]
fn inverse_kinematics_round_trip_over_the_workspace() {
    let grid = actuator_grid();
    let mut theta_err = [Vec::new(), Vec::new(), Vec::new()];
    let mut tip_err = [Vec::new(), Vec::new(), Vec::new()];
    let mut d_err = [Vec::new(), Vec::new(), Vec::new()];
    for d in &grid {
        let theta = joints_from_actuators(d).unwrap();
        let tip = tip_from_actuators(d).unwrap();
        let back = inverse(&tip).unwrap();
        let d_back = actuators_for_tip(&tip).unwrap();
        let tip_back = tip_from_actuators(&d_back).unwrap();
        for i in 0..3 {
            theta_err[i].push((back[i] - theta[i]) / DEG);
            tip_err[i].push((tip_back[i] - tip[i]) * 1000.0);
            d_err[i].push((d_back[i] - d[i]) * 1000.0);
        }
    }
    let r = |v: &Vec<f64>| rmsd(v.iter().copied());
    println!("crane kinematics over the 11³ actuator grid (cf. Table 4.5):");
    println!("  IK θ2z (4.78)      RMSD {:.4e} deg", r(&theta_err[0]));
    println!("  IK θ3x (4.80–4.86) RMSD {:.4e} deg", r(&theta_err[1]));
    println!("  IK θ4x (4.88)      RMSD {:.4e} deg", r(&theta_err[2]));
    println!("  FK∘IK x_t, y_t, z_t RMSD {:.4e}, {:.4e}, {:.4e} mm", r(&tip_err[0]), r(&tip_err[1]), r(&tip_err[2]));
    println!("  d (IK then mechanisms) RMSD {:.4e}, {:.4e}, {:.4e} mm", r(&d_err[0]), r(&d_err[1]), r(&d_err[2]));
    for v in theta_err.iter().chain(&tip_err).chain(&d_err) {
        assert!(r(v) < 1e-12, "RMSD {}", r(v));
    }
}

#[test]
fn the_spec_set_point_is_mid_workspace() {
    // {3, −502, −153} mm in W is {3, −277, −153} mm in J12 with the crane 225 mm to port.
    let d = actuators_for_tip(&Vec3::new(0.003, -0.277, -0.153)).unwrap();
    let mm = d.map(|v| v * 1000.0);
    println!("actuators for the tip set-point (3, −277, −153) mm in J12: {mm:.3?} mm");
    for (got, expected) in mm.iter().zip([25.7, 30.7, 23.7]) {
        assert!((got - expected).abs() < 0.05, "{mm:?}");
    }
}

#[test]
fn unreachable_targets_are_errors_not_nan() {
    // Beyond the boom and jib's reach.
    let far = inverse(&Vec3::new(0.0, -1.0, -0.2));
    assert!(matches!(far, Err(KinematicsError::OutOfReach { .. })), "{far:?}");
    println!("{}", far.unwrap_err());
    // Too close to the boom pivot (closer than l3y − l4y).
    let near = inverse(&Vec3::new(0.0, -0.03, -0.1846));
    assert!(matches!(near, Err(KinematicsError::OutOfReach { .. })), "{near:?}");
    // On the slewing axis.
    assert!(matches!(inverse(&Vec3::new(0.0, 0.0, -0.5)), Err(KinematicsError::OnSlewAxis { .. })));
    assert_eq!(inverse(&Vec3::new(f64::NAN, -0.3, -0.1)), Err(KinematicsError::NotFinite));
    // Geometrically reachable, but the slewing actuator cannot turn the tower that far.
    let behind = actuators_for_tip(&Vec3::new(0.0, 0.3, -0.15));
    assert!(matches!(behind, Err(KinematicsError::OutOfStroke { mechanism: "base", .. })), "{behind:?}");
    println!("{}", behind.unwrap_err());
    // Every grid point is reachable with in-stroke extensions.
    let corner = tip_from_actuators(&[STROKE; 3]).unwrap();
    assert!(actuators_for_tip(&corner).is_ok());
    assert_eq!(MECHANISMS.len(), 3);
}

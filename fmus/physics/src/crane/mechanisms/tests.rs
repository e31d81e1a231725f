use super::*;
use crate::math::{rot_x, rot_z, Vec3};
use num_dual::HyperDual64;

const DEG: f64 = std::f64::consts::PI / 180.0;

/// The 11 actuator set-points of §4.2.7: 0–50 mm in 5 mm steps (m).
fn stroke_grid() -> impl Iterator<Item = f64> {
    (0..=10).map(|i| i as f64 * 0.005)
}

fn rmsd(errors: &[f64]) -> f64 {
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
}

/// Pin-to-pin length (mm) of each mechanism at joint angle θ, from the pin positions of
/// eqs. 4.17–4.21, 4.40–4.44 and 4.53–4.57 (an independent statement of the loop closure).
fn pin_distance(m: &Mechanism, theta: f64) -> f64 {
    let (fixed, moving) = match m.name {
        // LA at (−c2x1, −c2y1, 0) in J12; the rod end at (0, −c2y2, 0) in J21, turned about z.
        "base" => (Vec3::new(-122.0, -47.825, 0.0), rot_z(theta) * Vec3::new(0.0, -53.975, 0.0)),
        // LA at (0, −c3y1, c3z1) in J22; the rod end at (0, −c3y2, c3z2) in J31, turned about x.
        "boom" => (Vec3::new(0.0, -62.865, 107.315), rot_x(theta) * Vec3::new(0.0, -66.04, 9.525)),
        // LA at (0, c4y1, c4z1) in J32; the rod end at (0, −c4y2, c4z2) in J41, turned about x.
        "jib" => (Vec3::new(0.0, 120.8532, 9.525), rot_x(theta) * Vec3::new(0.0, -46.99, 9.525)),
        other => panic!("unknown mechanism {other}"),
    };
    (moving - fixed).norm()
}

#[test]
fn home_angles_match_the_thesis() {
    // Fully retracted actuators (d = 0) give the home configuration (§4.2.2–4.2.4).
    let expected = [("base", -27.6, 0.05), ("boom", -0.73, 0.005), ("jib", -114.8, 0.05)];
    for (m, (name, thesis, tol)) in MECHANISMS.iter().zip(expected) {
        let home = m.home_angle() / DEG;
        println!("home angle of the {name} joint (d = 0 mm): {home:.4}° (thesis {thesis}°)");
        assert_eq!(m.name, name);
        assert!((home - thesis).abs() < tol, "{name}: {home}° vs {thesis}°");
    }
}

#[test]
fn forward_kinematics_closes_the_pin_loop() {
    for m in &MECHANISMS {
        let worst = stroke_grid()
            .map(|d| {
                let theta = m.angle(d).unwrap();
                (pin_distance(m, theta) - (d * 1000.0 + m.retracted)).abs()
            })
            .fold(0.0, f64::max);
        println!("{}: pin-to-pin length vs d + d0 over the stroke, max error {worst:.3e} mm", m.name);
        assert!(worst < 1e-12, "{}: {worst} mm", m.name);
    }
}

#[test]
fn mechanism_round_trips_over_the_stroke() {
    println!("actuator mechanisms, 11 set-points 0–50 mm (cf. Table 4.5):");
    for m in &MECHANISMS {
        // IK(FK(d)) − d over the grid (mm).
        let d_errors: Vec<f64> = stroke_grid().map(|d| (m.extension(m.angle(d).unwrap()) - d) * 1000.0).collect();
        // FK(IK(θ)) − θ over 11 angles spanning the joint's range (deg).
        let (lo, hi) = (m.angle(0.0).unwrap(), m.angle(STROKE).unwrap());
        let theta_errors: Vec<f64> = (0..=10)
            .map(|i| {
                let theta = lo + (hi - lo) * i as f64 / 10.0;
                (m.angle(m.extension(theta)).unwrap() - theta) / DEG
            })
            .collect();
        let (rd, rt) = (rmsd(&d_errors), rmsd(&theta_errors));
        println!("  {:4}: IK∘FK d RMSD {rd:.4e} mm, FK∘IK θ RMSD {rt:.4e} deg", m.name);
        assert!(rd < 1e-12 && rt < 1e-12);
    }
}

#[test]
fn angle_derivatives_match_finite_differences() {
    for m in &MECHANISMS {
        for d in [0.002, 0.025, 0.048] {
            let x = m.angle(HyperDual64::new(d, 1.0, 1.0, 0.0)).unwrap();
            let f = |d: f64| m.angle(d).unwrap();
            let h1 = 1e-6;
            let first = (f(d + h1) - f(d - h1)) / (2.0 * h1);
            let h2 = 1e-4;
            let second = (f(d + h2) - 2.0 * f(d) + f(d - h2)) / (h2 * h2);
            let e1 = (x.eps1 - first).abs() / first.abs();
            let e2 = (x.eps1eps2 - second).abs() / second.abs().max(1.0);
            assert!(
                e1 < 1e-8 && e2 < 1e-5,
                "{} at {d} m: dθ/dd {} vs {first}, d²θ/dd² {} vs {second}",
                m.name,
                x.eps1,
                x.eps1eps2
            );
            // The IK derivative is the reciprocal of the FK derivative.
            let back = m.extension(HyperDual64::new(x.re, 1.0, 1.0, 0.0));
            assert!((back.eps1 * x.eps1 - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn extensions_outside_the_stroke_are_errors() {
    let m = Mechanism::BOOM;
    let beyond = m.angle(0.051).unwrap();
    assert!(matches!(m.extension_in_stroke(beyond), Err(KinematicsError::OutOfStroke { mechanism: "boom", .. })));
    assert!(m.extension_in_stroke(m.angle(0.0).unwrap()).is_ok());
    assert!(matches!(m.angle(1.0), Err(KinematicsError::NoClosure { mechanism: "boom", .. })));
    assert_eq!(m.angle(f64::NAN), Err(KinematicsError::NotFinite));
    assert_eq!(m.extension_in_stroke(f64::INFINITY), Err(KinematicsError::NotFinite));
}

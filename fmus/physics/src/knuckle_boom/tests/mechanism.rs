use super::Worst;
use crate::knuckle_boom::{ArmParams, Mechanism};

fn mechanisms() -> [(&'static str, Mechanism); 2] {
    [("boom", ArmParams::DEFAULT.boom_cylinder), ("jib", ArmParams::DEFAULT.jib_cylinder)]
}

/// θ over the joint range, ends included.
fn over_range(m: &Mechanism) -> Vec<f64> {
    let (low, high) = m.joint_range().unwrap();
    (0..=40).map(|i| low + (high - low) * i as f64 / 40.0).collect()
}

#[test]
fn lever_arm_and_curvature_match_central_differences() {
    let mut worst = Worst::new(1e-7);
    for (name, m) in mechanisms() {
        let h = 1e-5;
        for theta in over_range(&m) {
            let (_, lever, curvature) = m.length(theta);
            let fd_lever = (m.length(theta + h).0 - m.length(theta - h).0) / (2.0 * h);
            let fd_curvature = (m.length(theta + h).1 - m.length(theta - h).1) / (2.0 * h);
            // Relative to the lever arm, the derivatives' natural scale (the curvature crosses 0).
            let error = ((lever - fd_lever).abs()).max((curvature - fd_curvature).abs()) / lever.abs();
            worst.record(error, || {
                format!("{name} θ = {theta}: dL/dθ {lever} vs {fd_lever}, d²L/dθ² {curvature} vs {fd_curvature}")
            });
        }
    }
    worst.report("mechanism derivatives");
}

#[test]
fn the_stroke_ends_are_the_joint_limits_of_the_chosen_geometry() {
    // Expected limits (deg) and the smallest lever arm (m) of the chosen attachment points,
    // from the law of cosines evaluated independently (params.rs documents them).
    let expected = [("boom", -20.4527, 75.0236, 0.7054), ("jib", -133.0960, -0.2349, 0.3308)];
    for ((name, m), (_, low_deg, high_deg, min_lever)) in mechanisms().into_iter().zip(expected) {
        let (low, high) = m.joint_range().unwrap();
        assert!((m.length(low).0 - 2.1).abs() < 1e-12 && (m.length(high).0 - 3.7).abs() < 1e-12, "{name}");
        assert!((low.to_degrees() - low_deg).abs() < 1e-3 && (high.to_degrees() - high_deg).abs() < 1e-3, "{name}");
        let lever = over_range(&m).iter().map(|t| m.length(*t).1).fold(f64::INFINITY, f64::min);
        assert!((lever - min_lever).abs() < 1e-3 && lever > 0.3, "{name}: smallest lever arm {lever} m");
        println!("{name}: θ {:.4}°…{:.4}°, smallest lever arm {lever:.4} m", low.to_degrees(), high.to_degrees());
    }
}

#[test]
fn length_matches_the_law_of_cosines() {
    for (name, m) in mechanisms() {
        let (a, b) = (m.lower_pin[0].hypot(m.lower_pin[1]), m.upper_pin[0].hypot(m.upper_pin[1]));
        let offset = m.upper_pin[1].atan2(m.upper_pin[0]) - m.lower_pin[1].atan2(m.lower_pin[0]);
        for theta in over_range(&m) {
            let psi = theta + offset;
            let length = (a * a + b * b - 2.0 * a * b * psi.cos()).sqrt();
            let (l, lever, _) = m.length(theta);
            assert!((l - length).abs() < 1e-12, "{name} θ = {theta}");
            assert!((lever - a * b * psi.sin() / length).abs() < 1e-12, "{name} θ = {theta}");
        }
    }
}

#[test]
fn angle_inverts_length() {
    let mut worst: f64 = 0.0;
    for (name, m) in mechanisms() {
        for theta in over_range(&m) {
            let back = m.angle(m.length(theta).0.clamp(m.min_length, m.max_length)).unwrap();
            assert!((back - theta).abs() < 1e-10, "{name}: θ {theta} came back as {back}");
            worst = worst.max((back - theta).abs());
        }
    }
    println!("angle(length(θ)) − θ: largest {worst:.2e} rad");
}

#[test]
fn lengths_outside_the_stroke_and_bad_pins_are_refused() {
    let m = ArmParams::DEFAULT.boom_cylinder;
    for length in [2.0999, 3.7001, f64::NAN, f64::INFINITY] {
        let error = m.angle(length).unwrap_err();
        assert!(error.contains("outside the stroke"), "{error}");
    }
    assert!(m.validate("boom_cylinder").is_ok());
    let short = Mechanism { lower_pin: [0.3, -0.2], ..m };
    assert!(short.validate("boom_cylinder").unwrap_err().contains("boom_cylinder: pins"));
    let reversed = Mechanism { min_length: 3.7, max_length: 2.1, ..m };
    assert!(reversed.validate("jib_cylinder").unwrap_err().contains("jib_cylinder: stroke"));
    let nan = Mechanism { upper_pin: [f64::NAN, 0.0], ..m };
    assert!(nan.validate("boom_cylinder").unwrap_err().contains("must be finite"));
}

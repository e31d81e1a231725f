use super::*;
use crate::motion::{HEAVE, PITCH, ROLL, SURGE, SWAY, YAW};

const DEG: f64 = std::f64::consts::PI / 180.0;

fn close(a: Complex<f64>, b: Complex<f64>, tol: f64) -> bool {
    (a - b).norm() < tol
}

#[test]
fn long_waves_carry_the_ship_with_the_water_surface() {
    // ω = 0.02 rad/s: λ ≈ 150 km. Heave follows the elevation (z down: −1), pitch the slope along
    // the hull, surge and sway the horizontal particle motion.
    let hull = Hull::default();
    let omega = 0.02;
    let k = omega * omega / STANDARD_GRAVITY;
    let i = Complex::new(0.0, 1.0);
    for beta in [0.0, 45.0, 90.0, 135.0, 180.0, 270.0] {
        let b = beta * DEG;
        let h = hull.response(omega, b);
        assert!(close(h[HEAVE], Complex::new(-1.0, 0.0), 1e-3), "β {beta}°: heave {}", h[HEAVE]);
        assert!(close(h[PITCH], -i * k * b.cos(), 1e-3 * k), "β {beta}°: pitch {}", h[PITCH]);
        assert!(close(h[SURGE], -i * b.cos(), 1e-3), "β {beta}°: surge {}", h[SURGE]);
        assert!(close(h[SWAY], -i * b.sin(), 1e-3), "β {beta}°: sway {}", h[SWAY]);
        assert_eq!(h[YAW], Complex::new(0.0, 0.0));
    }
}

#[test]
fn headings_switch_the_motions_on_and_off() {
    let hull = Hull::default();
    for omega in [0.4, 0.65, 1.0, 1.6] {
        let head = hull.response(omega, 180.0 * DEG);
        assert!(head[ROLL].norm() < 1e-12 && head[SWAY].norm() < 1e-12, "head seas roll or sway at ω {omega}");
        let beam = hull.response(omega, 90.0 * DEG);
        assert!(beam[PITCH].norm() < 1e-12 && beam[SURGE].norm() < 1e-12, "beam seas pitch or surge at ω {omega}");
        assert!(beam[ROLL].norm() > 0.0 && beam[HEAVE].norm() > 0.0);
        // Waves from the other side mirror sway and roll.
        let port = hull.response(omega, 60.0 * DEG);
        let starboard = hull.response(omega, -60.0 * DEG);
        assert!(close(port[ROLL], -starboard[ROLL], 1e-15) && close(port[SWAY], -starboard[SWAY], 1e-15));
        assert!(close(port[HEAVE], starboard[HEAVE], 1e-15) && close(port[PITCH], starboard[PITCH], 1e-15));
    }
}

#[test]
fn roll_resonates_at_the_natural_period() {
    let hull = Hull::default();
    let wn = TAU / hull.roll_period;
    let roll = |omega: f64| hull.response(omega, 90.0 * DEG)[ROLL].norm();
    // Scan the band for the largest roll: it is near the natural frequency (a little above, as
    // the excitation grows with frequency).
    let peak = (200..=1500).map(|n| n as f64 / 1000.0).max_by(|a, b| roll(*a).total_cmp(&roll(*b))).unwrap();
    println!(
        "GM {:.3} m; roll RAO peak at ω {peak:.3} rad/s (ωn {wn:.3}), {:.2} deg/m; wave damping {:.2} % of \
            critical at ωn",
        hull.metacentric_height(),
        roll(peak) / DEG,
        100.0 * hull.length * hull.sectional_roll_damping(wn) * wn
            / (2.0 * RHO * STANDARD_GRAVITY * hull.displacement() * hull.metacentric_height())
    );
    assert!((peak - wn).abs() < 0.05 * wn);
    assert!((hull.metacentric_height() - 1.1786).abs() < 1e-3);
}

#[test]
fn heave_and_pitch_fall_off_in_short_waves() {
    let hull = Hull::default();
    let heave = |omega: f64| hull.response(omega, 180.0 * DEG)[HEAVE].norm();
    let pitch = |omega: f64| hull.response(omega, 180.0 * DEG)[PITCH].norm();
    assert!(heave(1.5) < 0.1 * heave(0.3), "heave {} vs {}", heave(1.5), heave(0.3));
    assert!(pitch(1.5) < 0.1 * pitch(0.5));
}

#[test]
fn invalid_hulls_are_rejected() {
    assert!(Hull::default().validate().is_ok());
    assert!(Hull { draught: 0.0, ..Hull::default() }.validate().is_err());
    assert!(Hull { block_coefficient: 1.2, ..Hull::default() }.validate().is_err());
    let narrow = Hull { breadth: 3.0, ..Hull::default() }.validate().unwrap_err();
    assert!(narrow.contains("B/T"), "{narrow}");
    assert!(Hull { roll_damping: -0.1, ..Hull::default() }.validate().is_err());
}

use super::*;
use crate::math::{Vec3, STANDARD_GRAVITY};
use crate::pendulum::{linear_angular_acceleration, Swing};

fn residual(a: &DMatrix<f64>, b: &DMatrix<f64>, q: &DMatrix<f64>, r: &DMatrix<f64>, s: &DMatrix<f64>) -> f64 {
    let g = b * r.clone().try_inverse().unwrap() * b.transpose();
    (a.transpose() * s + s * a - s * g * s + q).norm() / s.norm()
}

#[test]
fn the_double_integrator_has_its_closed_form_solution() {
    // Aᵀ S + S A − S B Bᵀ S + I = 0 gives S = [√3 1; 1 √3], K = [1 √3].
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let design = lqr(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1)).unwrap();
    let r3 = 3f64.sqrt();
    let expected = DMatrix::from_row_slice(2, 2, &[r3, 1.0, 1.0, r3]);
    assert!((&design.s - expected).norm() < 1e-13, "{}", design.s);
    assert!((design.k[(0, 0)] - 1.0).abs() < 1e-13 && (design.k[(0, 1)] - r3).abs() < 1e-13);
    assert!(design.poles.iter().all(|p| p.re < 0.0));
}

#[test]
fn the_scalar_equation_matches_its_root() {
    // 2 a s − s² b²/r + q = 0, stabilising root s = r (a + √(a² + b² q / r)) / b², also for an
    // unstable a.
    for (a, b, q, r) in [(1.5, 2.0, 3.0, 0.5), (-0.7, 1.0, 10.0, 1.0), (0.0, 0.3, 2.0, 4.0)] {
        let s = care(
            &DMatrix::from_element(1, 1, a),
            &DMatrix::from_element(1, 1, b),
            &DMatrix::from_element(1, 1, q),
            &DMatrix::from_element(1, 1, r),
        )
        .unwrap();
        let expected = r * (a + (a * a + b * b * q / r).sqrt()) / (b * b);
        assert!((s[(0, 0)] - expected).abs() < 1e-12 * expected, "a = {a}: {} vs {expected}", s[(0, 0)]);
    }
}

#[test]
fn shapes_and_unsolvable_problems_are_errors() {
    let a = DMatrix::<f64>::zeros(2, 2);
    let b = DMatrix::<f64>::zeros(2, 1);
    assert!(care(&a, &b, &DMatrix::identity(3, 3), &DMatrix::identity(1, 1)).unwrap_err().contains("shapes"));
    assert!(care(&a, &b, &DMatrix::identity(2, 2), &DMatrix::from_element(1, 1, -1.0))
        .unwrap_err()
        .contains("positive definite"));
    // B = 0: the marginally stable modes of A = 0 cannot be moved.
    assert!(care(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1)).is_err());
}

#[test]
fn the_model_is_the_linearised_pendulum() {
    let (lp, g) = (0.7, STANDARD_GRAVITY);
    let (a, b) = pendulum_model(lp, g);
    let swing = Swing { theta_x: 0.03, theta_y: -0.02, omega_x: 0.1, omega_y: 0.2 };
    let tip_acc = Vec3::new(0.4, -0.3, 0.2);
    let mut x = DMatrix::zeros(12, 1);
    x[3] = swing.theta_x;
    x[4] = swing.theta_y;
    x[9] = swing.omega_x;
    x[10] = swing.omega_y;
    let u = DMatrix::from_column_slice(6, 1, &[tip_acc.x, tip_acc.y, tip_acc.z, 0.0, 0.0, 0.5]);
    let xd = &a * &x + &b * &u;
    let (ax, ay) = linear_angular_acceleration(g, lp, &swing, &tip_acc);
    assert!((xd[9] - ax).abs() < 1e-15 && (xd[10] - ay).abs() < 1e-15);
    assert_eq!((xd[3], xd[4]), (swing.omega_x, swing.omega_y));
    assert_eq!((xd[6], xd[7], xd[8], xd[11]), (tip_acc.x, tip_acc.y, tip_acc.z, 0.5));
}

/// K for Q = 10·I12, R = I6 (§6.2) at the pendulum length `lp`.
fn thesis_design(lp: f64) -> Lqr {
    let (a, b) = pendulum_model(lp, STANDARD_GRAVITY);
    lqr(&a, &b, &(DMatrix::identity(12, 12) * 10.0), &DMatrix::identity(6, 6)).unwrap()
}

#[test]
fn the_thesis_design_has_the_expected_sign_structure() {
    let d = thesis_design(0.7);
    let (a, b) = pendulum_model(0.7, STANDARD_GRAVITY);
    let r = residual(&a, &b, &(DMatrix::identity(12, 12) * 10.0), &DMatrix::identity(6, 6), &d.s);
    let slowest = d.poles.iter().map(|p| p.re).fold(f64::MIN, f64::max);
    println!("l_p = 0.7 m: relative residual {r:.1e}, slowest closed-loop pole Re = {slowest:.3} 1/s");
    println!("K =\n{:.3}", d.k);
    assert!(r < 1e-13);
    assert!(slowest < 0.0, "A − BK is Hurwitz");
    let k = &d.k;
    // e_θx drives ÿ_t positively, e_θy drives ẍ_t negatively (SPEC §4.5).
    assert!((k[(1, 3)] - 8.951).abs() < 1e-3, "K[ÿ_t, θx] = {}", k[(1, 3)]);
    assert!((k[(0, 4)] + 8.951).abs() < 1e-3, "K[ẍ_t, θy] = {}", k[(0, 4)]);
    // Diagonal: √10 on the positions, 4.70 on the coupled velocities, √(10 + 2√10) = 4.04 on
    // the uncoupled ones.
    for (row, col) in [(0, 0), (1, 1), (2, 2), (5, 5)] {
        assert!((k[(row, col)] - 10f64.sqrt()).abs() < 1e-9);
    }
    assert!((k[(0, 6)] - 4.701).abs() < 1e-3 && (k[(1, 7)] - 4.701).abs() < 1e-3);
    let double_integrator = (10.0 + 2.0 * 10f64.sqrt()).sqrt();
    assert!((k[(2, 8)] - double_integrator).abs() < 1e-9 && (k[(5, 11)] - double_integrator).abs() < 1e-9);
    // The angle inputs get no gain; x and y do not couple.
    assert!(k.row(3).iter().chain(k.row(4).iter()).all(|v| *v == 0.0));
    assert!(k[(0, 1)].abs() < 1e-12 && k[(0, 3)].abs() < 1e-12 && k[(1, 4)].abs() < 1e-12);
}

#[test]
fn the_gains_barely_depend_on_the_pendulum_length() {
    let mut angle_gains = Vec::new();
    for lp in [0.05, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0] {
        let d = thesis_design(lp);
        assert!(d.poles.iter().all(|p| p.re < 0.0), "l_p = {lp}: not Hurwitz");
        assert!((d.k[(1, 3)] + d.k[(0, 4)]).abs() < 1e-9, "symmetric in x and y");
        angle_gains.push((lp, d.k[(1, 3)]));
    }
    println!("K[ÿ_t, θx] over l_p: {angle_gains:.3?}");
    assert!(angle_gains.iter().all(|(_, k)| (8.4..=10.2).contains(k)));
}

#[test]
fn the_angle_coupling_is_the_full_designs() {
    // The 4-state y axis against the 12-state design of §6.2 (Q = 10·I12, R = I6): the entry
    // (ÿ_t, θx) and, mirrored, (ẍ_t, θy).
    let q = DMatrix::identity(12, 12) * 10.0;
    let r = DMatrix::identity(6, 6);
    for lp in [0.05, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0, 1.3] {
        let (a, b) = pendulum_model(lp, STANDARD_GRAVITY);
        let k = lqr(&a, &b, &q, &r).unwrap().k;
        let coupling = angle_coupling(lp, STANDARD_GRAVITY).unwrap();
        assert!((coupling - k[(1, 3)]).abs() < 1e-12, "{lp} m: {coupling} vs {}", k[(1, 3)]);
        assert!((coupling + k[(0, 4)]).abs() < 1e-12, "{lp} m: {coupling} vs {}", k[(0, 4)]);
    }
    assert!(angle_coupling(0.0, STANDARD_GRAVITY).is_err());
}

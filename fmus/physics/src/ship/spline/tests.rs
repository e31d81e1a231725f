use super::*;

#[test]
fn the_spline_passes_through_the_samples_and_reproduces_lines() {
    let t = vec![0.0, 0.3, 1.0, 1.2, 2.5];
    let y = t.iter().map(|x| 2.0 - 3.0 * x).collect::<Vec<_>>();
    let s = CubicSpline::natural(t.clone(), y.clone()).unwrap();
    for (ti, yi) in t.iter().zip(&y) {
        assert!((s.eval(*ti).pos - yi).abs() < 1e-14);
    }
    for x in [0.1, 0.65, 1.1, 2.0] {
        let a = s.eval(x);
        assert!((a.pos - (2.0 - 3.0 * x)).abs() < 1e-14 && (a.vel + 3.0).abs() < 1e-13 && a.acc.abs() < 1e-12);
    }
}

#[test]
fn the_spline_is_twice_continuously_differentiable_with_natural_ends() {
    let t: Vec<f64> = (0..12).map(|i| i as f64 * 0.5 + 0.1 * (i as f64).sin()).collect();
    let y: Vec<f64> = t.iter().map(|x| (1.3 * x).sin() + 0.2 * x * x).collect();
    let s = CubicSpline::natural(t.clone(), y).unwrap();
    let e = 1e-9;
    for &knot in &t[1..t.len() - 1] {
        let (l, r) = (s.eval(knot - e), s.eval(knot + e));
        assert!(
            (l.pos - r.pos).abs() < 1e-8 && (l.vel - r.vel).abs() < 1e-7 && (l.acc - r.acc).abs() < 1e-6,
            "kink at {knot}"
        );
    }
    assert!(s.eval(t[0] + 1e-12).acc.abs() < 1e-9 && s.eval(t[11] - 1e-12).acc.abs() < 1e-9);
    // Derivatives against central differences inside the intervals.
    let h = 1e-5;
    for x in [0.2, 1.7, 3.05, 5.1] {
        let (a, p, m) = (s.eval(x), s.eval(x + h), s.eval(x - h));
        assert!((a.vel - (p.pos - m.pos) / (2.0 * h)).abs() < 1e-8);
        assert!((a.acc - (p.vel - m.vel) / (2.0 * h)).abs() < 1e-7);
    }
}

#[test]
fn a_finely_sampled_signal_is_interpolated_accurately() {
    let t: Vec<f64> = (0..=1000).map(|i| i as f64 * 0.01).collect();
    let y: Vec<f64> = t.iter().map(|x| (2.0 * x).sin()).collect();
    let s = CubicSpline::natural(t, y).unwrap();
    for x in [1.005, 4.333, 7.777] {
        let a = s.eval(x);
        assert!((a.pos - (2.0 * x).sin()).abs() < 1e-8);
        assert!((a.vel - 2.0 * (2.0 * x).cos()).abs() < 1e-5);
        assert!((a.acc + 4.0 * (2.0 * x).sin()).abs() < 1e-3);
    }
}

#[test]
fn outside_the_samples_the_end_values_are_held() {
    let s = CubicSpline::natural(vec![1.0, 2.0, 3.0], vec![5.0, 7.0, 6.0]).unwrap();
    assert_eq!(s.eval(0.0), AxisMotion { pos: 5.0, vel: 0.0, acc: 0.0 });
    assert_eq!(s.eval(9.0), AxisMotion { pos: 6.0, vel: 0.0, acc: 0.0 });
    assert_eq!(s.span(), (1.0, 3.0));
    // Two samples: a straight line.
    let line = CubicSpline::natural(vec![0.0, 2.0], vec![1.0, 2.0]).unwrap();
    assert!((line.eval(1.0).pos - 1.5).abs() < 1e-15 && (line.eval(1.0).vel - 0.5).abs() < 1e-15);
}

#[test]
fn bad_samples_are_rejected() {
    assert!(CubicSpline::natural(vec![0.0], vec![1.0]).unwrap_err().contains("at least 2"));
    assert!(CubicSpline::natural(vec![0.0, 1.0, 1.0], vec![1.0, 2.0, 3.0]).unwrap_err().contains("increase strictly"));
    assert!(CubicSpline::natural(vec![0.0, 1.0], vec![1.0, f64::NAN]).unwrap_err().contains("finite"));
    assert!(CubicSpline::natural(vec![0.0, 1.0], vec![1.0]).is_err());
}

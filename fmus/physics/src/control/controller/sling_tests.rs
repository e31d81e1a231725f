//! The controller with a sling below the hook ([`SlingConfig`]): where it puts the load, and the
//! notch it takes the hook–load mode out of the load angles with.

use super::*;
use crate::math::STANDARD_GRAVITY;

fn with_sling(length: f64) -> ControllerConfig {
    ControllerConfig { sling: SlingConfig { length, ..SlingConfig::NONE }, ..ControllerConfig::DEFAULT }
}

#[test]
fn the_load_hangs_the_sling_below_the_hoist_rope_of_the_set_point() {
    let mut plain = Controller::new(ControllerConfig::DEFAULT).unwrap();
    let mut slung = Controller::new(with_sling(0.2)).unwrap();
    let (a, b) = (plain.step(0.0, 0.01, &Inputs::AT_REST).unwrap(), slung.step(0.0, 0.01, &Inputs::AT_REST).unwrap());
    // The winch is commanded as without the sling: sp.lp stays the hoist rope's length.
    assert_eq!((a.commanded, a.winch, a.commands), (b.commanded, b.winch, b.commands));
    assert_eq!(b.desired_load, a.desired.load() + Vec3::new(0.0, 0.0, 0.2));
    assert!((b.load - a.load - Vec3::new(0.0, 0.0, 0.2)).norm() < 1e-12, "{:?} vs {:?}", b.load, a.load);
    assert_eq!(a.desired_load, a.desired.load());
}

#[test]
fn the_notch_removes_the_hook_load_mode_of_the_hoist_length_and_passes_the_swing() {
    let (hoist, sling, dt) = (0.7, 0.2, 0.01);
    let config = with_sling(sling);
    let mut controller = Controller::new(config).unwrap();
    let mut swing_only = Controller::new(config).unwrap();
    // The rigging's closed-form modes for the default hook and load (one to two).
    let (first, second) = crate::rigging::normal_modes(1.0, 2.0, hoist, sling, STANDARD_GRAVITY);
    assert!((config.sling.hook_load_mode(hoist, STANDARD_GRAVITY) - second).abs() < 1e-12 * second);
    let mut worst: f64 = 0.0;
    for k in 0..3000 {
        let t = k as f64 * dt;
        let swing = 0.1 * (first * t).sin();
        let both = swing + 0.05 * (second * t).cos();
        let y = controller.notch_hook_load_mode([both, -both], hoist, dt);
        let y_swing = swing_only.notch_hook_load_mode([swing, -swing], hoist, dt);
        if t > 10.0 {
            // The filter is linear: what is left of the mode is the difference.
            worst = worst.max((y[0] - y_swing[0]).abs()).max((y[1] - y_swing[1]).abs());
        }
    }
    assert!(worst < 0.01 * 0.05, "{:.2} % of the mode is left", 100.0 * worst / 0.05);
    // And the swing passes with ≥ 98 % of its amplitude (|H(jω₁)| of the notch).
    let r = first / second;
    let gain = (1.0 - r * r) / ((1.0 - r * r).powi(2) + (2.0 * 0.2 * r).powi(2)).sqrt();
    assert!(gain > 0.98, "{gain}");
}

#[test]
fn a_sling_needs_a_length_and_a_hook_share_in_range() {
    for (length, fraction, damping) in
        [(-0.1, 0.3, 0.2), (f64::NAN, 0.3, 0.2), (0.2, 0.0, 0.2), (0.2, 1.0, 0.2), (0.2, 0.3, -1.0)]
    {
        let config = ControllerConfig {
            sling: SlingConfig { length, hook_fraction: fraction, notch_damping: damping },
            ..ControllerConfig::DEFAULT
        };
        let error = Controller::new(config).expect_err("refused");
        assert!(error.starts_with("sling: "), "{error}");
    }
}

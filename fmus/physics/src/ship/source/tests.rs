use super::*;
use crate::motion::{HEAVE, ROLL};
use crate::platform::{drive, InverseModel};
use crate::ship::table::RECORDED_DECK;

fn config(kind: SourceKind) -> SourceConfig {
    SourceConfig {
        kind,
        scale: MotionScale::Test,
        seed: None,
        sine_omega: 3.743,
        sine_amplitude: 0.004,
        motion_file: String::new(),
    }
}

const PROFILE_1: SourceKind = SourceKind::Sea(ProfileId::One);

fn build(c: &SourceConfig, dir: Option<&Path>) -> Result<MotionSource, String> {
    MotionSource::build(c, dir, &Hull::default(), &PlatformGeometry::default())
}

#[test]
fn still_water_does_not_move() {
    let mut s = build(&config(SourceKind::Still), None).unwrap();
    assert_eq!(s.sample(12.3), DeckMotion::default());
}

#[test]
fn the_sine_of_tests_084_to_096_fits_the_platform() {
    // ω = √(g/0.7 m), 4 mm runs inside the platform's limits; 6 mm does not.
    let geom = PlatformGeometry::default();
    let omega = (crate::math::STANDARD_GRAVITY / 0.7).sqrt();
    for (amplitude, expected) in [(0.004, false), (0.006, true)] {
        let mut source = MotionSource::Sine { omega, amplitude };
        let any = (0..200)
            .any(|k| drive(&geom, &source.sample(k as f64 * 0.01), InverseModel::Exact, false).unwrap().la_limit);
        assert_eq!(any, expected, "amplitude {amplitude}");
    }
}

#[test]
fn the_sine_moves_surge_and_sway_in_phase() {
    let mut s = build(&config(SourceKind::Sine), None).unwrap();
    let (w, a) = (3.743, 0.004);
    for t in [0.0, 0.3, 1.7] {
        let m = s.sample(t);
        let expected =
            AxisMotion { pos: a * (w * t).sin(), vel: a * w * (w * t).cos(), acc: -a * w * w * (w * t).sin() };
        assert_eq!(m.dof[SURGE], expected);
        assert_eq!(m.dof[SWAY], expected);
        assert_eq!(m.dof[HEAVE], AxisMotion::default());
        assert_eq!(m.dof[ROLL], AxisMotion::default());
    }
}

#[test]
fn profiles_are_test_scale_and_deterministic() {
    let mut a = build(&config(PROFILE_1), None).unwrap();
    let b = build(&config(PROFILE_1), None).unwrap();
    assert_eq!(a, b);
    let MotionSource::Profile { scale, .. } = &a else { panic!("not a profile") };
    assert!(*scale > 0.0 && *scale < 1.0);
    let mut other_seed = build(&SourceConfig { seed: Some(99), ..config(PROFILE_1) }, None).unwrap();
    assert_ne!(a.sample(10.0), other_seed.sample(10.0));
}

#[test]
fn the_motion_file_is_read_relative_to_the_resources_folder() {
    let dir = std::env::temp_dir().join(format!("physics-source-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("deck.csv"), RECORDED_DECK).unwrap();
    let c = SourceConfig { motion_file: "deck.csv".into(), ..config(SourceKind::File) };
    let mut s = build(&c, Some(&dir)).unwrap();
    assert!((s.sample(1.0).dof[SURGE].pos - 0.02).abs() < 1e-15);
    let missing =
        build(&SourceConfig { motion_file: "absent.csv".into(), ..config(SourceKind::File) }, Some(&dir)).unwrap_err();
    assert!(missing.contains("cannot read motion file") && missing.contains("absent.csv"), "{missing}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_configurations_are_errors() {
    assert!(build(&config(SourceKind::File), None).unwrap_err().contains("motion_file is empty"));
    assert!(build(&SourceConfig { sine_omega: f64::NAN, ..config(SourceKind::Sine) }, None).is_err());
}

#[test]
fn only_the_profiles_depend_on_the_scale() {
    let full = |kind| SourceConfig { scale: MotionScale::Full, ..config(kind) };
    for kind in [SourceKind::Still, SourceKind::Sine] {
        assert_eq!(build(&full(kind), None).unwrap(), build(&config(kind), None).unwrap(), "{kind:?}");
    }
    let Ok(MotionSource::Profile { motion, scale }) = build(&full(PROFILE_1), None) else { panic!("not a profile") };
    assert_eq!(scale, 1.0);
    assert_eq!(motion.motion(), &ProfileId::One.profile().full_scale(&Hull::default(), 1));
}

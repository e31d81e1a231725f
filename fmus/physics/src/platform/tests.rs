use super::*;
use kinematics::exact_inverse;

const DEG: f64 = std::f64::consts::PI / 180.0;

fn motion(pose: [f64; 6], rates: [f64; 6]) -> DeckMotion {
    let mut m = DeckMotion::default();
    for j in 0..6 {
        m.dof[j] = AxisMotion { pos: pose[j], vel: rates[j], acc: 0.1 * rates[j] };
    }
    m
}

#[test]
fn the_stern_frame_turns_the_motion_by_minus_90_degrees() {
    let m = motion([0.01, 0.02, 0.03, 0.04, 0.05, 0.06], [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]);
    assert_eq!(CraneLocation::Port.resolve(&m), m);
    let s = CraneLocation::Stern.resolve(&m);
    assert_eq!(s.pose(), [-0.02, 0.01, 0.03, -0.05, 0.04, 0.06]);
    assert_eq!(s.dof[SURGE].vel, -0.2);
    assert_eq!(s.dof[ROLL].acc, -0.05);
    // Ship's bow (+x_B) is the platform's +y, so the crane on the platform's −y side faces aft.
    let bow = crate::math::rot_z(90.0 * DEG) * crate::math::Vec3::x();
    assert!((bow - crate::math::Vec3::y()).norm() < 1e-15);
}

#[test]
fn the_deck_yaws_with_the_mechanism_only_when_asked() {
    let geom = PlatformGeometry::default();
    let m = motion([0.0, 0.0, 0.0, 10.0 * DEG, 10.0 * DEG, 0.0], [0.0, 0.0, 0.0, 0.01, -0.02, 0.0]);
    let ideal = drive(&geom, &m, InverseModel::Exact, false).unwrap();
    let yawing = drive(&geom, &m, InverseModel::Exact, true).unwrap();
    let expected = exact_inverse(&geom, &[0.0, 0.0, 0.0, 10.0 * DEG, 10.0 * DEG]).unwrap().yaw;
    assert!(expected.abs() > 1e-3);
    assert_eq!(ideal.deck, m);
    assert_eq!(ideal.dependent_yaw.pos, expected);
    assert_eq!(yawing.deck.dof[YAW].pos, expected);
    assert_eq!(yawing.deck.dof[YAW].vel, yawing.dependent_yaw.vel);
    assert_eq!(ideal.la, yawing.la);
    let simplified = drive(&geom, &m, InverseModel::Simplified, false).unwrap();
    assert_eq!(simplified.dependent_yaw, AxisMotion::default());
    assert!((simplified.la[0].pos - 0.1).abs() < 1e-15, "simplified LA1 = nominal + sway");
    assert!((simplified.la[0].pos - ideal.la[0].pos).abs() > 1e-4, "exact LA1 corrects the sway");
}

#[test]
fn the_limit_flag_catches_strokes_and_speeds() {
    let geom = PlatformGeometry::default();
    let flag = |pose: [f64; 6], rates: [f64; 6]| {
        drive(&geom, &motion(pose, rates), InverseModel::Exact, false).unwrap().la_limit
    };
    assert!(!flag([0.0; 6], [0.0; 6]));
    assert!(!flag([0.05, -0.05, 0.02, 0.0, 0.0, 0.0], [0.019, 0.0, 0.0, 0.0, 0.0, 0.0]));
    assert!(flag([0.11, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0; 6]), "LA2 beyond 0.2 m");
    assert!(flag([0.0, -0.11, 0.0, 0.0, 0.0, 0.0], [0.0; 6]), "LA1 below 0");
    assert!(flag([0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.021, 0.0, 0.0, 0.0, 0.0]), "LA1 too fast");
    assert!(flag([0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.1, 0.0, 0.0]), "legs too fast in roll");
}

#[test]
fn without_the_platform_the_deck_follows_and_the_set_points_rest_at_the_neutral_pose() {
    let geom = PlatformGeometry::default();
    // Full-scale motion: metres of heave, far beyond the 0.2 m stroke.
    let requested = motion([0.4, -1.2, 2.5, 3.0 * DEG, -1.5 * DEG, 0.5 * DEG], [0.3, 0.8, 1.1, 0.02, 0.01, 0.001]);
    let state = PlatformState::unactuated(&geom, &requested);
    assert_eq!(state.deck, requested);
    assert!(!state.la_limit);
    assert_eq!(state.dependent_yaw, AxisMotion::default());
    // The neutral extension is where the exact chain puts every actuator at the zero pose.
    let rest = drive(&geom, &DeckMotion::default(), InverseModel::Exact, false).unwrap();
    for (neutral, at_zero_pose) in state.la.iter().zip(rest.la) {
        assert_eq!((neutral.vel, neutral.acc), (0.0, 0.0));
        assert!((neutral.pos - at_zero_pose.pos).abs() < 1e-15, "{neutral:?} vs {at_zero_pose:?}");
    }
}

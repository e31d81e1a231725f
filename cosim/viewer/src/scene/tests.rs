use super::*;
use physics::crane::kinematics::L4Y;
use physics::crane::motion::tip_in_world;
use physics::crane::plant::{CraneConfig, DEFAULT_POSE};

/// A tilted, displaced ship: every term of the rigid-body transform matters.
const SHIP: [f64; 6] = [0.012, -0.031, 0.044, 0.09, -0.06, 0.35];

/// Actuator extensions (m) across the stroke, the crane FMU's default among them.
const EXTENSIONS: [[f64; 3]; 4] =
    [DEFAULT_POSE.extensions, [0.005, 0.01, 0.045], [0.045, 0.04, 0.005], [0.03, 0.02, 0.035]];

/// The crane FMU's `tip.*` for the chain at `extensions` on `ship`, and its `joint.*` outputs.
fn crane_fmu_tip(extensions: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let config = CraneConfig::DEFAULT;
    let state = config.initial_state(extensions, 0.7).expect("extensions inside the stroke");
    let chain = config.motion(&state, &physics::crane::plant::Commands::NEUTRAL).expect("the mechanisms close");
    let ship = ship_pose(&SHIP);
    (tip_in_world(&ship, &chain).pos.into(), chain.joints.map(|j| j.pos))
}

#[test]
fn the_drawn_tip_is_the_crane_fmus_tip_output() {
    for extensions in EXTENSIONS {
        let (tip, joints) = crane_fmu_tip(extensions);
        let frame = Frame::of(&Crane::TestScale, &Sample { ship: SHIP, joints, ..Sample::default() });
        assert_eq!(frame.tip(), tip, "extensions {extensions:?}");
    }
}

#[test]
fn the_links_have_the_thesis_lengths_in_the_world_frame() {
    for extensions in EXTENSIONS {
        let (_, joints) = crane_fmu_tip(extensions);
        let [base, boom_pivot, jib_pivot, tip] =
            Frame::of(&Crane::TestScale, &Sample { ship: SHIP, joints, ..Sample::default() }).crane.map(Vec3::from);
        for (from, to, length_mm) in [(base, boom_pivot, L2Z), (boom_pivot, jib_pivot, L3Y), (jib_pivot, tip, L4Y)] {
            assert!(((to - from).norm() * MM_PER_M - length_mm).abs() < 1e-9, "{extensions:?}: {length_mm} mm");
        }
    }
}

#[test]
fn the_base_stands_on_the_deck_at_the_crane_base_offset() {
    let frame = Frame::of(&Crane::TestScale, &Sample { ship: SHIP, ..Sample::default() });
    let ship = ship_pose(&SHIP);
    let expected = ship.pos + ship.attitude() * CRANE_BASE;
    assert!((Vec3::from(frame.crane[0]) - expected).norm() < 1e-15);
    assert_eq!(frame.deck_position, [SHIP[0], SHIP[1], SHIP[2]]);
    // The attitude quaternion rotates B's z axis (deck normal) like the ship's rotation does.
    // (w, x, y, z) rotates B's axes as the ship's R does: v' = v + 2w (q × v) + 2 q × (q × v).
    let [w, x, y, z] = frame.deck_attitude;
    let q = Vec3::new(x, y, z);
    for v in [Vec3::x(), Vec3::y(), Vec3::z()] {
        let rotated = v + q.cross(&v) * (2.0 * w) + q.cross(&q.cross(&v)) * 2.0;
        assert!((rotated - ship.attitude() * v).norm() < 1e-15, "{v:?}");
    }
}

#[test]
fn the_setpoint_error_is_the_load_distance_to_its_setpoint() {
    let sample = Sample { load: [0.1, -0.5, 0.55], setpoint: Some([0.1, -0.53, 0.51]), ..Sample::default() };
    assert!((Frame::of(&Crane::TestScale, &sample).setpoint_error.unwrap() - 0.05).abs() < 1e-15);
}

mod full_scale;

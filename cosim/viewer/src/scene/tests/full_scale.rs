//! The full-scale knuckle-boom crane's frame against the FMU's own outputs: its `tip.*` (the
//! hydraulic plant's `tip_in_world`) and its cylinders' pin-to-pin lengths.

use super::*;
use physics::hydraulic_crane::plant::{CraneParams, Loads, Spools, DEFAULT_JOINTS};
use physics::knuckle_boom::Joints;
use physics::math::STANDARD_GRAVITY;

/// A heaving, rolling, pitching and yawing 120 m vessel, displaced from the origin (m, rad).
const SHIP: [f64; 6] = [3.2, -1.4, 0.85, 0.06, -0.035, 0.4];

/// Joints (rad) across the cylinders' strokes (boom −20.45…75.02°, jib −133.10…−0.23°), the
/// FMU's default pose among them.
const JOINTS: [Joints; 4] = [
    DEFAULT_JOINTS,
    [0.3, 10.0 * DEG, -100.0 * DEG],
    [-2.0, 70.0 * DEG, -20.0 * DEG],
    [2.9, -15.0 * DEG, -130.0 * DEG],
];
const DEG: f64 = std::f64::consts::PI / 180.0;

/// The knuckle_boom FMU's `tip.*` with its joints at `q` on `SHIP` moving, a 5 t load hanging.
fn fmu_tip(q: Joints) -> [f64; 3] {
    let params = CraneParams::DEFAULT;
    let mut ship = ship_pose(&SHIP);
    // Rates change the tip's velocity and acceleration, not its position.
    ship.vel = Vec3::new(0.4, -0.2, 1.1);
    ship.omega = Vec3::new(0.05, -0.02, 0.01);
    let loads = Loads { ship, cable: Vec3::new(0.0, 0.0, 5000.0 * STANDARD_GRAVITY), load_mass: 5000.0 };
    let state = params.initial_state(q, &loads).expect("the joints are inside the strokes");
    let evaluation = params.evaluate(&state, &Spools::default(), &loads);
    params.tip_in_world(&state, &evaluation, &loads.ship).pos.into()
}

fn frame(q: Joints) -> Frame {
    Frame::of(&Crane::FULL_SCALE, &Sample { ship: SHIP, joints: q, ..Sample::default() })
}

#[test]
fn the_drawn_tip_is_the_knuckle_boom_fmus_tip_output() {
    for q in JOINTS {
        assert_eq!(frame(q).tip(), fmu_tip(q), "joints {q:?}");
    }
}

#[test]
fn each_cylinder_spans_its_pins_at_the_length_the_fmu_drives_it_with() {
    let arm = ArmParams::DEFAULT;
    for q in JOINTS {
        let points = frame(q).cylinders.expect("the full-scale crane has cylinders").map(Vec3::from);
        let mechanisms = [arm.boom_cylinder, arm.jib_cylinder];
        for ((pins, (length, _)), mechanism) in points.chunks(3).zip(arm.cylinders(&q)).zip(mechanisms) {
            let (barrel_pin, barrel_end, rod_pin) = (pins[0], pins[1], pins[2]);
            assert!(((rod_pin - barrel_pin).norm() - length).abs() < 1e-12, "{q:?}: {length} m");
            // The barrel is as long as the retracted cylinder, on the line between the pins.
            assert!(((barrel_end - barrel_pin).norm() - mechanism.min_length).abs() < 1e-12, "{q:?}");
            let off_line = (barrel_end - barrel_pin).cross(&(rod_pin - barrel_pin)).norm();
            assert!(off_line < 1e-9, "{q:?}: {off_line}");
        }
    }
}

#[test]
fn the_pedestal_stands_on_the_deck_at_the_base_offset() {
    let arm = ArmParams::DEFAULT;
    let ship = ship_pose(&SHIP);
    let [foot, pivot, knuckle, tip] = frame(DEFAULT_JOINTS).crane.map(Vec3::from);
    assert!((foot - (ship.pos + ship.attitude() * Vec3::new(0.0, -8.0, 0.0))).norm() < 1e-12);
    // The boom pivot 2.2 m above the foot along the deck's normal (B's −z).
    let up = ship.attitude() * Vec3::new(0.0, 0.0, -1.0);
    assert!((pivot - foot - up * 2.2).norm() < 1e-12);
    assert!(((knuckle - pivot).norm() - arm.boom_length).abs() < 1e-12);
    assert!(((tip - knuckle).norm() - arm.jib_length).abs() < 1e-12);
    // The default pose reaches to port (θ1 = −90°): outreach ρ = L_b cos θ2 + L_j cos(θ2 + θ3),
    // height h = h_p + L_b sin θ2 + L_j sin(θ2 + θ3) (the tip equation of physics::knuckle_boom).
    let (boom, jib) = (40.0 * DEG, -20.0 * DEG);
    let reach = 7.0 * boom.cos() + 5.2 * jib.cos();
    let height = 2.2 + 7.0 * boom.sin() + 5.2 * jib.sin();
    let in_ship = ship.attitude().inverse() * (tip - foot);
    assert!((in_ship - Vec3::new(0.0, -reach, -height)).norm() < 1e-12, "{in_ship:?} vs {reach} m, {height} m");
}

#[test]
fn a_moved_base_moves_the_whole_crane() {
    let moved = Crane::FullScale { arm: ArmParams { base: Vec3::new(20.0, 6.0, -1.5), ..ArmParams::DEFAULT } };
    let sample = Sample { joints: DEFAULT_JOINTS, ..Sample::default() };
    let (at_default, at_moved) = (Frame::of(&Crane::FULL_SCALE, &sample), Frame::of(&moved, &sample));
    for (a, b) in at_default.crane.iter().zip(&at_moved.crane) {
        assert!((Vec3::from(*b) - Vec3::from(*a) - Vec3::new(20.0, 14.0, -1.5)).norm() < 1e-12);
    }
}

#[test]
fn the_full_scale_frame_has_no_ghost_markers() {
    let frame = frame(DEFAULT_JOINTS);
    assert_eq!((frame.estimated_load, frame.setpoint, frame.setpoint_error), (None, None, None));
    let json = serde_json::to_value(frame).unwrap();
    assert!(json.get("setpoint").is_none() && json.get("estimated_load").is_none(), "{json}");
    assert_eq!(json["cylinders"].as_array().map(Vec::len), Some(6));
}

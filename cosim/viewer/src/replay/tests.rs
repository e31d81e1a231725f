use std::path::PathBuf;

use super::*;
use crate::columns::FULL_SCALE_JOINTS;
use crate::scene::Sample;

/// A table with every column the view needs, each column holding its index plus the row
/// (so a value read from the wrong column or row shows).
fn table(names: Vec<String>, rows: usize) -> SignalTable {
    let columns = (0..names.len()).map(|c| (0..rows).map(|r| c as f64 + r as f64 / 10.0).collect()).collect();
    SignalTable { file: PathBuf::from("run.csv"), names, times: (0..rows).map(|r| r as f64 * 0.01).collect(), columns }
}

fn view_names(crane: &Crane) -> Vec<String> {
    columns::required(crane).map(String::from).collect()
}

/// `first`, then the columns the view of `crane` needs in reverse order (so that they are found
/// by name, not position), and the frames of a [`table`] of `rows` rows with those columns.
fn reversed_view(first: &str, crane: &Crane, rows: usize) -> (Vec<String>, FrameColumns) {
    let mut names: Vec<String> = vec![first.into()];
    names.extend(view_names(crane).into_iter().rev());
    let frames = FrameColumns::from_table(&table(names.clone(), rows), None).expect("every column is there");
    (names, frames)
}

/// What [`table`] holds in row `row` of the column `name` of `names`.
fn cell(names: &[String], name: &str, row: usize) -> f64 {
    names.iter().position(|n| n == name).unwrap() as f64 + row as f64 / 10.0
}

/// The platform's six ship coordinates, each from `value` of its column.
fn ship(value: impl Fn(&str) -> f64) -> [f64; 6] {
    ["x", "y", "z", "roll", "pitch", "yaw"].map(|dof| value(&format!("platform.ship.{dof}")))
}

#[test]
fn each_frame_is_drawn_from_its_own_row() {
    let (names, frames) = reversed_view("crane.tip.x", &Crane::TestScale, 3);
    assert_eq!(frames.scale, "test");
    assert_eq!(frames.time, [0.0, 0.01, 0.02]);
    let value = |name: &str| cell(&names, name, 2);
    let three = |prefix: &str, axes: [&str; 3]| axes.map(|axis| value(&format!("{prefix}{axis}")));
    let row_2 = Sample {
        time: 0.02,
        ship: ship(value),
        joints: three("crane.joint.theta", ["2z", "3x", "4x"]),
        load: three("pendulum.load.", ["x", "y", "z"]),
        theta: [value("pendulum.theta_x"), value("pendulum.theta_y")],
        estimated_load: Some(three("controller.est.load.", ["x", "y", "z"])),
        setpoint: Some(three("controller.sp.load.", ["x", "y", "z"])),
        hook: None,
    };
    let expected = Frame::of(&Crane::TestScale, &row_2);
    assert_eq!(&frames.load[6..9], &row_2.load);
    assert_eq!(&frames.crane[24..36], expected.crane.as_flattened());
    assert_eq!(&frames.deck_attitude[8..12], &expected.deck_attitude);
    assert_eq!(frames.estimated_load[6..9], row_2.estimated_load.unwrap());
    assert_eq!(frames.setpoint[6..9], row_2.setpoint.unwrap());
    assert_eq!(&frames.theta[4..6], &row_2.theta);
    assert_eq!(Some(frames.setpoint_error[2]), expected.setpoint_error);
    assert!(frames.cylinders.is_empty() && frames.hook.is_empty());
}

#[test]
fn a_riggings_hook_is_drawn_where_the_table_has_it() {
    // A recording of the rigging in place of the pendulum: its hook.* beside the load's.
    let mut names = view_names(&Crane::TestScale);
    names.extend(columns::HOOK.map(String::from).into_iter().rev());
    let frames = FrameColumns::from_table(&table(names.clone(), 3), None).expect("every column is there");
    assert_eq!(&frames.hook[3..6], &columns::HOOK.map(|name| cell(&names, name, 1)));
    assert!(serde_json::to_value(&frames).unwrap().get("hook").is_some());
    // Two of the three hook columns are no hook.
    let partial: Vec<String> = names.iter().filter(|n| *n != "pendulum.hook.z").cloned().collect();
    let frames = FrameColumns::from_table(&table(partial, 2), None).expect("every required column is there");
    assert!(frames.hook.is_empty());
    assert!(serde_json::to_value(&frames).unwrap().get("hook").is_none());
}

#[test]
fn a_table_of_the_knuckle_boom_joints_is_drawn_as_the_full_scale_crane() {
    let (names, frames) = reversed_view("knuckle_boom.tip.x", &Crane::FULL_SCALE, 2);
    assert_eq!(frames.scale, "full");
    let value = |name: &str| cell(&names, name, 1);
    let row_1 = Sample {
        time: 0.01,
        ship: ship(value),
        joints: FULL_SCALE_JOINTS.map(value),
        load: ["x", "y", "z"].map(|axis| value(&format!("pendulum.load.{axis}"))),
        theta: [value("pendulum.theta_x"), value("pendulum.theta_y")],
        ..Sample::default()
    };
    let expected = Frame::of(&Crane::FULL_SCALE, &row_1);
    assert_eq!(&frames.crane[12..24], expected.crane.as_flattened());
    assert_eq!(&frames.cylinders[18..36], expected.cylinders.unwrap().as_flattened());
    assert_eq!(&frames.load[3..6], &row_1.load);
    // No ghost markers: the columns are empty and left out of the page's JSON.
    assert!(frames.estimated_load.is_empty() && frames.setpoint.is_empty() && frames.setpoint_error.is_empty());
    let json = serde_json::to_value(&frames).unwrap();
    let keys: Vec<&str> = json.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(keys, ["crane", "cylinders", "deck_attitude", "deck_position", "load", "scale", "theta", "time"]);
}

#[test]
fn a_missing_column_is_named_with_how_to_record_it() {
    let names: Vec<String> =
        view_names(&Crane::TestScale).into_iter().filter(|n| !n.starts_with("crane.joint")).collect();
    let error = FrameColumns::from_table(&table(names, 2), None).unwrap_err();
    assert_eq!(
        error.to_string(),
        "run.csv has no column crane.joint.theta2z, crane.joint.theta3x, crane.joint.theta4x: record them (the \
         scenario's \"record\" variables), or give the scenario file itself to `crane-cosim view`, which records \
         what the view needs"
    );
}

#[test]
fn a_full_scale_table_missing_ship_columns_names_them() {
    let names: Vec<String> = view_names(&Crane::FULL_SCALE)
        .into_iter()
        .filter(|n| !["platform.ship.x", "platform.ship.yaw"].contains(&n.as_str()))
        .collect();
    let error = FrameColumns::from_table(&table(names, 2), None).unwrap_err();
    assert!(error.to_string().starts_with("run.csv has no column platform.ship.x, platform.ship.yaw: record them"));
}

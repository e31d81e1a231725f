use std::path::PathBuf;

use super::*;
use crate::scene::Sample;

/// A table with every column the view needs, each column holding its index plus the row
/// (so a value read from the wrong column or row shows).
fn table(names: Vec<String>, rows: usize) -> SignalTable {
    let columns = (0..names.len()).map(|c| (0..rows).map(|r| c as f64 + r as f64 / 10.0).collect()).collect();
    SignalTable { file: PathBuf::from("run.csv"), names, times: (0..rows).map(|r| r as f64 * 0.01).collect(), columns }
}

fn view_names() -> Vec<String> {
    columns::required().map(String::from).collect()
}

#[test]
fn each_frame_is_drawn_from_its_own_row() {
    // Extra columns, and the required ones in reverse order: found by name, not position.
    let mut names: Vec<String> = vec!["crane.tip.x".into()];
    names.extend(view_names().into_iter().rev());
    let frames = FrameColumns::from_table(&table(names.clone(), 3)).expect("every column is there");
    assert_eq!(frames.time, [0.0, 0.01, 0.02]);
    let value = |name: &str| names.iter().position(|n| n == name).unwrap() as f64 + 0.2;
    let three = |prefix: &str, axes: [&str; 3]| axes.map(|axis| value(&format!("{prefix}{axis}")));
    let row_2 = Sample {
        time: 0.02,
        ship: ["x", "y", "z", "roll", "pitch", "yaw"].map(|dof| value(&format!("platform.ship.{dof}"))),
        joints: three("crane.joint.theta", ["2z", "3x", "4x"]),
        load: three("pendulum.load.", ["x", "y", "z"]),
        theta: [value("pendulum.theta_x"), value("pendulum.theta_y")],
        estimated_load: three("controller.est.load.", ["x", "y", "z"]),
        setpoint: three("controller.sp.load.", ["x", "y", "z"]),
    };
    let expected = Frame::of(&row_2);
    assert_eq!(&frames.load[6..9], &row_2.load);
    assert_eq!(&frames.crane[24..36], expected.crane.as_flattened());
    assert_eq!(&frames.deck_attitude[8..12], &expected.deck_attitude);
    assert_eq!(&frames.estimated_load[6..9], &row_2.estimated_load);
    assert_eq!(&frames.setpoint[6..9], &row_2.setpoint);
    assert_eq!(&frames.theta[4..6], &row_2.theta);
    assert_eq!(frames.setpoint_error[2], expected.setpoint_error);
}

#[test]
fn a_missing_column_is_named_with_how_to_record_it() {
    let names: Vec<String> = view_names().into_iter().filter(|n| !n.starts_with("crane.joint")).collect();
    let error = FrameColumns::from_table(&table(names, 2)).unwrap_err();
    assert_eq!(
        error.to_string(),
        "run.csv has no column crane.joint.theta2z, crane.joint.theta3x, crane.joint.theta4x: record them (the \
         scenario's \"record\" variables), or give the scenario file itself to `crane-cosim view`, which records \
         what the view needs"
    );
}

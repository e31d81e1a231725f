//! `crane-cosim view` of the full-scale knuckle-boom crane: the page written from a results CSV
//! of systems/full_scale.json draws the crane where the FMU's own outputs say (its `tip.*` and
//! its cylinders' `stroke.*`), and a scenario given directly is run and drawn the same way.
//!
//! Needs the packaged FMUs in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::path::Path;
use std::process::Output;

use serde_json::Value;

fn crane_cosim(args: &[&str]) -> Output {
    let output = common::crane_cosim_command()
        .args(args)
        .current_dir(common::workspace_root())
        .output()
        .expect("crane-cosim runs");
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    output
}

/// The page's embedded data.
fn page_data(page: &Path) -> Value {
    let html = std::fs::read_to_string(page).expect("the page is written");
    let json = html.split("<script id=\"crane-data\" type=\"application/json\">").nth(1).expect("data element");
    serde_json::from_str(json.split("</script>").next().unwrap()).expect("JSON data")
}

/// Point `k` of frame `i` of the flattened column `name`, `points` points per frame.
fn point(frames: &Value, name: &str, points: usize, i: usize, k: usize) -> [f64; 3] {
    let column = frames[name].as_array().unwrap_or_else(|| panic!("no column {name}"));
    std::array::from_fn(|axis| column[(i * points + k) * 3 + axis].as_f64().unwrap())
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
}

/// The knuckle_boom FMU's cylinders' retracted pin-to-pin length (m), stroke 0
/// (physics::knuckle_boom::params, the OSP test crane's).
const CYLINDER_MIN_LENGTH: f64 = 2.1;

#[test]
fn a_full_scale_results_csv_is_drawn_where_the_knuckle_boom_fmu_says() {
    let dir = tempfile::tempdir().unwrap();
    let (results, page) = (dir.path().join("run.csv"), dir.path().join("run.html"));
    let [results_arg, page_arg] = [&results, &page].map(|p| p.to_str().unwrap());
    // The vessel moves in profile 1, so the deck's whole rigid-body transform matters.
    crane_cosim(&["run", "scenarios/full_scale_profile1.json", "--stop-time", "3", "-o", results_arg, "-q"]);
    let out = crane_cosim(&["view", results_arg, "-o", page_arg]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("(301 frames, t = 0 to 3 s)"), "{out:?}");

    let data = page_data(&page);
    let frames = &data["frames"];
    assert_eq!(frames["scale"], "full");
    for ghost in ["estimated_load", "setpoint", "setpoint_error"] {
        assert!(frames.get(ghost).is_none(), "a full-scale page has no {ghost}");
    }
    let (header, rows) = common::read_results(&results);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    let tip = ["x", "y", "z"].map(|axis| column(&format!("knuckle_boom.tip.{axis}")));
    let strokes = [column("knuckle_boom.stroke.boom"), column("knuckle_boom.stroke.jib")];
    let load = ["x", "y", "z"].map(|axis| column(&format!("pendulum.load.{axis}")));
    let (mut worst_tip, mut worst_stroke) = (0.0_f64, 0.0_f64);
    for (i, row) in rows.iter().enumerate() {
        worst_tip = worst_tip.max(distance(point(frames, "crane", 4, i, 3), tip.map(|c| row[c])));
        for (cylinder, stroke) in strokes.iter().enumerate() {
            let [barrel_pin, _, rod_pin] = [0, 1, 2].map(|k| point(frames, "cylinders", 6, i, 3 * cylinder + k));
            let drawn_stroke = distance(barrel_pin, rod_pin) - CYLINDER_MIN_LENGTH;
            worst_stroke = worst_stroke.max((drawn_stroke - row[*stroke]).abs());
        }
        assert_eq!(point(frames, "load", 1, i, 0), load.map(|c| row[c]), "row {i}");
    }
    assert!(worst_tip < 1e-9, "the drawn tip is {worst_tip} m from knuckle_boom.tip.*");
    assert!(worst_stroke < 1e-9, "the drawn cylinders are {worst_stroke} m off knuckle_boom.stroke.*");
    // The ship moved: the deck is not at the origin at the end.
    let last = rows.len() - 1;
    assert!(distance(point(frames, "deck_position", 1, last, 0), [0.0; 3]) > 1e-3);
}

#[test]
fn a_full_scale_scenario_is_run_and_drawn_with_its_controller() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("ahc.html");
    let scenario = "scenarios/full_scale_profile1_compensated.json";
    let out = crane_cosim(&["view", scenario, "-o", page.to_str().unwrap(), "--stop-time", "1"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("(101 frames, t = 0 to 1 s)"), "{out:?}");
    let frames = &page_data(&page)["frames"];
    assert_eq!(frames["scale"], "full");
    assert_eq!(frames["crane"].as_array().unwrap().len(), 101 * 12);
    assert_eq!(frames["cylinders"].as_array().unwrap().len(), 101 * 18);
    // The pedestal foot stands 8 m to port of the deck's origin (ArmParams::DEFAULT.base).
    let (foot, deck) = (point(frames, "crane", 4, 0, 0), point(frames, "deck_position", 1, 0, 0));
    assert!((distance(foot, deck) - 8.0).abs() < 1e-9, "{foot:?} {deck:?}");
}

#[test]
fn a_system_that_moves_the_pedestal_is_drawn_with_it_there() {
    let dir = tempfile::tempdir().unwrap();
    let root = common::workspace_root();
    let system = root.join("systems/full_scale.json").canonicalize().unwrap();
    // Still water: the deck frame is the world frame, so the foot is drawn at base.* itself.
    let scenario = serde_json::json!({
        "system": system,
        "start": {"knuckle_boom.base.x": 10.0, "knuckle_boom.base.y": -6.0},
        "stop_time": 0.1,
    });
    let (file, page) = (dir.path().join("moved.json"), dir.path().join("moved.html"));
    std::fs::write(&file, scenario.to_string()).unwrap();
    crane_cosim(&["view", file.to_str().unwrap(), "-o", page.to_str().unwrap()]);
    let frames = &page_data(&page)["frames"];
    assert_eq!(point(frames, "crane", 4, 0, 0), [10.0, -6.0, 0.0]);
}

#[test]
fn a_scenario_with_another_crane_is_drawn_with_that_cranes_arm() {
    let dir = tempfile::tempdir().unwrap();
    let system = common::workspace_root().join("systems/full_scale_ahc.json").canonicalize().unwrap();
    let scenario = serde_json::json!({
        "system": system,
        "start": {"knuckle_boom.crane": "ahc_10t", "knuckle_boom_controller.crane": "ahc_10t"},
        "stop_time": 0.1,
    });
    let (file, page, results) = (dir.path().join("ahc.json"), dir.path().join("ahc.html"), dir.path().join("ahc.csv"));
    std::fs::write(&file, scenario.to_string()).unwrap();
    crane_cosim(&["view", file.to_str().unwrap(), "-o", page.to_str().unwrap()]);
    crane_cosim(&["run", file.to_str().unwrap(), "-o", results.to_str().unwrap()]);
    let frames = &page_data(&page)["frames"];
    let (header, rows) = common::read_results(&results);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    let tip = ["x", "y", "z"].map(|axis| rows[0][column(&format!("knuckle_boom.tip.{axis}"))]);
    // The AHC crane's arm is the default one scaled by 1.2: drawn with the default arm, the tip
    // would be metres off.
    assert!(distance(point(frames, "crane", 4, 0, 3), tip) < 1e-9, "{:?} vs {tip:?}", point(frames, "crane", 4, 0, 3));
}

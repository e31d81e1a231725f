use super::*;
use physics::hydraulic_crane::plant::CraneParams;
use serde_json::json;

fn default_base() -> Vec3 {
    CraneParams::DEFAULT.arm.base
}

#[test]
fn the_default_crane_is_the_third_waves_crane_bit_for_bit() {
    let d = load("", None).unwrap();
    assert_eq!(d.name, catalogue::DEFAULT_CRANE);
    assert_eq!(d.params(default_base()), CraneParams::DEFAULT);
    assert_eq!(d.sensors, SensorSet::DEFAULT);
    assert_eq!(fingerprint(&d.params(default_base())), fingerprint(&CraneParams::DEFAULT));
}

#[test]
fn every_catalogue_crane_loads_consistent_with_a_source_for_every_value() {
    for name in catalogue::names() {
        let (_, value) = json::resolve(name, None).unwrap();
        let d = from_value(value.clone()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(d.name, name);
        let written = serde_json::to_value(&d).unwrap();
        for leaf in json::leaves(&written).iter().filter(|p| !p.starts_with("sources.") && !p.starts_with("arm.base")) {
            let covered = d
                .sources
                .keys()
                .any(|k| leaf == k || leaf.starts_with(&format!("{k}.")) || leaf.starts_with(&format!("{k}[")));
            assert!(covered || leaf == "name" || leaf == "title", "{name}: no source for {leaf}");
        }
    }
}

#[test]
fn the_catalogue_cranes_differ_where_their_files_say() {
    let osp = load("osp_test_crane", None).unwrap();
    assert_eq!(osp.boom.cylinder.count, 2.0);
    // The OSP pin triangle reproduces its joint range, 1.2…69.3° (docs/crane-description.md).
    let (low, high) = osp.arm.boom_cylinder.joint_range().unwrap();
    assert!((low.to_degrees() - 1.2).abs() < 0.05 && (high.to_degrees() - 69.3).abs() < 0.05, "{low} {high}");
    let (low, high) = osp.arm.jib_cylinder.joint_range().unwrap();
    assert!((low.to_degrees() + 150.3).abs() < 0.05 && (high.to_degrees() + 44.3).abs() < 0.05, "{low} {high}");
    let ahc = load("ahc_10t", None).unwrap();
    assert_eq!(ahc.winch.circuit, WinchCircuit::Closed);
    let params = ahc.params(default_base());
    // 191 kN at 30 MPa: twice the rated 10 t (98 kN).
    let pull = checks::line_pull(&params, 30e6);
    assert!(pull > 1.9 * 10_000.0 * 9.80665 && pull < 2.0 * 10_000.0 * 9.80665, "{pull}");
    // Full pump flow pays out at ≥ 1.5 m/s: r·D_p·ω_p/(D_m·n).
    let speed = ahc.winch.drum_radius * ahc.winch.pump.displacement * ahc.winch.pump.speed
        / (ahc.winch.drive.displacement * ahc.winch.drive.gear);
    assert!(speed > 1.5 && speed < 2.5, "{speed}");
}

/// The default crane's JSON with `change` applied (through `extends`, as a user would write it).
fn changed(change: serde_json::Value) -> Result<CraneDescription, String> {
    let (_, mut value) = json::resolve("osp_derived", None).unwrap();
    json::merge(&mut value, change);
    from_value(value)
}

#[test]
fn an_unknown_field_is_named_with_the_nearest_known_one() {
    let e = changed(json!({"boom": {"cylinder": {"boer": 0.4}}})).unwrap_err();
    assert!(e.contains("unknown field boom.cylinder.boer") && e.contains("did you mean boom.cylinder.bore"), "{e}");
    let e = changed(json!({"sources": {"boom.cylindr": "x"}})).unwrap_err();
    assert!(e.contains("sources.boom.cylindr names no field") && e.contains("boom.cylinder"), "{e}");
}

#[test]
fn a_missing_field_is_named_by_its_path() {
    let (_, mut value) = json::resolve("osp_derived", None).unwrap();
    value["boom"]["cylinder"].as_object_mut().unwrap().remove("coulomb");
    let e = from_value(value).unwrap_err();
    assert!(e.contains("missing field boom.cylinder.coulomb"), "{e}");
    let (_, mut value) = json::resolve("osp_derived", None).unwrap();
    value["winch"].as_object_mut().unwrap().remove("drum_radius");
    let e = from_value(value).unwrap_err();
    assert!(e.contains("winch") && e.contains("drum_radius"), "{e}");
}

#[test]
fn the_mounting_point_is_not_part_of_a_description() {
    let e = changed(json!({"arm": {"base": [0.0, 0.0, 0.0]}})).unwrap_err();
    assert!(e.contains("arm.base") && e.contains("base.*"), "{e}");
}

#[test]
fn a_joint_limit_beyond_the_cylinders_reach_is_refused_naming_both() {
    let e = changed(json!({"joint_limits": {"boom": [-0.35, 1.4]}})).unwrap_err();
    assert!(e.contains("joint_limits.boom") && e.contains("80.21°") && e.contains("75.02°"), "{e}");
}

#[test]
fn a_rope_weaker_than_its_winch_is_refused() {
    // The winch's largest pull: 30 MPa × 0.4 L/rev × 30 / 0.25 m = 229.2 kN.
    let e = changed(json!({"rope": {"minimum_breaking_load": 200e3}})).unwrap_err();
    assert!(e.contains("rope.minimum_breaking_load 200.0 kN") && e.contains("229.2 kN"), "{e}");
    assert!(changed(json!({"rope": {"minimum_breaking_load": 230e3}})).is_ok());
}

#[test]
fn a_winch_too_weak_for_the_rated_load_is_refused() {
    // 28 MPa × 0.4 L/rev × 30 / 0.25 m = 213.9 kN lifts 21.8 t, not 25 t.
    let e = changed(json!({"rating": {"safe_working_load": 25000.0}})).unwrap_err();
    assert!(e.contains("rating.safe_working_load 25000 kg") && e.contains("213.9 kN"), "{e}");
}

#[test]
fn a_closed_circuit_whose_rated_flow_disagrees_with_its_pump_is_refused() {
    let e = changed(json!({"winch": {"circuit": "Closed", "drive": {"valve": {"max_flow": 0.005}}}})).unwrap_err();
    assert!(e.contains("winch.drive.valve.max_flow") && e.contains("pump"), "{e}");
    assert!(changed(json!({"winch": {"circuit": "Closed"}})).is_ok());
}

#[test]
fn json_mistakes_get_a_hint_and_the_file_name() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("mine.json");
    std::fs::write(&file, "{\"extends\": \"osp_derived\", // my crane\n}").unwrap();
    let e = load(file.to_str().unwrap(), None).unwrap_err();
    assert!(e.contains("mine.json") && e.contains("no comments"), "{e}");
    let e = load("no_such_crane", None).unwrap_err();
    assert!(e.contains("no crane named 'no_such_crane'") && e.contains("osp_derived, osp_test_crane, ahc_10t"), "{e}");
    let e = load("missing/file.json", Some(dir.path())).unwrap_err();
    assert!(e.contains("not found") && e.contains(&dir.path().join("missing/file.json").display().to_string()), "{e}");
}

#[test]
fn a_description_extends_another_from_its_own_folder_and_the_fingerprint_follows() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(
        dir.path().join("sub/big_drum.json"),
        r#"{"extends": "osp_derived", "name": "big_drum", "winch": {"drum_radius": 0.5}}"#,
    )
    .unwrap();
    std::fs::write(dir.path().join("mine.json"), r#"{"extends": "sub/big_drum.json", "name": "mine"}"#).unwrap();
    // Found through the resources folder, as an FMU in another tool would.
    let d = load("mine.json", Some(dir.path())).unwrap();
    assert_eq!((d.name.as_str(), d.winch.drum_radius), ("mine", 0.5));
    let (mine, default) = (fingerprint(&d.params(default_base())), fingerprint(&CraneParams::DEFAULT));
    assert_ne!(mine, default);
    assert!(mine.fract() == 0.0 && mine < 2f64.powi(52) && default.fract() == 0.0);
    std::fs::write(dir.path().join("loop.json"), r#"{"extends": "loop.json"}"#).unwrap();
    assert!(load(dir.path().join("loop.json").to_str().unwrap(), None).unwrap_err().contains("a loop?"));
}

#[test]
fn the_fingerprint_sees_a_change_of_one_unit_in_the_last_place() {
    let mut p = CraneParams::DEFAULT;
    let before = fingerprint(&p);
    assert_eq!(before, fingerprint(&CraneParams::DEFAULT));
    p.supply.pressure = f64::from_bits(p.supply.pressure.to_bits() + 1);
    assert_ne!(before, fingerprint(&p));
    p = CraneParams::DEFAULT;
    p.arm.base.y = -5.0;
    assert_ne!(before, fingerprint(&p));
}

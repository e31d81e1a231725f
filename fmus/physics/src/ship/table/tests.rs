use super::*;

#[test]
fn a_well_formed_file_is_interpolated() {
    let table = MotionTable::parse(RECORDED_DECK).unwrap();
    assert_eq!(table.span(), (0.0, 1.5));
    let at = table.sample(0.5);
    assert_eq!(at.pose(), [0.01, -0.02, 0.005, 0.01, -0.01, 0.001]);
    let between = table.sample(0.75);
    assert!(between.dof.iter().all(|a| a.pos.is_finite() && a.vel.is_finite() && a.acc.is_finite()));
    // Without a header the same data gives the same table.
    let bare: String = RECORDED_DECK.lines().filter(|l| !l.starts_with("time")).map(|l| format!("{l}\n")).collect();
    assert_eq!(MotionTable::parse(&bare).unwrap(), table);
}

#[test]
fn malformed_files_are_clear_errors() {
    let cases = [
        ("time,surge\n0,1\n1,2\n", "line 2: expected 7 comma-separated columns"),
        ("0,0,0,0,0,0,0\n1,0,0,x,0,0,0\n", "line 2: heave = \"x\" is not a finite number"),
        ("0,0,0,0,0,0,0\n1,0,0,0,0,0,0\n1,0,0,0,0,0,0\n", "line 3: time 1 does not increase"),
        ("0,0,0,0,0,0,0\n", "at least 2 samples"),
        ("", "at least 2 samples"),
        ("0,0,0,0,0,0,0\n1,0,0,0,0,0,inf\n", "yaw = \"inf\" is not a finite number"),
        ("0,0,0,0,0,0,0,0\n", "line 1: expected 7"),
    ];
    for (text, expected) in cases {
        let error = MotionTable::parse(text).unwrap_err();
        assert!(error.contains(expected), "{text:?}: {error}");
    }
}

#[test]
fn a_missing_file_names_the_path() {
    let error = MotionTable::load(Path::new("no/such/motion.csv")).unwrap_err();
    assert!(error.contains("cannot read motion file no/such/motion.csv"), "{error}");
}

#[test]
fn relative_paths_resolve_in_the_resources_folder() {
    let resources = Path::new("/fmu/resources");
    assert_eq!(resolve_path("sea.csv", Some(resources)), Path::new("/fmu/resources/sea.csv"));
    assert_eq!(resolve_path("/data/sea.csv", Some(resources)), Path::new("/data/sea.csv"));
    assert_eq!(resolve_path("sea.csv", None), Path::new("sea.csv"));
}

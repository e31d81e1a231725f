//! The bias study's scenarios (studies/bias, docs/bias-study.md), shortened to 15 s after the
//! release: IMU2's magnetic field turned 5.95° from IMU1's resolves part of the released θx swing
//! into θy (thesis §7.2.1), which the thesis' common yaw removal leaves and the load heading
//! calibration (`bias.load_heading`) removes.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

/// True θy RMS (deg) over 10–25 s, after the release, and the estimated θy (deg) averaged over
/// the last 0.5 s of the hold, when the true θy is 0: the estimation error at release.
fn off_axis(scenario: &str) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("run.csv");
    let path = common::workspace_root().join("studies/bias").join(scenario);
    let out = common::crane_cosim_command()
        .args(["run", path.to_str().unwrap(), "--stop-time", "25", "-o", csv.to_str().unwrap(), "-q"])
        .output()
        .expect("crane-cosim runs");
    assert!(out.status.success(), "{scenario}: {}", String::from_utf8_lossy(&out.stderr));
    let (header, rows) = common::read_results(&csv);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (time, theta_y, estimate) = (column("time"), column("pendulum.theta_y"), column("controller.est.theta_y"));
    let released: Vec<f64> = rows.iter().filter(|r| r[time] >= 10.0).map(|r| r[theta_y]).collect();
    let rms = (released.iter().map(|v| v * v).sum::<f64>() / released.len() as f64).sqrt();
    let hold: Vec<f64> = rows.iter().filter(|r| (9.5..10.0).contains(&r[time])).map(|r| r[estimate]).collect();
    (rms.to_degrees(), (hold.iter().sum::<f64>() / hold.len() as f64).to_degrees())
}

#[test]
fn a_field_discrepancy_of_5_95_degrees_makes_off_axis_swing_that_the_load_heading_calibration_removes() {
    // Held at θx = −23°, a load whose field is turned 5.95° reads θy ≈ 23° · sin 5.95° = 2.4°.
    let (none_rms, none_error) = off_axis("none.json");
    let (field_rms, field_error) = off_axis("field.json");
    let (calibrated_rms, calibrated_error) = off_axis("field_cal.json");
    println!("θy RMS 10–25 s / estimated θy at release: none {none_rms:.3}° / {none_error:.3}°, 5.95° field {field_rms:.3}° / {field_error:.3}°, calibrated {calibrated_rms:.3}° / {calibrated_error:.3}°");
    assert!((2.1..2.7).contains(&field_error), "5.95° field: estimated θy at release {field_error}°");
    assert!(none_error.abs() < 0.3 && calibrated_error.abs() < 0.3, "{none_error}°, {calibrated_error}°");
    // Measured: 0.46° with the discrepancy, 0.16° without or calibrated.
    assert!(field_rms > 0.3, "5.95° field: θy RMS {field_rms}°");
    assert!(none_rms < 0.3 && calibrated_rms < 0.3, "θy RMS {none_rms}°, calibrated {calibrated_rms}°");
}

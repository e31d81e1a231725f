//! The controller's optional initialisation calibrations on a bare controller at rest: the gyro
//! biases (`gyro_bias`) and the encoder counted from the initial length (`relative_encoder`).

use super::*;
use crate::crane::winch::CableModel;

const DT: f64 = 0.01;

/// The estimated load angles (θx, θy) in rad after `seconds` of `inputs`, with commands from 10 s.
fn load_angles_after(config: ControllerConfig, inputs: &Inputs, seconds: f64) -> (f64, f64) {
    let mut controller = Controller::new(ControllerConfig { mode: Mode::Hold, active_from: 10.0, ..config }).unwrap();
    let mut out = None;
    for k in 0..(seconds / DT).round() as u64 {
        out = Some(controller.step(k as f64 * DT, DT, inputs).unwrap());
    }
    let out = out.unwrap();
    (out.theta_x, out.theta_y)
}

#[test]
fn a_gyro_bias_learnt_at_rest_no_longer_tilts_the_load_estimate() {
    // IMU2 at rest, level, with a 0.3 °/s bias on x (the data-sheet limit): the load filter's
    // accelerometer correction (ᾱ_a = 0.005 per sample, a 2 s time constant) holds the estimate
    // 0.3 °/s × 2 s ≈ 0.6° off; learnt over the 10 s before active_from and removed, it is gone.
    let mut inputs = Inputs::AT_REST;
    inputs.imu2.gyro = Vec3::new(0.3f64.to_radians(), 0.0, 0.0);
    let config = ControllerConfig { angle_cutoff: 0.0, ..ControllerConfig::DEFAULT };
    let (biased, _) = load_angles_after(config, &inputs, 40.0);
    let (calibrated, _) = load_angles_after(ControllerConfig { gyro_bias: true, ..config }, &inputs, 40.0);
    assert!(biased.to_degrees().abs() > 0.4, "without calibration θx = {}°", biased.to_degrees());
    assert!(calibrated.to_degrees().abs() < 0.01, "with calibration θx = {}°", calibrated.to_degrees());
}

#[test]
fn the_relative_encoder_starts_at_the_initial_length_despite_the_drum_mismatch() {
    // The plant's encoder counts from the winch home on its 41.26 mm drum (eq. 3.3); read as an
    // absolute angle on the controller's nominal 41.32 mm drum, l_p = 0.7 m reads 0.5 mm long —
    // the size of the delta law's 0.5 mm length deadband. Counted from the first sample and offset
    // by the initial length's angle (§6.1), it reads the initial length.
    let mut inputs = Inputs::AT_REST;
    let jib = ControllerConfig::DEFAULT.potentiometer.extension(inputs.pots[2]);
    inputs.encoder = CableModel::THESIS.winch_angle(0.7, jib);
    let length = |config: ControllerConfig| Controller::new(config).unwrap().step(0.0, DT, &inputs).unwrap().lp;
    let absolute = length(ControllerConfig { relative_encoder: false, ..ControllerConfig::DEFAULT });
    let relative = length(ControllerConfig::DEFAULT);
    assert!(absolute - 0.7 > 0.0004, "absolute encoder: l_p = {absolute} m");
    assert!((relative - 0.7).abs() < 1e-12, "relative encoder: l_p = {relative} m");
}

#[test]
fn the_relative_encoder_starts_at_an_initial_length_other_than_the_set_point() {
    // Winching from 0.7 m to a 0.9 m set-point: the encoder's start is the given 0.7 m, not the
    // set-point (which would read 0.2 m too long and never winch).
    let mut inputs = Inputs::AT_REST;
    let jib = ControllerConfig::DEFAULT.potentiometer.extension(inputs.pots[2]);
    inputs.encoder = CableModel::THESIS.winch_angle(0.7, jib);
    let fixed = Setpoint { lp: 0.9, ..Setpoint::FIXED };
    let length = |initial_length| {
        let config = ControllerConfig { fixed, initial_length, ..ControllerConfig::DEFAULT };
        Controller::new(config).unwrap().step(0.0, DT, &inputs).unwrap().lp
    };
    assert!((length(Some(0.7)) - 0.7).abs() < 1e-12);
    assert!((length(None) - 0.9).abs() < 1e-12);
    let invalid = ControllerConfig { initial_length: Some(0.0), ..ControllerConfig::DEFAULT };
    assert!(Controller::new(invalid).is_err());
}

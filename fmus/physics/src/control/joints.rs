//! From a world-frame set-point to the joint controllers' references (thesis §6.1–6.2, Fig. 6.2).
//!
//! The tip set-point (W) goes into the crane base frame J12 with the ship pose estimate
//! (eq. 5.65 inverted), then through the crane's inverse kinematics (eqs. 4.78–4.88) and the
//! actuator mechanisms' (eqs. 4.30, 4.45, 4.58) to actuator extensions. The length set-point
//! becomes a winch angle through eqs. 3.1–3.4 solved for Δθ_wm with the controller's nominal
//! drum diameter, 41.32 mm (§6.1), at the measured jib extension. (The plant's drum is
//! 41.26 mm: the mismatch is the thesis'.)

use crate::crane::kinematics::inverse;
use crate::crane::mechanisms::{MECHANISMS, STROKE};
use crate::crane::winch::CableModel;
use crate::crane::KinematicsError;
use crate::estimation::pose::BaseFrame;
use crate::math::Vec3;

/// The controller's cable model: eqs. 3.1–3.4 with the nominal 41.32 mm drum (§6.1).
pub const CONTROLLER_CABLE: CableModel =
    CableModel { base_length: 325.0, drum_diameter: 41.32, jib_fit: [0.010668, 0.5327, 0.59982] };

/// Actuator extensions (m) that put the tip at `tip` (m, W) for the crane base at `frame`, each
/// clamped to the 0–50 mm stroke, and whether any was clamped. Fails when the target is out of
/// the boom and jib's reach (or on the slewing axis, or not finite).
pub fn extensions_for_tip(frame: &BaseFrame, tip: &Vec3) -> Result<([f64; 3], bool), KinematicsError> {
    let joints = inverse(&frame.to_base(tip))?;
    let raw = [0, 1, 2].map(|i| MECHANISMS[i].extension(joints[i]));
    if !raw.iter().all(|d| d.is_finite()) {
        return Err(KinematicsError::NotFinite);
    }
    let clamped = raw.map(|d| d.clamp(0.0, STROKE));
    Ok((clamped, clamped != raw))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crane::kinematics::tip_from_actuators;
    use crate::crane::motion::CRANE_BASE;
    use crate::crane::winch::CableModel;
    use crate::math::{euler_zyx, Quat};

    #[test]
    fn the_world_set_point_round_trips_through_the_kinematics() {
        let frame = BaseFrame::new(&Vec3::new(0.004, -0.003, 0.002), &euler_zyx(0.04, -0.03, 0.01), &CRANE_BASE);
        let target = Vec3::new(0.003, -0.502, -0.153);
        let (d, limited) = extensions_for_tip(&frame, &target).unwrap();
        assert!(!limited);
        let back = frame.to_world(&tip_from_actuators(&d).unwrap());
        assert!((back - target).norm() < 1e-12, "{back:?}");
    }

    #[test]
    fn targets_beyond_the_stroke_are_clamped_and_out_of_reach_is_an_error() {
        let frame = BaseFrame::new(&Vec3::zeros(), &Quat::identity(), &CRANE_BASE);
        // Far to the north: the base actuator would need more than its stroke.
        let (d, limited) = extensions_for_tip(&frame, &Vec3::new(0.25, -0.45, -0.153)).unwrap();
        assert!(limited && d.iter().all(|d| (0.0..=STROKE).contains(d)));
        assert!(matches!(
            extensions_for_tip(&frame, &Vec3::new(0.0, -2.0, 0.0)),
            Err(KinematicsError::OutOfReach { .. })
        ));
    }

    #[test]
    fn the_controller_drum_is_the_nominal_one() {
        assert_eq!(CONTROLLER_CABLE.drum_diameter, 41.32);
        assert_eq!(CONTROLLER_CABLE.jib_fit, CableModel::default().jib_fit);
        assert_eq!(CONTROLLER_CABLE.base_length, CableModel::default().base_length);
    }
}

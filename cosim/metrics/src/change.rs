//! Small conversions of the thesis' result tables and pendulum plots: the percentage change of a
//! metric (eq. 7.1) and the cable angles from the load's position (§7.2, the second and third
//! plots of Figs. 7.2/7.3).

/// (value − reference)/reference·100 (%), thesis eq. 7.1: value the compensated metric, reference
/// the uncompensated one; −50 is "a reduction of 50 %". A zero reference has no percentage:
/// `f64::NAN` (not ±∞, which would read as a measured change).
pub fn percent_change(value: f64, reference: f64) -> f64 {
    if reference == 0.0 {
        return f64::NAN;
    }
    (value - reference) / reference * 100.0
}

/// The pendulum angles (θx, θy) (rad) of the cable from the crane tip to the load, both given in
/// the world frame W (North-East-Down, m).
///
/// The pendulum model's convention (thesis eqs. 4.89–4.96, `physics::pendulum`): the load sits
/// at tip + l·R_x(θx)·R_y(θy)·(0, 0, 1), i.e. along d = (sin θy, −sin θx·cos θy, cos θx·cos θy),
/// so θy = asin(d_x) ∈ [−π/2, π/2] and θx = atan2(−d_y, d_z) ∈ (−π, π]. At θy = ±π/2 θx is
/// undefined (the X–Y sequence's gimbal lock) and comes out 0; coincident points give NaN.
pub fn cable_angles(load: [f64; 3], tip: [f64; 3]) -> (f64, f64) {
    let d = [0, 1, 2].map(|k| load[k] - tip[k]);
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if !(length > 0.0) {
        return (f64::NAN, f64::NAN);
    }
    // Clamped: rounding can push |d_x|/length a hair above 1.
    let theta_y = (d[0] / length).clamp(-1.0, 1.0).asin();
    // atan2 needs no normalisation: both arguments share the factor cos θy / length ≥ 0.
    let theta_x = (-d[1]).atan2(d[2]);
    (theta_x, theta_y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use physics::math::Vec3;
    use physics::pendulum::{load_kinematics, PendulumParams, Swing, TipMotion};

    #[test]
    fn percentage_change_of_eq_7_1() {
        assert_eq!(percent_change(25.0, 100.0), -75.0);
        assert_eq!(percent_change(0.3, 0.2), (0.3 - 0.2) / 0.2 * 100.0);
        assert!((percent_change(0.3, 0.2) - 50.0).abs() < 1e-12);
        assert!(percent_change(1.0, 0.0).is_nan());
    }

    #[test]
    fn cable_angles_by_hand() {
        let tip = [1.0, 2.0, -3.0];
        let below = [1.0, 2.0, -2.3];
        assert_eq!(cable_angles(below, tip), (0.0, 0.0));
        // Swung north (+x): positive θy. Swung east (+y): negative θx (e_r,y = −sin θx cos θy).
        let (tx, ty) = cable_angles([1.0 + 0.7 * 0.2f64.sin(), 2.0, -3.0 + 0.7 * 0.2f64.cos()], tip);
        assert!(tx.abs() < 1e-15 && (ty - 0.2).abs() < 1e-15);
        let (tx, ty) = cable_angles([1.0, 2.0 + 0.7 * 0.2f64.sin(), -3.0 + 0.7 * 0.2f64.cos()], tip);
        assert!((tx + 0.2).abs() < 1e-15 && ty.abs() < 1e-15);
        let (tx, ty) = cable_angles(tip, tip);
        assert!(tx.is_nan() && ty.is_nan());
    }

    /// The physics crate places the load at the given angles (eqs. 4.94–4.96); cable_angles must
    /// give them back, including swings beyond 90° in θx.
    #[test]
    fn cable_angles_invert_the_pendulum_model() {
        let params = PendulumParams::default();
        let tip = TipMotion { pos: Vec3::new(0.4, -1.2, -2.5), lp: 0.7, ..TipMotion::default() };
        for (theta_x, theta_y) in [(0.3, -0.2), (-0.1, 0.25), (-1.2, 0.7), (2.5, -1.3), (-3.0, 1.5), (0.0, -0.9)] {
            let swing = Swing { theta_x, theta_y, ..Swing::default() };
            let load = load_kinematics(&params, &swing, &tip, (0.0, 0.0)).pos;
            let (tx, ty) = cable_angles(load.into(), tip.pos.into());
            assert!(
                (tx - theta_x).abs() < 1e-12 && (ty - theta_y).abs() < 1e-12,
                "({theta_x}, {theta_y}) → ({tx}, {ty})"
            );
        }
    }
}

//! The LQR-based delta compensation law of thesis §6.2 (eqs. 6.27–6.31, Figs. 6.2–6.3).
//!
//! Errors e = x_d − x on the world-frame tip position, the pendulum angles and the length, each
//! set to zero inside its deadband (0.5 mm on lengths, 0.0175 rad on angles). The desired length
//! is first offset by the tip's height error, l_pd ← l_pd + (z_td − z_t), so the winch takes over
//! heave the tip cannot follow. The delta action u_Δ = K_Δ e has the structure and signs of the
//! LQR gain (Q = 10·I, R = I: e_θx enters ÿ_t with +8.95, e_θy enters ẍ_t with −8.95) with the
//! thesis' tuned gains K_PΔ = 1 on x, y, z and l_p, 0.1 m/rad on the angle couplings and
//! K_DΔ = 0:
//!
//! ```text
//! Δx_t = e_x − 0.1 e_θy,   Δy_t = e_y + 0.1 e_θx,   Δz_t = e_z,   Δl_p = e_lp,
//! ```
//!
//! and the set-points are the measured state plus the delta (eqs. 6.28–6.31). The signs move the
//! tip toward the load: the load hangs at y_t − l_p sin θx and x_t + l_p sin θy, and with
//! e_θ = −θ the tip set-point moves by −0.1 θx in y and +0.1 θy in x. The joint controllers turn
//! the offset into a tip velocity opposing the swing, ẏ_t ∝ −θx, which in
//! θ̈x = −(g/l) θx + ÿ_t / l damps θx.
//!
//! Gain scheduling over the cable length (beyond the thesis; docs/tuning.md). The thesis tunes
//! the angle gain once, and finds the LQR gain insensitive to the length ("linearising the system
//! with various pendulum lengths in the range of 0.050–1.000 m does not have a significant effect
//! on the final gain matrix", §6.2), while §4.3.2 (Fig. 4.16) shows the linear model losing
//! accuracy away from its length and recommends updating the matrices. With
//! [`GainSchedule::Length`] the controller ([`super::controller`]) scales the tuned angle gain as
//! the LQR's own angle coupling scales with the measured length l:
//!
//! ```text
//! k_θ(l) = k_θ · K_θ(l) / K_θ(l_d),
//! ```
//!
//! K_θ(l) the entry (ÿ_t, θx) of the gain of eq. 6.25 designed at l (eqs. 6.17–6.18, Q = 10·I,
//! R = I; [`crate::control::lqr::angle_coupling`]: 10.17 at 0.05 m, 8.95 at 0.7 m, 8.50 at
//! 1.0 m), and l_d the length the tuned 0.1 m/rad is taken to hold at. The thesis designs "with an
//! initial pendulum length l_p" without naming it; l_d is the desired length at the first active
//! sample (the length of the equilibrium x_d, eq. 6.15, that the design linearises about; 0.7 m in
//! every thesis test). The position gain is not scheduled: K's position and velocity entries of
//! the tip's and the length's own double integrators do not depend on l (√10 and
//! √(10 + 2√10) at every length).

use super::lqr::GainSchedule;
use super::setpoint::Setpoint;
use crate::math::Vec3;
use serde::{Deserialize, Serialize};

/// The gains and error deadbands of the delta law (config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CompensationGains {
    /// K_PΔ on the tip position and the length errors (m/m).
    pub position: f64,
    /// K_PΔ on the pendulum angle errors (m/rad).
    pub angle: f64,
    /// Deadband on the tip position and length errors (m).
    pub position_deadband: f64,
    /// Deadband on the angle errors (rad).
    pub angle_deadband: f64,
    /// Whether `angle` holds at every length or is scaled with the LQR's angle coupling at the
    /// measured length (the controller applies it: [`CompensationGains::scheduled_angle`]).
    pub schedule: GainSchedule,
}

default_is_const!(CompensationGains);

impl CompensationGains {
    /// §6.2: K_PΔ = 1 and 0.1 m/rad, deadbands 0.5 mm and 0.0175 rad (1°); the angle gain fixed,
    /// as the thesis has it.
    pub const DEFAULT: CompensationGains = CompensationGains {
        position: 1.0,
        angle: 0.1,
        position_deadband: 0.0005,
        angle_deadband: 0.0175,
        schedule: GainSchedule::Fixed,
    };

    /// The scheduled angle gain k_θ · K_θ(l) / K_θ(l_d) (m/rad, the module documentation) for the
    /// LQR angle couplings `coupling` = K_θ(l) at the measured length and `design` = K_θ(l_d) at
    /// the design length; exactly `angle` when they are equal.
    pub fn scheduled_angle(&self, coupling: f64, design: f64) -> f64 {
        self.angle * (coupling / design)
    }
}

/// The measured (or estimated) state the law acts on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// Tip position (m, W).
    pub tip: Vec3,
    /// Pendulum angles (rad).
    pub theta_x: f64,
    pub theta_y: f64,
    /// Pendulum length (m).
    pub lp: f64,
}

/// Zero inside the deadband, the error itself outside.
fn deadband(error: f64, band: f64) -> f64 {
    if error.abs() < band {
        0.0
    } else {
        error
    }
}

impl CompensationGains {
    /// The delta action (Δx_t, Δy_t, Δz_t) and Δl_p for the desired state `desired` and the
    /// measured state `x`.
    pub fn delta(&self, desired: &Setpoint, x: &Measured) -> Setpoint {
        let e_tip = (desired.tip - x.tip).map(|e| deadband(e, self.position_deadband));
        let e_theta_x = deadband(-x.theta_x, self.angle_deadband);
        let e_theta_y = deadband(-x.theta_y, self.angle_deadband);
        let lp_desired = desired.lp + (desired.tip.z - x.tip.z);
        let e_lp = deadband(lp_desired - x.lp, self.position_deadband);
        Setpoint {
            tip: Vec3::new(
                self.position * e_tip.x - self.angle * e_theta_y,
                self.position * e_tip.y + self.angle * e_theta_x,
                self.position * e_tip.z,
            ),
            lp: self.position * e_lp,
        }
    }

    /// The compensated set-point: the measured state plus the delta action (eqs. 6.28–6.31).
    pub fn setpoint(&self, desired: &Setpoint, x: &Measured) -> Setpoint {
        let delta = self.delta(desired, x);
        Setpoint { tip: x.tip + delta.tip, lp: x.lp + delta.lp }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::lqr::{lqr, pendulum_model};
    use crate::estimation::pose::load_position;
    use crate::math::STANDARD_GRAVITY;
    use nalgebra::DMatrix;

    const DEG: f64 = std::f64::consts::PI / 180.0;

    fn at_setpoint() -> Measured {
        Measured { tip: Setpoint::FIXED.tip, theta_x: 0.0, theta_y: 0.0, lp: Setpoint::FIXED.lp }
    }

    #[test]
    fn the_delta_law_moves_the_tip_toward_the_load() {
        let gains = CompensationGains::default();
        for (theta_x, theta_y) in [(10.0, 0.0), (-10.0, 0.0), (0.0, 8.0), (0.0, -8.0), (5.0, -7.0)] {
            let x = Measured { theta_x: theta_x * DEG, theta_y: theta_y * DEG, ..at_setpoint() };
            let delta = gains.delta(&Setpoint::FIXED, &x);
            let load = load_position(&x.tip, x.lp, x.theta_x, x.theta_y);
            let toward = load - x.tip;
            // The horizontal step points at the load's horizontal offset.
            let step = Vec3::new(delta.tip.x, delta.tip.y, 0.0);
            let offset = Vec3::new(toward.x, toward.y, 0.0);
            assert!(step.dot(&offset) > 0.0, "θ = ({theta_x}, {theta_y})°: step {step:?}, load offset {offset:?}");
            assert!((delta.tip.y - (-0.1 * x.theta_x)).abs() < 1e-15 && (delta.tip.x - 0.1 * x.theta_y).abs() < 1e-15);
        }
    }

    #[test]
    fn the_signs_are_those_of_the_lqr_gain() {
        // ũ = K e: the ÿ_t row's θx entry and the ẍ_t row's θy entry have the signs of the delta
        // law's angle couplings.
        let (a, b) = pendulum_model(0.7, STANDARD_GRAVITY);
        let k = lqr(&a, &b, &(DMatrix::identity(12, 12) * 10.0), &DMatrix::identity(6, 6)).unwrap().k;
        let gains = CompensationGains::default();
        let x = Measured { theta_x: -0.2, theta_y: -0.2, ..at_setpoint() };
        let delta = gains.delta(&Setpoint::FIXED, &x);
        // e_θx = e_θy = +0.2.
        assert_eq!(delta.tip.y.signum(), k[(1, 3)].signum());
        assert_eq!(delta.tip.x.signum(), k[(0, 4)].signum());
    }

    #[test]
    fn errors_inside_the_deadbands_give_no_action() {
        let gains = CompensationGains::default();
        let x = Measured {
            tip: Setpoint::FIXED.tip + Vec3::new(0.0004, -0.0004, 0.0),
            theta_x: 0.9 * DEG,
            theta_y: -0.9 * DEG,
            lp: Setpoint::FIXED.lp + 0.0004,
        };
        let delta = gains.delta(&Setpoint::FIXED, &x);
        assert_eq!(delta, Setpoint { tip: Vec3::zeros(), lp: 0.0 });
        assert_eq!(gains.setpoint(&Setpoint::FIXED, &x), Setpoint { tip: x.tip, lp: x.lp });
    }

    #[test]
    fn position_errors_pass_through_and_the_length_takes_the_height_error() {
        let gains = CompensationGains::default();
        // The tip is 4 mm too low (z down) and 2 mm north; the length is right.
        let x = Measured { tip: Setpoint::FIXED.tip + Vec3::new(0.002, 0.0, 0.004), ..at_setpoint() };
        let sp = gains.setpoint(&Setpoint::FIXED, &x);
        assert!((sp.tip - Setpoint::FIXED.tip).norm() < 1e-15, "K_PΔ = 1 sends the tip to its set-point");
        // l_pd + (z_td − z_t) = 0.7 − 0.004: shorten the cable so the load stays put.
        assert!((sp.lp - 0.696).abs() < 1e-15);
    }
}

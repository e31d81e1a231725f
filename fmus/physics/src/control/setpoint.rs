//! The desired crane state over time: tip position in the world frame and pendulum length.
//!
//! - Fixed (thesis §7.3, Table 7.6): tip {3, −502, −153} mm in W and l_p = 700 mm by default.
//! - Pick and place (Fig. 3.4; the timing of SPEC §8.4, 120 s): holds joined by quintic blends
//!   v(s) = v0 + (v1 − v0)(10s³ − 15s⁴ + 6s⁵), s = (t − t0)/(t1 − t0), which start and end with
//!   zero velocity and acceleration. The tip stays at y = −0.502 m, z = −0.153 m; x and l_p:
//!
//! ```text
//!   0– 10 s  x = +0.10, l_p = 0.70      hold
//!  10– 25 s  l_p 0.70 → 1.00            lower (pick)
//!  25– 30 s                             hold
//!  30– 45 s  l_p 1.00 → 0.70            raise
//!  45– 75 s  x +0.10 → −0.10            move
//!  75– 90 s  l_p 0.70 → 1.00            lower (place)
//!  90– 95 s                             hold
//!  95–110 s  l_p 1.00 → 0.70            raise
//! 110–120 s                             hold (and after)
//! ```

use crate::crane::plant::DEFAULT_POSE;
use crate::math::Vec3;
use serde::{Deserialize, Serialize};

/// A desired tip position (m, W) and pendulum length (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Setpoint {
    pub tip: Vec3,
    pub lp: f64,
}

impl Setpoint {
    /// The thesis' fixed set-point: tip (0.003, −0.502, −0.153) m in W, l_p = 0.700 m (the crane's
    /// default pose, [`DEFAULT_POSE`]).
    pub const FIXED: Setpoint = Setpoint { tip: Vec3::new(0.003, -0.502, -0.153), lp: DEFAULT_POSE.lp };

    /// Where the load hangs at rest below the tip: (x_t, y_t, z_t + l_p) (eqs. 5.62–5.64 at
    /// θx = θy = 0).
    pub fn load(&self) -> Vec3 {
        self.tip + Vec3::new(0.0, 0.0, self.lp)
    }
}

/// The quintic blend 10s³ − 15s⁴ + 6s⁵ of s clamped to [0, 1].
pub fn quintic(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * s * (10.0 + s * (-15.0 + 6.0 * s))
}

/// A piecewise profile through `knots` (time s, value), blended between consecutive knots and
/// held before the first and after the last.
fn blend(knots: &[(f64, f64)], t: f64) -> f64 {
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if t <= first.0 {
        return first.1;
    }
    knots
        .windows(2)
        .find(|w| t < w[1].0)
        .map_or(last.1, |w| w[0].1 + (w[1].1 - w[0].1) * quintic((t - w[0].0) / (w[1].0 - w[0].0)))
}

/// Knots of the pick-and-place tip x (m).
const PICK_AND_PLACE_X: [(f64, f64); 4] = [(0.0, 0.10), (45.0, 0.10), (75.0, -0.10), (120.0, -0.10)];
/// Knots of the pick-and-place pendulum length (m).
const PICK_AND_PLACE_LP: [(f64, f64); 10] = [
    (0.0, 0.70),
    (10.0, 0.70),
    (25.0, 1.00),
    (30.0, 1.00),
    (45.0, 0.70),
    (75.0, 0.70),
    (90.0, 1.00),
    (95.0, 1.00),
    (110.0, 0.70),
    (120.0, 0.70),
];

/// The pick-and-place set-point `t` seconds into the test (SPEC §8.4).
pub fn pick_and_place(t: f64) -> Setpoint {
    Setpoint { tip: Vec3::new(blend(&PICK_AND_PLACE_X, t), -0.502, -0.153), lp: blend(&PICK_AND_PLACE_LP, t) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::joints::{extensions_for_tip, CONTROLLER_CABLE};
    use crate::crane::motion::CRANE_BASE;
    use crate::estimation::pose::BaseFrame;
    use crate::math::Quat;

    #[test]
    fn the_quintic_starts_and_ends_at_rest() {
        assert_eq!((quintic(0.0), quintic(1.0), quintic(-1.0), quintic(2.0)), (0.0, 1.0, 0.0, 1.0));
        assert!((quintic(0.5) - 0.5).abs() < 1e-15);
        // One-sided differences inside [0, 1]: slope and curvature vanish at both ends.
        let h = 1e-4;
        for (s, dir) in [(0.0, 1.0), (1.0, -1.0)] {
            let (q0, q1, q2) = (quintic(s), quintic(s + dir * h), quintic(s + 2.0 * dir * h));
            let slope = (q1 - q0) / h;
            let curvature = (q2 - 2.0 * q1 + q0) / (h * h);
            assert!(slope.abs() < 1e-6 && curvature.abs() < 1e-2, "s = {s}: {slope}, {curvature}");
        }
    }

    #[test]
    fn the_pick_and_place_profile_follows_the_timetable() {
        let at = |t: f64| pick_and_place(t);
        assert_eq!(at(-1.0), Setpoint { tip: Vec3::new(0.10, -0.502, -0.153), lp: 0.70 });
        assert_eq!((at(10.0).lp, at(25.0).lp, at(29.9).lp, at(45.0).lp), (0.70, 1.00, 1.00, 0.70));
        assert!((at(17.5).lp - 0.85).abs() < 1e-15, "half way down");
        assert_eq!((at(45.0).tip.x, at(75.0).tip.x, at(60.0).tip.x), (0.10, -0.10, 0.0));
        assert_eq!((at(90.0).lp, at(95.0).lp, at(110.0).lp, at(130.0).lp), (1.00, 1.00, 0.70, 0.70));
        assert_eq!(at(130.0).tip, Vec3::new(-0.10, -0.502, -0.153));
        assert_eq!(at(50.0).load(), Vec3::new(at(50.0).tip.x, -0.502, -0.153 + 0.70));
    }

    #[test]
    fn the_pick_and_place_profile_stays_inside_the_workspace() {
        // Ship at rest: every instant's tip needs actuator extensions inside the 0–50 mm stroke
        // and a winch angle past its home (cable longer than its 325 mm minimum).
        let frame = BaseFrame::new(&Vec3::zeros(), &Quat::identity(), &CRANE_BASE);
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        let mut speed: f64 = 0.0;
        for k in 0..=12_000 {
            let t = k as f64 * 0.01;
            let sp = pick_and_place(t);
            let (d, limited) = extensions_for_tip(&frame, &sp.tip).unwrap_or_else(|e| panic!("t = {t}: {e}"));
            assert!(!limited, "t = {t}: set-point needs a stroke limit");
            assert!(CONTROLLER_CABLE.winch_angle(sp.lp, d[2]) > 0.0);
            for i in 0..3 {
                lo[i] = lo[i].min(d[i] * 1000.0);
                hi[i] = hi[i].max(d[i] * 1000.0);
            }
            speed = speed.max((pick_and_place(t + 0.01).lp - sp.lp).abs() / 0.01);
        }
        println!(
            "pick and place: actuators base {:.1}-{:.1} mm, boom {:.1}-{:.1} mm, jib {:.1}-{:.1} mm; peak \
                length rate {:.1} mm/s",
            lo[0],
            hi[0],
            lo[1],
            hi[1],
            lo[2],
            hi[2],
            speed * 1000.0
        );
    }
}

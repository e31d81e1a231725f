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

/// The slope d/ds of [`quintic`], 30s²(1 − s)², inside [0, 1]; zero outside, where the blend holds.
pub fn quintic_rate(s: f64) -> f64 {
    if !(0.0..=1.0).contains(&s) {
        return 0.0;
    }
    30.0 * s * s * (1.0 - s) * (1.0 - s)
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

/// The time derivative of [`blend`] at `t` (value/s): the quintic's slope over the segment's
/// duration; zero in the holds.
fn blend_rate(knots: &[(f64, f64)], t: f64) -> f64 {
    knots.windows(2).find(|w| t >= w[0].0 && t < w[1].0).map_or(0.0, |w| {
        let duration = w[1].0 - w[0].0;
        (w[1].1 - w[0].1) * quintic_rate((t - w[0].0) / duration) / duration
    })
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

/// The rates of [`pick_and_place`] at `t`: the tip's velocity (m/s, W) and l̇_p (m/s).
pub fn pick_and_place_rate(t: f64) -> Setpoint {
    Setpoint { tip: Vec3::new(blend_rate(&PICK_AND_PLACE_X, t), 0.0, 0.0), lp: blend_rate(&PICK_AND_PLACE_LP, t) }
}

/// The pick-and-place timetable's length (s): its last knot; it holds after.
pub const PICK_AND_PLACE_DURATION: f64 = PICK_AND_PLACE_LP[PICK_AND_PLACE_LP.len() - 1].0;

/// Froude similarity between the thesis' rig and a crane `length` (λ) times larger: with the
/// Froude number v²/(g·l) kept, lengths scale by λ, times by √λ and velocities by √λ — the
/// gravity pendulum's period 2π√(l/g) (the linearised swing of thesis eqs. 4.141–4.142) scales by
/// √λ, so a profile timed by √λ excites the larger load as the test-scale one does its own.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Froude {
    /// λ, full-scale length per test-scale length.
    pub length: f64,
}

impl Froude {
    /// √λ, full-scale time per test-scale time.
    pub fn time(&self) -> f64 {
        self.length.sqrt()
    }

    /// [`pick_and_place`] at this scale, `t` seconds into the scaled test: the test-scale
    /// set-point at t/√λ, its lengths ×λ.
    pub fn pick_and_place(&self, t: f64) -> Setpoint {
        let s = pick_and_place(t / self.time());
        Setpoint { tip: s.tip * self.length, lp: s.lp * self.length }
    }

    /// The rates of [`Froude::pick_and_place`] (m/s): the test scale's at t/√λ, ×λ/√λ = ×√λ.
    pub fn pick_and_place_rate(&self, t: f64) -> Setpoint {
        let r = pick_and_place_rate(t / self.time());
        let velocity = self.length / self.time();
        Setpoint { tip: r.tip * velocity, lp: r.lp * velocity }
    }

    /// The scaled timetable's length (s).
    pub fn pick_and_place_duration(&self) -> f64 {
        PICK_AND_PLACE_DURATION * self.time()
    }
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
    fn froude_scaling_puts_the_knots_at_25_times_the_lengths_and_5_times_the_times() {
        let full = Froude { length: 25.0 };
        assert_eq!((full.time(), full.pick_and_place_duration()), (5.0, 600.0));
        for (t, x) in PICK_AND_PLACE_X {
            let (sp, rate) = (full.pick_and_place(5.0 * t), full.pick_and_place_rate(5.0 * t));
            assert!((sp.tip.x - 25.0 * x).abs() < 1e-12 && rate.tip.x == 0.0, "x knot at {t} s: {sp:?}, {rate:?}");
            assert!((sp.tip - Vec3::new(25.0 * x, -12.55, -3.825)).norm() < 1e-12, "{sp:?}");
        }
        for (t, lp) in PICK_AND_PLACE_LP {
            let (sp, rate) = (full.pick_and_place(5.0 * t), full.pick_and_place_rate(5.0 * t));
            assert!((sp.lp - 25.0 * lp).abs() < 1e-12 && rate.lp == 0.0, "l_p knot at {t} s: {sp:?}, {rate:?}");
        }
    }

    #[test]
    fn the_scaled_rates_are_the_profiles_slope_and_peak_at_the_quintics_1_875_times_the_mean() {
        let full = Froude { length: 25.0 };
        // The lowering 10–25 s → 50–125 s: 7.5 m in 75 s, peak 1.875 · 0.1 m/s half way.
        let peak = full.pick_and_place_rate(87.5).lp;
        assert!((peak - 1.875 * 7.5 / 75.0).abs() < 1e-15, "{peak}");
        // The move 45–75 s → 225–375 s: 5 m towards −x in 150 s.
        let peak = full.pick_and_place_rate(300.0).tip.x;
        assert!((peak + 1.875 * 5.0 / 150.0).abs() < 1e-15, "{peak}");
        // No faster anywhere, and the rate is the profile's slope (central differences).
        let h = 1e-3;
        let (mut fastest_rope, mut fastest_tip): (f64, f64) = (0.0, 0.0);
        for k in 0..=6000 {
            let t = k as f64 * 0.1;
            let rate = full.pick_and_place_rate(t);
            let (before, after) = (full.pick_and_place(t - h), full.pick_and_place(t + h));
            assert!((rate.lp - (after.lp - before.lp) / (2.0 * h)).abs() < 1e-6, "t = {t}");
            assert!((rate.tip.x - (after.tip.x - before.tip.x) / (2.0 * h)).abs() < 1e-6, "t = {t}");
            fastest_rope = fastest_rope.max(rate.lp.abs());
            fastest_tip = fastest_tip.max(rate.tip.x.abs());
        }
        println!("full-scale pick and place: peak rope speed {fastest_rope:.4} m/s, tip {fastest_tip:.4} m/s");
        assert!(fastest_rope <= 0.1875 + 1e-15 && fastest_tip <= 0.0625 + 1e-15);
        // At λ = 1 the scaling is the identity.
        let unit = Froude { length: 1.0 };
        assert_eq!(
            (unit.pick_and_place(17.5), unit.pick_and_place_rate(17.5)),
            (pick_and_place(17.5), pick_and_place_rate(17.5))
        );
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

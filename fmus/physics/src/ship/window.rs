//! When the deck starts moving: rest until a start time, then a smooth fade-in of the motion.
//!
//! The thesis' tests start the ship motion with a trigger after 10 s of recording that let the
//! estimators initialise (§7.3; the trigger, §3.6): the deck is at rest until then. Switching a
//! moving source on at once would step the deck's velocity and acceleration and swing the pendulum
//! for reasons that have nothing to do with the sea, so the motion is instead multiplied by a
//! weight that rises from 0 to 1 with zero first and second derivatives at both ends: the quintic
//! that Perlin introduced as the C² successor of the cubic 3s² − 2s³ (K. Perlin, "Improving
//! noise", *ACM Transactions on Graphics* 21(3), 2002), known as "smootherstep"
//!
//! ```text
//! s = (t − t_start)/T_fade,   w(s) = 10 s³ − 15 s⁴ + 6 s⁵,
//! w'(s) = 30 s² (1 − s)²,     w''(s) = 60 s (1 − s)(1 − 2 s),
//! ```
//!
//! and, per degree of freedom, the weighted motion y = w x keeps position, velocity and
//! acceleration exactly consistent by the product rule, with ẇ = w'(s)/T_fade and
//! ẅ = w''(s)/T_fade² (chain rule through s):
//!
//! ```text
//! y = w x,   ẏ = w ẋ + ẇ x,   ÿ = w ẍ + 2 ẇ ẋ + ẅ x.
//! ```
//!
//! The rest pose is the zero pose: profiles 1–4 are zero-mean (1–3 are centred on their mean over
//! the 120 s test window of profile time), so the deck fades in about its mean pose. A motion file
//! is faded from zero to its own values.

use super::source::MotionSource;
use crate::motion::{AxisMotion, DeckMotion};
use serde::{Deserialize, Serialize};

/// The start time and fade-in of the deck motion (the platform's `motion_start` and `fade_in`).
///
/// The default (0, 0) moves from t = 0 with profile time equal to simulation time, i.e. what the
/// source gives without a window, for every t ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MotionWindow {
    /// Simulation time (s) before which the deck rests at the zero pose, and at which profile
    /// time 0 falls (before any `time_offset`).
    pub start: f64,
    /// Duration (s, ≥ 0) of the fade-in after `start`; 0 switches the motion on at `start` at once
    /// (a step in position, velocity and acceleration unless the source is at rest there).
    pub fade_in: f64,
}

default_is_const!(MotionWindow);

impl MotionWindow {
    /// Moving from t = 0 without a fade-in.
    pub const DEFAULT: MotionWindow = MotionWindow { start: 0.0, fade_in: 0.0 };

    /// Rejects a non-finite start and a negative or non-finite fade-in (NaN included).
    pub fn validate(&self) -> Result<(), String> {
        if !self.start.is_finite() {
            return Err(format!("motion_start must be finite, got {}", self.start));
        }
        if !(self.fade_in >= 0.0 && self.fade_in.is_finite()) {
            return Err(format!("fade_in must be finite and >= 0, got {}", self.fade_in));
        }
        Ok(())
    }

    /// The source's own time (s) at simulation time `t` (s): τ = t − start + `time_offset`.
    pub fn profile_time(&self, t: f64, time_offset: f64) -> f64 {
        (t - self.start) + time_offset
    }

    /// The weight at simulation time `t` (s) with its first and second time derivatives: `pos` w
    /// (1), `vel` ẇ (1/s), `acc` ẅ (1/s²). Exactly (0, 0, 0) up to and including `start` when
    /// fading (before `start` without), exactly (1, 0, 0) from `start + fade_in` on.
    pub fn weight(&self, t: f64) -> AxisMotion {
        const OFF: AxisMotion = AxisMotion { pos: 0.0, vel: 0.0, acc: 0.0 };
        const ON: AxisMotion = AxisMotion { pos: 1.0, vel: 0.0, acc: 0.0 };
        if t < self.start {
            return OFF;
        }
        if t >= self.start + self.fade_in {
            return ON;
        }
        let s = (t - self.start) / self.fade_in;
        let u = 1.0 - s;
        AxisMotion {
            pos: s * s * s * (10.0 - 15.0 * s + 6.0 * s * s),
            vel: 30.0 * s * s * u * u / self.fade_in,
            acc: 60.0 * s * u * (1.0 - 2.0 * s) / (self.fade_in * self.fade_in),
        }
    }

    /// `motion` (the source sampled at [`profile_time`](Self::profile_time)) weighted for
    /// simulation time `t` (s): every degree of freedom by the product rule above. Returned
    /// unchanged (bit for bit) once the fade is over, exactly zero before it begins.
    pub fn apply(&self, t: f64, motion: &DeckMotion) -> DeckMotion {
        let w = self.weight(t);
        if w.pos == 1.0 && w.vel == 0.0 && w.acc == 0.0 {
            return *motion;
        }
        if w.pos == 0.0 && w.vel == 0.0 && w.acc == 0.0 {
            return DeckMotion::default();
        }
        DeckMotion { dof: motion.dof.map(|x| product(w, x)) }
    }

    /// The deck motion at simulation time `t` (s): `source` at τ = t − start + `time_offset`,
    /// weighted. The source is not sampled while the deck rests.
    pub fn sample(&self, source: &mut MotionSource, t: f64, time_offset: f64) -> DeckMotion {
        if t < self.start {
            return DeckMotion::default();
        }
        self.apply(t, &source.sample(self.profile_time(t, time_offset)))
    }
}

/// w x with its first and second time derivatives (product rule).
fn product(w: AxisMotion, x: AxisMotion) -> AxisMotion {
    AxisMotion {
        pos: w.pos * x.pos,
        vel: w.pos * x.vel + w.vel * x.pos,
        acc: w.pos * x.acc + 2.0 * w.vel * x.vel + w.acc * x.pos,
    }
}

#[cfg(test)]
mod tests;

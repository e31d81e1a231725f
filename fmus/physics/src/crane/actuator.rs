//! The actuator and winch plant (thesis §3.4.3, §3.5.3, Table 3.2, eqs. 3.5–3.8).
//!
//! A command goes through the steps of §3.5.3:
//! 1. saturation to the hardware range (0–3.3 V, or duty 0–1) and removal of the neutral value
//!    (1.65 V, or 0.5);
//! 2. the deadband of Table 3.2: inside [lower, upper] the linearised input is zero, outside the
//!    crossed bound is subtracted;
//! 3. the identified transfer function G(s) = K/(s(s + a)) from the linearised input to the
//!    position, i.e. ẍ = −a ẋ + K u;
//! 4. the offset by the initial position (the state starts there);
//! 5. saturation of the position to the stroke, 0–50 mm, which stops the state there with zero
//!    velocity; the winch has no stroke and turns freely.
//!
//! Units are the thesis' (the gains are identified in them): linear actuators in mm, mm/s and V
//! (K in mm/(V·s²)); the winch in degrees and duty (K in deg/s² per unit duty — eq. 3.8 labels it
//! "per % duty cycle", but its linearised input range ±0.17 is in unit duty).
//!
//! Integration is exact for an input held over the step (zero-order hold): the double integrator
//! with a pole has the closed-form solution used by [`Actuator::advance`]; a stroke end reached
//! inside the step is located exactly and the motion continues from rest there.

use serde::{Deserialize, Serialize};

/// The asymmetric input deadband relative to the neutral input (Table 3.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Deadband {
    /// Lower bound (≤ 0), in the input's unit.
    pub lower: f64,
    /// Upper bound (≥ 0), in the input's unit.
    pub upper: f64,
}

impl Deadband {
    /// Step 2: zero inside [lower, upper]; outside, the input less the crossed bound.
    pub fn apply(&self, u: f64) -> f64 {
        if u > self.upper {
            u - self.upper
        } else if u < self.lower {
            u - self.lower
        } else {
            0.0
        }
    }
}

/// G(s) = K / (s (s + a)): position output for the linearised input.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TransferFunction {
    /// K (position unit per input unit per s²).
    pub gain: f64,
    /// a (1/s), > 0: the velocity's time constant is 1/a and its steady value K/a per unit input.
    pub pole: f64,
}

/// Position and velocity of one actuator (mm and mm/s, or deg and deg/s for the winch).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AxisState {
    pub pos: f64,
    pub vel: f64,
}

/// One actuator: command conditioning, transfer function and stroke (config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Actuator {
    /// Hardware command range (V, or duty).
    pub input_min: f64,
    pub input_max: f64,
    /// Neutral (stationary) command.
    pub neutral: f64,
    pub deadband: Deadband,
    pub plant: TransferFunction,
    /// Position limits (mm); `None` for the winch.
    pub stroke: Option<(f64, f64)>,
}

/// Command range and neutral of the linear actuators (V).
const VOLTS: (f64, f64, f64) = (0.0, 3.3, 1.65);
/// Stroke of the linear actuators (mm).
const STROKE_MM: Option<(f64, f64)> = Some((0.0, 50.0));

impl Actuator {
    /// Base actuator: deadband −0.145/+0.145 V, G = 185.6/(s(s + 13.8)) mm/V (eq. 3.5).
    pub const BASE: Actuator = Actuator::linear(-0.145, 0.145, 185.6, 13.8);
    /// Boom actuator: deadband −0.145/+0.525 V, G = 458/(s(s + 31.61)) mm/V (eq. 3.6).
    pub const BOOM: Actuator = Actuator::linear(-0.145, 0.525, 458.0, 31.61);
    /// Jib actuator: deadband −0.145/+0.175 V, G = 640.09/(s(s + 48.32)) mm/V (eq. 3.7).
    pub const JIB: Actuator = Actuator::linear(-0.145, 0.175, 640.09, 48.32);
    /// Winch motor: duty 0–1, neutral 0.5, deadband −0.0165/0, G = 37928/(s(s + 24.43)) deg per
    /// unit duty (eq. 3.8), no stroke.
    pub const WINCH: Actuator = Actuator {
        input_min: 0.0,
        input_max: 1.0,
        neutral: 0.5,
        deadband: Deadband { lower: -0.0165, upper: 0.0 },
        plant: TransferFunction { gain: 37928.0, pole: 24.43 },
        stroke: None,
    };

    const fn linear(lower: f64, upper: f64, gain: f64, pole: f64) -> Actuator {
        Actuator {
            input_min: VOLTS.0,
            input_max: VOLTS.1,
            neutral: VOLTS.2,
            deadband: Deadband { lower, upper },
            plant: TransferFunction { gain, pole },
            stroke: STROKE_MM,
        }
    }

    pub fn validate(&self) -> Result<(), String> {
        let Deadband { lower, upper } = self.deadband;
        if !(lower <= 0.0 && upper >= 0.0) {
            return Err(format!("deadband [{lower}, {upper}] must contain 0"));
        }
        if !(self.plant.pole > 0.0 && self.plant.gain.is_finite()) {
            return Err(format!(
                "transfer function K = {}, a = {} needs a finite K and a > 0",
                self.plant.gain, self.plant.pole
            ));
        }
        if !(self.input_min < self.input_max && (self.input_min..=self.input_max).contains(&self.neutral)) {
            return Err(format!(
                "input range [{}, {}] must be ordered and contain the neutral {}",
                self.input_min, self.input_max, self.neutral
            ));
        }
        Ok(())
    }

    /// Steps 1–2: the linearised input to the transfer function for the hardware command `u`.
    pub fn linearise(&self, u: f64) -> f64 {
        self.deadband.apply(u.clamp(self.input_min, self.input_max) - self.neutral)
    }

    /// The acceleration the transfer function demands for command `u`, K·u_lin (unit/s²).
    fn drive(&self, u: f64) -> f64 {
        self.plant.gain * self.linearise(u)
    }

    /// Whether the state rests against a stroke end that the drive `c` pushes into.
    fn held(&self, s: &AxisState, c: f64) -> bool {
        match self.stroke {
            Some((lo, hi)) => s.vel == 0.0 && ((s.pos >= hi && c >= 0.0) || (s.pos <= lo && c <= 0.0)),
            None => false,
        }
    }

    /// Acceleration (unit/s²) in state `s` under command `u`: ẍ = −a ẋ + K u_lin, or 0 while the
    /// actuator rests against a stroke end.
    pub fn acceleration(&self, s: &AxisState, u: f64) -> f64 {
        let c = self.drive(u);
        if self.held(s, c) {
            0.0
        } else {
            -self.plant.pole * s.vel + c
        }
    }

    /// This plant's [`Propagator`] over `tau` seconds.
    pub fn propagator(&self, tau: f64) -> Propagator {
        Propagator::new(self.plant.pole, tau)
    }

    /// Advances the state by `h` seconds with the command `u` held (exact zero-order-hold
    /// solution; steps 3–5).
    pub fn advance(&self, s: &AxisState, u: f64, h: f64) -> AxisState {
        self.advance_with(s, u, &self.propagator(h))
    }

    /// [`Actuator::advance`] over `step.tau` seconds, given this plant's propagator over that
    /// span (which a model stepping with a fixed h computes once).
    pub fn advance_with(&self, s: &AxisState, u: f64, step: &Propagator) -> AxisState {
        let c = self.drive(u);
        let Some((lo, hi)) = self.stroke else {
            return step.motion(s, c);
        };
        let mut state = *s;
        let mut left = *step;
        // Each pass either finishes the step or stops at a stroke end and restarts from rest
        // there; from rest the motion is monotonic, so it can reach at most the other end.
        for _ in 0..4 {
            if self.held(&state, c) {
                return AxisState { pos: state.pos.clamp(lo, hi), vel: 0.0 };
            }
            match first_exit(self.plant.pole, &state, c, &left, lo, hi) {
                None => return left.motion(&state, c),
                Some((tau, bound)) => {
                    state = AxisState { pos: bound, vel: 0.0 };
                    left = self.propagator(left.tau - tau);
                }
            }
        }
        state
    }
}

/// The exact solution of ẍ = −a ẋ + c over a span of τ seconds, reduced to its three
/// coefficients e^(−aτ), φ1(τ) and φ2(τ): they depend on a and τ only, not on the state or the
/// drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Propagator {
    /// The span τ (s).
    pub tau: f64,
    decay: f64,
    phi1: f64,
    phi2: f64,
}

impl Propagator {
    /// The propagator of the pole `a` (1/s) over `tau` seconds.
    pub fn new(a: f64, tau: f64) -> Propagator {
        Propagator { tau, decay: (-a * tau).exp(), phi1: phi1(a, tau), phi2: phi2(a, tau) }
    }

    /// The state τ seconds after `s` under the constant drive `c`.
    fn motion(&self, s: &AxisState, c: f64) -> AxisState {
        AxisState { pos: s.pos + s.vel * self.phi1 + c * self.phi2, vel: s.vel * self.decay + c * self.phi1 }
    }
}

/// φ1(τ) = (1 − e^(−aτ))/a: the position gained per unit initial velocity.
fn phi1(a: f64, tau: f64) -> f64 {
    -(-a * tau).exp_m1() / a
}

/// φ2(τ) = (τ − φ1(τ))/a: the position gained per unit constant drive K·u, by its series
/// τ² Σ (−aτ)ⁿ/(n + 2)! where the difference would cancel.
fn phi2(a: f64, tau: f64) -> f64 {
    let x = a * tau;
    if x < 0.5 {
        let (mut term, mut sum) = (0.5, 0.5);
        for n in 1..20 {
            term *= -x / (n as f64 + 2.0);
            sum += term;
        }
        tau * tau * sum
    } else {
        (tau - phi1(a, tau)) / a
    }
}

/// The first time in (0, `whole.tau`] at which the free motion leaves [lo, hi], and the bound
/// it crosses. The velocity relaxes monotonically toward c/a, so the position has at most one
/// turning point; on either side of it the position is monotonic and the crossing is found by
/// bisection to the last bit. `whole` is the propagator over the whole span: the end position,
/// the only one a step that stays inside needs, comes from it.
fn first_exit(a: f64, s: &AxisState, c: f64, whole: &Propagator, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let span = whole.tau;
    let pos = |tau: f64| if tau == span { whole.motion(s, c).pos } else { Propagator::new(a, tau).motion(s, c).pos };
    let outside = |x: f64| {
        if x > hi {
            Some(hi)
        } else if x < lo {
            Some(lo)
        } else {
            None
        }
    };
    // Turning point: v(τ) = 0 ⇔ e^(−aτ) = c / (c − a v0).
    let turn = {
        let ratio = c / (c - a * s.vel);
        (ratio > 0.0 && ratio < 1.0).then(|| -ratio.ln() / a).filter(|t| *t < span)
    };
    let segments = match turn {
        Some(t) => [(0.0, t), (t, span)],
        None => [(0.0, span), (span, span)],
    };
    for (start, end) in segments {
        if end <= start {
            continue;
        }
        if let Some(bound) = outside(pos(end)) {
            let (mut inside, mut out) = (start, end);
            while out - inside > f64::EPSILON * span.max(f64::MIN_POSITIVE) {
                let mid = 0.5 * (inside + out);
                if mid <= inside || mid >= out {
                    break;
                }
                if outside(pos(mid)).is_some() {
                    out = mid;
                } else {
                    inside = mid;
                }
            }
            return Some((out, bound));
        }
    }
    None
}

#[cfg(test)]
mod tests;

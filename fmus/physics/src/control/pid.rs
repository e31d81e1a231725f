//! The discrete joint controller of thesis §6.1 (eqs. 6.1–6.11, Fig. 6.1, Table 6.1).
//!
//! At each sample k, with reference r_k and measurement y_k:
//!
//! ```text
//! y'_k   = r_k if |r_k − y_k| < e_db, else y_k                      (6.10)
//! e_k    = r_k − y'_k                                               (6.2)
//! u_p,k  = K_p e_k                                                  (6.6)
//! u_i,k  = u_aw,k−1 + K_i Δt (e_k + e_k−1)/2                        (6.7)
//! u_aw,k−1 = sat(u_p,k−1 + u_i,k−1) − u_p,k−1, limited to [0, u_i,k−1]  (6.9)
//! u_d,k  = −K_d (y'_k − y'_k−1)/Δt                                  (6.8)
//! u_k    = u_p,k + u_i,k + u_d,k                                    (6.5)
//! sat(u) = u clamped to [u_sat,ll, u_sat,ul]                        (6.4)
//! u'_k   = sat(u_k) + u_db,ul   if sat(u_k) ≥ u_db
//!          0                    if −u_db < sat(u_k) < u_db
//!          sat(u_k) + u_db,ll   if sat(u_k) ≤ −u_db                 (6.11)
//! ```
//!
//! and the hardware command is the neutral value plus u'_k (1.65 V for the linear actuators, duty
//! 0.5 for the winch). At the first sample u_i,0 = u_d,0 = 0: only the proportional action acts.
//!
//! Units follow the myRIO (§6.1): the linear actuators' references and measurements are
//! extensions in mm and their commands volts; the winch's are angles in degrees and PWM duty.

use serde::{Deserialize, Serialize};

/// Gains, limits and deadbands of one joint controller (Table 6.1; config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PidParams {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    /// Error deadband e_db (mm or deg), eq. 6.10.
    pub error_deadband: f64,
    /// Saturation limits u_sat,ll and u_sat,ul (V or duty, relative to neutral), eq. 6.4.
    pub sat_lower: f64,
    pub sat_upper: f64,
    /// Actuator deadband u_db,ll and u_db,ul to jump (V or duty), eq. 6.11.
    pub deadband_lower: f64,
    pub deadband_upper: f64,
    /// Minimum action u_db for a jump (V or duty), eq. 6.11.
    pub jump_threshold: f64,
    /// Neutral (stationary) hardware command added to the action (V or duty).
    pub neutral: f64,
}

impl PidParams {
    /// LA1 (base): K_p = 0.6 V/mm, e_db = 0.25 mm, sat ±1.505 V, deadband −0.145/+0.145 V,
    /// u_db = 0.005 V.
    pub const BASE: PidParams = PidParams::linear(0.6, -1.505, 1.505, -0.145, 0.145);
    /// LA2 (boom): K_p = 0.45 V/mm, sat −1.505/+1.125 V, deadband −0.145/+0.525 V.
    pub const BOOM: PidParams = PidParams::linear(0.45, -1.505, 1.125, -0.145, 0.525);
    /// LA3 (jib): K_p = 0.59 V/mm, sat −1.505/+1.475 V, deadband −0.145/+0.175 V.
    pub const JIB: PidParams = PidParams::linear(0.59, -1.505, 1.475, -0.145, 0.175);
    /// Winch: K_p = 0.015, K_i = 0.2, K_d = 0.00075 (duty per deg, deg·s, deg/s), e_db = 0.25°,
    /// sat −0.1535/+0.17, deadband −0.0165/0, u_db = 0.0035, neutral duty 0.5.
    pub const WINCH: PidParams = PidParams {
        kp: 0.015,
        ki: 0.2,
        kd: 0.00075,
        error_deadband: 0.25,
        sat_lower: -0.1535,
        sat_upper: 0.17,
        deadband_lower: -0.0165,
        deadband_upper: 0.0,
        jump_threshold: 0.0035,
        neutral: 0.5,
    };

    /// A linear actuator of Table 6.1: P only, e_db = 0.25 mm, u_db = 0.005 V, neutral 1.65 V.
    const fn linear(kp: f64, sat_lower: f64, sat_upper: f64, deadband_lower: f64, deadband_upper: f64) -> PidParams {
        PidParams {
            kp,
            ki: 0.0,
            kd: 0.0,
            error_deadband: 0.25,
            sat_lower,
            sat_upper,
            deadband_lower,
            deadband_upper,
            jump_threshold: 0.005,
            neutral: 1.65,
        }
    }

    pub fn validate(&self) -> Result<(), String> {
        let all = [
            self.kp,
            self.ki,
            self.kd,
            self.error_deadband,
            self.sat_lower,
            self.sat_upper,
            self.deadband_lower,
            self.deadband_upper,
            self.jump_threshold,
            self.neutral,
        ];
        if !all.iter().all(|v| v.is_finite()) {
            return Err("PID parameters must be finite".into());
        }
        if !(self.sat_lower <= 0.0 && self.sat_upper >= 0.0) {
            return Err(format!("saturation limits must bracket 0, got {} and {}", self.sat_lower, self.sat_upper));
        }
        if !(self.deadband_lower <= 0.0 && self.deadband_upper >= 0.0) {
            return Err(format!(
                "deadband limits must bracket 0, got {} and {}",
                self.deadband_lower, self.deadband_upper
            ));
        }
        if !(self.error_deadband >= 0.0 && self.jump_threshold >= 0.0) {
            return Err("deadbands must be ≥ 0".into());
        }
        Ok(())
    }

    /// Saturation, eq. 6.4.
    pub fn saturate(&self, u: f64) -> f64 {
        u.clamp(self.sat_lower, self.sat_upper)
    }

    /// The anti-windup term u_aw,k−1 of eq. 6.9 from the previous sample's proportional and
    /// integral actions: the integral less the amount by which the PI action exceeded the
    /// saturation, sat(u_p + u_i) − u_p, but never past zero. The printed form alone also
    /// covers the case where the proportional action by itself saturates; it then sets
    /// u_i = sat − u_p, an integral of the opposite sign that, with K_i = 0 (the linear actuators),
    /// is never integrated away and leaves a permanent offset. Limited to [0, u_i] the term does
    /// what §6.1 says it is for: it reduces the integral action, and equals eq. 6.9 whenever the
    /// proportional action alone is within the limits.
    pub fn anti_windup(&self, proportional: f64, integral: f64) -> f64 {
        let excess = proportional + integral - self.saturate(proportional + integral);
        if excess > 0.0 {
            (integral - excess).max(integral.min(0.0))
        } else if excess < 0.0 {
            (integral - excess).min(integral.max(0.0))
        } else {
            integral
        }
    }

    /// The deadband jump of eq. 6.11 applied to a saturated action.
    pub fn jump(&self, u_sat: f64) -> f64 {
        if u_sat >= self.jump_threshold {
            u_sat + self.deadband_upper
        } else if u_sat <= -self.jump_threshold {
            u_sat + self.deadband_lower
        } else {
            0.0
        }
    }
}

/// What the controller remembers from the previous sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Memory {
    error: f64,
    measurement: f64,
    proportional: f64,
    integral: f64,
}

/// The parts of one sample's action.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PidOutput {
    /// Error e_k after the error deadband.
    pub error: f64,
    /// u_p,k, u_i,k, u_d,k.
    pub proportional: f64,
    pub integral: f64,
    pub derivative: f64,
    /// sat(u_k), eq. 6.4.
    pub saturated: f64,
    /// u'_k, eq. 6.11.
    pub action: f64,
    /// The hardware command: neutral + u'_k.
    pub command: f64,
}

/// One joint controller with its state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pid {
    pub params: PidParams,
    memory: Option<Memory>,
}

impl Pid {
    pub fn new(params: PidParams) -> Self {
        Pid { params, memory: None }
    }

    /// Forgets the past: the next sample is handled as k = 0.
    pub fn reset(&mut self) {
        self.memory = None;
    }

    /// One sample: reference `r`, measurement `y`, sample period `dt` (s).
    pub fn step(&mut self, r: f64, y: f64, dt: f64) -> PidOutput {
        let p = &self.params;
        let y = if (r - y).abs() < p.error_deadband { r } else { y };
        let error = r - y;
        let proportional = p.kp * error;
        let (integral, derivative) = match self.memory {
            None => (0.0, 0.0),
            Some(m) => (
                p.anti_windup(m.proportional, m.integral) + p.ki * dt * 0.5 * (error + m.error),
                -p.kd * (y - m.measurement) / dt,
            ),
        };
        self.memory = Some(Memory { error, measurement: y, proportional, integral });
        let saturated = p.saturate(proportional + integral + derivative);
        let action = p.jump(saturated);
        PidOutput { error, proportional, integral, derivative, saturated, action, command: p.neutral + action }
    }
}

#[cfg(test)]
mod tests;

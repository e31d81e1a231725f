//! A test rig: one vertical valve–cylinder–mass drive lifting a mass against gravity, integrated
//! with RK4 at fixed substeps, with energy accumulators for the power balance (H12).
//!
//! Mechanics (Newton's second law on the rod, x up): m·dv/dt = F − m·g + F_ext, F from H7.

use super::cylinder::CylinderDrive;
use super::drive::{DriveRates, DriveState};
use super::oil::{Oil, Supply};
use crate::integrate::rk4;
use crate::math::STANDARD_GRAVITY;
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// The rig's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Rig {
    pub drive: CylinderDrive,
    pub oil: Oil,
    pub supply: Supply,
    /// Moving mass on the rod (kg). 1e5 kg: a boom's equivalent mass at the rod, p_A ≈ 8 MPa.
    pub mass: f64,
    /// g (m/s²), against extension.
    pub gravity: f64,
    /// Constant external force on the rod, positive extending (N).
    pub external_force: f64,
    /// RK4 substep (s). 1 ms, the crane FMU's largest substep.
    pub substep: f64,
}

impl Rig {
    pub const DEFAULT: Rig = Rig {
        drive: CylinderDrive::DEFAULT,
        oil: Oil::DEFAULT,
        supply: Supply::DEFAULT,
        mass: 1e5,
        gravity: STANDARD_GRAVITY,
        external_force: 0.0,
        substep: 1e-3,
    };

    pub fn validate(&self) -> Result<(), String> {
        self.oil.validate()?;
        self.drive.validate(&self.supply)?;
        if !(self.mass > 0.0 && self.mass.is_finite()) {
            return Err(format!("rig mass must be a finite value > 0 kg, got {}", self.mass));
        }
        if !(self.gravity.is_finite() && self.external_force.is_finite()) {
            return Err(format!(
                "rig gravity ({}) and external_force ({}) must be finite",
                self.gravity, self.external_force
            ));
        }
        if !(self.substep > 0.0 && self.substep <= 0.1) {
            return Err(format!("rig substep must be in (0, 0.1] s, got {}", self.substep));
        }
        Ok(())
    }

    /// The rod force that holds the load at rest (N): m·g − F_ext.
    pub fn load_force(&self) -> f64 {
        self.mass * self.gravity - self.external_force
    }

    /// A state at rest at stroke x with p_B given and p_A from static equilibrium.
    pub fn holding_state(&self, x: f64, p_b: f64) -> DriveState {
        let (p_a, p_b) = self.drive.holding_pressures(self.load_force(), p_b);
        DriveState { pos: x, vel: 0.0, p_a, p_b, pilot: p_b }
    }

    /// Mechanical energy ½·m·v² + m·g·x (J, datum x = 0).
    pub fn mechanical_energy(&self, s: &DriveState) -> f64 {
        0.5 * self.mass * s.vel * s.vel + self.mass * self.gravity * s.pos
    }

    fn derivative(&self, spool: f64, y: &SVector<f64, 11>) -> SVector<f64, 11> {
        let s = state_of(y);
        let r = self.drive.rates(&self.oil, &self.supply, spool, &s);
        let stop = self.drive.cylinder.stop_force(s.pos, s.vel);
        let accel = (r.force - self.mass * self.gravity + self.external_force) / self.mass;
        SVector::<f64, 11>::from([
            s.vel,
            accel,
            r.dp_a,
            r.dp_b,
            r.power_in,
            r.throttle_loss,
            r.friction_loss,
            r.compression_power,
            self.external_force * s.vel,
            stop * s.vel,
            r.dpilot,
        ])
    }

    /// Integrates from `initial` over `duration` (s) under the spool program, recording every
    /// `record_every`-th substep (and the start).
    pub fn simulate(
        &self,
        program: &SpoolProgram,
        initial: DriveState,
        duration: f64,
        record_every: usize,
    ) -> Result<Vec<Sample>, String> {
        self.validate()?;
        if !(duration >= 0.0 && duration.is_finite()) {
            return Err(format!("rig duration must be a finite value ≥ 0 s, got {duration}"));
        }
        let steps = (duration / self.substep).round() as usize;
        let every = record_every.max(1);
        let mut y = SVector::<f64, 11>::zeros();
        (y[0], y[1], y[2], y[3], y[10]) = (initial.pos, initial.vel, initial.p_a, initial.p_b, initial.pilot);
        let mut samples = Vec::with_capacity(steps / every + 2);
        samples.push(self.sample(program, 0.0, &y));
        for i in 0..steps {
            let t = i as f64 * self.substep;
            y = rk4(&y, t, self.substep, |t, y| self.derivative(program.at(t), y));
            if (i + 1) % every == 0 || i + 1 == steps {
                samples.push(self.sample(program, (i + 1) as f64 * self.substep, &y));
            }
        }
        Ok(samples)
    }

    fn sample(&self, program: &SpoolProgram, t: f64, y: &SVector<f64, 11>) -> Sample {
        let state = state_of(y);
        let spool = program.at(t);
        let energy = RigEnergy {
            mechanical: self.mechanical_energy(&state),
            stored: self.drive.stored_energy(&self.oil, &state),
            pump: y[4],
            throttling: y[5],
            friction: y[6],
            compression: y[7],
            external: y[8],
            stops: y[9],
        };
        Sample { t, state, spool, rates: self.drive.rates(&self.oil, &self.supply, spool, &state), energy }
    }
}

/// The drive's state in the rig's vector: [x, v, p_A, p_B, six energy integrals, π].
fn state_of(y: &SVector<f64, 11>) -> DriveState {
    DriveState { pos: y[0], vel: y[1], p_a: y[2], p_b: y[3], pilot: y[10] }
}

default_is_const!(Rig);

/// Energies at one instant (J); all but `mechanical` and `stored` are integrals from the start.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RigEnergy {
    /// ½·m·v² + m·g·x.
    pub mechanical: f64,
    /// H10 over both chambers.
    pub stored: f64,
    /// ∫(p_S·Q_S − p_T·Q_T) dt.
    pub pump: f64,
    /// ∫ throttling losses dt.
    pub throttling: f64,
    /// ∫ friction losses dt.
    pub friction: f64,
    /// ∫ Σ p·(Q_net − dV/dt) dt: work done compressing the oil.
    pub compression: f64,
    /// ∫ F_ext·v dt: work of the external force on the mass.
    pub external: f64,
    /// ∫ F_stop·v dt: work of the end stops on the mass.
    pub stops: f64,
}

/// One recorded instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    pub t: f64,
    pub state: DriveState,
    pub spool: f64,
    pub rates: DriveRates,
    pub energy: RigEnergy,
}

/// A spool command u(t): linear between breakpoints (t_i, u_i), held before the first and after
/// the last; two breakpoints at one time make a step (the later one applies from that time on).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SpoolProgram {
    points: Vec<(f64, f64)>,
}

impl SpoolProgram {
    /// Breakpoints [t (s), u]; times must be finite and non-decreasing, commands finite.
    pub fn new(points: &[[f64; 2]]) -> Result<Self, String> {
        for (i, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(format!("spool program point {i} must be finite, got {:?}", p));
            }
        }
        if let Some(i) = points.windows(2).position(|w| w[1][0] < w[0][0]) {
            return Err(format!("spool program times must not decrease: point {} at {} s", i + 1, points[i + 1][0]));
        }
        Ok(SpoolProgram { points: points.iter().map(|p| (p[0], p[1])).collect() })
    }

    /// u(t).
    pub fn at(&self, t: f64) -> f64 {
        let after = self.points.partition_point(|p| p.0 <= t);
        match (after.checked_sub(1).and_then(|i| self.points.get(i)), self.points.get(after)) {
            (Some(&(t0, u0)), Some(&(t1, u1))) => u0 + (u1 - u0) * (t - t0) / (t1 - t0),
            (Some(&(_, u)), None) | (None, Some(&(_, u))) => u,
            (None, None) => 0.0,
        }
    }
}

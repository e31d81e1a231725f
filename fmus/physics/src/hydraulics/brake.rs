//! The spring-applied, hydraulically released brake of a winch or slew drive (H18).
//!
//! Winch and slew drives carry a multi-disc brake that springs close and is held open by the
//! drive's pressure (a "fail-safe" or negative brake; DNV-ST-0378 asks for one on every hoist and
//! slew): it holds the load whenever the drive's command is centred, so a centred valve no
//! longer lets the load creep down through the motor's internal leakage.
//!
//! **H18.** The brake is modelled as a Dahl friction element (Dahl 1968; Olsson et al. 1998,
//! "Friction models and friction compensation", §3.2) at the drive's output: with the brake
//! applied, a bristle deflection z (rad) follows
//!
//! ```text
//! dz/dt = ω·(1 − sign(ω)·z/z_max),   z_max = T_b/k_b,
//! T = k_b·z + c_b·dz/dt              (the torque opposing the output's motion, N·m)
//! ```
//!
//! so the brake sticks like a torsional spring k_b (damped by c_b) as long as the load is below
//! its holding torque T_b, and slips at T_b beyond (|z| → z_max). Released, the discs part and
//! the deflection relaxes, dz/dt = −z/τ_r, with no torque. The state z is integrated with the
//! plant's; a load held below T_b comes to rest at z = T_load/k_b, without drift.
//!
//! The brake is applied while the drive's command is centred (the spool, or the closed
//! circuit's pump command, inside its deadband) and released otherwise: the brake valve takes
//! its release pressure from the drive's work lines (a shuttle valve), so it opens with the
//! command. Its own release and application times are not modelled (a few tenths of a second
//! in practice; the relaxation τ_r stands for them).

use crate::check::check_fields;
use serde::{Deserialize, Serialize};

/// τ_r (s): how fast the deflection relaxes once the brake is released.
const RELEASE_TIME: f64 = 0.05;

/// A spring-applied brake at a drive's output (the slewing ring, the drum), H18.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Brake {
    /// T_b (N·m at the drive's output): the holding torque before the brake slips.
    pub torque: f64,
    /// k_b (N·m/rad): the stiffness of the applied brake and its shaft.
    pub stiffness: f64,
    /// c_b (N·m·s/rad): the damping of the applied brake.
    pub damping: f64,
}

impl Brake {
    pub fn validate(&self) -> Result<(), String> {
        check_fields!("brake", self; torque > 0, stiffness > 0, damping >= 0)
    }

    /// H18: (dz/dt, the torque opposing the output's motion (N·m)) at deflection `z` (rad) and
    /// output speed `omega` (rad/s), applied or released.
    pub fn rates(&self, applied: bool, z: f64, omega: f64) -> (f64, f64) {
        if !applied {
            return (-z / RELEASE_TIME, 0.0);
        }
        let z_max = self.torque / self.stiffness;
        let dz = omega * (1.0 - omega.signum() * z / z_max);
        (dz, self.stiffness * z + self.damping * dz)
    }
}

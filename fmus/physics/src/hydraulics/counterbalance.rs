//! The counterbalance (load-holding) valve (H6) and its pilot lag (H6b).

use super::valve::effective_opening;
use serde::{Deserialize, Serialize};

/// A pilot-assisted counterbalance (overcentre) valve on the load-holding port (A): a free check
/// valve for flow into the chamber, and a relief-type poppet for flow out of it. The poppet is
/// held shut by a spring set to `setting`; the load pressure p_A on its seat and the pilot
/// pressure on a pilot piston `pilot_ratio` times larger push it open, so it opens when
/// p_A + R·p_pilot reaches the setting (H6). Its spring chamber is vented to atmosphere, so the
/// pressure in the line to the directional valve does not add to the setting. Leak-free when
/// closed.
///
/// This is the force balance of the counterbalance valves of the Simscape Fluids library
/// (MathWorks, "Counterbalance Valve (IL)": pilot, load and back-pressure areas against the
/// spring, 3:1 and 4:1 the typical pilot ratios) and of the Modelica hydraulic library's
/// counterbalance valve (Wolfram SystemModeler, `Hydraulic.Valves.FlowControl.CounterBalanceValve`,
/// an unloading relief with a pilot ratio plus a check valve, after Eaton's Industrial
/// Hydraulics Manual); Sun Hydraulics describes the pilot as lowering the relief's effective
/// setting at the rate of the pilot ratio. Lowering, the pump's flow into B raises the pilot
/// until the poppet passes the load's outflow; when the load overruns the pump, p_B falls and
/// the poppet throttles A (the valve meters the load), and with the valve centred the load
/// alone cannot open it below the setting (load holding).
///
/// The poppet does not see p_B itself but the pressure π of its pilot chamber, which fills
/// through the pilot line's damping orifice: H6b, dπ/dt = (p_B − π)/τ_pilot, a first-order lag
/// (the linearised orifice-plus-pilot-volume filter; pilot-operated spools are modelled the same
/// way, with a time constant, in the Modelica hydraulic libraries, e.g. Wolfram SystemModeler's
/// `Hydraulic.Utilities.SpoolHPilotOperated`). It is the damping a real valve has: without it
/// the loop p_B → opening → load speed → p_B has no phase margin at the hydraulic frequency
/// (docs/hydraulics.md, H6b).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Counterbalance {
    /// p_set (Pa): the load pressure at which the poppet cracks with no pilot pressure. 36.4 MPa,
    /// 1.3 times the highest load-holding pressure (the 28 MPa supply: any load the drive can
    /// lift it must hold), the usual rule for counterbalance settings (at least 30 % above the
    /// highest load-induced pressure, so the valve reseats). Above the 30 MPa port relief, so
    /// the relief, not the poppet, takes overloads.
    pub setting: f64,
    /// k: how much of the load pressure p_A pushes the poppet open (its seat area over the
    /// seat's, 1 for a counterbalance valve; 0 for a pilot-operated check valve, which the pilot
    /// alone opens). See [`Counterbalance::PILOT_OPERATED`].
    pub load_ratio: f64,
    /// R: pilot piston area over the poppet's seat area (pilot ratio). 3: the low end of
    /// the usual 3:1–10:1, chosen for unstable loads (booms, winches), which a low ratio keeps
    /// under control at the cost of a higher pilot pressure.
    pub pilot_ratio: f64,
    /// Δp_o (Pa): the rise of p_A + R·π from cracking to fully open (the spring's opening
    /// gradient). See [`Counterbalance::DEFAULT`].
    pub opening_range: f64,
    /// Flow through the fully open poppet at `rated_drop` (m³/s). 480 L/min, twice the
    /// directional valve: it passes the piston side's outflow, A_A/A_B = 2.29 times the rod
    /// side's inflow, when lowering (a choice; the OSP data gives no size).
    pub rated_flow: f64,
    /// Pressure drop of that rating (Pa). 1 MPa.
    pub rated_drop: f64,
    /// τ_pilot of H6b (s), the pilot damping orifice. 0 = no lag (the poppet follows p_B; the
    /// pilot state is then not integrated).
    pub pilot_lag: f64,
    /// p_cmd (Pa): 0 for a hydraulic pilot, the pressure of port B through the pilot line
    /// (H6b). Above 0, an electro-proportional pilot: a pressure-reducing valve driven by the
    /// lowering command sets the pilot's target to π* = p_cmd·max(0, −u) (H6c), u the spool
    /// command in [−1, 1] (the reducing valve and the spool get the same signal), so the
    /// poppet opens with the operator's command and not with p_B. It removes the loop
    /// p_B → opening → load speed → p_B that makes hydraulically piloted valves oscillate on
    /// heavy overrunning loads (Kjelland & Hansen, "Numerical and experimental study of motion
    /// control using pressure feedback", SICFP 2013, on the oscillatory nature of overcentre
    /// valves and their electronic compensation); the poppet then meters the outflow in series
    /// with the directional valve's meter-out edge, which damps the load (docs/hydraulics.md,
    /// H6c). The lag `pilot_lag` is then the reducing valve's response.
    pub command_pilot: f64,
}

impl Counterbalance {
    pub const DEFAULT: Counterbalance = Counterbalance {
        setting: 36.4e6,
        load_ratio: 1.0,
        pilot_ratio: 3.0,
        opening_range: 10e6,
        rated_flow: 480e-3 / 60.0,
        rated_drop: 1e6,
        pilot_lag: 0.05,
        command_pilot: 0.0,
    };

    /// The winch's valve: [`Counterbalance::DEFAULT`] with a 1 s pilot lag. With R = 3 the pilot
    /// acts on the lowering winch as a spring of (1 + R)·(n·D)²·β/V at the drum; lagged by
    /// τ_pilot, its R part adds the negative damping R·(n·D)²·β/V·τ/(1 + ω²τ²), which the
    /// poppet's flow damping (n·D)²/(∂Q/∂p_A) outweighs only for ωτ ≫ 1 (docs/hydraulics.md,
    /// H6b): 0.05 s leaves the default winch in a limit cycle, 0.5 s the 10 t AHC winch, 1 s
    /// settles every catalogue winch. The OSP test crane's own valve filters its pilot with
    /// 0.32 s (a 0.5 Hz low-pass).
    pub const WINCH: Counterbalance = Counterbalance { pilot_lag: 1.0, ..Counterbalance::DEFAULT };

    /// The luffing cylinders' lowering valves: pilot-operated, opening on the pilot alone from
    /// 2 MPa (OSP's `Popen`) to fully open at 20 MPa (OSP's `PfullyOpen`), k = 0, R = 1. The
    /// load-assisted law of [`Counterbalance::DEFAULT`] (k = 1, R = 3) with the 0.05 s pilot lag
    /// limit-cycles at about 2.5 Hz in the arm's closed loop (the full-scale campaign's
    /// compensated runs lose the rope 2–4 s after release, docs/hydraulics.md H6b), which a
    /// longer lag would trade for a sluggish arm; until the arm's valves are tuned with the
    /// controller in the loop, they keep the law the campaign was validated with.
    pub const PILOT_OPERATED: Counterbalance = Counterbalance {
        setting: 2e6,
        load_ratio: 0.0,
        pilot_ratio: 1.0,
        opening_range: 18e6,
        rated_flow: 480e-3 / 60.0,
        rated_drop: 1e6,
        pilot_lag: 0.05,
        command_pilot: 0.0,
    };

    pub fn validate(&self) -> Result<(), String> {
        for (name, value) in [
            ("setting", self.setting),
            ("pilot_ratio", self.pilot_ratio),
            ("opening_range", self.opening_range),
            ("rated_flow", self.rated_flow),
            ("rated_drop", self.rated_drop),
        ] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("counterbalance {name} must be a finite value > 0, got {value}"));
            }
        }
        if !(self.load_ratio >= 0.0 && self.load_ratio <= 1.0) {
            return Err(format!("counterbalance load_ratio must lie in 0…1, got {}", self.load_ratio));
        }
        if !(self.pilot_lag >= 0.0 && self.pilot_lag.is_finite()) {
            return Err(format!("counterbalance pilot_lag must be a finite value ≥ 0 s, got {}", self.pilot_lag));
        }
        if !(self.command_pilot >= 0.0 && self.command_pilot.is_finite()) {
            return Err(format!(
                "counterbalance command_pilot must be a finite value ≥ 0 Pa, got {}",
                self.command_pilot
            ));
        }
        if self.is_commanded() && self.pilot_ratio * self.command_pilot <= self.setting {
            return Err(format!(
                "counterbalance command_pilot {} Pa times pilot_ratio {} does not reach the setting {} Pa: \
                 full command would not open the valve",
                self.command_pilot, self.pilot_ratio, self.setting
            ));
        }
        Ok(())
    }

    /// Whether the pilot is electro-proportional (H6c) rather than port B's pressure (H6b).
    pub fn is_commanded(&self) -> bool {
        self.command_pilot > 0.0
    }

    /// The pressure the pilot chamber tends to (Pa): port B's pressure `p_b` through the pilot
    /// line (H6b), or H6c's π* = p_cmd·max(0, −u) for the spool command `spool` (clamped to
    /// [−1, 1], NaN as 0; negative when A drains: lowering).
    pub fn pilot_target(&self, p_b: f64, spool: f64) -> f64 {
        if self.is_commanded() {
            self.command_pilot * (-effective_opening(spool, 0.0)).max(0.0)
        } else {
            p_b
        }
    }

    /// The pilot chamber at rest with the spool centred and port B at `p_b` (Pa).
    pub fn rest_pilot(&self, p_b: f64) -> f64 {
        self.pilot_target(p_b, 0.0)
    }

    /// The pilot pressure the poppet sees (Pa): the lagged π of H6b, or the target itself when
    /// `pilot_lag` is 0.
    pub fn pilot(&self, target: f64, lagged: f64) -> f64 {
        if self.pilot_lag > 0.0 {
            lagged
        } else {
            target
        }
    }

    /// H6b, dπ/dt = (π* − π)/τ_pilot (Pa/s), π* the [`Counterbalance::pilot_target`]; 0 without
    /// a lag.
    pub fn pilot_rate(&self, target: f64, lagged: f64) -> f64 {
        if self.pilot_lag > 0.0 {
            (target - lagged) / self.pilot_lag
        } else {
            0.0
        }
    }

    /// H6, the poppet opening from the load pressure p_A and the pilot pressure π (the force
    /// balance of a pilot-assisted relief poppet, its spring chamber vented):
    /// o_cb = clamp((k·p_A + R·π − p_set)/Δp_o, 0, 1).
    pub fn opening(&self, load: f64, pilot: f64) -> f64 {
        ((self.load_ratio * load + self.pilot_ratio * pilot - self.setting) / self.opening_range).clamp(0.0, 1.0)
    }

    /// The pilot pressure at which the poppet cracks under the load pressure `load` (Pa):
    /// (p_set − k·p_A)/R (H6 with o_cb = 0).
    pub fn cracking_pilot(&self, load: f64) -> f64 {
        (self.setting - self.load_ratio * load) / self.pilot_ratio
    }

    /// The poppet's turbulent conductance K_cb·o_cb (m³/(s·Pa^½)), K_cb = Q_rated/√Δp_rated (H2).
    pub fn conductance(&self, load: f64, pilot: f64) -> f64 {
        self.rated_flow / self.rated_drop.sqrt() * self.opening(load, pilot)
    }
}

default_is_const!(Counterbalance);

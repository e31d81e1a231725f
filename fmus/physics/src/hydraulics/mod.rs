//! Hydraulic drives of the knuckle-boom crane: directional valves, counterbalance valves, port
//! reliefs, cylinders and motors, as pure functions (parameters, state, command) → derivatives
//! for the caller's integrator.
//!
//! Units SI: gauge pressures in Pa (tank p_T = 0), volumes m³, flows m³/s, forces N, torques
//! N·m, strokes m, angles rad. Cylinder stroke x from 0 (retracted), positive extending; chamber
//! A is the piston side, B the rod side. Motor: u > 0 feeds A and turns it positive.
//!
//! - [`oil`] — oil and supply, H4, H10, H11;
//! - [`orifice`] — H2 and the valve–counterbalance junction of H6;
//! - [`valve`] — H1, H3;
//! - [`counterbalance`] — H6;
//! - [`relief`] — H5;
//! - [`drive`] — the drive's state and rates, the ports and H12;
//! - [`cylinder`] — H7, H13;
//! - [`motor`] — H8, H9, H14;
//! - [`closed_circuit`] — the winch's pump-controlled alternative, H15–H17;
//! - [`brake`] — the spring-applied winch and slew brakes, H18;
//! - [`rig`] — a vertical valve–cylinder–mass test rig integrated with RK4.
//!
//! # Equations
//!
//! - **H1** spool opening (deadband d): u clamped to [−1, 1],
//!   u_eff = sign(u)·max(0, |u| − d)/(1 − d).
//! - **H2** regularised turbulent orifice (Merritt 1967 §3.3; Jelali & Kroll 2003 §3.2): an edge of
//!   opening o passes Q = K·o·φ(Δp), φ(Δp) = Δp/(Δp² + Δp_t²)^¼, K = Q_rated/√Δp_rated;
//!   φ → sign(Δp)·√|Δp| for |Δp| ≫ Δp_t and is linear near 0 (Lipschitz right-hand side).
//! - **H3** 4/3 critical-centre valve, supply p_S, tank p_T: u_eff > 0 opens P→A and B→T,
//!   u_eff < 0 P→B and A→T, each by o = |u_eff|. Meter-in edges (P→A, P→B) are
//!   pressure-compensated with a load-holding check: Q = clamp(K·o·φ(p_S − p_line), 0, o·Q_max).
//!   Meter-out edges: Q = K·o·φ(p_line − p_T). Every edge has laminar spool leakage in
//!   parallel, C_P·(p_S − p_line) on P→A, P→B and C_T·(p_line − p_T) on A→T, B→T, present at
//!   any opening, so a centred spool does not hold a load.
//! - **H4** chamber pressure (Merritt 1967 ch. 3, continuity with compressibility):
//!   dp/dt = β/V·(Q_in − dV/dt), V_A = V_dead + A_A·x, V_B = V_dead + A_B·(s − x),
//!   A_A = π·bore²/4, A_B = A_A − π·rod²/4.
//! - **H5** port relief and make-up on each chamber: a relief of finite capacity to tank,
//!   Q_relief = 0 below p_relief, G·(p − p_relief) up to its rated flow Q_r at
//!   p_full = p_relief + Q_r/G, Q_r·√(p/p_full) above (fully open orifice); make-up
//!   Q_makeup = G_mu·max(0, p_T − p) from tank.
//! - **H6** counterbalance valve on port A (load pressure p_A plus pilot ratio R times the pilot
//!   π, H6b's lagged p_B): o_cb = clamp((p_A + R·π − p_set)/Δp_o, 0, 1), conductance K_cb·o_cb, K_cb = Q_cb,rated/√Δp_cb,rated, leak-free
//!   when closed; a free check valve for flow into A. The line between valve and CBV holds no
//!   volume: if the valve's net flow into the line at p_line = p_A, q_v(p_A), is ≥ 0 the check
//!   passes it (Q_A = q_v(p_A)); otherwise p_line solves q_v(p_line) + K_cb·o_cb·φ(p_A − p_line) = 0
//!   (one root: both terms decrease in p_line) and Q_A = −K_cb·o_cb·φ(p_A − p_line) (zero
//!   when o_cb = 0). This is the exact series combination of the valve's paths (edges and
//!   leakage) with the poppet under H2.
//! - **H7** cylinder force on the rod, positive extending:
//!   F = p_A·A_A − p_B·A_B − (b·v + F_c·tanh(v/v_s)) + F_stop, F_stop = max(0, −k·x − c·v) for x < 0,
//!   min(0, −k·(x − s) − c·v) for x > s, 0 otherwise.
//! - **H8** motor torque: τ_m = D·(p_A − p_B) − (b·ω_m + τ_c·tanh(ω_m/ω_s)), output torque n·τ_m,
//!   ω_m = n·ω_out.
//! - **H9** motor line pressures: dp_A/dt = β/V_A·(Q_A − D·ω_m − C_m·(p_A − p_B)),
//!   dp_B/dt = β/V_B·(Q_B + D·ω_m + C_m·(p_A − p_B)).
//! - **H10** stored oil energy (first order in p/β): E = p²·V/(2β).
//! - **H11** exact work on a closed chamber (Q = 0, constant β, so p = p0 − β·ln(V/V0)):
//!   −∫p dV = V0·[p0·(1 − e^(−s)) + β·(1 − (1 + s)·e^(−s))], s = (p − p0)/β.
//! - **H12** power balance: p_S·Q_S − p_T·Q_T = Σ Δp·Q (orifices, reliefs, make-up, leakage) plus
//!   Σ p·(Q_net − dV/dt) (compression) plus F_hyd·v (or D·(p_A − p_B)·ω_m), an identity of H2–H9
//!   because the massless lines conserve flow.
//! - **H13** cylinder hydraulic frequency (Merritt 1967 ch. 5; Jelali & Kroll 2003 ch. 4):
//!   ω_h = √(β·(A_A²/V_A + A_B²/V_B)/m).
//! - **H14** motor hydraulic frequency at the gear output: ω_h = n·D·√(β·(1/V_A + 1/V_B)/J).
//!
//! - **H15** swash-plate servo of the closed circuit's over-centre pump (first-order lag):
//!   dε/dt = (u_eff − ε)/τ_sw, u_eff of H1 (with the pump control's deadband), ε ∈ [−1, 1].
//! - **H16** pump flow from line B into line A, constant drive speed ω_p, volumetric loss as
//!   laminar leakage (Merritt 1967, the pump-controlled motor): Q_p = ε·D_p·ω_p − C_p·(p_A − p_B).
//! - **H17** charge and cross-port reliefs: a check from the charge pump at p_c into each line,
//!   Q_c = G_c·max(0, p_c − p); a relief each way between the lines set to a pressure
//!   difference Δp_r, Q_A→B = G·max(0, p_A − p_B − Δp_r) (and B→A alike). The lines then follow
//!   H9 with Q_A = Q_p + Q_c,A − Q_A→B + Q_B→A, Q_B = −Q_p + Q_c,B + Q_A→B − Q_B→A, and H12 holds
//!   with the pump's ε·D_p·ω_p·(p_A − p_B) + p_c·Q_c in place of the supply's power.
//!
//! - **H18** spring-applied brake at a drive's output (Dahl friction): applied while the
//!   command is centred, dz/dt = ω·(1 − sign(ω)·z/z_max), z_max = T_b/k_b, torque
//!   k_b·z + c_b·dz/dt against the motion; released, dz/dt = −z/τ_r and no torque ([`brake`]).
//!
//! docs/hydraulics.md repeats these with the parameter sources and the verification figures.

pub mod brake;
pub mod closed_circuit;
pub mod counterbalance;
pub mod cylinder;
pub mod drive;
pub mod motor;
pub mod oil;
pub mod orifice;
pub mod relief;
pub mod rig;
pub mod valve;

#[cfg(test)]
mod tests;

pub use brake::Brake;
pub use closed_circuit::{ClosedCircuit, Flushing, WinchCircuit};
pub use counterbalance::Counterbalance;
pub use cylinder::{Cylinder, CylinderDrive};
pub use drive::{DriveRates, DriveState};
pub use motor::MotorDrive;
pub use oil::{Oil, Supply};
pub use relief::Relief;
pub use valve::Valve;

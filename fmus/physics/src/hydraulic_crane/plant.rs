//! The coupled plant of the full-scale crane: arm, four hydraulic drives and the winch drum.
//!
//! State x (21 numbers, SI): joint angles q = (θ1 slew, θ2 boom, θ3 jib) (rad) and their rates
//! (rad/s); the chamber pressures (p_A, p_B) (Pa, gauge) of the slew motor, the boom and jib
//! cylinders and the winch motor; the winch drum's angle φ from its start (rad, positive pays
//! rope out) and its rate; each drive's lagged counterbalance pilot pressure π (Pa, H6b); the
//! winch pump's swash-plate angle ε (H15, constant 0 with the open circuit). Its right-hand side (docs/full-scale.md, eqs. F1–F5):
//!
//! - F1, the drives' states from the arm's: a luffing cylinder's stroke x = L(θ) − L_closed and
//!   speed ẋ = (dL/dθ)·θ̇ (the mechanism of [`crate::knuckle_boom`]); the slew motor turns with
//!   joint 1, the winch motor with the drum (both through their gears, inside the drive);
//! - F2, the pressure build-up of every chamber and the force (N) or torque (N·m) each drive
//!   delivers: [`crate::hydraulics`]; the winch by its valve section (open circuit) or by its
//!   pump (closed circuit, [`crate::hydraulics::ClosedCircuit`]), as `winch_circuit` selects;
//! - F3, joint torques by virtual work: τ1 = slew torque, τ2 = F_boom·dL_b/dθ2,
//!   τ3 = F_jib·dL_j/dθ3;
//! - F4, the arm's forward dynamics on the moving deck with the cable force at the tip
//!   (Featherstone 2008, ch. 5–6): q̈ = M(q)⁻¹(τ − b(q, q̇, deck, f_tip));
//! - F5, the drum: J_w·φ̈ = τ_winch + T·r_d, with T = |f_tip| the rope tension pulling rope off the
//!   drum of pitch radius r_d; the hoist length is l = l_0 + r_d·φ.
//!
//! Over a communication step the spool commands, the deck motion and the cable force are held
//! (zero-order hold) and x is integrated with classical RK4 at substeps of at most
//! [`crate::integrate::MAX_SUBSTEP`]: the stiffest mode with the default parameters, the oil
//! column of a drive (docs/hydraulics.md), stays well inside RK4's stability limit there.

use crate::hydraulics::{
    ClosedCircuit, CylinderDrive, DriveRates, DriveState, MotorDrive, Oil, Supply, Valve, WinchCircuit,
};
use crate::integrate::{rk4, substeps};
use crate::knuckle_boom::{ArmParams, Joints};
use crate::math::{SVector, Vec3};
use crate::motion::{PointMotion, ShipMotion};
use nalgebra::{Matrix4, Vector4};
use serde::{Deserialize, Serialize};

/// Index of each drive in [`PlantState::pressures`], [`Spools`] and the outputs.
pub const SLEW: usize = 0;
pub const BOOM: usize = 1;
pub const JIB: usize = 2;
pub const WINCH: usize = 3;
/// The drives' names, by index.
pub const DRIVE_NAMES: [&str; 4] = ["slew", "boom", "jib", "winch"];

/// Length of the state vector ([`PlantState::to_array`]).
pub const STATES: usize = 23;
type X = SVector<f64, STATES>;

/// Spool commands of the four directional valves (−1…1 each, clamped by the valve; index by
/// [`SLEW`] … [`WINCH`]). Positive extends a cylinder, turns the slew positively about K's z axis
/// (clockwise seen from above) and pays rope out.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Spools(pub [f64; 4]);

/// What acts on the crane from outside over a step: the deck motion and the hoist rope's load.
///
/// The rope's pull on the tip is F = T·e, e the unit vector from the tip toward the load. For
/// a load hanging in a taut rope the tension is affine in the tip's acceleration a and the
/// rope's length acceleration l̈ (the rope is a length constraint; thesis eq. 4.127):
/// T = T₀ − m·(e·a + l̈), with T₀ the tension the load would pull with if the tip did not
/// accelerate and the length were steady. The pendulum reports F₀ = T₀·e and its mass m; the
/// crane completes the tension with its own a and l̈ inside its integration ([`CraneParams::evaluate`]),
/// so the load's inertia along the rope is integrated implicitly and only F₀ is held over a
/// step. With m = 0, F₀ is simply the force on the tip.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Loads {
    pub ship: ShipMotion,
    /// F₀ (N, W coordinates).
    pub cable: Vec3,
    /// m, the mass hanging in the rope (kg).
    pub load_mass: f64,
}

/// Configuration of the plant (not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CraneParams {
    pub arm: ArmParams,
    pub oil: Oil,
    pub supply: Supply,
    pub slew: MotorDrive,
    pub boom: CylinderDrive,
    pub jib: CylinderDrive,
    pub winch: MotorDrive,
    /// Pitch radius of the rope on the drum (m).
    pub drum_radius: f64,
    /// Inertia of the drum with the gear-reflected motor (kg·m², about the drum axis).
    pub winch_inertia: f64,
    /// What feeds the winch motor: its valve section (`winch`'s valve, counterbalance valve and
    /// reliefs on the supply) or the closed circuit's pump `winch_pump`.
    pub winch_circuit: WinchCircuit,
    /// The closed circuit's pump side (used with [`WinchCircuit::Closed`]; the motor, gear and
    /// lines are `winch`'s).
    pub winch_pump: ClosedCircuit,
}

/// The plant's continuous state (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PlantState {
    pub q: Joints,
    pub qd: Joints,
    /// (p_A, p_B) of each drive (Pa), index [`SLEW`] … [`WINCH`].
    pub pressures: [[f64; 2]; 4],
    /// Drum angle from the start (rad, positive pays out) and its rate (rad/s).
    pub drum: f64,
    pub drum_rate: f64,
    /// π, each drive's lagged counterbalance pilot pressure (Pa, H6b), index [`SLEW`] …
    /// [`WINCH`]; constant in a drive without a counterbalance valve (the slew, the winch in
    /// the closed circuit).
    pub pilots: [f64; 4],
    /// ε, the closed-circuit winch pump's swash-plate angle (−1…1, H15); 0 with the open circuit.
    pub swash: f64,
    /// z, the slew's and the winch drum's brake deflections (rad, H18; positive in the slew's
    /// and in the drum's paying-out sense); 0 without a brake.
    pub brakes: [f64; 2],
}

/// Everything the outputs need at one instant: the state's time derivatives under the held
/// inputs and what each drive does.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Evaluation {
    /// Joint accelerations (rad/s²).
    pub qdd: Joints,
    /// Drum acceleration (rad/s²).
    pub drum_acc: f64,
    /// Each drive's stroke or angle, rate and pressures (index [`SLEW`] … [`WINCH`]).
    pub drives: [DriveState; 4],
    pub rates: [DriveRates; 4],
    /// The rope tension T (N) and its force on the tip T·e (N, W).
    pub tension: f64,
    pub cable_force: Vec3,
    /// The slew's and the drum's brakes (H18): the deflection rates dz/dt (rad/s) and the
    /// torques against the motion (N·m, at the slewing ring and at the drum).
    pub brake_rates: [f64; 2],
    pub brake_torques: [f64; 2],
}

impl PlantState {
    /// The state as the integrator's vector: [q (3), q̇ (3), (p_A, p_B) of each drive (8), φ, φ̇,
    /// π of each drive (4), ε, z of the slew's and the drum's brake] — the one place that fixes
    /// the layout.
    pub fn to_array(&self) -> [f64; STATES] {
        let ([q1, q2, q3], [w1, w2, w3], p, pi) = (self.q, self.qd, self.pressures, self.pilots);
        [
            q1,
            q2,
            q3,
            w1,
            w2,
            w3,
            p[0][0],
            p[0][1],
            p[1][0],
            p[1][1],
            p[2][0],
            p[2][1],
            p[3][0],
            p[3][1],
            self.drum,
            self.drum_rate,
            pi[0],
            pi[1],
            pi[2],
            pi[3],
            self.swash,
            self.brakes[0],
            self.brakes[1],
        ]
    }

    /// The inverse of [`Self::to_array`]; `None` unless `x` holds exactly [`STATES`] numbers.
    pub fn from_slice(x: &[f64]) -> Option<PlantState> {
        let x: &[f64; STATES] = x.try_into().ok()?;
        let pair = |i: usize| [x[i], x[i + 1]];
        Some(PlantState {
            q: [x[0], x[1], x[2]],
            qd: [x[3], x[4], x[5]],
            pressures: [pair(6), pair(8), pair(10), pair(12)],
            drum: x[14],
            drum_rate: x[15],
            pilots: [x[16], x[17], x[18], x[19]],
            swash: x[20],
            brakes: [x[21], x[22]],
        })
    }

    fn to_vector(self) -> X {
        X::from(self.to_array())
    }

    fn from_vector(x: &X) -> PlantState {
        // A vector of N = STATES numbers always converts.
        PlantState::from_slice(x.as_slice()).unwrap_or_default()
    }

    /// Whether every number is finite (a state that is not came from a configuration or an input
    /// the model cannot follow).
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|v| v.is_finite())
    }
}

/// The default start (rad): reaching out to port (θ1 = −π/2) with the boom 40° up and the jib
/// 60° below the boom line — 10.25 m outreach, the tip 4.9 m above the deck; both cylinders in
/// mid-stroke region (our choice, a typical working pose).
pub const DEFAULT_JOINTS: Joints = [-std::f64::consts::FRAC_PI_2, 40.0 * DEG, -60.0 * DEG];
const DEG: f64 = std::f64::consts::PI / 180.0;

impl CraneParams {
    /// The Open Simulation Platform crane with the drives of [`crate::hydraulics`]: the arm of
    /// [`ArmParams::DEFAULT`], boom and jib cylinders [`CylinderDrive::DEFAULT`], the slew and
    /// winch motors [`MotorDrive::SLEW_DEFAULT`], [`MotorDrive::WINCH_DEFAULT`]; the winch's 0.5 m
    /// drum (r_d = 0.25 m) with 500 kg·m² for the drum, its rope layers and the motor through the
    /// 30:1 gear (our choice: a 1.5 t steel drum of 0.5 m core, 1.2 m flanges).
    pub const DEFAULT: CraneParams = CraneParams {
        arm: ArmParams::DEFAULT,
        oil: Oil::DEFAULT,
        supply: Supply::DEFAULT,
        slew: MotorDrive::SLEW_DEFAULT,
        boom: CylinderDrive::DEFAULT,
        jib: CylinderDrive::DEFAULT,
        winch: MotorDrive::WINCH_DEFAULT,
        drum_radius: 0.25,
        winch_inertia: 500.0,
        winch_circuit: WinchCircuit::Open,
        winch_pump: ClosedCircuit::DEFAULT,
    };

    /// Checks every part; the message names the part and the value.
    pub fn validate(&self) -> Result<(), String> {
        self.arm.validate()?;
        self.oil.validate()?;
        self.supply.validate()?;
        for (name, drive) in [("slew", &self.slew), ("winch", &self.winch)] {
            drive.validate(&self.supply).map_err(|e| format!("{name} drive: {e}"))?;
        }
        self.winch_pump.validate().map_err(|e| format!("winch pump: {e}"))?;
        for (name, drive, mechanism) in
            [("boom", &self.boom, &self.arm.boom_cylinder), ("jib", &self.jib, &self.arm.jib_cylinder)]
        {
            drive.validate(&self.supply).map_err(|e| format!("{name} cylinder: {e}"))?;
            let travel = mechanism.max_length - mechanism.min_length;
            if (travel - drive.cylinder.stroke).abs() > 1e-9 {
                return Err(format!(
                    "{name} cylinder: the stroke {} m differs from the mechanism's pin-to-pin travel {travel} m",
                    drive.cylinder.stroke
                ));
            }
        }
        for (name, value) in [("drum radius", self.drum_radius), ("winch inertia", self.winch_inertia)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("{name} must be > 0, got {value}"));
            }
        }
        Ok(())
    }

    /// The drives' states (eq. F1) at the cylinders' pin-to-pin lengths and lever arms
    /// `cylinders` ([`ArmParams::cylinders`] at `s.q`).
    fn drive_states(&self, s: &PlantState, cylinders: &[(f64, f64); 2]) -> [DriveState; 4] {
        let [(l_boom, arm_boom), (l_jib, arm_jib)] = *cylinders;
        let state = |i: usize, pos, vel| {
            let [p_a, p_b] = s.pressures[i];
            DriveState { pos, vel, p_a, p_b, pilot: s.pilots[i] }
        };
        [
            state(SLEW, s.q[0], s.qd[0]),
            state(BOOM, l_boom - self.arm.boom_cylinder.min_length, arm_boom * s.qd[1]),
            state(JIB, l_jib - self.arm.jib_cylinder.min_length, arm_jib * s.qd[2]),
            // The winch motor turns positively hoisting (its counterbalance valve holds against
            // payout), the drum angle positively paying out.
            state(WINCH, -s.drum, -s.drum_rate),
        ]
    }

    /// The state's time derivatives and the drives' rates under the held inputs (eqs. F1–F5).
    pub fn evaluate(&self, s: &PlantState, spools: &Spools, loads: &Loads) -> Evaluation {
        let cylinders = self.arm.cylinders(&s.q);
        let drives = self.drive_states(s, &cylinders);
        let u = spools.0;
        let rates = [
            self.slew.rates(&self.oil, &self.supply, u[SLEW], &drives[SLEW]),
            self.boom.rates(&self.oil, &self.supply, u[BOOM], &drives[BOOM]),
            self.jib.rates(&self.oil, &self.supply, u[JIB], &drives[JIB]),
            self.winch_rates(s, -u[WINCH], &drives[WINCH]),
        ];
        let [(_, arm_boom), (_, arm_jib)] = cylinders;
        // F3: virtual work of each actuator on its joint.
        let mut tau = [rates[SLEW].force, rates[BOOM].force * arm_boom, rates[JIB].force * arm_jib];
        let mut winch_torque = -rates[WINCH].force;
        let (brake_rates, brake_torques) = self.brakes(s, spools);
        // H18: each brake's torque opposes its output's motion (only a fitted brake adds a term).
        if self.slew.brake.is_some() {
            tau[0] -= brake_torques[0];
        }
        if self.winch.brake.is_some() {
            winch_torque -= brake_torques[1];
        }
        let (qdd, drum_acc, tension) = self.accelerations(s, &tau, winch_torque, loads);
        let cable_force = direction(&loads.cable) * tension;
        Evaluation { qdd, drum_acc, drives, rates, tension, cable_force, brake_rates, brake_torques }
    }

    /// H18 for the slew's and the drum's brakes: (dz/dt, torque) of each, applied while its
    /// drive's command is centred (the valve's opening, or the closed circuit's pump command, is
    /// zero). A drive without a brake gives zeros.
    fn brakes(&self, s: &PlantState, spools: &Spools) -> ([f64; 2], [f64; 2]) {
        let u = spools.0;
        let winch_centred = match self.winch_circuit {
            WinchCircuit::Open => self.winch.valve.opening(u[WINCH]) == 0.0,
            WinchCircuit::Closed => self.winch_pump.command(u[WINCH]) == 0.0,
        };
        let one = |brake: &Option<crate::hydraulics::Brake>, applied: bool, z: f64, omega: f64| {
            brake.map_or((0.0, 0.0), |b| b.rates(applied, z, omega))
        };
        let slew = one(&self.slew.brake, self.slew.valve.opening(u[SLEW]) == 0.0, s.brakes[0], s.qd[0]);
        let drum = one(&self.winch.brake, winch_centred, s.brakes[1], s.drum_rate);
        ([slew.0, drum.0], [slew.1, drum.1])
    }

    /// The winch drive's rates for the motor-side command `spool` (positive hoisting) in the
    /// selected circuit.
    fn winch_rates(&self, s: &PlantState, spool: f64, drive: &DriveState) -> DriveRates {
        match self.winch_circuit {
            WinchCircuit::Open => self.winch.rates(&self.oil, &self.supply, spool, drive),
            WinchCircuit::Closed => self.winch_pump.rates(&self.winch, &self.oil, spool, s.swash, drive),
        }
    }

    /// Joint and drum accelerations and the rope tension (eqs. F4, F5 with the load of
    /// [`Loads`]): with the tip acceleration a = J q̈ + c (J the tip Jacobian in W, c the part
    /// from velocities and the deck), g = Jᵀe and T = T₀ − m(e·a + r_d φ̈), the arm and the drum
    /// solve together
    ///
    /// ```text
    /// [ M + m g gᵀ    m r_d g      ] [ q̈ ]   [ τ − b + g (T₀ − m e·c) ]
    /// [ m r_d gᵀ      J_w + m r_d² ] [ φ̈ ] = [ τ_w + r_d (T₀ − m e·c) ]
    /// ```
    ///
    /// (b the joint torques at q̈ = 0 without the rope). A tension that comes out negative means
    /// the rope would push: it goes slack, and the crane moves free of the load (T = 0). A
    /// singular system (a degenerate configuration) gives NaN, which the step reports.
    fn accelerations(&self, s: &PlantState, tau: &Joints, winch_torque: f64, loads: &Loads) -> (Joints, f64, f64) {
        let ship = &loads.ship;
        let e = direction(&loads.cable);
        let t0 = loads.cable.norm();
        let (jacobian, c) = self.arm.tip_jacobian_in_world(ship, &s.q, &s.qd);
        let g = jacobian.transpose() * e;
        let (bias, mass) = self.arm.bias_and_mass_matrix(ship, &s.q, &s.qd);
        let r = self.drum_radius;
        let solve = |m: f64, t0: f64| {
            let free = t0 - m * e.dot(&c);
            let mut lhs = Matrix4::zeros();
            lhs.fixed_view_mut::<3, 3>(0, 0).copy_from(&(mass + g * g.transpose() * m));
            lhs.fixed_view_mut::<3, 1>(0, 3).copy_from(&(g * (m * r)));
            lhs.fixed_view_mut::<1, 3>(3, 0).copy_from(&(g.transpose() * (m * r)));
            lhs[(3, 3)] = self.winch_inertia + m * r * r;
            let arm_rhs = Vec3::from(*tau) - Vec3::from(bias) + g * free;
            let rhs = Vector4::new(arm_rhs.x, arm_rhs.y, arm_rhs.z, winch_torque + r * free);
            let x = lhs.cholesky().map(|ch| ch.solve(&rhs)).unwrap_or(Vector4::repeat(f64::NAN));
            let qdd = [x[0], x[1], x[2]];
            let a = jacobian * Vec3::new(x[0], x[1], x[2]) + c;
            (qdd, x[3], free - m * (e.dot(&(a - c)) + r * x[3]))
        };
        let (qdd, drum_acc, tension) = solve(loads.load_mass, t0);
        if tension >= 0.0 || loads.load_mass == 0.0 {
            return (qdd, drum_acc, tension);
        }
        let (qdd, drum_acc, _) = solve(0.0, 0.0);
        (qdd, drum_acc, 0.0)
    }

    /// The state's time derivative, as a state (eqs. F1–F5, H6b, H15), from the state `s` and its
    /// evaluation `e` ([`Self::evaluate`] under the held inputs).
    pub fn rate(s: &PlantState, e: &Evaluation) -> PlantState {
        PlantState {
            q: s.qd,
            qd: e.qdd,
            pressures: e.rates.map(|r| [r.dp_a, r.dp_b]),
            drum: s.drum_rate,
            drum_rate: e.drum_acc,
            pilots: e.rates.map(|r| r.dpilot),
            swash: e.rates[WINCH].dswash,
            brakes: e.brake_rates,
        }
    }

    fn derivative(&self, x: &X, spools: &Spools, loads: &Loads) -> X {
        let s = PlantState::from_vector(x);
        CraneParams::rate(&s, &self.evaluate(&s, spools, loads)).to_vector()
    }

    /// The state `h` seconds later with the inputs held: RK4 at equal substeps ≤ 1 ms.
    pub fn advance(&self, s: &PlantState, spools: &Spools, loads: &Loads, h: f64) -> PlantState {
        let n = substeps(h);
        let dt = h / n as f64;
        let mut x = s.to_vector();
        for _ in 0..n {
            x = rk4(&x, 0.0, dt, |_, x| self.derivative(x, spools, loads));
        }
        PlantState::from_vector(&x)
    }

    /// The crane at rest at joints `q` under `loads`: every drive's pressures balance the static
    /// joint torque it must hold (inverse dynamics with q̇ = q̈ = 0), the return chambers at tank
    /// pressure, the drum at rest.
    pub fn initial_state(&self, q: Joints, loads: &Loads) -> Result<PlantState, String> {
        let zero = [0.0; 3];
        let tau = self.arm.joint_torques(&loads.ship, &q, &zero, &zero, &loads.cable);
        let [(l_boom, arm_boom), (l_jib, arm_jib)] = self.arm.cylinders(&q);
        let strokes = [
            ("boom", l_boom - self.arm.boom_cylinder.min_length, &self.boom),
            ("jib", l_jib - self.arm.jib_cylinder.min_length, &self.jib),
        ];
        for (name, stroke, cylinder) in strokes {
            if !(0.0..=cylinder.cylinder.stroke).contains(&stroke) {
                return Err(format!(
                    "the initial joints put the {name} cylinder at a stroke of {stroke:.3} m, outside 0-{} m",
                    cylinder.cylinder.stroke
                ));
            }
        }
        // The return chambers at the pressure a centred spool's leakage holds them at.
        let neutral = |valve: &Valve| valve.neutral_pressure(self.supply.pressure, self.supply.tank);
        let pressures = [
            self.slew.holding_pressures(tau[0], neutral(&self.slew.valve)),
            self.boom.holding_pressures(tau[1] / arm_boom, neutral(&self.boom.valve)),
            self.jib.holding_pressures(tau[2] / arm_jib, neutral(&self.jib.valve)),
            // The winch holds the rope's torque T·r_d on the hoisting side, its low line at the
            // valve's neutral pressure (open circuit) or the charge pressure (closed circuit).
            self.winch_holding(loads.cable.norm() * self.drum_radius),
        ]
        .map(|(a, b)| [a, b]);
        // Each pilot chamber at rest: at its line's pressure p_B (H6b), or at the centred
        // command's target (H6c).
        let holdings = [self.slew.holding, self.boom.holding, self.jib.holding, self.winch.holding];
        let pilots: [f64; 4] =
            std::array::from_fn(|i| holdings[i].map_or(pressures[i][1], |cbv| cbv.rest_pilot(pressures[i][1])));
        let state =
            PlantState { q, qd: zero, pressures, drum: 0.0, drum_rate: 0.0, pilots, swash: 0.0, brakes: [0.0; 2] };
        if !state.is_finite() {
            return Err(format!("no finite equilibrium at joints {q:?} rad under the given loads"));
        }
        Ok(state)
    }

    /// The winch's (p_A, p_B) at rest holding the drum torque `torque` (N·m, hoisting positive).
    fn winch_holding(&self, torque: f64) -> (f64, f64) {
        match self.winch_circuit {
            WinchCircuit::Open => {
                let neutral = self.winch.valve.neutral_pressure(self.supply.pressure, self.supply.tank);
                self.winch.holding_pressures(torque, neutral)
            }
            WinchCircuit::Closed => self.winch_pump.holding_pressures(&self.winch, torque),
        }
    }

    /// The tip in W (position, velocity, acceleration) for the state, its evaluation and the deck.
    pub fn tip_in_world(&self, s: &PlantState, e: &Evaluation, ship: &ShipMotion) -> PointMotion {
        self.arm.tip_in_world(ship, &s.q, &s.qd, &e.qdd)
    }

    /// Total hydraulic power drawn from the pump by the four drives (W).
    pub fn pump_power(e: &Evaluation) -> f64 {
        e.rates.iter().map(|r| r.power_in).sum()
    }
}

/// The unit vector of `v`, or zero for a zero vector (no load).
fn direction(v: &Vec3) -> Vec3 {
    let norm = v.norm();
    if norm > 0.0 {
        v / norm
    } else {
        Vec3::zeros()
    }
}

//! The power balance of a general run (friction and leakage on, every drive moving, a 5 t load):
//! what the pump delivers goes into the arm's and the drum's mechanical energy, the oil's stored
//! energy, the losses and the work on the load (H12 extended by the arm's and the drum's
//! equations of motion: Σ τ·q̇ + τ_w·φ̇ = dE_mech/dt − F·v_tip − T·r_d·φ̇ on a still deck).
//!
//! The test integrates the plant's state together with the power integrals by the same RK4
//! substeps as [`CraneParams::advance`] (and checks that its state is `advance`'s, bit for bit).

use super::*;
use crate::hydraulic_crane::plant::{Evaluation, BOOM, JIB, SLEW, STATES, WINCH};
use crate::hydraulics::rig::SpoolProgram;
use crate::hydraulics::Relief;
use crate::integrate::{rk4, substeps};
use crate::math::SVector;

/// The power integrals (J), in the order of the augmented state after the plant's state.
#[derive(Debug, Clone, Copy, Default)]
struct Work {
    /// ∫ p_S·Q_S − p_T·Q_T dt over the four drives.
    pump: f64,
    /// ∫ Δp·Q of the valve edges, their leakage, the counterbalance poppets, the make-up checks
    /// and the motors' leakage.
    throttling: f64,
    /// ∫ Δp·Q of the port reliefs.
    relief: f64,
    /// ∫ friction power of the cylinders' seals and the motors' shafts.
    friction: f64,
    /// ∫ the power compressing the oil, Σ p·(Q_net − dV/dt) (H12's compression term).
    compression: f64,
    /// ∫ −F·v_tip − T·r_d·φ̇ dt: the work the crane does on the load through the rope.
    load: f64,
    /// ∫ F_stop·v dt of the cylinders' end stops (the work they do on the arm).
    stops: f64,
}

const TOTAL: usize = STATES + 7;
type Augmented = SVector<f64, TOTAL>;

fn pack(s: &PlantState, w: &Work) -> Augmented {
    let work = [w.pump, w.throttling, w.relief, w.friction, w.compression, w.load, w.stops];
    Augmented::from_iterator(s.to_array().into_iter().chain(work))
}

fn unpack(x: &Augmented) -> (PlantState, Work) {
    let (plant, w) = x.as_slice().split_at(STATES);
    let state = PlantState::from_slice(plant).unwrap_or_default();
    let work =
        Work { pump: w[0], throttling: w[1], relief: w[2], friction: w[3], compression: w[4], load: w[5], stops: w[6] };
    (state, work)
}

/// H5's relief power (p − p_T)·Q_relief of both chambers of a drive (W).
fn relief_power(relief: &Relief, tank: f64, p: [f64; 2]) -> f64 {
    p.iter().map(|&p| (p - tank) * relief.relief_flow(p)).sum()
}

/// The powers (W) at one instant, in [`Work`]'s order.
fn powers(params: &CraneParams, s: &PlantState, e: &Evaluation, loads: &Loads) -> Work {
    let reliefs = [&params.slew.relief, &params.boom.relief, &params.jib.relief, &params.winch.relief];
    let tank = params.supply.tank;
    let mut w = Work::default();
    for (index, (rates, relief)) in e.rates.iter().zip(reliefs).enumerate() {
        let relief = relief_power(relief, tank, s.pressures[index]);
        w.pump += rates.power_in;
        w.relief += relief;
        w.throttling += rates.throttle_loss - relief;
        w.friction += rates.friction_loss;
        w.compression += rates.compression_power;
    }
    for (index, drive) in [(BOOM, &params.boom), (JIB, &params.jib)] {
        let d = &e.drives[index];
        w.stops += drive.cylinder.stop_force(d.pos, d.vel) * d.vel;
    }
    let tip = params.arm.tip_in_world(&loads.ship, &s.q, &s.qd, &e.qdd);
    w.load = -e.cable_force.dot(&tip.vel) - e.tension * params.drum_radius * s.drum_rate;
    w
}

fn derivative(params: &CraneParams, x: &Augmented, spools: &Spools, loads: &Loads) -> Augmented {
    let (s, _) = unpack(x);
    let e = params.evaluate(&s, spools, loads);
    pack(&CraneParams::rate(&s, &e), &powers(params, &s, &e, loads))
}

/// Mechanical energy on the still deck (J): the arm's (Siciliano et al. 2009, eqs. 7.13–7.14,
/// 7.28) and the drum's ½·J_w·φ̇².
fn mechanical(params: &CraneParams, s: &PlantState) -> f64 {
    let (kinetic, potential) = params.arm.energy(&s.q, &s.qd);
    kinetic + potential + 0.5 * params.winch_inertia * s.drum_rate * s.drum_rate
}

/// H10 over the eight chambers (J).
fn stored(params: &CraneParams, s: &PlantState, spools: &Spools, loads: &Loads) -> f64 {
    let d = params.evaluate(s, spools, loads).drives;
    let oil = &params.oil;
    params.slew.stored_energy(oil, &d[SLEW])
        + params.boom.stored_energy(oil, &d[BOOM])
        + params.jib.stored_energy(oil, &d[JIB])
        + params.winch.stored_energy(oil, &d[WINCH])
}

/// Breakpoints [t (s), u] of each drive over the 20 s run: slew out and back, boom up and down,
/// jib out and in, hoist and lower; every move ramps through the deadband.
fn programs() -> [SpoolProgram; 4] {
    let program = |points: &[[f64; 2]]| match SpoolProgram::new(points) {
        Ok(p) => p,
        Err(e) => panic!("{e}"),
    };
    [
        program(&[[1.0, 0.0], [2.0, 0.5], [5.0, 0.5], [6.0, 0.0], [8.0, 0.0], [9.0, -0.5], [11.0, -0.5], [12.0, 0.0]]),
        program(&[
            [2.0, 0.0],
            [3.0, 0.6],
            [6.0, 0.6],
            [7.0, 0.0],
            [10.0, 0.0],
            [11.0, -0.5],
            [14.0, -0.5],
            [15.0, 0.0],
        ]),
        program(&[
            [3.0, 0.0],
            [4.0, 0.6],
            [7.0, 0.6],
            [8.0, 0.0],
            [11.0, 0.0],
            [12.0, -0.6],
            [15.0, -0.6],
            [16.0, 0.0],
        ]),
        program(&[
            [1.0, 0.0],
            [2.0, -0.6],
            [6.0, -0.6],
            [7.0, 0.0],
            [12.0, 0.0],
            [13.0, 0.6],
            [16.0, 0.6],
            [17.0, 0.0],
        ]),
    ]
}

#[test]
fn the_pump_energy_balances_energies_losses_and_the_load_work() {
    let params = CraneParams::DEFAULT;
    let loads = hanging(5.0);
    let start = at_rest(&params, &loads);
    let programs = programs();
    let spools_at = |t: f64| Spools(programs.each_ref().map(|p| p.at(t)));
    let steps = (20.0 / STEP).round() as usize;
    let n = substeps(STEP);
    let dt = STEP / n as f64;
    let (mut x, mut plain) = (pack(&start, &Work::default()), start);
    let mut identical = true;
    // The largest excursion of each joint and of the drum from the start.
    let mut excursion = [0.0f64; 4];
    for k in 0..steps {
        let spools = spools_at(k as f64 * STEP);
        for _ in 0..n {
            x = rk4(&x, 0.0, dt, |_, x| derivative(&params, x, &spools, &loads));
        }
        plain = params.advance(&plain, &spools, &loads, STEP);
        identical &= unpack(&x).0 == plain;
        let moved = [plain.q[0] - start.q[0], plain.q[1] - start.q[1], plain.q[2] - start.q[2], plain.drum];
        excursion = std::array::from_fn(|i| excursion[i].max(moved[i].abs()));
    }
    let (end, w) = unpack(&x);
    let last = spools_at(20.0);
    let d_mech = mechanical(&params, &end) - mechanical(&params, &start);
    let d_stored = stored(&params, &end, &last, &loads) - stored(&params, &start, &Spools::default(), &loads);
    let losses = w.throttling + w.relief + w.friction;
    let accounted = d_mech + d_stored + losses + w.load - w.stops;
    let residual = (w.pump - accounted) / w.pump;
    let with_compression = (w.pump - (d_mech + w.compression + losses + w.load - w.stops)) / w.pump;
    println!(
        "power balance, 20 s: pump {:.1} kJ = Δmech {:.1} + Δstored (H10) {:.2} + throttling {:.1} + relief {:.3} + \
         friction {:.2} + load {:.1} − stops {:.3} kJ; residual {residual:+.2e} of the pump energy \
         ({with_compression:+.2e} with ∫compression {:.2} kJ); largest excursions (slew, boom, jib, drum) \
         {excursion:.3?} rad",
        w.pump / 1e3,
        d_mech / 1e3,
        d_stored / 1e3,
        w.throttling / 1e3,
        w.relief / 1e3,
        w.friction / 1e3,
        w.load / 1e3,
        w.stops / 1e3,
        w.compression / 1e3,
    );
    assert!(identical, "the augmented integration left CraneParams::advance's path");
    assert!(end.is_finite());
    assert!(residual.abs() <= 0.01 && with_compression.abs() <= 0.01);
    // Every drive moved (by more than 0.05 rad): the balance is not that of a crane at rest.
    assert!(excursion.iter().all(|&e| e > 0.05), "excursions {excursion:?} rad");
}

//! Verification of the hydraulic drives against closed forms (H1, H2, H6, H11, H13), the power
//! balance (H12), holding and relief behaviour; the closed circuit (H15–H17).

use super::orifice::{flow_function, port_flow};
use super::rig::{Rig, Sample, SpoolProgram};
use super::*;
use crate::hydraulic_crane::plant::CraneParams;
use crate::integrate::rk4;
use nalgebra::SVector;

fn centred() -> SpoolProgram {
    SpoolProgram::new(&[[0.0, 0.0]]).unwrap_or_default()
}

/// A rig with closed chambers: no counterbalance valve, no leakage, no friction.
fn closed_rig(mass: f64) -> Rig {
    let mut rig = Rig { mass, ..Rig::DEFAULT };
    rig.drive.holding = None;
    rig.drive.valve.leak_supply = 0.0;
    rig.drive.valve.leak_tank = 0.0;
    rig.drive.cylinder.viscous = 0.0;
    rig.drive.cylinder.coulomb = 0.0;
    rig
}

fn run(rig: &Rig, program: &SpoolProgram, initial: DriveState, duration: f64) -> Vec<Sample> {
    match rig.simulate(program, initial, duration, 1) {
        Ok(samples) => samples,
        Err(e) => panic!("rig refused: {e}"),
    }
}

fn last(samples: &[Sample]) -> Sample {
    *samples.last().expect("at least the initial sample")
}

/// Frequency (rad/s) from the zero crossings of the velocity (linearly interpolated).
fn frequency_from_crossings(samples: &[Sample]) -> f64 {
    let crossings: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].state.vel < 0.0 && w[1].state.vel >= 0.0 || w[0].state.vel > 0.0 && w[1].state.vel <= 0.0)
        .map(|w| w[0].t + (w[1].t - w[0].t) * w[0].state.vel / (w[0].state.vel - w[1].state.vel))
        .collect();
    assert!(crossings.len() > 10, "only {} crossings", crossings.len());
    let (first, end) = (crossings[1], crossings[crossings.len() - 1]);
    let half_periods = (crossings.len() - 2) as f64;
    std::f64::consts::PI * half_periods / (end - first)
}

#[test]
fn h1_opening_has_the_deadband_and_is_clamped() {
    let valve = Valve::DEFAULT;
    assert_eq!(valve.opening(0.05), 0.0);
    assert_eq!(valve.opening(-0.1), 0.0);
    assert!((valve.opening(0.55) - 0.5).abs() < 1e-15);
    assert!((valve.opening(-0.55) + 0.5).abs() < 1e-15);
    assert_eq!(valve.opening(3.0), 1.0);
    assert_eq!(valve.opening(-3.0), -1.0);
    assert_eq!(valve.opening(f64::NAN), 0.0);
}

#[test]
fn h2_is_turbulent_far_from_zero_and_linear_near_it() {
    let dp_t = 1e5;
    let rel = (flow_function(1e7, dp_t) - 1e7f64.sqrt()) / 1e7f64.sqrt();
    assert!(rel.abs() < 1e-4, "φ(10 MPa)/√Δp − 1 = {rel}");
    assert!((flow_function(-1e7, dp_t) + flow_function(1e7, dp_t)).abs() < 1e-12);
    let slope = flow_function(1.0, dp_t) / 1.0;
    assert!((slope - dp_t.powf(-0.5)).abs() / slope < 1e-9, "slope {slope}");
    // The valve passes its rating: K·φ(1 MPa) within 0.25 % of 240 L/min (the transition).
    let valve = Valve::DEFAULT;
    let q = valve.coefficient() * flow_function(1e6, valve.transition);
    assert!((q / valve.rated_flow - 1.0).abs() < 3e-3, "q = {q}");
}

#[test]
fn h6_the_junction_conserves_flow_and_holds_when_closed() {
    let valve = Valve::DEFAULT;
    let cbv = Counterbalance::DEFAULT;
    let supply = Supply::DEFAULT;
    let [s_a, t_a, _, _] = valve.edges(-0.5);
    let p_a = 12e6;
    for pilot in [0.0, 5e6, 11e6, 25e6] {
        let k = cbv.conductance(p_a, pilot);
        let port = port_flow(&s_a, &t_a, supply.pressure, supply.tank, Some(k), p_a, valve.transition);
        let valve_side = port.from_supply - port.to_tank;
        let poppet = -k * flow_function(p_a - port.line_pressure, valve.transition);
        assert!(port.line_pressure < p_a);
        // H6: the poppet cracks at (p_set − p_A)/R = 8.13 MPa under 12 MPa.
        if pilot <= cbv.cracking_pilot(p_a) {
            assert_eq!(port.into_chamber, 0.0, "a closed poppet is leak-free");
        } else {
            assert!((valve_side - poppet).abs() <= 1e-9 * poppet.abs(), "{valve_side} vs {poppet}");
            assert!((port.into_chamber - poppet).abs() <= 1e-12 * poppet.abs());
        }
    }
    // Fully open against the same valve path: the turbulent series law bounds the exact flow.
    let port =
        port_flow(&s_a, &t_a, supply.pressure, supply.tank, Some(cbv.conductance(p_a, 25e6)), p_a, valve.transition);
    let (k1, k2) = (valve.coefficient() * 0.5, cbv.conductance(p_a, 25e6));
    let series = k1 * k2 / (k1 * k1 + k2 * k2).sqrt() * p_a.sqrt();
    assert!((-port.into_chamber / series - 1.0).abs() < 0.01, "{} vs {series}", -port.into_chamber);
}

#[test]
fn h6b_the_poppet_opens_on_the_lagged_pilot_pressure_not_on_p_b() {
    let (oil, supply) = (Oil::DEFAULT, Supply::DEFAULT);
    let drive = CylinderDrive::DEFAULT;
    let tau = drive.holding.map_or(0.0, |cbv| cbv.pilot_lag);
    assert_eq!(tau, 0.05);
    // Lowering (u < 0 feeds B): p_B has risen to the full pilot pressure, π has not yet.
    let rising = DriveState { pos: 0.6, vel: 0.0, p_a: 8e6, p_b: 20e6, pilot: 0.0 };
    let r = drive.rates(&oil, &supply, -0.5, &rising);
    assert_eq!(r.cbv_opening, 0.0);
    assert_eq!(r.q_a, 0.0, "a closed poppet passes nothing out of A");
    assert_eq!(r.dpilot, 20e6 / tau);
    // p_B has fallen, π is still high: the poppet stays open.
    let falling = DriveState { p_b: 0.0, pilot: 20e6, ..rising };
    let r = drive.rates(&oil, &supply, -0.5, &falling);
    assert_eq!(r.cbv_opening, 1.0);
    assert!(r.q_a < 0.0);
    assert_eq!(r.dpilot, -20e6 / tau);
    // Without the lag the poppet follows p_B and π is not integrated.
    let mut instant = drive;
    instant.holding = drive.holding.map(|cbv| Counterbalance { pilot_lag: 0.0, ..cbv });
    let r = instant.rates(&oil, &supply, -0.5, &rising);
    assert_eq!((r.cbv_opening, r.dpilot), (1.0, 0.0));
    // A step of p_B: RK4 at 1 ms follows the closed form π = p_B·(1 − e^(−t/τ)) (the lag alone).
    let cbv = Counterbalance::DEFAULT;
    let mut pi = 0.0;
    for _ in 0..50 {
        pi = rk4(&SVector::<f64, 1>::new(pi), 0.0, 1e-3, |_, y| SVector::<f64, 1>::new(cbv.pilot_rate(20e6, y[0])))[0];
    }
    let exact = 20e6 * (1.0 - (-1.0f64).exp());
    println!("H6b: π after τ = {:.6} MPa, closed form {:.6} MPa", pi * 1e-6, exact * 1e-6);
    assert!((pi - exact).abs() < 1e-6 * exact);
    let negative = Counterbalance { pilot_lag: -0.01, ..Counterbalance::DEFAULT };
    assert!(negative.validate().is_err_and(|e| e.contains("pilot_lag")));
}

#[test]
fn h6c_a_commanded_pilot_opens_with_the_lowering_command_not_with_p_b() {
    let (oil, supply) = (Oil::DEFAULT, Supply::DEFAULT);
    let cbv = Counterbalance { command_pilot: 20e6, ..Counterbalance::PILOT_OPERATED };
    let drive = CylinderDrive { holding: Some(cbv), ..CylinderDrive::DEFAULT };
    // π* = p_cmd·max(0, −u): lowering commands only, whatever p_B; NaN counts as centred.
    for (p_b, spool, target) in [
        (20e6, 0.0, 0.0),
        (0.0, -0.5, 10e6),
        (0.0, -1.0, 20e6),
        (0.0, -2.0, 20e6),
        (25e6, 0.7, 0.0),
        (5e6, f64::NAN, 0.0),
    ] {
        assert_eq!(cbv.pilot_target(p_b, spool), target, "p_B {p_b}, u {spool}");
    }
    assert_eq!(cbv.rest_pilot(9e6), 0.0);
    // At rest with the pilot settled: centred, the poppet holds the load even with p_B at the
    // supply; at u = −0.55 the pilot is 11 MPa, the opening (11 − 2)/18 = 0.5 with p_B at tank.
    let held = DriveState { pos: 0.6, vel: 0.0, p_a: 15e6, p_b: 28e6, pilot: 0.0 };
    let r = drive.rates(&oil, &supply, 0.0, &held);
    assert_eq!((r.cbv_opening, r.q_a, r.dpilot), (0.0, 0.0, 0.0));
    let lowering = DriveState { p_b: 0.0, pilot: 11e6, ..held };
    let r = drive.rates(&oil, &supply, -0.55, &lowering);
    assert!((r.cbv_opening - 0.5).abs() < 1e-12, "{}", r.cbv_opening);
    assert!(r.q_a < 0.0 && r.dpilot.abs() < 1e-6, "{} {}", r.q_a, r.dpilot);
    // The hydraulic pilot of the same valve would follow p_B = 0 and close it.
    let hydraulic = CylinderDrive { holding: Some(Counterbalance::PILOT_OPERATED), ..drive };
    assert!(hydraulic.rates(&oil, &supply, -0.55, &lowering).dpilot < 0.0);
    // A pilot that full command cannot raise to the setting is refused, as a negative one.
    let weak = Counterbalance { command_pilot: 1.5e6, ..cbv };
    assert!(weak.validate().is_err_and(|e| e.contains("command_pilot")));
    let negative = Counterbalance { command_pilot: -1.0, ..cbv };
    assert!(negative.validate().is_err_and(|e| e.contains("command_pilot")));
}

#[test]
fn h13_natural_frequency_matches_at_three_strokes() {
    let rig = closed_rig(1e5);
    for x in [0.2, 0.8, 1.4] {
        let mut initial = rig.holding_state(x, 2e6);
        initial.p_a += 2e5;
        let samples = run(&rig, &centred(), initial, 1.0);
        let measured = frequency_from_crossings(&samples);
        let expected = rig.drive.hydraulic_frequency(&rig.oil, x, rig.mass);
        let error = measured / expected - 1.0;
        println!("H13 at x = {x} m: measured {measured:.3} rad/s, ω_h = {expected:.3} rad/s, error {error:+.2e}");
        assert!(error.abs() < 0.02);
    }
}

fn holding_run(with_cbv: bool) -> (f64, f64, f64) {
    let mut rig = Rig { mass: 1.5e5, ..Rig::DEFAULT };
    if !with_cbv {
        rig.drive.holding = None;
    }
    let neutral = rig.drive.valve.neutral_pressure(rig.supply.pressure, rig.supply.tank);
    let initial = rig.holding_state(0.8, neutral);
    let end = last(&run(&rig, &centred(), initial, 60.0));
    let (a_a, a_b) = rig.drive.areas();
    let balance = (end.state.p_a * a_a - end.state.p_b * a_b) / (rig.mass * rig.gravity) - 1.0;
    (end.state.pos - initial.pos, balance, end.state.p_a)
}

#[test]
fn a_centred_valve_with_the_counterbalance_valve_holds_the_load() {
    let (drift, balance, p_a) = holding_run(true);
    let (drift_free, _, _) = holding_run(false);
    println!(
        "holding 150 t for 60 s: drift {:.4} mm with the CBV (p_A = {:.3} MPa, force balance {balance:+.2e}), \
         {:.3} mm without",
        drift * 1e3,
        p_a * 1e-6,
        drift_free * 1e3
    );
    assert!(drift.abs() <= 1e-3);
    assert!(balance.abs() <= 1e-3);
    assert!(drift_free.abs() > 4e-3 && drift_free.abs() > 10.0 * drift.abs());
}

#[test]
fn h5_the_relief_cracks_opens_along_its_override_and_then_is_an_orifice() {
    let relief = Relief::DEFAULT;
    let (set, g, rated) = (relief.pressure, relief.gain, relief.rated_flow);
    let full = relief.full_open_pressure();
    assert_eq!(full, set + rated / g);
    assert_eq!(relief.relief_flow(set), 0.0);
    assert_eq!(relief.relief_flow(set - 1e6), 0.0);
    // The override slope up to the rated flow at p_full (31 MPa with the default) …
    assert!((relief.relief_flow(set + 0.5e6) - 0.5e6 * g).abs() < 1e-15);
    assert!((relief.relief_flow(full) / rated - 1.0).abs() < 1e-12);
    // … then the fully open orifice: twice the rated flow at four times p_full.
    assert!((relief.relief_flow(4.0 * full) / (2.0 * rated) - 1.0).abs() < 1e-12);
    for q in [0.3 * rated, rated, 1.5 * rated, 3.0 * rated] {
        let p = set + relief.override_at(q);
        assert!((relief.relief_flow(p) / q - 1.0).abs() < 1e-12, "override_at inverts the law at {q}");
    }
    // Non-decreasing, continuous, slope at most G: β·G·dt/V_dead at the 1 ms substep stays below
    // RK4's limit of 2.78.
    let (mut last, mut steepest) = (0.0, 0.0f64);
    for k in 0..=4000 {
        let p = set - 1e6 + k as f64 * 1e4;
        let q = relief.relief_flow(p);
        assert!(q >= last && q - last <= g * 1e4 * (1.0 + 1e-9));
        steepest = steepest.max((q - last) / 1e4);
        last = q;
    }
    let stiffness = Oil::DEFAULT.bulk_modulus * steepest * 1e-3 / Cylinder::DEFAULT.dead_volume;
    println!("H5: p_full {:.3} MPa, steepest dQ/dp {steepest:.3e}, β·(dQ/dp)·dt/V = {stiffness:.3}", full * 1e-6);
    assert!(stiffness < 2.78);
}

#[test]
fn an_overloaded_cylinder_sinks_at_the_flow_the_relief_law_gives() {
    // Loads needing 30.5 MPa (on the override slope) to 50 MPa (beyond the rated flow, on the
    // fully open orifice) on the piston side with the valve centred: the cylinder sinks until the
    // relief passes A_A·|v|, at the pressure H5 gives for that flow.
    let rig = Rig::DEFAULT;
    let (a_a, _) = rig.drive.areas();
    let relief = rig.drive.relief;
    for needed in [30.5e6, 36e6, 50e6] {
        let rig = Rig { external_force: -(needed * a_a - rig.mass * rig.gravity), ..rig };
        let samples = run(&rig, &centred(), rig.holding_state(1.5, 0.0), 3.0);
        let end = last(&samples);
        let displaced = -end.state.vel * a_a;
        // Above p_set the load pressure opens the counterbalance valve into the centred valve's
        // line, which leaks C_T·p_A to tank less C_P·(p_S − p_A) from the supply (H3, H6).
        let valve = &rig.drive.valve;
        let p = end.state.p_a;
        let leak = if end.rates.cbv_opening > 0.0 {
            valve.leak_tank * p - valve.leak_supply * (rig.supply.pressure - p)
        } else {
            0.0
        };
        let law = relief.pressure + relief.override_at(displaced - leak);
        println!(
            "overload needing {:.1} MPa: sinks at {:.4} m/s, A_A·|v| = {:.1} L/min (rated {:.0}); p_A {:.3} MPa, \
             H5 at that flow {:.3} MPa; counterbalance opening {:.3}",
            needed * 1e-6,
            -end.state.vel,
            displaced * 6e4,
            relief.rated_flow * 6e4,
            end.state.p_a * 1e-6,
            law * 1e-6,
            end.rates.cbv_opening
        );
        // The relief takes the displaced flow less what the open counterbalance valve leaks.
        assert!((end.rates.relief_flow / displaced - 1.0).abs() < 0.02, "{} vs {displaced}", end.rates.relief_flow);
        assert!((end.state.p_a / law - 1.0).abs() < 2e-3, "p_A {} vs the law's {law}", end.state.p_a);
    }
}

#[test]
fn an_overload_is_relieved_and_a_stall_stays_below_the_relief() {
    let mut rig = Rig::DEFAULT;
    let (a_a, _) = rig.drive.areas();
    // With the rod side at tank pressure (it empties towards the neutral valve and then cavitates
    // to the make-up), the load needs 30.5 MPa on the piston side.
    let needed = 30.5e6;
    rig.external_force = -(needed * a_a - rig.mass * rig.gravity);
    let samples = run(&rig, &centred(), rig.holding_state(1.0, 0.0), 2.0);
    let end = last(&samples);
    let p_max = samples.iter().map(|s| s.state.p_a).fold(f64::MIN, f64::max);
    let limit = rig.drive.relief.pressure + rig.drive.relief.override_at(rig.drive.valve.rated_flow);
    let displaced = -end.state.vel * a_a;
    println!(
        "overload needing {:.1} MPa: p_A max {:.3} MPa (limit {:.1}), relief {:.4e} m³/s vs A_A·|v| {:.4e}",
        needed * 1e-6,
        p_max * 1e-6,
        limit * 1e-6,
        end.rates.relief_flow,
        displaced
    );
    assert!(p_max <= limit);
    assert!(end.state.vel < -1e-3 && (end.rates.relief_flow / displaced - 1.0).abs() < 0.01);
    assert!(samples.iter().all(|s| s.state.p_b > -0.5e6), "make-up keeps the rod side near tank pressure");

    let rig = Rig::DEFAULT;
    let full = SpoolProgram::new(&[[0.0, 1.0]]).unwrap_or_default();
    let samples = run(&rig, &full, rig.holding_state(1.5, 1.3e6), 10.0);
    let end = last(&samples);
    let p_max = samples.iter().map(|s| s.state.p_a.max(s.state.p_b)).fold(f64::MIN, f64::max);
    let stroke = rig.drive.cylinder.stroke;
    println!(
        "stall at the end stop: p_A max {:.3} MPa, x = {:.5} m, relief {:.2e} m³/s",
        p_max * 1e-6,
        end.state.pos,
        end.rates.relief_flow
    );
    assert!(p_max <= rig.supply.pressure + 1e3 && end.rates.relief_flow == 0.0);
    assert!(end.state.pos > stroke && end.state.pos < stroke + 5e-3 && end.state.vel.abs() < 1e-5);
}

#[test]
fn h11_energy_is_conserved_with_closed_chambers() {
    let rig = closed_rig(1e5);
    let mut initial = rig.holding_state(0.8, 2e6);
    initial.p_a += 5e5;
    let (v_a0, v_b0) = rig.drive.volumes(initial.pos);
    let energy = |s: &DriveState| {
        let (v_a, v_b) = rig.drive.volumes(s.pos);
        rig.mechanical_energy(s)
            + rig.oil.closed_chamber_work(initial.p_a, v_a0, v_a)
            + rig.oil.closed_chamber_work(initial.p_b, v_b0, v_b)
    };
    let e0 = energy(&initial);
    let samples = run(&rig, &centred(), initial, 60.0);
    let worst = samples.iter().map(|s| (energy(&s.state) - e0).abs() / e0.abs()).fold(0.0, f64::max);
    let p_error = samples
        .iter()
        .map(|s| {
            let (v_a, _) = rig.drive.volumes(s.state.pos);
            (s.state.p_a - (initial.p_a - rig.oil.bulk_modulus * (v_a / v_a0).ln())).abs()
        })
        .fold(0.0, f64::max);
    println!(
        "closed chambers, 60 s: max |E − E0|/E0 = {worst:.2e} (E0 = {e0:.1} J), max |p_A − H11| = {p_error:.2e} Pa"
    );
    assert!(worst <= 1e-6);
}

/// The run of the SciPy comparison: extend, hold, retract, hold, through the deadband.
pub(crate) const SEQUENCE: [[f64; 2]; 10] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [2.0, 0.6],
    [5.0, 0.6],
    [6.0, 0.0],
    [9.0, 0.0],
    [10.0, -0.5],
    [13.0, -0.5],
    [14.0, 0.0],
    [20.0, 0.0],
];

#[test]
fn h12_the_pump_power_balances_the_energies_and_losses() {
    let rig = Rig::DEFAULT;
    let program = SpoolProgram::new(&SEQUENCE).unwrap_or_default();
    let neutral = rig.drive.valve.neutral_pressure(rig.supply.pressure, rig.supply.tank);
    let initial = rig.holding_state(0.6, neutral);
    let samples = run(&rig, &program, initial, 20.0);
    let (start, end) = (samples[0], last(&samples));
    let e = end.energy;
    let mechanical = e.mechanical - start.energy.mechanical;
    let accounted = mechanical - e.external - e.stops + e.compression + e.throttling + e.friction;
    let residual = (e.pump - accounted) / e.pump;
    let stored = e.stored - start.energy.stored;
    println!(
        "20 s run: pump {:.1} J = Δmech {:.1} + compression {:.1} (ΔH10 {:.1}) + throttling {:.1} + friction {:.1} \
         − stops {:.2}; residual {residual:+.2e} of the pump energy; x {:.4} → {:.4} m",
        e.pump, mechanical, e.compression, stored, e.throttling, e.friction, e.stops, start.state.pos, end.state.pos
    );
    let residual_h10 = (e.pump - (accounted - e.compression + stored)) / e.pump;
    println!("with ΔH10 in place of the compression work: residual {residual_h10:+.2e}");
    assert!(residual.abs() < 0.01 && residual_h10.abs() < 0.01);
    assert!((end.state.pos - initial.pos).abs() > 0.01);
}

/// A winch on a drum: output inertia J (kg·m²) and a constant load torque (N·m) at the output.
fn winch_run(drive: &MotorDrive, inertia: f64, load_torque: f64, initial: DriveState, duration: f64) -> DriveState {
    let (oil, supply, dt) = (Oil::DEFAULT, Supply::DEFAULT, 1e-3);
    let state = |y: &SVector<f64, 5>| DriveState { pos: y[0], vel: y[1], p_a: y[2], p_b: y[3], pilot: y[4] };
    let mut y = SVector::<f64, 5>::from([initial.pos, initial.vel, initial.p_a, initial.p_b, initial.pilot]);
    for i in 0..(duration / dt).round() as usize {
        y = rk4(&y, i as f64 * dt, dt, |_, y| {
            let s = state(y);
            let r = drive.rates(&oil, &supply, 0.0, &s);
            SVector::<f64, 5>::from([s.vel, (r.force + load_torque) / inertia, r.dp_a, r.dp_b, r.dpilot])
        });
    }
    state(&y)
}

#[test]
fn the_winch_holds_on_its_counterbalance_valve_and_relieves_an_overload() {
    let (mass, radius, drum) = (1e4, 0.25, 500.0);
    let inertia = drum + mass * radius * radius;
    let load = -mass * crate::math::STANDARD_GRAVITY * radius;
    let mut drive = MotorDrive { coulomb: 0.0, viscous: 0.0, ..MotorDrive::WINCH_DEFAULT };
    let supply = Supply::DEFAULT;
    let neutral = drive.valve.neutral_pressure(supply.pressure, supply.tank);
    let (p_a, p_b) = drive.holding_pressures(-load, neutral);
    let initial = DriveState { pos: 0.0, vel: 0.0, p_a, p_b, pilot: p_b };
    let held = winch_run(&drive, inertia, load, initial, 60.0);
    let creep = -drive.leakage * (p_a - p_b) / (drive.displacement * drive.gear);
    let drift = held.pos * radius;
    drive.holding = None;
    let free = winch_run(&drive, inertia, load, initial, 60.0);
    println!(
        "winch holding 10 t for 60 s: rope {:.2} mm with the CBV (motor-leak creep {:.4e} rad/s, closed form \
         {creep:.4e}), {:.1} mm without",
        drift * 1e3,
        held.vel,
        free.pos * radius * 1e3
    );
    assert!((held.vel / creep - 1.0).abs() < 0.02);
    assert!(free.pos.abs() > 5.0 * held.pos.abs());

    let drive = MotorDrive::WINCH_DEFAULT;
    let overload = -31e6 * drive.displacement * drive.gear;
    let start = DriveState { p_a: 31e6, p_b: 0.0, pilot: 0.0, ..initial };
    let end = winch_run(&drive, inertia, overload, start, 2.0);
    let rates = drive.rates(&Oil::DEFAULT, &supply, 0.0, &end);
    let through = -drive.displacement * drive.gear * end.vel - drive.leakage * (end.p_a - end.p_b);
    println!(
        "winch overload needing 31 MPa over p_B = 0: p_A {:.3} MPa, relief {:.4e} m³/s vs motor flow {through:.4e}",
        end.p_a * 1e-6,
        rates.relief_flow
    );
    assert!(end.p_a <= drive.relief.pressure + drive.relief.override_at(drive.valve.rated_flow));
    assert!(end.vel < 0.0 && (rates.relief_flow / through - 1.0).abs() < 0.01);
}

#[test]
fn hydraulic_frequencies_of_the_crane_drives_stay_far_below_rk4s_limit() {
    let oil = Oil::DEFAULT;
    let cylinder = CylinderDrive::DEFAULT;
    let dt = crate::integrate::MAX_SUBSTEP;
    let stroke = cylinder.cylinder.stroke;
    let worst = |mass: f64| {
        (0..=32).map(|i| cylinder.hydraulic_frequency(&oil, stroke * i as f64 / 32.0, mass)).fold(0.0, f64::max)
    };
    for (name, inertia) in [("boom", 1.5e5), ("jib", 1e4)] {
        for lever in [0.5, 1.0] {
            let mass = inertia / (lever * lever);
            let mid = cylinder.hydraulic_frequency(&oil, 0.5 * stroke, mass);
            let w = worst(mass);
            println!("{name} (J = {inertia:.1e} kg·m², lever {lever} m): ω_h = {mid:.1} rad/s mid-stroke, {w:.1} max, ω_h·dt ≤ {:.3}", w * dt);
            // Well inside RK4's stability limit (2.8) and accurate: ω·dt ≤ 0.6 keeps RK4's
            // amplitude error per step below (ω·dt)⁶/72 = 7e-4.
            assert!(w * dt < 0.6);
        }
    }
    let slew = MotorDrive::SLEW_DEFAULT.hydraulic_frequency(&oil, 1.5e5);
    let winch = MotorDrive::WINCH_DEFAULT.hydraulic_frequency(&oil, 500.0 + 1e4 * 0.25 * 0.25);
    println!("slew (1.5e5 kg·m²): ω_h = {slew:.1} rad/s; winch (drum 500 kg·m² + 10 t on 0.25 m): {winch:.1} rad/s");
    assert!(slew * dt < 0.5 && winch * dt < 0.5);
}

#[test]
fn invalid_configurations_are_refused_with_their_name() {
    let supply = Supply::DEFAULT;
    let mut drive = CylinderDrive::DEFAULT;
    assert!(drive.validate(&supply).is_ok());
    assert!(MotorDrive::WINCH_DEFAULT.validate(&supply).is_ok());
    drive.cylinder.rod = 0.5;
    assert!(drive.validate(&supply).is_err_and(|e| e.contains("rod")));
    let mut drive = CylinderDrive::DEFAULT;
    drive.valve.leak_supply = drive.valve.leak_tank;
    assert!(drive.validate(&supply).is_err_and(|e| e.contains("cracking pilot")));
    let mut drive = CylinderDrive::DEFAULT;
    drive.valve.deadband = 1.0;
    assert!(drive.validate(&supply).is_err_and(|e| e.contains("deadband")));
    let motor = MotorDrive { displacement: f64::NAN, ..MotorDrive::SLEW_DEFAULT };
    assert!(motor.validate(&supply).is_err_and(|e| e.contains("displacement")));
    assert!(SpoolProgram::new(&[[1.0, 0.0], [0.5, 0.0]]).is_err());
}

#[test]
fn rates_stay_finite_over_and_beyond_the_working_range() {
    let (oil, supply) = (Oil::DEFAULT, Supply::DEFAULT);
    let cylinder = CylinderDrive::DEFAULT;
    let winch = MotorDrive::WINCH_DEFAULT;
    let mut count = 0;
    for pos in [-0.1, 0.0, 0.8, 1.6, 1.9, 5.0] {
        for vel in [-1.0, 0.0, 0.3] {
            for p_a in [-2e6, 0.0, 1e6, 15e6, 35e6] {
                for p_b in [-2e6, 0.0, 3e6, 25e6, 40e6] {
                    for spool in [-2.0, -0.5, 0.0, 0.05, 0.7, f64::NAN] {
                        let s = DriveState { pos, vel, p_a, p_b, pilot: p_b };
                        for r in [cylinder.rates(&oil, &supply, spool, &s), winch.rates(&oil, &supply, spool, &s)] {
                            let values = [r.dp_a, r.dp_b, r.force, r.q_a, r.q_b, r.power_in, r.throttle_loss];
                            assert!(values.iter().all(|v| v.is_finite()), "{s:?} u = {spool}: {r:?}");
                            assert!(r.throttle_loss >= -1e-9 * r.power_in.abs().max(1.0), "{s:?}: {r:?}");
                            count += 1;
                        }
                    }
                }
            }
        }
    }
    assert_eq!(count, 2 * 6 * 3 * 5 * 5 * 6);
}

// The closed circuit (H15–H17): the winch motor on its over-centre pump.

/// The state of a closed-circuit winch run: the drive, ε, and the energies integrated with it
/// (pump, throttling, friction, compression, the load's work on the drum) (J).
#[derive(Debug, Clone, Copy, Default)]
struct PumpRun {
    drive: DriveState,
    swash: f64,
    pump: f64,
    throttling: f64,
    friction: f64,
    compression: f64,
    load_work: f64,
    /// ∫|pump power| dt (J): the scale of the balance when the load drives the pump back.
    pump_gross: f64,
    /// The lowest line pressure seen (Pa).
    lowest: f64,
}

/// Integrates the pump-and-motor drive on an output inertia `inertia` (kg·m²) with a constant
/// load torque (N·m, positive hoisting) and the command `spool(t)`, RK4 at 1 ms; `locked` holds
/// the output still (a stalled drum).
fn pump_run(
    pump: &ClosedCircuit,
    motor: &MotorDrive,
    (inertia, load_torque, locked): (f64, f64, bool),
    spool: impl Fn(f64) -> f64,
    start: PumpRun,
    duration: f64,
) -> PumpRun {
    let (oil, dt) = (Oil::DEFAULT, 1e-3);
    let unpack = |y: &SVector<f64, 11>| PumpRun {
        drive: DriveState { pos: y[0], vel: y[1], p_a: y[2], p_b: y[3], pilot: 0.0 },
        swash: y[4],
        pump: y[5],
        throttling: y[6],
        friction: y[7],
        compression: y[8],
        load_work: y[9],
        pump_gross: y[10],
        lowest: 0.0,
    };
    let d = start.drive;
    let mut y = SVector::<f64, 11>::from([
        d.pos,
        d.vel,
        d.p_a,
        d.p_b,
        start.swash,
        start.pump,
        start.throttling,
        start.friction,
        start.compression,
        start.load_work,
        start.pump_gross,
    ]);
    let mut lowest = start.drive.p_a.min(start.drive.p_b);
    for i in 0..(duration / dt).round() as usize {
        y = rk4(&y, i as f64 * dt, dt, |t, y| {
            let s = unpack(y);
            let r = pump.rates(motor, &oil, spool(t), s.swash, &s.drive);
            let acc = if locked { 0.0 } else { (r.force + load_torque) / inertia };
            let vel = s.drive.vel;
            SVector::<f64, 11>::from([
                vel,
                acc,
                r.dp_a,
                r.dp_b,
                r.dswash,
                r.power_in,
                r.throttle_loss,
                r.friction_loss,
                r.compression_power,
                load_torque * vel,
                r.power_in.abs(),
            ])
        });
        lowest = lowest.min(y[2].min(y[3]));
    }
    PumpRun { lowest, ..unpack(&y) }
}

/// The 5 t of the pick-and-place tests on the default 0.25 m drum radius: output inertia and load
/// torque (positive hoisting, so the load's is negative).
fn five_tonnes() -> (f64, f64) {
    let (mass, radius) = (5e3, CraneParams::DEFAULT.drum_radius);
    (CraneParams::DEFAULT.winch_inertia + mass * radius * radius, -mass * crate::math::STANDARD_GRAVITY * radius)
}

/// The default pump driving a winch motor with [`five_tonnes`] on the rope.
struct PumpWinch {
    pump: ClosedCircuit,
    motor: MotorDrive,
    /// Output inertia (kg·m²) and load torque (N·m) of [`five_tonnes`].
    inertia: f64,
    load: f64,
    /// The drive at rest holding the load at ε = 0 (H8 with the low line at the charge pressure).
    start: PumpRun,
}

impl PumpWinch {
    fn new(motor: MotorDrive) -> Self {
        let pump = ClosedCircuit::DEFAULT;
        let (inertia, load) = five_tonnes();
        let (p_a, p_b) = pump.holding_pressures(&motor, -load);
        let start = PumpRun { drive: DriveState { p_a, p_b, ..DriveState::default() }, ..PumpRun::default() };
        PumpWinch { pump, motor, inertia, load, start }
    }

    /// The winch motor with viscous friction only, so that steady states have closed forms.
    fn viscous() -> Self {
        PumpWinch::new(MotorDrive { coulomb: 0.0, ..MotorDrive::WINCH_DEFAULT })
    }

    /// [`pump_run`] for `duration` s of the spool program `spool` from `start`, the drum held
    /// where `locked`.
    fn run(&self, spool: impl Fn(f64) -> f64, locked: bool, duration: f64) -> PumpRun {
        pump_run(&self.pump, &self.motor, (self.inertia, self.load, locked), spool, self.start, duration)
    }

    /// C_p + C_m (m³/(s·Pa)): the pump's and the motor's leakage together.
    fn leak(&self) -> f64 {
        self.pump.leakage + self.motor.leakage
    }
}

/// The spool command that gives the swash-plate command `target` through the pump's deadband.
fn pump_spool(pump: &ClosedCircuit, target: f64) -> f64 {
    target.signum() * (pump.deadband + (1.0 - pump.deadband) * target.abs())
}

#[test]
fn h15_the_swash_plate_follows_a_step_as_a_first_order_lag() {
    let winch = PumpWinch::new(MotorDrive::WINCH_DEFAULT);
    let (pump, motor) = (&winch.pump, &winch.motor);
    let target = 0.5;
    let u = pump_spool(pump, target);
    assert!((pump.command(u) - target).abs() < 1e-15 && pump.command(0.5 * pump.deadband) == 0.0);
    let mut worst: f64 = 0.0;
    let mut state = winch.start;
    for k in 1..=40 {
        state = pump_run(pump, motor, (winch.inertia, winch.load, false), |_| u, state, 0.01);
        let t = k as f64 * 0.01;
        let expected = target * (1.0 - (-t / pump.swash_lag).exp());
        worst = worst.max((state.swash - expected).abs());
    }
    println!(
        "H15 step to ε = 0.5 with τ_sw = {} s: worst |ε − 0.5·(1 − e^(−t/τ))| over 0.4 s {worst:.2e}",
        pump.swash_lag
    );
    assert!(worst < 1e-6);
}

#[test]
fn h16_the_rope_runs_at_the_pumps_flow_less_its_leakage() {
    // Viscous friction only, so the steady state has a closed form: with the motor speed ω_m and
    // Δp = p_A − p_B, D·Δp = τ_L/n + b·ω_m (H8 at rest) and D·ω_m = ε·D_p·ω_p − (C_p + C_m)·Δp
    // (H9 and H16 at steady pressures).
    let winch = PumpWinch::viscous();
    let (pump, motor, load, leak) = (&winch.pump, &winch.motor, winch.load, winch.leak());
    let radius = CraneParams::DEFAULT.drum_radius;
    for target in [0.5, -0.3] {
        let u = pump_spool(pump, target);
        let end = winch.run(|_| u, false, 40.0);
        let (d, n, b) = (motor.displacement, motor.gear, motor.viscous);
        let torque = -load / n;
        let q = pump.ideal_flow(target);
        let motor_speed = (q - leak * torque / d) / (d + leak * b / d);
        let dp = (torque + b * motor_speed) / d;
        let efficiency = 1.0 - leak * dp / q;
        let rope = q * efficiency / d / n * radius;
        let measured = end.drive.vel * radius;
        println!(
            "H16 ε = {target}: rope {:.6} m/s hoisting, closed form ε·D_p·ω_p·η_v/D/n·r_d = {rope:.6} m/s \
             (η_v = {efficiency:.4}, Δp {:.3} MPa, measured {:.3} MPa)",
            measured,
            dp * 1e-6,
            (end.drive.p_a - end.drive.p_b) * 1e-6
        );
        assert!((measured / rope - 1.0).abs() < 1e-6);
        assert!(((end.drive.p_a - end.drive.p_b) / dp - 1.0).abs() < 1e-6);
    }
}

#[test]
fn the_pump_holds_a_load_at_zero_displacement_and_creeps_by_its_leakage() {
    let winch = PumpWinch::viscous();
    let (motor, load, leak) = (&winch.motor, winch.load, winch.leak());
    let radius = CraneParams::DEFAULT.drum_radius;
    let end = winch.run(|_| 0.0, false, 40.0);
    let (d, n, b) = (motor.displacement, motor.gear, motor.viscous);
    let static_dp = -load / (n * d);
    let dp = end.drive.p_a - end.drive.p_b;
    // Creep: D·ω_m = −(C_p + C_m)·Δp, Δp = (τ_L/n)/(D + (C_p + C_m)·b/D).
    let creep_dp = (-load / n) / (d + leak * b / d);
    let creep = -leak * creep_dp / d / n * radius;
    let measured = end.drive.vel * radius;
    println!(
        "holding 5 t at ε = 0: Δp {:.4} MPa vs static torque/D {:.4} MPa ({:+.2e}); creep {:.4} mm/s, \
         leakage closed form {:.4} mm/s; p_B {:.3} MPa",
        dp * 1e-6,
        static_dp * 1e-6,
        dp / static_dp - 1.0,
        measured * 1e3,
        creep * 1e3,
        end.drive.p_b * 1e-6
    );
    assert!((dp / static_dp - 1.0).abs() < 1e-3);
    assert!((measured / creep - 1.0).abs() < 1e-4);
    assert!(creep < 0.0 && end.swash == 0.0);
}

#[test]
fn h17_the_cross_port_relief_caps_the_stall_pressure_and_the_charge_keeps_the_low_line_up() {
    let winch = PumpWinch::new(MotorDrive::WINCH_DEFAULT);
    let (pump, motor) = (&winch.pump, &winch.motor);
    let u = pump_spool(pump, 1.0);
    // The drum stalled, the pump at full displacement: at steady pressures the pump's flow
    // goes back through the relief and the leakages, ε·D_p·ω_p = (C_p + C_m)·Δp + G·(Δp − Δp_r).
    let stall = winch.run(|_| u, true, 5.0);
    let (g, set) = (pump.relief.gain, pump.relief.pressure);
    let q = pump.ideal_flow(1.0);
    let expected = (q + g * set) / (pump.leakage + motor.leakage + g);
    let dp = stall.drive.p_a - stall.drive.p_b;
    let cap = set + q / g;
    let margin = q / pump.relief.makeup_gain;
    println!(
        "stall at ε = 1: Δp {:.4} MPa, closed form {:.4} MPa, cap Δp_r + Q/G = {:.4} MPa; p_B {:.4} MPa, \
         lowest line {:.4} MPa (charge {:.1} MPa − check override at full flow {:.3} MPa)",
        dp * 1e-6,
        expected * 1e-6,
        cap * 1e-6,
        stall.drive.p_b * 1e-6,
        stall.lowest * 1e-6,
        pump.charge_pressure * 1e-6,
        margin * 1e-6
    );
    assert!((dp / expected - 1.0).abs() < 1e-6 && dp <= cap);
    assert!(stall.lowest >= pump.charge_pressure - margin);
    assert!(stall.drive.p_b >= pump.charge_pressure - 1e3);

    // Reversals at full displacement with the load swinging the lines: the lower line stays at
    // the charge pressure less the check's override; without the checks it goes far below.
    let reversing = |t: f64| {
        if t < 2.0 {
            -u
        } else if t < 4.0 {
            u
        } else {
            0.0
        }
    };
    let run = winch.run(reversing, false, 6.0);
    let unfed =
        PumpWinch { pump: ClosedCircuit { relief: Relief { makeup_gain: 0.0, ..pump.relief }, ..*pump }, ..winch };
    let without = unfed.run(reversing, false, 6.0);
    println!(
        "reversing at full displacement: lowest line {:.4} MPa with the charge checks, {:.4} MPa without",
        run.lowest * 1e-6,
        without.lowest * 1e-6
    );
    assert!(run.lowest >= pump.charge_pressure - margin);
    assert!(without.lowest < pump.charge_pressure - 2.0 * margin);
}

/// A flushing valve of 10–15 % of the default pump's flow: relief at 2.0 MPa, 1 L/min per 16.7 kPa
/// (G_f = 1e-9 m³/(s·Pa)), 36 L/min at most, the shuttle open from 1.0 to 1.5 MPa of difference.
const FLUSHING: Flushing = Flushing { pressure: 2.0e6, gain: 1e-9, max_flow: 6e-4, shift: 1.0e6, shift_range: 0.5e6 };

#[test]
fn h17b_the_flushing_valve_brings_a_floating_low_line_down_to_the_charge_pressure() {
    // Hoisting 5 t at ε = 0.5 with the low line B started at 8.6 MPa (where the full-scale
    // campaign left it without a flushing valve). At steady state B's flows balance: what the
    // pump draws the motor returns, so the charge check feeds exactly what the flushing valve
    // drains, G_c·(p_c − p_B) = G_f·(p_B − p_f) with the shuttle open, and
    // p_B = (G_c·p_c + G_f·p_f)/(G_c + G_f).
    let mut winch = PumpWinch::viscous();
    let static_dp = winch.start.drive.p_a - winch.start.drive.p_b;
    let floating = DriveState { p_a: 8.6e6 + static_dp, p_b: 8.6e6, ..winch.start.drive };
    winch.start = PumpRun { drive: floating, ..winch.start };
    let u = pump_spool(&winch.pump, 0.5);
    let without = winch.run(|_| u, false, 20.0);
    winch.pump.flushing = Some(FLUSHING);
    let with = winch.run(|_| u, false, 20.0);
    let (g_c, p_c) = (winch.pump.relief.makeup_gain, winch.pump.charge_pressure);
    let expected = (g_c * p_c + FLUSHING.gain * FLUSHING.pressure) / (g_c + FLUSHING.gain);
    let flushed = winch.pump.flushing_flows(with.drive.p_a, with.drive.p_b);
    println!(
        "H17b hoisting 5 t at ε = 0.5 from a low line at 8.6 MPa: after 20 s p_B {:.4} MPa with the flushing valve \
         (closed form {:.4} MPa, flushing {:.1} L/min), {:.3} MPa without",
        with.drive.p_b * 1e-6,
        expected * 1e-6,
        flushed.1 * 6e4,
        without.drive.p_b * 1e-6
    );
    assert!((with.drive.p_b - expected).abs() < 1e-3 * expected);
    assert!(flushed.0 == 0.0 && (flushed.1 - FLUSHING.gain * (expected - FLUSHING.pressure)).abs() < 1e-6 * flushed.1);
    assert!(without.drive.p_b > 8e6, "without a flushing valve nothing drains the low line");
    // The shuttle is closed with the lines equal, and the valve refuses a setting at or above
    // the charge pressure.
    assert_eq!(FLUSHING.flows(3e6, 3e6), (0.0, 0.0));
    let high = ClosedCircuit { flushing: Some(Flushing { pressure: 2.5e6, ..FLUSHING }), ..ClosedCircuit::DEFAULT };
    assert!(high.validate().is_err_and(|e| e.contains("flushing valve pressure")));
}

#[test]
fn h12_the_pumps_power_balances_the_closed_circuits_energies_and_losses() {
    for flushing in [None, Some(FLUSHING)] {
        closed_circuit_power_balance(flushing);
    }
}

/// H12 over a hoist, hold, lower and sharp reversal with the flushing valve `flushing`.
fn closed_circuit_power_balance(flushing: Option<Flushing>) {
    let mut winch = PumpWinch::new(MotorDrive::WINCH_DEFAULT);
    winch.pump.flushing = flushing;
    let (motor, inertia, start) = (&winch.motor, winch.inertia, winch.start);
    // Hoist, hold, lower, reverse sharply: every term works.
    let spool = |t: f64| match t {
        t if t < 3.0 => 0.8 * (t / 3.0),
        t if t < 5.0 => 0.0,
        t if t < 8.0 => -0.9,
        t if t < 8.5 => 1.0,
        _ => 0.3 * (t - 8.5).sin(),
    };
    let end = winch.run(spool, false, 15.0);
    let kinetic = 0.5 * inertia * end.drive.vel.powi(2);
    let mechanical = kinetic - end.load_work;
    let accounted = mechanical + end.compression + end.throttling + end.friction;
    // Relative to the pump's gross energy: lowering, the load drives the pump (negative power).
    let residual = (end.pump - accounted) / end.pump_gross;
    let stored = motor.stored_energy(&Oil::DEFAULT, &end.drive) - motor.stored_energy(&Oil::DEFAULT, &start.drive);
    let residual_h10 = (end.pump - (accounted - end.compression + stored)) / end.pump_gross;
    println!(
        "15 s closed-circuit run (flushing valve: {}): pump {:.1} kJ (gross {:.1}) = mechanical {:.1} + compression {:.2} (ΔH10 {:.2}) + throttling \
         {:.2} + friction {:.2} kJ; residual {residual:+.2e}, with ΔH10 {residual_h10:+.2e}; rope {:.3} m",
        flushing.is_some(),
        end.pump * 1e-3,
        end.pump_gross * 1e-3,
        mechanical * 1e-3,
        end.compression * 1e-3,
        stored * 1e-3,
        end.throttling * 1e-3,
        end.friction * 1e-3,
        end.drive.pos * CraneParams::DEFAULT.drum_radius
    );
    assert!(residual.abs() < 0.01 && residual_h10.abs() < 0.01);
    assert!(end.throttling > 0.0 && end.friction > 0.0 && end.drive.pos.abs() > 0.1);
}

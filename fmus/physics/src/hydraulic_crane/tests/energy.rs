//! Conservation of energy: with leak-free centred valves, closed counterbalance valves, no
//! friction, no load and a fixed level deck, nothing dissipates and nothing does work on the
//! crane, so the arm's kinetic and potential energy, the drum's kinetic energy and the energy of
//! the compressed oil add up to a constant. Started off equilibrium, the arm and the drum swing
//! on the oil springs of the closed chambers.

use super::*;
use crate::hydraulic_crane::plant::{BOOM, JIB, SLEW, WINCH};
use crate::hydraulics::{CylinderDrive, MotorDrive, Oil};

/// A drive without valve leakage and without friction (the end stops, reliefs and make-up stay
/// in place; the start is chosen so that none of them acts).
fn lossless_cylinder(drive: &CylinderDrive) -> CylinderDrive {
    let mut d = *drive;
    (d.valve.leak_supply, d.valve.leak_tank) = (0.0, 0.0);
    (d.cylinder.viscous, d.cylinder.coulomb) = (0.0, 0.0);
    d
}

fn lossless_motor(drive: &MotorDrive) -> MotorDrive {
    let mut d = *drive;
    (d.valve.leak_supply, d.valve.leak_tank, d.leakage) = (0.0, 0.0, 0.0);
    (d.viscous, d.coulomb) = (0.0, 0.0);
    d
}

/// The return chambers' pressure at the start (Pa): half the counterbalance valves' 2 MPa
/// cracking pilot, so the valves stay closed and the make-up checks (below 0 Pa) stay shut
/// while the pressures swing by less than 1 MPa.
const RETURN_PRESSURE: f64 = 1e6;

/// The oil's energy relative to the start (J). Cylinder chambers: H11, exact for H4 with Q = 0
/// (p = p0 − β·ln(V/V0)). Motor lines: H9 with Q = 0 and the constant line volume V gives
/// dp/dt = −β·D·ω_m/V for A (and the opposite for B), so the work the shaft does on the oil,
/// −∫p·D·ω_m dt, is exactly V·(p² − p0²)/(2β) (H10's form, relative to the start).
fn oil_energy(params: &CraneParams, start: &PlantState, s: &PlantState) -> f64 {
    let oil: &Oil = &params.oil;
    let [(l_boom0, _), (l_jib0, _)] = params.arm.cylinders(&start.q);
    let [(l_boom, _), (l_jib, _)] = params.arm.cylinders(&s.q);
    let cylinders = [
        (
            BOOM,
            &params.boom,
            l_boom0 - params.arm.boom_cylinder.min_length,
            l_boom - params.arm.boom_cylinder.min_length,
        ),
        (JIB, &params.jib, l_jib0 - params.arm.jib_cylinder.min_length, l_jib - params.arm.jib_cylinder.min_length),
    ];
    let mut energy = 0.0;
    for (index, drive, x0, x) in cylinders {
        let ((v_a0, v_b0), (v_a, v_b)) = (drive.volumes(x0), drive.volumes(x));
        let [p_a0, p_b0] = start.pressures[index];
        energy += oil.closed_chamber_work(p_a0, v_a0, v_a) + oil.closed_chamber_work(p_b0, v_b0, v_b);
    }
    for (index, drive) in [(SLEW, &params.slew), (WINCH, &params.winch)] {
        for chamber in 0..2 {
            let (p0, p) = (start.pressures[index][chamber], s.pressures[index][chamber]);
            energy += drive.line_volume * (p * p - p0 * p0) / (2.0 * oil.bulk_modulus);
        }
    }
    energy
}

/// Arm (Siciliano et al. 2009, eqs. 7.13–7.14, 7.28) plus drum ½·J_w·φ̇² (J).
fn mechanical_energy(params: &CraneParams, s: &PlantState) -> f64 {
    let (kinetic, potential) = params.arm.energy(&s.q, &s.qd);
    kinetic + potential + 0.5 * params.winch_inertia * s.drum_rate * s.drum_rate
}

#[test]
fn closed_loss_free_drives_conserve_the_crane_energy() {
    let base = CraneParams::DEFAULT;
    let params = CraneParams {
        slew: lossless_motor(&base.slew),
        boom: lossless_cylinder(&base.boom),
        jib: lossless_cylinder(&base.jib),
        winch: lossless_motor(&base.winch),
        ..base
    };
    assert_eq!(params.validate(), Ok(()));
    let no_load = Loads::default();
    let mut start = at_rest(&params, &no_load);
    // Return chambers at RETURN_PRESSURE, the load-holding chambers balancing the static force
    // (H7, H8 at rest); then the joints and the drum set moving (the slew at 0.01 rad/s, the
    // luffing joints at 0.005 rad/s, the drum at 0.02 rad/s: pressure swings of at most
    // ±0.9 MPa, so the 1 MPa return chambers neither cavitate nor crack a counterbalance valve).
    let zero = [0.0; 3];
    let torques = params.arm.joint_torques(&no_load.ship, &start.q, &zero, &zero, &no_load.cable);
    let [(_, arm_boom), (_, arm_jib)] = params.arm.cylinders(&start.q);
    let hold = |(a, b): (f64, f64)| [a, b];
    start.pressures = [
        hold(params.slew.holding_pressures(torques[0], RETURN_PRESSURE)),
        hold(params.boom.holding_pressures(torques[1] / arm_boom, RETURN_PRESSURE)),
        hold(params.jib.holding_pressures(torques[2] / arm_jib, RETURN_PRESSURE)),
        hold(params.winch.holding_pressures(0.0, RETURN_PRESSURE)),
    ];
    start.pilots = start.pressures.map(|[_, p_b]| p_b);
    start.qd = [0.01, 0.005, 0.005];
    start.drum_rate = 0.02;

    let e0 = mechanical_energy(&params, &start);
    let (kinetic0, _) = params.arm.energy(&start.q, &start.qd);
    let swing0 = kinetic0 + 0.5 * params.winch_inertia * start.drum_rate * start.drum_rate;
    let (mut worst, mut p_min, mut p_max, mut pilot_max) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY, 0.0f64);

    let (mut q_min, mut q_max) = (start.q, start.q);
    run(
        &params,
        start,
        60.0,
        |_| Spools::default(),
        |_| no_load,
        |_, s| {
            let e = mechanical_energy(&params, s) + oil_energy(&params, &start, s);
            worst = worst.max((e - e0).abs());
            for p in s.pressures.iter().flatten() {
                (p_min, p_max) = (p_min.min(*p), p_max.max(*p));
            }
            // The pilots of the counterbalance valves on boom, jib and winch: their B chambers.
            pilot_max = [BOOM, JIB, WINCH].iter().fold(pilot_max, |m, &i| m.max(s.pressures[i][1]));
            for i in 0..3 {
                (q_min[i], q_max[i]) = (q_min[i].min(s.q[i]), q_max[i].max(s.q[i]));
            }
        },
    );
    println!(
        "energy, 60 s: max |E − E0| = {worst:.3e} J, {:.2e} of E0 = {e0:.1} J (potential above the deck), {:.2e} of \
         the initial swing energy {swing0:.2} J; pressures {:.3}…{:.3} MPa, pilots ≤ {:.3} MPa; joints {q_min:.4?}…{q_max:.4?} rad",
        worst / e0.abs(),
        worst / swing0,
        p_min / 1e6,
        p_max / 1e6,
        pilot_max / 1e6,
    );
    // The perturbation must keep every relief, make-up check and counterbalance valve shut.
    // H6: a poppet under a load pressure of at most p_max cracks at a pilot of (p_set − p_max)/R.
    let cracking = base.boom.holding.map_or(0.0, |c| c.cracking_pilot(p_max));
    assert!(p_min > 0.0 && p_max < base.boom.relief.pressure, "pressures {p_min}…{p_max} Pa");
    assert!(pilot_max < cracking, "a pilot reached the counterbalance valves' crack pressure: {pilot_max} Pa");
    assert!(worst / e0.abs() <= 1e-6, "relative energy error {}", worst / e0.abs());
}

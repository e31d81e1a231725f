//! Holding a 10 t load with centred spools: the counterbalance valves keep the piston sides and
//! the winch's hoisting side closed, so the arm stays where it started and the pressures carry
//! the static loads.

use super::*;
use crate::hydraulic_crane::plant::{BOOM, JIB, WINCH};

#[test]
fn a_centred_crane_holds_ten_tonnes_in_place() {
    let params = CraneParams::DEFAULT;
    let loads = hanging(10.0);
    let start = at_rest(&params, &loads);
    let still = ShipMotion::default();
    let tip0 = tip(&params, &start, &still);
    let mut drift = 0.0f64;
    let end = run(
        &params,
        start,
        60.0,
        |_| Spools::default(),
        |_| loads,
        |_, s| {
            drift = drift.max((tip(&params, s, &still) - tip0).norm());
        },
    );
    assert!(end.is_finite());

    // Reference: the arm's inverse dynamics at rest with the rope force at the tip (RNEA,
    // Featherstone 2008 ch. 5) through the lever arms (virtual work, F = τ/(dL/dθ)) against H7
    // at v = 0 without the stop: F = p_A·A_A − p_B·A_B.
    let zero = [0.0; 3];
    let torques = params.arm.joint_torques(&still, &end.q, &zero, &zero, &loads.cable);
    let [(_, arm_boom), (_, arm_jib)] = params.arm.cylinders(&end.q);
    let mut worst_cylinder = 0.0f64;
    for (index, drive, lever, torque) in
        [(BOOM, &params.boom, arm_boom, torques[1]), (JIB, &params.jib, arm_jib, torques[2])]
    {
        let (a_a, a_b) = drive.areas();
        let [p_a, p_b] = end.pressures[index];
        let hydraulic = p_a * a_a - p_b * a_b;
        let reference = torque / lever;
        let error = (hydraulic - reference).abs() / reference.abs();
        println!("holding 60 s, cylinder {index}: p_A A_A − p_B A_B = {hydraulic:.1} N, static {reference:.1} N, error {error:.2e}");
        worst_cylinder = worst_cylinder.max(error);
    }

    // Reference: the drum at rest carries the rope's torque T·r_d, and the motor D·(p_A − p_B)
    // through the gear n (H8 at ω = 0): Δp = T·r_d/(n·D). The motor's cross-port leakage lets
    // the drum creep out at ω_m = C_m·Δp/D (the closed hoisting side's continuity, H9), so the
    // shaft's friction at that speed (H8) is part of the balance too; both figures are printed.
    let winch = &params.winch;
    let [p_a, p_b] = end.pressures[WINCH];
    let (n, d) = (winch.gear, winch.displacement);
    let static_dp = loads.cable.norm() * params.drum_radius / (n * d);
    let motor_speed = -n * end.drum_rate;
    let friction = crate::hydraulics::drive::friction(winch.viscous, winch.coulomb, winch.coulomb_speed, motor_speed);
    let creeping_dp = static_dp + friction / d;
    let winch_error = ((p_a - p_b) - creeping_dp).abs() / creeping_dp;
    println!(
        "holding 60 s: tip drift {:.3e} m; winch Δp {:.4} MPa, T·r_d/(n·D) {:.4} MPa ({:+.2e}), with the creep's \
         friction {:.4} MPa ({winch_error:.2e}); drum creep {:.3e} rad/s (leakage C_m·Δp/(n·D) = {:.3e})",
        drift,
        (p_a - p_b) / 1e6,
        static_dp / 1e6,
        ((p_a - p_b) - static_dp) / static_dp,
        creeping_dp / 1e6,
        end.drum_rate,
        winch.leakage * (p_a - p_b) / (n * d),
    );
    assert!(drift <= 1e-3, "tip drift {drift} m");
    assert!(worst_cylinder <= 1e-3, "cylinder force error {worst_cylinder}");
    assert!(winch_error <= 1e-3, "winch pressure error {winch_error}");
}

//! The port reliefs at crane level: driving the boom cylinder into its end stop with the spool
//! fully open, the piston side's pressure stays bounded by the supply and the relief (H3, H5).

use super::*;
use crate::hydraulic_crane::plant::BOOM;

#[test]
fn a_boom_driven_into_its_end_stop_stays_below_the_relief() {
    let params = CraneParams::DEFAULT;
    let loads = hanging(10.0);
    let start = at_rest(&params, &loads);
    let drive = &params.boom;
    let stroke = drive.cylinder.stroke;
    // H5: the relief passes Q at p_relief + Q/G; the most the valve can feed is its meter-in
    // cap Q_max, so no more can have to pass the relief.
    let bound = drive.relief.pressure + drive.relief.override_at(drive.valve.max_flow);
    let mut full_up = Spools::default();
    full_up.0[BOOM] = 1.0;
    let (mut p_a_max, mut finite, mut reached) = (0.0f64, true, None);
    let (mut x_last, mut v_last) = (0.0f64, 0.0f64);
    let end = run(
        &params,
        start,
        40.0,
        |_| full_up,
        |_| loads,
        |t, s| {
            let [(length, lever)] = [params.arm.cylinders(&s.q)[0]];
            let x = length - params.arm.boom_cylinder.min_length;
            (x_last, v_last) = (x, lever * s.qd[1]);
            if reached.is_none() && x >= stroke {
                reached = Some(t);
            }
            p_a_max = p_a_max.max(s.pressures[BOOM][0]);
            finite &= s.is_finite();
        },
    );
    println!(
        "boom into its end stop: stroke end reached at {reached:?} s, x = {x_last:.5} m (stroke {stroke} m), \
         v = {v_last:.2e} m/s after 40 s; max p_A = {:.3} MPa ≤ relief + override {:.3} MPa (supply {:.1} MPa)",
        p_a_max / 1e6,
        bound / 1e6,
        params.supply.pressure / 1e6,
    );
    assert!(finite && end.is_finite());
    assert!(reached.is_some_and(|t| t < 30.0), "the cylinder did not reach its end stop");
    assert!((x_last - stroke).abs() < 0.01 && v_last.abs() < 1e-4, "not resting on the stop: x {x_last}, v {v_last}");
    assert!(p_a_max <= bound, "p_A {p_a_max} Pa above {bound} Pa");
}

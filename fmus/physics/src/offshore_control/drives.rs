//! From a desired actuator speed to a spool command: the inverse of the pressure-compensated
//! valve (docs/hydraulics.md, H1 and H3's meter-in cap).
//!
//! The crane's valves are pressure compensated: with enough supply pressure the meter-in edge
//! passes o·Q_max whatever the load, o = u_eff the effective opening of H1. A cylinder then
//! moves at ẋ = o·Q_max/A (A_A extending, the annulus A_B retracting: H4's continuity with the
//! chamber compression neglected), a motor at ω = o·Q_max/(D·n) at the gear output (H8). The
//! controller inverts that: o from the speed it wants, then the spool from H1 solved for u,
//! u = sign(o)·(d + (1 − d)·|o|) — the deadband compensation: a spool inside the deadband
//! passes no flow, so the command jumps over it.

use crate::hydraulic_crane::plant::CraneParams;
use crate::hydraulics::{MotorDrive, Valve};

/// The speed each drive reaches at full effective opening o = 1, from the plant's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatedSpeeds {
    /// Boom and jib cylinders extending and retracting (m/s): Q_max/A_A and Q_max/A_B.
    pub cylinders: [(f64, f64); 2],
    /// The slew at the slewing ring (rad/s): Q_max/(D·n).
    pub slew: f64,
    /// The hoist rope (m/s): r_d·Q_max/(D·n).
    pub rope: f64,
}

impl RatedSpeeds {
    /// With the default parameters: cylinders 31.8 mm/s extending, 72.8 mm/s retracting; slew
    /// 0.180 rad/s; rope 0.524 m/s.
    pub fn of(params: &CraneParams) -> RatedSpeeds {
        let cylinder = |drive: &crate::hydraulics::CylinderDrive| {
            let (a_a, a_b) = drive.areas();
            (drive.valve.max_flow / a_a, drive.valve.max_flow / a_b)
        };
        let motor = |drive: &MotorDrive| drive.valve.max_flow / (drive.displacement * drive.gear);
        RatedSpeeds {
            cylinders: [cylinder(&params.boom), cylinder(&params.jib)],
            slew: motor(&params.slew),
            rope: params.drum_radius * motor(&params.winch),
        }
    }
}

/// The effective opening that moves a cylinder at `speed` (m/s, positive extending) with the
/// rated speeds `(extend, retract)`; beyond ±1 when the speed is more than the valve gives.
pub fn cylinder_opening(speed: f64, (extend, retract): (f64, f64)) -> f64 {
    speed / if speed >= 0.0 { extend } else { retract }
}

/// The spool command (−1…1) that gives the effective opening `opening` through `valve`'s
/// deadband: H1 solved for u. Zero gives zero (the centred spool, the counterbalance valves
/// holding); a NaN opening gives zero.
pub fn spool_for(valve: &Valve, opening: f64) -> f64 {
    if opening == 0.0 || opening.is_nan() {
        return 0.0;
    }
    let o = opening.clamp(-1.0, 1.0);
    o.signum() * (valve.deadband + (1.0 - valve.deadband) * o.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spool_inverse_round_trips_through_the_valve() {
        let valve = Valve::DEFAULT;
        for o in [-1.0, -0.5, -1e-6, 0.0, 1e-6, 0.3, 0.999, 1.0] {
            let u = spool_for(&valve, o);
            assert!((valve.opening(u) - o).abs() < 1e-15, "o = {o}: u = {u}, back {}", valve.opening(u));
        }
        assert_eq!(spool_for(&valve, 2.0), 1.0);
        assert_eq!(spool_for(&valve, f64::NAN), 0.0);
        // Just outside the deadband.
        assert!((spool_for(&valve, 1e-9) - 0.1).abs() < 1e-9);
    }

    #[test]
    fn the_rated_speeds_follow_from_flow_area_and_displacement() {
        let s = RatedSpeeds::of(&CraneParams::DEFAULT);
        let q = 240e-3 / 60.0;
        let piston = std::f64::consts::PI * 0.4 * 0.4 / 4.0;
        let annulus = piston - std::f64::consts::PI * 0.3 * 0.3 / 4.0;
        assert!((s.cylinders[0].0 - q / piston).abs() < 1e-15 && (s.cylinders[1].1 - q / annulus).abs() < 1e-15);
        assert!((s.cylinders[0].0 - 0.0318).abs() < 1e-4 && (s.cylinders[0].1 - 0.0728).abs() < 1e-4);
        // 0.7 L/rev through 200:1 and 0.4 L/rev through 30:1 onto a 0.25 m drum radius.
        assert!((s.slew - q / (0.7e-3 / std::f64::consts::TAU * 200.0)).abs() < 1e-12);
        assert!((s.rope - 0.25 * q / (0.4e-3 / std::f64::consts::TAU * 30.0)).abs() < 1e-12);
        let half_retract = -0.5 * s.cylinders[0].1;
        assert_eq!(cylinder_opening(half_retract, s.cylinders[0]), -0.5);
        assert_eq!(cylinder_opening(3.0 * s.cylinders[0].0, s.cylinders[0]), 3.0);
    }
}

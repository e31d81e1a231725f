//! The consistency of a description, each refusal naming the field and the values that
//! disagree:
//!
//! - every part valid on its own (the plant's own checks, [`CraneParams::validate`]), which
//!   includes each luffing cylinder's stroke equal to its mechanism's pin-to-pin travel;
//! - the joint limits within what the cylinders reach (the mechanism's joint range at the
//!   shortest and longest pin-to-pin length, docs/full-scale.md);
//! - the winch able to hoist the rated load at the supply pressure, and a rope whose minimum
//!   breaking load is above the largest pull the winch can make (at its relief setting): the
//!   rope must not be the weakest part of the hoist (DNV-ST-0378 sizes the rope from the
//!   winch's largest pull, not the rated load alone);
//! - in the closed circuit, the winch's rated flow equal to the pump's full flow;
//! - a rating, a rope and joint limits with finite, positive values.

use crate::CraneDescription;
use physics::hydraulic_crane::plant::CraneParams;
use physics::hydraulics::WinchCircuit;
use physics::math::Vec3;

/// Ok, or the first inconsistency (module documentation).
pub fn consistent(d: &CraneDescription) -> Result<(), String> {
    let params = d.params(Vec3::zeros());
    params.validate()?;
    positive("rating.safe_working_load", d.rating.safe_working_load, "kg")?;
    positive("rating.outreach", d.rating.outreach, "m")?;
    positive("rope.diameter", d.rope.diameter, "m")?;
    positive("rope.axial_stiffness", d.rope.axial_stiffness, "N")?;
    positive("rope.minimum_breaking_load", d.rope.minimum_breaking_load, "N")?;
    if !(d.rope.damping_time >= 0.0 && d.rope.damping_time.is_finite()) {
        return Err(format!("rope.damping_time {} s must be finite and ≥ 0", d.rope.damping_time));
    }
    joint_limits(d, &params)?;
    closed_circuit_flow(&params)?;
    winch_pull(d, &params)
}

/// In the closed circuit the controller's drive model reads the winch's rated flow from
/// `winch.drive.valve.max_flow` ([`physics::offshore_control::drives::RatedSpeeds`]); it must be
/// the pump's full flow D_p·ω_p, or the controller would command the wrong rope speed.
fn closed_circuit_flow(params: &CraneParams) -> Result<(), String> {
    let pump = params.winch_pump.displacement * params.winch_pump.speed;
    let rated = params.winch.valve.max_flow;
    if params.winch_circuit == WinchCircuit::Closed && (rated - pump).abs() > 1e-9 * pump {
        return Err(format!(
            "winch.drive.valve.max_flow {:.1} L/min must equal the pump's full flow {:.1} L/min              (winch.pump.displacement × winch.pump.speed) in the closed circuit: the controller takes the              winch's rated flow from it",
            rated * 6e4,
            pump * 6e4
        ));
    }
    Ok(())
}

fn positive(field: &str, value: f64, unit: &str) -> Result<(), String> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(format!("{field} {value} {unit} must be finite and > 0"))
    }
}

/// The joint limits against the cylinders' reach.
fn joint_limits(d: &CraneDescription, params: &CraneParams) -> Result<(), String> {
    let reach = params.arm.joint_limits()?;
    for ((name, limits), (low, high)) in
        [("boom", d.joint_limits.boom), ("jib", d.joint_limits.jib)].into_iter().zip(reach)
    {
        let [lo, hi] = limits;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(format!("joint_limits.{name} [{lo}, {hi}] rad must be finite and increasing"));
        }
        if lo < low - 1e-9 || hi > high + 1e-9 {
            return Err(format!(
                "joint_limits.{name} {:.2}°…{:.2}° is beyond what the {name} cylinder reaches, {:.2}°…{:.2}° \
                 (its stroke {:.3} m over pins {:?} and {:?} m)",
                lo.to_degrees(),
                hi.to_degrees(),
                low.to_degrees(),
                high.to_degrees(),
                mechanism(params, name).max_length - mechanism(params, name).min_length,
                mechanism(params, name).lower_pin,
                mechanism(params, name).upper_pin,
            ));
        }
    }
    Ok(())
}

fn mechanism<'a>(params: &'a CraneParams, name: &str) -> &'a physics::knuckle_boom::Mechanism {
    if name == "boom" {
        &params.arm.boom_cylinder
    } else {
        &params.arm.jib_cylinder
    }
}

/// The line pull (N) at the drum's pitch radius for a pressure difference `dp` (Pa) across the
/// winch motor: T = Δp·D·n/r_d (docs/hydraulics.md, H8, friction neglected).
pub fn line_pull(params: &CraneParams, dp: f64) -> f64 {
    dp * params.winch.displacement * params.winch.gear / params.drum_radius
}

/// The largest pressure difference the winch motor can see (Pa): the port relief setting in the
/// open circuit, the cross-port relief's in the closed one.
pub fn largest_winch_pressure(params: &CraneParams) -> f64 {
    match params.winch_circuit {
        WinchCircuit::Open => params.winch.relief.pressure,
        WinchCircuit::Closed => params.winch_pump.relief.pressure,
    }
}

/// The pressure difference the winch motor works at (Pa): the supply's in the open circuit, the
/// cross-port relief's in the closed one (the pump drives up to it).
pub fn working_winch_pressure(params: &CraneParams) -> f64 {
    match params.winch_circuit {
        WinchCircuit::Open => params.supply.pressure,
        WinchCircuit::Closed => params.winch_pump.relief.pressure,
    }
}

/// The winch against the rated load and the rope.
fn winch_pull(d: &CraneDescription, params: &CraneParams) -> Result<(), String> {
    let weight = d.rating.safe_working_load * params.arm.g;
    let working = working_winch_pressure(params);
    let pull = line_pull(params, working);
    if pull < weight {
        return Err(format!(
            "rating.safe_working_load {} kg weighs {:.1} kN, more than the winch's {:.1} kN of line pull at \
             {:.1} MPa (winch.drive.displacement, winch.drive.gear, winch.drum_radius)",
            d.rating.safe_working_load,
            weight / 1e3,
            pull / 1e3,
            working / 1e6
        ));
    }
    let largest = line_pull(params, largest_winch_pressure(params));
    if d.rope.minimum_breaking_load <= largest {
        return Err(format!(
            "rope.minimum_breaking_load {:.1} kN is not above the winch's largest pull {:.1} kN (at its relief \
             setting {:.1} MPa): the rope would break before the winch stalls",
            d.rope.minimum_breaking_load / 1e3,
            largest / 1e3,
            largest_winch_pressure(params) / 1e6
        ));
    }
    Ok(())
}

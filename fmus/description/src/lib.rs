//! Crane description files: every parameter of the full-scale crane in one JSON file
//! (docs/crane-description.md), read the same way by the crane FMU `knuckle_boom` and its
//! controller `knuckle_boom_controller`, so the two cannot disagree about the crane.
//!
//! A description names its values in SI units (m, kg, kg·m², Pa, m³/s, m³/rad, rad, N, s), in
//! sections that are the plant's own parameter types ([`physics::hydraulic_crane::plant`],
//! [`physics::hydraulics`], [`physics::knuckle_boom`]), plus what only a description carries:
//! the rating, the joint limits the cylinders must reach, the hoist rope and the sources.
//!
//! - [`json`]: the file's JSON: `extends` (a description written as changes to another), every
//!   field present and none unknown, named by its path;
//! - [`catalogue`]: the shipped cranes of `cranes/` (compiled in) and how a name or path finds a
//!   file;
//! - [`checks`]: the consistency of a description (joint limits within the cylinders' reach, a
//!   rope that outlasts its winch, a winch that lifts the rated load);
//! - this module: the description and the plant parameters and fingerprint made from it.
//!
//! The crane's mounting point on the vessel (`base`) is not part of a crane's description: the
//! FMUs take it as their own parameters, and it enters the fingerprint with the rest.

pub mod catalogue;
pub mod checks;
pub mod json;

use physics::hydraulic_crane::plant::CraneParams;
use physics::hydraulic_crane::sensors::SensorSet;
use physics::hydraulics::{ClosedCircuit, CylinderDrive, MotorDrive, Oil, Supply, WinchCircuit};
use physics::knuckle_boom::ArmParams;
use physics::math::Vec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// A crane as its description file gives it (docs/crane-description.md has every field with its
/// unit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CraneDescription {
    /// Short name, the file's stem in the catalogue (e.g. `osp_derived`).
    pub name: String,
    /// One line saying what crane this is.
    pub title: String,
    pub rating: Rating,
    /// The arm; its `base` is not read from the file (the FMUs' `base.*` parameters).
    pub arm: ArmParams,
    pub joint_limits: JointLimits,
    pub oil: Oil,
    pub supply: Supply,
    pub slew: MotorDrive,
    pub boom: CylinderDrive,
    pub jib: CylinderDrive,
    pub winch: Winch,
    pub rope: Rope,
    pub sensors: SensorSet,
    /// Where each value comes from, keyed by a field's path (`boom.cylinder.bore`) or by a
    /// section's (`boom.cylinder`) for every value under it.
    #[serde(default)]
    pub sources: BTreeMap<String, String>,
}

/// What the crane is rated for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rating {
    /// Safe working load at `outreach` (kg).
    pub safe_working_load: f64,
    /// Outreach of that rating, horizontal from the slew axis to the tip (m).
    pub outreach: f64,
}

/// The joint ranges the crane must be able to reach (rad): boom elevation above the horizontal,
/// jib angle relative to the boom (positive up). The cylinders' strokes must cover them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct JointLimits {
    pub boom: [f64; 2],
    pub jib: [f64; 2],
}

/// The winch: its circuit, motor drive, drum and the closed circuit's pump.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Winch {
    /// `Open` (the valve section `drive.valve` on the supply) or `Closed` (the pump `pump`).
    pub circuit: WinchCircuit,
    /// Motor, gear, lines, valve section, counterbalance valve and port reliefs.
    pub drive: MotorDrive,
    /// Pitch radius of the rope on the drum (m).
    pub drum_radius: f64,
    /// Inertia of the drum with the gear-reflected motor, about the drum axis (kg·m²).
    pub inertia: f64,
    /// The closed circuit's over-centre pump, charge circuit and cross-port reliefs.
    pub pump: ClosedCircuit,
}

/// The hoist rope.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rope {
    /// Nominal diameter (m).
    pub diameter: f64,
    /// Axial stiffness EA (N): the spring rate of l metres is EA/l.
    pub axial_stiffness: f64,
    /// Stiffness-proportional damping time β (s): c = β·EA/l (the rigging FMU's rope damping).
    pub damping_time: f64,
    /// Minimum breaking load (N).
    pub minimum_breaking_load: f64,
}

impl CraneDescription {
    /// The plant's parameters with the crane mounted at `base` (m, ship frame B).
    pub fn params(&self, base: Vec3) -> CraneParams {
        CraneParams {
            arm: ArmParams { base, ..self.arm },
            oil: self.oil,
            supply: self.supply,
            slew: self.slew,
            boom: self.boom,
            jib: self.jib,
            winch: self.winch.drive,
            drum_radius: self.winch.drum_radius,
            winch_inertia: self.winch.inertia,
            winch_circuit: self.winch.circuit,
            winch_pump: self.winch.pump,
        }
    }
}

/// Reads the description `spec` names: a catalogue name (`ahc_10t`), or a file's path (a
/// relative one from the working directory, else from `resource_dir`). Empty names the
/// default crane. The description is complete, known field by field and consistent, or the
/// error names the file and the field.
pub fn load(spec: &str, resource_dir: Option<&Path>) -> Result<CraneDescription, String> {
    let (origin, value) = json::resolve(spec, resource_dir)?;
    from_value(value).map_err(|e| format!("crane description {origin}: {e}"))
}

/// A description from its merged JSON (see [`load`]).
pub fn from_value(value: serde_json::Value) -> Result<CraneDescription, String> {
    let description: CraneDescription = json::typed(&value)?;
    checks::consistent(&description)?;
    Ok(description)
}

/// A number that changes whenever any parameter of `params` does, the same on every machine:
/// FNV-1a (64 bit) over the parameters' JSON, cut to 52 bits so that an FMI Real carries it
/// exactly. The crane and its controller compare theirs.
pub fn fingerprint(params: &CraneParams) -> f64 {
    // The JSON of plain numbers cannot fail to serialise; an empty text would still hash.
    let text = serde_json::to_string(params).unwrap_or_default();
    let hash =
        text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3));
    (hash >> 12) as f64
}

#[cfg(test)]
mod tests;

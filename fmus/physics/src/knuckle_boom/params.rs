//! The arm's parameters and their validation.
//!
//! Lengths and masses are the Open Simulation Platform's knuckle-boom test crane (OSP test data,
//! MPL-2.0). The inertia models, the column radius, the box sections, the base position and the
//! cylinder attachment points are our choices (documented at each constant), not OSP data: the
//! attachment points are chosen so that the OSP cylinders' 2.1–3.7 m pin-to-pin range maps onto
//! a useful joint range with a lever arm of at least 0.3 m, for a 4–20 m outreach knuckle boom of
//! the Palfinger PK 65002 M class. The cylinders' own masses are neglected.

use super::mechanism::Mechanism;
use crate::math::{Vec3, STANDARD_GRAVITY};
use serde::{Deserialize, Serialize};

/// One link's mass properties, axisymmetric about the link's line (the slew axis for the column,
/// the boom or jib line for those), centre of mass on that line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinkInertia {
    /// Mass (kg).
    pub mass: f64,
    /// Distance of the centre of mass from the link's joint along the link's line (m; for the
    /// column: height above the pedestal foot).
    pub com: f64,
    /// Moment of inertia about the link's line through the centre of mass (kg·m²).
    pub axial: f64,
    /// Moment of inertia about any axis through the centre of mass perpendicular to the line
    /// (kg·m²).
    pub transverse: f64,
}

/// Everything the arm's kinematics and dynamics need.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ArmParams {
    /// Pedestal foot, the origin of the crane base frame K, in the ship frame B (m).
    pub base: Vec3,
    /// Height h_p of the boom pivot above the deck (m).
    pub pedestal_height: f64,
    /// Horizontal distance a_p of the boom pivot from the slew axis, along the boom plane's
    /// direction e (m).
    pub pivot_offset: f64,
    /// Boom pivot to knuckle, L_b (m).
    pub boom_length: f64,
    /// Knuckle to tip, L_j (m).
    pub jib_length: f64,
    /// Slewing column, boom, jib.
    pub links: [LinkInertia; 3],
    /// The boom cylinder: lower pin on the column (plane frame at the boom pivot, x along e, y
    /// up), upper pin on the boom (x along the boom, from the pivot).
    pub boom_cylinder: Mechanism,
    /// The jib cylinder: lower pin on the boom (plane frame at the knuckle, x along the boom),
    /// upper pin on the jib (x along the jib, from the knuckle).
    pub jib_cylinder: Mechanism,
    /// Gravitational acceleration (m/s², along W's +z).
    pub g: f64,
}

/// OSP test crane: pedestal height (m).
const PEDESTAL_HEIGHT: f64 = 2.2;
/// OSP test crane: boom length (m).
const BOOM_LENGTH: f64 = 7.0;
/// OSP test crane: jib length (m).
const JIB_LENGTH: f64 = 5.2;
/// OSP test crane: slewing column (pedestal) mass (kg).
const COLUMN_MASS: f64 = 1524.0;
/// OSP test crane: boom mass (kg).
const BOOM_MASS: f64 = 2236.0;
/// OSP test crane: jib mass (kg).
const JIB_MASS: f64 = 1264.0;
/// Our choice: the slewing column as a solid cylinder of this radius (m), a PK 65002-class
/// column's size; the boom cylinder's lower pin sits on its surface.
const COLUMN_RADIUS: f64 = 0.6;
/// Our choice: the boom's representative thin-walled square box section, side (m).
const BOOM_SECTION: f64 = 0.45;
/// Our choice: the jib's representative thin-walled square box section, side (m).
const JIB_SECTION: f64 = 0.35;
/// OSP test crane: the luffing cylinders' shortest pin-to-pin length (m).
const CYLINDER_MIN_LENGTH: f64 = 2.1;
/// OSP test crane: the luffing cylinders' longest pin-to-pin length (m), 1.6 m stroke.
const CYLINDER_MAX_LENGTH: f64 = 3.7;

/// A uniform slender beam of `mass` and `length` hinged at one end with a thin-walled square box
/// section of side `section`: centre of mass at mid-length, transverse inertia m L²/12 (the
/// slender rod), axial inertia m s²/3 (four walls of mass m/4, each at s/2 from the axis with
/// its own m s²/48: (m/4)(s²/12 + s²/4) per wall).
const fn slender_beam(mass: f64, length: f64, section: f64) -> LinkInertia {
    LinkInertia {
        mass,
        com: 0.5 * length,
        axial: mass * section * section / 3.0,
        transverse: mass * length * length / 12.0,
    }
}

/// A solid cylinder of `mass`, `radius` and `height` standing on its foot: centre of mass at
/// half height, axial inertia m r²/2, transverse m (3 r² + h²)/12 (the solid cylinder's
/// textbook inertias).
const fn solid_column(mass: f64, radius: f64, height: f64) -> LinkInertia {
    LinkInertia {
        mass,
        com: 0.5 * height,
        axial: 0.5 * mass * radius * radius,
        transverse: mass * (3.0 * radius * radius + height * height) / 12.0,
    }
}

impl ArmParams {
    /// The OSP test crane with our inertia models and cylinder attachment points.
    ///
    /// - base (0, −8, 0) m in B: our choice, the pedestal 8 m to port of the centre line (a
    ///   supply vessel's crane on the port side, the arm reaching out to port at θ1 = −π/2);
    /// - boom cylinder, our choice: lower pin 0.6 m out and 0.9 m below the boom pivot on the
    ///   column's face, upper pin 2.95 m along the boom and 0.3 m below its line. The OSP
    ///   2.1–3.7 m range gives θ2 ∈ −20.45°…+75.02° with a lever arm ≥ 0.705 m;
    /// - jib cylinder, our choice: under the boom from 2.9 m behind the knuckle, 0.25 m below the
    ///   boom line, to the jib's underside 0.8 m beyond the knuckle, 0.35 m below the jib line.
    ///   θ3 ∈ −133.10°…−0.23° with a lever arm ≥ 0.33 m. A direct two-pin cylinder with a
    ///   1.76 length ratio cannot sweep much more: the widest sweep with a lever arm ≥ 0.3 m at
    ///   both ends is about 137° (pins 2.91 m and 0.86 m from the joint); the −150° fold of a
    ///   linkage-driven jib is not reached.
    pub const DEFAULT: ArmParams = ArmParams {
        base: Vec3::new(0.0, -8.0, 0.0),
        pedestal_height: PEDESTAL_HEIGHT,
        pivot_offset: 0.0,
        boom_length: BOOM_LENGTH,
        jib_length: JIB_LENGTH,
        links: [
            solid_column(COLUMN_MASS, COLUMN_RADIUS, PEDESTAL_HEIGHT),
            slender_beam(BOOM_MASS, BOOM_LENGTH, BOOM_SECTION),
            slender_beam(JIB_MASS, JIB_LENGTH, JIB_SECTION),
        ],
        boom_cylinder: Mechanism {
            lower_pin: [0.6, -0.9],
            upper_pin: [2.95, -0.3],
            min_length: CYLINDER_MIN_LENGTH,
            max_length: CYLINDER_MAX_LENGTH,
        },
        jib_cylinder: Mechanism {
            lower_pin: [-2.9, -0.25],
            upper_pin: [0.8, -0.35],
            min_length: CYLINDER_MIN_LENGTH,
            max_length: CYLINDER_MAX_LENGTH,
        },
        g: STANDARD_GRAVITY,
    };

    /// Checks every parameter: finite; lengths, masses and transverse inertias positive; axial
    /// inertias within 0…2·transverse (the triangle inequality of principal moments); both
    /// mechanisms valid; g ≥ 0. The message names the parameter and its value.
    pub fn validate(&self) -> Result<(), String> {
        if !self.base.iter().all(|v| v.is_finite()) {
            return Err(format!("base {:?} m must be finite", self.base));
        }
        positive("pedestal_height", self.pedestal_height)?;
        positive("boom_length", self.boom_length)?;
        positive("jib_length", self.jib_length)?;
        if !self.pivot_offset.is_finite() {
            return Err(format!("pivot_offset {} m must be finite", self.pivot_offset));
        }
        for (link, name) in self.links.iter().zip(["column", "boom", "jib"]) {
            link.validate(name)?;
        }
        self.boom_cylinder.validate("boom_cylinder")?;
        self.jib_cylinder.validate("jib_cylinder")?;
        if !(self.g >= 0.0 && self.g.is_finite()) {
            return Err(format!("g {} m/s² must be finite and ≥ 0", self.g));
        }
        Ok(())
    }

    /// The joint limits of θ2 and θ3 (rad), where the cylinders reach their stroke ends.
    pub fn joint_limits(&self) -> Result<[(f64, f64); 2], String> {
        Ok([self.boom_cylinder.joint_range()?, self.jib_cylinder.joint_range()?])
    }
}

impl LinkInertia {
    /// See [`ArmParams::validate`]; `name` names the link.
    fn validate(&self, name: &str) -> Result<(), String> {
        positive(&format!("{name} mass"), self.mass)?;
        positive(&format!("{name} transverse inertia"), self.transverse)?;
        if !self.com.is_finite() {
            return Err(format!("{name} centre of mass {} m must be finite", self.com));
        }
        if !(self.axial >= 0.0 && self.axial <= 2.0 * self.transverse) {
            return Err(format!(
                "{name} axial inertia {} kg·m² must lie within 0…2 × transverse ({} kg·m²)",
                self.axial, self.transverse
            ));
        }
        Ok(())
    }
}

/// Err unless `value` is finite and > 0.
fn positive(name: &str, value: f64) -> Result<(), String> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(format!("{name} {value} must be finite and > 0"))
    }
}

//! The rigging's constants (config, not state) and their validation.

use crate::pendulum::PendulumParams;
use serde::{Deserialize, Serialize};

/// How a rope (the hoist rope or the sling) carries load.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub enum RopeLaw {
    /// Inextensible and bilateral: a length constraint, as the thesis' cable (§4.3). Its tension is
    /// the constraint force and can come out negative; the model then reports the rope slack but
    /// keeps the constraint (choose [`RopeLaw::Elastic`] to model slack and snap).
    #[default]
    Rigid,
    /// Axially elastic and unilateral: the tension law of [`super::elastic_tension`].
    Elastic(ElasticRope),
}

/// An axially elastic rope: a Kelvin–Voigt element (spring and dashpot in parallel) that carries
/// no compression.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ElasticRope {
    /// Axial stiffness EA (N): Young's modulus of the rope times its metallic cross-section.
    /// The spring rate of a rope of unstretched length l is k = EA/l.
    pub ea: f64,
    /// Stiffness-proportional (Rayleigh) damping time β (s): the dashpot is c = β·k, so an axial
    /// mode of angular frequency ω has the damping ratio ζ = β ω / 2 (Chopra, Dynamics of
    /// Structures, §11.4, Rayleigh damping with the mass term zero). 0 = undamped.
    pub damping_time: f64,
}

impl ElasticRope {
    /// A steel wire rope of nominal diameter `d` (m) without damping: EA = E·f·π d²/4 with the rope
    /// modulus E = 1.0·10¹¹ Pa referred to the metallic area and the fill factor f = 0.55, the
    /// order Feyrer gives for stranded steel wire ropes (Feyrer, Wire Ropes, 2nd ed., 2015: fill
    /// factors about 0.5–0.6 in ch. 1, rope moduli of about 100 kN/mm² in ch. 3). An order of
    /// magnitude, not a data sheet: use the maker's EA where known.
    pub fn steel_wire(d: f64) -> ElasticRope {
        const MODULUS: f64 = 1.0e11;
        const FILL_FACTOR: f64 = 0.55;
        ElasticRope { ea: MODULUS * FILL_FACTOR * std::f64::consts::PI * d * d / 4.0, damping_time: 0.0 }
    }

    fn validate(&self, which: &str) -> Result<(), String> {
        if !(self.ea > 0.0 && self.ea.is_finite()) {
            return Err(format!("{which} EA must be a finite value > 0 N, got {}", self.ea));
        }
        if !(self.damping_time >= 0.0 && self.damping_time.is_finite()) {
            return Err(format!("{which} damping time must be a finite value ≥ 0 s, got {}", self.damping_time));
        }
        Ok(())
    }
}

/// Hook, sling and load.
///
/// The hoist rope runs from the crane tip to the hook (its unstretched length is the input
/// `TipMotion::lp`), the sling from the hook to the load. With `sling_length = 0` the load sits at
/// the hook: one point mass m_h + m_l, and with a rigid hoist rope exactly the thesis' pendulum
/// ([`crate::pendulum`], taken as its code path).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RiggingParams {
    /// The load: its mass m_l (kg), its drag rates κx, κy (1/s) in the swing directions of the rope
    /// it hangs from (the sling, or the hoist rope when there is no sling; §7.2.3's law) and g.
    pub load: PendulumParams,
    /// Hook (block) mass m_h (kg), ≥ 0; > 0 when there is a sling (two bodies).
    pub hook_mass: f64,
    /// Hook drag rate κ_h (1/s), in both swing directions of the hoist rope.
    pub hook_drag: f64,
    /// Sling length l_s (m), hook to load; 0 = no sling.
    pub sling_length: f64,
    /// The hoist rope, tip to hook.
    pub hoist: RopeLaw,
    /// The sling, hook to load (must be rigid when `sling_length = 0`).
    pub sling: RopeLaw,
}

default_is_const!(RiggingParams);

impl RiggingParams {
    /// The thesis' single pendulum: its load (m = 0.3018 kg, κx = 0.0272 s⁻¹, κy = 0.018 s⁻¹,
    /// §7.2.3) on its rigid cable (§4.3), no sling. The thesis weighs the load with whatever hangs
    /// on the cable, so the separate hook mass is 0; its drag rate is the smaller of the thesis'
    /// two, 0.018 s⁻¹, for want of a hook measurement (it matters only once the hook has mass).
    pub const DEFAULT: RiggingParams = RiggingParams {
        load: PendulumParams::DEFAULT,
        hook_mass: 0.0,
        hook_drag: 0.018,
        sling_length: 0.0,
        hoist: RopeLaw::Rigid,
        sling: RopeLaw::Rigid,
    };

    pub fn validate(&self) -> Result<(), String> {
        self.load.validate()?;
        if !(self.hook_mass >= 0.0 && self.hook_mass.is_finite()) {
            return Err(format!("hook mass must be a finite value ≥ 0 kg, got {}", self.hook_mass));
        }
        if !(self.hook_drag >= 0.0 && self.hook_drag.is_finite()) {
            return Err(format!("hook drag must be a finite value ≥ 0 1/s, got {}", self.hook_drag));
        }
        if !(self.sling_length >= 0.0 && self.sling_length.is_finite()) {
            return Err(format!("sling length must be a finite value ≥ 0 m, got {}", self.sling_length));
        }
        if self.has_sling() && !(self.hook_mass > 0.0) {
            return Err(format!(
                "a sling of {} m needs a hook mass > 0 kg (two bodies), got {}",
                self.sling_length, self.hook_mass
            ));
        }
        if let RopeLaw::Elastic(rope) = self.hoist {
            rope.validate("hoist rope")?;
        }
        if let RopeLaw::Elastic(rope) = self.sling {
            if !self.has_sling() {
                return Err("an elastic sling needs a sling length > 0 m".into());
            }
            rope.validate("sling")?;
        }
        Ok(())
    }

    /// Whether hook and load are two bodies (a sling of positive length).
    pub fn has_sling(&self) -> bool {
        self.sling_length > 0.0
    }

    /// Whether a rope in use is elastic: the hoist rope, or the sling when there is one.
    pub fn has_elastic_rope(&self) -> bool {
        let elastic = |law: RopeLaw| matches!(law, RopeLaw::Elastic(_));
        elastic(self.hoist) || (self.has_sling() && elastic(self.sling))
    }

    /// The same rigging with both ropes rigid.
    pub fn rigid(&self) -> RiggingParams {
        RiggingParams { hoist: RopeLaw::Rigid, sling: RopeLaw::Rigid, ..*self }
    }

    /// The single pendulum's code path applies: no sling and a rigid hoist rope.
    pub fn is_single_pendulum(&self) -> bool {
        !self.has_sling() && self.hoist == RopeLaw::Rigid
    }

    /// The lumped body of hook and load (no sling) as the pendulum's parameters: mass m_h + m_l and
    /// the mass-weighted drag rates κ = κ_l + (κ_h − κ_l)·m_h/(m_h + m_l), which are the load's
    /// own to the bit when m_h = 0 (so the default is the thesis' pendulum exactly).
    pub fn lumped(&self) -> PendulumParams {
        let mass = self.hook_mass + self.load.mass;
        let share = self.hook_mass / mass;
        PendulumParams {
            mass,
            kappa_x: self.load.kappa_x + (self.hook_drag - self.load.kappa_x) * share,
            kappa_y: self.load.kappa_y + (self.hook_drag - self.load.kappa_y) * share,
            g: self.load.g,
        }
    }
}

//! Hook and load rigging: a hook on the hoist rope and a load on a sling below it, a double
//! spherical pendulum whose ropes may be rigid or elastic, and an elastic rope that goes slack
//! and snaps taut again (the thesis' future work 3 and its §1 limits: double-pendulum effects at
//! the hook and the flexibility of the cable).
//!
//! Conventions as [`crate::pendulum`]: world frame W North-East-Down, gravity along +z, SI units;
//! the crane tip's motion and the hoist length l_p(t) (the unstretched length of an elastic rope)
//! are kinematic inputs ([`TipMotion`]); rope angles in the thesis' X–Y convention, the unit
//! vector along a rope e = (sin θy, −cos θy sin θx, cos θy cos θx) (eqs. 4.94–4.96).
//!
//! Formulation (docs/rigging.md): generalised coordinates per rope segment — a rigid rope's two
//! X–Y angles, an elastic rope's end position relative to its start in Cartesian W components —
//! and Kane's (Lagrange's) equations of the two point masses (its `dynamics` submodule). Two
//! rigid ropes give the double spherical pendulum in four angles; an elastic rope puts the body
//! below it in Cartesian coordinates, where slack needs no special case (the rope's tension is
//! zero, the body flies free). No sling with a rigid rope is the thesis' pendulum, taken as its code path
//! ([`crate::pendulum::advance`]) so that its results stay the same to the bit.

mod dynamics;
mod motion;
mod params;
mod rope;
mod segment;
mod state;

pub use crate::pendulum::TipMotion;
pub use dynamics::{advance, BodyMotion};
pub use motion::{
    chord_rate, energy, mode_shape, normal_modes, rigging_motion, snap_load_estimate, start_state, tip_coupling,
    RiggingMotion, TipCoupling,
};
pub use params::{ElasticRope, RiggingParams, RopeLaw};
pub use rope::tension as elastic_tension;
pub use state::{RiggingState, SnapRecord, STATE_LEN};

#[cfg(test)]
mod tests;

//! The elastic rope's tension law, and the X–Y angles and swing directions of a rope's direction.

use super::params::ElasticRope;
use crate::math::Vec3;

/// Tension (N) of an elastic rope of unstretched length `rest` (m) changing at `rest_rate` (m/s),
/// whose ends are `length` (m) apart and separate at `length_rate` (m/s):
///
/// T = max(0, k δ + c δ̇),  k = EA / l₀,  c = β k,  δ = r − l₀,  δ̇ = ṙ − l̇₀.
///
/// The Kelvin–Voigt law (spring and dashpot in parallel) with the elastic cable's axial rate EA/l₀
/// (Irvine, Cable Structures, MIT Press, 1981: the elastic catenary's extensibility) made
/// unilateral: a rope carries no compression (DNV-RP-H103, Modelling and Analysis of Marine
/// Operations, 2011, §4.7: slack slings and hoisting lines and the snap loads when they tighten).
/// The dashpot acts on the elongation rate, not on ṙ: a winch paying out a taut rope at a steady
/// rate strains it at no rate.
///
/// The max is taken of the whole sum, so T is continuous (Lipschitz) in the state, which the
/// fourth-order Runge–Kutta steps need to converge. The price: a damped rope (β > 0) that is
/// being pulled taut fast starts to pull an elongation β·δ̇ before it is straight (δ = −β δ̇ < 0),
/// and lets go an elongation β·|δ̇| early when it unloads fast. Without damping the law is the
/// plain unilateral spring T = k·max(0, δ), whose energy ½ k max(0, δ)² the model conserves.
pub fn tension(rope: &ElasticRope, rest: f64, rest_rate: f64, length: f64, length_rate: f64) -> f64 {
    let k = rope.ea / rest;
    let stretch = length - rest;
    let stretch_rate = length_rate - rest_rate;
    (k * (stretch + rope.damping_time * stretch_rate)).max(0.0)
}

/// Strain energy (J) of an elastic rope stretched to `length` over its unstretched `rest`:
/// ½ (EA/l₀) max(0, r − l₀)², the potential of the undamped [`tension`].
pub fn strain_energy(rope: &ElasticRope, rest: f64, length: f64) -> f64 {
    let stretch = (length - rest).max(0.0);
    0.5 * rope.ea / rest * stretch * stretch
}

/// Unit direction of the vector `d` (the rope's chord); straight down (+z in North-East-Down)
/// when `d` is zero, where no direction exists and an elastic rope carries no tension anyway.
pub fn direction(d: &Vec3) -> Vec3 {
    let n = d.norm();
    if n > 0.0 {
        d / n
    } else {
        Vec3::z()
    }
}

/// The X–Y angles (θx, θy) (rad) of a unit rope direction e = (sin θy, −cos θy sin θx,
/// cos θy cos θx) (thesis eqs. 4.94–4.96): θy = asin e_x ∈ [−90°, 90°], θx = atan2(−e_y, e_z).
pub fn angles(e: &Vec3) -> (f64, f64) {
    ((-e.y).atan2(e.z), e.x.clamp(-1.0, 1.0).asin())
}

/// The unit swing directions (ê_x, ê_y) of a unit rope direction e: the directions in which θx and
/// θy move the rope's end, ê_x = ∂e/∂θx / cos θy = (0, −cos θx, −sin θx) and
/// ê_y = ∂e/∂θy = (cos θy, sin θy sin θx, −sin θy cos θx), both orthogonal to e and to each other.
/// Computed from e's components (cos θy = √(e_y² + e_z²), sin θx = −e_y / cos θy,
/// cos θx = e_z / cos θy); at the X–Y angles' singularity e = ±x (cos θy = 0) θx = 0 is taken.
pub fn swing_directions(e: &Vec3) -> (Vec3, Vec3) {
    let cy = e.y.hypot(e.z);
    let (sx, cx) = if cy > 0.0 { (-e.y / cy, e.z / cy) } else { (0.0, 1.0) };
    let sy = e.x;
    (Vec3::new(0.0, -cx, -sx), Vec3::new(cy, sy * sx, -sy * cx))
}

/// Drag force (N) on a point mass `mass` (kg) moving at `v` (m/s, in still air) at the end of a
/// rope with swing directions `dirs`: F = −m [κx (v·ê_x) ê_x + κy (v·ê_y) ê_y], the linear
/// aerodynamic damping the thesis identified for its load (§7.2.3), acting across the rope. Along
/// the rope there is none (an elastic rope's own damping acts there).
pub fn drag(mass: f64, kappa_x: f64, kappa_y: f64, v: &Vec3, dirs: &(Vec3, Vec3)) -> Vec3 {
    let (e_x, e_y) = dirs;
    -(e_x * (kappa_x * v.dot(e_x)) + e_y * (kappa_y * v.dot(e_y))) * mass
}

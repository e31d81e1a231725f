//! What the rigging shows: hook and load motion, rope angles and tensions, slack, energy, and the
//! closed forms the verification measures the model against.

use super::dynamics::{evaluate, BodyMotion};
use super::params::{RiggingParams, RopeLaw};
use super::rope::{angles, strain_energy};
use super::state::RiggingState;
use crate::math::Vec3;
use crate::pendulum::{self, Swing, TipMotion};
use serde::{Deserialize, Serialize};

/// The start of a run: hook and load at the X–Y angles and rates of `hoist` and `sling` (the
/// sling's absolute, ignored without a sling), each elastic rope stretched by the tension the
/// same rigging with rigid ropes has in that state, so that the ropes start in axial
/// equilibrium: no axial oscillation, no slack and snap from a stretch that does not fit the
/// start. Hanging straight at rest that is the static stretch m g / k; a pendulum released from
/// rest at θ carries m g cos θ (the centripetal and tangential terms vanish at zero rate), so
/// the weight's stretch would start it 1/cos θ − 1 too long. A rope whose rigid tension would
/// be compressive starts at its unstretched length. The stretch rate starts at zero: the chord
/// turns at the angle rates with its length held.
pub fn start_state(p: &RiggingParams, u: &TipMotion, hoist: &Swing, sling: &Swing) -> Result<RiggingState, String> {
    let rigid = p.rigid();
    let angles = |s: &Swing| (s.theta_x, s.theta_y);
    let mut s = RiggingState::at_angles(&rigid, u, angles(hoist), angles(sling));
    s.hoist_rate = Vec3::new(hoist.omega_x, hoist.omega_y, 0.0);
    if p.has_sling() {
        s.sling_rate = Vec3::new(sling.omega_x, sling.omega_y, 0.0);
    }
    if !p.has_elastic_rope() {
        return Ok(s);
    }
    let tensions = rigging_motion(&rigid, &s, u)?;
    if let RopeLaw::Elastic(rope) = p.hoist {
        (s.hoist, s.hoist_rate) = stretched_chord(u.lp, rope.ea, tensions.hoist_tension, hoist);
    }
    if let (true, RopeLaw::Elastic(rope)) = (p.has_sling(), p.sling) {
        (s.sling, s.sling_rate) = stretched_chord(p.sling_length, rope.ea, tensions.sling_tension, sling);
    }
    Ok(s)
}

/// The chord (end − start, W) and its rate of a rope of unstretched `length` (m) and axial
/// stiffness `ea` (N) carrying `tension` (N; none below zero) at the angles and rates of `swing`:
/// length·(1 + T/EA) along e(θx, θy), turning at the angle rates.
fn stretched_chord(length: f64, ea: f64, tension: f64, swing: &Swing) -> (Vec3, Vec3) {
    let chord = length + tension.max(0.0) * length / ea;
    (direction(swing.theta_x, swing.theta_y) * chord, chord_rate(chord, swing))
}

/// The unit vector e = (sin θy, −cos θy sin θx, cos θy cos θx) of the X–Y angles (eqs. 4.94–4.96).
fn direction(theta_x: f64, theta_y: f64) -> Vec3 {
    Vec3::new(theta_y.sin(), -theta_y.cos() * theta_x.sin(), theta_y.cos() * theta_x.cos())
}

/// The chord rate l (∂e/∂θx θ̇x + ∂e/∂θy θ̇y) of a chord of length `r` at the X–Y angles and rates
/// of `s` (the derivatives of eqs. 4.94–4.96).
pub fn chord_rate(r: f64, s: &Swing) -> Vec3 {
    let (sx, cx) = s.theta_x.sin_cos();
    let (sy, cy) = s.theta_y.sin_cos();
    let d_x = Vec3::new(0.0, -cy * cx, -cy * sx);
    let d_y = Vec3::new(cy, sy * sx, -sy * cx);
    (d_x * s.omega_x + d_y * s.omega_y) * r
}

/// Everything observable about hook and load at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RiggingMotion {
    /// The hook (the hoist rope's end) in W.
    pub hook: BodyMotion,
    /// The load (the sling's end; the hook's point without a sling) in W.
    pub load: BodyMotion,
    /// X–Y angles (θx, θy) (rad) of the hoist rope's chord tip → hook, in the thesis' convention
    /// e = (sin θy, −cos θy sin θx, cos θy cos θx).
    pub hoist_angles: (f64, f64),
    /// X–Y angles (rad) of the sling's chord hook → load (the hoist rope's without a sling).
    pub sling_angles: (f64, f64),
    /// Distance tip → hook (m): l_p for a rigid rope, l_p plus the stretch (or less, slack) for an
    /// elastic one.
    pub hoist_chord: f64,
    /// Hoist rope tension (N), ≥ 0 for an elastic rope (a rigid one's constraint force can be < 0).
    pub hoist_tension: f64,
    /// Sling tension (N); without a sling the load's share of the hoist rope's, e₁·(F_l − m_l a_l).
    pub sling_tension: f64,
    /// Hoist rope slack now (zero tension, or a rigid rope that would need compression).
    pub hoist_slack: bool,
    /// Sling slack now (never without a sling).
    pub sling_slack: bool,
    /// Force of the hoist rope on the crane tip in W (N): T₁ e₁, toward the hook.
    pub tip_force: Vec3,
    /// Peak snap loads (N) of hoist rope and sling so far ([`super::SnapRecord`]).
    pub hoist_peak_snap: f64,
    pub sling_peak_snap: f64,
}

/// Hook and load motion, angles and tensions at state `s` under inputs `u`.
pub fn rigging_motion(p: &RiggingParams, s: &RiggingState, u: &TipMotion) -> Result<RiggingMotion, String> {
    let (hoist_peak_snap, sling_peak_snap) = (s.snap.hoist_peak, s.snap.sling_peak);
    if p.is_single_pendulum() {
        if !(u.lp > 0.0) {
            return Err(format!("hoist length lp must be > 0 m, got {}", u.lp));
        }
        // The pendulum's own outputs, so that this path shows exactly what the pendulum shows.
        let lumped = p.lumped();
        let m = pendulum::load_motion(&lumped, &s.swing(), u);
        let body = BodyMotion { pos: m.pos, vel: m.vel, acc: m.acc };
        let hoist_angles = (s.hoist.x, s.hoist.y);
        let sling_tension = p.load.mass / lumped.mass * m.tension;
        return Ok(RiggingMotion {
            hook: body,
            load: body,
            hoist_angles,
            sling_angles: hoist_angles,
            hoist_chord: u.lp,
            hoist_tension: m.tension,
            sling_tension,
            hoist_slack: m.tension <= 0.0,
            sling_slack: false,
            tip_force: m.cable_force,
            hoist_peak_snap,
            sling_peak_snap,
        });
    }
    let e = evaluate(p, s, u)?;
    let hoist_angles = angles(&e.hoist.unit);
    Ok(RiggingMotion {
        hook: e.hook,
        load: e.load,
        hoist_angles,
        sling_angles: if p.has_sling() { angles(&e.sling.unit) } else { hoist_angles },
        hoist_chord: e.hoist.chord.norm(),
        hoist_tension: e.hoist_tension,
        sling_tension: e.sling_tension,
        hoist_slack: e.hoist_slack,
        sling_slack: e.sling_slack,
        tip_force: e.hoist.unit * e.hoist_tension,
        hoist_peak_snap,
        sling_peak_snap,
    })
}

/// Mechanical energy (J) of hook and load relative to the tip: ½ Σ m |v|² − Σ m g (z − z_t) plus
/// the elastic ropes' strain energy ½ (EA/l₀) max(0, r − l₀)². Conserved for a fixed tip and
/// hoist length without drag and rope damping (the Lagrangian has no explicit time dependence then; Goldstein,
/// Classical Mechanics, 3rd ed., §2.7).
pub fn energy(p: &RiggingParams, s: &RiggingState, u: &TipMotion) -> Result<f64, String> {
    let m = rigging_motion(p, s, u)?;
    let g = p.load.g;
    let (m_h, m_l) = (p.hook_mass, p.load.mass);
    let kinetic = 0.5 * (m_h * m.hook.vel.norm_squared() + m_l * m.load.vel.norm_squared());
    let potential = -g * (m_h * (m.hook.pos.z - u.pos.z) + m_l * (m.load.pos.z - u.pos.z));
    let mut strain = 0.0;
    if let RopeLaw::Elastic(rope) = p.hoist {
        strain += strain_energy(&rope, u.lp, m.hoist_chord);
    }
    if let (true, RopeLaw::Elastic(rope)) = (p.has_sling(), p.sling) {
        strain += strain_energy(&rope, p.sling_length, (m.load.pos - m.hook.pos).norm());
    }
    Ok(kinetic + potential + strain)
}

/// Angular frequencies (ω₁, ω₂) (rad/s, ω₁ < ω₂) of the small-angle normal modes of a double
/// pendulum: hook mass `m_h` on a rigid rope of length `lp` from a fixed point, load `m_l` on a
/// rigid sling of length `ls` below it, gravity `g`. Each swing plane has the same two modes.
///
/// Linearised about the hanging equilibrium the planar motion in the rope angles (φ₁, φ₂) has
/// M φ̈ + K φ = 0 with M = [[(m_h+m_l) l_p², m_l l_p l_s], [m_l l_p l_s, m_l l_s²]] and
/// K = diag((m_h+m_l) g l_p, m_l g l_s); det(K − ω² M) = 0 is
/// m_h l_p l_s ω⁴ − (m_h+m_l) g (l_p+l_s) ω² + (m_h+m_l) g² = 0, so
/// ω² = g/(2 m_h l_p l_s) · [(m_h+m_l)(l_p+l_s) ∓ √((m_h+m_l)((m_h+m_l)(l_p+l_s)² −
/// 4 m_h l_p l_s))]
/// (Landau & Lifshitz, Mechanics, 3rd ed., §23, the double plane pendulum problem; Meirovitch,
/// Elements of Vibration Analysis, 2nd ed., the two-degree-of-freedom eigenproblem).
pub fn normal_modes(m_h: f64, m_l: f64, lp: f64, ls: f64, g: f64) -> (f64, f64) {
    let m = m_h + m_l;
    let sum = lp + ls;
    let root = (m * (m * sum * sum - 4.0 * m_h * lp * ls)).sqrt();
    let scale = g / (2.0 * m_h * lp * ls);
    ((scale * (m * sum - root)).sqrt(), (scale * (m * sum + root)).sqrt())
}

/// The shape of the mode of angular frequency `omega` of [`normal_modes`]: the sling angle per unit
/// rope angle, from the first row of (K − ω² M) φ = 0, (m_h+m_l) l_p (g − ω² l_p) φ₁ −
/// m_l l_p l_s ω² φ₂ = 0: φ₂/φ₁ = (m_h+m_l)(g − ω² l_p) / (m_l ω² l_s).
pub fn mode_shape(m_h: f64, m_l: f64, lp: f64, ls: f64, g: f64, omega: f64) -> f64 {
    let w2 = omega * omega;
    (m_h + m_l) * (g - w2 * lp) / (m_l * w2 * ls)
}

/// Peak tension (N) of a rope caught taut by a body of mass `m` (kg) arriving at `v` (m/s) along
/// the rope as it becomes straight, spring rate k = EA/l (N/m), gravity `g`, no damping: the
/// energy balance from the catch to the largest stretch δ (where the body stops),
/// ½ m v² + m g δ = ½ k δ², gives δ = (m g + √((m g)² + k m v²))/k and
///
///   T_peak = k δ = m g + √((m g)² + k m v²)
///
/// (the suddenly applied / falling-weight impact load, Gere & Timoshenko, Mechanics of Materials,
/// §2.8 "Impact loading", with the drop height h = v²/(2g); without gravity it is DNV-RP-H103's
/// snap force v √(k m), §4.7).
pub fn snap_load_estimate(m: f64, v: f64, k: f64, g: f64) -> f64 {
    let weight = m * g;
    weight + (weight * weight + k * m * v * v).sqrt()
}

/// The hoist rope's force on the tip as an affine function of the tip's acceleration and the hoist
/// length's acceleration at one state and tip velocity: F = F₀ + A a_t + b l̈_p (N).
///
/// Why: a crane model that is handed the whole force held over a step, against a load heavier than
/// its own effective mass at the tip, diverges (the added-mass instability of partitioned
/// schemes, docs/full-scale.md); it instead takes F₀ and the sensitivities and solves its own
/// accelerations with them. The equations of motion are linear in a_t and l̈_p (M does not depend
/// on them, f is affine in them), so a rigid rope's tension — and with it F — is affine in them and
/// the columns below are exact to round-off; an elastic rope's force depends on the state alone
/// (A = 0, b = 0). For the single pendulum A = −m e eᵀ and b = −m e (thesis eq. 4.127).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TipCoupling {
    /// F₀: the force for an unaccelerated tip and a steady hoist length (N).
    pub free_force: Vec3,
    /// A = ∂F/∂a_t (kg).
    pub per_tip_acc: nalgebra::Matrix3<f64>,
    /// b = ∂F/∂l̈_p (kg).
    pub per_lp_acc: Vec3,
}

/// [`TipCoupling`] at state `s` with the tip's position and velocity and the hoist length and its
/// rate from `u` (its accelerations are not used).
pub fn tip_coupling(p: &RiggingParams, s: &RiggingState, u: &TipMotion) -> Result<TipCoupling, String> {
    let steady = TipMotion { acc: Vec3::zeros(), lp_ddot: 0.0, ..*u };
    let free_force = rigging_motion(p, s, &steady)?.tip_force;
    let mut per_tip_acc = nalgebra::Matrix3::<f64>::zeros();
    for (i, axis) in [Vec3::x(), Vec3::y(), Vec3::z()].into_iter().enumerate() {
        let pushed = rigging_motion(p, s, &TipMotion { acc: axis, ..steady })?.tip_force;
        per_tip_acc.set_column(i, &(pushed - free_force));
    }
    let paid = rigging_motion(p, s, &TipMotion { lp_ddot: 1.0, ..steady })?.tip_force;
    Ok(TipCoupling { free_force, per_tip_acc, per_lp_acc: paid - free_force })
}

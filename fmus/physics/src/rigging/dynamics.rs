//! Equations of motion of hook and load, and their integration.
//!
//! Two point masses: the hook at x_h = x_t + s₁ and the load at x_l = x_h + s₂, with s₁ the hoist
//! rope's chord and s₂ the sling's ([`super::segment`]; no sling: s₂ = 0, one lumped body). With
//! the generalised coordinates q = (q₁, q₂) of the two segments, x_t(t) and l_p(t) prescribed:
//!
//!   ẍ_h = a_t + J₁ q̈₁ + b₁,   ẍ_l = ẍ_h + J₂ q̈₂ + b₂.
//!
//! The equations of motion are Newton's laws of the two bodies projected on the partial
//! velocities ∂ẋ/∂q̇ (Kane's equations, Kane & Levinson, Dynamics: Theory and Applications, 1985,
//! ch. 6; for holonomic coordinates they are Lagrange's equations of the second kind, Goldstein,
//! Classical Mechanics, 3rd ed., §1.4), so that the rigid ropes' constraint forces, normal to the
//! motion they allow, drop out:
//!
//!   J₁ᵀ [m_h ẍ_h + m_l ẍ_l − F_h − F_l] = 0,   J₂ᵀ [m_l ẍ_l − F_l] = 0,
//!
//! that is M q̈ = f with the symmetric positive definite
//!
//!   M = [[(m_h + m_l) J₁ᵀJ₁, m_l J₁ᵀJ₂], [m_l J₂ᵀJ₁, m_l J₂ᵀJ₂]],
//!   f = [J₁ᵀ (F_h + F_l − (m_h + m_l)(a_t + b₁) − m_l b₂), J₂ᵀ (F_l − m_l (a_t + b₁ + b₂))],
//!
//! where the applied forces are gravity m g ẑ (W is North-East-Down), the drag of
//! [`super::rope::drag`] and the elastic ropes' tensions T along their unit chords e:
//! F_h = m_h g ẑ + D_h − T₁ e₁ + T₂ e₂ and F_l = m_l g ẑ + D_l − T₂ e₂ (T of a rigid rope is not an
//! applied force: it is the constraint force, recovered afterwards from Newton's law along the
//! rope). Unused coordinate slots get a unit diagonal and a zero right-hand side (q̈ = 0 there).
//! With two rigid ropes this is the double spherical pendulum in four angles (for its planar
//! small-angle limit, Landau & Lifshitz, Mechanics, 3rd ed., §23, the double plane pendulum
//! problem); with an elastic rope the body below it moves in Cartesian coordinates, where a slack
//! rope is simply no force: the body flies free (ballistic plus drag) until the rope tightens
//! again.

use super::params::{RiggingParams, RopeLaw};
use super::rope::{drag, tension};
use super::segment::{Coordinates, Length, Segment};
use super::state::{layout, RiggingState, SnapRecord, STATE_LEN};
use crate::integrate::{rk4_from, substeps};
use crate::math::{Matrix3, Vec3};
use crate::pendulum::{self, TipMotion};
use nalgebra::{Matrix6, SVector, Vector6};

/// Below this cos θy a rigid rope's θx coordinate is singular (the pendulum's limit, the gimbal
/// lock of the X–Y sequence).
const MIN_COS_THETA_Y: f64 = 1e-6;

/// Largest phase (rad) the fastest mode may advance in one substep: substeps are shortened below
/// [`crate::integrate::MAX_SUBSTEP`] until ω_max·dt ≤ 0.02, where RK4's relative frequency error
/// (ω dt)⁴/120 is 1.3·10⁻⁹ and its amplitude loss (ω dt)⁶/144 per step 4.4·10⁻¹³, from RK4's
/// stability function R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 at z = iω dt (Hairer, Nørsett & Wanner,
/// Solving Ordinary Differential Equations I). A stiff steel rope needs it.
const MAX_PHASE_PER_SUBSTEP: f64 = 0.02;

/// At most this many substeps per call (a bound on the work, not a physical limit).
const MAX_SUBSTEPS: usize = 10_000_000;

/// Position, velocity and acceleration of one body in W (m, m/s, m/s²).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct BodyMotion {
    pub pos: Vec3,
    pub vel: Vec3,
    pub acc: Vec3,
}

/// Everything the equations give at one state and input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Evaluation {
    pub hoist: Segment,
    pub sling: Segment,
    pub hook: BodyMotion,
    pub load: BodyMotion,
    /// q̈ of both segments (slots as the state's).
    pub hoist_acc: Vec3,
    pub sling_acc: Vec3,
    /// Tensions (N) and slack states of both ropes.
    pub hoist_tension: f64,
    pub hoist_slack: bool,
    pub sling_tension: f64,
    pub sling_slack: bool,
}

/// The equations of motion at state `s` (continuous part) under inputs `u`; an error where the
/// hoist length is not positive, a rigid rope reaches θy = ±90°, or the state is not finite.
pub(super) fn evaluate(p: &RiggingParams, s: &RiggingState, u: &TipMotion) -> Result<Evaluation, String> {
    if !(u.lp > 0.0) {
        return Err(format!("hoist length lp must be > 0 m, got {}", u.lp));
    }
    let finite = [s.hoist, s.sling, s.hoist_rate, s.sling_rate].iter().all(|v| v.iter().all(|c| c.is_finite()));
    if !finite {
        return Err(format!("the rigging state is not finite: {s:?}"));
    }
    let (kind1, kind2) = layout(p);
    let hoist_len = Length { l: u.lp, rate: u.lp_dot, acc: u.lp_ddot };
    let sling_len = Length { l: p.sling_length, rate: 0.0, acc: 0.0 };
    let seg1 = Segment::new(kind1, &s.hoist, &s.hoist_rate, &hoist_len);
    let seg2 = Segment::new(kind2, &s.sling, &s.sling_rate, &sling_len);
    // As the pendulum's check: cos θy must be positive, not only large in magnitude, since a fast
    // swing can step over ±90° between two checks.
    for (kind, seg, theta_y, name) in [(kind1, &seg1, s.hoist.y, "hoist rope"), (kind2, &seg2, s.sling.y, "sling")] {
        let clear = seg.cos_theta_y > MIN_COS_THETA_Y && theta_y.abs() < std::f64::consts::PI;
        if kind == Coordinates::Angles && !clear {
            return Err(format!("{name} theta_y = {theta_y} rad reaches the ±90° singularity of the X–Y angles"));
        }
    }
    let (m_h, m_l, g) = (p.hook_mass, p.load.mass, p.load.g);
    let gravity = Vec3::new(0.0, 0.0, g);
    let v_h = u.vel + seg1.chord_rate;
    let v_l = v_h + seg2.chord_rate;
    // Elastic tensions (applied forces); zero for rigid ropes, whose tension comes afterwards.
    let elastic = |law, seg: &Segment, len: &Length| match law {
        RopeLaw::Elastic(rope) => {
            Some(tension(&rope, len.l, len.rate, seg.chord.norm(), seg.unit.dot(&seg.chord_rate)))
        }
        RopeLaw::Rigid => None,
    };
    let t1_elastic = elastic(p.hoist, &seg1, &hoist_len);
    let t2_elastic = if kind2 == Coordinates::Absent { None } else { elastic(p.sling, &seg2, &sling_len) };
    let (t1e, t2e) = (t1_elastic.unwrap_or(0.0), t2_elastic.unwrap_or(0.0));
    // The load's drag acts across the rope it hangs from: the sling, or the hoist rope without one.
    let load_swing = if kind2 == Coordinates::Absent { &seg1.swing } else { &seg2.swing };
    let f_h =
        gravity * m_h + drag(m_h, p.hook_drag, p.hook_drag, &v_h, &seg1.swing) - seg1.unit * t1e + seg2.unit * t2e;
    let f_l = gravity * m_l + drag(m_l, p.load.kappa_x, p.load.kappa_y, &v_l, load_swing) - seg2.unit * t2e;
    // M q̈ = f (module documentation).
    let (j1, j2) = (&seg1.jacobian, &seg2.jacobian);
    let m_sum = m_h + m_l;
    let a_base = u.acc + seg1.bias;
    let mut mass = Matrix6::<f64>::zeros();
    mass.fixed_view_mut::<3, 3>(0, 0).copy_from(&(j1.transpose() * j1 * m_sum));
    let coupling: Matrix3<f64> = j1.transpose() * j2 * m_l;
    mass.fixed_view_mut::<3, 3>(0, 3).copy_from(&coupling);
    mass.fixed_view_mut::<3, 3>(3, 0).copy_from(&coupling.transpose());
    mass.fixed_view_mut::<3, 3>(3, 3).copy_from(&(j2.transpose() * j2 * m_l));
    let unused = |kind: Coordinates, i: usize| if kind.uses(i) { 0.0 } else { 1.0 };
    let padding = Vector6::from_fn(|i, _| if i < 3 { unused(kind1, i) } else { unused(kind2, i - 3) });
    mass += Matrix6::from_diagonal(&padding);
    let f1 = j1.transpose() * (f_h + f_l - a_base * m_sum - seg2.bias * m_l);
    let f2 = j2.transpose() * (f_l - (a_base + seg2.bias) * m_l);
    let rhs = Vector6::new(f1.x, f1.y, f1.z, f2.x, f2.y, f2.z);
    let qdd = mass.cholesky().ok_or_else(|| format!("the rigging's mass matrix is singular at {s:?}"))?.solve(&rhs);
    let hoist_acc: Vec3 = qdd.fixed_rows::<3>(0).into_owned();
    let sling_acc: Vec3 = qdd.fixed_rows::<3>(3).into_owned();
    let a_h = a_base + j1 * hoist_acc;
    let a_l = a_h + j2 * sling_acc + seg2.bias;
    // Rigid tensions: Newton's law along the rope, m_h a_h + m_l a_l = F_h + F_l − T₁ e₁ for the
    // hoist rope (the sling's forces are internal), m_l a_l = F_l − T₂ e₂ for the sling. Without a
    // sling the "sling tension" is the load's share of the hoist rope's, e₁·(F_l − m_l a_l).
    let hoist_tension = t1_elastic.unwrap_or_else(|| seg1.unit.dot(&(f_h + f_l - a_h * m_h - a_l * m_l)));
    let sling_tension = match (kind2, t2_elastic) {
        (_, Some(t)) => t,
        (Coordinates::Absent, None) => seg1.unit.dot(&(f_l - a_l * m_l)),
        (_, None) => seg2.unit.dot(&(f_l - a_l * m_l)),
    };
    let slack = |t: f64, elastic: Option<f64>| if elastic.is_some() { t == 0.0 } else { t <= 0.0 };
    Ok(Evaluation {
        hoist: seg1,
        sling: seg2,
        hook: BodyMotion { pos: u.pos + seg1.chord, vel: v_h, acc: a_h },
        load: BodyMotion { pos: u.pos + seg1.chord + seg2.chord, vel: v_l, acc: a_l },
        hoist_acc,
        sling_acc,
        hoist_tension,
        hoist_slack: slack(hoist_tension, t1_elastic),
        sling_tension,
        sling_slack: kind2 != Coordinates::Absent && slack(sling_tension, t2_elastic),
    })
}

/// dx/dt of the continuous state vector x (layout of [`RiggingState`]).
fn rate_of(e: &Evaluation, x: &SVector<f64, STATE_LEN>) -> SVector<f64, STATE_LEN> {
    let mut dx = SVector::<f64, STATE_LEN>::zeros();
    dx.fixed_rows_mut::<6>(0).copy_from(&x.fixed_rows::<6>(6));
    dx.fixed_rows_mut::<3>(6).copy_from(&e.hoist_acc);
    dx.fixed_rows_mut::<3>(9).copy_from(&e.sling_acc);
    dx
}

/// [`rate_of`] for a stage of the Runge–Kutta step, where an error cannot be returned: a state the
/// equations reject gives NaN rates, which the next substep's check reports.
fn stage_rate(p: &RiggingParams, x: &SVector<f64, STATE_LEN>, u: &TipMotion) -> SVector<f64, STATE_LEN> {
    match evaluate(p, &RiggingState::from_vector(x, SnapRecord::default()), u) {
        Ok(e) => rate_of(&e, x),
        Err(_) => SVector::<f64, STATE_LEN>::repeat(f64::NAN),
    }
}

/// Squared angular frequency (rad²/s²) of the fastest mode, an upper estimate from the
/// parameters and the shortest hoist length `lp` of the step: an elastic hoist rope's bounce
/// k₁/m (m the mass it carries directly: the hook, or hook and load without a sling), an elastic
/// sling's k₂ (1/m_h + 1/m_l) (the two-mass relative mode), and a rigid sling's second pendulum
/// mode, bounded by g (m_h + m_l)/m_h · (1/l_s + 1/l_p) (the large root of the double pendulum's
/// frequency equation, [`super::normal_modes`], is below it).
fn fastest_mode_squared(p: &RiggingParams, lp: f64) -> f64 {
    let (m_h, m_l, g) = (p.hook_mass, p.load.mass, p.load.g);
    let mut w2 = 0.0;
    if let RopeLaw::Elastic(rope) = p.hoist {
        let carried = if p.has_sling() { m_h } else { m_h + m_l };
        w2 += rope.ea / lp / carried;
    }
    if p.has_sling() {
        w2 += match p.sling {
            RopeLaw::Elastic(rope) => rope.ea / p.sling_length * (1.0 / m_h + 1.0 / m_l),
            RopeLaw::Rigid => g * (m_h + m_l) / m_h * (1.0 / p.sling_length + 1.0 / lp),
        };
    }
    w2
}

/// Number of equal substeps for a step of `h` seconds: at most 1 ms each ([`substeps`]) and
/// short enough for [`MAX_PHASE_PER_SUBSTEP`] at the fastest mode.
fn substep_count(p: &RiggingParams, u: &TipMotion, rate: &TipMotion, h: f64) -> Result<usize, String> {
    let lp = u.lp.min(u.ramp(rate, h).lp);
    if !(lp > 0.0) {
        return Err(format!("hoist length lp must stay > 0 m over the step, reaches {lp}"));
    }
    let by_phase = h * fastest_mode_squared(p, lp).sqrt() / MAX_PHASE_PER_SUBSTEP;
    if !(by_phase <= MAX_SUBSTEPS as f64) {
        return Err(format!("the step of {h} s needs more than {MAX_SUBSTEPS} substeps for the rope stiffness"));
    }
    Ok(substeps(h).max(by_phase.ceil() as usize))
}

/// Advances the rigging over one communication step [t, t + h]. `u` holds the inputs at t and
/// `rate` their time derivatives within the step (as [`pendulum::advance`]).
///
/// No sling and a rigid hoist rope: exactly [`pendulum::advance`] with the lumped body
/// ([`RiggingParams::lumped`]), the thesis' code path. Otherwise RK4 substeps of at most 1 ms,
/// shorter for stiff ropes, of the equations of the module documentation; the snap record is
/// sampled at every substep end. A slack rope is no error.
pub fn advance(
    p: &RiggingParams,
    s: &RiggingState,
    u: &TipMotion,
    rate: &TipMotion,
    h: f64,
) -> Result<RiggingState, String> {
    if p.is_single_pendulum() {
        let lumped = p.lumped();
        let swing = pendulum::advance(&lumped, &s.swing(), u, rate, h)?;
        let mut end = RiggingState { snap: s.snap, ..RiggingState::from_swing(&swing) };
        let tension = pendulum::tension(&lumped, &swing, &u.ramp(rate, h));
        end.snap.sample((tension, tension <= 0.0), (0.0, false));
        return Ok(end);
    }
    let n = substep_count(p, u, rate, h)?;
    let dt = h / n as f64;
    let mut snap = s.snap;
    let mut x = s.to_vector();
    for i in 0..n {
        let tau = i as f64 * dt;
        let u_tau = u.ramp(rate, tau);
        let e = evaluate(p, &RiggingState::from_vector(&x, snap), &u_tau)?;
        if i > 0 {
            snap.sample((e.hoist_tension, e.hoist_slack), (e.sling_tension, e.sling_slack));
        }
        let k1 = rate_of(&e, &x);
        let (u_mid, u_end) = (u.ramp(rate, tau + 0.5 * dt), u.ramp(rate, tau + dt));
        x = rk4_from(&x, k1, dt, |x| stage_rate(p, x, &u_mid), |x| stage_rate(p, x, &u_end));
    }
    let end = evaluate(p, &RiggingState::from_vector(&x, snap), &u.ramp(rate, h))?;
    snap.sample((end.hoist_tension, end.hoist_slack), (end.sling_tension, end.sling_slack));
    Ok(RiggingState::from_vector(&x, snap))
}

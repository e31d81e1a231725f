//! FMU `rigging`: hook and load below the crane tip (docs/rigging.md), a sibling of the
//! pendulum FMU that wraps [`physics::rigging`].
//!
//! A hook (block) on the hoist rope and a load on a sling below it: a double spherical pendulum
//! whose ropes are rigid or elastic; an elastic rope carries no compression, so that hook and load
//! fly free while it is slack and snap it taut again (no error, the run goes on). The crane tip's
//! motion and the hoist length are inputs, with the pendulum FMU's names, causalities and
//! interpolation (inputs ramp within a step when the importer sets their derivatives, velocity
//! ramps are reconciled with their accelerations, [`TipMotion::reconciled`]), and every output the
//! pendulum has keeps its name (`load.*`, `theta_*`, `omega_*`, `tension`, `cable.*`), so that the
//! rigging replaces the pendulum in a system file by changing the instance's FMU only.
//!
//! With `sling.length = 0` and a rigid hoist rope the rigging is the pendulum's code path
//! ([`physics::rigging::advance`] hands the step to [`physics::pendulum::advance`]): with the
//! pendulum's parameters (`hook.mass = 0`) the outputs equal the pendulum FMU's to the bit.
//! All ports SI, world frame W North-East-Down.

use fmu_model::{
    body_outputs, load_outputs, pendulum_parameters, swing_outputs, swing_parameters, tip_motion_inputs, Environment,
    Model, ModelInfo, Variable,
};
use physics::crane::plant::DEFAULT_POSE;
use physics::math::{components, rot_x, rot_y, Quat, Vec3};
use physics::pendulum::{load_kinematics, PendulumParams, Swing, TipMotion, VelocitySlopes};
use physics::rigging::{
    advance, rigging_motion, start_state, tip_coupling, BodyMotion, ElasticRope, RiggingMotion, RiggingParams,
    RiggingState, RopeLaw, TipCoupling,
};
use serde::{Deserialize, Serialize};

#[cfg(test)]
mod tests;

/// A rope's direction and its rate as the thesis' X–Y angles, and what an IMU on the body hanging
/// from it sees of it.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RopeSwing {
    pub swing: Swing,
    /// Orientation W←body, R_x(θx) R_y(θy), no twist about the rope (the pendulum's `load.q*`).
    pub orientation: Quat,
    /// Angular velocity in the body frame (rad/s): (θ̇x cos θy, θ̇y, θ̇x sin θy).
    pub angular_velocity: Vec3,
}

impl RopeSwing {
    fn new(swing: Swing) -> RopeSwing {
        let (sy, cy) = swing.theta_y.sin_cos();
        RopeSwing {
            swing,
            orientation: rot_x(swing.theta_x) * rot_y(swing.theta_y),
            angular_velocity: Vec3::new(swing.omega_x * cy, swing.omega_y, swing.omega_x * sy),
        }
    }
}

/// The X–Y angles of a chord `s` (end − start, W) and their rates from the chord's rate `s_dot`:
/// e = s/|s|, ė = (ṡ − e (e·ṡ))/|s|, θx = atan2(−e_y, e_z), θy = asin e_x, so
/// θ̇x = (e_y ė_z − e_z ė_y)/(e_y² + e_z²) and θ̇y = ė_x / cos θy (0 at the singularity e = ±x,
/// and everything 0 for a chord of length 0).
pub fn chord_swing(s: &Vec3, s_dot: &Vec3) -> Swing {
    let r = s.norm();
    if !(r > 0.0) {
        return Swing::default();
    }
    let e = s / r;
    let e_dot = (s_dot - e * e.dot(s_dot)) / r;
    let across = e.y * e.y + e.z * e.z;
    let (omega_x, omega_y) =
        if across > 0.0 { ((e.y * e_dot.z - e.z * e_dot.y) / across, e_dot.x / across.sqrt()) } else { (0.0, 0.0) };
    Swing { theta_x: (-e.y).atan2(e.z), theta_y: e.x.clamp(-1.0, 1.0).asin(), omega_x, omega_y }
}

/// Rope law codes of the `hoist.law` and `sling.law` parameters.
const RIGID: i32 = 0;
const ELASTIC: i32 = 1;

/// The rope law of a code with the elastic rope's constants, or `None` for an unknown code.
pub fn rope_law(code: i32, rope: ElasticRope) -> Option<RopeLaw> {
    match code {
        RIGID => Some(RopeLaw::Rigid),
        ELASTIC => Some(RopeLaw::Elastic(rope)),
        _ => None,
    }
}

/// The code of a rope law (inverse of [`rope_law`]).
pub fn law_code(law: RopeLaw) -> i32 {
    match law {
        RopeLaw::Rigid => RIGID,
        RopeLaw::Elastic(_) => ELASTIC,
    }
}

/// What the outputs show, computed at every communication point.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
struct Outputs {
    motion: RiggingMotion,
    hoist: RopeSwing,
    sling: RopeSwing,
    /// F₀ of [`physics::rigging::TipCoupling`] (N, W).
    free_force: Vec3,
    /// The mass along the rope the crane integrates with F₀ (kg).
    cable_mass: f64,
}

/// Instance data: configuration, inputs, continuous state and the outputs last computed.
#[derive(Clone, Serialize, Deserialize)]
pub struct Rigging {
    /// The load (mass, drag rates κx, κy, g), as the pendulum's parameters.
    load: PendulumParams,
    hook_mass: f64,
    hook_drag: f64,
    sling_length: f64,
    /// Rope law codes ([`RIGID`], [`ELASTIC`]) and the elastic ropes' constants (used when elastic).
    hoist_law: i32,
    hoist_rope: ElasticRope,
    sling_law: i32,
    sling_rope: ElasticRope,
    /// Initial hoist rope angles and rates (applied at release).
    initial: Swing,
    /// Initial sling angles relative to the hoist rope's (added to `initial`'s) and the sling's
    /// angle rates (rad, rad/s).
    sling_initial: Swing,
    /// Hook and load are held at their initial angles (rates zero) until this time (s).
    release_time: f64,
    /// Inputs as last set, and their time derivatives for the coming step.
    input: TipMotion,
    input_rate: TipMotion,
    /// Which velocity inputs have a derivative for the coming step (acceleration reconciliation).
    slopes: VelocitySlopes,
    state: RiggingState,
    /// Inputs at the current communication point (the interpolated end of the last step).
    input_now: TipMotion,
    time: f64,
    out: Outputs,
}

impl Rigging {
    fn held(&self) -> bool {
        self.time < self.release_time
    }

    /// The rigging's constants from the parameters, validated.
    fn params(&self) -> Result<RiggingParams, String> {
        let law = |name: &str, code: i32, rope: ElasticRope| {
            rope_law(code, rope).ok_or_else(|| format!("{name} must be 0 (rigid) or 1 (elastic), got {code}"))
        };
        let p = RiggingParams {
            load: self.load,
            hook_mass: self.hook_mass,
            hook_drag: self.hook_drag,
            sling_length: self.sling_length,
            hoist: law("hoist.law", self.hoist_law, self.hoist_rope)?,
            sling: law("sling.law", self.sling_law, self.sling_rope)?,
        };
        p.validate()?;
        Ok(p)
    }

    /// Hook and load at the initial angles under the inputs `u`, at rest when `held`, else with
    /// the initial rates; an elastic rope stretched by the tension it carries in that state
    /// ([`start_state`]: the ropes start in axial equilibrium).
    fn initial_state(&self, p: &RiggingParams, u: &TipMotion, held: bool) -> Result<RiggingState, String> {
        let rest = |swing: Swing| if held { Swing { omega_x: 0.0, omega_y: 0.0, ..swing } } else { swing };
        let sling = Swing {
            theta_x: self.initial.theta_x + self.sling_initial.theta_x,
            theta_y: self.initial.theta_y + self.sling_initial.theta_y,
            ..self.sling_initial
        };
        start_state(p, u, &rest(self.initial), &rest(sling))
    }

    /// The crane's force coupling (`cable.f0` and its partial derivatives) and `cable.mass`.
    ///
    /// Held (before release), hook and load ride with the tip whatever the ropes are, so the
    /// crane carries them as the rigid rigging at the held angles: their inertia as `cable.mass`
    /// with the force of an unaccelerated tip. An elastic rope's own coupling would instead pass
    /// the held bodies' inertia as a force that follows the tip's acceleration one step late, an
    /// explicit added-mass coupling that diverges when the load outweighs the tip's own effective
    /// mass (5.3 t under the full-scale crane: the rope's tension grew from 52 kN to 2.6 GN in
    /// 0.18 s).
    fn crane_coupling(&self, p: &RiggingParams) -> Result<(TipCoupling, f64), String> {
        let u = &self.input_now;
        let coupling_of = |p: &RiggingParams, s: &RiggingState| {
            let coupling = tip_coupling(p, s, u)?;
            let cable_mass = if p.is_single_pendulum() {
                p.lumped().mass
            } else {
                effective_mass(&coupling.free_force, &coupling.per_lp_acc)
            };
            Ok((coupling, cable_mass))
        };
        if self.held() && p.has_elastic_rope() {
            let rigid = p.rigid();
            coupling_of(&rigid, &self.initial_state(&rigid, u, true)?)
        } else {
            coupling_of(p, &self.state)
        }
    }

    fn check_inputs(&self) -> Result<(), String> {
        let u = &self.input;
        let finite = [u.pos, u.vel, u.acc].iter().all(|v| v.iter().all(|c| c.is_finite()))
            && [u.lp, u.lp_dot, u.lp_ddot].iter().all(|c| c.is_finite());
        if !finite {
            return Err(format!("the inputs are not finite: {u:?}"));
        }
        if !(u.lp > 0.0) {
            return Err(format!("hoist length lp must be > 0 m, got {}", u.lp));
        }
        Ok(())
    }

    /// Computes the outputs. A rigid hoist rope that would have to push is an error, as the
    /// pendulum's slack cable: the model holds the hook at the rope's length, which only a taut
    /// rope can do (an elastic rope law models slack and snap). A rigid sling is only flagged
    /// (`sling.slack`): it carries exactly zero tension whenever hook and load fly free together on
    /// a slack elastic hoist rope, and keeps its constraint (physics::rigging).
    fn update_outputs(&mut self, p: &RiggingParams) -> Result<(), String> {
        let (s, u) = (&self.state, &self.input_now);
        let mut motion = rigging_motion(p, s, u)?;
        if self.held() {
            held_kinematics(p, s, u, &mut motion);
        }
        // A state too large for the equations (a start rate of 1e300 rad/s squares to infinity)
        // is named as such, not taken for a rope that goes slack.
        if !motion.hoist_tension.is_finite() {
            return Err(format!(
                "the hoist rope tension is {} N at t = {} s: the swing state is too large to compute with \
                 ({:?}; check the start angles and rates)",
                motion.hoist_tension,
                self.time,
                s.swing()
            ));
        }
        if p.hoist == RopeLaw::Rigid && !(motion.hoist_tension > 0.0) {
            return Err(format!(
                "the rigid hoist rope goes slack at t = {} s (tension {} N <= 0): the hook would leave the length \
                 constraint (hoist.law = 1, an elastic rope, models slack)",
                self.time, motion.hoist_tension
            ));
        }
        let hoist = match p.hoist {
            RopeLaw::Rigid => s.swing(),
            RopeLaw::Elastic(_) => chord_swing(&s.hoist, &s.hoist_rate),
        };
        let sling = match (p.has_sling(), p.sling) {
            (false, _) => hoist,
            (true, RopeLaw::Rigid) => {
                Swing { theta_x: s.sling.x, theta_y: s.sling.y, omega_x: s.sling_rate.x, omega_y: s.sling_rate.y }
            }
            (true, RopeLaw::Elastic(_)) => chord_swing(&s.sling, &s.sling_rate),
        };
        let (coupling, cable_mass) = self.crane_coupling(p)?;
        self.out = Outputs {
            motion,
            hoist: RopeSwing::new(hoist),
            sling: RopeSwing::new(sling),
            free_force: coupling.free_force,
            cable_mass,
        };
        Ok(())
    }
}

/// The mass m along the rope for the crane's force coupling F = (T₀ − m (e·a_t + l̈_p)) e with
/// e = F₀/|F₀| (physics::hydraulic_crane::plant::Loads): m = −e·b, b = ∂F/∂l̈_p of
/// [`physics::rigging::TipCoupling`]; 0 when the force is zero (a slack rope) or does not depend on
/// l̈_p (an elastic rope, b = 0), never negative.
pub fn effective_mass(free_force: &Vec3, per_lp_acc: &Vec3) -> f64 {
    let norm = free_force.norm();
    if !(norm > 0.0) {
        return 0.0;
    }
    (-(free_force / norm).dot(per_lp_acc)).max(0.0)
}

/// Hook and load held (before release): they move with the tip and the paid-out rope, the ropes at
/// their held directions, velocity and acceleration of both ẋ_t + ṙ e₁ and ẍ_t + r̈ e₁ with
/// r the hoist chord and ṙ = l̇_p r/l_p, r̈ = l̈_p r/l_p (the pendulum's held load: zero angular
/// rates and accelerations). The tensions stay those of the state at rest.
fn held_kinematics(p: &RiggingParams, s: &RiggingState, u: &TipMotion, motion: &mut RiggingMotion) {
    if p.is_single_pendulum() {
        // The pendulum's own held kinematics, so that this path shows what the pendulum shows.
        let m = load_kinematics(&p.lumped(), &s.swing(), u, (0.0, 0.0));
        let body = BodyMotion { pos: m.pos, vel: m.vel, acc: m.acc };
        (motion.hook, motion.load) = (body, body);
        return;
    }
    let chord = motion.hook.pos - u.pos;
    let r = chord.norm();
    let e = if r > 0.0 { chord / r } else { Vec3::z() };
    let scale = r / u.lp;
    let vel = u.vel + e * (u.lp_dot * scale);
    let acc = u.acc + e * (u.lp_ddot * scale);
    for body in [&mut motion.hook, &mut motion.load] {
        (body.vel, body.acc) = (vel, acc);
    }
}

impl Model for Rigging {
    const INFO: ModelInfo = ModelInfo::new(
        "rigging",
        concat!(
            "Hook and load below the crane tip: a double spherical pendulum on a rigid or elastic, slack-capable ",
            "hoist rope and sling, driven by the crane tip motion and hoist length (the pendulum FMU's ",
            "ports; sling length 0 and a rigid rope are the pendulum, thesis eqs. 4.131-4.133)",
        ),
    )
    .stop_time(60.0)
    .interpolating_inputs()
    .max_step(MAX_STEP_SIZE);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(_env: &Environment) -> Self {
        Rigging {
            load: LOAD,
            hook_mass: HOOK_MASS,
            hook_drag: HOOK_DRAG,
            sling_length: SLING_LENGTH,
            hoist_law: RIGID,
            hoist_rope: ROPE,
            sling_law: RIGID,
            sling_rope: ROPE,
            initial: INITIAL,
            sling_initial: INITIAL,
            release_time: RELEASE_TIME,
            input: INPUT,
            input_rate: TipMotion::default(),
            slopes: VelocitySlopes::default(),
            state: RiggingState::default(),
            input_now: TipMotion::default(),
            time: 0.0,
            out: Outputs::default(),
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        let p = self.params()?;
        self.check_inputs()?;
        self.time = start_time;
        self.input_now = self.input;
        self.state = self.initial_state(&p, &self.input, self.held())?;
        self.update_outputs(&p)
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        let p = self.params()?;
        self.check_inputs()?;
        let end = t + h;
        if end <= self.release_time {
            self.state = self.initial_state(&p, &self.input.ramp(&self.input_rate, h), true)?;
        } else {
            // Release inside this step: the free motion starts from the initial state at release.
            let free_from = (self.release_time - t).max(0.0);
            if free_from > 0.0 {
                self.state = self.initial_state(&p, &self.input.ramp(&self.input_rate, free_from), false)?;
            }
            let (input, rate) = self.input.reconciled(&self.input_rate, &self.slopes, h);
            let start = input.ramp(&rate, free_from);
            self.state = advance(&p, &self.state, &start, &rate, h - free_from)?;
        }
        self.time = end;
        self.input_now = self.input.ramp(&self.input_rate, h);
        self.update_outputs(&p)
    }
}

type V = Variable<Rigging>;
type Real = fmu_model::Real<Rigging>;
type Integer = fmu_model::Integer<Rigging>;
type Boolean = fmu_model::Boolean<Rigging>;

/// Largest communication step (s): at most one million RK4 substeps of 1 ms per `fmi2DoStep` (a
/// stiff elastic rope shortens the substeps, and `physics::rigging` bounds their number).
const MAX_STEP_SIZE: f64 = 1000.0;

/// The defaults, the start values of the table and of [`Model::new`]: the thesis' rig (its load's
/// drag, §7.2.3, on the crane's default 0.7 m of rigid hoist rope) with a hook: the thesis' 0.3018 kg
/// that hangs on the cable split 1 : 2 into a 0.1006 kg hook and a 0.2012 kg load (hook/load mass
/// ratio 0.5) on a rigid 0.2 m sling, inside the test-scale study's range (l_s = 0.1–0.3 m, ratios
/// 0.2–1); hanging straight down at rest, released at once, the tip at rest at the origin of W.
const LOAD: PendulumParams = PendulumParams { mass: 0.2012, ..PendulumParams::DEFAULT };
const HOOK_MASS: f64 = 0.1006;
/// The smaller of the thesis' two drag rates (`RiggingParams::DEFAULT`'s, no hook measurement).
const HOOK_DRAG: f64 = RiggingParams::DEFAULT.hook_drag;
const SLING_LENGTH: f64 = 0.2;
/// The elastic rope's constants when a law is switched to elastic: EA = 1000 N, a thin synthetic
/// line at test scale (0.3 % static stretch under the rig's 2.96 N), undamped. An order of
/// magnitude, not a measurement: set the rope's EA.
const ROPE: ElasticRope = ElasticRope { ea: 1000.0, damping_time: 0.0 };
const INITIAL: Swing = Swing { theta_x: 0.0, theta_y: 0.0, omega_x: 0.0, omega_y: 0.0 };
const RELEASE_TIME: f64 = 0.0;
const INPUT: TipMotion = TipMotion {
    pos: Vec3::new(0.0, 0.0, 0.0),
    vel: Vec3::new(0.0, 0.0, 0.0),
    acc: Vec3::new(0.0, 0.0, 0.0),
    lp: DEFAULT_POSE.lp,
    lp_dot: 0.0,
    lp_ddot: 0.0,
};

fn motion(m: &Rigging) -> &RiggingMotion {
    &m.out.motion
}

/// The three parameter rows of one rope's law, value references `vr` to `vr + 2`: `<prefix>law`
/// (rigid or elastic), `<prefix>ea` (N) and `<prefix>damping_time` (s) of its [`ElasticRope`],
/// with the same start values ([`RIGID`], [`ROPE`]) and ranges for the hoist rope and the sling, so
/// that the two ropes stay switchable alike; only their descriptions differ.
macro_rules! rope_parameters {
    ($vr:expr, $prefix:literal, $m:ident => $law:expr, $rope:expr, docs: [$law_doc:expr, $ea_doc:expr, $damping_doc:expr $(,)?]) => {
        [
            fmu_model::field!(Integer::parameter($vr, concat!($prefix, "law")), start: RIGID, range: (RIGID, ELASTIC),
                doc: $law_doc, field: $m => $law),
            fmu_model::field!(Real::parameter($vr + 1, concat!($prefix, "ea")), unit: "N", start: ROPE.ea,
                range: (1e-6, 1e12), doc: $ea_doc, field: $m => $rope.ea),
            fmu_model::field!(Real::parameter($vr + 2, concat!($prefix, "damping_time")), unit: "s",
                start: ROPE.damping_time, range: (0.0, 1e3), doc: $damping_doc, field: $m => $rope.damping_time),
        ]
    };
}

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+; the
/// pendulum's variables keep its value references).
const GROUPS: &[&[V]] = &[
    // Parameters shared with the pendulum (same names, same meaning for the hoist rope and load).
    &pendulum_parameters!(m => {
        swing: m.initial, INITIAL, ["Initial hoist rope angle about x (X-Y sequence)", "Initial hoist rope angle about y"],
        load: m.load, LOAD, "Load mass m_l (below the sling; hook and load are one body without a sling)",
            ("Load aerodynamic damping rate across its rope along theta_" + axis + " (section 7.2.3)"),
        release_time: m.release_time, RELEASE_TIME,
            "Hook and load are held at their initial angles (rates zero) until this time",
    }),
    &[
        // Parameters of the rigging.
        fmu_model::field!(Real::parameter(10, "hook.mass"), unit: "kg", start: HOOK_MASS, range: (0.0, 1e6),
            doc: "Hook (block) mass m_h; > 0 with a sling",
            field: m => m.hook_mass),
        fmu_model::field!(Real::parameter(11, "hook.kappa"), unit: "1/s", start: HOOK_DRAG, range: (0.0, 1e3),
            doc: "Hook aerodynamic damping rate across the hoist rope, both directions",
            field: m => m.hook_drag),
        fmu_model::field!(Real::parameter(12, "sling.length"), unit: "m", start: SLING_LENGTH, range: (0.0, 1e3),
            doc: "Sling length l_s, hook to load (unstretched); 0: no sling, hook and load one body",
            field: m => m.sling_length),
    ],
    &swing_parameters!(13, m => m.sling_initial, start: INITIAL,
        names: ["sling.dtheta_x0", "sling.dtheta_y0", "sling.omega_x0", "sling.omega_y0"],
        docs: [
            "Initial sling angle about x minus theta_x0 (0: the sling in line with the hoist rope)",
            "Initial sling angle about y minus theta_y0",
            "Initial rate of the sling's angle about x (at release)",
            "Initial rate of the sling's angle about y (at release)",
        ]),
    &[
    ],
    &rope_parameters!(20, "hoist.", m => m.hoist_law, m.hoist_rope, docs: [
        "Hoist rope law: 0 rigid (length constraint, the thesis' cable), 1 elastic and unilateral (EA, damping)",
        "Hoist rope axial stiffness EA (elastic law): spring rate EA/lp",
        "Hoist rope stiffness-proportional damping time beta (elastic law): damping ratio beta*omega/2",
    ]),
    &rope_parameters!(23, "sling.", m => m.sling_law, m.sling_rope, docs: [
        "Sling law: 0 rigid, 1 elastic and unilateral (EA, damping; needs sling.length > 0)",
        "Sling axial stiffness EA (elastic law): spring rate EA/sling.length",
        "Sling stiffness-proportional damping time beta (elastic law)",
    ]),
    // Inputs: crane tip motion in W and the hoist length (the pendulum's).
    &tip_motion_inputs!(m => m.input, rate: m.input_rate, slopes: m.slopes, start: INPUT,
        lp: "Hoist length, tip to hook (unstretched for an elastic rope)"),
    // Outputs shared with the pendulum.
    &load_outputs!(m => {
        swing: m.out.hoist.swing, [
            "Hoist rope angle about x (X-Y sequence, chord tip to hook, relative to W at the tip)",
            "Hoist rope angle about y",
        ],
        load: motion(m).load, ("Load position " + axis + ", W"),
        orientation: m.out.sling.orientation,
            "Load orientation W<-load Rx(sling.theta_x)Ry(sling.theta_y), scalar part",
        angular_velocity: m.out.sling.angular_velocity,
            ("Load angular velocity " + axis + ", load frame (the sling's swing)"),
        tension: motion(m).hoist_tension,
            "Hoist rope tension (a rigid rope's constraint force; an elastic rope's max(0, k stretch + c rate))",
        cable_force: motion(m).tip_force,
            ("Force of the hoist rope on the crane tip, W " + axis + ": tension times the unit chord tip to hook"),
        free_cable_force: m.out.free_force,
            ("Hoist rope force on the tip for an unaccelerated tip and a steady length, W " + axis
            + " (F0 of the exactly affine tip coupling; an elastic rope's force, which depends on the state only)"),
        cable_mass: m.out.cable_mass, concat!(
            "Mass along the rope for a crane that integrates the load's inertia with cable.f0: -e.dF/d(lp_ddot), ",
            "e along cable.f0 (hook plus load for a straight rigid rig, 0 for an elastic rope)"
        ),
    }),
    // Outputs of the rigging.
    &body_outputs!(230, "hook", "Hook", m => {
        motion: motion(m).hook, ("Hook position " + axis + ", W"),
        orientation: m.out.hoist.orientation,
            "Hook orientation W<-hook Rx(theta_x)Ry(theta_y) (the hoist rope's), scalar part",
        angular_velocity: m.out.hoist.angular_velocity,
            ("Hook angular velocity " + axis + ", hook frame (the hoist rope's swing)"),
    }),
    &swing_outputs!(246, "sling.", m => m.out.sling.swing, [
        "Sling angle about x (X-Y sequence, chord hook to load, relative to W; the hoist rope's without a sling)",
        "Sling angle about y",
    ]),
    &[
        Real::output(250, "sling.tension")
            .unit("N")
            .doc("Sling tension (without a sling the load's share of the hoist rope's)")
            .get(|m| motion(m).sling_tension),
        Real::output(251, "hoist.chord")
            .unit("m")
            .doc("Distance tip to hook: lp for a rigid rope, lp plus stretch (or less, slack) for an elastic one")
            .get(|m| motion(m).hoist_chord),
        Real::output(252, "hoist.peak_snap")
            .unit("N")
            .doc("Peak snap load of the hoist rope: largest tension sampled after its first slack sample (0: never slack)")
            .get(|m| motion(m).hoist_peak_snap),
        Real::output(253, "sling.peak_snap")
            .unit("N")
            .doc("Peak snap load of the sling: largest tension sampled after its first slack sample (0: never slack)")
            .get(|m| motion(m).sling_peak_snap),
        Boolean::output(260, "hoist.slack")
            .doc("The hoist rope is slack now (an elastic rope at zero tension)")
            .get(|m| motion(m).hoist_slack),
        Boolean::output(261, "sling.slack")
            .doc("The sling is slack now (an elastic sling at zero tension; never without a sling)")
            .get(|m| motion(m).sling_slack),
        Boolean::output(262, "slack")
            .doc("Either rope is slack now")
            .get(|m| motion(m).hoist_slack || motion(m).sling_slack),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(Rigging);

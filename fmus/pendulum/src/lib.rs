//! FMU `pendulum`: the variable-length spherical pendulum load (SPEC §4.3, thesis §4.3).
//!
//! States θx, θy, θ̇x, θ̇y; the crane tip motion and the cable length are inputs (never integrated
//! here, so nothing drifts). Inputs are interpolated linearly within a step when the master sets
//! their first derivatives; otherwise they are held. When a velocity input (tip velocity, cable
//! length rate) has a derivative, its acceleration ramp is reconciled with it so that the
//! acceleration integrates exactly to the announced velocity change
//! ([`TipMotion::reconciled`]): a sampled crane command makes the tip acceleration jump at
//! communication points. RK4 with substeps of at most 1 ms.
//! All ports SI, world frame W North-East-Down.

use fmi2::{Model, ModelInfo, Variable};
use physics::crane::plant::DEFAULT_POSE;
use physics::math::{components, Quat, Vec3};
use physics::pendulum::{
    advance, load_kinematics, load_motion, LoadMotion, PendulumParams, Swing, TipMotion, VelocitySlopes,
};
use serde::{Deserialize, Serialize};

/// Instance data: configuration, inputs, continuous state and the outputs last computed.
#[derive(Clone, Serialize, Deserialize)]
pub struct Pendulum {
    params: PendulumParams,
    /// Initial angles and rates (applied at release).
    initial: Swing,
    /// The load is held at its initial angles (rates zero) until this time (s).
    release_time: f64,
    /// Inputs as last set, and their time derivatives for the coming step.
    input: TipMotion,
    input_rate: TipMotion,
    /// Which velocity inputs have a derivative for the coming step (acceleration reconciliation).
    slopes: VelocitySlopes,
    swing: Swing,
    /// Inputs at the current communication point (the interpolated end of the last step).
    input_now: TipMotion,
    time: f64,
    load: LoadMotion,
}

impl Pendulum {
    fn held(&self) -> bool {
        self.time < self.release_time
    }

    /// Computes the outputs; a slack cable is an error: the model holds the load at the cable
    /// length, which only a taut cable (tension > 0) can do.
    fn update_outputs(&mut self) -> Result<(), String> {
        self.load = if self.held() {
            load_kinematics(&self.params, &self.swing, &self.input_now, (0.0, 0.0))
        } else {
            load_motion(&self.params, &self.swing, &self.input_now)
        };
        if !(self.load.tension > 0.0) {
            return Err(format!(
                "the cable goes slack at t = {} s (tension {} N <= 0): the load would leave the length constraint",
                self.time, self.load.tension
            ));
        }
        Ok(())
    }

    fn held_swing(&self) -> Swing {
        Swing { omega_x: 0.0, omega_y: 0.0, ..self.initial }
    }
}

impl Model for Pendulum {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "pendulum",
        description: "Variable-length spherical pendulum load with aerodynamic damping, driven by the crane tip motion and cable length (thesis eqs. 4.131-4.133, section 7.2.3)",
        default_stop_time: 60.0,
        default_step_size: 0.01,
        can_interpolate_inputs: true,
        max_step_size: MAX_STEP_SIZE,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(_env: &fmi2::Environment) -> Self {
        Pendulum {
            params: PARAMS,
            initial: INITIAL,
            release_time: RELEASE_TIME,
            input: INPUT,
            input_rate: TipMotion::default(),
            slopes: VelocitySlopes::default(),
            swing: Swing::default(),
            input_now: TipMotion::default(),
            time: 0.0,
            load: LoadMotion::default(),
        }
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.params.validate()?;
        self.time = start_time;
        self.swing = if self.held() { self.held_swing() } else { self.initial };
        self.input_now = self.input;
        if !(self.input.lp > 0.0) {
            return Err(format!("cable length lp must be > 0 m, got {}", self.input.lp));
        }
        self.update_outputs()
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        let end = t + h;
        if end <= self.release_time {
            self.swing = self.held_swing();
        } else {
            // Release inside this step: the free swing starts from the initial state at release.
            let free_from = (self.release_time - t).max(0.0);
            if free_from > 0.0 {
                self.swing = self.initial;
            }
            let (input, rate) = self.input.reconciled(&self.input_rate, &self.slopes, h);
            let start = input.ramp(&rate, free_from);
            self.swing = advance(&self.params, &self.swing, &start, &rate, h - free_from)?;
        }
        self.time = end;
        self.input_now = self.input.ramp(&self.input_rate, h);
        self.update_outputs()
    }
}

type V = Variable<Pendulum>;

/// Largest communication step (s): at most one million RK4 substeps of 1 ms (about a second of
/// work) per `fmi2DoStep`.
const MAX_STEP_SIZE: f64 = 1000.0;

/// The defaults, the start values of the table and of [`Model::new`]: the thesis' load
/// (§7.2.3); hanging straight down at rest; released at once; the tip at rest at the origin of W
/// with the crane's default pendulum length (m).
const PARAMS: PendulumParams = PendulumParams::DEFAULT;
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

fn q(m: &Pendulum) -> &Quat {
    &m.load.orientation
}

fn w(m: &Pendulum) -> &Vec3 {
    &m.load.angular_velocity
}

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
static VARIABLES: &[V] = &[
    // Parameters.
    V::parameter(
        0,
        "theta_x0",
        "rad",
        INITIAL.theta_x,
        "Initial cable angle about x (X-Y sequence)",
        |m| m.initial.theta_x,
        |m, v| m.initial.theta_x = v,
    )
    .range(-1.5, 1.5),
    V::parameter(
        1,
        "theta_y0",
        "rad",
        INITIAL.theta_y,
        "Initial cable angle about y",
        |m| m.initial.theta_y,
        |m, v| m.initial.theta_y = v,
    )
    .range(-1.5, 1.5),
    V::parameter(
        2,
        "omega_x0",
        "rad/s",
        INITIAL.omega_x,
        "Initial rate of theta_x (at release)",
        |m| m.initial.omega_x,
        |m, v| m.initial.omega_x = v,
    ),
    V::parameter(
        3,
        "omega_y0",
        "rad/s",
        INITIAL.omega_y,
        "Initial rate of theta_y (at release)",
        |m| m.initial.omega_y,
        |m, v| m.initial.omega_y = v,
    ),
    V::parameter(
        4,
        "mass",
        "kg",
        PARAMS.mass,
        "Load mass m_p (enters the cable tension)",
        |m| m.params.mass,
        |m, v| m.params.mass = v,
    )
    .range(1e-6, 1e6),
    V::parameter(
        5,
        "kappa_x",
        "1/s",
        PARAMS.kappa_x,
        "Aerodynamic damping c_thx/m_p along the theta_x direction (section 7.2.3)",
        |m| m.params.kappa_x,
        |m, v| m.params.kappa_x = v,
    )
    .range(0.0, 1e3),
    V::parameter(
        6,
        "kappa_y",
        "1/s",
        PARAMS.kappa_y,
        "Aerodynamic damping c_thy/m_p along the theta_y direction (section 7.2.3)",
        |m| m.params.kappa_y,
        |m, v| m.params.kappa_y = v,
    )
    .range(0.0, 1e3),
    V::parameter(7, "g", "m/s2", PARAMS.g, "Gravitational acceleration", |m| m.params.g, |m, v| m.params.g = v)
        .range(1e-6, 1e3),
    V::parameter(
        8,
        "release_time",
        "s",
        RELEASE_TIME,
        "The load is held at its initial angles (rates zero) until this time",
        |m| m.release_time,
        |m, v| m.release_time = v,
    ),
    // Inputs: crane tip motion in W and the cable length.
    V::input(
        100,
        "tip.x",
        "m",
        components(&INPUT.pos)[0],
        "Crane tip position x (north), W",
        |m| m.input.pos.x,
        |m, v| m.input.pos.x = v,
        |m, d| m.input_rate.pos.x = d.unwrap_or(0.0),
    ),
    V::input(
        101,
        "tip.y",
        "m",
        components(&INPUT.pos)[1],
        "Crane tip position y (east), W",
        |m| m.input.pos.y,
        |m, v| m.input.pos.y = v,
        |m, d| m.input_rate.pos.y = d.unwrap_or(0.0),
    ),
    V::input(
        102,
        "tip.z",
        "m",
        components(&INPUT.pos)[2],
        "Crane tip position z (down), W",
        |m| m.input.pos.z,
        |m, v| m.input.pos.z = v,
        |m, d| m.input_rate.pos.z = d.unwrap_or(0.0),
    ),
    V::input(
        103,
        "tip.vx",
        "m/s",
        components(&INPUT.vel)[0],
        "Crane tip velocity x, W",
        |m| m.input.vel.x,
        |m, v| m.input.vel.x = v,
        |m, d| (m.input_rate.vel.x, m.slopes.tip[0]) = (d.unwrap_or(0.0), d.is_some()),
    ),
    V::input(
        104,
        "tip.vy",
        "m/s",
        components(&INPUT.vel)[1],
        "Crane tip velocity y, W",
        |m| m.input.vel.y,
        |m, v| m.input.vel.y = v,
        |m, d| (m.input_rate.vel.y, m.slopes.tip[1]) = (d.unwrap_or(0.0), d.is_some()),
    ),
    V::input(
        105,
        "tip.vz",
        "m/s",
        components(&INPUT.vel)[2],
        "Crane tip velocity z, W",
        |m| m.input.vel.z,
        |m, v| m.input.vel.z = v,
        |m, d| (m.input_rate.vel.z, m.slopes.tip[2]) = (d.unwrap_or(0.0), d.is_some()),
    ),
    V::input(
        106,
        "tip.ax",
        "m/s2",
        components(&INPUT.acc)[0],
        "Crane tip acceleration x, W",
        |m| m.input.acc.x,
        |m, v| m.input.acc.x = v,
        |m, d| m.input_rate.acc.x = d.unwrap_or(0.0),
    ),
    V::input(
        107,
        "tip.ay",
        "m/s2",
        components(&INPUT.acc)[1],
        "Crane tip acceleration y, W",
        |m| m.input.acc.y,
        |m, v| m.input.acc.y = v,
        |m, d| m.input_rate.acc.y = d.unwrap_or(0.0),
    ),
    V::input(
        108,
        "tip.az",
        "m/s2",
        components(&INPUT.acc)[2],
        "Crane tip acceleration z, W",
        |m| m.input.acc.z,
        |m, v| m.input.acc.z = v,
        |m, d| m.input_rate.acc.z = d.unwrap_or(0.0),
    ),
    V::input(
        109,
        "lp",
        "m",
        INPUT.lp,
        "Cable (pendulum) length, tip to load",
        |m| m.input.lp,
        |m, v| m.input.lp = v,
        |m, d| m.input_rate.lp = d.unwrap_or(0.0),
    ),
    V::input(
        110,
        "lp_dot",
        "m/s",
        INPUT.lp_dot,
        "Cable length rate",
        |m| m.input.lp_dot,
        |m, v| m.input.lp_dot = v,
        |m, d| (m.input_rate.lp_dot, m.slopes.lp) = (d.unwrap_or(0.0), d.is_some()),
    ),
    V::input(
        111,
        "lp_ddot",
        "m/s2",
        INPUT.lp_ddot,
        "Cable length acceleration",
        |m| m.input.lp_ddot,
        |m, v| m.input.lp_ddot = v,
        |m, d| m.input_rate.lp_ddot = d.unwrap_or(0.0),
    ),
    // Outputs.
    V::output(200, "theta_x", "rad", "Cable angle about x (X-Y sequence, relative to W at the tip)", |m| {
        m.swing.theta_x
    }),
    V::output(201, "theta_y", "rad", "Cable angle about y", |m| m.swing.theta_y),
    V::output(202, "omega_x", "rad/s", "Rate of theta_x", |m| m.swing.omega_x),
    V::output(203, "omega_y", "rad/s", "Rate of theta_y", |m| m.swing.omega_y),
    V::output(204, "load.x", "m", "Load position x, W (eq. 4.94)", |m| m.load.pos.x),
    V::output(205, "load.y", "m", "Load position y, W (eq. 4.95)", |m| m.load.pos.y),
    V::output(206, "load.z", "m", "Load position z, W (eq. 4.96)", |m| m.load.pos.z),
    V::output(207, "load.vx", "m/s", "Load velocity x, W", |m| m.load.vel.x),
    V::output(208, "load.vy", "m/s", "Load velocity y, W", |m| m.load.vel.y),
    V::output(209, "load.vz", "m/s", "Load velocity z, W", |m| m.load.vel.z),
    V::output(210, "load.ax", "m/s2", "Load acceleration x, W", |m| m.load.acc.x),
    V::output(211, "load.ay", "m/s2", "Load acceleration y, W", |m| m.load.acc.y),
    V::output(212, "load.az", "m/s2", "Load acceleration z, W", |m| m.load.acc.z),
    V::output(213, "load.q0", "1", "Load orientation W<-load Rx(theta_x)Ry(theta_y), scalar part", |m| q(m).w),
    V::output(214, "load.q1", "1", "Load orientation, x part", |m| q(m).i),
    V::output(215, "load.q2", "1", "Load orientation, y part", |m| q(m).j),
    V::output(216, "load.q3", "1", "Load orientation, z part", |m| q(m).k),
    V::output(217, "load.wx", "rad/s", "Load angular velocity x, load frame", |m| w(m).x),
    V::output(218, "load.wy", "rad/s", "Load angular velocity y, load frame", |m| w(m).y),
    V::output(219, "load.wz", "rad/s", "Load angular velocity z, load frame", |m| w(m).z),
    V::output(220, "tension", "N", "Cable tension from the length constraint force (eq. 4.127)", |m| m.load.tension),
];

fmi2::export_fmu!(Pendulum);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variable_table_is_consistent_and_renders() {
        fmi2::variables::check_table(VARIABLES).unwrap();
        let description = fmi2::xml::render::<Pendulum>().unwrap();
        assert!(description.xml.contains(r#"name="tip.ax""#));
        assert!(description.guid.starts_with('{'));
    }

    /// The tip falling faster than g (NED: z down) leaves the cable slack, an error rather than
    /// outputs with a negative tension.
    #[test]
    fn a_slack_cable_is_an_error() {
        use fmi2::harness::{instantiate, set_real};
        let mut m = instantiate::<Pendulum>();
        m.initialize(0.0).unwrap();
        assert!(m.load.tension > 0.0);
        m.do_step(0.0, 0.01).unwrap();
        set_real(&mut m, "tip.az", 12.0);
        let message = m.do_step(0.01, 0.01).unwrap_err();
        assert!(message.contains("cable goes slack at t = 0.02 s"), "{message}");
        set_real(&mut m, "tip.az", 20.0);
        assert!(m.initialize(0.0).unwrap_err().contains("tension -"));
    }
}

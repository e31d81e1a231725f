//! FMU `pendulum`: the variable-length spherical pendulum load (SPEC §4.3, thesis §4.3).
//!
//! States θx, θy, θ̇x, θ̇y; the crane tip motion and the cable length are inputs (never integrated
//! here, so nothing drifts). Inputs are interpolated linearly within a step when the importer sets
//! their first derivatives; otherwise they are held. When a velocity input (tip velocity, cable
//! length rate) has a derivative, its acceleration ramp is reconciled with it so that the
//! acceleration integrates exactly to the announced velocity change
//! ([`TipMotion::reconciled`]): a sampled crane command makes the tip acceleration jump at
//! communication points. Butcher's sixth-order Runge–Kutta method with substeps of at most 10 ms.
//! All ports SI, world frame W North-East-Down.

use fmu_model::{load_outputs, pendulum_parameters, tip_motion_inputs, Environment, Model, ModelInfo, Variable};
use physics::crane::plant::DEFAULT_POSE;
use physics::math::{components, Vec3};
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
    const INFO: ModelInfo = ModelInfo::new(
        "pendulum",
        concat!(
            "Variable-length spherical pendulum load with aerodynamic damping, driven by the crane tip motion ",
            "and cable length (thesis eqs. 4.131-4.133, section 7.2.3)",
        ),
    )
    .stop_time(60.0)
    .interpolating_inputs()
    .max_step(MAX_STEP_SIZE);

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(_env: &Environment) -> Self {
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
type Real = fmu_model::Real<Pendulum>;

/// Largest communication step (s): at most 100,000 substeps of 10 ms (well under a second of work)
/// per `fmi2DoStep`.
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

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
const GROUPS: &[&[V]] = &[
    // Parameters.
    &pendulum_parameters!(m => {
        swing: m.initial, INITIAL, ["Initial cable angle about x (X-Y sequence)", "Initial cable angle about y"],
        load: m.params, PARAMS, "Load mass m_p (enters the cable tension)", [
            "Aerodynamic damping c_thx/m_p along the theta_x direction (section 7.2.3)",
            "Aerodynamic damping c_thy/m_p along the theta_y direction (section 7.2.3)",
        ],
        release_time: m.release_time, RELEASE_TIME,
            "The load is held at its initial angles (rates zero) until this time",
    }),
    // Inputs: crane tip motion in W and the cable length.
    &tip_motion_inputs!(m => m.input, rate: m.input_rate, slopes: m.slopes, start: INPUT,
        lp: "Cable (pendulum) length, tip to load"),
    // Outputs.
    &load_outputs!(m => {
        swing: m.swing, ["Cable angle about x (X-Y sequence, relative to W at the tip)", "Cable angle about y"],
        load: m.load,
            ["Load position x, W (eq. 4.94)", "Load position y, W (eq. 4.95)", "Load position z, W (eq. 4.96)"],
        orientation: m.load.orientation, "Load orientation W<-load Rx(theta_x)Ry(theta_y), scalar part",
        angular_velocity: m.load.angular_velocity, ("Load angular velocity " + axis + ", load frame"),
        tension: m.load.tension, "Cable tension from the length constraint force (eq. 4.127)",
        cable_force: m.load.cable_force, ("Force of the cable on the crane tip, W " + axis
            + ": tension times the unit vector tip to load (eqs. 4.94-4.96, 4.127); (0, 0, m g) at rest"),
        free_cable_force: m.load.free_cable_force,
            ("Cable force on the tip for an unaccelerated tip and a steady length, W " + axis
            + ": the tension T0 = T + m (a e_r + lp_ddot) along the cable, for a crane that adds the load's inertia"),
        cable_mass: m.params.mass,
            "The load mass m_p, for a crane that integrates the load's inertia along the cable (with cable.f0)",
    }),
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(Pendulum);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variable_table_is_consistent_and_renders() {
        fmu_model::check_table(&VARIABLES).unwrap();
        let description = fmu_export::fmi2::xml::render::<Pendulum>().unwrap();
        assert!(description.xml.contains(r#"name="tip.ax""#));
        assert!(description.guid.starts_with('{'));
    }

    /// The tip falling faster than g (NED: z down) leaves the cable slack, an error rather than
    /// outputs with a negative tension.
    #[test]
    fn a_slack_cable_is_an_error() {
        use fmu_export::harness::{instantiate, set_real};
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

    fn vector(m: &Pendulum, prefix: &str) -> Vec3 {
        Vec3::from(fmu_export::harness::get_xyz(m, prefix))
    }

    /// A full-scale load (8 t on 25 m of cable) hanging at rest pulls the tip down (NED +z) with
    /// its weight, and swinging, with the tension along the cable toward the load.
    #[test]
    fn the_cable_force_output_at_full_scale() {
        use fmu_export::harness::{get_real, instantiate, set_real};
        let mut m = instantiate::<Pendulum>();
        set_real(&mut m, "mass", 8000.0);
        set_real(&mut m, "lp", 25.0);
        m.initialize(0.0).unwrap();
        for k in 0..3 {
            let (f, weight) = (vector(&m, "cable.f"), 8000.0 * PARAMS.g);
            assert_eq!((f.x, f.y), (0.0, 0.0));
            assert!((f.z - weight).abs() <= 1e-12 * weight, "{} vs {weight}", f.z);
            m.do_step(k as f64 * 0.01, 0.01).unwrap();
        }
        let mut m = instantiate::<Pendulum>();
        set_real(&mut m, "mass", 8000.0);
        set_real(&mut m, "lp", 25.0);
        set_real(&mut m, "theta_x0", 0.3);
        set_real(&mut m, "theta_y0", -0.2);
        m.initialize(0.0).unwrap();
        for k in 0..500 {
            m.do_step(k as f64 * 0.01, 0.01).unwrap();
            let (f, tension) = (vector(&m, "cable.f"), get_real(&m, "tension"));
            let towards_load = (vector(&m, "load.") - m.input_now.pos).normalize();
            assert!((f.norm() - tension).abs() <= 1e-12 * tension, "step {k}");
            assert!((f - towards_load * tension).norm() <= 1e-12 * tension, "step {k}: {f} vs {towards_load}");
        }
    }

    /// The free cable force completes to the tension with the tip's acceleration and the length
    /// acceleration the pendulum was given (T = T0 - m (a e_r + lp_ddot)), and points the same way.
    #[test]
    fn the_free_cable_force_completes_to_the_tension() {
        use fmu_export::harness::{get_real, instantiate, set_real};
        let mut m = instantiate::<Pendulum>();
        set_real(&mut m, "mass", 5000.0);
        set_real(&mut m, "lp", 15.0);
        set_real(&mut m, "theta_x0", 0.2);
        m.initialize(0.0).unwrap();
        for k in 0..300 {
            let t = k as f64 * 0.01;
            let acc = Vec3::new(0.8 * (0.7 * t).sin(), -0.5 * (1.1 * t).cos(), 0.6 * (0.9 * t).sin());
            for (name, value) in
                [("tip.ax", acc.x), ("tip.ay", acc.y), ("tip.az", acc.z), ("lp_ddot", 0.3 * (0.5 * t).cos())]
            {
                set_real(&mut m, name, value);
            }
            m.do_step(t, 0.01).unwrap();
            let (f0, f, tension) = (vector(&m, "cable.f0"), vector(&m, "cable.f"), get_real(&m, "tension"));
            let e = f / tension;
            let completed = f0.norm() - 5000.0 * (vector(&m, "tip.a").dot(&e) + get_real(&m, "lp_ddot"));
            assert!((completed - tension).abs() <= 1e-9 * tension, "step {k}: {completed} vs {tension}");
            assert!((f0.normalize() - e).norm() <= 1e-12, "step {k}");
            assert_eq!(get_real(&m, "cable.mass"), 5000.0);
        }
    }
}

//! The names of each scale's closed loop: `systems/closed_loop.json` (the thesis' test-scale
//! crane) and `systems/full_scale_ahc.json` (the full-scale hydraulic crane under its control
//! software), both with the platform named `platform` and the load `pendulum`.

use crate::set::{name_struct, Instance};
use crate::{xyz, Xyz};

name_struct! {
    /// The names one closed-loop system gives its instances and variables, the same fields at
    /// both scales; what only one scale's controller has is in [`CraneNames::test`] or
    /// [`CraneNames::full`].
    pub struct CraneNames {
        /// The crane's and its controller's instances.
        pub crane: Instance,
        pub controller: Instance,
        /// The load position (pendulum output), its cable angles θx, θy and their rates, and the
        /// rope length it hangs on.
        pub load: Xyz,
        pub theta: [&'static str; 2],
        pub omega: [&'static str; 2],
        pub rope_length: &'static str,
        /// The pendulum's initial cable angles θx0, θy0 and its release time (s).
        pub theta0: [&'static str; 2],
        pub release_time: &'static str,
        /// The crane tip, its joint angles, its hoisted rope length and that length at the start.
        pub tip: Xyz,
        pub joints: [&'static str; 3],
        pub lp: &'static str,
        pub lp0: &'static str,
        /// The crane's sensor noise switches and noise seeds (the IMUs' at test scale too), in
        /// the order the studies draw their seeds.
        pub noise: &'static [&'static str],
        pub noise_seeds: &'static [&'static str],
        /// The controller's mode (0 off; 2 the law), when it starts acting (s) and where its
        /// set-point comes from (0 fixed, 1 pick-and-place, 2 inputs at test scale).
        pub mode: &'static str,
        pub active_from: &'static str,
        pub setpoint_source: &'static str,
        /// The controller's load set-point, its tip and hoist references.
        pub setpoint: Xyz,
        pub tip_reference: Xyz,
        pub lp_reference: &'static str,
        /// The residual an agent adds to the controller's law (tip position at test scale, m; tip
        /// velocity at full scale, m/s).
        pub residual: Xyz,
        /// The actuator commands: voltages and winch duty at test scale, valve spools at full.
        pub commands: [&'static str; 4],
        /// What the controller estimates or measures: the load, the tip, the hoist length and the
        /// ship's roll and pitch.
        pub estimated_load: Xyz,
        pub estimated_tip: Xyz,
        pub estimated_lp: &'static str,
        pub estimated_tilt: [&'static str; 2],
        /// Ship surge, sway, heave, roll, pitch, yaw (platform outputs), the seed of its motion.
        pub ship: [&'static str; 6],
        pub ship_seed: &'static str,
        /// The platform's motion profile, its sine excitation and the start and fade-in of its
        /// motion.
        pub profile: &'static str,
        pub sine_omega: &'static str,
        pub sine_amplitude: &'static str,
        pub motion_start: &'static str,
        pub fade_in: &'static str,
        /// The names only one scale's controller and crane have.
        pub test: Option<TestScaleControl>,
        pub full: Option<FullScaleControl>,
    }
}

name_struct! {
    /// What only the test-scale loop has: the controller's set-point inputs and options, the
    /// crane's initial cylinder extensions.
    pub struct TestScaleControl {
        /// The controller's external set-point inputs tip x, y, z and cable length (read with
        /// `setpoint_source` = 2), and its fixed set-point parameters of the same.
        pub setpoint_inputs: [&'static str; 4],
        pub fixed_setpoint: [&'static str; 4],
        /// What the controller feeds back (0 truth, 1 sensors, 2 sensors and its EKF), how its
        /// filters start (1 aligned on the first sample), its attitude filter (0 complementary,
        /// 1 Madgwick).
        pub feedback: &'static str,
        pub filter_init: &'static str,
        pub attitude_filter: &'static str,
        /// The controller's estimate of the swing angles.
        pub estimated_theta: [&'static str; 2],
        /// The controller's set-point cable length and its encoder's initial length.
        pub setpoint_lp: &'static str,
        pub encoder_lp0: &'static str,
        /// The crane's initial cylinder extensions (base, boom, jib).
        pub extensions0: [&'static str; 3],
    }
}

name_struct! {
    /// What only the full-scale loop has: heave compensation and the arm's initial joint angles.
    pub struct FullScaleControl {
        /// Heave compensation (0 none, 1 by the winch, 2 by the arm).
        pub heave: &'static str,
        /// The crane's initial joint angles (rad: slew, boom, jib).
        pub joints0: [&'static str; 3],
    }
}

/// The test scale's controller names (`TEST_SCALE.test`).
const TEST_CONTROL: TestScaleControl = TestScaleControl {
    setpoint_inputs: [
        "controller.sp_in.tip.x",
        "controller.sp_in.tip.y",
        "controller.sp_in.tip.z",
        "controller.sp_in.lp",
    ],
    fixed_setpoint: ["controller.sp.tip.x", "controller.sp.tip.y", "controller.sp.tip.z", "controller.sp.lp"],
    feedback: "controller.feedback",
    filter_init: "controller.cf_init",
    attitude_filter: "controller.attitude_filter",
    estimated_theta: ["controller.est.theta_x", "controller.est.theta_y"],
    setpoint_lp: "controller.sp.lp",
    encoder_lp0: "controller.encoder.lp0",
    extensions0: ["crane.d0.base", "crane.d0.boom", "crane.d0.jib"],
};

/// The platform's names, the same in every system of either scale.
const SHIP: [&str; 6] = [
    "platform.ship.x",
    "platform.ship.y",
    "platform.ship.z",
    "platform.ship.roll",
    "platform.ship.pitch",
    "platform.ship.yaw",
];

/// `systems/closed_loop.json`: the thesis' test-scale crane.
pub const TEST_SCALE: CraneNames = CraneNames {
    crane: Instance("crane"),
    controller: Instance("controller"),
    load: xyz!("pendulum.load."),
    theta: ["pendulum.theta_x", "pendulum.theta_y"],
    omega: ["pendulum.omega_x", "pendulum.omega_y"],
    rope_length: "pendulum.lp",
    theta0: ["pendulum.theta_x0", "pendulum.theta_y0"],
    release_time: "pendulum.release_time",
    tip: xyz!("crane.tip."),
    joints: ["crane.joint.theta2z", "crane.joint.theta3x", "crane.joint.theta4x"],
    lp: "crane.lp",
    lp0: "crane.lp0",
    noise: &["crane.noise", "imu1.noise", "imu2.noise"],
    noise_seeds: &["imu1.seed", "imu2.seed", "crane.seed"],
    mode: "controller.mode",
    active_from: "controller.active_from",
    setpoint_source: "controller.setpoint",
    setpoint: xyz!("controller.sp.load."),
    tip_reference: xyz!("controller.sp.ref.tip."),
    lp_reference: "controller.sp.ref.lp",
    residual: xyz!("controller.residual.tip."),
    commands: ["controller.u.base", "controller.u.boom", "controller.u.jib", "controller.u.winch"],
    estimated_load: xyz!("controller.est.load."),
    estimated_tip: xyz!("controller.est.tip."),
    estimated_lp: "controller.est.lp",
    estimated_tilt: ["controller.est.ship.roll", "controller.est.ship.pitch"],
    ship: SHIP,
    ship_seed: "platform.seed",
    profile: "platform.profile",
    sine_omega: "platform.sine_omega",
    sine_amplitude: "platform.sine_amplitude",
    motion_start: "platform.motion_start",
    fade_in: "platform.fade_in",
    test: Some(TEST_CONTROL),
    full: None,
};

/// `systems/full_scale_ahc.json`: the full-scale hydraulic crane under its control software.
pub const FULL_SCALE: CraneNames = CraneNames {
    crane: Instance("knuckle_boom"),
    controller: Instance("knuckle_boom_controller"),
    tip: xyz!("knuckle_boom.tip."),
    joints: ["knuckle_boom.joint.slew", "knuckle_boom.joint.boom", "knuckle_boom.joint.jib"],
    lp: "knuckle_boom.lp",
    lp0: "knuckle_boom.lp0",
    noise: &["knuckle_boom.noise"],
    noise_seeds: &["knuckle_boom.seed"],
    mode: "knuckle_boom_controller.mode",
    active_from: "knuckle_boom_controller.active_from",
    setpoint_source: "knuckle_boom_controller.setpoint",
    setpoint: xyz!("knuckle_boom_controller.setpoint."),
    tip_reference: xyz!("knuckle_boom_controller.tip.ref."),
    lp_reference: "knuckle_boom_controller.lp.ref",
    residual: xyz!("knuckle_boom_controller.residual.tip.v"),
    commands: [
        "knuckle_boom_controller.spool.slew",
        "knuckle_boom_controller.spool.boom",
        "knuckle_boom_controller.spool.jib",
        "knuckle_boom_controller.spool.winch",
    ],
    estimated_load: xyz!("knuckle_boom_controller.load."),
    estimated_tip: xyz!("knuckle_boom_controller.tip."),
    estimated_lp: "knuckle_boom_controller.lp",
    estimated_tilt: ["knuckle_boom_controller.ship.roll", "knuckle_boom_controller.ship.pitch"],
    test: None,
    full: Some(FullScaleControl {
        heave: "knuckle_boom_controller.heave",
        joints0: ["knuckle_boom.q0.slew", "knuckle_boom.q0.boom", "knuckle_boom.q0.jib"],
    }),
    // The load and the platform are named as at test scale.
    ..TEST_SCALE
};

/// The hook's position (m, W) that a rigging in place of the pendulum records (the `rigging`
/// FMU's `hook.*`, docs/rigging.md; `systems/closed_loop_rigging.json`).
pub const RIGGING_HOOK: Xyz = xyz!("pendulum.hook.");

impl CraneNames {
    /// The instances the names belong to: the crane, its controller and those of the other
    /// names.
    pub fn instances(&self) -> Vec<&'static str> {
        let mut instances = vec![self.crane.0, self.controller.0];
        for name in self.all() {
            let instance = crate::split(name).map_or(name, |(instance, _)| instance);
            if !instances.contains(&instance) {
                instances.push(instance);
            }
        }
        instances
    }
}

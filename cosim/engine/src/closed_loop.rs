//! The instance and variable names of the crane's closed loop that code outside the system
//! file relies on: the campaign's start values and metrics, the viewer's scene and the live
//! session. Each system has its own set ([`ClosedLoopNames::TEST_SCALE`] for
//! `systems/closed_loop.json`), so that a second system adds its names beside it; the
//! integration test `closed_loop_names` checks that every name resolves in its system.

/// An `"instance.variable"` triple `<prefix>x`, `<prefix>y`, `<prefix>z`, with its prefix (the
/// form the campaign's traces read).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Xyz {
    pub prefix: &'static str,
    pub axes: [&'static str; 3],
}

/// [`Xyz`] of a literal prefix.
macro_rules! xyz {
    ($prefix:literal) => {
        Xyz { prefix: $prefix, axes: [concat!($prefix, "x"), concat!($prefix, "y"), concat!($prefix, "z")] }
    };
}

/// The names one closed-loop system gives its instances and variables, all qualified
/// (`"instance.variable"`). Positions are in the world frame W (North-East-Down, m), angles in
/// rad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ClosedLoopNames {
    /// The controller instance (the live session sets its inputs).
    pub controller: &'static str,
    /// The load position (pendulum output).
    pub load: Xyz,
    /// The pendulum's cable angles θx, θy.
    pub theta: [&'static str; 2],
    /// The crane tip (crane output).
    pub tip: Xyz,
    /// The controller's load set-point.
    pub setpoint: Xyz,
    /// The controller's estimate of the load position.
    pub estimated_load: Xyz,
    /// Ship surge, sway, heave, roll, pitch, yaw (platform outputs).
    pub ship: [&'static str; 6],
    /// The crane's joint angles.
    pub joints: [&'static str; 3],
    /// The controller's external set-point inputs tip x, y, z and cable length (read with
    /// [`ClosedLoopNames::setpoint_source`] = 2).
    pub setpoint_inputs: [&'static str; 4],
    /// The controller's fixed set-point parameters tip x, y, z and cable length.
    pub fixed_setpoint: [&'static str; 4],
    /// The controller's mode (0 off, 1 energy dissipation, 2 set-point tracking).
    pub mode: &'static str,
    /// Where the controller's set-point comes from (0 fixed, 1 pick-and-place, 2 inputs).
    pub setpoint_source: &'static str,
    /// What the controller feeds back (0 truth, 1 sensors, 2 sensors and its EKF).
    pub feedback: &'static str,
    /// When the controller starts acting (s).
    pub active_from: &'static str,
    /// How the controller's filters start (1 aligned on the first sample).
    pub filter_init: &'static str,
    /// The controller's attitude filter (0 complementary, 1 Madgwick).
    pub attitude_filter: &'static str,
    /// The controller's set-point cable length and its encoder's initial length.
    pub setpoint_lp: &'static str,
    pub encoder_lp0: &'static str,
    /// The pendulum's initial cable angles θx0, θy0 and its release time (s).
    pub theta0: [&'static str; 2],
    pub release_time: &'static str,
    /// The crane's initial cable length and cylinder extensions (base, boom, jib).
    pub lp0: &'static str,
    pub extensions0: [&'static str; 3],
    /// The sensor noise switches of the crane (encoders) and the two IMUs.
    pub noise: [&'static str; 3],
    /// The platform's motion profile, its sine excitation and the start and fade-in of its motion.
    pub profile: &'static str,
    pub sine_omega: &'static str,
    pub sine_amplitude: &'static str,
    pub motion_start: &'static str,
    pub fade_in: &'static str,
}

impl ClosedLoopNames {
    /// `systems/closed_loop.json`: the thesis' test-scale crane.
    pub const TEST_SCALE: ClosedLoopNames = ClosedLoopNames {
        controller: "controller",
        load: xyz!("pendulum.load."),
        theta: ["pendulum.theta_x", "pendulum.theta_y"],
        tip: xyz!("crane.tip."),
        setpoint: xyz!("controller.sp.load."),
        estimated_load: xyz!("controller.est.load."),
        ship: [
            "platform.ship.x",
            "platform.ship.y",
            "platform.ship.z",
            "platform.ship.roll",
            "platform.ship.pitch",
            "platform.ship.yaw",
        ],
        joints: ["crane.joint.theta2z", "crane.joint.theta3x", "crane.joint.theta4x"],
        setpoint_inputs: [
            "controller.sp_in.tip.x",
            "controller.sp_in.tip.y",
            "controller.sp_in.tip.z",
            "controller.sp_in.lp",
        ],
        fixed_setpoint: ["controller.sp.tip.x", "controller.sp.tip.y", "controller.sp.tip.z", "controller.sp.lp"],
        mode: "controller.mode",
        setpoint_source: "controller.setpoint",
        feedback: "controller.feedback",
        active_from: "controller.active_from",
        filter_init: "controller.cf_init",
        attitude_filter: "controller.attitude_filter",
        setpoint_lp: "controller.sp.lp",
        encoder_lp0: "controller.encoder.lp0",
        theta0: ["pendulum.theta_x0", "pendulum.theta_y0"],
        release_time: "pendulum.release_time",
        lp0: "crane.lp0",
        extensions0: ["crane.d0.base", "crane.d0.boom", "crane.d0.jib"],
        noise: ["crane.noise", "imu1.noise", "imu2.noise"],
        profile: "platform.profile",
        sine_omega: "platform.sine_omega",
        sine_amplitude: "platform.sine_amplitude",
        motion_start: "platform.motion_start",
        fade_in: "platform.fade_in",
    };

    /// Every qualified name of the set (for the check that they resolve).
    pub fn all(&self) -> Vec<&'static str> {
        let xyz = [self.load, self.tip, self.setpoint, self.estimated_load].into_iter().flat_map(|v| v.axes);
        let single = [
            self.mode,
            self.setpoint_source,
            self.feedback,
            self.active_from,
            self.filter_init,
            self.attitude_filter,
            self.setpoint_lp,
            self.encoder_lp0,
            self.release_time,
            self.lp0,
            self.profile,
            self.sine_omega,
            self.sine_amplitude,
            self.motion_start,
            self.fade_in,
        ];
        xyz.chain(self.theta)
            .chain(self.ship)
            .chain(self.joints)
            .chain(self.setpoint_inputs)
            .chain(self.fixed_setpoint)
            .chain(single)
            .chain(self.theta0)
            .chain(self.extensions0)
            .chain(self.noise)
            .collect()
    }
}

/// The names of `systems/full_scale_ahc.json`, the full-scale hydraulic crane under its control
/// software, that the campaign's full-scale matrix (`campaign --scale full`) relies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FullScaleNames {
    /// The load position (pendulum output), the crane tip (crane output) and the controller's
    /// load set-point (W, m).
    pub load: Xyz,
    pub tip: Xyz,
    pub setpoint: Xyz,
    /// The pendulum's initial cable angles θx0, θy0 (rad) and its release time (s).
    pub theta0: [&'static str; 2],
    pub release_time: &'static str,
    /// The crane's initial joint angles (rad: slew, boom, jib), hoist length (m) and its sensor
    /// noise switch.
    pub joints0: [&'static str; 3],
    pub lp0: &'static str,
    pub noise: &'static str,
    /// The controller's arm mode (0 off, 1 joints held, 2 compensated), heave compensation (0
    /// none, 1 winch, 2 arm) and when it starts acting (s).
    pub mode: &'static str,
    pub heave: &'static str,
    pub active_from: &'static str,
    /// The controller's set-point source (0 fixed, 1 pick-and-place).
    pub setpoint_source: &'static str,
    /// The platform's motion profile, its sine excitation and the start and fade-in of its motion.
    pub profile: &'static str,
    pub sine_omega: &'static str,
    pub sine_amplitude: &'static str,
    pub motion_start: &'static str,
    pub fade_in: &'static str,
}

impl FullScaleNames {
    pub const FULL_SCALE: FullScaleNames = FullScaleNames {
        load: xyz!("pendulum.load."),
        tip: xyz!("knuckle_boom.tip."),
        setpoint: xyz!("knuckle_boom_controller.setpoint."),
        theta0: ["pendulum.theta_x0", "pendulum.theta_y0"],
        release_time: "pendulum.release_time",
        joints0: ["knuckle_boom.q0.slew", "knuckle_boom.q0.boom", "knuckle_boom.q0.jib"],
        lp0: "knuckle_boom.lp0",
        noise: "knuckle_boom.noise",
        mode: "knuckle_boom_controller.mode",
        heave: "knuckle_boom_controller.heave",
        active_from: "knuckle_boom_controller.active_from",
        setpoint_source: "knuckle_boom_controller.setpoint",
        profile: "platform.profile",
        sine_omega: "platform.sine_omega",
        sine_amplitude: "platform.sine_amplitude",
        motion_start: "platform.motion_start",
        fade_in: "platform.fade_in",
    };

    /// Every qualified name of the set (for the check that they resolve).
    pub fn all(&self) -> Vec<&'static str> {
        let single = [
            self.release_time,
            self.lp0,
            self.noise,
            self.mode,
            self.heave,
            self.active_from,
            self.setpoint_source,
            self.profile,
            self.sine_omega,
            self.sine_amplitude,
            self.motion_start,
            self.fade_in,
        ];
        let axes = [self.load, self.tip, self.setpoint].into_iter().flat_map(|v| v.axes);
        axes.chain(self.theta0).chain(self.joints0).chain(single).collect()
    }
}

/// `"instance.variable"` split at the first dot (instance names hold none); `None` without one.
pub fn split(name: &str) -> Option<(&str, &str)> {
    name.split_once('.')
}

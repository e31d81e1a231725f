//! The thesis' test matrix (Tables 7.4–7.7) as run definitions for `systems/closed_loop.json`.
//!
//! Every test runs in two variants: 1 truth feedback (the controller reads the truth tip,
//! length, pendulum angles and ship attitude; every sensor noise off) and 2 sensor feedback
//! (potentiometers, encoder and complementary filters, with the SPEC §8.1 noise); a third, 3,
//! is variant 2 with the ship's surge, sway and heave from the controller's EKF (§5.1.3) instead
//! of the truth the thesis supplied, so that the controller reads no truth at all. The sensor
//! variants may use Madgwick's attitude filter instead of the complementary filter
//! ([`AttitudeFilter`]). Each run has
//! [`INIT_TIME`] of estimator initialisation first: the load is held at its initial angles
//! (`pendulum.release_time`), the controller estimates but does not command until
//! `controller.active_from`, and ship motion starts then (fading in over [`FADE_IN`]); the test
//! proper is the [`TEST_TIME`] after it. [`Init::Thesis`] instead starts everything at t = 0 with
//! the filters at the identity, as the thesis' simulations did (§7.2.5).

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde_json::Value;

use cosim_engine::system::scenario::ScenarioSpec;
use crane_metrics::run::G;
use crane_names::{CraneNames, FullScaleControl, TestScaleControl, FULL_SCALE, TEST_SCALE};

use crate::scale::{CampaignScale, Scale, LENGTH_SCALE};

/// The names of the system every run starts from, at test scale and at full scale.
const N: CraneNames = TEST_SCALE;
const F: CraneNames = FULL_SCALE;
/// What only each scale's loop has (checked when this compiles: a `None` fails the build).
const NT: TestScaleControl = match N.test {
    Some(names) => names,
    None => panic!("the test scale's names have its controller's"),
};
const FF: FullScaleControl = match F.full {
    Some(names) => names,
    None => panic!("the full scale's names have its controller's"),
};

/// Estimator initialisation before the test starts (s): thesis §7.3 "10 seconds of recording
/// before ... to allow for initialization of the estimation algorithms".
pub const INIT_TIME: f64 = 10.0;
/// The test proper (s), after [`INIT_TIME`].
pub const TEST_TIME: f64 = 120.0;
/// Ship motion fades in over this time (s) after [`INIT_TIME`] (a smooth start instead of a
/// velocity jump the platform could not follow).
pub const FADE_IN: f64 = 2.0;
/// Amplitude of the sinusoidal surge/sway excitation of tests 084–088 and 092–096 (m).
pub const SINE_AMPLITUDE: f64 = 0.004;

/// The three groups of Chapter 7.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// §7.2, tests 001–080: release from an initial angle, no ship motion.
    EnergyDissipation,
    /// §7.3, tests 081–096: fixed set-point under ship motion or natural-frequency excitation.
    FixedSetpoint,
    /// §7.4, tests 097–104: the pick-and-place set-point profile.
    VariableSetpoint,
}

/// What the controller does (`controller.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Control {
    /// 0: crane off (neutral commands) — the free response of tests 001–040.
    Off,
    /// 1: inverse-kinematic positioning only, no compensation (081–088, 097–100).
    InverseKinematics,
    /// 2: world-frame compensation (041–080, 089–096, 101–104).
    Compensated,
}

impl Family {
    /// In words, for reports: "energy dissipation".
    pub fn label(self) -> &'static str {
        match self {
            Family::EnergyDissipation => "energy dissipation",
            Family::FixedSetpoint => "fixed set-point",
            Family::VariableSetpoint => "variable set-point",
        }
    }
}

impl Control {
    /// In words, for reports: "inverse kinematics only".
    pub fn label(self) -> &'static str {
        match self {
            Control::Off => "crane off",
            Control::InverseKinematics => "inverse kinematics only",
            Control::Compensated => "compensated",
        }
    }

    fn mode(self) -> i64 {
        match self {
            Control::Off => 0,
            Control::InverseKinematics => 1,
            Control::Compensated => 2,
        }
    }

    /// Whether this is the compensated half of a comparison.
    pub fn compensated(self) -> bool {
        self == Control::Compensated
    }
}

/// Base excitation (`platform.profile`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Motion {
    Still,
    /// Test-scale ship motion profile 1–3 (Appendix A; SPEC §8.2).
    Profile(u8),
    /// Surge and sway sine at the natural frequency √(g/l) of a pendulum of this length (m).
    NaturalFrequency(f64),
}

impl Motion {
    /// A short label: "still", "profile 1", "wn(0.70 m)".
    pub fn label(&self) -> String {
        self.label_at(Scale::Test)
    }

    /// [`Motion::label`] with the lengths at `scale`: "wn(17.50 m)" at full scale.
    pub fn label_at(&self, scale: Scale) -> String {
        match self {
            Motion::Still => "no motion".into(),
            Motion::Profile(p) => format!("profile {p}"),
            Motion::NaturalFrequency(l) => format!("wn({:.2} m)", scale.length(*l)),
        }
    }
}

/// The feedback variant of a simulation (thesis §7.2.1: "1" truth, "2" simulated sensors; "3"
/// simulated sensors and the surge/sway/heave EKF, beyond the thesis).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Variant {
    Truth = 1,
    Sensors = 2,
    Estimated = 3,
}

impl Variant {
    /// The thesis' two variants, the campaign's default.
    pub const BOTH: [Variant; 2] = [Variant::Truth, Variant::Sensors];
    pub const ALL: [Variant; 3] = [Variant::Truth, Variant::Sensors, Variant::Estimated];

    pub fn number(self) -> u8 {
        self as u8
    }

    pub fn from_number(n: u8) -> Option<Variant> {
        Variant::ALL.into_iter().find(|v| v.number() == n)
    }

    /// The controller's `feedback` code: 0 truth, 1 sensors, 2 sensors and the EKF.
    fn feedback(self) -> i64 {
        i64::from(self.number()) - 1
    }

    /// Whether the sensors (and their noise) are simulated.
    pub fn sensors(self) -> bool {
        self != Variant::Truth
    }

    /// In words, for reports.
    pub fn label(self) -> &'static str {
        match self {
            Variant::Truth => "truth feedback",
            Variant::Sensors => "sensor feedback with noise",
            Variant::Estimated => "sensor feedback with noise, surge/sway/heave from the EKF",
        }
    }
}

/// The attitude estimator of the sensor variants (`controller.attitude_filter`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttitudeFilter {
    /// The thesis' complementary filter (§5.1.1, Tables 5.1–5.2).
    #[default]
    Complementary,
    /// Madgwick's gradient-descent filter.
    Madgwick,
}

impl AttitudeFilter {
    pub fn is_complementary(&self) -> bool {
        *self == AttitudeFilter::Complementary
    }
}

/// One row of Tables 7.4–7.7.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TestCase {
    /// Test number 1–104.
    pub number: u16,
    /// The group of Chapter 7 it belongs to.
    pub family: Family,
    /// What the controller does.
    pub control: Control,
    /// Pendulum length at the set-point (m).
    pub lp: f64,
    /// Initial cable angles θx, θy (deg).
    pub theta0_deg: [f64; 2],
    /// The base excitation.
    pub motion: Motion,
}

/// Lengths of Tables 7.4/7.5 (m) and the initial angles (deg) tested at each.
const LENGTHS: [f64; 5] = [0.40, 0.55, 0.70, 0.85, 1.00];
const INITIAL_ANGLES: [[f64; 2]; 8] =
    [[-8.5, 0.0], [-13.0, 0.0], [-18.0, 0.0], [-23.0, 0.0], [0.0, 7.6], [0.0, 13.0], [0.0, 18.0], [0.0, 24.0]];
/// Natural-frequency excitation lengths in the order of Table 7.6 (084–088, 092–096).
const SINE_LENGTHS: [f64; 5] = [0.70, 0.40, 0.55, 0.85, 1.00];

/// The crane actuator extensions (m) that put the tip at the start of the pick-and-place
/// profile, (+0.100, −0.277, −0.153) m in J12 = (+0.100, −0.502, −0.153) m in W (SPEC §8.4):
/// crane inverse kinematics (eqs. 4.78–4.88) and the mechanisms' (checked by a test).
pub const PICK_START_EXTENSIONS: [f64; 3] = [0.0433586640, 0.0279318264, 0.0306367279];

/// The full-scale crane's joints (rad: slew, boom, jib) that put the tip at the start of the
/// pick-and-place profile scaled by λ: the default pose's tip (`knuckle_boom`'s q0.*: −90°, 40°,
/// −60°, 10.25 m out to port) moved +2.5 m along x (the test scale's x = +0.10 m × 25), so that
/// the profile's 5 m move to −x ends 2.5 m the other side: the arm's inverse kinematics
/// (`ArmParams::inverse_kinematics`; checked by a test). 10.55 m out, slew −76.3°, boom 37.2°,
/// jib −54.1°, both cylinders inside their strokes.
pub const FULL_SCALE_PICK_START_JOINTS: [f64; 3] = [-1.3315358122, 0.6496097296, -0.9448657927];

/// All 104 tests in thesis order.
pub fn tests() -> Vec<TestCase> {
    let mut all = Vec::with_capacity(104);
    for control in [Control::Off, Control::Compensated] {
        for lp in LENGTHS {
            for theta0_deg in INITIAL_ANGLES {
                let number = all.len() as u16 + 1;
                all.push(TestCase {
                    number,
                    family: Family::EnergyDissipation,
                    control,
                    lp,
                    theta0_deg,
                    motion: Motion::Still,
                });
            }
        }
    }
    for control in [Control::InverseKinematics, Control::Compensated] {
        let motions = (1..=3).map(Motion::Profile).chain(SINE_LENGTHS.map(Motion::NaturalFrequency));
        for motion in motions {
            let lp = if let Motion::NaturalFrequency(l) = motion { l } else { 0.70 };
            let number = all.len() as u16 + 1;
            all.push(TestCase { number, family: Family::FixedSetpoint, control, lp, theta0_deg: [0.0; 2], motion });
        }
    }
    for control in [Control::InverseKinematics, Control::Compensated] {
        for motion in [Motion::Still, Motion::Profile(1), Motion::Profile(2), Motion::Profile(3)] {
            let number = all.len() as u16 + 1;
            all.push(TestCase {
                number,
                family: Family::VariableSetpoint,
                control,
                lp: 0.70,
                theta0_deg: [0.0; 2],
                motion,
            });
        }
    }
    all
}

/// How the estimators start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Init {
    /// [`INIT_TIME`] with the load held and the complementary filters aligned on their first
    /// sample (`controller.cf_init = 1`), then the test: no estimation transient in the test.
    #[default]
    Held,
    /// The thesis' simulations (§7.2.5): filters started at the identity (`cf_init = 0`), no
    /// hold — release, control and ship motion start at t = 0, so the test contains the initial
    /// estimation "kick".
    Thesis,
}

/// One simulation: a test in one variant.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RunSpec {
    /// The test of the matrix.
    pub test: TestCase,
    /// The feedback variant.
    pub variant: Variant,
    /// How the estimators start.
    pub init: Init,
    /// The sensor variants' attitude filter (not written for the default complementary filter, so
    /// that metrics.json of a thesis campaign is what it was).
    #[serde(skip_serializing_if = "AttitudeFilter::is_complementary")]
    pub attitude: AttitudeFilter,
    /// The crane (not written at test scale, so that metrics.json of a thesis campaign is what
    /// it was).
    #[serde(skip_serializing_if = "Scale::is_test")]
    pub scale: Scale,
}

impl RunSpec {
    /// A run with the default initialisation ([`Init::Held`]) and attitude filter.
    pub fn new(test: TestCase, variant: Variant) -> Self {
        RunSpec { test, variant, init: Init::Held, attitude: AttitudeFilter::Complementary, scale: Scale::Test }
    }

    /// The excitation in words, lengths at the run's scale.
    pub fn excitation(&self) -> String {
        self.test.motion.label_at(self.scale)
    }

    /// The run's rope length (m) at its scale.
    pub fn lp(&self) -> f64 {
        self.scale.length(self.test.lp)
    }

    /// How long the test proper runs (s): [`TEST_TIME`], and at full scale √λ times that for the
    /// pick-and-place tests, whose set-point timetable is Froude-scaled (the winch could not pay
    /// out the scaled rope in the thesis' 120 s: docs/full-scale.md).
    pub fn test_time(&self) -> f64 {
        match (self.scale, self.test.family) {
            (Scale::Full, Family::VariableSetpoint) => TEST_TIME * LENGTH_SCALE.sqrt(),
            _ => TEST_TIME,
        }
    }

    /// When the test proper starts (s): release, control and ship motion.
    pub fn init_time(&self) -> f64 {
        match self.init {
            Init::Held => INIT_TIME,
            Init::Thesis => 0.0,
        }
    }

    /// "020-1": the thesis' simulation label.
    pub fn id(&self) -> String {
        format!("{:03}-{}", self.test.number, self.variant.number())
    }

    /// The scenario for `system` (a path relative to where the scenario is written or
    /// resolved): the closed loop with this test's start values.
    pub fn scenario(&self, system: PathBuf) -> ScenarioSpec {
        ScenarioSpec {
            description: self.description(),
            system,
            start: self.start_values(),
            stop_time: Some(self.init_time() + self.test_time()),
            step_size: None,
            algorithm: None,
            record: None,
        }
    }

    fn description(&self) -> String {
        let t = &self.test;
        let control = match t.control {
            Control::Compensated => "world-frame compensation",
            other => other.label(),
        };
        let feedback = match (self.variant.sensors(), self.attitude) {
            (true, AttitudeFilter::Madgwick) => format!("{}, Madgwick attitude filter", self.variant.label()),
            _ => self.variant.label().to_string(),
        };
        let scale = match self.scale {
            Scale::Test => String::new(),
            Scale::Full => format!("{}, ", self.scale.label()),
        };
        format!(
            "Simulation {}: {scale}{}, {control}, {feedback}, l_p = {:.0} mm, theta0 = ({}, {}) deg, {}",
            self.id(),
            t.family.label(),
            self.lp() * 1e3,
            t.theta0_deg[0],
            t.theta0_deg[1],
            self.excitation()
        )
    }

    /// `"instance.variable"` start values over the closed loop's defaults.
    pub fn start_values(&self) -> BTreeMap<String, Value> {
        if self.scale == Scale::Full {
            return self.full_scale_start_values();
        }
        let t = &self.test;
        let sensors = self.variant.sensors();
        let mut start: Vec<(&str, Value)> = vec![
            (N.theta0[0], t.theta0_deg[0].to_radians().into()),
            (N.theta0[1], t.theta0_deg[1].to_radians().into()),
            (N.release_time, self.init_time().into()),
            (N.lp0, t.lp.into()),
            (NT.setpoint_lp, t.lp.into()),
            // The length the controller counts its winch encoder from (§6.1).
            (NT.encoder_lp0, t.lp.into()),
            (N.mode, t.control.mode().into()),
            (NT.feedback, self.variant.feedback().into()),
            (N.active_from, self.init_time().into()),
            (NT.filter_init, i64::from(self.init == Init::Held).into()),
            (N.noise[0], sensors.into()),
            (N.noise[1], sensors.into()),
            (N.noise[2], sensors.into()),
        ];
        if sensors && self.attitude == AttitudeFilter::Madgwick {
            start.push((NT.attitude_filter, 1.into()));
        }
        start.extend(motion_start_values(&N, &t.motion, self.init_time(), 1.0));
        if t.family == Family::VariableSetpoint {
            start.push((N.setpoint_source, 1.into()));
            for (name, d) in NT.extensions0.into_iter().zip(PICK_START_EXTENSIONS) {
                start.push((name, d.into()));
            }
        }
        start.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
    }
}

impl RunSpec {
    /// The start values over `systems/full_scale_ahc.json` (docs/full-scale.md, the full-scale
    /// campaign): the same release, hold and motion window as at test scale; the arm off (mode 0)
    /// for the crane-off tests, holding its joints (mode 1) for the inverse-kinematics-only ones,
    /// compensating in the world with the anti-sway law (mode 2) for the compensated ones; the
    /// heave compensated by the winch in the compensated tests only, so that each pair compares
    /// the control with none. Variant 2 switches the crane's encoder and pressure noise on (the
    /// controller reads the encoders). The pick-and-place tests start the arm at
    /// [`FULL_SCALE_PICK_START_JOINTS`] and switch the controller to its pick-and-place profile
    /// (`setpoint` 1), which moves the references it latches at release.
    fn full_scale_start_values(&self) -> BTreeMap<String, Value> {
        let t = &self.test;
        let (mode, heave) = match t.control {
            Control::Off => (0, 0),
            Control::InverseKinematics => (1, 0),
            Control::Compensated => (2, 1),
        };
        let mut start: Vec<(&str, Value)> = vec![
            (F.theta0[0], t.theta0_deg[0].to_radians().into()),
            (F.theta0[1], t.theta0_deg[1].to_radians().into()),
            (F.release_time, self.init_time().into()),
            (F.lp0, self.lp().into()),
            (F.mode, mode.into()),
            (FF.heave, heave.into()),
            (F.active_from, self.init_time().into()),
            (F.noise[0], self.variant.sensors().into()),
        ];
        start.extend(motion_start_values(&F, &t.motion, self.init_time(), LENGTH_SCALE));
        if t.family == Family::VariableSetpoint {
            start.push((F.setpoint_source, 1.into()));
            for (name, q) in FF.joints0.into_iter().zip(FULL_SCALE_PICK_START_JOINTS) {
                start.push((name, q.into()));
            }
        }
        start.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
    }
}

/// The excitation of `motion` from `start` (s), lengths ×`scale` (the natural frequency of the
/// scaled length, the sine's amplitude scaled).
fn motion_start_values(names: &CraneNames, motion: &Motion, start: f64, scale: f64) -> Vec<(&'static str, Value)> {
    let profile = match motion {
        Motion::Still => return vec![(names.profile, 0.into())],
        Motion::Profile(p) => vec![(names.profile, i64::from(*p).into())],
        Motion::NaturalFrequency(l) => vec![
            (names.profile, 4.into()),
            (names.sine_omega, (G / (l * scale)).sqrt().into()),
            (names.sine_amplitude, (SINE_AMPLITUDE * scale).into()),
        ],
    };
    let window = [(names.motion_start, start.into()), (names.fade_in, FADE_IN.into())];
    profile.into_iter().chain(window).collect()
}

/// Whether `run` can run at its scale: the full-scale controller has no surge/sway/heave EKF
/// (variant 3).
pub fn supported(run: &RunSpec) -> Result<(), String> {
    if run.scale == Scale::Full && run.variant == Variant::Estimated {
        return Err("variant 3 (the surge/sway/heave EKF) does not run at full scale (variants 1 and 2 do)".into());
    }
    Ok(())
}

/// Every run of `tests` in `variants`, test-major, with the default attitude filter.
pub fn runs(tests: &[TestCase], variants: &[Variant], init: Init) -> Vec<RunSpec> {
    tests
        .iter()
        .flat_map(|&test| variants.iter().map(move |&variant| RunSpec { init, ..RunSpec::new(test, variant) }))
        .collect()
}

/// The uncompensated test a compensated one is compared with (eq. 7.1's reference): 041–080 →
/// 001–040, 089–096 → 081–088, 101–104 → 097–100.
pub fn reference_of(test: &TestCase) -> Option<u16> {
    match (test.family, test.control) {
        (Family::EnergyDissipation, Control::Compensated) => Some(test.number - 40),
        (Family::FixedSetpoint, Control::Compensated) => Some(test.number - 8),
        (Family::VariableSetpoint, Control::Compensated) => Some(test.number - 4),
        _ => None,
    }
}

/// Parses a selection like "1-40,60,97-104" into test numbers (1–104).
pub fn parse_selection(text: &str) -> Result<Vec<u16>, String> {
    let mut numbers = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let parse = |s: &str| s.trim().parse::<u16>().map_err(|_| format!("'{s}' in '{text}' is not a test number"));
        let (a, b) = match part.split_once('-') {
            Some((a, b)) => (parse(a)?, parse(b)?),
            None => (parse(part)?, parse(part)?),
        };
        if a < 1 || b > 104 || a > b {
            return Err(format!("'{part}': tests are numbered 1-104 in increasing ranges"));
        }
        numbers.extend(a..=b);
    }
    numbers.sort_unstable();
    numbers.dedup();
    Ok(numbers)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_matrix_has_the_rows_of_tables_7_4_to_7_7() {
        let all = tests();
        assert_eq!(all.len(), 104);
        assert!(all.iter().enumerate().all(|(i, t)| t.number as usize == i + 1));
        // Table 7.4: 020 = no compensation, 700 mm, θx0 = −23°; Table 7.5: 060 its compensated twin.
        let (t20, t60) = (&all[19], &all[59]);
        assert_eq!((t20.control, t20.lp, t20.theta0_deg), (Control::Off, 0.70, [-23.0, 0.0]));
        assert_eq!((t60.control, t60.lp, t60.theta0_deg), (Control::Compensated, 0.70, [-23.0, 0.0]));
        assert_eq!(all[39].theta0_deg, [0.0, 24.0]);
        assert_eq!(all[39].lp, 1.00);
        // Table 7.6: 084 = IK, ωn(0.70 m); 085 ωn(0.40 m); 092 compensated ωn(0.70 m).
        assert_eq!(
            (all[83].control, all[83].motion, all[83].lp),
            (Control::InverseKinematics, Motion::NaturalFrequency(0.70), 0.70)
        );
        assert_eq!(all[84].motion, Motion::NaturalFrequency(0.40));
        assert_eq!((all[91].control, all[91].motion), (Control::Compensated, Motion::NaturalFrequency(0.70)));
        assert_eq!(all[88].motion, Motion::Profile(1));
        // Table 7.7: 097 IK no motion, 104 compensated profile 3.
        assert_eq!(
            (all[96].family, all[96].control, all[96].motion),
            (Family::VariableSetpoint, Control::InverseKinematics, Motion::Still)
        );
        assert_eq!((all[103].control, all[103].motion), (Control::Compensated, Motion::Profile(3)));
        assert_eq!(runs(&all, &Variant::BOTH, Init::Held).len(), 208);
    }

    #[test]
    fn each_compensated_test_has_its_uncompensated_reference() {
        let all = tests();
        for t in all.iter().filter(|t| t.control.compensated()) {
            let r = &all[reference_of(t).unwrap() as usize - 1];
            assert!(!r.control.compensated(), "{} -> {}", t.number, r.number);
            assert_eq!(
                (r.family, r.lp, r.theta0_deg, r.motion),
                (t.family, t.lp, t.theta0_deg, t.motion),
                "{}",
                t.number
            );
        }
        assert_eq!(all.iter().filter(|t| reference_of(t).is_some()).count(), 52);
    }

    #[test]
    fn start_values_set_the_variant_and_the_excitation() {
        let all = tests();
        let run = RunSpec::new(all[86], Variant::Sensors); // 087: ωn(0.85 m)
        let start = run.start_values();
        assert_eq!(run.id(), "087-2");
        assert_eq!(start["controller.feedback"], 1);
        assert_eq!(start["imu2.noise"], true);
        assert_eq!(start["platform.profile"], 4);
        assert!((start["platform.sine_omega"].as_f64().unwrap() - 3.3967).abs() < 1e-4);
        assert_eq!(start["crane.lp0"], 0.85);
        assert_eq!(
            (start["controller.sp.lp"].clone(), start["controller.encoder.lp0"].clone()),
            (0.85.into(), 0.85.into())
        );
        let truth = RunSpec::new(all[19], Variant::Truth).start_values();
        assert_eq!((truth["controller.feedback"].clone(), truth["crane.noise"].clone()), (0.into(), false.into()));
        assert!((truth["pendulum.theta_x0"].as_f64().unwrap() + 23f64.to_radians()).abs() < 1e-15);
        assert!(!truth.contains_key("platform.motion_start"));
        let pick = RunSpec::new(all[101], Variant::Truth).start_values();
        assert_eq!(pick["controller.setpoint"], 1);
        assert_eq!(pick["crane.d0.base"], PICK_START_EXTENSIONS[0]);
        assert_eq!(
            (pick["controller.cf_init"].clone(), pick["platform.motion_start"].clone()),
            (1.into(), 10.0.into())
        );
    }

    #[test]
    fn variant_3_reads_no_truth_and_madgwick_applies_to_the_sensor_variants_only() {
        let test = tests()[90]; // 091: compensated, profile 3
        let estimated = RunSpec::new(test, Variant::Estimated);
        let start = estimated.start_values();
        assert_eq!(estimated.id(), "091-3");
        assert_eq!((start["controller.feedback"].clone(), start["imu1.noise"].clone()), (2.into(), true.into()));
        assert!(!start.contains_key("controller.attitude_filter"));
        assert_eq!(Variant::from_number(3), Some(Variant::Estimated));
        assert_eq!(Variant::from_number(4), None);
        let madgwick = |variant| RunSpec { attitude: AttitudeFilter::Madgwick, ..RunSpec::new(test, variant) };
        assert_eq!(madgwick(Variant::Estimated).start_values()["controller.attitude_filter"], 1);
        assert_eq!(madgwick(Variant::Sensors).start_values()["controller.attitude_filter"], 1);
        assert!(!madgwick(Variant::Truth).start_values().contains_key("controller.attitude_filter"));
        assert!(madgwick(Variant::Estimated).description().ends_with(
            "sensor feedback with noise, surge/sway/heave from the EKF, Madgwick attitude filter, l_p = 700 mm, theta0 = (0, 0) deg, profile 3"
        ));
    }

    #[test]
    fn the_thesis_initialisation_starts_everything_at_zero_with_identity_filters() {
        let run = RunSpec { init: Init::Thesis, ..RunSpec::new(tests()[59], Variant::Sensors) };
        let start = run.start_values();
        assert_eq!(start["controller.cf_init"], 0);
        assert_eq!(
            (start["pendulum.release_time"].clone(), start["controller.active_from"].clone()),
            (0.0.into(), 0.0.into())
        );
        assert_eq!(run.scenario(PathBuf::from("s.json")).stop_time, Some(TEST_TIME));
    }

    #[test]
    fn the_pick_and_place_start_pose_puts_the_tip_at_the_profile_start() {
        let tip = physics::crane::kinematics::tip_from_actuators(&PICK_START_EXTENSIONS).unwrap();
        let expected = [0.100, -0.277, -0.153];
        assert!((0..3).all(|i| (tip[i] - expected[i]).abs() < 1e-9), "{tip:?}");
    }

    #[test]
    fn the_full_scale_runs_map_lengths_by_froude_and_control_to_the_offshore_modes() {
        let all = tests();
        let full = |n: usize, variant| RunSpec { scale: Scale::Full, ..RunSpec::new(all[n - 1], variant) };
        // 060: compensated, 700 mm → 17.5 m, θx0 = −23°.
        let start = full(60, Variant::Truth).start_values();
        assert_eq!(start["knuckle_boom.lp0"], 17.5);
        assert_eq!(
            (start["knuckle_boom_controller.mode"].clone(), start["knuckle_boom_controller.heave"].clone()),
            (2.into(), 1.into())
        );
        assert_eq!(start["knuckle_boom_controller.active_from"], 10.0);
        assert!((start["pendulum.theta_x0"].as_f64().unwrap() + 23f64.to_radians()).abs() < 1e-15);
        assert_eq!(start["knuckle_boom.noise"], false);
        assert!(!start.keys().any(|k| k.starts_with("controller.") || k.starts_with("crane.")), "{start:?}");
        // 020 off; 084 joints held at ωn(17.5 m) with the sine's 4 mm × 25.
        let off = full(20, Variant::Sensors).start_values();
        assert_eq!(
            (off["knuckle_boom_controller.mode"].clone(), off["knuckle_boom.noise"].clone()),
            (0.into(), true.into())
        );
        let sine = full(84, Variant::Truth);
        let start = sine.start_values();
        assert_eq!(
            (start["knuckle_boom_controller.mode"].clone(), start["knuckle_boom_controller.heave"].clone()),
            (1.into(), 0.into())
        );
        assert!((start["platform.sine_omega"].as_f64().unwrap() - (G / 17.5).sqrt()).abs() < 1e-15);
        assert_eq!(start["platform.sine_amplitude"], 0.1);
        assert_eq!(sine.excitation(), "wn(17.50 m)");
        assert!(
            sine.description().starts_with("Simulation 084-1: full scale, fixed set-point"),
            "{}",
            sine.description()
        );
        // What the full-scale crane cannot run; everything at test scale.
        assert!(supported(&full(97, Variant::Truth)).is_ok() && supported(&full(104, Variant::Sensors)).is_ok());
        assert!(supported(&full(89, Variant::Estimated)).unwrap_err().contains("variant 3"));
        assert!(supported(&RunSpec::new(all[96], Variant::Estimated)).is_ok());
    }

    #[test]
    fn the_full_scale_pick_and_place_runs_start_at_the_scaled_profile_and_run_its_600_s() {
        let all = tests();
        let full = |n: usize| RunSpec { scale: Scale::Full, ..RunSpec::new(all[n - 1], Variant::Truth) };
        // 102: compensated, profile 1, 17.5 m of rope (0.70 m × 25).
        let run = full(102);
        let start = run.start_values();
        assert_eq!(start["knuckle_boom_controller.setpoint"], 1);
        assert_eq!(start["knuckle_boom.q0.slew"], FULL_SCALE_PICK_START_JOINTS[0]);
        assert_eq!((start["knuckle_boom.lp0"].clone(), start["platform.profile"].clone()), (17.5.into(), 1.into()));
        assert_eq!((run.test_time(), run.scenario(PathBuf::from("s.json")).stop_time), (600.0, Some(610.0)));
        // 098, its twin: joints held on the profile, no heave compensation.
        let start = full(98).start_values();
        assert_eq!(
            (start["knuckle_boom_controller.mode"].clone(), start["knuckle_boom_controller.heave"].clone()),
            (1.into(), 0.into())
        );
        // The fixed set-point tests keep the thesis' 120 s and the default pose.
        let fixed = full(89);
        assert_eq!(fixed.test_time(), TEST_TIME);
        assert!(!fixed.start_values().keys().any(|k| k.contains("q0.") || k.ends_with(".setpoint")));
        // The campaign's λ is the controller's.
        assert_eq!(LENGTH_SCALE, physics::offshore_control::setpoint::FULL_SCALE.length);
    }

    #[test]
    fn the_full_scale_pick_start_pose_puts_the_tip_2_5_m_along_x_from_the_default_pose() {
        let arm = physics::knuckle_boom::params::ArmParams::DEFAULT;
        let default = physics::hydraulic_crane::plant::DEFAULT_JOINTS;
        let tip = arm.tip_in_base(&default, &[0.0; 3], &[0.0; 3]).pos;
        let shift = physics::math::Vec3::new(0.1 * LENGTH_SCALE, 0.0, 0.0);
        let joints = arm.inverse_kinematics(&(tip + shift)).unwrap();
        assert!((0..3).all(|i| (joints[i] - FULL_SCALE_PICK_START_JOINTS[i]).abs() < 1e-9), "{joints:?}");
        // The end of the move is in reach too.
        assert!(arm.inverse_kinematics(&(tip - shift)).is_ok());
    }

    #[test]
    fn selections_parse_ranges_and_reject_nonsense() {
        assert_eq!(parse_selection("1-3, 20,2").unwrap(), vec![1, 2, 3, 20]);
        assert!(parse_selection("0-4").is_err());
        assert!(parse_selection("9-3").is_err());
        assert!(parse_selection("x").is_err());
        assert!(parse_selection("105").is_err());
    }
}

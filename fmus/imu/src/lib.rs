//! FMU `imu`: the 9-axis inertial measurement unit (SPEC §4.4, thesis §3.4.5 and §3.5.4).
//!
//! A sampled sensor without continuous state: the readings at a communication point are a pure
//! function of the parameters, the inputs currently set (true orientation, angular velocity and
//! linear acceleration of the sensor) and the sample index k = the number of completed steps, so
//! k = 0 at the start time. Inputs act directly on the outputs (direct feedthrough) and are held,
//! never interpolated. Noise comes from `physics::noise` and depends only on (seed, channel, k).
//! All ports SI; W is North-East-Down, the outputs are in the sensor frame.

use fmu_model::{noise_parameters, xyz, Environment, Model, ModelInfo, Variable};
use physics::imu::{orientation_from_components, readings_with, ImuMotion, ImuNoise, ImuParams, ImuReadings};
use physics::math::{components, Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::cell::OnceCell;

/// Instance data: configuration, the inputs as last set, the sample index and its noise.
#[derive(Clone, Serialize, Deserialize)]
pub struct Imu {
    params: ImuParams,
    /// Orientation W←sensor as set (scalar first); normalised when used.
    q: [f64; 4],
    /// Angular velocity of the sensor, sensor frame (rad/s).
    w: Vec3,
    /// Linear acceleration of the sensor point, W (m/s²).
    a: Vec3,
    /// Sample index k of the current readings: steps completed since initialization.
    k: u64,
    /// The random terms of sample k, drawn whenever k is set (parameters change only before
    /// initialization, which sets it).
    noise: ImuReadings,
    /// The channels' noise memos (a cache: rebuilt after deserialization, never changes a value).
    #[serde(skip)]
    streams: ImuNoise,
    /// The readings for the current inputs and sample once computed, so that each getter does
    /// not compute all nine; emptied whenever an input or the sample changes.
    #[serde(skip)]
    readings: OnceCell<ImuReadings>,
}

impl Imu {
    fn orientation(&self) -> Result<Quat, String> {
        orientation_from_components(self.q)
    }

    /// Moves to sample index `k`: draws its noise and forgets the readings of the previous one.
    fn set_sample(&mut self, k: u64) {
        self.k = k;
        self.noise = self.streams.draw(&self.params, k);
        self.readings = OnceCell::new();
    }

    /// Applies `set` to the inputs; the readings depend on them directly (direct feedthrough).
    fn set_input(&mut self, set: impl FnOnce(&mut Self)) {
        set(self);
        self.readings = OnceCell::new();
    }

    /// The nine outputs for the current inputs at sample k. NaN while the orientation input is
    /// unusable (`initialize` and `do_step` report that as an error).
    fn readings(&self) -> &ImuReadings {
        // A reference, not a copy: each of the nine getters reads one component.
        self.readings.get_or_init(|| match self.orientation() {
            Ok(orientation) => {
                let motion = ImuMotion { orientation, angular_velocity: self.w, acceleration: self.a };
                readings_with(&self.params, &motion, &self.noise)
            }
            Err(_) => ImuReadings { gyro: NAN3, acc: NAN3, mag: NAN3 },
        })
    }
}

const NAN3: Vec3 = Vec3::new(f64::NAN, f64::NAN, f64::NAN);

impl Model for Imu {
    const INFO: ModelInfo = ModelInfo::new(
        "imu",
        concat!(
            "9-axis IMU: gyroscope, accelerometer (specific force) and magnetometer in the sensor frame, with ",
            "seeded Gaussian noise, biases and quantisation (thesis sections 3.4.5, 3.5.4)",
        ),
    );

    fn variables() -> &'static [Variable<Self>] {
        &VARIABLES
    }

    fn new(_env: &Environment) -> Self {
        let mut imu = Imu {
            params: PARAMS,
            q: REST_Q,
            w: REST_W,
            a: REST_A,
            k: 0,
            noise: ImuReadings::default(),
            streams: ImuNoise::default(),
            readings: OnceCell::new(),
        };
        imu.set_sample(0);
        imu
    }

    fn initialize(&mut self, _start_time: f64) -> Result<(), String> {
        let checked = self.params.validate().and_then(|()| self.orientation().map(drop));
        // The parameters may have changed since the sample was drawn, so it is drawn again even
        // when they are refused (the outputs stay those of the parameters as set).
        self.set_sample(if checked.is_ok() { 0 } else { self.k });
        checked
    }

    fn do_step(&mut self, _t: f64, _h: f64) -> Result<(), String> {
        self.orientation()?;
        self.set_sample(self.k + 1);
        Ok(())
    }
}

type V = Variable<Imu>;
type Real = fmu_model::Real<Imu>;
type Integer = fmu_model::Integer<Imu>;
type Boolean = fmu_model::Boolean<Imu>;

/// The default error model (SPEC §8.1): the start values of the table and of [`Model::new`].
const PARAMS: ImuParams = ImuParams::DEFAULT;
/// The default inputs, a sensor at rest: level (identity orientation W←sensor, scalar first), no
/// rotation (rad/s, sensor frame), no acceleration (m/s², W).
const REST_Q: [f64; 4] = [1.0, 0.0, 0.0, 0.0];
const REST_W: Vec3 = Vec3::new(0.0, 0.0, 0.0);
const REST_A: Vec3 = Vec3::new(0.0, 0.0, 0.0);

/// Largest accepted noise standard deviation or bias (in the sensor's unit); a guard against
/// unit mistakes, far beyond any real sensor.
const MAX_ERROR: f64 = 1e3;

/// The held input row of component `I` of the orientation quaternion (0 the scalar part, 1-3 the
/// vector part), starting at rest: one place for the four components, which differ only in their
/// index, name and description. It writes through [`Imu::set_input`], like every input.
const fn orientation<const I: usize>(vr: u32, name: &'static str, doc: &'static str) -> V {
    Real::held_input(vr, name)
        .unit("1")
        .start(REST_Q[I])
        .doc(doc)
        .get(|m| m.q[I])
        .set(|m, v| m.set_input(|m| m.q[I] = v))
}

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
const GROUPS: &[&[V]] = &[
    // Parameters.
    &noise_parameters!(0, m => m.params.noise, m.params.seed, start: (PARAMS.noise, PARAMS.seed as i32),
        noise: "Apply the random noise (biases and quantisation apply regardless)",
        seed: "Noise seed; give every instance its own (equal seeds give identical noise)"),
    &xyz!(Real::parameter(2, "gyro.sigma."),
        unit: "rad/s",
        range: (0.0, MAX_ERROR),
        doc: ("Gyroscope noise standard deviation, " + axis),
        field: (m.params, PARAMS).gyro.sigma),
    &xyz!(Real::parameter(5, "acc.sigma."),
        unit: "m/s2",
        range: (0.0, MAX_ERROR),
        doc: ("Accelerometer noise standard deviation, " + axis),
        field: (m.params, PARAMS).acc.sigma),
    &xyz!(Real::parameter(8, "mag.sigma."),
        unit: "1",
        range: (0.0, MAX_ERROR),
        doc: [
            "Magnetometer noise standard deviation (unit-vector components), x",
            "Magnetometer noise standard deviation, y",
            "Magnetometer noise standard deviation, z",
        ],
        field: (m.params, PARAMS).mag.sigma),
    &xyz!(Real::parameter(11, "gyro.bias."),
        unit: "rad/s",
        range: (-MAX_ERROR, MAX_ERROR),
        doc: ("Gyroscope constant bias, " + axis),
        field: (m.params, PARAMS).gyro.bias),
    &xyz!(Real::parameter(14, "acc.bias."),
        unit: "m/s2",
        range: (-MAX_ERROR, MAX_ERROR),
        doc: ("Accelerometer constant bias, " + axis),
        field: (m.params, PARAMS).acc.bias),
    &xyz!(Real::parameter(17, "mag.bias."),
        unit: "1",
        range: (-MAX_ERROR, MAX_ERROR),
        doc: [
            "Magnetometer constant bias (unit-vector components), x",
            "Magnetometer constant bias, y",
            "Magnetometer constant bias, z",
        ],
        field: (m.params, PARAMS).mag.bias),
    &[
        fmu_model::field!(Real::parameter(20, "gyro.lsb"), unit: "rad/s", range: (0.0, MAX_ERROR),
            doc: "Gyroscope quantisation step (0 = off)",
            field: (m.params, PARAMS).gyro.lsb),
        fmu_model::field!(Real::parameter(21, "acc.lsb"), unit: "m/s2", range: (0.0, MAX_ERROR),
            doc: "Accelerometer quantisation step (0 = off)",
            field: (m.params, PARAMS).acc.lsb),
        fmu_model::field!(Real::parameter(22, "mag.lsb"), unit: "1", range: (0.0, MAX_ERROR),
            doc: "Magnetometer quantisation step (0 = off)",
            field: (m.params, PARAMS).mag.lsb),
        fmu_model::field!(Real::parameter(23, "mag_declination"), unit: "rad",
            range: (-std::f64::consts::PI, std::f64::consts::PI),
            doc: "Magnetic field direction turned from north toward east about +z (W)",
            field: (m.params, PARAMS).mag_declination),
        fmu_model::field!(Real::parameter(24, "mag_inclination"), unit: "rad",
            range: (-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2),
            doc: "Magnetic field dip below the horizontal, positive down (W)",
            field: (m.params, PARAMS).mag_inclination),
        fmu_model::field!(Real::parameter(25, "g"), unit: "m/s2", range: (0.0, 1e3),
            doc: "Gravitational acceleration",
            field: (m.params, PARAMS).g),
        // Inputs: the true motion of the sensor.
        orientation::<0>(100, "q0", "Orientation W<-sensor, scalar part (normalised inside)"),
        orientation::<1>(101, "q1", "Orientation W<-sensor, x part"),
        orientation::<2>(102, "q2", "Orientation W<-sensor, y part"),
        orientation::<3>(103, "q3", "Orientation W<-sensor, z part"),
    ],
    &xyz!(Real::held_input(104, "w."),
        unit: "rad/s",
        start: components(&REST_W),
        doc: ("Angular velocity of the sensor, sensor frame, " + axis),
        get: |m| m.w,
        set: |m, v| m.set_input(|m| m.w)),
    &xyz!(Real::held_input(107, "a."),
        unit: "m/s2",
        start: components(&REST_A),
        doc: [
            "Linear acceleration of the sensor point, W, x (north)",
            "Linear acceleration of the sensor point, W, y (east)",
            "Linear acceleration of the sensor point, W, z (down)",
        ],
        get: |m| m.a,
        set: |m, v| m.set_input(|m| m.a)),
    &[
        // Outputs, sensor frame.
        Real::output(200, "gyro.x")
            .unit("rad/s")
            .doc("Gyroscope x: angular velocity + bias + noise, quantised")
            .get(|m| m.readings().gyro.x),
        Real::output(201, "gyro.y").unit("rad/s").doc("Gyroscope y").get(|m| m.readings().gyro.y),
        Real::output(202, "gyro.z").unit("rad/s").doc("Gyroscope z").get(|m| m.readings().gyro.z),
    ],
    &xyz!(Real::output(203, "acc."),
        unit: "m/s2",
        doc: [
            "Accelerometer x: specific force R^T(a + (0,0,-g)) + bias + noise, quantised",
            "Accelerometer y",
            "Accelerometer z (reads -g at rest, level)",
        ],
        get: |m| m.readings().acc),
    &[
        Real::output(206, "mag.x")
            .unit("1")
            .doc("Magnetometer x: unit field vector R^T m_W + bias + noise, quantised")
            .get(|m| m.readings().mag.x),
        Real::output(207, "mag.y").unit("1").doc("Magnetometer y").get(|m| m.readings().mag.y),
        Real::output(208, "mag.z").unit("1").doc("Magnetometer z").get(|m| m.readings().mag.z),
    ],
];

/// The groups joined into one table, in order.
static VARIABLES: [V; fmu_model::table_len(GROUPS)] = fmu_model::table(GROUPS);

fmu_export::export_fmu!(Imu);

#[cfg(test)]
mod tests;

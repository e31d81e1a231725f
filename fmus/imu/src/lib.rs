//! FMU `imu`: the 9-axis inertial measurement unit (SPEC §4.4, thesis §3.4.5 and §3.5.4).
//!
//! A sampled sensor without continuous state: the readings at a communication point are a pure
//! function of the parameters, the inputs currently set (true orientation, angular velocity and
//! linear acceleration of the sensor) and the sample index k = the number of completed steps, so
//! k = 0 at the start time. Inputs act directly on the outputs (direct feedthrough) and are held,
//! never interpolated. Noise comes from `physics::noise` and depends only on (seed, channel, k).
//! All ports SI; W is North-East-Down, the outputs are in the sensor frame.

use fmi2::{Model, ModelInfo, Variable};
use physics::imu::{orientation_from_components, readings_with, ImuMotion, ImuNoise, ImuParams, ImuReadings};
use physics::math::{components, Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::cell::Cell;

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
    readings: Cell<Option<ImuReadings>>,
}

impl Imu {
    fn orientation(&self) -> Result<Quat, String> {
        orientation_from_components(self.q)
    }

    /// Moves to sample index `k`: draws its noise and forgets the readings of the previous one.
    fn set_sample(&mut self, k: u64) {
        self.k = k;
        self.noise = self.streams.draw(&self.params, k);
        self.readings.set(None);
    }

    /// Applies `set` to the inputs; the readings depend on them directly (direct feedthrough).
    fn set_input(&mut self, set: impl FnOnce(&mut Self)) {
        set(self);
        self.readings.set(None);
    }

    /// The nine outputs for the current inputs at sample k. NaN while the orientation input is
    /// unusable (`initialize` and `do_step` report that as an error).
    fn readings(&self) -> ImuReadings {
        if let Some(readings) = self.readings.get() {
            return readings;
        }
        let readings = match self.orientation() {
            Ok(orientation) => {
                let motion = ImuMotion { orientation, angular_velocity: self.w, acceleration: self.a };
                readings_with(&self.params, &motion, &self.noise)
            }
            Err(_) => ImuReadings { gyro: NAN3, acc: NAN3, mag: NAN3 },
        };
        self.readings.set(Some(readings));
        readings
    }
}

const NAN3: Vec3 = Vec3::new(f64::NAN, f64::NAN, f64::NAN);

impl Model for Imu {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "imu",
        description: "9-axis IMU: gyroscope, accelerometer (specific force) and magnetometer in the sensor frame, with seeded Gaussian noise, biases and quantisation (thesis sections 3.4.5, 3.5.4)",
        default_stop_time: 10.0,
        default_step_size: 0.01,
        can_interpolate_inputs: false,
        max_step_size: f64::MAX,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(_env: &fmi2::Environment) -> Self {
        let mut imu = Imu {
            params: PARAMS,
            q: REST_Q,
            w: REST_W,
            a: REST_A,
            k: 0,
            noise: ImuReadings::default(),
            streams: ImuNoise::default(),
            readings: Cell::new(None),
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

/// The variable table (value references: parameters 0–99, inputs 100–199, outputs 200+).
static VARIABLES: &[V] = &[
    // Parameters.
    V::boolean_parameter(
        0,
        "noise",
        PARAMS.noise,
        "Apply the random noise (biases and quantisation apply regardless)",
        |m| m.params.noise,
        |m, v| m.params.noise = v,
    ),
    V::integer_parameter(
        1,
        "seed",
        PARAMS.seed as i32,
        0,
        i32::MAX,
        "Noise seed; give every instance its own (equal seeds give identical noise)",
        |m| m.params.seed as i32,
        |m, v| m.params.seed = v as u64,
    ),
    V::parameter(
        2,
        "gyro.sigma.x",
        "rad/s",
        components(&PARAMS.gyro.sigma)[0],
        "Gyroscope noise standard deviation, x",
        |m| m.params.gyro.sigma.x,
        |m, v| m.params.gyro.sigma.x = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        3,
        "gyro.sigma.y",
        "rad/s",
        components(&PARAMS.gyro.sigma)[1],
        "Gyroscope noise standard deviation, y",
        |m| m.params.gyro.sigma.y,
        |m, v| m.params.gyro.sigma.y = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        4,
        "gyro.sigma.z",
        "rad/s",
        components(&PARAMS.gyro.sigma)[2],
        "Gyroscope noise standard deviation, z",
        |m| m.params.gyro.sigma.z,
        |m, v| m.params.gyro.sigma.z = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        5,
        "acc.sigma.x",
        "m/s2",
        components(&PARAMS.acc.sigma)[0],
        "Accelerometer noise standard deviation, x",
        |m| m.params.acc.sigma.x,
        |m, v| m.params.acc.sigma.x = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        6,
        "acc.sigma.y",
        "m/s2",
        components(&PARAMS.acc.sigma)[1],
        "Accelerometer noise standard deviation, y",
        |m| m.params.acc.sigma.y,
        |m, v| m.params.acc.sigma.y = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        7,
        "acc.sigma.z",
        "m/s2",
        components(&PARAMS.acc.sigma)[2],
        "Accelerometer noise standard deviation, z",
        |m| m.params.acc.sigma.z,
        |m, v| m.params.acc.sigma.z = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        8,
        "mag.sigma.x",
        "1",
        components(&PARAMS.mag.sigma)[0],
        "Magnetometer noise standard deviation (unit-vector components), x",
        |m| m.params.mag.sigma.x,
        |m, v| m.params.mag.sigma.x = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        9,
        "mag.sigma.y",
        "1",
        components(&PARAMS.mag.sigma)[1],
        "Magnetometer noise standard deviation, y",
        |m| m.params.mag.sigma.y,
        |m, v| m.params.mag.sigma.y = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        10,
        "mag.sigma.z",
        "1",
        components(&PARAMS.mag.sigma)[2],
        "Magnetometer noise standard deviation, z",
        |m| m.params.mag.sigma.z,
        |m, v| m.params.mag.sigma.z = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        11,
        "gyro.bias.x",
        "rad/s",
        components(&PARAMS.gyro.bias)[0],
        "Gyroscope constant bias, x",
        |m| m.params.gyro.bias.x,
        |m, v| m.params.gyro.bias.x = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        12,
        "gyro.bias.y",
        "rad/s",
        components(&PARAMS.gyro.bias)[1],
        "Gyroscope constant bias, y",
        |m| m.params.gyro.bias.y,
        |m, v| m.params.gyro.bias.y = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        13,
        "gyro.bias.z",
        "rad/s",
        components(&PARAMS.gyro.bias)[2],
        "Gyroscope constant bias, z",
        |m| m.params.gyro.bias.z,
        |m, v| m.params.gyro.bias.z = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        14,
        "acc.bias.x",
        "m/s2",
        components(&PARAMS.acc.bias)[0],
        "Accelerometer constant bias, x",
        |m| m.params.acc.bias.x,
        |m, v| m.params.acc.bias.x = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        15,
        "acc.bias.y",
        "m/s2",
        components(&PARAMS.acc.bias)[1],
        "Accelerometer constant bias, y",
        |m| m.params.acc.bias.y,
        |m, v| m.params.acc.bias.y = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        16,
        "acc.bias.z",
        "m/s2",
        components(&PARAMS.acc.bias)[2],
        "Accelerometer constant bias, z",
        |m| m.params.acc.bias.z,
        |m, v| m.params.acc.bias.z = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        17,
        "mag.bias.x",
        "1",
        components(&PARAMS.mag.bias)[0],
        "Magnetometer constant bias (unit-vector components), x",
        |m| m.params.mag.bias.x,
        |m, v| m.params.mag.bias.x = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        18,
        "mag.bias.y",
        "1",
        components(&PARAMS.mag.bias)[1],
        "Magnetometer constant bias, y",
        |m| m.params.mag.bias.y,
        |m, v| m.params.mag.bias.y = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        19,
        "mag.bias.z",
        "1",
        components(&PARAMS.mag.bias)[2],
        "Magnetometer constant bias, z",
        |m| m.params.mag.bias.z,
        |m, v| m.params.mag.bias.z = v,
    )
    .range(-MAX_ERROR, MAX_ERROR),
    V::parameter(
        20,
        "gyro.lsb",
        "rad/s",
        PARAMS.gyro.lsb,
        "Gyroscope quantisation step (0 = off)",
        |m| m.params.gyro.lsb,
        |m, v| m.params.gyro.lsb = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        21,
        "acc.lsb",
        "m/s2",
        PARAMS.acc.lsb,
        "Accelerometer quantisation step (0 = off)",
        |m| m.params.acc.lsb,
        |m, v| m.params.acc.lsb = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        22,
        "mag.lsb",
        "1",
        PARAMS.mag.lsb,
        "Magnetometer quantisation step (0 = off)",
        |m| m.params.mag.lsb,
        |m, v| m.params.mag.lsb = v,
    )
    .range(0.0, MAX_ERROR),
    V::parameter(
        23,
        "mag_declination",
        "rad",
        PARAMS.mag_declination,
        "Magnetic field direction turned from north toward east about +z (W)",
        |m| m.params.mag_declination,
        |m, v| m.params.mag_declination = v,
    )
    .range(-std::f64::consts::PI, std::f64::consts::PI),
    V::parameter(
        24,
        "mag_inclination",
        "rad",
        PARAMS.mag_inclination,
        "Magnetic field dip below the horizontal, positive down (W)",
        |m| m.params.mag_inclination,
        |m, v| m.params.mag_inclination = v,
    )
    .range(-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2),
    V::parameter(25, "g", "m/s2", PARAMS.g, "Gravitational acceleration", |m| m.params.g, |m, v| m.params.g = v)
        .range(0.0, 1e3),
    // Inputs: the true motion of the sensor.
    V::held_input(
        100,
        "q0",
        "1",
        REST_Q[0],
        "Orientation W<-sensor, scalar part (normalised inside)",
        |m| m.q[0],
        |m, v| m.set_input(|m| m.q[0] = v),
    ),
    V::held_input(
        101,
        "q1",
        "1",
        REST_Q[1],
        "Orientation W<-sensor, x part",
        |m| m.q[1],
        |m, v| m.set_input(|m| m.q[1] = v),
    ),
    V::held_input(
        102,
        "q2",
        "1",
        REST_Q[2],
        "Orientation W<-sensor, y part",
        |m| m.q[2],
        |m, v| m.set_input(|m| m.q[2] = v),
    ),
    V::held_input(
        103,
        "q3",
        "1",
        REST_Q[3],
        "Orientation W<-sensor, z part",
        |m| m.q[3],
        |m, v| m.set_input(|m| m.q[3] = v),
    ),
    V::held_input(
        104,
        "w.x",
        "rad/s",
        components(&REST_W)[0],
        "Angular velocity of the sensor, sensor frame, x",
        |m| m.w.x,
        |m, v| m.set_input(|m| m.w.x = v),
    ),
    V::held_input(
        105,
        "w.y",
        "rad/s",
        components(&REST_W)[1],
        "Angular velocity of the sensor, sensor frame, y",
        |m| m.w.y,
        |m, v| m.set_input(|m| m.w.y = v),
    ),
    V::held_input(
        106,
        "w.z",
        "rad/s",
        components(&REST_W)[2],
        "Angular velocity of the sensor, sensor frame, z",
        |m| m.w.z,
        |m, v| m.set_input(|m| m.w.z = v),
    ),
    V::held_input(
        107,
        "a.x",
        "m/s2",
        components(&REST_A)[0],
        "Linear acceleration of the sensor point, W, x (north)",
        |m| m.a.x,
        |m, v| m.set_input(|m| m.a.x = v),
    ),
    V::held_input(
        108,
        "a.y",
        "m/s2",
        components(&REST_A)[1],
        "Linear acceleration of the sensor point, W, y (east)",
        |m| m.a.y,
        |m, v| m.set_input(|m| m.a.y = v),
    ),
    V::held_input(
        109,
        "a.z",
        "m/s2",
        components(&REST_A)[2],
        "Linear acceleration of the sensor point, W, z (down)",
        |m| m.a.z,
        |m, v| m.set_input(|m| m.a.z = v),
    ),
    // Outputs, sensor frame.
    V::output(200, "gyro.x", "rad/s", "Gyroscope x: angular velocity + bias + noise, quantised", |m| {
        m.readings().gyro.x
    }),
    V::output(201, "gyro.y", "rad/s", "Gyroscope y", |m| m.readings().gyro.y),
    V::output(202, "gyro.z", "rad/s", "Gyroscope z", |m| m.readings().gyro.z),
    V::output(
        203,
        "acc.x",
        "m/s2",
        "Accelerometer x: specific force R^T(a + (0,0,-g)) + bias + noise, quantised",
        |m| m.readings().acc.x,
    ),
    V::output(204, "acc.y", "m/s2", "Accelerometer y", |m| m.readings().acc.y),
    V::output(205, "acc.z", "m/s2", "Accelerometer z (reads -g at rest, level)", |m| m.readings().acc.z),
    V::output(206, "mag.x", "1", "Magnetometer x: unit field vector R^T m_W + bias + noise, quantised", |m| {
        m.readings().mag.x
    }),
    V::output(207, "mag.y", "1", "Magnetometer y", |m| m.readings().mag.y),
    V::output(208, "mag.z", "1", "Magnetometer z", |m| m.readings().mag.z),
];

fmi2::export_fmu!(Imu);

#[cfg(test)]
mod tests;

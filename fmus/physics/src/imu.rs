//! The 9-axis inertial measurement unit (thesis §3.4.5: two Yost Labs 3-Space IMUs, one on the
//! deck and one on the load; §3.5.4: how the simulation emulates them).
//!
//! Frames and units: world frame W North-East-Down (x north, y east, z down, gravity along +z);
//! sensor frame S fixed to the IMU case (Fig. 3.17 axes, aligned with the body it is mounted on).
//! The orientation q is W←S (scalar first), so a sensor-frame vector v_S = Rᵀ v_W with R = R(q).
//!
//! True values, all in S (§3.5.4):
//! - gyroscope (rad/s): the angular velocity ω of S relative to W, given in S;
//! - accelerometer (m/s²): the specific force Rᵀ (a + (0, 0, −g)), a the linear acceleration of the
//!   sensor point in W. Gravity enters as a vector with a negative (upward) z component, "to match
//!   how gravity is sensed by the physical IMU" (§3.5.4), so a sensor at rest reads (0, 0, −g) when
//!   level;
//! - magnetometer (unit-vector components): Rᵀ m_W with m_W the unit field vector. The thesis takes
//!   a unit vector pointing north (§3.5.4); here it may be turned by a declination D (about +z, east
//!   positive) and dipped by an inclination I (positive pointing down), which reproduces the
//!   field discrepancy between the two IMUs of §7.2.1:
//!   m_W = (cos I cos D, cos I sin D, sin I).
//!
//! Measurement errors (§3.4.5 and §3.5.4: normally distributed noise with the standard deviations
//! of Figs. 3.18–3.19, values in SPEC §8.1; quantisation to the signal resolution, which §3.5.4
//! applies through data-type conversions), per axis i of sensor s:
//!
//!   y_i = quantize(true_i + bias_i + σ_i · z(seed, channel(s, i), k), lsb_s)
//!
//! with z a standard normal sample from [`crate::noise`] that depends only on the seed, the channel
//! (gyro x, y, z = 0, 1, 2; accelerometer 3, 4, 5; magnetometer 6, 7, 8) and the sample index k.
//! The random term is present only when `noise` is on; biases and quantisation are applied always
//! (both default to values that are harmless; set an LSB to 0 to switch quantisation off).

use crate::math::{Quat, Vec3, STANDARD_GRAVITY};
use crate::noise::{channels, quantize, NoiseStream};
use serde::{Deserialize, Serialize};

/// The three sensors of the IMU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sensor {
    Gyro,
    Acc,
    Mag,
}

impl Sensor {
    pub const ALL: [Sensor; 3] = [Sensor::Gyro, Sensor::Acc, Sensor::Mag];

    /// Noise channel of `axis` (0 = x, 1 = y, 2 = z) of this sensor: 9 in the IMU's block.
    pub fn channel(self, axis: usize) -> u64 {
        assert!(axis < 3, "axis {axis} is not 0, 1 or 2");
        let first = match self {
            Sensor::Gyro => 0,
            Sensor::Acc => 3,
            Sensor::Mag => 6,
        };
        channels::IMU + first + axis as u64
    }
}

/// Error model of one sensor (three axes): noise, bias and converter resolution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorErrors {
    /// Standard deviation of the white Gaussian noise per axis (the sensor's unit).
    pub sigma: Vec3,
    /// Constant bias per axis (the sensor's unit).
    pub bias: Vec3,
    /// Quantisation step, one least significant bit (the sensor's unit); 0 = no quantisation.
    pub lsb: f64,
}

impl SensorErrors {
    const fn isotropic(sigma: f64, lsb: f64) -> Self {
        SensorErrors { sigma: Vec3::new(sigma, sigma, sigma), bias: Vec3::new(0.0, 0.0, 0.0), lsb }
    }

    fn validate(&self, name: &str) -> Result<(), String> {
        if !self.sigma.iter().all(|s| s.is_finite() && *s >= 0.0) {
            return Err(format!(
                "{name} noise standard deviations must be finite and ≥ 0, got {:?}",
                self.sigma.as_slice()
            ));
        }
        if !self.bias.iter().all(|b| b.is_finite()) {
            return Err(format!("{name} biases must be finite, got {:?}", self.bias.as_slice()));
        }
        if !(self.lsb.is_finite() && self.lsb >= 0.0) {
            return Err(format!("{name} quantisation step must be finite and ≥ 0, got {}", self.lsb));
        }
        Ok(())
    }
}

/// Configuration of one IMU (config, not state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImuParams {
    /// Gyroscope errors (rad/s).
    pub gyro: SensorErrors,
    /// Accelerometer errors (m/s²).
    pub acc: SensorErrors,
    /// Magnetometer errors (components of the unit field vector, dimensionless).
    pub mag: SensorErrors,
    /// Magnetic declination D (rad): field direction turned from north toward east about +z.
    pub mag_declination: f64,
    /// Magnetic inclination I (rad): dip of the field below the horizontal, positive down.
    pub mag_inclination: f64,
    /// Gravitational acceleration g (m/s²).
    pub g: f64,
    /// Seed of the noise; instances with equal seeds produce identical noise.
    pub seed: u64,
    /// Whether the random noise term is applied (biases and quantisation apply regardless).
    pub noise: bool,
}

default_is_const!(ImuParams);

impl ImuParams {
    /// SPEC §8.1 (standard deviations at 100 Hz from the Yost 3-Space data sheet; the thesis'
    /// Figs. 3.18–3.19 give only histograms): gyro σ = 0.0035 rad/s, LSB 0.00007 rad/s;
    /// accelerometer σ = 0.01 m/s², LSB 0.0006 m/s²; magnetometer σ = 0.01, LSB 0.0001; biases 0;
    /// field pointing north (D = I = 0); g = 9.80665 m/s²; seed 1; noise on.
    pub const DEFAULT: ImuParams = ImuParams {
        gyro: SensorErrors::isotropic(0.0035, 0.00007),
        acc: SensorErrors::isotropic(0.01, 0.0006),
        mag: SensorErrors::isotropic(0.01, 0.0001),
        mag_declination: 0.0,
        mag_inclination: 0.0,
        g: STANDARD_GRAVITY,
        seed: 1,
        noise: true,
    };

    pub fn validate(&self) -> Result<(), String> {
        self.gyro.validate("gyroscope")?;
        self.acc.validate("accelerometer")?;
        self.mag.validate("magnetometer")?;
        if !(self.g.is_finite() && self.g >= 0.0) {
            return Err(format!("g must be finite and ≥ 0 m/s², got {}", self.g));
        }
        if !self.mag_declination.is_finite() {
            return Err(format!("mag_declination must be finite, got {}", self.mag_declination));
        }
        if !(self.mag_inclination.abs() <= std::f64::consts::FRAC_PI_2) {
            return Err(format!("mag_inclination must be within ±π/2 rad, got {}", self.mag_inclination));
        }
        Ok(())
    }

    /// The error model of `sensor`.
    pub fn errors(&self, sensor: Sensor) -> &SensorErrors {
        match sensor {
            Sensor::Gyro => &self.gyro,
            Sensor::Acc => &self.acc,
            Sensor::Mag => &self.mag,
        }
    }

    /// The unit magnetic field vector in W: north, turned by the declination about +z and dipped
    /// by the inclination, m_W = (cos I cos D, cos I sin D, sin I).
    pub fn magnetic_field(&self) -> Vec3 {
        let (sd, cd) = self.mag_declination.sin_cos();
        let (si, ci) = self.mag_inclination.sin_cos();
        Vec3::new(ci * cd, ci * sd, si)
    }
}

/// The true motion of the sensor: what the IMU measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImuMotion {
    /// Orientation W←S (scalar first).
    pub orientation: Quat,
    /// Angular velocity of S relative to W, in S (rad/s).
    pub angular_velocity: Vec3,
    /// Linear acceleration of the sensor point relative to W, in W (m/s²).
    pub acceleration: Vec3,
}

impl Default for ImuMotion {
    /// At rest, level, heading north.
    fn default() -> Self {
        ImuMotion { orientation: Quat::identity(), angular_velocity: Vec3::zeros(), acceleration: Vec3::zeros() }
    }
}

/// Smallest norm a quaternion input may have before it is normalised; anything shorter has no
/// usable direction (typically an unconnected or zeroed input).
pub const MIN_QUATERNION_NORM: f64 = 1e-6;

/// The unit quaternion W←S from scalar-first components (q0, q1, q2, q3), normalised. A quaternion
/// that is not finite or shorter than [`MIN_QUATERNION_NORM`] is an error.
pub fn orientation_from_components(q: [f64; 4]) -> Result<Quat, String> {
    let raw = nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = raw.norm();
    if !(norm.is_finite() && norm >= MIN_QUATERNION_NORM) {
        return Err(format!(
            "orientation quaternion (q0, q1, q2, q3) = ({}, {}, {}, {}) has norm {norm}: it must be finite \
                and ≥ {MIN_QUATERNION_NORM:e}",
            q[0], q[1], q[2], q[3]
        ));
    }
    Ok(Quat::new_unchecked(raw / norm))
}

/// Readings of the three sensors, each in S: gyroscope (rad/s), accelerometer (m/s²) and
/// magnetometer (unit-vector components).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ImuReadings {
    pub gyro: Vec3,
    pub acc: Vec3,
    pub mag: Vec3,
}

impl ImuReadings {
    /// An error-free IMU at rest, level and facing north (field along +x, no inclination): no
    /// rotation, the specific force (0, 0, −g) (§5.1.1), the unit field (1, 0, 0).
    pub const LEVEL: ImuReadings = ImuReadings {
        gyro: Vec3::new(0.0, 0.0, 0.0),
        acc: Vec3::new(0.0, 0.0, -STANDARD_GRAVITY),
        mag: Vec3::new(1.0, 0.0, 0.0),
    };

    pub fn sensor(&self, sensor: Sensor) -> &Vec3 {
        match sensor {
            Sensor::Gyro => &self.gyro,
            Sensor::Acc => &self.acc,
            Sensor::Mag => &self.mag,
        }
    }
}

/// Specific force in S (m/s²): Rᵀ (a + (0, 0, −g)) (§3.5.4). At rest and level: (0, 0, −g).
pub fn specific_force(g: f64, motion: &ImuMotion) -> Vec3 {
    motion.orientation.inverse_transform_vector(&(motion.acceleration + Vec3::new(0.0, 0.0, -g)))
}

/// What an ideal `sensor` reads (no bias, noise or quantisation), in S.
pub fn true_value(p: &ImuParams, motion: &ImuMotion, sensor: Sensor) -> Vec3 {
    match sensor {
        Sensor::Gyro => motion.angular_velocity,
        Sensor::Acc => specific_force(p.g, motion),
        Sensor::Mag => motion.orientation.inverse_transform_vector(&p.magnetic_field()),
    }
}

/// One axis (0 = x, 1 = y, 2 = z) of a sensor with errors `e`: the true value `truth` plus bias
/// and the random term `noise`, then quantised.
fn measure(e: &SensorErrors, axis: usize, truth: f64, noise: f64) -> f64 {
    quantize(truth + e.bias[axis] + noise, e.lsb)
}

/// The nine IMU readings for the true motion `motion` and the random terms `noise` of the
/// sample (from [`ImuNoise::draw`]).
pub fn readings_with(p: &ImuParams, motion: &ImuMotion, noise: &ImuReadings) -> ImuReadings {
    let reading = |sensor| {
        let (truth, e, noise) = (true_value(p, motion, sensor), p.errors(sensor), noise.sensor(sensor));
        Vec3::from_fn(|axis, _| measure(e, axis, truth[axis], noise[axis]))
    };
    ImuReadings { gyro: reading(Sensor::Gyro), acc: reading(Sensor::Acc), mag: reading(Sensor::Mag) }
}

/// The nine IMU readings at sample index `k` for the true motion `motion`. A pure function: the
/// same arguments always give bit-identical readings.
pub fn readings(p: &ImuParams, motion: &ImuMotion, k: u64) -> ImuReadings {
    readings_with(p, motion, &ImuNoise::default().draw(p, k))
}

/// The noise memos of the nine channels of one IMU ([`NoiseStream`]): a cache, not state.
#[derive(Debug, Clone, Default)]
pub struct ImuNoise {
    streams: [NoiseStream; 9],
}

impl ImuNoise {
    /// The random terms σ_i · z(seed, channel(s, i), k) of the nine axes at sample index `k`, laid
    /// out like the readings (each in its sensor's unit); all zero when noise is off.
    pub fn draw(&mut self, p: &ImuParams, k: u64) -> ImuReadings {
        let mut term = |sensor: Sensor, axis: usize| {
            let channel = sensor.channel(axis);
            let stream = &mut self.streams[(channel - channels::IMU) as usize];
            if p.noise {
                stream.gaussian(p.seed, channel, k, p.errors(sensor).sigma[axis])
            } else {
                0.0
            }
        };
        let mut terms = |sensor| Vec3::new(term(sensor, 0), term(sensor, 1), term(sensor, 2));
        ImuReadings { gyro: terms(Sensor::Gyro), acc: terms(Sensor::Acc), mag: terms(Sensor::Mag) }
    }
}

#[cfg(test)]
mod tests;

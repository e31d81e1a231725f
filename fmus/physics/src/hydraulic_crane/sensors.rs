//! The sensors of the full-scale crane, as an industrial crane control system reads them.
//!
//! Each reading is quantize(true + σ·z(seed, channel, k), LSB), z the standard normal sample of
//! [`crate::noise`] for macro step k (noise only when on), as for the test-scale crane's sensors.
//! The values are representative of the sensors fitted to offshore knuckle-boom cranes, not data
//! of one product:
//!
//! | sensor | quantity | LSB | σ | why |
//! | --- | --- | --- | --- | --- |
//! | joint encoders (slew, boom, jib) | angle (rad) | 2π/2¹⁷ | 5e-5 rad | 17-bit single-turn absolute encoders on the joint axes |
//! | stroke transducers (boom, jib) | stroke (m) | 10 µm | 20 µm | magnetostrictive position sensors inside the cylinders |
//! | pressure transducers (8 chambers) | pressure (Pa) | 40 MPa/4096 | 20 kPa | 0–40 MPa transducers on a 12-bit input, noise 0.05 % of full scale |
//! | drum encoder | drum angle (rad) | 2π/4096 | 0.06° | the thesis' winch encoder (12 bits per turn, SPEC §8.1), multi-turn |
//!
//! Channels: the block from [`channels::HYDRAULIC_CRANE`], in the order of [`Readings`]' fields
//! (joints, strokes, pressures by drive then chamber, drum).

use super::plant::{PlantState, BOOM, JIB};
use crate::noise::{channels, quantize, NoiseDraw, NoiseStream};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Number of noisy channels the crane reads.
pub const CHANNELS: usize = 14;

/// One sensor: resolution and noise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Transducer {
    /// One least significant bit (the quantity's unit).
    pub lsb: f64,
    /// Standard deviation of the noise before quantisation.
    pub sigma: f64,
}

impl Transducer {
    /// The reading of `value` on noise channel `channel` (an offset in the crane's block).
    pub fn read(&self, value: f64, channel: usize, draw: NoiseDraw, stream: &mut NoiseStream) -> f64 {
        let channel = channels::HYDRAULIC_CRANE + channel as u64;
        quantize(value + draw.sample(stream, channel, self.sigma), self.lsb)
    }
}

/// The crane's sensor set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorSet {
    pub joint: Transducer,
    pub stroke: Transducer,
    pub pressure: Transducer,
    pub drum: Transducer,
}

impl SensorSet {
    /// The values of the module documentation's table.
    pub const DEFAULT: SensorSet = SensorSet {
        joint: Transducer { lsb: TAU / 131_072.0, sigma: 5e-5 },
        stroke: Transducer { lsb: 1e-5, sigma: 2e-5 },
        pressure: Transducer { lsb: 40e6 / 4096.0, sigma: 20e3 },
        drum: Transducer { lsb: TAU / 4096.0, sigma: 0.06 * TAU / 360.0 },
    };
}

default_is_const!(SensorSet);

/// What the sensors read at one communication point.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Readings {
    /// Joint encoders θ1, θ2, θ3 (rad).
    pub joints: [f64; 3],
    /// Stroke transducers of the boom and jib cylinders (m).
    pub strokes: [f64; 2],
    /// Pressure transducers (p_A, p_B) of the slew, boom, jib and winch drives (Pa).
    pub pressures: [[f64; 2]; 4],
    /// Drum encoder (rad, multi-turn, from the start).
    pub drum: f64,
}

impl SensorSet {
    /// Every reading for the plant state `s` with the cylinders at `strokes` (m), one noise memo
    /// per channel in `streams`.
    pub fn read(
        &self,
        s: &PlantState,
        strokes: [f64; 2],
        draw: NoiseDraw,
        streams: &mut [NoiseStream; CHANNELS],
    ) -> Readings {
        let mut next = 0;
        let mut read = |sensor: &Transducer, value: f64| {
            let channel = next;
            next += 1;
            sensor.read(value, channel, draw, &mut streams[channel])
        };
        let joints = s.q.map(|q| read(&self.joint, q));
        let strokes = [read(&self.stroke, strokes[BOOM - 1]), read(&self.stroke, strokes[JIB - 1])];
        let pressures = s.pressures.map(|p| p.map(|p| read(&self.pressure, p)));
        let drum = read(&self.drum, s.drum);
        Readings { joints, strokes, pressures, drum }
    }
}

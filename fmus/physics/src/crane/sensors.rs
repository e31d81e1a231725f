//! The crane's feedback sensors as the myRIO saw them (thesis §3.4.4, §3.5.4; SPEC §8.1 values).
//!
//! - Potentiometers on the base, boom and jib actuators: 0–5 V over the 0–50 mm stroke, read by a
//!   12-bit converter (1 LSB = 5/4096 V ≈ 0.012 mm) with Gaussian noise σ = 1.2 mV. The reading is
//!   clipped to the converter's codes 0–4095.
//! - Winch encoder: 12-bit absolute within a turn (1 LSB = 360/4096° ≈ 0.088°) extended over many
//!   turns by a software counter, so the reading is the quantised multi-turn angle (deg), with
//!   Gaussian noise σ = 0.06°.
//!
//! Each reading is quantize(true + σ · z(seed, channel, k), LSB) with z the standard normal
//! sample of [`crate::noise`] for the macro step k; the crane's channels (the block from
//! [`channels::CRANE`]) are the base, boom and jib potentiometers, then the encoder. The noise term is present only
//! when noise is on.
//! A reading draws its sample through the channel's [`NoiseStream`] (a memo that only saves
//! time: a fresh one gives the same sample).

pub use crate::noise::NoiseDraw;
use crate::noise::{channels, quantize, NoiseStream};
use serde::{Deserialize, Serialize};

/// Noise channel of the base, boom and jib potentiometers.
pub const POT_CHANNELS: [u64; 3] = [channels::CRANE, channels::CRANE + 1, channels::CRANE + 2];
/// Noise channel of the winch encoder.
pub const ENCODER_CHANNEL: u64 = channels::CRANE + 3;

/// An actuator potentiometer read by a converter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Potentiometer {
    /// Output per extension (V/m): 5 V over 50 mm.
    pub volts_per_metre: f64,
    /// Converter full scale (V) and resolution (V per code).
    pub full_scale: f64,
    pub lsb: f64,
    /// Standard deviation of the noise (V).
    pub sigma: f64,
}

default_is_const!(Potentiometer);

impl Potentiometer {
    /// 0–5 V over 0–50 mm, 12 bits, σ = 1.2 mV (SPEC §8.1).
    pub const DEFAULT: Potentiometer =
        Potentiometer { volts_per_metre: 100.0, full_scale: 5.0, lsb: 5.0 / 4096.0, sigma: 0.0012 };

    /// The true output (V) for the extension `d` (m): no noise, no converter.
    pub const fn volts(&self, d: f64) -> f64 {
        d * self.volts_per_metre
    }

    /// The reading (V) for the extension `d` (m) of the actuator on noise `channel`, drawn through
    /// that channel's `stream`.
    pub fn read(&self, d: f64, channel: u64, noise: NoiseDraw, stream: &mut NoiseStream) -> f64 {
        let volts = self.volts(d) + noise.sample(stream, channel, self.sigma);
        quantize(volts, self.lsb).clamp(0.0, self.full_scale - self.lsb)
    }

    /// The extension (m) a reading (V) stands for: what the controller computes.
    pub const fn extension(&self, volts: f64) -> f64 {
        volts / self.volts_per_metre
    }
}

/// The winch's absolute encoder with a software turn counter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Encoder {
    /// Resolution (deg per code).
    pub lsb: f64,
    /// Standard deviation of the noise (deg).
    pub sigma: f64,
}

default_is_const!(Encoder);

impl Encoder {
    /// 12 bits per turn, σ = 0.06° (SPEC §8.1).
    pub const DEFAULT: Encoder = Encoder { lsb: 360.0 / 4096.0, sigma: 0.06 };

    /// The multi-turn reading (deg) for the winch angle `angle` (deg), drawn through the encoder
    /// channel's `stream`.
    pub fn read(&self, angle: f64, noise: NoiseDraw, stream: &mut NoiseStream) -> f64 {
        quantize(angle + noise.sample(stream, ENCODER_CHANNEL, self.sigma), self.lsb)
    }
}

#[cfg(test)]
mod tests;

//! Deterministic, counter-based sensor noise shared by every sensor model.
//!
//! A noise sample is a pure function of three numbers: the instance's `seed`, the signal's
//! `channel` and the macro-step index `k`. Nothing is drawn from a running generator, so a
//! sample never depends on how often an importer reads the outputs, in which order the channels are
//! queried, or whether the FMU state was saved and restored in between; two runs with the same
//! inputs and seed are bit-identical (SPEC §3, determinism).
//!
//! Construction: a ChaCha8 stream cipher keyed by the seed (`SeedableRng::seed_from_u64`, which
//! the `rand_core` crate documents as portable), its 64-bit stream id set to the channel and its
//! word position to `k · WORDS_PER_SAMPLE`. The two 64-bit words found there become one standard
//! normal variate by the Box–Muller transform. Each (channel, k) owns its own words, so samples of
//! different channels and steps never share random bits.
//!
//! Every model draws from its own block of channels ([`channels`]), so instances of different
//! models never share noise even with equal seeds; two instances of one model (the two IMUs)
//! must be given different seeds.
//!
//! Cost: keying ChaCha and filling its block buffer costs far more than reading four words from
//! it, and a model reads one channel at k = 0, 1, 2, …, so a [`NoiseStream`] keeps the keyed
//! generator of one channel where its last sample left it: the next step's words follow
//! directly, and the buffer is refilled once every 16 samples. The memo only changes the cost:
//! its samples are [`standard_normal`]'s, bit for bit, for any order of (seed, channel, k).

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// The first noise channel of each model; a model numbers its signals upward from there.
pub mod channels {
    /// IMU: 9 channels (gyro, accelerometer, magnetometer × 3 axes).
    pub const IMU: u64 = 0;
    /// Crane: potentiometers base, boom, jib, then the winch encoder.
    pub const CRANE: u64 = 16;
    /// Full-scale hydraulic crane: joint encoders, stroke and pressure transducers, drum encoder
    /// (`hydraulic_crane::sensors`).
    pub const HYDRAULIC_CRANE: u64 = 32;
}

/// 32-bit words of the ChaCha stream consumed by one sample (two u64 for Box–Muller).
pub const WORDS_PER_SAMPLE: u128 = 4;

/// The ChaCha8 keystream of (`seed`, `channel`), positioned at its start.
fn keystream(seed: u64, channel: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(channel);
    rng
}

/// The standard normal sample k of the keystream `rng`. The generator is moved to the sample's
/// words only when it is not already there (moving refills its block buffer) and is left just
/// past them, where sample k + 1 begins.
///
/// Box–Muller on the two uniform variates u1 in (0, 1] and u2 in [0, 1), each with 53 random
/// bits: z = √(−2 ln u1) · cos(2π u2). With u1 ∈ (0, 1] the logarithm is finite, so
/// |z| ≤ √(106 ln 2) ≈ 8.6.
fn sample_at(rng: &mut ChaCha8Rng, k: u64) -> f64 {
    let word = u128::from(k) * WORDS_PER_SAMPLE;
    if rng.get_word_pos() != word {
        rng.set_word_pos(word);
    }
    let u1 = common::unit::open_closed(rng.next_u64());
    let u2 = common::unit::closed_open(rng.next_u64());
    (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
}

/// `sigma` times the standard normal sample `z()`, which is not drawn when `sigma` is 0.
fn scaled(sigma: f64, z: impl FnOnce() -> f64) -> f64 {
    if sigma == 0.0 {
        0.0
    } else {
        sigma * z()
    }
}

/// A standard normal sample N(0, 1) for (`seed`, `channel`, step `k`).
pub fn standard_normal(seed: u64, channel: u64, k: u64) -> f64 {
    sample_at(&mut keystream(seed, channel), k)
}

/// A zero-mean Gaussian sample with standard deviation `sigma` (same unit as `sigma`).
pub fn gaussian(seed: u64, channel: u64, k: u64, sigma: f64) -> f64 {
    scaled(sigma, || standard_normal(seed, channel, k))
}

/// A memo of one channel's keystream: draws the samples of [`standard_normal`] and [`gaussian`]
/// without keying a generator per sample (see the module documentation).
///
/// It is a cache, not state: a model keeps one per channel outside its serialized state (a
/// fresh memo gives the same samples), and it keys itself again whenever asked for another seed
/// or channel.
#[derive(Debug, Clone, Default)]
pub struct NoiseStream {
    keyed: Option<Keyed>,
}

/// A keystream, the (seed, channel) it was keyed with and the last sample drawn from it.
#[derive(Debug, Clone)]
struct Keyed {
    seed: u64,
    channel: u64,
    rng: ChaCha8Rng,
    /// (k, z): a model in initialization mode draws sample 0 again for every read, and moving
    /// the generator back would refill its buffer each time.
    last: Option<(u64, f64)>,
}

impl NoiseStream {
    /// [`standard_normal`]`(seed, channel, k)`.
    pub fn standard_normal(&mut self, seed: u64, channel: u64, k: u64) -> f64 {
        let keyed = match &mut self.keyed {
            Some(keyed) if keyed.seed == seed && keyed.channel == channel => keyed,
            stale => stale.insert(Keyed { seed, channel, rng: keystream(seed, channel), last: None }),
        };
        match keyed.last {
            Some((last, z)) if last == k => z,
            _ => {
                let z = sample_at(&mut keyed.rng, k);
                keyed.last = Some((k, z));
                z
            }
        }
    }

    /// [`gaussian`]`(seed, channel, k, sigma)`.
    pub fn gaussian(&mut self, seed: u64, channel: u64, k: u64, sigma: f64) -> f64 {
        scaled(sigma, || self.standard_normal(seed, channel, k))
    }
}

/// Where a noise sample comes from: the instance's seed and the macro-step index k, or no noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseDraw {
    Off,
    On { seed: u64, k: u64 },
}

impl NoiseDraw {
    /// The Gaussian sample of `channel` (standard deviation `sigma`) for this draw, through the
    /// channel's `stream`; 0 without noise.
    pub fn sample(self, stream: &mut NoiseStream, channel: u64, sigma: f64) -> f64 {
        match self {
            NoiseDraw::Off => 0.0,
            NoiseDraw::On { seed, k } => stream.gaussian(seed, channel, k, sigma),
        }
    }
}

/// `value` rounded to the nearest multiple of `lsb` (one least significant bit of the converter;
/// halves round away from zero). `lsb = 0` (or any value that is not > 0) leaves `value` unchanged.
pub fn quantize(value: f64, lsb: f64) -> f64 {
    if lsb > 0.0 {
        (value / lsb).round() * lsb
    } else {
        value
    }
}

/// Sample mean and standard deviation (n − 1 denominator) of `samples`: how the noise tests
/// check a generated sequence against its parameters.
pub fn mean_std(samples: &[f64]) -> (f64, f64) {
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<f64>() / n;
    let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: u64 = 100_000;

    #[test]
    fn a_sample_repeats_bit_for_bit() {
        for (seed, channel, k) in [(0, 0, 0), (1, 3, 17), (u64::MAX, u64::MAX, u64::MAX), (42, 8, 1 << 40)] {
            let a = standard_normal(seed, channel, k);
            let b = standard_normal(seed, channel, k);
            assert!(a.is_finite());
            assert_eq!(a.to_bits(), b.to_bits(), "seed {seed}, channel {channel}, k {k}");
        }
    }

    /// Pins the generator: a change of the algorithm or of the ChaCha crate's stream layout would
    /// silently change every recorded run, so it must show up here. (The tolerance only allows for
    /// a last-bit difference of `ln`/`cos` between C libraries.)
    #[test]
    fn known_samples_are_reproduced() {
        for (seed, channel, k, expected) in [
            (1, 0, 0, 1.180_694_150_218_984_7),
            (1, 8, 99, 0.807_882_109_498_636),
            (12_345, 3, 1_000_000, -0.421_050_779_107_570_77),
        ] {
            let z = standard_normal(seed, channel, k);
            assert!((z - expected).abs() < 1e-14, "({seed}, {channel}, {k}) gave {z:?}, expected {expected:?}");
        }
    }

    #[test]
    fn a_sample_does_not_depend_on_query_order() {
        let keys: Vec<(u64, u64)> = (0..9).flat_map(|c| (0..50).map(move |k| (c, k))).collect();
        let forward: Vec<f64> = keys.iter().map(|&(c, k)| standard_normal(7, c, k)).collect();
        // Backwards, with repeated queries interleaved.
        let mut backward = vec![0.0; keys.len()];
        for (i, &(c, k)) in keys.iter().enumerate().rev() {
            let _ = standard_normal(7, (c + 1) % 9, k + 3);
            backward[i] = standard_normal(7, c, k);
            let _ = standard_normal(7, c, k);
        }
        for (a, b) in forward.iter().zip(&backward) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }

    /// Draws `queries` through `stream` and checks each against the direct function.
    fn assert_stream_matches(stream: &mut NoiseStream, queries: &[(u64, u64, u64)]) {
        for &(seed, channel, k) in queries {
            let memo = stream.standard_normal(seed, channel, k);
            let direct = standard_normal(seed, channel, k);
            assert_eq!(memo.to_bits(), direct.to_bits(), "seed {seed}, channel {channel}, k {k}");
        }
    }

    /// The memo must position its generator for every query: a stale position (left after the
    /// previous sample, or after another channel's) returns a neighbouring sample, which these
    /// patterns would catch at once.
    #[test]
    fn a_stream_gives_the_direct_samples_in_any_order() {
        let forward: Vec<_> = (0..40).map(|k| (5, 3, k)).collect(); // crosses two buffer refills
        let backward: Vec<_> = (0..40).rev().map(|k| (5, 3, k)).collect();
        let repeated: Vec<_> = [7, 7, 8, 8, 8, 7, 15, 16, 15, 16].map(|k| (5, 3, k)).to_vec();
        let interleaved: Vec<_> = (0..30).flat_map(|k| [(5, 3, k), (5, 4, k), (6, 3, k)]).collect();
        let far: Vec<_> = [u64::MAX, 0, 1 << 40, (1 << 40) + 1, u64::MAX - 1].map(|k| (5, 3, k)).to_vec();
        for pattern in [&forward, &backward, &repeated, &interleaved, &far] {
            assert_stream_matches(&mut NoiseStream::default(), pattern);
        }
        // All patterns one after the other through one memo.
        let mut stream = NoiseStream::default();
        for pattern in [&forward, &backward, &repeated, &interleaved, &far] {
            assert_stream_matches(&mut stream, pattern);
        }
    }

    #[test]
    fn a_stream_gives_the_direct_samples_at_random() {
        let mut choice = ChaCha8Rng::seed_from_u64(99);
        let queries: Vec<_> = (0..2000)
            .map(|_| {
                let r = choice.next_u64();
                (r % 2, (r >> 8) % 3, (r >> 16) % 50)
            })
            .collect();
        assert_stream_matches(&mut NoiseStream::default(), &queries);
    }

    /// A clone is a snapshot (an FMU state): both the clone and the original continue as a
    /// fresh memo would, whichever runs first.
    #[test]
    fn a_cloned_stream_continues_like_the_original() {
        let mut stream = NoiseStream::default();
        assert_stream_matches(&mut stream, &(0..21).map(|k| (1, 0, k)).collect::<Vec<_>>());
        let mut snapshot = stream.clone();
        let after: Vec<_> = (21..60).map(|k| (1, 0, k)).collect();
        assert_stream_matches(&mut stream, &after);
        assert_stream_matches(&mut snapshot, &(10..60).map(|k| (1, 0, k)).collect::<Vec<_>>());
        assert_stream_matches(&mut stream.clone(), &after);
    }

    #[test]
    fn a_stream_scales_like_gaussian() {
        let mut stream = NoiseStream::default();
        assert_eq!(stream.gaussian(1, 2, 3, 0.0), 0.0);
        assert_eq!(stream.gaussian(1, 2, 3, 0.5).to_bits(), gaussian(1, 2, 3, 0.5).to_bits());
    }

    #[test]
    fn seeds_channels_and_steps_give_different_samples() {
        let base = standard_normal(1, 0, 0);
        assert_ne!(base, standard_normal(2, 0, 0));
        assert_ne!(base, standard_normal(1, 1, 0));
        assert_ne!(base, standard_normal(1, 0, 1));
    }

    #[test]
    fn samples_are_standard_normal() {
        let samples: Vec<f64> = (0..N).map(|k| standard_normal(2024, 5, k)).collect();
        let (mean, std) = mean_std(&samples);
        let n = N as f64;
        let within_one = samples.iter().filter(|x| x.abs() < 1.0).count() as f64 / n;
        let within_two = samples.iter().filter(|x| x.abs() < 2.0).count() as f64 / n;
        println!(
            "standard normal, {N} samples: mean {mean:+.5} (limit ±{:.5}), std {std:.5}, \
             P(|z|<1) {within_one:.4} (0.6827), P(|z|<2) {within_two:.4} (0.9545)",
            4.0 / n.sqrt()
        );
        assert!(mean.abs() < 4.0 / n.sqrt(), "mean {mean}");
        assert!((std - 1.0).abs() < 0.02, "std {std}");
        // Binomial standard errors ≈ 0.0015 and 0.0007; allow 4 of them.
        assert!((within_one - 0.682_689).abs() < 0.006, "P(|z|<1) = {within_one}");
        assert!((within_two - 0.954_500).abs() < 0.003, "P(|z|<2) = {within_two}");
    }

    #[test]
    fn neighbouring_steps_and_channels_are_uncorrelated() {
        let n = N as f64;
        let a: Vec<f64> = (0..N).map(|k| standard_normal(3, 0, k)).collect();
        let b: Vec<f64> = (0..N).map(|k| standard_normal(3, 1, k)).collect();
        let lag1 = a.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / (n - 1.0);
        let cross = a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>() / n;
        println!("correlation: lag-1 {lag1:+.5}, channel 0 × 1 {cross:+.5} (limit ±{:.5})", 4.0 / n.sqrt());
        assert!(lag1.abs() < 4.0 / n.sqrt(), "lag-1 correlation {lag1}");
        assert!(cross.abs() < 4.0 / n.sqrt(), "cross-channel correlation {cross}");
    }

    #[test]
    fn gaussian_scales_and_zero_sigma_is_silent() {
        assert_eq!(gaussian(1, 2, 3, 0.0), 0.0);
        let z = standard_normal(1, 2, 3);
        assert_eq!(gaussian(1, 2, 3, 0.5), 0.5 * z);
    }

    #[test]
    fn quantize_rounds_to_the_nearest_multiple() {
        assert_eq!(quantize(1.234_567, 0.0), 1.234_567);
        assert_eq!(quantize(0.26, 0.5), 0.5);
        assert_eq!(quantize(0.24, 0.5), 0.0);
        assert_eq!(quantize(-0.76, 0.5), -1.0);
        assert_eq!(quantize(0.75, 0.5), 1.0); // a half rounds away from zero
        let lsb = 0.0006;
        for x in [-9.80665, -0.123_456, 0.0, 3e-4, 1.0] {
            let q = quantize(x, lsb);
            assert!((q - x).abs() <= 0.5 * lsb + 1e-15, "{x} → {q}");
            assert!(((q / lsb) - (q / lsb).round()).abs() < 1e-9, "{q} is not a multiple of {lsb}");
        }
    }
}

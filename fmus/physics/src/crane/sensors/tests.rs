use super::*;
use crate::noise::{mean_std, NoiseStream};

#[test]
fn potentiometer_scale_and_quantisation() {
    let pot = Potentiometer::default();
    let lsb = 5.0 / 4096.0;
    for i in 0..=500 {
        let d = i as f64 * 1e-4; // 0–50 mm in 0.1 mm steps
        let v = pot.read(d, 0, NoiseDraw::Off, &mut NoiseStream::default());
        assert!(((v / lsb) - (v / lsb).round()).abs() < 1e-9, "{v} is not a whole number of codes");
        let truth = d * 100.0;
        // Within half a code, except the clipped top code.
        assert!((v - truth).abs() <= 0.5 * lsb + 1e-12 || (truth > 5.0 - lsb && v == 5.0 - lsb), "{d} m → {v} V");
    }
    assert_eq!(pot.read(0.0, 0, NoiseDraw::Off, &mut NoiseStream::default()), 0.0);
    assert_eq!(pot.read(0.05, 0, NoiseDraw::Off, &mut NoiseStream::default()), 4095.0 * lsb);
    assert_eq!(pot.read(0.0257, 0, NoiseDraw::Off, &mut NoiseStream::default()), (2.57f64 / lsb).round() * lsb);
    assert!((pot.extension(2.5) - 0.025).abs() < 1e-15);
}

#[test]
fn potentiometer_noise_statistics() {
    let pot = Potentiometer::default();
    let n = 50_000;
    let truth = 0.0257;
    let mut stream = NoiseStream::default();
    let errors: Vec<f64> =
        (0..n).map(|k| pot.read(truth, 1, NoiseDraw::On { seed: 9, k }, &mut stream) - truth * 100.0).collect();
    let (mean, std) = mean_std(&errors);
    // Noise plus quantisation: √(σ² + LSB²/12).
    let expected = (pot.sigma.powi(2) + pot.lsb.powi(2) / 12.0).sqrt();
    println!(
        "potentiometer at 25.7 mm, {n} samples: mean error {:.3} mV, std {:.4} mV (expected √(σ² + \
        LSB²/12) = {:.4} mV)",
        mean * 1e3,
        std * 1e3,
        expected * 1e3
    );
    assert!(mean.abs() < 0.05e-3);
    assert!((std / expected - 1.0).abs() < 0.03);
}

#[test]
fn encoder_is_multi_turn_with_noise() {
    let enc = Encoder::default();
    let lsb = 360.0 / 4096.0;
    for angle in [-725.3, -0.04, 0.0, 359.99, 991.234, 5000.0] {
        let r = enc.read(angle, NoiseDraw::Off, &mut NoiseStream::default());
        assert!((r - angle).abs() <= 0.5 * lsb + 1e-12, "{angle} → {r}");
        assert!(((r / lsb) - (r / lsb).round()).abs() < 1e-9);
    }
    let n = 50_000;
    let truth = 991.234;
    let mut stream = NoiseStream::default();
    let errors: Vec<f64> = (0..n).map(|k| enc.read(truth, NoiseDraw::On { seed: 9, k }, &mut stream) - truth).collect();
    let (mean, std) = mean_std(&errors);
    let expected = (enc.sigma.powi(2) + lsb * lsb / 12.0).sqrt();
    println!("encoder at 991.234°, {n} samples: mean error {mean:.4}°, std {std:.4}° (expected {expected:.4}°)");
    assert!(mean.abs() < 0.003);
    assert!((std / expected - 1.0).abs() < 0.03);
}

#[test]
fn readings_depend_only_on_seed_channel_and_step() {
    let pot = Potentiometer::default();
    let draw = |k| NoiseDraw::On { seed: 4, k };
    let read = |channel, k| pot.read(0.02, channel, draw(k), &mut NoiseStream::default());
    assert_eq!(read(0, 7), read(0, 7));
    let series: Vec<f64> = (0..20).map(|k| read(0, k)).collect();
    assert!(series.windows(2).any(|w| w[0] != w[1]));
    let other: Vec<f64> = (0..20).map(|k| read(2, k)).collect();
    assert_ne!(series, other);
    // One stream shared by both channels, read backwards: the same readings.
    let mut stream = NoiseStream::default();
    for k in (0..20).rev() {
        assert_eq!(pot.read(0.02, 0, draw(k), &mut stream), series[k as usize]);
        assert_eq!(pot.read(0.02, 2, draw(k), &mut stream), other[k as usize]);
    }
}

use super::*;
use crate::motion::{DOF_NAMES, HEAVE, PITCH, ROLL, SURGE, SWAY};
use crate::ship::spectrum::{components, SeaState, COMPONENTS};

const DEG: f64 = std::f64::consts::PI / 180.0;

fn beam_sea() -> HarmonicMotion {
    let waves = components(&SeaState { hs: 3.25, tp: 9.7 }, COMPONENTS, 11);
    HarmonicMotion::from_waves(&Hull::default(), &waves, 120.0 * DEG)
}

#[test]
fn velocities_and_accelerations_are_the_exact_derivatives() {
    let mut m = beam_sea();
    m.gains = [0.02, 0.03, 0.01, 1.0, 1.0, 0.5];
    m.offsets = [0.001, -0.002, 0.0, 0.01, 0.0, 0.0];
    let h = 1e-4;
    for t in [0.0, 13.7, 60.0, 119.9] {
        let (a, plus, minus) = (m.sample(t), m.sample(t + h), m.sample(t - h));
        for (j, name) in DOF_NAMES.iter().enumerate() {
            let (x, p, m) = (a.dof[j], plus.dof[j], minus.dof[j]);
            let vel = (p.pos - m.pos) / (2.0 * h);
            let acc = (p.vel - m.vel) / (2.0 * h);
            let scale = 1.0 + x.vel.abs() + x.acc.abs();
            assert!((x.vel - vel).abs() < 1e-8 * scale, "{name} at t = {t}: velocity {} vs {vel}", x.vel);
            assert!((x.acc - acc).abs() < 1e-8 * scale, "{name} at t = {t}: acceleration {} vs {acc}", x.acc);
        }
    }
}

#[test]
fn the_window_mean_is_exact() {
    let mut m = beam_sea();
    m.gains = [1.0, 2.0, 1.0, 1.0, 1.0, 1.0];
    m.offsets = [0.1, 0.0, -0.2, 0.0, 0.0, 0.0];
    let mean = m.window_mean(5.0, 125.0);
    // Simpson over 120 s at 5 ms.
    let n = 24_000;
    let h = 120.0 / n as f64;
    let mut sum = [0.0; 6];
    for k in 0..=n {
        let w = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let p = m.sample(5.0 + k as f64 * h).pose();
        for j in 0..6 {
            sum[j] += w * p[j];
        }
    }
    for j in 0..6 {
        let numeric = sum[j] * h / 3.0 / 120.0;
        assert!((mean[j] - numeric).abs() < 1e-9, "{}: {} vs {numeric}", DOF_NAMES[j], mean[j]);
    }
}

#[test]
fn significant_amplitudes_match_the_time_series() {
    // 2√m0 from the spectrum against 2 × the standard deviation of one hour of motion.
    let m = beam_sea();
    let (n, dt) = (14_400, 0.25);
    for j in [SURGE, SWAY, HEAVE, ROLL, PITCH] {
        let series: Vec<f64> = (0..n).map(|k| m.sample(k as f64 * dt).dof[j].pos).collect();
        let mean = series.iter().sum::<f64>() / n as f64;
        let std = (series.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        let spectral = m.significant_amplitude(j);
        println!("{:5}: 2√m0 = {spectral:.4}, 2σ(1 h) = {:.4}", DOF_NAMES[j], 2.0 * std);
        assert!((2.0 * std / spectral - 1.0).abs() < 0.05);
    }
}

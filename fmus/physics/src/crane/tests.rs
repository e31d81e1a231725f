use super::*;
use num_dual::{DualNum, HyperDual64};

#[test]
fn atan2_carries_derivatives_in_every_quadrant() {
    // y = sin t·ρ, x = cos t·ρ with t = 0.3 + k π/2: the angle is t (wrapped) and its derivative
    // with respect to t is 1, the second 0.
    for k in 0..8 {
        let t = -3.0 + 0.8 * k as f64;
        let tj = HyperDual64::new(t, 1.0, 1.0, 0.0);
        let angle = atan2(tj.sin() * 2.0, tj.cos() * 2.0);
        let wrapped = t.sin().atan2(t.cos());
        assert!((angle.re - wrapped).abs() < 1e-15, "t = {t}");
        assert!((angle.eps1 - 1.0).abs() < 1e-14 && angle.eps1eps2.abs() < 1e-14, "t = {t}: {angle:?}");
    }
}

#[test]
fn errors_say_what_failed() {
    let e = KinematicsError::OutOfStroke { mechanism: "jib", extension: 0.0512 };
    assert_eq!(e.to_string(), "the jib actuator would need an extension of 51.200 mm, outside its 0–50 mm stroke");
}

mod plant {
    use crate::crane::plant::{Commands, CraneConfig};

    #[test]
    fn the_initial_state_rests_at_the_requested_pendulum_length() {
        let config = CraneConfig::default();
        config.validate().unwrap();
        let s = config.initial_state([0.0257, 0.0307, 0.0237], 0.7).unwrap();
        let m = config.motion(&s, &Commands::default()).unwrap();
        assert!((m.lp.pos - 0.7).abs() < 1e-15);
        assert_eq!((m.lp.vel, m.lp.acc), (0.0, 0.0));
        assert_eq!(m.tip.vel.norm() + m.tip.acc.norm(), 0.0);
        assert!(config.initial_state([0.0257, 0.051, 0.0237], 0.7).is_err());
        assert!(config.initial_state([0.0257, 0.03, 0.0237], 0.0).is_err());
    }

    #[test]
    fn plant_velocities_and_accelerations_match_its_positions() {
        // The outputs of the stepped plant against central differences of its own positions.
        let config = CraneConfig::default();
        let cmd = Commands { volts: [2.6, 0.9, 2.2], duty: 0.65 };
        let h = 1e-4;
        let mut s = config.initial_state([0.01, 0.04, 0.02], 0.5).unwrap();
        let mut trace = vec![config.motion(&s, &cmd).unwrap()];
        for _ in 0..3000 {
            s = config.advance(&s, &cmd, h);
            trace.push(config.motion(&s, &cmd).unwrap());
        }
        let (mut worst_v, mut worst_a) = (0.0f64, 0.0f64);
        for w in trace.windows(3) {
            let v = (w[2].tip.pos - w[0].tip.pos) / (2.0 * h);
            let a = (w[2].tip.pos - 2.0 * w[1].tip.pos + w[0].tip.pos) / (h * h);
            let lv = (w[2].lp.pos - w[0].lp.pos) / (2.0 * h);
            worst_v = worst_v.max((v - w[1].tip.vel).amax()).max((lv - w[1].lp.vel).abs());
            worst_a = worst_a.max((a - w[1].tip.acc).amax());
        }
        println!(
            "stepped plant, 0.3 s at constant commands: tip/l_p velocity vs differences {worst_v:.2e} \
            m/s, tip acceleration {worst_a:.2e} m/s²"
        );
        assert!(worst_v < 1e-6 && worst_a < 1e-4, "finite-difference truncation is O(h²): {worst_v}, {worst_a}");
    }
}

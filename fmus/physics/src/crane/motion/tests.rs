use super::*;
use crate::math::Vec3;
use num_dual::{DualNum, HyperDual64};

/// A smooth test trajectory q(t) = c + A sin(ω t + φ) with exact derivatives.
#[derive(Clone, Copy)]
struct Sine {
    centre: f64,
    amplitude: f64,
    omega: f64,
    phase: f64,
}

impl Sine {
    fn at(&self, t: f64) -> AxisMotion {
        let arg = self.omega * t + self.phase;
        AxisMotion {
            pos: self.centre + self.amplitude * arg.sin(),
            vel: self.amplitude * self.omega * arg.cos(),
            acc: -self.amplitude * self.omega * self.omega * arg.sin(),
        }
    }

    fn jet(&self, t: f64) -> HyperDual64 {
        let m = self.at(t);
        HyperDual64::new(m.pos, m.vel, m.vel, m.acc)
    }
}

/// Actuators swept through most of their stroke (m) and the winch turning (deg).
const ACTUATORS: [Sine; 3] = [
    Sine { centre: 0.025, amplitude: 0.02, omega: 1.3, phase: 0.2 },
    Sine { centre: 0.030, amplitude: 0.015, omega: 2.1, phase: -0.7 },
    Sine { centre: 0.024, amplitude: 0.02, omega: 1.7, phase: 1.1 },
];
const WINCH: Sine = Sine { centre: 900.0, amplitude: 400.0, omega: 0.9, phase: 0.4 };

fn chain_at(t: f64) -> ChainMotion {
    chain_motion(&ACTUATORS.map(|s| s.at(t)), &WINCH.at(t), &CableModel::default()).unwrap()
}

/// Central differences of f (vector valued) for the first and second derivative.
fn differences(f: impl Fn(f64) -> Vec<f64>, t: f64) -> (Vec<f64>, Vec<f64>) {
    let h1 = 1e-5;
    let (p, m) = (f(t + h1), f(t - h1));
    let first = p.iter().zip(&m).map(|(a, b)| (a - b) / (2.0 * h1)).collect();
    let h2 = 1e-3;
    let (p, c, m) = (f(t + h2), f(t), f(t - h2));
    let second = p.iter().zip(&c).zip(&m).map(|((a, b), c)| (a - 2.0 * b + c) / (h2 * h2)).collect();
    (first, second)
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

#[test]
fn chain_derivatives_match_finite_differences() {
    let (mut worst_v, mut worst_a) = (0.0f64, 0.0f64);
    for k in 0..40 {
        let t = 0.1 + 0.25 * k as f64;
        let c = chain_at(t);
        let values = |t: f64| {
            let c = chain_at(t);
            let mut v: Vec<f64> = c.tip.pos.iter().copied().collect();
            v.extend(c.joints.iter().map(|j| j.pos));
            v.push(c.lp.pos);
            v
        };
        let (first, second) = differences(values, t);
        let mut vel: Vec<f64> = c.tip.vel.iter().copied().collect();
        vel.extend(c.joints.iter().map(|j| j.vel));
        vel.push(c.lp.vel);
        let mut acc: Vec<f64> = c.tip.acc.iter().copied().collect();
        acc.extend(c.joints.iter().map(|j| j.acc));
        acc.push(c.lp.acc);
        worst_v = worst_v.max(max_abs_diff(&vel, &first));
        worst_a = worst_a.max(max_abs_diff(&acc, &second));
    }
    println!(
        "chain (tip, joints, l_p) derivatives vs central differences over 40 instants: \
         velocity max {worst_v:.2e}, acceleration max {worst_a:.2e} (m/s, m/s², rad/s, rad/s²)"
    );
    assert!(worst_v < 1e-8 && worst_a < 1e-5);
}

#[test]
fn the_chain_at_rest_does_not_move() {
    let rest = [0.01, 0.02, 0.03].map(|d| AxisMotion { pos: d, vel: 0.0, acc: 0.0 });
    let c = chain_motion(&rest, &AxisMotion { pos: 100.0, vel: 0.0, acc: 0.0 }, &CableModel::default()).unwrap();
    assert_eq!(c.tip.vel, Vec3::zeros());
    assert_eq!(c.tip.acc, Vec3::zeros());
    assert_eq!((c.lp.vel, c.lp.acc), (0.0, 0.0));
}

/// Ship attitude angles as sinusoids, with ω_B and α_B from the Z–Y–X kinematic equations
/// ω_B = (φ̇ − ψ̇ sθ, θ̇ cφ + ψ̇ cθ sφ, −θ̇ sφ + ψ̇ cθ cφ), differentiated with dual numbers.
struct Ship {
    roll: Sine,
    pitch: Sine,
    yaw: Sine,
    translation: [Sine; 3],
}

impl Ship {
    fn at(&self, t: f64) -> ShipMotion {
        let (r, p) = (self.roll.jet(t), self.pitch.jet(t));
        // Rates as jets: their ε1 parts are the angle accelerations, so ω's ε1 part is α.
        let rate = |s: &Sine| {
            let m = s.at(t);
            HyperDual64::new(m.vel, m.acc, m.acc, 0.0)
        };
        let (dr, dp, dy) = (rate(&self.roll), rate(&self.pitch), rate(&self.yaw));
        let w = [dr - dy * p.sin(), dp * r.cos() + dy * p.cos() * r.sin(), -(dp * r.sin()) + dy * p.cos() * r.cos()];
        let tr = self.translation.map(|s| s.at(t));
        ShipMotion {
            pos: Vec3::new(tr[0].pos, tr[1].pos, tr[2].pos),
            roll: r.re,
            pitch: p.re,
            yaw: self.yaw.at(t).pos,
            vel: Vec3::new(tr[0].vel, tr[1].vel, tr[2].vel),
            acc: Vec3::new(tr[0].acc, tr[1].acc, tr[2].acc),
            omega: Vec3::new(w[0].re, w[1].re, w[2].re),
            alpha: Vec3::new(w[0].eps1, w[1].eps1, w[2].eps1),
        }
    }
}

const STILL: Sine = Sine { centre: 0.0, amplitude: 0.0, omega: 0.0, phase: 0.0 };

fn check_world_tip(ship: &Ship, label: &str) -> (f64, f64) {
    let world = |t: f64| tip_in_world(&ship.at(t), &chain_at(t));
    let (mut worst_v, mut worst_a) = (0.0f64, 0.0f64);
    for k in 0..40 {
        let t = 0.1 + 0.25 * k as f64;
        let w = world(t);
        let (first, second) = differences(|t| world(t).pos.iter().copied().collect(), t);
        worst_v = worst_v.max(max_abs_diff(w.vel.as_slice(), &first));
        worst_a = worst_a.max(max_abs_diff(w.acc.as_slice(), &second));
    }
    println!(
        "tip in W, {label}: velocity vs central differences max {worst_v:.2e} m/s, acceleration {worst_a:.2e} m/s²"
    );
    (worst_v, worst_a)
}

#[test]
fn world_tip_acceleration_under_ship_roll_is_rigid_body_kinematics() {
    // Roll ±5° at 0.6 rad/s with the crane moving: transport, centripetal and Coriolis terms.
    let rolling = Ship {
        roll: Sine { centre: 0.0, amplitude: 5f64.to_radians(), omega: 0.6 * 2.0, phase: 0.3 },
        pitch: STILL,
        yaw: STILL,
        translation: [STILL; 3],
    };
    let (v, a) = check_world_tip(&rolling, "ship rolling ±5°, crane moving");
    assert!(v < 1e-8 && a < 1e-5);
    // Without the Coriolis term the error would be visible: 2 ω × ṙ is of order 1e-2 m/s² here.
    let t = 1.3;
    let (s, c) = (rolling.at(t), chain_at(t));
    let coriolis = s.attitude() * (s.omega.cross(&c.tip.vel) * 2.0);
    println!("  size of the Coriolis term at t = {t} s: {:.2e} m/s²", coriolis.norm());
    assert!(coriolis.norm() > 1e3 * a);
}

#[test]
fn world_tip_motion_under_full_ship_motion_is_rigid_body_kinematics() {
    let ship = Ship {
        roll: Sine { centre: 0.02, amplitude: 0.1, omega: 1.1, phase: 0.0 },
        pitch: Sine { centre: -0.01, amplitude: 0.08, omega: 0.7, phase: 0.5 },
        yaw: Sine { centre: 0.3, amplitude: 0.2, omega: 0.4, phase: -0.2 },
        translation: [
            Sine { centre: 0.1, amplitude: 0.05, omega: 0.8, phase: 0.0 },
            Sine { centre: -0.05, amplitude: 0.04, omega: 1.2, phase: 0.9 },
            Sine { centre: 0.0, amplitude: 0.03, omega: 0.6, phase: 2.0 },
        ],
    };
    let (v, a) = check_world_tip(&ship, "surge/sway/heave, roll, pitch and yaw");
    assert!(v < 1e-8 && a < 1e-5);
}

#[test]
fn the_crane_base_is_on_the_port_side() {
    // Ship at rest: the tip in W is the tip in J12 shifted 0.225 m to port.
    let c = chain_at(0.0);
    let w = tip_in_world(&ShipMotion::default(), &c);
    assert_eq!(w.pos, c.tip.pos + Vec3::new(0.0, -0.225, 0.0));
    assert_eq!(w.vel, c.tip.vel);
    assert_eq!(w.acc, c.tip.acc);
}

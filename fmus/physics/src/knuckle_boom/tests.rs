//! Tests of the arm against independent references: closed forms, central finite differences of
//! the kinematics and of the energy (the Lagrangian), Einstein's equivalence and the world-frame
//! Lagrangian on a moving deck.

mod dynamics;
mod kinematics;
mod mechanism;
mod moving_base;

use super::{ArmParams, Joints};
use crate::math::Vec3;

/// The default arm with a boom pivot offset and a raised, shifted base, so that the offsets'
/// terms are exercised too.
fn offset_arm() -> ArmParams {
    ArmParams { pivot_offset: 0.45, base: Vec3::new(3.0, -7.5, -0.4), ..ArmParams::DEFAULT }
}

/// The default arm and [`offset_arm`].
fn arms() -> [ArmParams; 2] {
    [ArmParams::DEFAULT, offset_arm()]
}

/// Joint states spread over the working range (θ1 over a full turn, θ2 and θ3 inside their
/// limits), with rates and accelerations of crane-like size.
fn samples() -> Vec<(Joints, Joints, Joints)> {
    let mut out = Vec::new();
    for i in 0..7 {
        let s = i as f64;
        let q = [-2.9 + 0.95 * s, -0.3 + 0.26 * s, -2.2 + 0.34 * s];
        let qd = [0.2 * (1.3 * s).sin(), 0.3 * (0.7 * s + 0.5).cos(), -0.4 * (0.9 * s).sin() + 0.1];
        let qdd = [0.1 * (0.5 * s).cos(), -0.2 * (1.1 * s).sin(), 0.3 * (0.3 * s + 1.0).cos()];
        out.push((q, qd, qdd));
    }
    out
}

/// The largest relative error of a test's comparisons, each asserted below the test's tolerance.
struct Worst {
    tolerance: f64,
    error: f64,
}

impl Worst {
    fn new(tolerance: f64) -> Self {
        Worst { tolerance, error: 0.0 }
    }

    /// Asserts `error` < the tolerance (`message` says what was compared) and keeps the largest.
    fn record(&mut self, error: f64, message: impl FnOnce() -> String) {
        assert!(error < self.tolerance, "{}", message());
        self.error = self.error.max(error);
    }

    /// [`Worst::record`] of the [`relative_error`] of `value` against `reference`.
    fn compare(&mut self, value: &[f64], reference: &[f64], case: impl std::fmt::Display) {
        self.record(relative_error(value, reference), || format!("{case}: {value:?} vs {reference:?}"));
    }

    /// Prints the largest error, `what` naming the comparison.
    fn report(&self, what: &str) {
        println!("{what}: largest relative error {:.2e}", self.error);
    }
}

/// Largest |a_i − b_i| over the largest |b_i| (the vectors' common scale).
fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

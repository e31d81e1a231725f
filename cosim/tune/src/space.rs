//! The optimiser's coordinates: each tuned parameter's range mapped onto [0, 1], linearly or
//! logarithmically, so that one step size suits every parameter whatever its unit.
//!
//! A point outside the unit box is repaired to the nearest point inside (the values simulated)
//! and its objective gets the squared distance of the repair times [`BOUND_PENALTY`]: the
//! "repair and penalise" boundary handling of CMA-ES (Hansen, The CMA Evolution Strategy: A
//! Tutorial, 2016, §B.3), which keeps the search inside without a hard wall.

use crate::study::{AxisScale, TunedParameter};

/// Objective added per unit of squared distance between a point and its repair.
pub const BOUND_PENALTY: f64 = 1.0;

/// The tuned parameters' ranges.
#[derive(Debug, Clone)]
pub struct Space {
    /// The tuned parameters, in the tuning file's order.
    pub parameters: Vec<TunedParameter>,
}

impl Space {
    /// The parameter's value at coordinate `u` ∈ [0, 1]: lower + u (upper − lower), or
    /// lower (upper / lower)^u on a log scale.
    pub fn value(parameter: &TunedParameter, u: f64) -> f64 {
        let [lower, upper] = parameter.bounds;
        let value = match parameter.scale {
            AxisScale::Linear => lower + u * (upper - lower),
            AxisScale::Log => lower * (upper / lower).powf(u),
        };
        // Round-off at u = 1 must not leave the bounds.
        value.clamp(lower, upper)
    }

    /// The coordinate of `value` (the inverse of [`Space::value`]).
    pub fn coordinate(parameter: &TunedParameter, value: f64) -> f64 {
        let [lower, upper] = parameter.bounds;
        match parameter.scale {
            AxisScale::Linear => (value - lower) / (upper - lower),
            AxisScale::Log => (value / lower).ln() / (upper / lower).ln(),
        }
    }

    /// The values of the point `point` repaired into the box, and the repair's penalty.
    pub fn values(&self, point: &[f64]) -> (Vec<f64>, f64) {
        let mut penalty = 0.0;
        let values = self
            .parameters
            .iter()
            .zip(point)
            .map(|(parameter, &u)| {
                let repaired = u.clamp(0.0, 1.0);
                penalty += (u - repaired) * (u - repaired);
                Space::value(parameter, repaired)
            })
            .collect();
        (values, BOUND_PENALTY * penalty)
    }

    /// The point of the values `values`.
    pub fn point(&self, values: &[f64]) -> Vec<f64> {
        self.parameters.iter().zip(values).map(|(p, &v)| Space::coordinate(p, v)).collect()
    }
}

//! The recorded variables a frame is drawn from, and a [`Sample`] read from any row of them.

use cosim_engine::closed_loop::ClosedLoopNames;

use crate::scene::Sample;

/// The closed loop's names the view is drawn from.
const NAMES: ClosedLoopNames = ClosedLoopNames::TEST_SCALE;

/// Every variable the view needs, in the order [`Columns::sample`] reads them: the ship's
/// motion, the crane's joints, the load and its cable angles, the controller's estimate of the
/// load and its set-point.
pub fn required() -> impl Iterator<Item = &'static str> {
    let n = NAMES;
    n.ship
        .into_iter()
        .chain(n.joints)
        .chain(n.load.axes)
        .chain(n.theta)
        .chain(n.estimated_load.axes)
        .chain(n.setpoint.axes)
}

/// Where each required variable sits among a row's values.
#[derive(Debug, Clone)]
pub struct Columns {
    index: Vec<usize>,
}

impl Columns {
    /// The positions of the required variables in `names`, or the names that are missing.
    pub fn find(names: &[String]) -> Result<Columns, Vec<&'static str>> {
        let found: Vec<_> = required().map(|name| (name, names.iter().position(|n| n == name))).collect();
        let missing: Vec<_> = found.iter().filter(|(_, i)| i.is_none()).map(|(name, _)| *name).collect();
        if !missing.is_empty() {
            return Err(missing);
        }
        Ok(Columns { index: found.into_iter().filter_map(|(_, i)| i).collect() })
    }

    /// The sample at `time` of a row whose `value(i)` is the value of the i-th name given to
    /// [`Columns::find`].
    pub fn sample(&self, time: f64, value: impl Fn(usize) -> f64) -> Sample {
        let mut values = self.index.iter().map(|&i| value(i));
        let mut next = || values.next().unwrap_or(f64::NAN);
        Sample {
            time,
            ship: std::array::from_fn(|_| next()),
            joints: std::array::from_fn(|_| next()),
            load: std::array::from_fn(|_| next()),
            theta: std::array::from_fn(|_| next()),
            estimated_load: std::array::from_fn(|_| next()),
            setpoint: std::array::from_fn(|_| next()),
        }
    }
}

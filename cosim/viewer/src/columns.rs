//! The recorded variables a frame is drawn from, which crane they belong to, and a [`Sample`]
//! read from any row of them.

use crane_names::{FULL_SCALE, RIGGING_HOOK, TEST_SCALE};

use crate::scene::{Crane, Sample};

/// The full-scale crane's joint outputs slew, boom, jib (systems/full_scale*.json). Its systems
/// name the platform and the pendulum as the test-scale loop does.
pub const FULL_SCALE_JOINTS: [&str; 3] = FULL_SCALE.joints;

/// The crane whose joints are among `names`: the full-scale crane (at its default arm
/// parameters, since a results table does not hold the FMU's `base.*`) when they hold
/// `knuckle_boom.joint.*`, else the test-scale crane.
pub fn crane_in(names: &[String]) -> Crane {
    if names.iter().any(|name| FULL_SCALE_JOINTS.contains(&name.as_str())) {
        Crane::FULL_SCALE
    } else {
        Crane::TestScale
    }
}

/// The hook's position (m, W), which a rigging in place of the pendulum records (the `rigging`
/// FMU's `hook.*`; docs/rigging.md): drawn, with the sling to the load, where a recording has it.
pub const HOOK: [&str; 3] = RIGGING_HOOK.axes;

/// Every variable the view of `crane` needs, in the order [`Columns::sample`] reads them: the
/// ship's motion, the crane's joints, the load and its cable angles and, for the test-scale
/// loop, the controller's estimate of the load and its set-point (the full-scale controller has
/// neither).
pub fn required(crane: &Crane) -> impl Iterator<Item = &'static str> {
    let n = TEST_SCALE;
    let (joints, ghosts) = match crane {
        Crane::TestScale => (n.joints, Some(n.estimated_load.axes.into_iter().chain(n.setpoint.axes))),
        Crane::FullScale { .. } => (FULL_SCALE_JOINTS, None),
    };
    n.ship.into_iter().chain(joints).chain(n.load.axes).chain(n.theta).chain(ghosts.into_iter().flatten())
}

/// Where each required variable sits among a row's values.
#[derive(Debug, Clone)]
pub struct Columns {
    crane: Crane,
    index: Vec<usize>,
    /// Where the [`HOOK`] columns sit, when `names` has all three.
    hook: Option<[usize; 3]>,
}

impl Columns {
    /// The positions of the variables `crane` needs in `names`, or the names that are missing.
    pub fn find(crane: Crane, names: &[String]) -> Result<Columns, Vec<&'static str>> {
        let found: Vec<_> = required(&crane).map(|name| (name, names.iter().position(|n| n == name))).collect();
        let missing: Vec<_> = found.iter().filter(|(_, i)| i.is_none()).map(|(name, _)| *name).collect();
        if !missing.is_empty() {
            return Err(missing);
        }
        let position = |name: &str| names.iter().position(|n| n == name);
        let hook = match HOOK.map(position) {
            [Some(x), Some(y), Some(z)] => Some([x, y, z]),
            _ => None,
        };
        Ok(Columns { crane, index: found.into_iter().filter_map(|(_, i)| i).collect(), hook })
    }

    /// The crane the columns belong to.
    pub fn crane(&self) -> &Crane {
        &self.crane
    }

    /// The sample at `time` of a row whose `value(i)` is the value of the i-th name given to
    /// [`Columns::find`].
    pub fn sample(&self, time: f64, value: impl Fn(usize) -> f64) -> Sample {
        let mut values = self.index.iter().map(|&i| value(i));
        let mut next = || values.next().unwrap_or(f64::NAN);
        let ship = std::array::from_fn(|_| next());
        let joints = std::array::from_fn(|_| next());
        let load = std::array::from_fn(|_| next());
        let theta = std::array::from_fn(|_| next());
        let ghosts = matches!(self.crane, Crane::TestScale);
        let mut ghost = || ghosts.then(|| std::array::from_fn(|_| next()));
        let estimated_load = ghost();
        let setpoint = ghost();
        let hook = self.hook.map(|index| index.map(&value));
        Sample { time, ship, joints, load, theta, estimated_load, setpoint, hook }
    }

    /// The frame of the sample at `time` (see [`Columns::sample`]).
    pub fn frame(&self, time: f64, value: impl Fn(usize) -> f64) -> crate::scene::Frame {
        crate::scene::Frame::of(&self.crane, &self.sample(time, value))
    }
}

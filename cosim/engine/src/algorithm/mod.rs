//! Co-simulation algorithms: how instances are stepped and how their inputs
//! are fed during one macro step.

mod wiring;

pub use wiring::Wiring;

use serde::{Deserialize, Serialize};

use crate::simulator::{Simulator, SimulatorError};

/// Fixed-step co-simulation algorithm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AlgorithmKind {
    /// Instances step one after the other in the listed order; each uses the
    /// newest outputs of its sources (those earlier in the order are already
    /// at `t_{k+1}`).
    #[default]
    #[serde(alias = "gauss_seidel")]
    GaussSeidel,
    /// All inputs are taken from outputs at `t_k`, then all instances step.
    Jacobi,
}

impl std::str::FromStr for AlgorithmKind {
    type Err = String;

    /// Parses the names a system file accepts, e.g. for a command-line option.
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name {
            "gauss-seidel" | "gauss_seidel" => Ok(Self::GaussSeidel),
            "jacobi" => Ok(Self::Jacobi),
            _ => Err(format!("unknown algorithm '{name}': expected gauss-seidel or jacobi")),
        }
    }
}

/// A fixed-step co-simulation algorithm.
///
/// The execution calls [`Algorithm::initialize`] once, with every instance
/// in initialization mode at `t0`, then [`Algorithm::step`] for each macro
/// step `t_k → t_k + step`.
pub trait Algorithm: Send {
    /// Short name, e.g. `"gauss-seidel"`.
    fn name(&self) -> &'static str;

    /// Sets all inputs at the start time `time` (s) in initialization mode.
    fn initialize(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64) -> Result<(), SimulatorError>;

    /// Feeds inputs and calls `fmi2DoStep(time, step)` on every instance.
    fn step(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64, step: f64) -> Result<(), SimulatorError>;

    /// The wiring with what it carries from one step to the next (the inputs' values at the
    /// last communication point, for interpolation and extrapolation), to save with the
    /// instances' states.
    fn wiring(&self) -> &Wiring;

    /// Puts back a wiring [`Algorithm::wiring`] gave, with the instances' states it was saved with.
    fn set_wiring(&mut self, wiring: Wiring);
}

/// The algorithm for a system file setting.
pub fn algorithm(kind: AlgorithmKind, wiring: Wiring) -> Box<dyn Algorithm> {
    match kind {
        AlgorithmKind::GaussSeidel => Box::new(GaussSeidel { wiring }),
        AlgorithmKind::Jacobi => Box::new(Jacobi { wiring }),
    }
}

/// [`Algorithm::name`] giving `$name`, and [`Algorithm::wiring`] and [`Algorithm::set_wiring`] on
/// the algorithm's `wiring` field.
macro_rules! named_with_wiring {
    ($name:literal) => {
        fn name(&self) -> &'static str {
            $name
        }

        fn wiring(&self) -> &Wiring {
            &self.wiring
        }

        fn set_wiring(&mut self, wiring: Wiring) {
            self.wiring = wiring;
        }
    };
}

/// Sets inputs in order, each instance reading the newest outputs of its sources.
fn initialize_in_order(
    wiring: &mut Wiring,
    slaves: &mut [Box<dyn Simulator>],
    time: f64,
) -> Result<(), SimulatorError> {
    for index in 0..slaves.len() {
        wiring.gather(index, slaves)?;
        let slave = slaves[index].as_mut();
        slave.set_time_hint(time);
        wiring.apply_files(index, slave, time, None)?;
        wiring.set(index, slave)?;
    }
    Ok(())
}

/// Sequential stepping in the listed order: instance `i` steps with inputs
/// from the outputs of instances before it at `t_{k+1}` and of instances
/// after it at `t_k`.
///
/// With `input_derivatives`, a target that can interpolate inputs gets each
/// Real input from an earlier source as its value at `t_k` plus the slope to
/// `t_{k+1}` (both ends are known), i.e. exact linear interpolation across
/// the step; inputs from later sources are held.
#[derive(Debug)]
pub struct GaussSeidel {
    /// Also keeps the values at `t_k` of the interpolated inputs.
    wiring: Wiring,
}

impl Algorithm for GaussSeidel {
    named_with_wiring!("gauss-seidel");

    fn initialize(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64) -> Result<(), SimulatorError> {
        initialize_in_order(&mut self.wiring, slaves, time)?;
        // The values at t0 after initialization start the first step's interpolation.
        for index in 0..slaves.len() {
            if self.wiring.interpolates(index) {
                self.wiring.gather(index, slaves)?;
                self.wiring.remember(index);
            }
        }
        Ok(())
    }

    fn step(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64, step: f64) -> Result<(), SimulatorError> {
        let mut discard = Discards::default();
        for index in 0..slaves.len() {
            self.wiring.gather(index, slaves)?;
            self.wiring.interpolate(index, step);
            let slave = slaves[index].as_mut();
            slave.set_time_hint(time);
            self.wiring.apply_files(index, slave, time, Some(time + step))?;
            self.wiring.set(index, slave)?;
            self.wiring.set_slopes(index, slave)?;
            discard.note(slave.do_step(time, step))?;
        }
        discard.result()
    }
}

/// Parallel-style stepping: every input is taken from outputs at `t_k`
/// before any instance steps.
///
/// With `extrapolate_inputs`, a target that can interpolate inputs gets each
/// connected Real input as its value at `t_k` plus the slope from the last two
/// communication points, `(u_k − u_{k−1}) / (t_k − t_{k−1})`, i.e. linear
/// extrapolation across the step (at the first step it is held: there is no
/// earlier point).
#[derive(Debug)]
pub struct Jacobi {
    wiring: Wiring,
}

impl Algorithm for Jacobi {
    named_with_wiring!("jacobi");

    fn initialize(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64) -> Result<(), SimulatorError> {
        initialize_in_order(&mut self.wiring, slaves, time)
    }

    fn step(&mut self, slaves: &mut [Box<dyn Simulator>], time: f64, step: f64) -> Result<(), SimulatorError> {
        for index in 0..slaves.len() {
            self.wiring.gather(index, slaves)?;
        }
        let mut discard = Discards::default();
        for (index, slave) in slaves.iter_mut().enumerate() {
            let slave = slave.as_mut();
            slave.set_time_hint(time);
            self.wiring.apply_files(index, slave, time, Some(time + step))?;
            self.wiring.set(index, slave)?;
            if self.wiring.extrapolate(index, time) {
                self.wiring.set_extrapolated_slopes(index, slave)?;
            }
            discard.note(slave.do_step(time, step))?;
        }
        discard.result()
    }
}

/// The first `fmi2Discard` of a macro step. The other instances still take the step, so that
/// when the discarding one asks to end the run having reached the step's end (a model that
/// stops at a communication point), every instance is at `t_{k+1}` and that row can be kept.
/// Any other error ends the step at once.
#[derive(Default)]
struct Discards(Option<SimulatorError>);

impl Discards {
    fn note(&mut self, outcome: Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        match outcome {
            Err(error) if error.discarded_by().is_some() => {
                self.0.get_or_insert(error);
                Ok(())
            }
            other => other,
        }
    }

    fn result(self) -> Result<(), SimulatorError> {
        self.0.map_or(Ok(()), Err)
    }
}

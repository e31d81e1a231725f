//! A replay: the frames of a recorded run, from a results table or from running a system with
//! the view's variables recorded in memory.

use cosim_engine::execution::Execution;
use cosim_engine::interrupt::Interrupt;
use cosim_engine::observer::TableRecorder;
use cosim_engine::system::System;
use cosim_engine::table::SignalTable;
use cosim_engine::variable::VariableRef;
use crane_names::split;
use fmu_import::fmi::LogEcho;
use fmu_import::slave::InstantiateOptions;
use fmu_import::value::Value;
use physics::knuckle_boom::ArmParams;
use serde::Serialize;

use crate::columns::{self, Columns};
use crate::error::ViewerError;
use crate::scene::{Crane, Frame};

/// The frames of a run, column by column (the page's data): vectors are flattened, frame after
/// frame (`deck_position` holds x0, y0, z0, x1, ...). Units and frames as in [`Frame`]; the
/// columns of a crane without them (cylinders, ghost markers) are empty and left out of the
/// JSON.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct FrameColumns {
    /// The crane's [`Crane::scale`]: `"test"` or `"full"`.
    pub scale: &'static str,
    /// Each frame's time (s).
    pub time: Vec<f64>,
    /// [`Frame::deck_position`], three per frame.
    pub deck_position: Vec<f64>,
    /// [`Frame::deck_attitude`], four per frame.
    pub deck_attitude: Vec<f64>,
    /// Four joints per frame (base, boom pivot, jib pivot or knuckle, tip), three coordinates each.
    pub crane: Vec<f64>,
    /// Six points per frame (each cylinder's barrel pin, barrel end, rod pin): full scale only.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub cylinders: Vec<f64>,
    /// [`Frame::load`], three per frame.
    pub load: Vec<f64>,
    /// The hook, where the recording has one (a rigging in place of the pendulum).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub hook: Vec<f64>,
    /// [`Frame::estimated_load`], three per frame, where the controller has one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub estimated_load: Vec<f64>,
    /// [`Frame::setpoint`], three per frame, where the controller has one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub setpoint: Vec<f64>,
    /// [`Frame::theta`], two per frame.
    pub theta: Vec<f64>,
    /// [`Frame::setpoint_error`], one per frame, where there is a set-point.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub setpoint_error: Vec<f64>,
}

impl FrameColumns {
    /// Appends one frame.
    pub fn push(&mut self, frame: &Frame) {
        self.time.push(frame.time);
        self.deck_position.extend(frame.deck_position);
        self.deck_attitude.extend(frame.deck_attitude);
        self.crane.extend(frame.crane.iter().flatten());
        self.cylinders.extend(frame.cylinders.iter().flatten().flatten());
        self.load.extend(frame.load);
        self.hook.extend(frame.hook.iter().flatten());
        self.estimated_load.extend(frame.estimated_load.iter().flatten());
        self.setpoint.extend(frame.setpoint.iter().flatten());
        self.theta.extend(frame.theta);
        self.setpoint_error.extend(frame.setpoint_error);
    }

    /// The frames of a results table (a results CSV or an in-memory recording), of the crane
    /// whose joints it holds ([`columns::crane_in`]), or of `crane` if given.
    pub fn from_table(table: &SignalTable, crane: Option<Crane>) -> Result<FrameColumns, ViewerError> {
        let crane = crane.unwrap_or_else(|| columns::crane_in(&table.names));
        let columns = Columns::find(crane, &table.names).map_err(|missing| ViewerError::MissingColumns {
            file: table.file.clone(),
            missing: missing.into_iter().map(String::from).collect(),
        })?;
        let mut frames = FrameColumns { scale: crane.scale(), ..FrameColumns::default() };
        for (row, &time) in table.times.iter().enumerate() {
            frames.push(&columns.frame(time, |i| table.columns[i][row]));
        }
        Ok(frames)
    }
}

/// FMU instances of a view's run: hidden, FMU warnings echoed.
pub(crate) const INSTANTIATE: InstantiateOptions =
    InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Warnings };

/// The crane `system` holds: the full-scale crane when it has an instance `knuckle_boom`, drawn
/// with the arm of the crane description its `crane` start value names (docs/crane-description.md;
/// the default crane where it sets none or names one that does not load: the run then stops at
/// the FMU's own error) and the pedestal at its `base.*` start values (the FMU's defaults where
/// the system sets none); else the test-scale crane.
pub fn crane_of(system: &System) -> Crane {
    let Some(instance) = system.instance_index(FULL_SCALE_INSTANCE) else {
        return Crane::TestScale;
    };
    let instance = &system.instances[instance];
    let start = |name: &str| instance.start.iter().find(|(variable, _)| variable.name == name).map(|(_, value)| value);
    let mut arm = match start("crane") {
        Some(Value::String(spec)) => crane_description::load(spec, None).map_or(ArmParams::DEFAULT, |d| d.arm),
        _ => ArmParams::DEFAULT,
    };
    arm.base = ArmParams::DEFAULT.base;
    for (axis, coordinate) in ["base.x", "base.y", "base.z"].into_iter().zip(arm.base.iter_mut()) {
        if let Some(Value::Real(value)) = start(axis) {
            *coordinate = *value;
        }
    }
    Crane::FullScale { arm }
}

/// The full-scale crane's instance in its systems.
const FULL_SCALE_INSTANCE: &str = "knuckle_boom";

/// The view's variables of `system` for its crane, resolved against its instances, and the
/// hook's ([`columns::HOOK`]) where the load instance has them.
/// A system without them is refused naming every instance and variable it lacks.
pub fn view_variables(system: &System, crane: &Crane) -> Result<Vec<VariableRef>, ViewerError> {
    let needed: Vec<&str> = columns::required(crane).collect();
    let (found, missing): (Vec<_>, Vec<_>) =
        needed.iter().map(|name| (name, resolve(system, name))).partition(|(_, r)| r.is_ok());
    if !missing.is_empty() {
        return Err(missing_variables(system, missing.into_iter().map(|(name, _)| *name), &needed));
    }
    let mut variables: Vec<VariableRef> = found.into_iter().filter_map(|(_, r)| r.ok()).collect();
    let hook: Result<Vec<_>, _> = columns::HOOK.iter().map(|name| resolve(system, name)).collect();
    variables.extend(hook.unwrap_or_default());
    Ok(variables)
}

/// The error of a system that lacks the view's variables `missing` (of `needed`).
fn missing_variables<'a>(system: &System, missing: impl Iterator<Item = &'a str>, needed: &[&str]) -> ViewerError {
    let mut missing_instances: Vec<String> = Vec::new();
    let mut missing_variables = Vec::new();
    for name in missing {
        let instance = split(name).map_or(name, |(instance, _)| instance);
        if system.instance_index(instance).is_some() {
            missing_variables.push(name.to_string());
        } else if !missing_instances.iter().any(|i| i == instance) {
            missing_instances.push(instance.to_string());
        }
    }
    ViewerError::MissingVariables {
        file: system.file.clone(),
        missing_instances,
        missing_variables,
        instances: system.instances.iter().map(|i| i.name.clone()).collect(),
        needed: needed.iter().map(|n| n.to_string()).collect(),
    }
}

/// The variable of `system` named `"instance.variable"`.
pub(crate) fn resolve(system: &System, qualified_name: &str) -> Result<VariableRef, ViewerError> {
    let unknown = || ViewerError::UnknownVariable { file: system.file.clone(), name: qualified_name.to_string() };
    let (instance_name, variable_name) = split(qualified_name).ok_or_else(unknown)?;
    let instance = system.instance_index(instance_name).ok_or_else(unknown)?;
    let variable = system.instances[instance].fmu.model_description().variable(variable_name).ok_or_else(unknown)?;
    Ok(VariableRef { instance, qualified_name: qualified_name.to_string(), variable: variable.clone() })
}

/// Runs `system` to its stop time with the view's variables recorded in memory, at the
/// system's recording interval (no file is written).
pub fn record(system: &System, interrupt: Option<&Interrupt>) -> Result<SignalTable, ViewerError> {
    let variables = view_variables(system, &crane_of(system))?;
    let recorder = TableRecorder::new(&system.file, &variables, system.record.every)
        .ok_or_else(|| ViewerError::NotANumber { file: system.file.clone() })?;
    let mut execution = Execution::from_system(system, INSTANTIATE)?;
    if let Some(interrupt) = interrupt {
        execution.interrupt_on(interrupt.clone());
    }
    Ok(execution.run_into_table(recorder)?)
}

#[cfg(test)]
mod tests;

//! Step 4 of loading a system: name resolution and checks of a [`SystemSpec`], one function per
//! kind of check, taken in the order of [`validate`]. Every check reports all its problems and
//! the later checks still run (skipping what an earlier problem left unresolved), so that one
//! run lists every problem of the file.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::single::glob_matches;
use super::{
    BoundInput, Connection, Instance, Overrides, Problem, RecordPlan, System, SystemError, SystemFiles, SystemSpec,
    VariableRef,
};
use fmu_import::error_chain;
use fmu_import::fmu::{Causality, Fmu, ScalarVariable, Variability};
use fmu_import::names::{closest, did_you_mean, quoted_list};
use fmu_import::value::{Value, VariableType};

use crate::input::InputBinding;
use crate::table::SignalTable;
use crate::text::Decimal;
use crate::time::{TimeGrid, TimeGridError};

/// What a variable is used for; decides which causalities are accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    /// Source of a connection: an output.
    Source,
    /// Target of a connection or an inputs-file column: an input.
    Input,
    /// Recorded: anything.
    Recorded,
}

impl Role {
    fn accepts(self, variable: &ScalarVariable) -> bool {
        match self {
            Role::Source => variable.causality == Causality::Output,
            Role::Input => variable.causality == Causality::Input,
            Role::Recorded => true,
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Role::Source => "outputs",
            Role::Input => "inputs",
            Role::Recorded => "variables",
        }
    }
}

struct Validator<'a> {
    base: &'a Path,
    problems: Vec<Problem>,
    /// Instance name → (index, FMU if it could be opened).
    instances: Vec<(String, Option<Fmu>)>,
    /// Input (instance, value reference, ABI type) → where it is fed from: each input is fed by
    /// at most one connection or inputs-file column.
    fed: HashMap<(usize, u32, VariableType), String>,
}

impl Validator<'_> {
    fn problem(&mut self, location: impl Into<String>, message: impl Into<String>) {
        self.problems.push(Problem { location: location.into(), message: message.into() });
    }

    fn instance_names(&self) -> Vec<&str> {
        self.instances.iter().map(|(name, _)| name.as_str()).collect()
    }

    /// Resolves an instance name; reports a problem if it is unknown.
    fn instance(&mut self, name: &str, location: &str, context: &str) -> Option<usize> {
        if let Some(index) = self.instances.iter().position(|(n, _)| n == name) {
            return Some(index);
        }
        let names = self.instance_names();
        let message = format!(
            "unknown instance {name:?}{context}{}; instances: {}",
            did_you_mean(&closest(name, names.iter().copied())),
            quoted_list(names.iter().copied())
        );
        self.problem(location, message);
        None
    }

    /// Resolves `variable` of instance `index` for `role`. Returns `None`
    /// (silently) if the instance's FMU could not be opened.
    fn variable(&mut self, index: usize, name: &str, role: Role, location: &str) -> Option<ScalarVariable> {
        let (instance, fmu) = &self.instances[index];
        let fmu = fmu.as_ref()?;
        let md = fmu.model_description();
        let instance = instance.clone();
        let fitting: Vec<&str> = md.variables.iter().filter(|v| role.accepts(v)).map(|v| v.name.as_str()).collect();
        match md.variable(name) {
            Some(variable) if role.accepts(variable) => Some(variable.clone()),
            Some(variable) => {
                let message = format!(
                    "variable {name:?} of instance {instance:?} is {} {}, not {}; {} of {instance:?}: {}",
                    article(variable.causality.as_str()),
                    variable.causality,
                    match role {
                        Role::Source => "an output",
                        _ => "an input",
                    },
                    role.describe(),
                    quoted_list(fitting.iter().copied())
                );
                self.problem(location, message);
                None
            }
            None => {
                let suggestion = closest(name, fitting.iter().copied())
                    .or_else(|| closest(name, md.variables.iter().map(|v| v.name.as_str())));
                let message = format!(
                    "instance {instance:?} (model {:?}) has no variable {name:?}{}; {} of {instance:?}: {}",
                    md.model_name,
                    did_you_mean(&suggestion),
                    role.describe(),
                    quoted_list(fitting.iter().copied())
                );
                self.problem(location, message);
                None
            }
        }
    }

    /// Records that `location` feeds the input `target`; a problem if something already does.
    fn feed(&mut self, target: &VariableRef, location: &str) {
        let key = (target.instance, target.variable.value_reference, target.variable.variable_type.abi_type());
        if let Some(previous) = self.fed.get(&key) {
            let message = format!("input {:?} is already fed by {previous}", target.qualified_name);
            self.problem(location, message);
        } else {
            self.fed.insert(key, location.to_string());
        }
    }

    /// Resolves `"instance.variable"` (split at the first dot).
    fn qualified(&mut self, qualified: &str, role: Role, location: &str) -> Option<VariableRef> {
        let Some((instance_name, variable_name)) = qualified.split_once('.') else {
            self.problem(location, format!("{qualified:?} is not of the form \"<instance>.<variable>\""));
            return None;
        };
        let index = self.instance(instance_name, location, &format!(" in {qualified:?}"))?;
        let variable = self.variable(index, variable_name, role, location)?;
        Some(VariableRef { instance: index, qualified_name: qualified.to_string(), variable })
    }
}

/// True for a recorded name with wildcards (`*`, `?`), expanded by [`Validator::matching`].
fn is_pattern(name: &str) -> bool {
    name.contains(['*', '?'])
}

fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    }
}

/// ` with initial="calculated"` when that, not constancy, is why a start value is refused.
fn initial_note(variable: &ScalarVariable) -> String {
    match variable.initial_or_default() {
        Some(initial) if variable.variability != Variability::Constant => format!(" with initial=\"{initial}\""),
        _ => String::new(),
    }
}

/// Converts a JSON start value to the variable's type.
fn start_value(variable: &ScalarVariable, json: &serde_json::Value) -> Result<Value, String> {
    let expected = variable.variable_type;
    let mismatch = |wanted: &str| format!("variable {:?} is {expected}: expected {wanted}, got {json}", variable.name);
    match expected {
        VariableType::Real => json.as_f64().map(Value::Real).ok_or_else(|| mismatch("a number")),
        VariableType::Integer | VariableType::Enumeration => {
            let integer = json
                .as_i64()
                .or_else(|| json.as_f64().filter(|v| v.fract() == 0.0 && v.abs() < 1e10).map(|v| v as i64));
            match integer {
                Some(v) => i32::try_from(v)
                    .map(Value::Integer)
                    .map_err(|_| format!("variable {:?}: {v} does not fit a 32-bit fmi2Integer", variable.name)),
                None => Err(mismatch("an integer")),
            }
        }
        VariableType::Boolean => json.as_bool().map(Value::Boolean).ok_or_else(|| mismatch("true or false")),
        VariableType::String => json.as_str().map(|s| Value::String(s.to_string())).ok_or_else(|| mismatch("a string")),
    }
}

/// Checks `spec` and resolves its names into a [`System`] (relative paths against `base`, FMUs
/// from `files`), or every problem found, reported against `file`.
/// The caller's `record` and `inputs` ([`Overrides`]) are resolved after the file's.
pub(super) fn validate(
    spec: SystemSpec,
    file: &Path,
    base: &Path,
    files: &SystemFiles,
    overrides: &Overrides,
) -> Result<System, SystemError> {
    let mut v = Validator { base, problems: Vec::new(), instances: Vec::new(), fed: HashMap::new() };
    let grid = v.time_grid(&spec);
    let every = v.record_every(&spec);
    let fmus = v.fmus(&spec, files);
    v.instances(&spec, &fmus);
    let instances = v.start_values(&spec);
    if let Some(grid) = &grid {
        v.variable_step(&spec, grid, &instances);
    }
    let connections = v.connections(&spec);
    v.connected_starts(&overrides.start, &connections);
    let mut inputs = v.inputs(&spec);
    inputs.extend(v.qualified_inputs(&spec, &overrides.inputs));
    let recorded = v.recorded(&spec, &overrides.record);
    let unconnected_inputs = v.unconnected_inputs(&spec);
    match grid {
        Some(grid) if v.problems.is_empty() => Ok(System {
            file: file.to_path_buf(),
            spec,
            instances,
            connections,
            inputs,
            grid,
            record: RecordPlan { every, variables: recorded },
            unconnected_inputs,
            notes: Vec::new(),
        }),
        _ => Err(SystemError::Invalid { file: file.to_path_buf(), problems: v.problems }),
    }
}

impl Validator<'_> {
    /// The time grid of `start_time`, `stop_time` and `step_size`.
    fn time_grid(&mut self, spec: &SystemSpec) -> Option<TimeGrid> {
        match TimeGrid::new(spec.start_time, spec.stop_time, spec.step_size) {
            Ok(grid) => Some(grid),
            Err(error) => {
                let location = match &error {
                    TimeGridError::NotFinite { name, .. } => *name,
                    TimeGridError::NonPositiveStep(_) | TimeGridError::TooManySteps { .. } => "step_size",
                    TimeGridError::StopBeforeStart { .. } => "stop_time",
                };
                self.problem(location, error.to_string());
                None
            }
        }
    }

    /// A shortened last step needs every FMU to take steps of more than one size.
    fn variable_step(&mut self, spec: &SystemSpec, grid: &TimeGrid, instances: &[Instance]) {
        let Some(last) = grid.shortened_last_step() else {
            return;
        };
        let fixed = instances
            .iter()
            .filter(|i| !i.fmu.model_description().co_simulation.can_handle_variable_communication_step_size);
        for instance in fixed {
            let message = format!(
                "{} s is not a whole number of steps of {} s, and instance {:?} cannot shorten the last \
                 step to {} s (its FMU does not declare canHandleVariableCommunicationStepSize): give a \
                 stop time (Overrides::stop_time) or step size (Overrides::step_size) that fit",
                Decimal(spec.stop_time),
                Decimal(spec.step_size),
                instance.name,
                Decimal(last)
            );
            self.problem("stop_time", message);
        }
    }

    /// Every how many steps a row is recorded: `record.interval` over `step_size`, a whole number.
    fn record_every(&mut self, spec: &SystemSpec) -> u64 {
        let Some(interval) = spec.record.interval else {
            return 1;
        };
        let ratio = interval / spec.step_size;
        let rounded = ratio.round();
        if interval.is_finite() && rounded >= 1.0 && (ratio - rounded).abs() <= 1e-9 * rounded {
            rounded as u64
        } else {
            // An interval written for another step size: say how to change it without editing files.
            let message = format!(
                "{interval:?} s is not a positive whole multiple of step_size {:?} s: give one that is \
                 (Overrides::record_interval), or leave it out to record every step",
                spec.step_size
            );
            self.problem("record.interval", message);
            1
        }
    }

    /// Every FMU of `fmus` by alias, opened (`None` for one that cannot be, a problem).
    fn fmus<'s>(&mut self, spec: &'s SystemSpec, files: &SystemFiles) -> BTreeMap<&'s str, Option<Fmu>> {
        let mut fmus = BTreeMap::new();
        for (alias, path) in &spec.fmus {
            let full: PathBuf = self.base.join(path);
            let fmu = files.fmu(&full).map_err(|error| self.problem(format!("fmus[{alias:?}]"), error_chain(&error)));
            fmus.insert(alias.as_str(), fmu.ok());
        }
        fmus
    }

    /// Instance names (well-formed, unique) and their FMUs.
    fn instances(&mut self, spec: &SystemSpec, fmus: &BTreeMap<&str, Option<Fmu>>) {
        if spec.instances.is_empty() {
            self.problem("instances", "no instances: add at least one {\"name\": ..., \"fmu\": ...}");
        }
        for (i, instance) in spec.instances.iter().enumerate() {
            let location = format!("instances[{i}]");
            let name = &instance.name;
            if name.is_empty() || name.contains('.') || name.contains(',') || name.chars().any(char::is_control) {
                self.problem(
                    format!("{location}.name"),
                    format!("instance name {name:?} must be non-empty and contain no '.', ',' or control characters"),
                );
            } else if self.instances.iter().any(|(n, _)| n == name) {
                self.problem(format!("{location}.name"), format!("instance name {name:?} is used twice"));
            }
            let fmu = match fmus.get(instance.fmu.as_str()) {
                Some(fmu) => fmu.clone(),
                None => {
                    let aliases: Vec<&str> = fmus.keys().copied().collect();
                    let message = format!(
                        "unknown FMU {:?} for instance {name:?}{}; FMUs: {}",
                        instance.fmu,
                        did_you_mean(&closest(&instance.fmu, aliases.iter().copied())),
                        quoted_list(aliases.iter().copied())
                    );
                    self.problem(format!("{location}.fmu"), message);
                    None
                }
            };
            self.instances.push((name.clone(), fmu));
        }
    }

    /// The instances whose FMU could be opened, with their start values type-checked.
    fn start_values(&mut self, spec: &SystemSpec) -> Vec<Instance> {
        // A connected input takes its value from the connection, so a suggestion never offers it.
        let connected: std::collections::BTreeSet<&str> = spec.connections.iter().map(|c| c.to.as_str()).collect();
        let mut instances = Vec::new();
        for (index, instance) in spec.instances.iter().enumerate() {
            let Some(fmu) = self.instances[index].1.clone() else {
                continue;
            };
            let start = instance
                .start
                .iter()
                .filter_map(|(name, json)| {
                    let location = format!("instances[{index}].start[{name:?}]");
                    self.start_value(&instance.name, &fmu, name, json, &location, &connected)
                })
                .collect();
            instances.push(Instance { name: instance.name.clone(), fmu_alias: instance.fmu.clone(), fmu, start });
        }
        instances
    }

    /// The start value `json` of the variable `name` of `instance` (opened as `fmu`), if the
    /// variable exists, may be given a start value and `json` has its type.
    fn start_value(
        &mut self,
        instance: &str,
        fmu: &Fmu,
        name: &str,
        json: &serde_json::Value,
        location: &str,
        connected: &std::collections::BTreeSet<&str>,
    ) -> Option<(ScalarVariable, Value)> {
        let md = fmu.model_description();
        let settable: Vec<&str> = md
            .variables
            .iter()
            .filter(|v| v.is_settable_start() && !connected.contains(format!("{instance}.{}", v.name).as_str()))
            .map(|v| v.name.as_str())
            .collect();
        let message = match md.variable(name) {
            None => format!(
                "instance {instance:?} (model {:?}) has no variable {name:?}{}; settable variables: {}",
                md.model_name,
                did_you_mean(&closest(name, settable.iter().copied())),
                quoted_list(settable.iter().copied())
            ),
            Some(variable) if !variable.is_settable_start() => format!(
                "variable {name:?} of instance {instance:?} is {} {} {}{}; start values can be given for inputs and for non-constant variables with initial exact or approx: {}",
                article(variable.variability.as_str()),
                variable.variability,
                variable.causality,
                initial_note(variable),
                quoted_list(settable.iter().copied())
            ),
            Some(variable) => match start_value(variable, json) {
                Ok(value) => return Some((variable.clone(), value)),
                Err(message) => message,
            },
        };
        self.problem(location, message);
        None
    }

    /// The caller's start values ([`Overrides::start`]) on inputs a connection feeds: the
    /// connection overwrites them before the first step, so they would be ignored without a word.
    /// A system file's own start values on connected inputs stay allowed (the shipped full-scale
    /// systems give the cable's initial force and mass that way).
    fn connected_starts(&mut self, start: &[(String, serde_json::Value)], connections: &[Connection]) {
        for (name, _) in start {
            let Some(connection) = connections.iter().find(|c| c.to.qualified_name == *name) else {
                continue;
            };
            let message = format!(
                "{name} is fed by the connection {} -> {name}, which overwrites its start value before the \
                 first step: change what {} is computed from instead",
                connection.from.qualified_name, connection.from.qualified_name
            );
            self.problem(format!("Overrides::start[{name:?}]"), message);
        }
    }

    /// Connections from an output to an input of another instance, of the same ABI type.
    fn connections(&mut self, spec: &SystemSpec) -> Vec<Connection> {
        let mut connections = Vec::new();
        for (i, connection) in spec.connections.iter().enumerate() {
            let from = self.qualified(&connection.from, Role::Source, &format!("connections[{i}].from"));
            let location = format!("connections[{i}].to");
            let to = self.qualified(&connection.to, Role::Input, &location);
            let (Some(from), Some(to)) = (from, to) else {
                continue;
            };
            let (from_type, to_type) = (from.variable.variable_type.abi_type(), to.variable.variable_type.abi_type());
            if from_type != to_type {
                let message = format!(
                    "cannot connect {:?} ({from_type}) to {:?} ({to_type})",
                    from.qualified_name, to.qualified_name
                );
                self.problem(format!("connections[{i}]"), message);
                continue;
            }
            if from.instance == to.instance {
                self.problem(format!("connections[{i}]"), "an instance cannot feed its own inputs (algebraic loop)");
                continue;
            }
            self.feed(&to, &location);
            connections.push(Connection { from, to });
        }
        connections
    }

    /// Inputs files: each is read, and each of its columns names an input of its instance that
    /// nothing else feeds.
    fn inputs(&mut self, spec: &SystemSpec) -> Vec<BoundInput> {
        let mut inputs = Vec::new();
        for (i, input) in spec.inputs.iter().enumerate() {
            let location = format!("inputs[{i}]");
            let index = self.instance(&input.instance, &format!("{location}.instance"), "");
            let path = self.base.join(&input.file);
            let table = match SignalTable::read(&path) {
                Ok(table) => Arc::new(table),
                Err(error) => {
                    self.problem(format!("{location}.file"), error_chain(&error));
                    continue;
                }
            };
            let Some(index) = index else { continue };
            let Some(fmu) = self.instances[index].1.clone() else {
                continue;
            };
            let md = fmu.model_description();
            let mut columns = Vec::new();
            for (column, name) in table.names.iter().enumerate() {
                let column_location = format!("{location}.file ({}, column {name:?})", path.display());
                let Some(variable) = self.input_column(index, &table, column, name, &column_location) else {
                    continue;
                };
                let qualified_name = format!("{}.{name}", input.instance);
                let target = VariableRef { instance: index, qualified_name, variable: variable.clone() };
                self.feed(&target, &column_location);
                let position = md.variables.iter().position(|x| x.name == *name).unwrap_or(usize::MAX);
                columns.push((position, column, variable));
            }
            let derivatives = spec.input_derivatives && md.co_simulation.can_interpolate_inputs;
            let columns = columns.iter().map(|(position, column, variable)| (*position, *column, variable)).collect();
            let binding = InputBinding::new(Arc::clone(&table), columns, derivatives);
            inputs.push(BoundInput { instance: index, binding });
        }
        inputs
    }

    /// The input of instance `index` that `column` of `table` feeds, if its name resolves and its
    /// values fit its type (no strings; whole numbers for integers and Booleans).
    fn input_column(
        &mut self,
        index: usize,
        table: &SignalTable,
        column: usize,
        name: &str,
        location: &str,
    ) -> Option<ScalarVariable> {
        let variable = self.variable(index, name, Role::Input, location)?;
        let kind = variable.variable_type.abi_type();
        if kind == VariableType::String {
            self.problem(location, format!("String input {name:?} cannot be read from a CSV file"));
            return None;
        }
        if kind != VariableType::Real {
            if let Some(bad) = table.columns[column].iter().find(|x| !(x.is_finite() && x.abs() < 2.1e9)) {
                self.problem(location, format!("{kind} input {name:?} has the non-integer value {bad:?}"));
                return None;
            }
        }
        Some(variable)
    }

    /// The recorded variables: those `record.variables` lists (each once; a pattern expanded by
    /// [`Validator::matching`]), else every output of every instance; then those `added` names
    /// (the caller's, [`Overrides::record`]) that are not recorded yet. (Indices into
    /// `self.instances` equal indices into the resolved instances whenever no problem was found:
    /// an instance without an FMU is a problem.)
    fn recorded(&mut self, spec: &SystemSpec, added: &[String]) -> Vec<VariableRef> {
        let mut recorded: Vec<VariableRef> = match &spec.record.variables {
            None => self.every_output(),
            Some(names) => {
                let mut recorded: Vec<VariableRef> = Vec::new();
                for (i, name) in names.iter().enumerate() {
                    let location = format!("record.variables[{i}]");
                    if is_pattern(name) {
                        for variable in self.matching(name, &location) {
                            if !recorded.iter().any(|r| r.qualified_name == variable.qualified_name) {
                                recorded.push(variable);
                            }
                        }
                        continue;
                    }
                    let Some(variable) = self.qualified(name, Role::Recorded, &location) else {
                        continue;
                    };
                    if recorded.iter().any(|r| r.qualified_name == variable.qualified_name) {
                        self.problem(location, format!("{name:?} is listed twice"));
                    } else {
                        recorded.push(variable);
                    }
                }
                recorded
            }
        };
        for name in added {
            let location = format!("Overrides::record[{name:?}]");
            let variables = if is_pattern(name) {
                self.matching(name, &location)
            } else {
                self.qualified(name, Role::Recorded, &location).into_iter().collect()
            };
            for variable in variables {
                if !recorded.iter().any(|r| r.qualified_name == variable.qualified_name) {
                    recorded.push(variable);
                }
            }
        }
        recorded
    }

    /// The outputs and local variables whose qualified names (`instance.variable`) match
    /// `pattern`, in stepping and model-description order; a problem if there are none. A pattern
    /// never matches parameters, inputs or the independent variable: an exact name records them.
    fn matching(&mut self, pattern: &str, location: &str) -> Vec<VariableRef> {
        let Some((instance_pattern, _)) = pattern.split_once('.') else {
            self.problem(location, format!("{pattern:?} is not of the form \"<instance>.<variable>\""));
            return Vec::new();
        };
        if !is_pattern(instance_pattern) {
            self.instance(instance_pattern, location, &format!(" in {pattern:?}"));
        }
        let mut found = Vec::new();
        let (mut candidates, mut others) = (Vec::new(), Vec::new());
        for (index, (name, fmu)) in self.instances.iter().enumerate() {
            let Some(fmu) = fmu else { continue };
            for variable in &fmu.model_description().variables {
                let qualified_name = format!("{name}.{}", variable.name);
                let recordable = matches!(variable.causality, Causality::Output | Causality::Local);
                let matched = glob_matches(pattern, &qualified_name);
                if recordable && matched {
                    found.push(VariableRef { instance: index, qualified_name, variable: variable.clone() });
                } else if recordable {
                    candidates.push(qualified_name);
                } else if matched {
                    others.push(qualified_name);
                }
            }
        }
        let known_instance = is_pattern(instance_pattern) || self.instances.iter().any(|(n, _)| n == instance_pattern);
        if found.is_empty() && known_instance && self.instances.iter().all(|(_, fmu)| fmu.is_some()) {
            // The pattern with its wildcards left out reads like a name with a typo.
            let plain: String = pattern.chars().filter(|c| !matches!(c, '*' | '?')).collect();
            let mut message = format!(
                "pattern {pattern:?} matches no output or local variable{}",
                did_you_mean(&closest(&plain, candidates.iter().map(String::as_str)))
            );
            if !others.is_empty() {
                message.push_str(&format!(
                    "; it matches only parameters or inputs ({}), which are recorded when named exactly",
                    quoted_list(others.iter().map(String::as_str))
                ));
            }
            self.problem(location, message);
        }
        found
    }

    /// The inputs of instances whose FMU could be opened that nothing feeds and that have no
    /// start value in `spec`, qualified.
    fn unconnected_inputs(&self, spec: &SystemSpec) -> Vec<String> {
        let mut unconnected = Vec::new();
        for (index, (name, fmu)) in self.instances.iter().enumerate() {
            let Some(fmu) = fmu else { continue };
            let start = spec.instances.get(index).map(|i| &i.start);
            for variable in fmu.model_description().variables_with(Causality::Input) {
                let key = (index, variable.value_reference, variable.variable_type.abi_type());
                let started = start.is_some_and(|start| start.contains_key(&variable.name));
                if !self.fed.contains_key(&key) && !started {
                    unconnected.push(format!("{name}.{}", variable.name));
                }
            }
        }
        unconnected
    }

    /// The caller's input tables ([`Overrides::inputs`]): columns named `instance.variable`, each
    /// feeding an input that nothing else feeds; one binding per instance, sharing the table.
    fn qualified_inputs(&mut self, spec: &SystemSpec, files: &[PathBuf]) -> Vec<BoundInput> {
        let mut inputs = Vec::new();
        for file in files {
            let location = format!("Overrides::inputs[{:?}]", file.display().to_string());
            let table = match SignalTable::read(file) {
                Ok(table) => Arc::new(table),
                Err(error) => {
                    self.problem(location, error_chain(&error));
                    continue;
                }
            };
            // Instance index → (model-description position, column, variable).
            let mut columns: BTreeMap<usize, Vec<(usize, usize, ScalarVariable)>> = BTreeMap::new();
            for (column, name) in table.names.iter().enumerate() {
                let column_location = format!("{location} (column {name:?})");
                let Some((instance, variable)) = name.split_once('.') else {
                    self.problem(column_location, format!("{name:?} is not of the form \"<instance>.<input>\""));
                    continue;
                };
                let Some(index) = self.instance(instance, &column_location, &format!(" in {name:?}")) else {
                    continue;
                };
                let Some(fmu) = self.instances[index].1.clone() else { continue };
                let Some(resolved) = self.input_column(index, &table, column, variable, &column_location) else {
                    continue;
                };
                let target = VariableRef { instance: index, qualified_name: name.clone(), variable: resolved.clone() };
                self.feed(&target, &column_location);
                let md = fmu.model_description();
                let position = md.variables.iter().position(|x| x.name == variable).unwrap_or(usize::MAX);
                columns.entry(index).or_default().push((position, column, resolved));
            }
            for (index, columns) in columns {
                let Some(fmu) = &self.instances[index].1 else { continue };
                let derivatives =
                    spec.input_derivatives && fmu.model_description().co_simulation.can_interpolate_inputs;
                let columns =
                    columns.iter().map(|(position, column, variable)| (*position, *column, variable)).collect();
                let binding = InputBinding::new(Arc::clone(&table), columns, derivatives);
                inputs.push(BoundInput { instance: index, binding });
            }
        }
        inputs
    }

    /// Every output of every instance whose FMU could be opened, in stepping order.
    fn every_output(&self) -> Vec<VariableRef> {
        let mut recorded = Vec::new();
        for (index, (name, fmu)) in self.instances.iter().enumerate() {
            let Some(fmu) = fmu else { continue };
            for variable in fmu.model_description().variables_with(Causality::Output) {
                let qualified_name = format!("{name}.{}", variable.name);
                recorded.push(VariableRef { instance: index, qualified_name, variable: variable.clone() });
            }
        }
        recorded
    }
}

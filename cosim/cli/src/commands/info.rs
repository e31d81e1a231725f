//! `crane-cosim info`: an FMU's model description as a table or as JSON.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use fmu_import::describe::{describe_with, platforms};
use fmu_import::fmu::{Causality, ExtractLimits, Fmu, ScalarVariable};
use fmu_import::value::Value as Start;
use serde_json::{json, Value};

/// Arguments of `crane-cosim info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The .fmu file.
    pub fmu: PathBuf,
    /// Print the model description as one JSON object (header, flags, platforms, variables).
    #[arg(long)]
    pub json: bool,
    /// List only variables of this causality (repeat or separate with commas for several).
    #[arg(long, value_name = "CAUSALITY", value_delimiter = ',', value_parser = causality)]
    pub causality: Vec<Causality>,
    /// Wrap the descriptions so that lines stay within N characters (0: never wrap).
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub width: usize,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// Prints the description of one FMU.
pub fn info(args: &InfoArgs, limits: &ExtractLimits) -> Result<()> {
    let fmu = Fmu::open(&args.fmu, limits)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&as_json(&fmu, &args.causality))?)?;
    } else {
        let width = (args.width > 0).then_some(args.width);
        write!(out, "{}", describe_with(&fmu, &args.causality, width))?;
    }
    Ok(())
}

fn causality(text: &str) -> Result<Causality, String> {
    text.parse().map_err(|()| format!("'{text}' is not a causality: one of {}", Causality::KEYWORDS.join(", ")))
}

/// The same facts as the table, with the attributes' names of the model description.
fn as_json(fmu: &Fmu, causalities: &[Causality]) -> Value {
    let md = fmu.model_description();
    let cs = &md.co_simulation;
    let variables: Vec<Value> = md
        .variables
        .iter()
        .filter(|v| causalities.is_empty() || causalities.contains(&v.causality))
        .map(variable_json)
        .collect();
    json!({
        "fmiVersion": md.fmi_version,
        "modelName": md.model_name,
        "guid": md.guid,
        "description": md.description,
        "generationTool": md.generation_tool,
        "modelIdentifier": cs.model_identifier,
        "platforms": platforms(fmu),
        "coSimulation": {
            "canHandleVariableCommunicationStepSize": cs.can_handle_variable_communication_step_size,
            "canInterpolateInputs": cs.can_interpolate_inputs,
            "maxOutputDerivativeOrder": cs.max_output_derivative_order,
            "canGetAndSetFMUstate": cs.can_get_and_set_fmu_state,
            "canSerializeFMUstate": cs.can_serialize_fmu_state,
            "canBeInstantiatedOnlyOncePerProcess": cs.can_be_instantiated_only_once_per_process,
            "needsExecutionTool": cs.needs_execution_tool,
        },
        "defaultExperiment": md.default_experiment.map(|e| json!({
            "startTime": e.start_time,
            "stopTime": e.stop_time,
            "tolerance": e.tolerance,
            "stepSize": e.step_size,
        })),
        "variables": variables,
    })
}

fn variable_json(v: &ScalarVariable) -> Value {
    let text = |s: &Option<String>| s.clone().map_or(Value::Null, Value::String);
    json!({
        "name": v.name,
        "valueReference": v.value_reference,
        "causality": v.causality.as_str(),
        "variability": v.variability.as_str(),
        "initial": v.initial.map(|i| i.as_str()),
        "type": v.variable_type.to_string(),
        "start": start_json(v),
        "min": text(&v.range.0),
        "max": text(&v.range.1),
        "unit": text(&v.unit),
        "description": text(&v.description),
    })
}

/// The start value as a JSON number, boolean or string (null when there is none).
fn start_json(v: &ScalarVariable) -> Value {
    match &v.start {
        None => Value::Null,
        Some(Start::Real(x)) => json!(x),
        Some(Start::Integer(i)) => json!(i),
        Some(Start::Boolean(b)) => json!(b),
        Some(Start::String(s)) => json!(s),
    }
}

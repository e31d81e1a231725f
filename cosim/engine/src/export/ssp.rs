//! An SSP 1.0 archive: `SystemStructure.ssd` and the FMUs under `resources/`.
//!
//! The system structure holds one `ssd:Component` per instance (in stepping order) with a
//! typed `ssd:Connector` for every input, output and (calculated) parameter of its FMU, its
//! start values as an inline `ssd:ParameterBinding`, an `ssd:Connection` per connection, and the
//! `ssd:DefaultExperiment` (start and stop time). The step size, which SSP has no field for, is
//! given in the annotations of three importers: libcosim's `osp:FixedStepAlgorithm`,
//! OMSimulator's `oms:FixedStepMaster` and our own `cc:Master`, which also carries the
//! algorithm, the input derivatives and the recorded variables (see
//! [`crate::system::ssp`], which reads it back).

use std::io::Write;
use std::path::Path;

use fmu_import::fmu::Causality;
use fmu_import::value::VariableType;
use zip::write::SimpleFileOptions;
use zip::CompressionMethod;

use super::xml::{double, typed_value, Xml};
use super::{fmu_files, refuse_input_files, system_name, write_error, ExportError};
use crate::system::ssp::{
    ANNOTATION_TYPE, CRANE_COSIM, FMU_MIME_TYPE, OMS, OMS_TYPE, OSP, OSP_TYPE, SSC, SSD, SSD_FILE, SSV,
};
use crate::system::{Instance, RecordSpec, System};

/// Where the FMU of `alias` is stored in the archive.
pub fn fmu_entry(alias: &str) -> String {
    format!("resources/{alias}.fmu")
}

/// Writes the archive `path`: [`system_structure`] and every FMU the instances use.
pub fn write(system: &System, path: &Path) -> Result<(), ExportError> {
    let ssd = system_structure(system)?;
    let zip_error = |source| ExportError::Zip { path: path.to_path_buf(), source };
    let file = std::fs::File::create(path).map_err(write_error(path))?;
    let mut archive = zip::ZipWriter::new(file);
    // The FMUs are ZIP archives already: stored as they are.
    let stored = SimpleFileOptions::default().compression_method(CompressionMethod::Stored);
    archive.start_file(SSD_FILE, SimpleFileOptions::default()).map_err(zip_error)?;
    archive.write_all(ssd.as_bytes()).map_err(write_error(path))?;
    for (alias, source) in fmu_files(system) {
        let bytes = std::fs::read(source).map_err(write_error(source))?;
        archive.start_file(fmu_entry(alias), stored).map_err(zip_error)?;
        archive.write_all(&bytes).map_err(write_error(path))?;
    }
    archive.finish().map_err(zip_error)?;
    Ok(())
}

/// The text of `SystemStructure.ssd`.
pub fn system_structure(system: &System) -> Result<String, ExportError> {
    refuse_input_files(system)?;
    let name = system_name(system);
    let step = double(system.spec.step_size);
    let mut xml = Xml::new();
    xml.open(
        "ssd:SystemStructureDescription",
        &[
            ("xmlns:ssd", SSD),
            ("xmlns:ssc", SSC),
            ("xmlns:ssv", SSV),
            ("xmlns:osp", OSP),
            ("xmlns:oms", OMS),
            ("xmlns:cc", CRANE_COSIM),
            ("version", "1.0"),
            ("name", &name),
            ("generationTool", concat!("crane-cosim ", env!("CARGO_PKG_VERSION"))),
        ],
    );
    xml.open("ssd:System", &[("name", &name), ("description", &system.spec.description)]);
    xml.open("ssd:Elements", &[]);
    for instance in &system.instances {
        component(&mut xml, instance);
    }
    xml.close("ssd:Elements");
    xml.open("ssd:Connections", &[]);
    for connection in &system.connections {
        let (from, to) = (&connection.from, &connection.to);
        xml.empty(
            "ssd:Connection",
            &[
                ("startElement", &system.instances[from.instance].name),
                ("startConnector", &from.variable.name),
                ("endElement", &system.instances[to.instance].name),
                ("endConnector", &to.variable.name),
            ],
        );
    }
    xml.close("ssd:Connections");
    // OMSimulator reads its step size from the system's annotation.
    xml.open("ssd:Annotations", &[]);
    xml.open("ssc:Annotation", &[("type", OMS_TYPE)]);
    xml.open("oms:Annotations", &[]);
    xml.open("oms:SimulationInformation", &[]);
    xml.empty("oms:FixedStepMaster", &[("description", "oms-ma"), ("stepSize", &step)]);
    xml.close("oms:SimulationInformation");
    xml.close("oms:Annotations");
    xml.close("ssc:Annotation");
    xml.close("ssd:Annotations");
    xml.close("ssd:System");
    default_experiment(&mut xml, system, &step);
    xml.close("ssd:SystemStructureDescription");
    xml.finish().map_err(|(text, source)| ExportError::Text { file: system.file.clone(), text, source })
}

fn component(xml: &mut Xml, instance: &Instance) {
    let source = fmu_entry(&instance.fmu_alias);
    xml.open(
        "ssd:Component",
        &[("name", &instance.name), ("type", FMU_MIME_TYPE), ("source", &source), ("implementation", "CoSimulation")],
    );
    xml.open("ssd:Connectors", &[]);
    for variable in &instance.fmu.model_description().variables {
        let Some(kind) = connector_kind(variable.causality) else { continue };
        let connector = [("name", variable.name.as_str()), ("kind", kind)];
        match connector_type(variable.variable_type) {
            Some(element) => xml.wrapped("ssd:Connector", &connector, element, &[]),
            None => xml.empty("ssd:Connector", &connector),
        }
    }
    xml.close("ssd:Connectors");
    if !instance.start.is_empty() {
        xml.open("ssd:ParameterBindings", &[]);
        xml.open("ssd:ParameterBinding", &[]);
        xml.open("ssd:ParameterValues", &[]);
        xml.open("ssv:ParameterSet", &[("version", "1.0"), ("name", &instance.name)]);
        xml.open("ssv:Parameters", &[]);
        for (variable, value) in &instance.start {
            let (element, text) = typed_value(value);
            xml.wrapped("ssv:Parameter", &[("name", &variable.name)], &format!("ssv:{element}"), &[("value", &text)]);
        }
        xml.close("ssv:Parameters");
        xml.close("ssv:ParameterSet");
        xml.close("ssd:ParameterValues");
        xml.close("ssd:ParameterBinding");
        xml.close("ssd:ParameterBindings");
    }
    xml.close("ssd:Component");
}

/// The SSP connector kind of a variable the component exposes (locals and the independent
/// variable are not exposed).
fn connector_kind(causality: Causality) -> Option<&'static str> {
    match causality {
        Causality::Input => Some("input"),
        Causality::Output => Some("output"),
        Causality::Parameter => Some("parameter"),
        Causality::CalculatedParameter => Some("calculatedParameter"),
        Causality::Local | Causality::Independent => None,
    }
}

/// The `ssc:` type element of a connector. Enumerations get none: SSP's `ssc:Enumeration`
/// must name an `ssd:Enumerations` entry, and without a type element the FMU's declaration
/// applies.
fn connector_type(variable_type: VariableType) -> Option<&'static str> {
    match variable_type {
        VariableType::Real => Some("ssc:Real"),
        VariableType::Integer => Some("ssc:Integer"),
        VariableType::Boolean => Some("ssc:Boolean"),
        VariableType::String => Some("ssc:String"),
        VariableType::Enumeration => None,
    }
}

/// Start and stop time, libcosim's step size and our own settings (`cc:Master`).
fn default_experiment(xml: &mut Xml, system: &System, step: &str) {
    let spec = &system.spec;
    let (start, stop) = (double(spec.start_time), double(spec.stop_time));
    xml.open("ssd:DefaultExperiment", &[("startTime", &start), ("stopTime", &stop)]);
    xml.open("ssd:Annotations", &[]);
    xml.open("ssc:Annotation", &[("type", OSP_TYPE)]);
    xml.open("osp:Algorithm", &[]);
    xml.empty("osp:FixedStepAlgorithm", &[("baseStepSize", step)]);
    xml.close("osp:Algorithm");
    xml.close("ssc:Annotation");
    xml.open("ssc:Annotation", &[("type", ANNOTATION_TYPE)]);
    // The name a system file uses (serde's), which the reader parses back.
    let algorithm = serde_json::to_value(spec.algorithm).ok();
    let algorithm = algorithm.as_ref().and_then(|a| a.as_str()).unwrap_or_default();
    let derivatives = spec.input_derivatives.to_string();
    // An annotation holds one element (SSP 1.0 schema): the recording is inside `cc:Master`.
    let master = [("stepSize", step), ("algorithm", algorithm), ("inputDerivatives", derivatives.as_str())];
    let record = &spec.record;
    if record.interval.is_none() && record.variables.is_none() {
        xml.empty("cc:Master", &master);
    } else {
        xml.open("cc:Master", &master);
        write_record(xml, record);
        xml.close("cc:Master");
    }
    xml.close("ssc:Annotation");
    xml.close("ssd:Annotations");
    xml.close("ssd:DefaultExperiment");
}

/// `cc:Record`, for a system that chooses what to record (by default every output is); the
/// variables, when chosen, are listed in `cc:Variables`.
fn write_record(xml: &mut Xml, record: &RecordSpec) {
    let interval = record.interval.map(double);
    let attributes: Vec<(&str, &str)> = interval.iter().map(|i| ("interval", i.as_str())).collect();
    match &record.variables {
        Some(variables) => {
            xml.open("cc:Record", &attributes);
            xml.open("cc:Variables", &[]);
            for variable in variables {
                xml.empty("cc:Variable", &[("name", variable)]);
            }
            xml.close("cc:Variables");
            xml.close("cc:Record");
        }
        None => xml.empty("cc:Record", &attributes),
    }
}

//! An OSP system structure (`OspSystemStructure.xml`, libcosim's own format) beside copies of
//! the FMUs: the same instances, start values and connections, stepped by libcosim's fixed-step
//! algorithm (Jacobi: every instance steps, then all outputs are transferred). OSP has no stop
//! time: libcosim runs until it is told to stop. [`crate::system::osp`] reads it back.

use std::path::{Path, PathBuf};

use super::xml::{double, typed_value, Xml};
use super::{fmu_files, refuse_input_files, write_error, ExportError};
use crate::system::System;

/// The file name libcosim looks for in a folder.
pub use crate::system::osp::FILE;

/// Copies every FMU into the folder `dir` (created if missing) as `<alias>.fmu` and writes
/// [`FILE`] with sources relative to it; returns the path of that file.
pub fn write(system: &System, dir: &Path) -> Result<PathBuf, ExportError> {
    let xml = system_structure(system)?;
    std::fs::create_dir_all(dir).map_err(write_error(dir))?;
    for (alias, source) in fmu_files(system) {
        let copy = dir.join(fmu_file(alias));
        std::fs::copy(source, &copy).map_err(write_error(&copy))?;
    }
    let file = dir.join(FILE);
    std::fs::write(&file, xml).map_err(write_error(&file))?;
    Ok(file)
}

/// The file name of the FMU of `alias` beside the system structure.
fn fmu_file(alias: &str) -> String {
    format!("{alias}.fmu")
}

/// The text of [`FILE`], with each FMU's source as written by [`write()`].
pub fn system_structure(system: &System) -> Result<String, ExportError> {
    refuse_input_files(system)?;
    let mut xml = Xml::new();
    xml.open("OspSystemStructure", &[("xmlns", crate::system::osp::NAMESPACE), ("version", "0.1")]);
    xml.text_element("StartTime", &double(system.spec.start_time));
    xml.text_element("BaseStepSize", &double(system.spec.step_size));
    xml.text_element("Algorithm", "fixedStep");
    xml.open("Simulators", &[]);
    for instance in &system.instances {
        xml.open("Simulator", &[("name", &instance.name), ("source", &fmu_file(&instance.fmu_alias))]);
        xml.open("InitialValues", &[]);
        for (variable, value) in &instance.start {
            let (element, text) = typed_value(value);
            xml.wrapped("InitialValue", &[("variable", &variable.name)], element, &[("value", &text)]);
        }
        xml.close("InitialValues");
        xml.close("Simulator");
    }
    xml.close("Simulators");
    xml.open("Connections", &[]);
    for connection in &system.connections {
        xml.open("VariableConnection", &[]);
        for end in [&connection.from, &connection.to] {
            let instance = &system.instances[end.instance].name;
            xml.empty("Variable", &[("simulator", instance), ("name", &end.variable.name)]);
        }
        xml.close("VariableConnection");
    }
    xml.close("Connections");
    xml.close("OspSystemStructure");
    xml.finish().map_err(|(text, source)| ExportError::Text { file: system.file.clone(), text, source })
}

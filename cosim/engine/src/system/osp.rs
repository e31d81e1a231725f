//! OSP system structures (`OspSystemStructure.xml`, libcosim's own format) as system files: what
//! [`crate::export::osp`] writes, read back.
//!
//! The reader understands the subset crane-cosim writes:
//! * `StartTime` and `BaseStepSize` → the time grid (OSP has no stop time: [`Overrides::stop_time`]
//!   gives it; [`Overrides::step_size`] a missing step);
//! * `Algorithm` `fixedStep` (libcosim's, which steps every simulator, then transfers all
//!   outputs) → Jacobi, without input derivatives;
//! * `Simulator` (`source` relative to the file's folder) → an instance, in document order; its
//!   `InitialValue`s (`Real`, `Integer`, `Boolean`, `String`) → start values;
//! * `VariableConnection` (the first `Variable` the output, the second the input) → a connection.
//!
//! Every output is recorded at every step. Signal and group connections, functions and a
//! simulator's own step size other than the base step are refused with the element's location.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use roxmltree::{Document, Node};

use super::schema::{ConnectionSpec, InstanceSpec, RecordSpec, SystemSpec};
use super::ssp::{fmu_alias, typed_start_value, XmlReader};
use super::{AlgorithmKind, FileKind, Overrides, ParseError, Problem, SystemError};

/// The file name libcosim looks for in a folder.
pub const FILE: &str = "OspSystemStructure.xml";
/// The namespace of its elements.
pub const NAMESPACE: &str = "http://opensimulationplatform.com/MSMI/OSPSystemStructure";
/// The only algorithm libcosim has.
pub const FIXED_STEP: &str = "fixedStep";

/// Whether `text` looks like XML (its first non-blank character is `<`) rather than JSON.
pub fn is_xml(text: &str) -> bool {
    text.trim_start_matches('\u{feff}').trim_start().starts_with('<')
}

/// Reads the XML text of `file` as an OSP system structure (its FMU sources stay relative to its
/// folder). XML of another kind is refused saying what it is.
pub fn parse(file: &Path, text: &str, overrides: &Overrides) -> Result<SystemSpec, SystemError> {
    let document = Document::parse(text).map_err(|error| SystemError::Parse {
        file: file.to_path_buf(),
        error: ParseError {
            kind: FileKind::Osp,
            syntax: Some("XML"),
            line: error.pos().row as usize,
            column: error.pos().col as usize,
            message: error.to_string(),
        },
    })?;
    let root = document.root_element();
    if root.tag_name().name() != "OspSystemStructure" {
        return Err(SystemError::Kind { file: file.to_path_buf(), found: xml_kind(root) });
    }
    let mut reader = Reader { problems: Vec::new() };
    let spec = reader.system_structure(root, overrides);
    if reader.problems.is_empty() {
        Ok(spec)
    } else {
        Err(SystemError::Invalid { file: file.to_path_buf(), problems: reader.problems })
    }
}

/// What an XML document of another kind is, from its root element.
fn xml_kind(root: Node) -> String {
    match root.tag_name().name() {
        "SystemStructureDescription" => {
            "an SSP system structure (SystemStructure.ssd) outside its archive: pack it with its FMUs into an .ssp \
             archive"
                .into()
        }
        "fmiModelDescription" => "an FMU's model description (modelDescription.xml), not an FMU".into(),
        other => format!("XML whose root element is <{other}>"),
    }
}

fn children<'a, 'i>(node: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |n| n.is_element() && n.tag_name().name() == name)
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &'a str) -> Option<Node<'a, 'i>> {
    children(node, name).next()
}

struct Reader {
    problems: Vec<Problem>,
}

impl XmlReader for Reader {
    fn document(&self) -> &str {
        FILE
    }

    fn problems(&mut self) -> &mut Vec<Problem> {
        &mut self.problems
    }
}

impl Reader {
    /// The number in the text of the child element `name`, if there is one.
    fn number(&mut self, parent: Node, name: &str) -> Option<f64> {
        let element = child(parent, name)?;
        let text = element.text().unwrap_or_default().trim();
        let value = parse_double(text);
        if value.is_none() {
            self.problem(element, format!("\"{text}\" is not a number"));
        }
        value
    }

    fn system_structure(&mut self, root: Node, overrides: &Overrides) -> SystemSpec {
        for name in ["Functions"] {
            for found in children(root, name) {
                self.problem(found, format!("{name} are not supported"));
            }
        }
        let start_time = self.number(root, "StartTime").unwrap_or(0.0);
        let step_size = match self.number(root, "BaseStepSize").or(overrides.step_size) {
            Some(step) => step,
            None => {
                self.problem(root, "no BaseStepSize (or pass Overrides::step_size)");
                f64::NAN
            }
        };
        let stop_time = match overrides.stop_time {
            Some(stop) => stop,
            None => {
                self.problem(root, "an OSP system structure has no stop time: pass Overrides::stop_time");
                f64::NAN
            }
        };
        if let Some(algorithm) = child(root, "Algorithm") {
            let name = algorithm.text().unwrap_or_default().trim();
            if name != FIXED_STEP {
                self.problem(algorithm, format!("unknown algorithm \"{name}\": expected {FIXED_STEP}"));
            }
        }
        let mut fmus = BTreeMap::new();
        let simulators: Vec<_> = children(root, "Simulators").flat_map(|s| children(s, "Simulator")).collect();
        let instances = simulators.into_iter().filter_map(|s| self.simulator(s, step_size, &mut fmus)).collect();
        let mut connections = Vec::new();
        for list in children(root, "Connections").collect::<Vec<_>>() {
            for connection in list.children().filter(Node::is_element) {
                if connection.tag_name().name() == "VariableConnection" {
                    connections.extend(self.connection(connection));
                } else {
                    let name = connection.tag_name().name();
                    self.problem(connection, format!("{name}s are not supported (only VariableConnection)"));
                }
            }
        }
        SystemSpec {
            description: String::new(),
            fmus,
            instances,
            connections,
            inputs: Vec::new(),
            start_time,
            stop_time,
            step_size,
            algorithm: AlgorithmKind::Jacobi,
            input_derivatives: false,
            extrapolate_inputs: false,
            record: RecordSpec::default(),
        }
    }

    /// A simulator as an instance; its FMU gets an alias (the file stem) in `fmus`.
    fn simulator(
        &mut self,
        element: Node,
        base_step: f64,
        fmus: &mut BTreeMap<String, PathBuf>,
    ) -> Option<InstanceSpec> {
        let name = self.attribute(element, "name")?.to_string();
        let source = self.attribute(element, "source")?;
        if source.contains("://") || source.starts_with("file:") {
            self.problem(element, format!("source=\"{source}\": only file paths are supported, not URIs"));
            return None;
        }
        if let Some(step) = element.attribute("stepSize") {
            if parse_double(step) != Some(base_step) {
                self.problem(element, format!("stepSize=\"{step}\": only the BaseStepSize is supported"));
            }
        }
        // Relative to the folder, which validation resolves it against.
        let alias = fmu_alias(fmus, Path::new(source));
        let mut start = BTreeMap::new();
        let values: Vec<_> = children(element, "InitialValues").flat_map(|v| children(v, "InitialValue")).collect();
        for value in values {
            let Some(variable) = self.attribute(value, "variable") else { continue };
            if let Some(typed) = self.initial_value(value) {
                start.insert(variable.to_string(), typed);
            }
        }
        Some(InstanceSpec { name, fmu: alias, start })
    }

    /// `Real`, `Integer`, `Boolean` or `String` as a JSON start value.
    fn initial_value(&mut self, value: Node) -> Option<serde_json::Value> {
        let Some(typed) = value.children().find(Node::is_element) else {
            self.problem(value, "no Real, Integer, Boolean or String value");
            return None;
        };
        let text = self.attribute(typed, "value")?;
        let kind = typed.tag_name().name();
        let Some(parsed) = typed_start_value(kind, text, parse_double) else {
            self.problem(typed, format!("{kind} values are not supported"));
            return None;
        };
        if parsed.is_none() {
            self.problem(typed, format!("value=\"{text}\" is not a finite {kind}"));
        }
        parsed
    }

    fn connection(&mut self, connection: Node) -> Option<ConnectionSpec> {
        let ends: Vec<_> = children(connection, "Variable").collect();
        let [from, to] = ends.as_slice() else {
            self.problem(connection, format!("expected two Variable elements, found {}", ends.len()));
            return None;
        };
        let mut end = |node: Node| -> Option<String> {
            let simulator = self.attribute(node, "simulator")?;
            let name = self.attribute(node, "name")?;
            Some(format!("{simulator}.{name}"))
        };
        let (from, to) = (end(*from), end(*to));
        Some(ConnectionSpec { from: from?, to: to? })
    }
}

/// An `xs:double` as [`crate::export`] writes it (also `INF`, `-INF`, `NaN`).
fn parse_double(text: &str) -> Option<f64> {
    match text.trim() {
        "INF" => Some(f64::INFINITY),
        "-INF" => Some(f64::NEG_INFINITY),
        "NaN" => Some(f64::NAN),
        other => other.parse().ok(),
    }
}

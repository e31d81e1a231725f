//! SSP 1.0 archives (`.ssp`) as system files.
//!
//! An archive holds `SystemStructure.ssd` and the FMUs it references (usually under
//! `resources/`). The reader understands one flat system of FMU components:
//! * `ssd:Component` (`source` inside the archive, Co-Simulation) → an instance, in document
//!   order (the Gauss–Seidel order);
//! * `ssd:ParameterBinding`, inline (`ssd:ParameterValues`) or in an `.ssv` file → start values;
//! * `ssd:Connection` between two components → a connection;
//! * `ssd:DefaultExperiment` `startTime`/`stopTime` → the time grid.
//!
//! SSP has no standard field for the communication step or the co-simulation algorithm. The step
//! size is read, in this order, from our own annotation (below), libcosim's
//! (`com.opensimulationplatform`: `osp:FixedStepAlgorithm baseStepSize`) and OMSimulator's
//! (`org.openmodelica`: `oms:FixedStepMaster stepSize`); [`Overrides::step_size`] and [`Overrides::stop_time`] fill in
//! what an archive lacks. Our annotation (type [`ANNOTATION_TYPE`], namespace
//! [`CRANE_COSIM`]) in the `ssd:DefaultExperiment` carries what only crane-cosim uses:
//!
//! ```xml
//! <ssc:Annotation type="crane-cosim">
//!   <cc:Master stepSize="0.01" algorithm="gauss-seidel" inputDerivatives="true">
//!     <cc:Record interval="0.01">
//!       <cc:Variables><cc:Variable name="pendulum.theta_x"/></cc:Variables>
//!     </cc:Record>
//!   </cc:Master>
//! </ssc:Annotation>
//! ```
//!
//! Without it the system-file defaults apply (Gauss–Seidel, no input derivatives, every output
//! recorded; `cc:Record` is left out then). Nested systems, system connectors, parameter mappings and connection
//! transformations are refused with the element's location.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use fmu_import::fmu::{extract_within, safe_relative_path, ExtractLimits};
use roxmltree::{Document, Node};

use super::read::read_system_text;
use super::schema::{ConnectionSpec, InstanceSpec, RecordSpec, SystemSpec};
use super::{AlgorithmKind, FileKind, Overrides, ParseError, Problem, SystemError};

/// SSP 1.0 namespaces (the prefixes `ssd`, `ssc`, `ssv` are also what libcosim expects).
pub const SSD: &str = "http://ssp-standard.org/SSP1/SystemStructureDescription";
pub const SSC: &str = "http://ssp-standard.org/SSP1/SystemStructureCommon";
pub const SSV: &str = "http://ssp-standard.org/SSP1/SystemStructureParameterValues";
/// libcosim's annotation namespace (prefix `osp`) and type.
pub const OSP: &str = "http://opensimulationplatform.com/SSP/OSPAnnotations";
pub const OSP_TYPE: &str = "com.opensimulationplatform";
/// OMSimulator's annotation namespace (prefix `oms`) and type.
pub const OMS: &str = "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd";
pub const OMS_TYPE: &str = "org.openmodelica";
/// Our annotation namespace (prefix `cc`) and type.
pub const CRANE_COSIM: &str = "urn:crane-cosim:ssp:1";
pub const ANNOTATION_TYPE: &str = "crane-cosim";
/// The system structure file at the root of an archive.
pub const SSD_FILE: &str = "SystemStructure.ssd";
/// `type` of an FMU component.
pub const FMU_MIME_TYPE: &str = "application/x-fmu-sharedlibrary";

/// True if `file` names an SSP archive (by its `.ssp` extension).
pub fn is_ssp(file: &Path) -> bool {
    file.extension().is_some_and(|e| e.eq_ignore_ascii_case("ssp"))
}

/// Extracts the archive `file` (within `limits`) into a temporary folder, deleted when the
/// returned handle is dropped: the first step of loading an archive ([`parse`] is the second).
pub fn extract(file: &Path, limits: &ExtractLimits) -> Result<tempfile::TempDir, SystemError> {
    let directory = tempfile::Builder::new()
        .prefix("ssp-")
        .tempdir()
        .map_err(|source| SystemError::Read { file: file.to_path_buf(), source })?;
    extract_within(file, directory.path(), limits)
        .map_err(|source| SystemError::Archive { file: file.to_path_buf(), source })?;
    Ok(directory)
}

/// Reads the system structure of the archive `file` extracted to `directory`; the FMU paths of
/// the result are relative to `directory`. `overrides` supply the stop time and step size when
/// the archive has none (SSP has no standard field for the step), so that their absence is a
/// problem only when nothing gives them.
pub fn parse(file: &Path, directory: &Path, overrides: &Overrides) -> Result<SystemSpec, SystemError> {
    let ssd_path = directory.join(SSD_FILE);
    if !ssd_path.is_file() {
        let problem = Problem { location: SSD_FILE.into(), message: "the archive has no such file at its root".into() };
        return Err(SystemError::Invalid { file: file.to_path_buf(), problems: vec![problem] });
    }
    let text = read_system_text(&ssd_path).map_err(|source| SystemError::Read { file: file.to_path_buf(), source })?;
    let mut reader = Reader { file, directory, document: SSD_FILE.into(), problems: Vec::new() };
    let spec = reader.system_structure(&text, overrides)?;
    if reader.problems.is_empty() {
        Ok(spec)
    } else {
        Err(SystemError::Invalid { file: file.to_path_buf(), problems: reader.problems })
    }
}

struct Reader<'a> {
    file: &'a Path,
    directory: &'a Path,
    /// The file being read inside the archive: the SSD or a parameter values file.
    document: String,
    problems: Vec<Problem>,
}

/// Where an element of `document` is, e.g.
/// `SystemStructure.ssd:ssd:SystemStructureDescription[s]/ssd:System[s]/ssd:Elements/ssd:Component[crane]`.
pub(super) fn location(document: &str, node: Node) -> String {
    let mut parts: Vec<String> = node
        .ancestors()
        .filter(|n| n.is_element())
        .map(|n| {
            let name = n.tag_name().name();
            let prefix = n.lookup_prefix(n.tag_name().namespace().unwrap_or_default()).unwrap_or_default();
            let tag = if prefix.is_empty() { name.to_string() } else { format!("{prefix}:{name}") };
            match n.attribute("name") {
                Some(instance) => format!("{tag}[{instance}]"),
                None => tag,
            }
        })
        .collect();
    parts.reverse();
    format!("{document}:{}", parts.join("/"))
}

fn children<'a, 'i>(node: Node<'a, 'i>, namespace: &'a str, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |n| n.has_tag_name((namespace, name)))
}

fn child<'a, 'i>(node: Node<'a, 'i>, namespace: &'a str, name: &'a str) -> Option<Node<'a, 'i>> {
    children(node, namespace, name).next()
}

/// The `ssc:Annotation` children of `node`'s `ssd:Annotations` with the given `type`.
fn annotations<'a, 'i>(node: Node<'a, 'i>, kind: &'a str) -> impl Iterator<Item = Node<'a, 'i>> {
    children(node, SSD, "Annotations")
        .flat_map(|a| children(a, SSC, "Annotation"))
        .filter(move |a| a.attribute("type") == Some(kind))
}

/// The first element `path` (namespace, name pairs) below an annotation of type `kind`.
fn annotated<'a, 'i>(node: Node<'a, 'i>, kind: &'a str, path: &[(&'a str, &'a str)]) -> Option<Node<'a, 'i>> {
    annotations(node, kind).find_map(|annotation| {
        path.iter().try_fold(annotation, |parent, &(namespace, name)| child(parent, namespace, name))
    })
}

/// What the SSP and OSP readers share: the problems they find, each located in the document
/// being read.
pub(super) trait XmlReader {
    /// The document's name in the problems' locations.
    fn document(&self) -> &str;

    fn problems(&mut self) -> &mut Vec<Problem>;

    fn problem(&mut self, node: Node, message: impl Into<String>) {
        let location = location(self.document(), node);
        self.problems().push(Problem { location, message: message.into() });
    }

    /// A required attribute, or a problem naming it.
    fn attribute<'n>(&mut self, node: Node<'n, '_>, name: &str) -> Option<&'n str> {
        let value = node.attribute(name);
        if value.is_none() {
            self.problem(node, format!("missing attribute '{name}'"));
        }
        value
    }
}

impl XmlReader for Reader<'_> {
    fn document(&self) -> &str {
        &self.document
    }

    fn problems(&mut self) -> &mut Vec<Problem> {
        &mut self.problems
    }
}

impl Reader<'_> {
    /// An optional number attribute; a problem if it is not a number.
    fn number(&mut self, node: Node, name: &str) -> Option<f64> {
        let text = node.attribute(name)?;
        let value = text.trim().parse::<f64>().ok();
        if value.is_none() {
            self.problem(node, format!("{name}=\"{text}\" is not a number"));
        }
        value
    }

    fn system_structure(&mut self, text: &str, overrides: &Overrides) -> Result<SystemSpec, SystemError> {
        let document = Document::parse(text).map_err(|error| SystemError::Parse {
            file: self.file.to_path_buf(),
            error: ParseError {
                kind: FileKind::Ssp,
                syntax: Some("XML"),
                line: error.pos().row as usize,
                column: error.pos().col as usize,
                message: format!("{SSD_FILE}: {error}"),
            },
        })?;
        let root = document.root_element();
        let invalid = |message: String| SystemError::Invalid {
            file: self.file.to_path_buf(),
            problems: vec![Problem { location: SSD_FILE.into(), message }],
        };
        if !root.has_tag_name((SSD, "SystemStructureDescription")) {
            return Err(invalid(format!("the root element is not ssd:SystemStructureDescription (namespace {SSD})")));
        }
        let system = child(root, SSD, "System").ok_or_else(|| invalid("no ssd:System".into()))?;
        self.unsupported(system, &[(SSD, "Connectors"), (SSD, "ParameterBindings")], "system-level");
        let mut fmus = BTreeMap::new();
        let instances = children(system, SSD, "Elements")
            .flat_map(|e| e.children().filter(Node::is_element))
            .filter_map(|element| self.component(element, &mut fmus))
            .collect();
        let connections =
            children(system, SSD, "Connections").flat_map(|c| children(c, SSD, "Connection")).collect::<Vec<_>>();
        let connections = connections.into_iter().filter_map(|c| self.connection(c)).collect();
        let mut spec = SystemSpec {
            description: system.attribute("description").unwrap_or_default().to_string(),
            fmus,
            instances,
            connections,
            inputs: Vec::new(),
            start_time: 0.0,
            stop_time: f64::NAN,
            step_size: f64::NAN,
            algorithm: AlgorithmKind::default(),
            input_derivatives: false,
            extrapolate_inputs: false,
            record: RecordSpec::default(),
        };
        self.experiment(root, system, overrides, &mut spec);
        Ok(spec)
    }

    /// The time grid from `ssd:DefaultExperiment` and the step-size annotations (a problem for
    /// a missing stop time or step size that `overrides` do not give), and our own settings (`cc:Master`).
    fn experiment(&mut self, root: Node, system: Node, overrides: &Overrides, spec: &mut SystemSpec) {
        let experiment = child(root, SSD, "DefaultExperiment");
        let master = experiment.and_then(|e| annotated(e, ANNOTATION_TYPE, &[(CRANE_COSIM, "Master")]));
        let here = experiment.unwrap_or(root);
        match self.step_size(system, experiment, master).or(overrides.step_size) {
            Some(step) => spec.step_size = step,
            None => self.problem(
                here,
                "no step size: expected a cc:Master, osp:FixedStepAlgorithm or oms:FixedStepMaster annotation \
                 (or pass Overrides::step_size)",
            ),
        }
        match experiment.and_then(|e| self.number(e, "stopTime")).or(overrides.stop_time) {
            Some(stop) => spec.stop_time = stop,
            None => self.problem(here, "no stopTime in ssd:DefaultExperiment (or pass Overrides::stop_time)"),
        }
        spec.start_time = experiment.and_then(|e| self.number(e, "startTime")).unwrap_or(0.0);
        if let Some(master) = master {
            spec.algorithm = self.algorithm(master).unwrap_or_default();
            spec.input_derivatives = master.attribute("inputDerivatives") == Some("true");
            spec.record = child(master, CRANE_COSIM, "Record").map(|r| self.record(r)).unwrap_or_default();
        }
    }

    /// A problem for every child element `names` of `node` (features this reader lacks).
    fn unsupported(&mut self, node: Node, names: &[(&str, &str)], what: &str) {
        for &(namespace, name) in names {
            for found in children(node, namespace, name) {
                self.problem(found, format!("{what} {name} are not supported"));
            }
        }
    }

    fn step_size(&mut self, system: Node, experiment: Option<Node>, master: Option<Node>) -> Option<f64> {
        if let Some(master) = master {
            return self.number(master, "stepSize");
        }
        let osp = experiment.and_then(|e| annotated(e, OSP_TYPE, &[(OSP, "Algorithm"), (OSP, "FixedStepAlgorithm")]));
        if let Some(osp) = osp {
            return self.number(osp, "baseStepSize");
        }
        let oms = annotated(
            system,
            OMS_TYPE,
            &[(OMS, "Annotations"), (OMS, "SimulationInformation"), (OMS, "FixedStepMaster")],
        )?;
        self.number(oms, "stepSize")
    }

    fn algorithm(&mut self, master: Node) -> Option<AlgorithmKind> {
        let name = master.attribute("algorithm")?;
        name.parse().map_err(|message: String| self.problem(master, message)).ok()
    }

    fn record(&mut self, record: Node) -> RecordSpec {
        let variables = child(record, CRANE_COSIM, "Variables").map(|list| {
            children(list, CRANE_COSIM, "Variable")
                .filter_map(|v| self.attribute(v, "name").map(str::to_string))
                .collect()
        });
        RecordSpec { interval: self.number(record, "interval"), variables }
    }

    /// An FMU component as an instance; its FMU gets an alias (the file stem) in `fmus`.
    fn component(&mut self, element: Node, fmus: &mut BTreeMap<String, PathBuf>) -> Option<InstanceSpec> {
        if !element.has_tag_name((SSD, "Component")) {
            self.problem(element, "only ssd:Component elements are supported (no nested systems)");
            return None;
        }
        let name = self.attribute(element, "name")?.to_string();
        let source = self.attribute(element, "source")?;
        if element.attribute("type").is_some_and(|t| t != FMU_MIME_TYPE) {
            self.problem(element, format!("type must be {FMU_MIME_TYPE}"));
        }
        if element.attribute("implementation").is_some_and(|i| i == "ModelExchange") {
            self.problem(element, "implementation=\"ModelExchange\": only Co-Simulation FMUs can be run");
        }
        let path = match safe_relative_path(source) {
            Ok(path) => path,
            Err(reason) => {
                self.problem(element, format!("source=\"{source}\" must be a path inside the archive: {reason}"));
                return None;
            }
        };
        let alias = fmu_alias(fmus, &path);
        let mut start = BTreeMap::new();
        for binding in children(element, SSD, "ParameterBindings").flat_map(|b| children(b, SSD, "ParameterBinding")) {
            self.parameter_binding(binding, &mut start);
        }
        Some(InstanceSpec { name, fmu: alias, start })
    }

    fn parameter_binding(&mut self, binding: Node, start: &mut BTreeMap<String, serde_json::Value>) {
        self.unsupported(binding, &[(SSD, "ParameterMapping")], "parameter");
        let prefix = binding.attribute("prefix").unwrap_or_default();
        if let Some(source) = binding.attribute("source") {
            match self.read_ssv(source) {
                Ok(text) => match Document::parse(&text) {
                    Ok(ssv) => {
                        let ssd = std::mem::replace(&mut self.document, source.to_string());
                        self.parameter_set(ssv.root_element(), prefix, start);
                        self.document = ssd;
                    }
                    Err(error) => self.problem(binding, format!("source=\"{source}\": {error}")),
                },
                Err(message) => self.problem(binding, format!("source=\"{source}\": {message}")),
            }
        }
        let inline = children(binding, SSD, "ParameterValues").flat_map(|v| children(v, SSV, "ParameterSet"));
        for set in inline.collect::<Vec<_>>() {
            self.parameter_set(set, prefix, start);
        }
    }

    /// The text of a parameter values file inside the archive.
    fn read_ssv(&self, source: &str) -> Result<String, String> {
        let relative = safe_relative_path(source).map_err(|reason| reason.to_string())?;
        read_system_text(&self.directory.join(relative)).map_err(|error| error.to_string())
    }

    fn parameter_set(&mut self, set: Node, prefix: &str, start: &mut BTreeMap<String, serde_json::Value>) {
        if !set.has_tag_name((SSV, "ParameterSet")) {
            self.problem(set, "expected an ssv:ParameterSet");
            return;
        }
        for parameter in children(set, SSV, "Parameters").flat_map(|p| children(p, SSV, "Parameter")) {
            let Some(name) = self.attribute(parameter, "name") else { continue };
            if let Some(value) = self.parameter_value(parameter) {
                start.insert(format!("{prefix}{name}"), value);
            }
        }
    }

    /// `ssv:Real`, `ssv:Integer`, `ssv:Boolean` or `ssv:String` as a JSON start value.
    fn parameter_value(&mut self, parameter: Node) -> Option<serde_json::Value> {
        let Some(typed) = parameter.children().find(|n| n.is_element() && n.tag_name().namespace() == Some(SSV)) else {
            self.problem(parameter, "no ssv:Real, ssv:Integer, ssv:Boolean or ssv:String value");
            return None;
        };
        let text = self.attribute(typed, "value")?.trim();
        let Some(value) = typed_start_value(typed.tag_name().name(), text, |text| text.parse().ok()) else {
            self.problem(typed, format!("ssv:{} values are not supported", typed.tag_name().name()));
            return None;
        };
        if value.is_none() {
            self.problem(typed, format!("value=\"{text}\" is not a finite {}", typed.tag_name().name()));
        }
        value
    }

    fn connection(&mut self, connection: Node) -> Option<ConnectionSpec> {
        self.unsupported(
            connection,
            &[
                (SSC, "LinearTransformation"),
                (SSC, "BooleanMappingTransformation"),
                (SSC, "IntegerMappingTransformation"),
                (SSC, "EnumerationMappingTransformation"),
            ],
            "connection",
        );
        let Some(start) = connection.attribute("startElement") else {
            self.problem(connection, "connections to the system's own connectors (no startElement) are not supported");
            return None;
        };
        let Some(end) = connection.attribute("endElement") else {
            self.problem(connection, "connections to the system's own connectors (no endElement) are not supported");
            return None;
        };
        let from = self.attribute(connection, "startConnector")?;
        let to = self.attribute(connection, "endConnector")?;
        Some(ConnectionSpec { from: format!("{start}.{from}"), to: format!("{end}.{to}") })
    }
}

/// A start value of an SSP or OSP file as JSON: `text` read as a `kind` ("Real", "Integer",
/// "Boolean" or "String"), a Real by `real` (the two formats write them differently); `None` for
/// any other kind, `Some(None)` for text that is not a finite value of the kind.
pub(super) fn typed_start_value(
    kind: &str,
    text: &str,
    real: impl Fn(&str) -> Option<f64>,
) -> Option<Option<serde_json::Value>> {
    Some(match kind {
        "Real" => real(text).and_then(|v| serde_json::Number::from_f64(v).map(Into::into)),
        "Integer" => text.trim().parse::<i64>().ok().map(Into::into),
        "Boolean" => match text.trim() {
            "true" | "1" => Some(true.into()),
            "false" | "0" => Some(false.into()),
            _ => None,
        },
        "String" => Some(text.into()),
        _ => return None,
    })
}

/// The alias of the FMU at `path` (relative to the archive), added to `fmus` on first use: its
/// file stem, numbered if another FMU has that stem.
pub(super) fn fmu_alias(fmus: &mut BTreeMap<String, PathBuf>, path: &Path) -> String {
    if let Some((alias, _)) = fmus.iter().find(|(_, p)| p.as_path() == path) {
        return alias.clone();
    }
    let stem = path.file_stem().map_or_else(|| "fmu".to_string(), |s| s.to_string_lossy().into_owned());
    let alias =
        (1..).map(|n| if n == 1 { stem.clone() } else { format!("{stem}_{n}") }).find(|a| !fmus.contains_key(a));
    let alias = alias.expect("an unused alias exists");
    fmus.insert(alias.clone(), path.to_path_buf());
    alias
}

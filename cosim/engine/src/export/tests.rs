//! Export and re-import with a fake FMU (its binary is not a library: nothing is loaded).

use std::io::Write;
use std::path::{Path, PathBuf};

use super::*;
use crate::system::{Overrides, SystemError, SystemFiles};
use fmu_import::error_chain;
use fmu_import::value::Value;

/// Every type and causality the writers treat differently.
const MODEL: &str = r#"<fmiModelDescription fmiVersion="2.0" modelName="imu" guid="{g}">
<CoSimulation modelIdentifier="imu"/>
<TypeDefinitions><SimpleType name="Mode"><Enumeration><Item name="a" value="1"/><Item name="b" value="2"/></Enumeration></SimpleType></TypeDefinitions>
<ModelVariables>
  <ScalarVariable name="seed" valueReference="0" causality="parameter" variability="fixed" initial="exact"><Integer start="0"/></ScalarVariable>
  <ScalarVariable name="noise" valueReference="1" causality="parameter" variability="fixed" initial="exact"><Boolean start="false"/></ScalarVariable>
  <ScalarVariable name="gain" valueReference="2" causality="parameter" variability="fixed" initial="exact"><Real start="1"/></ScalarVariable>
  <ScalarVariable name="label" valueReference="3" causality="parameter" variability="fixed" initial="exact"><String start=""/></ScalarVariable>
  <ScalarVariable name="mode" valueReference="4" causality="parameter" variability="fixed" initial="exact"><Enumeration declaredType="Mode" start="1"/></ScalarVariable>
  <ScalarVariable name="a.x" valueReference="5" causality="input"><Real start="0"/></ScalarVariable>
  <ScalarVariable name="y.x" valueReference="6" causality="output" initial="calculated"><Real/></ScalarVariable>
  <ScalarVariable name="energy" valueReference="7" causality="local"><Real/></ScalarVariable>
</ModelVariables></fmiModelDescription>"#;

/// A folder with `fmu/imu.fmu`, `in.csv` and the system file written by [`Fixture::system`].
struct Fixture {
    dir: tempfile::TempDir,
}

fn zip(path: &Path, entries: &[(&str, &[u8])]) {
    let mut writer = zip::ZipWriter::new(std::fs::File::create(path).expect("create"));
    for (name, bytes) in entries {
        writer.start_file(*name, zip::write::SimpleFileOptions::default()).expect("start");
        writer.write_all(bytes).expect("write");
    }
    writer.finish().expect("finish");
}

impl Fixture {
    fn new() -> Self {
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::create_dir(dir.path().join("fmu")).expect("mkdir");
        let binary = format!("binaries/{}/imu.{}", fmu_import::fmu::platform().0, fmu_import::fmu::platform().1);
        zip(
            &dir.path().join("fmu/imu.fmu"),
            &[("modelDescription.xml", MODEL.as_bytes()), (&binary, b"not a shared library")],
        );
        std::fs::write(dir.path().join("in.csv"), "time,a.x\n0,0\n1,1\n").expect("csv");
        Self { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// Two instances of the IMU, `imu1.y.x → imu2.a.x`, with `extra` JSON members.
    fn system(&self, extra: &str) -> System {
        let json = format!(
            r#"{{"description": "two <IMUs> & a \"wire\"", "fmus": {{"imu": "fmu/imu.fmu"}},
                "instances": [{{"name": "imu1", "fmu": "imu",
                                "start": {{"seed": 3, "noise": true, "gain": 2, "label": "a<b", "mode": 2}}}},
                              {{"name": "imu2", "fmu": "imu", "start": {{"gain": -0.40142572795869574}}}}],
                "connections": [{{"from": "imu1.y.x", "to": "imu2.a.x"}}],
                "start_time": 0.5, "stop_time": 3, "step_size": 0.01 {extra}}}"#
        );
        let file = self.path("closed.json");
        std::fs::write(&file, json).expect("write system");
        System::load(&file, &Overrides::default(), &SystemFiles::default()).expect("valid system")
    }

    /// The archive `name` with this SSD and the IMU FMU at `resources/imu.fmu`.
    fn archive(&self, name: &str, ssd: &str, extra: &[(&str, &[u8])]) -> PathBuf {
        let fmu = std::fs::read(self.path("fmu/imu.fmu")).expect("fmu");
        let mut entries = vec![("SystemStructure.ssd", ssd.as_bytes()), ("resources/imu.fmu", fmu.as_slice())];
        entries.extend_from_slice(extra);
        let path = self.path(name);
        zip(&path, &entries);
        path
    }
}

fn problems(result: Result<System, SystemError>) -> Vec<String> {
    match result {
        Ok(_) => panic!("expected problems"),
        Err(error) => error.problems().iter().map(ToString::to_string).collect(),
    }
}

#[test]
fn a_system_exported_as_ssp_reads_back_as_the_same_system() {
    let fixture = Fixture::new();
    let system = fixture.system(
        r#", "algorithm": "jacobi", "input_derivatives": true,
             "record": {"interval": 0.02, "variables": ["imu2.y.x", "imu1.y.x"]}"#,
    );
    let archive = fixture.path("closed.ssp");
    ssp::write(&system, &archive).expect("export");
    let back =
        System::load(&archive, &Overrides::default(), &SystemFiles::default()).expect("the archive is a valid system");

    assert_eq!(back.file, archive);
    assert_eq!(back.spec.fmus, BTreeMap::from([("imu".to_string(), PathBuf::from("resources/imu.fmu"))]));
    let mut expected = system.spec.clone();
    expected.fmus = back.spec.fmus.clone();
    // JSON integers given for a Real come back as the Real they were set as.
    expected.instances[0].start.insert("gain".into(), 2.0.into());
    assert_eq!(back.spec, expected);
    let starts = |s: &System| s.instances.iter().map(|i| i.start.clone()).collect::<Vec<_>>();
    assert_eq!(starts(&back), starts(&system));
    assert_eq!((back.connections, back.grid, back.record), (system.connections, system.grid, system.record));
}

#[test]
fn the_defaults_are_kept_unwritten_and_come_back() {
    let fixture = Fixture::new();
    let system = fixture.system("");
    let ssd = ssp::system_structure(&system).expect("export");
    assert!(!ssd.contains("cc:Record"), "{ssd}");
    assert!(ssd.contains(r#"<cc:Master stepSize="0.01" algorithm="gauss-seidel" inputDerivatives="false"/>"#));
    let archive = fixture.path("defaults.ssp");
    ssp::write(&system, &archive).expect("export");
    let back = System::load(&archive, &Overrides::default(), &SystemFiles::default()).expect("valid");
    assert_eq!((back.spec.record, back.record), (system.spec.record, system.record));
}

#[test]
fn connectors_are_typed_by_kind_and_start_values_by_the_variable_type() {
    let fixture = Fixture::new();
    let ssd = ssp::system_structure(&fixture.system("")).expect("export");
    for expected in [
        r#"<ssd:Component name="imu1" type="application/x-fmu-sharedlibrary" source="resources/imu.fmu" implementation="CoSimulation">"#,
        r#"<ssd:Connector name="a.x" kind="input">"#,
        r#"<ssd:Connector name="y.x" kind="output">"#,
        r#"<ssd:Connector name="label" kind="parameter">"#,
        // Enumerations are untyped connectors (the FMU's declaration applies) and Integer values.
        r#"<ssd:Connector name="mode" kind="parameter"/>"#,
        r#"<ssv:Parameter name="mode">"#,
        r#"<ssv:Integer value="2"/>"#,
        r#"<ssv:Real value="2.0"/>"#,
        r#"<ssv:Boolean value="true"/>"#,
        r#"<ssv:String value="a&lt;b"/>"#,
        r#"<ssv:Real value="-0.40142572795869574"/>"#,
        r#"<ssd:System name="closed" description="two &lt;IMUs&gt; &amp; a &quot;wire&quot;">"#,
        r#"<ssd:Connection startElement="imu1" startConnector="y.x" endElement="imu2" endConnector="a.x"/>"#,
        r#"<ssd:DefaultExperiment startTime="0.5" stopTime="3.0">"#,
        r#"<osp:FixedStepAlgorithm baseStepSize="0.01"/>"#,
        r#"<oms:FixedStepMaster description="oms-ma" stepSize="0.01"/>"#,
    ] {
        assert!(ssd.contains(expected), "{expected} missing from\n{ssd}");
    }
    // Locals are not connectors.
    assert!(!ssd.contains("energy"), "{ssd}");
    assert!(roxmltree::Document::parse(&ssd).is_ok());
}

#[test]
fn the_osp_system_structure_carries_instances_start_values_and_connections() {
    let fixture = Fixture::new();
    let dir = fixture.path("osp");
    let file = osp::write(&fixture.system(""), &dir).expect("export");
    assert_eq!(file, dir.join("OspSystemStructure.xml"));
    assert!(dir.join("imu.fmu").is_file());
    let expected = r#"<?xml version="1.0" encoding="UTF-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure" version="0.1">
  <StartTime>0.5</StartTime>
  <BaseStepSize>0.01</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="imu1" source="imu.fmu">
      <InitialValues>
        <InitialValue variable="gain"><Real value="2.0"/></InitialValue>
        <InitialValue variable="label"><String value="a&lt;b"/></InitialValue>
        <InitialValue variable="mode"><Integer value="2"/></InitialValue>
        <InitialValue variable="noise"><Boolean value="true"/></InitialValue>
        <InitialValue variable="seed"><Integer value="3"/></InitialValue>
      </InitialValues>
    </Simulator>
    <Simulator name="imu2" source="imu.fmu">
      <InitialValues>
        <InitialValue variable="gain"><Real value="-0.40142572795869574"/></InitialValue>
      </InitialValues>
    </Simulator>
  </Simulators>
  <Connections>
    <VariableConnection>
      <Variable simulator="imu1" name="y.x"/>
      <Variable simulator="imu2" name="a.x"/>
    </VariableConnection>
  </Connections>
</OspSystemStructure>
"#;
    assert_eq!(std::fs::read_to_string(file).unwrap(), expected);
}

#[test]
fn input_files_are_refused_naming_the_input() {
    let fixture = Fixture::new();
    let system = fixture.system(r#", "inputs": [{"instance": "imu1", "file": "in.csv"}]"#);
    for error in [ssp::system_structure(&system).unwrap_err(), osp::system_structure(&system).unwrap_err()] {
        let message = error.to_string();
        assert!(
            message.contains("inputs[0] feeds instance 'imu1' from in.csv")
                && message.contains("SSP and OSP have no input files"),
            "{message}"
        );
    }
}

/// An SSD with the given `ssd:Elements` content, connections and default experiment.
fn ssd(elements: &str, connections: &str, experiment: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<ssd:SystemStructureDescription xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription"
    xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"
    xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues"
    xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations"
    xmlns:oms="https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd"
    version="1.0" name="s">
  <ssd:System name="s"><ssd:Elements>{elements}</ssd:Elements><ssd:Connections>{connections}</ssd:Connections>
    <ssd:Annotations><ssc:Annotation type="org.openmodelica"><oms:Annotations><oms:SimulationInformation>
      <oms:FixedStepMaster description="oms-ma" stepSize="0.05"/>
    </oms:SimulationInformation></oms:Annotations></ssc:Annotation></ssd:Annotations>
  </ssd:System>
  {experiment}
</ssd:SystemStructureDescription>"#
    )
}

const IMU1: &str = r#"<ssd:Component name="imu1" source="resources/imu.fmu"/>"#;

#[test]
fn other_tools_archives_give_step_sizes_through_their_annotations_and_parameters_in_ssv_files() {
    let fixture = Fixture::new();
    let elements = r#"<ssd:Component name="imu1" source="resources/imu.fmu">
        <ssd:ParameterBindings><ssd:ParameterBinding source="resources/imu1.ssv"/></ssd:ParameterBindings>
      </ssd:Component>"#;
    let ssv = br#"<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" version="1.0" name="p">
        <ssv:Parameters><ssv:Parameter name="seed"><ssv:Integer value="7"/></ssv:Parameter>
        <ssv:Parameter name="noise"><ssv:Boolean value="1"/></ssv:Parameter></ssv:Parameters></ssv:ParameterSet>"#;
    let osp = r#"<ssd:DefaultExperiment stopTime="2"><ssd:Annotations><ssc:Annotation type="com.opensimulationplatform">
        <osp:Algorithm><osp:FixedStepAlgorithm baseStepSize="0.1"/></osp:Algorithm></ssc:Annotation></ssd:Annotations>
      </ssd:DefaultExperiment>"#;
    let load = |name, experiment| {
        let archive = fixture.archive(name, &ssd(elements, "", experiment), &[("resources/imu1.ssv", ssv)]);
        System::load(&archive, &Overrides::default(), &SystemFiles::default()).expect("valid")
    };
    // libcosim's annotation wins over OMSimulator's, which applies without it.
    let libcosim = load("osp.ssp", osp);
    assert_eq!((libcosim.spec.step_size, libcosim.spec.stop_time), (0.1, 2.0));
    let omsimulator = load("oms.ssp", r#"<ssd:DefaultExperiment stopTime="2"/>"#);
    assert_eq!(omsimulator.spec.step_size, 0.05);
    assert_eq!(omsimulator.spec.algorithm, crate::algorithm::AlgorithmKind::GaussSeidel);
    let start: Vec<_> = omsimulator.instances[0].start.iter().map(|(v, value)| format!("{}={value}", v.name)).collect();
    assert_eq!(start, ["noise=true", "seed=7"]);
}

#[test]
fn a_missing_stop_time_is_a_problem_unless_given_on_the_command_line() {
    let fixture = Fixture::new();
    let archive = fixture.archive("nostop.ssp", &ssd(IMU1, "", ""), &[]);
    assert_eq!(
        problems(System::load(&archive, &Overrides::default(), &SystemFiles::default())),
        ["SystemStructure.ssd:ssd:SystemStructureDescription[s]: no stopTime in ssd:DefaultExperiment (or pass Overrides::stop_time)"]
    );
    let overrides = Overrides { stop_time: Some(1.0), ..Overrides::default() };
    assert_eq!(System::load(&archive, &overrides, &SystemFiles::default()).expect("valid").grid.steps(), 20);
}

#[test]
fn what_the_reader_cannot_run_is_named_with_its_location() {
    let fixture = Fixture::new();
    let elements = r#"<ssd:Component name="imu1" source="../imu.fmu"/>
        <ssd:Component name="imu2" source="resources/imu.fmu" implementation="ModelExchange"/>
        <ssd:System name="sub"/>
        <ssd:Component name="imu3" source="resources/imu.fmu">
          <ssd:ParameterBindings><ssd:ParameterBinding source="resources/bad.ssv"/></ssd:ParameterBindings>
        </ssd:Component>"#;
    let ssv = br#"<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" version="1.0" name="p">
        <ssv:Parameters><ssv:Parameter name="gain"><ssv:Real value="x"/></ssv:Parameter></ssv:Parameters></ssv:ParameterSet>"#;
    let connections = r#"<ssd:Connection startElement="imu2" startConnector="y.x" endElement="imu2" endConnector="a.x">
          <ssc:LinearTransformation factor="2"/></ssd:Connection>
        <ssd:Connection startConnector="u" endElement="imu2" endConnector="a.x"/>"#;
    let archive = fixture.archive(
        "bad.ssp",
        &ssd(elements, connections, r#"<ssd:DefaultExperiment stopTime="x"/>"#),
        &[("resources/bad.ssv", ssv)],
    );
    let root = "SystemStructure.ssd:ssd:SystemStructureDescription[s]/ssd:System[s]";
    assert_eq!(
        problems(System::load(&archive, &Overrides::default(), &SystemFiles::default())),
        [
            format!("{root}/ssd:Elements/ssd:Component[imu1]: source=\"../imu.fmu\" must be a path inside the archive: it contains a '..' component"),
            format!("{root}/ssd:Elements/ssd:Component[imu2]: implementation=\"ModelExchange\": only Co-Simulation FMUs can be run"),
            format!("{root}/ssd:Elements/ssd:System[sub]: only ssd:Component elements are supported (no nested systems)"),
            "resources/bad.ssv:ssv:ParameterSet[p]/ssv:Parameters/ssv:Parameter[gain]/ssv:Real: value=\"x\" is not a finite Real".to_string(),
            format!("{root}/ssd:Connections/ssd:Connection/ssc:LinearTransformation: connection LinearTransformation are not supported"),
            format!("{root}/ssd:Connections/ssd:Connection: connections to the system's own connectors (no startElement) are not supported"),
            "SystemStructure.ssd:ssd:SystemStructureDescription[s]/ssd:DefaultExperiment: stopTime=\"x\" is not a number".to_string(),
            "SystemStructure.ssd:ssd:SystemStructureDescription[s]/ssd:DefaultExperiment: no stopTime in ssd:DefaultExperiment (or pass Overrides::stop_time)".to_string(),
        ]
    );
}

#[test]
fn broken_archives_name_the_file() {
    let fixture = Fixture::new();
    let not_zip = fixture.path("not_zip.ssp");
    std::fs::write(&not_zip, "plain text").unwrap();
    let error = System::load(&not_zip, &Overrides::default(), &SystemFiles::default()).unwrap_err();
    assert!(matches!(error, SystemError::Archive { .. }), "{error:?}");
    assert!(error.to_string().starts_with(&format!("{}: cannot extract", not_zip.display())), "{error}");

    let bad_xml = fixture.archive("bad_xml.ssp", "<ssd:SystemStructureDescription", &[]);
    let error = System::load(&bad_xml, &Overrides::default(), &SystemFiles::default()).unwrap_err();
    assert!(matches!(&error, SystemError::Parse { error, .. } if error.line == 1), "{error:?}");
    assert!(error.to_string().contains("XML syntax error at line 1 column"), "{error}");
    assert!(error.to_string().contains("(read as an SSP archive): SystemStructure.ssd:"), "{error}");

    let no_ssd = fixture.path("no_ssd.ssp");
    zip(&no_ssd, &[("resources/imu.fmu", b"x")]);
    let error = System::load(&no_ssd, &Overrides::default(), &SystemFiles::default()).unwrap_err();
    assert!(error.to_string().contains("SystemStructure.ssd"), "{error}");
}

#[test]
fn text_that_xml_cannot_hold_is_refused() {
    let fixture = Fixture::new();
    let mut system = fixture.system("");
    system.spec.description = "two IMUs\u{7}".into();
    let message = error_chain(&ssp::system_structure(&system).expect_err("a BEL in the description"));
    assert!(message.contains("closed.json: cannot export \"two IMUs\\u{7}\""), "{message}");
    assert!(message.contains("the control character U+0007 at position 8 cannot be written to XML"), "{message}");

    let mut system = fixture.system("");
    let label = system.instances[0].start.iter_mut().find(|(v, _)| v.name == "label").expect("label");
    label.1 = Value::String("a\u{1b}[0m".into());
    for error in [ssp::system_structure(&system).unwrap_err(), osp::system_structure(&system).unwrap_err()] {
        assert!(matches!(&error, ExportError::Text { text, .. } if text == "a\u{1b}[0m"), "{error}");
    }
}

#[test]
fn an_osp_system_structure_reads_back_as_the_system_it_came_from() {
    let fixture = Fixture::new();
    let system = fixture.system("");
    let dir = fixture.path("osp");
    let file = osp::write(&system, &dir).expect("export");
    let overrides = Overrides { stop_time: Some(3.0), ..Overrides::default() };
    for path in [&dir, &file] {
        let back = System::load(path, &overrides, &SystemFiles::default()).expect("valid");
        let names = |s: &System| s.instances.iter().map(|i| (i.name.clone(), i.start.clone())).collect::<Vec<_>>();
        assert_eq!(names(&back), names(&system));
        assert_eq!(back.connections, system.connections);
        assert_eq!((back.spec.start_time, back.spec.step_size), (0.5, 0.01));
        assert_eq!(back.spec.algorithm, crate::algorithm::AlgorithmKind::Jacobi);
        assert!(!back.spec.input_derivatives);
    }
    let error = System::load(&dir, &Overrides::default(), &SystemFiles::default()).unwrap_err();
    assert!(error_chain(&error).contains("has no stop time: pass Overrides::stop_time"), "{}", error_chain(&error));

    // What the reader does not understand is refused with its location.
    let text = std::fs::read_to_string(&file).unwrap().replace(
        "<Connections>",
        r#"<Connections><SignalConnection><Signal function="f" name="in"/><Variable simulator="imu1" name="y.x"/></SignalConnection>"#,
    );
    std::fs::write(&file, text.replace("fixedStep", "variableStep")).unwrap();
    let error = System::load(&file, &overrides, &SystemFiles::default()).unwrap_err();
    let problems: Vec<String> = error.problems().iter().map(ToString::to_string).collect();
    assert_eq!(
        problems,
        [
            "OspSystemStructure.xml:OspSystemStructure/Algorithm: unknown algorithm \"variableStep\": expected fixedStep",
            "OspSystemStructure.xml:OspSystemStructure/Connections/SignalConnection: SignalConnections are not \
             supported (only VariableConnection)",
        ]
    );
    let empty = fixture.path("empty");
    std::fs::create_dir(&empty).unwrap();
    let error = System::load(&empty, &overrides, &SystemFiles::default()).unwrap_err();
    assert!(error.to_string().ends_with("but this is a folder without OspSystemStructure.xml"), "{error}");
}

//! Both versions' descriptions read into the same rows, and what each refuses, by name and
//! position.

use super::parser::parse_start;
use super::*;
use crate::value::Value;

const GOOD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="pendulum" guid="{abc}" generationTool="test">
  <CoSimulation modelIdentifier="pendulum" canHandleVariableCommunicationStepSize="true"
  canInterpolateInputs="true" maxOutputDerivativeOrder="0" canGetAndSetFMUstate="true"
  canSerializeFMUstate="true"/>
  <UnitDefinitions><Unit name="m"/><Unit name="rad"/></UnitDefinitions>
  <TypeDefinitions><SimpleType name="Angle"><Real quantity="Angle" unit="rad"/></SimpleType></TypeDefinitions>
  <DefaultExperiment startTime="0" stopTime="60" stepSize="0.01"/>
  <ModelVariables>
<ScalarVariable name="tip.x" valueReference="1" causality="input" description="tip x in W">
  <Real start="0" unit="m"/>
</ScalarVariable>
<ScalarVariable name="theta_x0" valueReference="100" causality="parameter" variability="fixed" initial="exact">
  <Real declaredType="Angle" start="-0.349"/>
</ScalarVariable>
<ScalarVariable name="theta_x" valueReference="200" causality="output" initial="calculated">
  <Real unit="rad"/>
</ScalarVariable>
<ScalarVariable name="count" valueReference="300" causality="output" variability="discrete">
  <Integer/>
</ScalarVariable>
<ScalarVariable name="held" valueReference="301" causality="parameter" variability="fixed">
  <Boolean start="true"/>
</ScalarVariable>
<ScalarVariable name="label" valueReference="302" causality="parameter" variability="fixed">
  <String start="a b"/>
</ScalarVariable>
<ScalarVariable name="mode" valueReference="303" causality="parameter" variability="fixed">
  <Enumeration declaredType="Mode" start="2"/>
</ScalarVariable>
<ScalarVariable name="time" valueReference="0" causality="independent"><Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure/>
</fmiModelDescription>"#;

#[test]
fn absent_initial_takes_the_fmi_default_and_decides_settable_starts() {
    let md = ModelDescription::parse(GOOD).expect("valid");
    let variable = |name: &str| md.variable(name).expect(name);
    let defaults = ["tip.x", "held", "count", "time"].map(|name| variable(name).initial_or_default());
    assert_eq!(defaults, [None, Some(Initial::Exact), Some(Initial::Calculated), None]);
    let settable =
        ["tip.x", "theta_x0", "held", "theta_x", "count", "time"].map(|name| variable(name).is_settable_start());
    assert_eq!(settable, [true, true, true, false, false, false]);
}

#[test]
fn parses_a_complete_description() {
    let md = ModelDescription::parse(GOOD).expect("valid");
    assert_eq!(md.fmi_version, "2.0");
    assert_eq!(md.model_name, "pendulum");
    assert_eq!(md.guid, "{abc}");
    assert_eq!(md.co_simulation.model_identifier, "pendulum");
    assert!(md.co_simulation.can_interpolate_inputs);
    assert!(md.co_simulation.can_handle_variable_communication_step_size);
    assert!(md.co_simulation.can_get_and_set_fmu_state && md.co_simulation.can_serialize_fmu_state);
    assert_eq!(md.co_simulation.max_output_derivative_order, 0);
    assert_eq!(md.default_experiment.and_then(|d| d.step_size), Some(0.01));
    assert_eq!(md.default_experiment.and_then(|d| d.stop_time), Some(60.0));
    assert_eq!(md.variables.len(), 8);

    let tip = md.variable("tip.x").expect("tip.x");
    assert_eq!(tip.value_reference, 1);
    assert_eq!(tip.causality, Causality::Input);
    assert_eq!(tip.variability, Variability::Continuous);
    assert_eq!(tip.initial, None);
    assert_eq!(tip.unit.as_deref(), Some("m"));
    assert_eq!(tip.description.as_deref(), Some("tip x in W"));
    assert_eq!(tip.start, Some(Value::Real(0.0)));

    let theta = md.variable("theta_x0").expect("theta_x0");
    assert_eq!(theta.unit.as_deref(), Some("rad"), "unit from the declared type");
    assert_eq!(theta.start, Some(Value::Real(-0.349)));
    assert_eq!(theta.initial, Some(Initial::Exact));
    assert_eq!(theta.variability, Variability::Fixed);

    assert_eq!(md.variable("count").map(|v| v.variable_type), Some(VariableType::Integer));
    assert_eq!(md.variable("held").and_then(|v| v.start.clone()), Some(Value::Boolean(true)));
    assert_eq!(md.variable("label").and_then(|v| v.start.clone()), Some(Value::String("a b".into())));
    assert_eq!(md.variable("mode").and_then(|v| v.start.clone()), Some(Value::Integer(2)));
    assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
    assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
    assert_eq!(md.variables_with(Causality::Output).count(), 2);
    assert_eq!(md.variable_by_reference(200, VariableType::Real).map(|v| v.name.as_str()), Some("theta_x"));
    assert!(md.variable("nope").is_none());
}

fn error_of(xml: &str) -> String {
    ModelDescription::parse(xml).expect_err("must be refused").to_string()
}

#[test]
fn malformed_xml_reports_the_position() {
    let message = error_of("<fmiModelDescription fmiVersion=\"2.0\">\n  <CoSimulation>\n</fmiModelDescription>");
    assert!(message.contains("not well-formed XML") && message.contains("line 3"), "{message}");
}

#[test]
fn wrong_root_version_and_missing_parts_are_refused() {
    assert!(error_of("<model/>").contains("expected <fmiModelDescription>"));
    let v1 = error_of(r#"<fmiModelDescription fmiVersion="1.0" modelName="m" guid="g"/>"#);
    assert!(v1.contains("\"1.0\"") && v1.contains("FMI \"2.0\" and \"3.0\""), "{v1}");
    let v3 = error_of(r#"<fmiModelDescription fmiVersion="3.0" modelName="m" instantiationToken="g"/>"#);
    assert!(v3.contains("no <CoSimulation>"), "an FMI 3.0 description is read as such: {v3}");
    let no_guid = error_of(r#"<fmiModelDescription fmiVersion="2.0" modelName="m"/>"#);
    assert!(no_guid.contains("\"guid\""), "{no_guid}");
    let me_only = error_of(
        r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><ModelExchange modelIdentifier="m"/><ModelVariables/></fmiModelDescription>"#,
    );
    assert!(me_only.contains("a Model Exchange FMU"), "{me_only}");
    let no_vars = error_of(
        r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="m"/></fmiModelDescription>"#,
    );
    assert!(no_vars.contains("<ModelVariables>"), "{no_vars}");
}

fn with_variable(variable: &str) -> String {
    format!(
        r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
<CoSimulation modelIdentifier="m"/>
<ModelVariables>{variable}</ModelVariables></fmiModelDescription>"#
    )
}

#[test]
fn bad_variables_are_named() {
    let cases = [
        (r#"<ScalarVariable name="a" valueReference="x"><Real/></ScalarVariable>"#, "valueReference=\"x\""),
        (r#"<ScalarVariable name="a" valueReference="-1"><Real/></ScalarVariable>"#, "valueReference=\"-1\""),
        (r#"<ScalarVariable name="a"><Real/></ScalarVariable>"#, "\"a\" has no valueReference"),
        (r#"<ScalarVariable valueReference="1"><Real/></ScalarVariable>"#, "no \"name\" attribute"),
        (r#"<ScalarVariable name="a" valueReference="1"/>"#, "\"a\" has no type element"),
        (
            r#"<ScalarVariable name="a" valueReference="1" causality="out"><Real/></ScalarVariable>"#,
            "causality=\"out\" is not one of",
        ),
        (
            r#"<ScalarVariable name="a" valueReference="1" variability="sometimes"><Real/></ScalarVariable>"#,
            "name=\"a\"",
        ),
        (
            r#"<ScalarVariable name="a" valueReference="1"><Real start="abc"/></ScalarVariable>"#,
            "start=\"abc\" is not a valid Real",
        ),
        (
            r#"<ScalarVariable name="a" valueReference="1"><Integer start="1.5"/></ScalarVariable>"#,
            "not a valid Integer",
        ),
        (
            r#"<ScalarVariable name="a" valueReference="1"><Boolean start="yes"/></ScalarVariable>"#,
            "not a valid Boolean",
        ),
        (r#"<ScalarVariable name="a" valueReference="1"><Enumeration start="1"/></ScalarVariable>"#, "no declaredType"),
        (r#"<ScalarVariable name="a" valueReference="1"><Real/><Integer/></ScalarVariable>"#, "more than one type"),
        (
            r#"<ScalarVariable name="a" valueReference="1"><Real/></ScalarVariable><ScalarVariable name="a" valueReference="2"><Real/></ScalarVariable>"#,
            "declared twice",
        ),
        (r#"<Variable name="a"/>"#, "unexpected <Variable>"),
    ];
    for (variable, expected) in cases {
        let message = error_of(&with_variable(variable));
        assert!(message.contains(expected), "{variable}: {message}");
        assert!(message.starts_with("line 3"), "{variable}: {message}");
    }
}

#[test]
fn bad_capabilities_are_named() {
    let bad_bool = error_of(
        r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="m" canInterpolateInputs="yes"/><ModelVariables/></fmiModelDescription>"#,
    );
    assert!(bad_bool.contains("canInterpolateInputs=\"yes\""), "{bad_bool}");
    let bad_identifier = error_of(
        r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"><CoSimulation modelIdentifier="../evil"/><ModelVariables/></fmiModelDescription>"#,
    );
    assert!(bad_identifier.contains("not a valid C identifier"), "{bad_identifier}");
}

#[test]
fn real_start_literals() {
    assert_eq!(parse_start(VariableType::Real, " 1e-3 "), Some(Value::Real(1e-3)));
    assert_eq!(parse_start(VariableType::Real, "-INF"), Some(Value::Real(f64::NEG_INFINITY)));
    assert_eq!(parse_start(VariableType::Real, "inf"), None);
    assert!(matches!(parse_start(VariableType::Real, "NaN"), Some(Value::Real(v)) if v.is_nan()));
}

const FMI3: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="3.0" modelName="m3" instantiationToken="{tok}">
  <CoSimulation modelIdentifier="m3" canHandleVariableCommunicationStepSize="true"
  canGetAndSetFMUState="true" canSerializeFMUState="true" hasEventMode="false"/>
  <TypeDefinitions><Float64Type name="Angle" unit="rad"/></TypeDefinitions>
  <ModelVariables>
<Float64 name="time" valueReference="0" causality="independent" variability="continuous"/>
<Float64 name="x" valueReference="1" causality="input" start="0.5" unit="m"/>
<Float64 name="phi" valueReference="2" causality="output" declaredType="Angle"/>
<Int32 name="n" valueReference="3" causality="parameter" variability="fixed" start="4"/>
<Boolean name="on" valueReference="4" causality="parameter" variability="fixed" start="true"/>
<String name="label" valueReference="5" causality="parameter" variability="fixed"><Start value="a b"/></String>
  </ModelVariables>
  <ModelStructure><Output valueReference="2"/></ModelStructure>
</fmiModelDescription>"#;

#[test]
fn an_fmi3_description_reads_into_the_same_rows() {
    let md = ModelDescription::parse(FMI3).expect("parses");
    assert!(md.is_fmi3());
    assert_eq!((md.guid.as_str(), md.co_simulation.model_identifier.as_str()), ("{tok}", "m3"));
    let cs = &md.co_simulation;
    assert!(cs.can_get_and_set_fmu_state && cs.can_serialize_fmu_state && !cs.can_interpolate_inputs);
    let x = md.variable("x").expect("x");
    assert_eq!(
        (x.variable_type, x.start.clone(), x.unit.as_deref()),
        (VariableType::Real, Some(Value::Real(0.5)), Some("m"))
    );
    assert_eq!(md.variable("phi").and_then(|v| v.unit.as_deref()), Some("rad"), "unit of the declared type");
    let n = md.variable("n").expect("n");
    assert_eq!((n.variable_type, n.start.clone()), (VariableType::Integer, Some(Value::Integer(4))));
    assert_eq!(md.variable("on").and_then(|v| v.start.clone()), Some(Value::Boolean(true)));
    assert_eq!(md.variable("label").and_then(|v| v.start.clone()), Some(Value::String("a b".into())));
    assert_eq!(md.variable("time").map(|v| v.causality), Some(Causality::Independent));
    assert_eq!(md.variable("n").map(|v| v.variability), Some(Variability::Fixed));
}

#[test]
fn fmi3_arrays_become_elements_and_other_types_convert() {
    let xml = FMI3.replace(
        "  </ModelVariables>",
        r#"    <Float32 name="gain" valueReference="10" causality="parameter" variability="fixed" start="0.5"/>
<Int8 name="small" valueReference="11" causality="output"/>
<UInt64 name="big" valueReference="12" causality="parameter" variability="fixed" start="5000000000"/>
<Float64 name="u" valueReference="13" causality="input" start="1 2 3"><Dimension start="3"/></Float64>
<Float64 name="m" valueReference="14" causality="output"><Dimension start="2"/><Dimension start="2"/></Float64>
<UInt64 name="size" valueReference="9" causality="structuralParameter" variability="fixed" start="3"/>
  </ModelVariables>"#,
    );
    let md = ModelDescription::parse(&xml).expect("parses");
    let gain = md.variable("gain").expect("gain");
    assert_eq!((gain.variable_type, gain.start.clone()), (VariableType::Real, Some(Value::Real(0.5))));
    assert_eq!(md.variable("small").map(|v| v.variable_type), Some(VariableType::Integer));
    assert_eq!(md.variable("big").map(|v| v.start.clone()), Some(None), "a start outside 32 bits is not a row start");
    let elements: Vec<(&str, Option<Value>)> =
        ["u[1]", "u[2]", "u[3]"].iter().map(|n| (*n, md.variable(n).and_then(|v| v.start.clone()))).collect();
    assert_eq!(
        elements,
        [("u[1]", Some(Value::Real(1.0))), ("u[2]", Some(Value::Real(2.0))), ("u[3]", Some(Value::Real(3.0)))]
    );
    assert!(["m[1,1]", "m[1,2]", "m[2,1]", "m[2,2]"].iter().all(|n| md.variable(n).is_some()));
    assert!(md.variable("u").is_none(), "an array is its elements");
    // Element value references come after the largest the FMU uses, and are unique.
    let mut references: Vec<u32> = md.variables.iter().map(|v| v.value_reference).collect();
    assert_eq!(md.variable("u[1]").map(|v| v.value_reference), Some(15));
    references.sort_unstable();
    references.dedup();
    assert_eq!(references.len(), md.variables.len());
    // Every converted row and element is listed with how it is reached.
    let m12 = md.fmi3_elements.iter().find(|e| e.name == "m[1,2]").expect("m[1,2]");
    assert_eq!((m12.fmi3_value_reference, m12.fmi3_type, m12.index, m12.size), (14, Fmi3Type::Float64, 1, 4));
    let gain = md.fmi3_elements.iter().find(|e| e.name == "gain").expect("gain");
    assert_eq!((gain.fmi3_type, gain.size), (Fmi3Type::Float32, 1));
    assert!(md.fmi3_elements.iter().all(|e| e.name != "x" && e.name != "n"), "direct scalars need no element");
    // A structural parameter is read, never set (only Configuration Mode may set it).
    assert_eq!(md.variable("size").map(|v| v.causality), Some(Causality::CalculatedParameter));
}

#[test]
fn fmi3_variables_no_row_can_carry_are_refused_by_name() {
    let with = |variable: &str| FMI3.replace("  </ModelVariables>", &format!("    {variable}\n  </ModelVariables>"));
    let refused = [
        (r#"<Binary name="blob" valueReference="20" causality="output"/>"#, r#"variable "blob" is an FMI 3.0 Binary"#),
        (r#"<Clock name="tick" valueReference="20" causality="input"/>"#, r#"variable "tick" is an FMI 3.0 Clock"#),
        (
            r#"<String name="words" valueReference="20" causality="output"><Dimension start="2"/></String>"#,
            r#"variable "words" is a String array"#,
        ),
        (
            r#"<Float64 name="v" valueReference="20" causality="output"><Dimension valueReference="3"/></Float64>"#,
            r#"array "v" is sized by a structural parameter"#,
        ),
        (
            r#"<Float64 name="w" valueReference="20" causality="input" start="1 2"><Dimension start="3"/></Float64>"#,
            r#"array "w" has 3 elements but 2 start values"#,
        ),
    ];
    for (variable, expected) in refused {
        let message = ModelDescription::parse(&with(variable)).expect_err(variable).to_string();
        assert!(message.contains(expected), "{message}");
    }
}

#[test]
fn model_exchange_fmus_of_either_version_are_refused_saying_so() {
    for xml in [GOOD.replace("<CoSimulation", "<ModelExchange"), FMI3.replace("<CoSimulation", "<ModelExchange")] {
        let message = ModelDescription::parse(&xml).expect_err("Model Exchange").to_string();
        assert!(message.contains("a Model Exchange FMU: this importer runs Co-Simulation FMUs only"), "{message}");
    }
    let message = ModelDescription::parse(&FMI3.replace(r#"fmiVersion="3.0""#, r#"fmiVersion="1.0""#))
        .expect_err("FMI 1.0")
        .to_string();
    assert!(message.contains(r#"FMI "2.0" and "3.0" are supported"#), "{message}");
}

#[test]
fn fmi3_arrays_beyond_the_bounds_are_refused_before_their_elements_are_made() {
    let with = |variables: &str| FMI3.replace("  </ModelVariables>", &format!("{variables}\n  </ModelVariables>"));
    let array = |name: &str, vr: u32, dimensions: &str| {
        format!(r#"<Float64 name="{name}" valueReference="{vr}" causality="output">{dimensions}</Float64>"#)
    };
    // One array of 10^9 elements (9 GB of rows before this bound), one whose sizes' product
    // overflows, one of 10^10 from two dimensions: refused at once, naming the array and the bound.
    let huge = [
        (r#"<Dimension start="1000000000"/>"#, "has 1000000000 elements (1000000000), more than the 100000"),
        (
            r#"<Dimension start="18446744073709551615"/><Dimension start="2"/>"#,
            "elements (18446744073709551615 x 2), more than the 100000",
        ),
        (r#"<Dimension start="100000"/><Dimension start="100000"/>"#, "has 10000000000 elements"),
    ];
    for (dimensions, expected) in huge {
        let started = std::time::Instant::now();
        let message = error_of(&with(&array("big", 20, dimensions)));
        assert!(message.contains(r#"array "big""#) && message.contains(expected), "{message}");
        assert!(started.elapsed().as_secs_f64() < 1.0, "refused before the elements are made");
    }
    // The largest array is read.
    let md = ModelDescription::parse(&with(&array("big", 20, r#"<Dimension start="100000"/>"#))).expect("parses");
    assert!(md.variable("big[100000]").is_some());
    // Eleven arrays of the largest size exceed the total.
    let many: String = (0..11).map(|i| array(&format!("a{i}"), 20 + i, r#"<Dimension start="100000"/>"#)).collect();
    let message = error_of(&with(&many));
    assert!(message.contains("1100006 scalars") && message.contains("more than the 1000000"), "{message}");
}

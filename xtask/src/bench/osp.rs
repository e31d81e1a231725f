//! An OSP system structure (`OspSystemStructure.xml`, the format libcosim reads) for a system
//! file of ours: the same instances, FMUs, start values and connections, stepped by libcosim's
//! fixed-step algorithm (Jacobi: every instance steps, then all outputs are transferred).

use anyhow::{anyhow, Result};
use cosim_engine::system::SystemSpec;
use fmu_import::fmu::ModelDescription;
use fmu_import::value::VariableType;
use serde_json::Value;
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

/// The XML for `spec`; `system_dir` is the folder the system file's FMU paths are relative to
/// (written into `source` as given, so an absolute folder gives absolute sources) and `models`
/// maps each FMU alias to its model description (for the types of the start values).
pub fn system_structure(
    spec: &SystemSpec,
    system_dir: &Path,
    models: &BTreeMap<String, ModelDescription>,
) -> Result<String> {
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n");
    xml.push_str(
        "<OspSystemStructure xmlns=\"http://opensimulationplatform.com/MSMI/OSPSystemStructure\" version=\"0.1\">\n",
    );
    writeln!(xml, "  <StartTime>{:?}</StartTime>", spec.start_time)?;
    writeln!(xml, "  <BaseStepSize>{:?}</BaseStepSize>", spec.step_size)?;
    xml.push_str("  <Algorithm>fixedStep</Algorithm>\n  <Simulators>\n");
    for instance in &spec.instances {
        let fmu = spec
            .fmus
            .get(&instance.fmu)
            .ok_or_else(|| anyhow!("instance {}: no FMU '{}'", instance.name, instance.fmu))?;
        let model = models.get(&instance.fmu).ok_or_else(|| anyhow!("no model description of '{}'", instance.fmu))?;
        let source = system_dir.join(fmu);
        writeln!(
            xml,
            "    <Simulator name=\"{}\" source=\"{}\">",
            escape(&instance.name),
            escape(&source.to_string_lossy())
        )?;
        xml.push_str("      <InitialValues>\n");
        for (variable, value) in &instance.start {
            let element =
                initial_value(model, variable, value).map_err(|e| anyhow!("{}.{variable}: {e}", instance.name))?;
            writeln!(xml, "        <InitialValue variable=\"{}\">{element}</InitialValue>", escape(variable))?;
        }
        xml.push_str("      </InitialValues>\n    </Simulator>\n");
    }
    xml.push_str("  </Simulators>\n  <Connections>\n");
    for connection in &spec.connections {
        xml.push_str("    <VariableConnection>\n");
        for end in [&connection.from, &connection.to] {
            let (simulator, variable) =
                end.split_once('.').ok_or_else(|| anyhow!("connection end '{end}' is not instance.variable"))?;
            writeln!(xml, "      <Variable simulator=\"{}\" name=\"{}\"/>", escape(simulator), escape(variable))?;
        }
        xml.push_str("    </VariableConnection>\n");
    }
    xml.push_str("  </Connections>\n</OspSystemStructure>\n");
    Ok(xml)
}

/// `<Real value="…"/>` etc. for a JSON start value of the variable's declared type.
fn initial_value(model: &ModelDescription, variable: &str, value: &Value) -> Result<String> {
    let declared = model.variable(variable).ok_or_else(|| anyhow!("not a variable of {}", model.model_name))?;
    let (element, text) = match declared.variable_type {
        // `{:?}` is the shortest text that reads back as the same double.
        VariableType::Real => {
            ("Real", format!("{:?}", value.as_f64().ok_or_else(|| anyhow!("{value} is not a number"))?))
        }
        VariableType::Integer | VariableType::Enumeration => {
            ("Integer", value.as_i64().ok_or_else(|| anyhow!("{value} is not an integer"))?.to_string())
        }
        VariableType::Boolean => {
            ("Boolean", value.as_bool().ok_or_else(|| anyhow!("{value} is not true/false"))?.to_string())
        }
        VariableType::String => ("String", escape(value.as_str().ok_or_else(|| anyhow!("{value} is not a string"))?)),
    };
    Ok(format!("<{element} value=\"{text}\"/>"))
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODEL: &str = r#"<?xml version="1.0"?>
<fmiModelDescription fmiVersion="2.0" modelName="imu" guid="{g}">
  <CoSimulation modelIdentifier="imu"/>
  <ModelVariables>
    <ScalarVariable name="seed" valueReference="0" causality="parameter" variability="fixed"><Integer start="0"/></ScalarVariable>
    <ScalarVariable name="noise" valueReference="1" causality="parameter" variability="fixed"><Boolean start="false"/></ScalarVariable>
    <ScalarVariable name="gain" valueReference="2" causality="parameter" variability="fixed"><Real start="1"/></ScalarVariable>
    <ScalarVariable name="a.x" valueReference="3" causality="input" variability="continuous"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="y.x" valueReference="4" causality="output" variability="continuous"><Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure><Outputs><Unknown index="5"/></Outputs></ModelStructure>
</fmiModelDescription>"#;

    fn spec(json: &str) -> SystemSpec {
        serde_json::from_str(json).unwrap()
    }

    fn models() -> BTreeMap<String, ModelDescription> {
        BTreeMap::from([("imu".to_string(), ModelDescription::parse(MODEL).unwrap())])
    }

    #[test]
    fn instances_start_values_and_connections_are_carried_over() {
        // `gain: 2` is written as a JSON integer but is a Real: the type comes from the model.
        let spec = spec(
            r#"{"fmus": {"imu": "../fmu/imu.fmu"}, "stop_time": 1, "step_size": 0.01,
                "instances": [{"name": "imu1", "fmu": "imu", "start": {"seed": 3, "noise": true, "gain": 2}},
                              {"name": "imu2", "fmu": "imu", "start": {"gain": -0.40142572795869574}}],
                "connections": [{"from": "imu1.y.x", "to": "imu2.a.x"}]}"#,
        );
        let xml = system_structure(&spec, Path::new("/sys"), &models()).unwrap();
        let expected = r#"<?xml version="1.0" encoding="utf-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure" version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>0.01</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="imu1" source="/sys/../fmu/imu.fmu">
      <InitialValues>
        <InitialValue variable="gain"><Real value="2.0"/></InitialValue>
        <InitialValue variable="noise"><Boolean value="true"/></InitialValue>
        <InitialValue variable="seed"><Integer value="3"/></InitialValue>
      </InitialValues>
    </Simulator>
    <Simulator name="imu2" source="/sys/../fmu/imu.fmu">
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
        assert_eq!(xml, expected);
    }

    #[test]
    fn start_values_of_the_wrong_type_or_unknown_variables_are_errors() {
        let with_start = |start: &str| {
            spec(&format!(
                r#"{{"fmus": {{"imu": "imu.fmu"}}, "stop_time": 1, "step_size": 0.01,
                     "instances": [{{"name": "imu1", "fmu": "imu", "start": {start}}}]}}"#
            ))
        };
        for bad in [r#"{"seed": 1.5}"#, r#"{"noise": 1}"#, r#"{"nothing": 1}"#, r#"{"gain": "x"}"#] {
            assert!(system_structure(&with_start(bad), Path::new(""), &models()).is_err(), "{bad}");
        }
    }
}

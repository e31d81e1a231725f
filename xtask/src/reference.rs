//! fmi-cross-check reference files next to every packaged FMU, so any importer can check itself:
//! `<model>_ref.opt` (experiment), `<model>_in.csv` (input signals, for FMUs with inputs) and
//! `<model>_ref.csv` (every output at every communication point).
//!
//! The cases are data, not code: `references/experiment.opt` is the experiment of every FMU and
//! `references/signals.csv` lists each input as a wave `mean + amplitude·sin(omega·t + phase)`,
//! sampled here at the communication points; inputs without a wave are held at their start
//! values, so `_in.csv` has a column for every input. The results are whatever the Rust importer
//! computes from those files, so no output value is written down anywhere. Every FMU runs with
//! its default start values (noise seeds included): the cross-check format has no place for
//! start values, and an importer that reads only these files must reproduce the results.

use crate::{build_master, root, run_command};
use anyhow::{anyhow, bail, ensure, Context, Result};
use fmu_import::fmu::{Causality, ExtractLimits, Fmu};
use fmu_import::value::Value;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

/// The cross-check rules cap every CSV file at one megabyte.
const MAX_CSV_BYTES: usize = 1_000_000;

/// The reference files of one FMU, by file name in the folder of its archive.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ReferenceFiles {
    /// `<model>_ref.opt`: the experiment.
    pub options: String,
    /// `<model>_in.csv`, for FMUs with inputs.
    pub inputs: Option<String>,
    /// `<model>_ref.csv`: every output at every communication point.
    pub results: String,
}

/// Writes the reference files of `models` into `fmu_dir`, where `<model>.fmu` already is; returns
/// them in the order of `models`.
pub fn write_all(models: &[&str], fmu_dir: &Path) -> Result<Vec<ReferenceFiles>> {
    let default = Experiment::parse(&read(&root().join("references/experiment.opt"))?)?;
    let mut signals = parse_signals(&read(&root().join("references/signals.csv"))?)?;
    if let Some(unknown) = signals.keys().find(|model| !models.contains(&model.as_str())) {
        bail!("references/signals.csv: {unknown:?} is not a packaged FMU");
    }
    let master = build_master()?;
    // Scratch space for the importer's system files and raw results (kept for rerunning by hand).
    let scratch = root().join("target/reference");
    std::fs::create_dir_all(&scratch)?;
    let mut written = Vec::new();
    for model in models {
        let waves = signals.remove(*model).unwrap_or_default();
        let experiment = experiment_of(model, &default)?;
        let files = write_model(model, waves, &experiment, fmu_dir, &master, &scratch)
            .with_context(|| format!("reference files of {model}"))?;
        println!("reference files of {model}: {}", fmu_dir.join(format!("{model}_ref.*")).display());
        written.push(files);
    }
    Ok(written)
}

fn write_model(
    model: &str,
    waves: Vec<Wave>,
    experiment: &Experiment,
    fmu_dir: &Path,
    master: &Path,
    scratch: &Path,
) -> Result<ReferenceFiles> {
    let files =
        ReferenceFiles { options: format!("{model}_ref.opt"), inputs: None, results: format!("{model}_ref.csv") };
    std::fs::write(fmu_dir.join(&files.options), experiment.opt_text())?;
    let columns = input_columns(real_inputs(&fmu_dir.join(format!("{model}.fmu")))?, waves)?;
    let input = fmu_dir.join(format!("{model}_in.csv"));
    if columns.is_empty() {
        // A stale table from an earlier build would wrongly claim the FMU has inputs.
        remove_if_present(&input)?;
    } else {
        write_csv(&input, input_csv(&columns, &experiment.times()))?;
    }
    let system = scratch.join(format!("{model}.json"));
    let fmu = fmu_dir.join(format!("{model}.fmu"));
    std::fs::write(&system, system_json(model, &fmu, (!columns.is_empty()).then_some(&input), experiment)?)?;
    let raw = scratch.join(format!("{model}_out.csv"));
    run_command(Command::new(master).arg("run").arg(&system).arg("--output").arg(&raw).arg("-q"))?;
    write_csv(&fmu_dir.join(&files.results), reference_csv(&read(&raw)?, model)?)?;
    Ok(ReferenceFiles { inputs: (!columns.is_empty()).then(|| format!("{model}_in.csv")), ..files })
}

/// The experiment of `model`: `references/<model>.opt` where an FMU's results would not fit the
/// cross-check's 1 MB at the common experiment's length, else `references/experiment.opt`.
fn experiment_of(model: &str, default: &Experiment) -> Result<Experiment> {
    let own = root().join(format!("references/{model}.opt"));
    if own.is_file() {
        Experiment::parse(&read(&own)?).with_context(|| format!("{}", own.display()))
    } else {
        Ok(default.clone())
    }
}

/// The Real inputs of a packaged FMU with their start values, in model-description order, read
/// from the archive as an importer sees it.
fn real_inputs(fmu: &Path) -> Result<Vec<(String, f64)>> {
    let fmu = Fmu::open(fmu, &ExtractLimits::default())?;
    let inputs = fmu.model_description().variables.iter().filter(|v| v.causality == Causality::Input);
    inputs
        .map(|v| match v.start {
            Some(Value::Real(start)) => Ok((v.name.clone(), start)),
            _ => Err(anyhow!("input {:?} is not a Real with a start value", v.name)),
        })
        .collect()
}

/// One column per input, so an importer needs no start values: the input's wave from
/// signals.csv, or its start value held constant.
fn input_columns(inputs: Vec<(String, f64)>, mut waves: Vec<Wave>) -> Result<Vec<Wave>> {
    let columns = inputs
        .into_iter()
        .map(|(input, start)| match waves.iter().position(|w| w.input == input) {
            Some(index) => waves.swap_remove(index),
            None => Wave { input, mean: start, amplitude: 0.0, omega: 0.0, phase: 0.0 },
        })
        .collect();
    if let Some(wave) = waves.first() {
        bail!("signals.csv: {:?} is not an input of the FMU", wave.input);
    }
    Ok(columns)
}

/// The `_ref.opt` settings; the cross-check rules require exactly these four.
#[derive(Debug, Clone, PartialEq)]
struct Experiment {
    start: f64,
    stop: f64,
    step: f64,
    rel_tol: f64,
}

impl Experiment {
    /// Parses `Key, value` lines (blank lines ignored); all four keys are required.
    fn parse(text: &str) -> Result<Self> {
        let mut values = BTreeMap::new();
        for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
            let (key, value) = line.split_once(',').with_context(|| format!("{line:?} is not `Key, value`"))?;
            let value: f64 = value.trim().parse().with_context(|| format!("{line:?}: not a number"))?;
            values.insert(key.trim(), value);
        }
        let get = |key: &str| values.get(key).copied().with_context(|| format!("experiment.opt: {key} is missing"));
        let experiment =
            Self { start: get("StartTime")?, stop: get("StopTime")?, step: get("StepSize")?, rel_tol: get("RelTol")? };
        ensure!(
            experiment.step > 0.0 && experiment.stop > experiment.start,
            "experiment.opt: needs StepSize > 0 and StopTime > StartTime"
        );
        Ok(experiment)
    }

    fn opt_text(&self) -> String {
        format!(
            "StartTime, {:?}\nStopTime, {:?}\nStepSize, {:?}\nRelTol, {:?}\n",
            self.start, self.stop, self.step, self.rel_tol
        )
    }

    /// The communication points `start + i·step`, both ends included.
    fn times(&self) -> Vec<f64> {
        let steps = ((self.stop - self.start) / self.step).round() as u64;
        (0..=steps).map(|i| self.start + i as f64 * self.step).collect()
    }
}

/// One input signal: `mean + amplitude·sin(omega·t + phase)`.
#[derive(Debug, Clone, PartialEq)]
struct Wave {
    input: String,
    mean: f64,
    amplitude: f64,
    omega: f64,
    phase: f64,
}

impl Wave {
    fn at(&self, t: f64) -> f64 {
        self.mean + self.amplitude * (self.omega * t + self.phase).sin()
    }
}

const SIGNALS_HEADER: &str = "model,input,mean,amplitude,omega,phase";

/// Parses `references/signals.csv` into the waves of each model, in file order.
fn parse_signals(text: &str) -> Result<BTreeMap<String, Vec<Wave>>> {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    ensure!(lines.next() == Some(SIGNALS_HEADER), "signals.csv: the header must be {SIGNALS_HEADER}");
    let mut models: BTreeMap<String, Vec<Wave>> = BTreeMap::new();
    for line in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [model, input, numbers @ ..] = fields.as_slice() else { bail!("signals.csv: {line:?} is too short") };
        let numbers = numbers.iter().map(|n| n.parse::<f64>()).collect::<Result<Vec<_>, _>>();
        let Ok([mean, amplitude, omega, phase]) = numbers.as_deref() else {
            bail!("signals.csv: {line:?} needs four numbers")
        };
        let waves = models.entry(model.to_string()).or_default();
        ensure!(waves.iter().all(|w| w.input != *input), "signals.csv: {model}.{input} appears twice");
        waves.push(Wave { input: input.to_string(), mean: *mean, amplitude: *amplitude, omega: *omega, phase: *phase });
    }
    Ok(models)
}

/// `"time","<input>",...` then one row per time; shortest round-trip numbers, so FMPy's
/// `read_csv` and the importer read back exactly the values the importer ran with.
fn input_csv(waves: &[Wave], times: &[f64]) -> String {
    let mut text = quoted_header(std::iter::once("time").chain(waves.iter().map(|w| w.input.as_str())));
    for &t in times {
        write!(text, "{t:?}").expect("writing to a String");
        for wave in waves {
            write!(text, ",{:?}", wave.at(t)).expect("writing to a String");
        }
        text.push('\n');
    }
    text
}

/// A single-instance system for the importer; `input_derivatives` stays off because FMPy's
/// `simulate_fmu` passes none either (both interpolate inputs linearly at communication points).
fn system_json(model: &str, fmu: &Path, input: Option<&Path>, e: &Experiment) -> Result<String> {
    let inputs = match input {
        Some(file) => format!(r#"[{{ "instance": "{model}", "file": {} }}]"#, json_path(file)?),
        None => "[]".into(),
    };
    Ok(format!(
        r#"{{
  "description": "fmi-cross-check reference run of {model} with its default start values",
  "fmus": {{ "{model}": {} }},
  "instances": [{{ "name": "{model}", "fmu": "{model}" }}],
  "inputs": {inputs},
  "start_time": {:?}, "stop_time": {:?}, "step_size": {:?},
  "input_derivatives": false
}}
"#,
        json_path(fmu)?,
        e.start,
        e.stop,
        e.step
    ))
}

/// A path as a JSON string (quotes and backslashes escaped; paths hold no control characters).
fn json_path(path: &Path) -> Result<String> {
    let text = path.to_str().with_context(|| format!("{} is not UTF-8", path.display()))?;
    Ok(format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\"")))
}

/// The importer's result with the cross-check header: `<model>.<output>` becomes `"<output>"`.
fn reference_csv(master_output: &str, model: &str) -> Result<String> {
    let (header, rows) = master_output.split_once('\n').context("the master wrote no header")?;
    let prefix = format!("{model}.");
    let mut names = header.trim_end().split(',');
    ensure!(names.next() == Some("time"), "unexpected header {header:?}");
    let names: Vec<&str> =
        names.map(|n| n.strip_prefix(&prefix).with_context(|| format!("column {n:?}"))).collect::<Result<_>>()?;
    Ok(quoted_header(std::iter::once("time").chain(names)) + rows)
}

/// The cross-check header row: names in double quotes.
fn quoted_header<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names.map(|n| format!("\"{n}\"")).collect::<Vec<_>>().join(",") + "\n"
}

fn write_csv(path: &Path, text: String) -> Result<()> {
    ensure!(
        text.len() <= MAX_CSV_BYTES,
        "{} would be {} bytes, over the cross-check limit of 1 MB",
        path.display(),
        text.len()
    );
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))
}

fn remove_if_present(path: &Path) -> Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            Err(e).with_context(|| format!("removing {}", path.display()))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn experiment_round_trips_through_the_opt_format() {
        let e = Experiment::parse("StartTime, 0.0\nStopTime,  2.0\n\nStepSize, 0.5\nRelTol, 1e-4\n").unwrap();
        assert_eq!(e, Experiment { start: 0.0, stop: 2.0, step: 0.5, rel_tol: 1e-4 });
        assert_eq!(e.times(), [0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(Experiment::parse(&e.opt_text()).unwrap(), e);
        assert!(Experiment::parse("StartTime, 0\nStopTime, 1\nStepSize, 0.1\n")
            .unwrap_err()
            .to_string()
            .contains("RelTol"));
    }

    #[test]
    fn signals_are_grouped_by_model_in_file_order() {
        let models =
            parse_signals("model,input,mean,amplitude,omega,phase\na,y,1,2,3,0\nb,x,0,1,1,0\na,x,0,1,1,0.5\n").unwrap();
        let names: Vec<&str> = models["a"].iter().map(|w| w.input.as_str()).collect();
        assert_eq!(names, ["y", "x"]);
        assert_eq!(models["a"][0].at(0.0), 1.0);
        assert!(parse_signals("model,input,mean,amplitude,omega,phase\na,x,0,1,1,0\na,x,0,1,1,0\n").is_err());
        assert!(parse_signals("model,input,mean,amplitude,omega,phase\na,x,0,1,one,0\n").is_err());
    }

    #[test]
    fn every_input_gets_a_column_held_at_its_start_unless_it_has_a_wave() {
        let wave = |input: &str, mean| Wave { input: input.into(), mean, amplitude: 1.0, omega: 2.0, phase: 0.0 };
        let inputs = vec![("a".to_string(), 1.0), ("b".to_string(), 2.0)];
        let columns = input_columns(inputs.clone(), vec![wave("b", 5.0)]).unwrap();
        assert_eq!(columns[0], Wave { input: "a".into(), mean: 1.0, amplitude: 0.0, omega: 0.0, phase: 0.0 });
        assert_eq!(columns[1], wave("b", 5.0));
        let unknown = input_columns(inputs, vec![wave("c", 0.0)]).unwrap_err().to_string();
        assert!(unknown.contains("\"c\" is not an input"), "{unknown}");
    }

    #[test]
    fn system_files_escape_paths_and_pass_no_input_derivatives() {
        let e = Experiment { start: 0.0, stop: 1.0, step: 0.5, rel_tol: 1e-4 };
        let json = system_json("imu", Path::new("/x/imu.fmu"), Some(Path::new(r#"/a"b\in.csv"#)), &e).unwrap();
        assert!(json.contains(r#""file": "/a\"b\\in.csv""#), "{json}");
        assert!(json.contains(r#""fmus": { "imu": "/x/imu.fmu" }"#) && json.contains(r#""input_derivatives": false"#));
        assert!(system_json("imu", Path::new("imu.fmu"), None, &e).unwrap().contains(r#""inputs": [],"#));
    }

    #[test]
    fn csv_files_have_quoted_headers_and_exact_numbers() {
        let wave = Wave { input: "u.x".into(), mean: 0.1, amplitude: 0.0, omega: 0.0, phase: 0.0 };
        assert_eq!(input_csv(&[wave], &[0.0, 0.25]), "\"time\",\"u.x\"\n0.0,0.1\n0.25,0.1\n");
        let reference = reference_csv("time,imu.gyro.x,imu.acc.z\n0.0,1e-7,-9.8\n", "imu").unwrap();
        assert_eq!(reference, "\"time\",\"gyro.x\",\"acc.z\"\n0.0,1e-7,-9.8\n");
        assert!(reference_csv("time,crane.lp\n", "imu").is_err());
    }
}

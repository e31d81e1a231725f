//! Recording variables to a CSV file.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use super::{Observer, ObserverError};
use fmu_import::value::VariableType;

use crate::simulator::Simulator;
use crate::variable::VariableRef;

/// Variables of one instance and their columns.
#[derive(Debug, Default)]
struct Group {
    slave: usize,
    real: (Vec<u32>, Vec<usize>),
    integer: (Vec<u32>, Vec<usize>),
    boolean: (Vec<u32>, Vec<usize>),
    string: (Vec<u32>, Vec<usize>),
}

/// Writes `time,<instance>.<variable>,...` rows to a CSV file.
///
/// * Header: `time` then the qualified names, unquoted. `fmpy.util.read_csv`
///   reads it as a structured array whose field names keep the dots, e.g.
///   `result["load.theta_x"]`.
/// * Reals (and time) use Rust's shortest round-trip formatting (`{:?}`:
///   `0.1`, `1e-7`, `NaN`, `inf`), so every value reads back bit-exactly.
/// * Booleans are `0`/`1`, integers and enumerations decimal; strings are
///   quoted by CSV rules when needed (FMPy cannot read string columns).
/// * A row is written at `k = 0, every, 2·every, ...`.
/// * Values are what the FMUs report at `t_k`; for an input that is the
///   value set for the step that ended at `t_k` (set at `t_{k−1}`), since
///   inputs for the next step are set only just before it.
pub struct CsvRecorder {
    file: PathBuf,
    writer: csv::Writer<BufWriter<File>>,
    every: u64,
    groups: Vec<Group>,
    row: Vec<String>,
    rows: u64,
}

impl std::fmt::Debug for CsvRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CsvRecorder").field("file", &self.file).field("rows", &self.rows).finish_non_exhaustive()
    }
}

impl CsvRecorder {
    /// Creates `file` (and its parent directories) and writes the header.
    pub fn create(file: &Path, variables: &[VariableRef], every: u64) -> Result<Self, ObserverError> {
        let io_error = |source| ObserverError::Io { file: file.to_path_buf(), source };
        if let Some(parent) = file.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).map_err(io_error)?;
        }
        let output = File::create(file).map_err(io_error)?;
        let mut writer = csv::WriterBuilder::new().from_writer(BufWriter::new(output));

        let mut groups: Vec<Group> = Vec::new();
        for (position, variable) in variables.iter().enumerate() {
            let column = position + 1;
            let group = match groups.iter().position(|g| g.slave == variable.instance) {
                Some(index) => &mut groups[index],
                None => {
                    groups.push(Group { slave: variable.instance, ..Group::default() });
                    let last = groups.len() - 1;
                    &mut groups[last]
                }
            };
            let vr = variable.variable.value_reference;
            let target = match variable.variable.variable_type.abi_type() {
                VariableType::Real => &mut group.real,
                VariableType::Boolean => &mut group.boolean,
                VariableType::String => &mut group.string,
                VariableType::Integer | VariableType::Enumeration => &mut group.integer,
            };
            target.0.push(vr);
            target.1.push(column);
        }

        let header = std::iter::once("time").chain(variables.iter().map(|v| v.qualified_name.as_str()));
        writer.write_record(header).map_err(|source| ObserverError::Csv { file: file.to_path_buf(), source })?;
        Ok(Self {
            file: file.to_path_buf(),
            writer,
            every: every.max(1),
            groups,
            row: vec![String::new(); variables.len() + 1],
            rows: 0,
        })
    }

    /// Data rows written so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// The output file.
    pub fn file(&self) -> &Path {
        &self.file
    }
}

impl Observer for CsvRecorder {
    // `u64::is_multiple_of` needs Rust 1.87; the workspace supports 1.80.
    #[allow(clippy::manual_is_multiple_of)]
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        if k % self.every != 0 {
            return Ok(());
        }
        self.row[0] = format!("{time:?}");
        for group in &self.groups {
            let slave = &slaves[group.slave];
            if !group.real.0.is_empty() {
                let mut values = vec![0.0; group.real.0.len()];
                slave.get_real(&group.real.0, &mut values)?;
                for (&column, value) in group.real.1.iter().zip(values) {
                    self.row[column] = format!("{value:?}");
                }
            }
            if !group.integer.0.is_empty() {
                let mut values = vec![0; group.integer.0.len()];
                slave.get_integer(&group.integer.0, &mut values)?;
                for (&column, value) in group.integer.1.iter().zip(values) {
                    self.row[column] = value.to_string();
                }
            }
            if !group.boolean.0.is_empty() {
                let mut values = vec![false; group.boolean.0.len()];
                slave.get_boolean(&group.boolean.0, &mut values)?;
                for (&column, value) in group.boolean.1.iter().zip(values) {
                    self.row[column] = u8::from(value).to_string();
                }
            }
            if !group.string.0.is_empty() {
                let values = slave.get_string(&group.string.0)?;
                for (&column, value) in group.string.1.iter().zip(values) {
                    self.row[column] = value;
                }
            }
        }
        self.writer.write_record(&self.row).map_err(|source| ObserverError::Csv { file: self.file.clone(), source })?;
        self.rows += 1;
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        self.writer.flush().map_err(|source| ObserverError::Io { file: self.file.clone(), source })
    }
}

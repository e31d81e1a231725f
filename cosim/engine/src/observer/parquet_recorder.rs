//! Recording variables to a Parquet file (`crane-cosim run -o results.parquet`).

use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use fmu_import::value::VariableType;
use parquet::basic::{LogicalType, Repetition, Type as PhysicalType};
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DoubleType, Int32Type};
use parquet::errors::ParquetError;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;

use super::row::{Cell, Row};
use super::{FlushPolicy, Live, Observer, ObserverError, RecordedRows};
use crate::partial::PartialFile;
use crate::simulator::Simulator;
use crate::variable::VariableRef;

/// The key of the file's key-value metadata that holds the units.
pub const UNITS_KEY: &str = "units";

/// Writes `time` and the recorded variables as the columns of a Parquet file.
///
/// * Columns, all required (no nulls): `time` and Reals as DOUBLE (the same bits the CSV's
///   shortest decimals read back to), Integers and Enumerations as INT32, Booleans as BOOLEAN,
///   Strings as UTF-8 BYTE_ARRAY; named like the CSV's header (`pendulum.theta_x`).
/// * Units: the file's key-value metadata `units` is a JSON object from column name to unit
///   (`{"time": "s", "pendulum.theta_x": "rad", …}`), with the columns whose variable declares
///   no unit left out; pyarrow reads it as `pq.read_schema(f).metadata[b"units"]`.
/// * Rows are written as one row group per [`FlushPolicy`] batch (rows or wall time, whichever
///   comes first); the footer that makes the file readable is written by
///   [`Observer::finish`], which runs also after a failed or interrupted run, and by an
///   emergency end ([`flush_live_recorders`](super::flush_live_recorders)), so every row computed
///   is in the file.
pub struct ParquetRecorder {
    file: PathBuf,
    every: u64,
    row: Row,
    sink: Arc<Shared>,
}

/// The writer and the rows of the current row group, shared with an emergency end.
pub(crate) struct Shared {
    sink: Mutex<Sink>,
}

struct Sink {
    /// `None` once closed.
    writer: Option<SerializedFileWriter<File>>,
    /// Renamed to the target once closed.
    partial: PartialFile,
    time: Vec<f64>,
    columns: Vec<Column>,
    pending_rows: u64,
    flush: FlushPolicy,
    last_flush: Instant,
    rows: u64,
    last_time: Option<f64>,
}

/// The values of one column in the current row group.
enum Column {
    Double(Vec<f64>),
    Int32(Vec<i32>),
    Boolean(Vec<bool>),
    Text(Vec<ByteArray>),
}

impl Sink {
    /// Writes the pending rows as one row group.
    fn write_pending(&mut self) -> Result<(), ParquetError> {
        let Some(writer) = self.writer.as_mut() else { return Ok(()) };
        if self.pending_rows == 0 {
            return Ok(());
        }
        let mut group = writer.next_row_group()?;
        let missing = || ParquetError::General("fewer columns than the schema".into());
        let mut time = group.next_column()?.ok_or_else(missing)?;
        time.typed::<DoubleType>().write_batch(&self.time, None, None)?;
        time.close()?;
        for column in &mut self.columns {
            let mut writer = group.next_column()?.ok_or_else(missing)?;
            match column {
                Column::Double(values) => writer.typed::<DoubleType>().write_batch(values, None, None)?,
                Column::Int32(values) => writer.typed::<Int32Type>().write_batch(values, None, None)?,
                Column::Boolean(values) => writer.typed::<BoolType>().write_batch(values, None, None)?,
                Column::Text(values) => writer.typed::<ByteArrayType>().write_batch(values, None, None)?,
            };
            writer.close()?;
            column.clear();
        }
        group.close()?;
        self.time.clear();
        self.pending_rows = 0;
        self.last_flush = Instant::now();
        Ok(())
    }

    /// Writes the pending rows and the footer and puts the file in place if it holds a row
    /// ([`crate::partial`]); later calls do nothing.
    fn close(&mut self) -> Result<(), ParquetError> {
        self.write_pending()?;
        if let Some(writer) = self.writer.take() {
            writer.close()?;
        }
        self.partial.settle(self.rows).map_err(|error| ParquetError::External(Box::new(error)))
    }
}

impl Column {
    fn clear(&mut self) {
        match self {
            Column::Double(values) => values.clear(),
            Column::Int32(values) => values.clear(),
            Column::Boolean(values) => values.clear(),
            Column::Text(values) => values.clear(),
        }
    }
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Sink> {
        self.sink.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl RecordedRows for Shared {
    fn recorded(&self) -> (u64, Option<f64>) {
        let sink = self.lock();
        (sink.rows, sink.last_time)
    }
}

/// Parquet recorders alive in the process, closed by an emergency end.
static LIVE: Live<Shared> = Live::new();

/// Writes every live Parquet recorder's pending rows and footer.
pub(super) fn close_live() {
    LIVE.each(|shared| {
        let _ = shared.lock().close();
    });
}

/// True if `file` is to be written as Parquet: its name ends in `.parquet` (any case).
pub fn is_parquet(file: &Path) -> bool {
    file.extension().is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
}

impl std::fmt::Debug for ParquetRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParquetRecorder").field("file", &self.file).finish_non_exhaustive()
    }
}

impl ParquetRecorder {
    /// Creates a partial file beside `file` (and `file`'s parent directories) with the schema
    /// of `variables`, renamed to `file` when the run ends with a row ([`crate::partial`]).
    pub fn create(file: &Path, variables: &[VariableRef], every: u64) -> Result<Self, ObserverError> {
        let error =
            |message: String| ObserverError::Io { file: file.to_path_buf(), source: std::io::Error::other(message) };
        let io_error = |source| ObserverError::Io { file: file.to_path_buf(), source };
        let (output, partial) = PartialFile::create(file).map_err(io_error)?;

        let mut fields = vec![field("time", PhysicalType::DOUBLE, None).map_err(|e| error(e.to_string()))?];
        let mut columns = Vec::with_capacity(variables.len());
        let mut units = BTreeMap::from([("time".to_string(), "s".to_string())]);
        for variable in variables {
            let (physical, logical, column) = match variable.variable.variable_type.abi_type() {
                VariableType::Real => (PhysicalType::DOUBLE, None, Column::Double(Vec::new())),
                VariableType::Boolean => (PhysicalType::BOOLEAN, None, Column::Boolean(Vec::new())),
                VariableType::String => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String), Column::Text(Vec::new())),
                VariableType::Integer | VariableType::Enumeration => {
                    (PhysicalType::INT32, None, Column::Int32(Vec::new()))
                }
            };
            fields.push(field(&variable.qualified_name, physical, logical).map_err(|e| error(e.to_string()))?);
            columns.push(column);
            if let Some(unit) = variable.variable.unit.as_ref().filter(|u| !u.is_empty()) {
                units.insert(variable.qualified_name.clone(), unit.clone());
            }
        }
        let schema =
            Type::group_type_builder("results").with_fields(fields).build().map_err(|e| error(e.to_string()))?;
        let units = serde_json::to_string(&units).map_err(|e| error(e.to_string()))?;
        let properties = WriterProperties::builder()
            .set_created_by(format!("crane-cosim {}", env!("CARGO_PKG_VERSION")))
            .set_key_value_metadata(Some(vec![KeyValue::new(UNITS_KEY.to_string(), units)]))
            .build();
        let writer = SerializedFileWriter::new(output, Arc::new(schema), Arc::new(properties))
            .map_err(|e| error(e.to_string()))?;
        let sink = Sink {
            writer: Some(writer),
            partial,
            time: Vec::new(),
            columns,
            pending_rows: 0,
            flush: FlushPolicy::default(),
            last_flush: Instant::now(),
            rows: 0,
            last_time: None,
        };
        let sink = Arc::new(Shared { sink: Mutex::new(sink) });
        LIVE.add(&sink);
        Ok(Self { file: file.to_path_buf(), every: every.max(1), row: Row::new(variables), sink })
    }

    /// Writes row groups as `policy` says instead of the default.
    pub fn with_flush(self, policy: FlushPolicy) -> Self {
        self.sink.lock().flush = policy;
        self
    }

    /// The shared rows, for an emergency end's summary.
    pub(crate) fn shared(&self) -> &Arc<Shared> {
        &self.sink
    }

    /// Data rows recorded so far.
    pub fn rows(&self) -> u64 {
        self.sink.lock().rows
    }

    fn error(&self, error: ParquetError) -> ObserverError {
        let source = match error {
            ParquetError::External(external) => std::io::Error::other(external),
            other => std::io::Error::other(other.to_string()),
        };
        ObserverError::Io { file: self.file.clone(), source }
    }
}

/// A required column of `physical` type.
fn field(name: &str, physical: PhysicalType, logical: Option<LogicalType>) -> Result<Arc<Type>, ParquetError> {
    let builder = Type::primitive_type_builder(name, physical).with_repetition(Repetition::REQUIRED);
    Ok(Arc::new(builder.with_logical_type(logical).build()?))
}

impl Observer for ParquetRecorder {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        if !k.is_multiple_of(self.every) {
            return Ok(());
        }
        self.row.read(slaves)?;
        let mut sink = self.sink.lock();
        sink.time.push(time);
        for (cell, column) in self.row.cells().iter().zip(&mut sink.columns) {
            match (cell, column) {
                (Cell::Real(value), Column::Double(values)) => values.push(*value),
                (Cell::Integer(value), Column::Int32(values)) => values.push(*value),
                (Cell::Boolean(value), Column::Boolean(values)) => values.push(*value),
                (Cell::String(value), Column::Text(values)) => values.push(value.as_str().into()),
                _ => unreachable!("a cell has its column's type"),
            }
        }
        sink.pending_rows += 1;
        sink.rows += 1;
        sink.last_time = Some(time);
        if sink.pending_rows >= sink.flush.rows || sink.last_flush.elapsed() >= sink.flush.interval {
            let written = sink.write_pending();
            drop(sink);
            written.map_err(|e| self.error(e))?;
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        let closed = self.sink.lock().close();
        closed.map_err(|e| self.error(e))
    }
}

impl Drop for ParquetRecorder {
    fn drop(&mut self) {
        let _ = self.sink.lock().close();
        LIVE.remove(&self.sink);
    }
}

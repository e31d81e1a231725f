//! `results.parquet`: the collected table as one Parquet row group, uncompressed, written with the
//! parquet crate's file-level writer (no Arrow: the table is flat and small).
//!
//! Columns: `case` (UTF-8), `index` (int64), `seed` (64-bit unsigned integer: an INT64 annotated
//! unsigned, since case seeds use all 64 bits), `status` (UTF-8), every parameter and every
//! metric (float64, null where the case has no value), `wall_time` (float64, s; null for a
//! pending case).

use std::sync::Arc;

use parquet::basic::{IntType, LogicalType, Repetition, Type as PhysicalType};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{Type, TypePtr};

use super::table::{status_label, Row, Table};

/// The values of one column, in row order.
enum Column {
    Text(Vec<ByteArray>),
    /// Stored as INT64; `unsigned` marks the bits as a u64.
    Integer {
        values: Vec<i64>,
        unsigned: bool,
    },
    Float(Vec<Option<f64>>),
}

/// The Parquet file's bytes.
pub fn results_parquet(table: &Table) -> Result<Vec<u8>, ParquetError> {
    let columns = columns(table);
    let fields = columns.iter().map(|(name, column)| field(name, column)).collect::<Result<Vec<_>, _>>()?;
    let schema = Arc::new(Type::group_type_builder("results").with_fields(fields).build()?);
    let properties = WriterProperties::builder().set_created_by(format!("crane-cosim {}", env!("CARGO_PKG_VERSION")));
    let mut writer = SerializedFileWriter::new(Vec::new(), schema, Arc::new(properties.build()))?;
    let mut row_group = writer.next_row_group()?;
    for (_, column) in &columns {
        let mut writer = row_group.next_column()?.ok_or_else(|| ParquetError::General("missing column".into()))?;
        match column {
            Column::Text(values) => writer.typed::<ByteArrayType>().write_batch(values, None, None)?,
            Column::Integer { values, .. } => writer.typed::<Int64Type>().write_batch(values, None, None)?,
            Column::Float(values) => {
                let present: Vec<f64> = values.iter().flatten().copied().collect();
                let levels: Vec<i16> = values.iter().map(|v| i16::from(v.is_some())).collect();
                writer.typed::<DoubleType>().write_batch(&present, Some(&levels), None)?
            }
        };
        writer.close()?;
    }
    row_group.close()?;
    writer.into_inner()
}

/// The table's columns by name, in file order.
fn columns(table: &Table) -> Vec<(String, Column)> {
    let rows = &table.rows;
    let text = |get: fn(&Row) -> String| Column::Text(rows.iter().map(|r| get(r).as_str().into()).collect());
    let mut columns = vec![
        ("case".to_string(), text(|r| r.id.clone())),
        (
            "index".to_string(),
            Column::Integer { values: rows.iter().map(|r| r.index as i64).collect(), unsigned: false },
        ),
        // The seed's bits, reinterpreted: readers see the u64 through the unsigned annotation.
        ("seed".to_string(), Column::Integer { values: rows.iter().map(|r| r.seed as i64).collect(), unsigned: true }),
        ("status".to_string(), text(|r| status_label(r.status).to_string())),
    ];
    for (k, name) in table.parameters.iter().enumerate() {
        columns.push((name.clone(), Column::Float(rows.iter().map(|r| r.parameters[k]).collect())));
    }
    for (k, name) in table.metrics.iter().enumerate() {
        columns.push((name.clone(), Column::Float(rows.iter().map(|r| r.metrics[k]).collect())));
    }
    columns.push(("wall_time".to_string(), Column::Float(rows.iter().map(|r| r.wall_time).collect())));
    columns
}

/// The schema field of a column: text and integers required, floats optional (nullable).
fn field(name: &str, column: &Column) -> Result<TypePtr, ParquetError> {
    let (physical, logical, repetition) = match column {
        Column::Text(_) => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String), Repetition::REQUIRED),
        Column::Integer { unsigned, .. } => {
            let integer = LogicalType::Integer(IntType { bit_width: 64, is_signed: !unsigned });
            (PhysicalType::INT64, Some(integer), Repetition::REQUIRED)
        }
        Column::Float(_) => (PhysicalType::DOUBLE, None, Repetition::OPTIONAL),
    };
    let builder = Type::primitive_type_builder(name, physical).with_repetition(repetition).with_logical_type(logical);
    Ok(Arc::new(builder.build()?))
}

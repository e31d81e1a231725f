//! Recording variables into an in-memory table, for a caller that evaluates the results itself
//! and need not write and parse a CSV file.

use std::path::Path;

use fmu_import::value::VariableType;

use super::row::{Cell, Row};
use super::{Observer, ObserverError};
use crate::simulator::Simulator;
use crate::table::SignalTable;
use crate::variable::VariableRef;

/// Records rows into an [`SignalTable`] equal to the one [`SignalTable::read`] gives for the CSV
/// a [`CsvRecorder`](super::CsvRecorder) writes with the same variables and interval: the CSV's
/// reals read back bit-exactly, so the table holds the same bits without the text in between.
/// Integers, enumerations and booleans (`0`/`1`) become `f64` as they read back.
#[derive(Debug)]
pub struct TableRecorder {
    every: u64,
    row: Row,
    table: SignalTable,
}

impl TableRecorder {
    /// A recorder of a row at `k = 0, every, 2·every, ...`; `file` names the table in messages.
    /// `None` if a variable is a string (a table holds numbers only).
    pub fn new(file: &Path, variables: &[VariableRef], every: u64) -> Option<Self> {
        if variables.iter().any(|v| v.variable.variable_type.abi_type() == VariableType::String) {
            return None;
        }
        let table = SignalTable {
            file: file.to_path_buf(),
            names: variables.iter().map(|v| v.qualified_name.clone()).collect(),
            times: Vec::new(),
            columns: vec![Vec::new(); variables.len()],
        };
        Some(Self { every: every.max(1), row: Row::new(variables), table })
    }

    /// The rows recorded.
    pub fn into_table(self) -> SignalTable {
        self.table
    }

    /// The rows recorded so far.
    pub fn table(&self) -> &SignalTable {
        &self.table
    }

    /// Forgets the rows of the steps after `k`, for an execution restored to step `k`
    /// ([`crate::execution::Execution::restore`]) that records them again.
    pub fn rewind(&mut self, k: u64) {
        let rows = usize::try_from(k / self.every + 1).unwrap_or(usize::MAX).min(self.table.times.len());
        self.table.times.truncate(rows);
        self.table.columns.iter_mut().for_each(|column| column.truncate(rows));
    }
}

impl Observer for TableRecorder {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        if !k.is_multiple_of(self.every) {
            return Ok(());
        }
        self.row.read(slaves)?;
        self.table.times.push(time);
        for (column, cell) in self.table.columns.iter_mut().zip(self.row.cells()) {
            column.push(match cell {
                Cell::Real(value) => *value,
                Cell::Integer(value) => f64::from(*value),
                Cell::Boolean(value) => f64::from(u8::from(*value)),
                // `new` refused string variables.
                Cell::String(_) => f64::NAN,
            });
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        Ok(())
    }
}

//! The recorded variables' values at one communication point, read with one get call per
//! instance and type; shared by the recorders.

use fmu_import::value::VariableType;

use super::ObserverError;
use crate::simulator::Simulator;
use crate::variable::VariableRef;

/// Variables of one type of one instance, read with one get call, and their cells.
#[derive(Debug, Default)]
struct Reads<T> {
    vrs: Vec<u32>,
    /// Index into [`Row::cells`] of each variable.
    cells: Vec<usize>,
    values: Vec<T>,
}

impl<T: Default> Reads<T> {
    fn push(&mut self, vr: u32, cell: usize) {
        self.vrs.push(vr);
        self.cells.push(cell);
        self.values.push(T::default());
    }
}

/// Variables of one instance.
#[derive(Debug, Default)]
struct Group {
    slave: usize,
    real: Reads<f64>,
    integer: Reads<i32>,
    boolean: Reads<bool>,
    string: Reads<String>,
}

/// The last value read of one recorded variable.
#[derive(Debug, Clone)]
pub(super) enum Cell {
    Real(f64),
    Integer(i32),
    Boolean(bool),
    String(String),
}

/// The last values read of the recorded variables, in their order.
#[derive(Debug)]
pub(super) struct Row {
    groups: Vec<Group>,
    cells: Vec<Cell>,
}

impl Row {
    /// A row of `variables` (all zero, false or empty until the first [`Row::read`]).
    pub(super) fn new(variables: &[VariableRef]) -> Self {
        let mut groups: Vec<Group> = Vec::new();
        let mut cells = Vec::with_capacity(variables.len());
        for (cell, variable) in variables.iter().enumerate() {
            let index = match groups.iter().position(|g| g.slave == variable.instance) {
                Some(index) => index,
                None => {
                    groups.push(Group { slave: variable.instance, ..Group::default() });
                    groups.len() - 1
                }
            };
            let group = &mut groups[index];
            let vr = variable.variable.value_reference;
            cells.push(match variable.variable.variable_type.abi_type() {
                VariableType::Real => {
                    group.real.push(vr, cell);
                    Cell::Real(0.0)
                }
                VariableType::Boolean => {
                    group.boolean.push(vr, cell);
                    Cell::Boolean(false)
                }
                VariableType::String => {
                    group.string.push(vr, cell);
                    Cell::String(String::new())
                }
                VariableType::Integer | VariableType::Enumeration => {
                    group.integer.push(vr, cell);
                    Cell::Integer(0)
                }
            });
        }
        Self { groups, cells }
    }

    /// The values, in the order of the variables.
    pub(super) fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// Reads every variable.
    pub(super) fn read(&mut self, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        for group in &mut self.groups {
            let slave = &slaves[group.slave];
            let Group { real, integer, boolean, string, .. } = group;
            if !real.vrs.is_empty() {
                slave.get_real(&real.vrs, &mut real.values)?;
                for (&cell, &value) in real.cells.iter().zip(&real.values) {
                    self.cells[cell] = Cell::Real(value);
                }
            }
            if !integer.vrs.is_empty() {
                slave.get_integer(&integer.vrs, &mut integer.values)?;
                for (&cell, &value) in integer.cells.iter().zip(&integer.values) {
                    self.cells[cell] = Cell::Integer(value);
                }
            }
            if !boolean.vrs.is_empty() {
                slave.get_boolean(&boolean.vrs, &mut boolean.values)?;
                for (&cell, &value) in boolean.cells.iter().zip(&boolean.values) {
                    self.cells[cell] = Cell::Boolean(value);
                }
            }
            if !string.vrs.is_empty() {
                for (&cell, value) in string.cells.iter().zip(slave.get_string(&string.vrs)?) {
                    self.cells[cell] = Cell::String(value);
                }
            }
        }
        Ok(())
    }
}

//! The declarative variable table: the single source of truth for a model's interface.
//!
//! An export layer generates its getters and setters, its model description and its checks from
//! one `&'static [Variable<M>]` per model; the table says what each variable is (causality,
//! variability, type, unit, start, range, description), never how an FMI version spells it.
//! Value references are written out explicitly, never derived from field order, so they stay
//! stable when the table is reordered or extended. Rows are built with [`crate::builder`].

use std::collections::HashSet;

/// How a variable relates to the host: what it may set and what it reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// Set by the host before the run (or between steps, if tunable).
    Parameter,
    /// Computed by the model from parameters.
    CalculatedParameter,
    /// Set by the host during the run.
    Input,
    /// Computed by the model and read by the host.
    Output,
    /// Internal, visible for inspection only.
    Local,
}

/// When a variable's value may change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    /// Never.
    Constant,
    /// Only before the run starts.
    Fixed,
    /// Between steps, at the host's request.
    Tunable,
    /// At discrete instants only.
    Discrete,
    /// At any time.
    Continuous,
}

/// Typed accessors of one variable. Getters read the model; setters are present for variables a
/// host may set (parameters and inputs).
pub enum Value<M: 'static> {
    Real {
        /// Unit symbol (a key of the export layer's unit table; `"1"` is dimensionless).
        unit: &'static str,
        start: f64,
        min: Option<f64>,
        max: Option<f64>,
        get: fn(&M) -> f64,
        set: Option<fn(&mut M, f64)>,
        /// Receives the first time derivative of an input (interpolated input), or `None` when
        /// the input's value is set again (the derivative is cleared: held until then).
        derivative: Option<fn(&mut M, Option<f64>)>,
    },
    Integer {
        start: i32,
        min: Option<i32>,
        max: Option<i32>,
        get: fn(&M) -> i32,
        set: Option<fn(&mut M, i32)>,
    },
    Boolean {
        start: bool,
        get: fn(&M) -> bool,
        set: Option<fn(&mut M, bool)>,
    },
    String {
        start: &'static str,
        get: fn(&M) -> &str,
        set: Option<fn(&mut M, &str)>,
    },
}

// By hand: a derive would require `M: Copy`, but only fn pointers to `M` are held.
impl<M> Clone for Value<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Value<M> {}

/// The types of [`Value`]; each has its own value-reference space (Real 0 and Integer 0 are
/// different variables).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueType {
    Real,
    Integer,
    Boolean,
    String,
}

impl ValueType {
    pub const ALL: [ValueType; 4] = [ValueType::Real, ValueType::Integer, ValueType::Boolean, ValueType::String];

    /// Type name for messages and model descriptions.
    pub fn name(self) -> &'static str {
        match self {
            ValueType::Real => "Real",
            ValueType::Integer => "Integer",
            ValueType::Boolean => "Boolean",
            ValueType::String => "String",
        }
    }
}

/// One row of the variable table.
pub struct Variable<M: 'static> {
    pub vr: u32,
    pub name: &'static str,
    pub description: &'static str,
    pub causality: Causality,
    pub variability: Variability,
    pub value: Value<M>,
}

impl<M> Clone for Variable<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Variable<M> {}

impl<M> Variable<M> {
    /// Whether the variable has a start value (and gets it when the instance is created): the
    /// ones the host may set.
    pub fn has_start(&self) -> bool {
        matches!(self.causality, Causality::Parameter | Causality::Input)
    }

    pub fn value_type(&self) -> ValueType {
        match self.value {
            Value::Real { .. } => ValueType::Real,
            Value::Integer { .. } => ValueType::Integer,
            Value::Boolean { .. } => ValueType::Boolean,
            Value::String { .. } => ValueType::String,
        }
    }

    /// Type name for messages and model descriptions.
    pub fn type_name(&self) -> &'static str {
        self.value_type().name()
    }

    /// Whether the table row has a setter.
    fn settable(&self) -> bool {
        match self.value {
            Value::Real { set, .. } => set.is_some(),
            Value::Integer { set, .. } => set.is_some(),
            Value::Boolean { set, .. } => set.is_some(),
            Value::String { set, .. } => set.is_some(),
        }
    }
}

/// Checks a table for what a row-by-row construction cannot see (duplicate value references or
/// names) and for rows written without the builder that break its rules; used by the tests of
/// every model.
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    let mut seen = HashSet::new();
    let mut names = HashSet::new();
    for v in table {
        if !seen.insert((v.type_name(), v.vr)) {
            return Err(format!("duplicate {} value reference {} ({})", v.type_name(), v.vr, v.name));
        }
        if !names.insert(v.name) {
            return Err(format!("duplicate variable name {}", v.name));
        }
        check_row(v).map_err(|what| format!("variable {}: {what}", v.name))?;
    }
    Ok(())
}

/// The rules the builder enforces, for rows written as struct literals.
fn check_row<M>(v: &Variable<M>) -> Result<(), &'static str> {
    if v.has_start() != v.settable() {
        return Err(if v.has_start() { "the host may set it, but it has no setter" } else { "a setter it never gets" });
    }
    if let Value::Real { unit, start, min, max, derivative, .. } = v.value {
        if unit.is_empty() {
            return Err("a Real without a unit (\"1\" is dimensionless)");
        }
        let lowest = min.unwrap_or(f64::NEG_INFINITY);
        let highest = max.unwrap_or(f64::INFINITY);
        if !(lowest <= highest) || (v.has_start() && !(lowest <= start && start <= highest)) {
            return Err("an empty range or a start outside it");
        }
        if derivative.is_some() && !(v.causality == Causality::Input && v.variability == Variability::Continuous) {
            return Err("a derivative setter on a variable that is not a continuous input");
        }
    }
    if let Value::Integer { start, min, max, .. } = v.value {
        let (lowest, highest) = (min.unwrap_or(i32::MIN), max.unwrap_or(i32::MAX));
        if lowest > highest || (v.has_start() && !(lowest..=highest).contains(&start)) {
            return Err("an empty range or a start outside it");
        }
    }
    Ok(())
}

/// The number of rows in `groups`, the length of the table [`table`] joins them into.
pub const fn table_len<M>(groups: &[&[Variable<M>]]) -> usize {
    let (mut n, mut i) = (0, 0);
    while i < groups.len() {
        n += groups[i].len();
        i += 1;
    }
    n
}

/// Joins groups of rows (sections of a table, [`crate::xyz!`] triples) into one table, in order,
/// at compile time: `static VARIABLES: [V; table_len(GROUPS)] = table(GROUPS);`.
pub const fn table<M, const N: usize>(groups: &[&[Variable<M>]]) -> [Variable<M>; N] {
    assert!(table_len(groups) == N, "the table's length is table_len of its groups");
    assert!(N > 0, "a table has at least one variable");
    let mut rows = [first(groups); N];
    let (mut n, mut i) = (0, 0);
    while i < groups.len() {
        let mut j = 0;
        while j < groups[i].len() {
            rows[n] = groups[i][j];
            (n, j) = (n + 1, j + 1);
        }
        i += 1;
    }
    rows
}

/// The first row of the first non-empty group (a table has one).
const fn first<M>(groups: &[&[Variable<M>]]) -> Variable<M> {
    let mut i = 0;
    while groups[i].is_empty() {
        i += 1;
    }
    groups[i][0]
}

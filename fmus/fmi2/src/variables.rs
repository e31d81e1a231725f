//! The declarative variable table: the single source of truth for an FMU's interface.
//!
//! `fmi2Get*`/`fmi2Set*`, `modelDescription.xml` and the GUID are all generated from one
//! `&'static [Variable<M>]` per model. Value references are written out explicitly, never derived
//! from field order, so they stay stable when the table is reordered or extended.

/// FMI 2.0 `causality`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    Local,
}

/// FMI 2.0 `variability`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    Constant,
    Fixed,
    Tunable,
    Discrete,
    Continuous,
}

/// FMI 2.0 `initial`, derived from causality and variability (never written by hand, so the
/// combinations the standard forbids cannot occur).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Initial {
    Exact,
    Calculated,
}

/// Typed accessors of one variable. Getters read the model; setters are present for variables a
/// master may set (parameters and inputs).
pub enum Value<M: 'static> {
    Real {
        unit: &'static str,
        start: f64,
        min: Option<f64>,
        max: Option<f64>,
        get: fn(&M) -> f64,
        set: Option<fn(&mut M, f64)>,
        /// Receives the first time derivative of an input (`fmi2SetRealInputDerivatives`), or
        /// `None` when the input's value is set again (the derivative is cleared: held input).
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

/// The FMI types of [`Value`]; each has its own value-reference space (Real 0 and Integer 0 are
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

    /// FMI type name for messages and XML.
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

impl<M> Variable<M> {
    /// A fixed Real parameter (`initial="exact"`), settable before initialization only.
    pub const fn parameter(
        vr: u32,
        name: &'static str,
        unit: &'static str,
        start: f64,
        description: &'static str,
        get: fn(&M) -> f64,
        set: fn(&mut M, f64),
    ) -> Self {
        Self::real(vr, name, Causality::Parameter, Variability::Fixed, unit, start, description, get, Some(set), None)
    }

    /// A tunable Real parameter, settable between steps too.
    pub const fn tunable(
        vr: u32,
        name: &'static str,
        unit: &'static str,
        start: f64,
        description: &'static str,
        get: fn(&M) -> f64,
        set: fn(&mut M, f64),
    ) -> Self {
        Self::real(vr, name, Causality::Parameter, Variability::Tunable, unit, start, description, get, Some(set), None)
    }

    /// A continuous Real input that accepts a first-order derivative for interpolation.
    #[allow(clippy::too_many_arguments)]
    pub const fn input(
        vr: u32,
        name: &'static str,
        unit: &'static str,
        start: f64,
        description: &'static str,
        get: fn(&M) -> f64,
        set: fn(&mut M, f64),
        derivative: fn(&mut M, Option<f64>),
    ) -> Self {
        Self::real(
            vr,
            name,
            Causality::Input,
            Variability::Continuous,
            unit,
            start,
            description,
            get,
            Some(set),
            Some(derivative),
        )
    }

    /// A continuous Real input that is held (sampled) over each step: it has no derivative
    /// setter, so `fmi2SetRealInputDerivatives` refuses it.
    pub const fn held_input(
        vr: u32,
        name: &'static str,
        unit: &'static str,
        start: f64,
        description: &'static str,
        get: fn(&M) -> f64,
        set: fn(&mut M, f64),
    ) -> Self {
        Self::real(vr, name, Causality::Input, Variability::Continuous, unit, start, description, get, Some(set), None)
    }

    /// A continuous Real output (`initial="calculated"`, no start).
    pub const fn output(
        vr: u32,
        name: &'static str,
        unit: &'static str,
        description: &'static str,
        get: fn(&M) -> f64,
    ) -> Self {
        Self::real(vr, name, Causality::Output, Variability::Continuous, unit, 0.0, description, get, None, None)
    }

    /// A fixed Integer parameter with an allowed range.
    #[allow(clippy::too_many_arguments)]
    pub const fn integer_parameter(
        vr: u32,
        name: &'static str,
        start: i32,
        min: i32,
        max: i32,
        description: &'static str,
        get: fn(&M) -> i32,
        set: fn(&mut M, i32),
    ) -> Self {
        Variable {
            vr,
            name,
            description,
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            value: Value::Integer { start, min: Some(min), max: Some(max), get, set: Some(set) },
        }
    }

    /// A fixed Boolean parameter.
    pub const fn boolean_parameter(
        vr: u32,
        name: &'static str,
        start: bool,
        description: &'static str,
        get: fn(&M) -> bool,
        set: fn(&mut M, bool),
    ) -> Self {
        Variable {
            vr,
            name,
            description,
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            value: Value::Boolean { start, get, set: Some(set) },
        }
    }

    /// A discrete Boolean output.
    pub const fn boolean_output(vr: u32, name: &'static str, description: &'static str, get: fn(&M) -> bool) -> Self {
        Variable {
            vr,
            name,
            description,
            causality: Causality::Output,
            variability: Variability::Discrete,
            value: Value::Boolean { start: false, get, set: None },
        }
    }

    /// A fixed String parameter (file names and the like).
    pub const fn string_parameter(
        vr: u32,
        name: &'static str,
        start: &'static str,
        description: &'static str,
        get: fn(&M) -> &str,
        set: fn(&mut M, &str),
    ) -> Self {
        Variable {
            vr,
            name,
            description,
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            value: Value::String { start, get, set: Some(set) },
        }
    }

    /// Restricts a Real variable to `[min, max]`; the bound is declared in the XML and enforced by
    /// `fmi2SetReal`.
    pub const fn range(mut self, lo: f64, hi: f64) -> Self {
        if let Value::Real { min, max, .. } = &mut self.value {
            *min = Some(lo);
            *max = Some(hi);
        }
        self
    }

    #[allow(clippy::too_many_arguments)]
    const fn real(
        vr: u32,
        name: &'static str,
        causality: Causality,
        variability: Variability,
        unit: &'static str,
        start: f64,
        description: &'static str,
        get: fn(&M) -> f64,
        set: Option<fn(&mut M, f64)>,
        derivative: Option<fn(&mut M, Option<f64>)>,
    ) -> Self {
        Variable {
            vr,
            name,
            description,
            causality,
            variability,
            value: Value::Real { unit, start, min: None, max: None, get, set, derivative },
        }
    }

    /// The `initial` attribute this variable gets (None: the attribute is omitted, as for inputs).
    pub fn initial(&self) -> Option<Initial> {
        match self.causality {
            Causality::Parameter => Some(Initial::Exact),
            Causality::Input => None,
            Causality::Output | Causality::CalculatedParameter | Causality::Local => Some(Initial::Calculated),
        }
    }

    /// Whether the variable carries a `start` value in the XML (and gets it at instantiation).
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

    /// FMI type name for messages and XML.
    pub fn type_name(&self) -> &'static str {
        self.value_type().name()
    }
}

/// Checks a table for duplicate value references or names; used by tests of every FMU.
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    let mut seen = std::collections::HashSet::new();
    let mut names = std::collections::HashSet::new();
    for v in table {
        if !seen.insert((v.type_name(), v.vr)) {
            return Err(format!("duplicate {} value reference {} ({})", v.type_name(), v.vr, v.name));
        }
        if !names.insert(v.name) {
            return Err(format!("duplicate variable name {}", v.name));
        }
    }
    Ok(())
}

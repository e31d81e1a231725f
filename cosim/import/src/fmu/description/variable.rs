//! The rows of a model description: one [`ScalarVariable`] per FMI 2.0 `ScalarVariable` or
//! FMI 3.0 variable (element), with its causality, variability and initial keywords.

use std::fmt;
use std::str::FromStr;

use crate::value::{Value, VariableType};

/// `causality` of a variable (FMI 2.0 default: `local`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    #[default]
    Local,
    Independent,
}

/// `variability` of a variable (FMI 2.0 default: `continuous`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Variability {
    Constant,
    Fixed,
    Tunable,
    Discrete,
    #[default]
    Continuous,
}

/// `initial` of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Initial {
    Exact,
    Approx,
    Calculated,
}

macro_rules! keyword_enum {
    ($type:ident { $($variant:ident = $text:literal),* $(,)? }) => {
        impl $type {
            /// All keywords, as written in the XML.
            pub const KEYWORDS: &'static [&'static str] = &[$($text),*];
            /// The keyword as written in the XML.
            pub fn as_str(self) -> &'static str {
                match self { $($type::$variant => $text),* }
            }
        }
        impl FromStr for $type {
            type Err = ();
            fn from_str(text: &str) -> Result<Self, ()> {
                match text { $($text => Ok($type::$variant),)* _ => Err(()) }
            }
        }
        impl fmt::Display for $type {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.as_str())
            }
        }
    };
}

keyword_enum!(Causality {
    Parameter = "parameter",
    CalculatedParameter = "calculatedParameter",
    Input = "input",
    Output = "output",
    Local = "local",
    Independent = "independent",
});
keyword_enum!(Variability {
    Constant = "constant",
    Fixed = "fixed",
    Tunable = "tunable",
    Discrete = "discrete",
    Continuous = "continuous",
});
keyword_enum!(Initial { Exact = "exact", Approx = "approx", Calculated = "calculated" });

/// One `ScalarVariable`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarVariable {
    pub name: String,
    pub value_reference: u32,
    pub description: Option<String>,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub variable_type: VariableType,
    /// `start` attribute of the type element, parsed to the variable's type
    /// (enumerations as [`Value::Integer`]).
    pub start: Option<Value>,
    /// Unit of a Real: the `unit` attribute, else the unit of its `declaredType`.
    pub unit: Option<String>,
    pub declared_type: Option<String>,
    /// The `min` and `max` attributes of the type element as written (shown, not enforced: the
    /// FMU checks what it is given).
    pub range: (Option<String>, Option<String>),
}

impl ScalarVariable {
    /// The `initial` attribute or, when it is absent, the FMI 2.0 default for the
    /// variable's causality and variability: exact for parameters and constants,
    /// calculated for calculated parameters and for other outputs and locals, none
    /// for inputs and the independent variable.
    pub fn initial_or_default(&self) -> Option<Initial> {
        self.initial.or(match (self.causality, self.variability) {
            (Causality::Input | Causality::Independent, _) => None,
            (Causality::Parameter, _) | (_, Variability::Constant) => Some(Initial::Exact),
            (Causality::CalculatedParameter | Causality::Output | Causality::Local, _) => Some(Initial::Calculated),
        })
    }

    /// True for variables the importer may set before initialization from a
    /// system file: FMI 2.0 allows it on inputs and on any variable that is not
    /// constant and whose `initial` is exact or approx (parameters, and outputs or
    /// locals whose start value the FMU takes as given or as a guess).
    pub fn is_settable_start(&self) -> bool {
        self.variability != Variability::Constant
            && (self.causality == Causality::Input
                || matches!(self.initial_or_default(), Some(Initial::Exact | Initial::Approx)))
    }
}

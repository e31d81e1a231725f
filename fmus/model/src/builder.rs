//! Rows of the variable table, built step by step in `const` so that tables stay `static`:
//!
//! ```text
//! Real::output(260, "est.ship.x").unit("m").doc("Ship surge, W x").get(|m| m.ship.x)
//! Real::parameter(8, "sp.lp").unit("m").start(0.5).range(0.01, 10.0).doc("…").get(..).set(..)
//! Integer::tunable(0, "mode").start(2).range(0, 2).doc("…").get(..).set(..)
//! ```
//!
//! Each step returns a type that has only the next step's method, so a row that skips one does
//! not compile: a parameter or input without a setter or without a start, an output with a start
//! or a setter, a Real without a unit, an interpolated input without its derivative setter, an
//! Integer parameter without its range. Every part is named at its call, so no two `&str`s (unit
//! and description) can be swapped unnoticed. What a type cannot say is checked while the table
//! is evaluated, which fails the build: an empty unit, name or description; an empty range or a
//! start outside it.
//!
//! The kinds (constructors) and what they mean for the host:
//! - `parameter`: fixed, set before the run only; `tunable`: also between steps.
//! - `Real::held_input`: held over each step (no derivative setter, so the host cannot make the
//!   model interpolate it); `Real::input`: interpolated with the first derivative the host gives.
//! - `Real::output`: continuous; `Boolean::output`: discrete. Outputs have no start.
//!
//! Wrong rows do not compile. The control, a complete parameter:
//!
//! ```
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::parameter(0, "x").unit("m").start(0.0).doc("x").get(|m| m.x).set(|m, v| m.x = v);
//! ```
//!
//! A parameter without a setter:
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::parameter(0, "x").unit("m").start(0.0).doc("x").get(|m| m.x);
//! ```
//!
//! A Real without a unit:
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::parameter(0, "x").start(0.0).doc("x").get(|m| m.x).set(|m, v| m.x = v);
//! ```
//!
//! An empty unit (refused while the static is evaluated):
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::parameter(0, "x").unit("").start(0.0).doc("x").get(|m| m.x).set(|m, v| m.x = v);
//! ```
//!
//! A start outside the range:
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V =
//!     Real::parameter(0, "x").unit("m").start(2.0).range(0.0, 1.0).doc("x").get(|m| m.x).set(|m, v| m.x = v);
//! ```
//!
//! An output with a start:
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::output(0, "x").unit("m").start(0.0).doc("x").get(|m| m.x);
//! ```
//!
//! An interpolated input without its derivative setter:
//!
//! ```compile_fail
//! # struct M { x: f64 }
//! # type Real = fmu_model::Real<M>;
//! # type V = fmu_model::Variable<M>;
//! static X: V = Real::input(0, "x").unit("m").start(0.0).doc("x").get(|m| m.x).set(|m, v| m.x = v);
//! ```

use crate::variables::{Causality, Value, Variability, Variable};
use std::marker::PhantomData;

/// Constructors of Real (f64) rows; `M` is the model. A model crate names it once,
/// `type Real = fmu_model::Real<MyModel>;`, so that its table reads `Real::output(..)`.
pub struct Real<M>(PhantomData<M>);
/// Constructors of Integer (i32) rows.
pub struct Integer<M>(PhantomData<M>);
/// Constructors of Boolean rows.
pub struct Boolean<M>(PhantomData<M>);
/// Constructors of String rows (named `Text` so that it does not hide `std::string::String`).
pub struct Text<M>(PhantomData<M>);

/// What a row is, as far as the steps after its constructor depend on it.
pub mod kind {
    pub struct RealOutput;
    /// A Real parameter or a held Real input: set, never interpolated.
    pub struct RealSet;
    /// A Real input the model interpolates.
    pub struct RealInterpolated;
    pub struct Integer;
    pub struct Boolean;
    pub struct BooleanOutput;
    pub struct Text;
}

/// The step a row under construction needs next.
pub mod next {
    pub struct Unit;
    pub struct Start;
    pub struct Range;
    pub struct Doc;
    pub struct Get;
}

/// A Real kind that has a start value and a setter.
pub trait RealSettable {}
impl RealSettable for kind::RealSet {}
impl RealSettable for kind::RealInterpolated {}

/// The attributes of a row before its getter is known.
#[derive(Clone, Copy)]
enum Attributes {
    Real { unit: &'static str, start: f64, min: Option<f64>, max: Option<f64> },
    Integer { start: i32, min: i32, max: i32 },
    Boolean { start: bool },
    Text { start: &'static str },
}

/// The types a [`Draft`] carries only for its methods (a fn pointer: `M` is never held).
type Marker<M, K, S> = PhantomData<(fn(&M), K, S)>;

/// A row under construction: a `K` row that needs step `S` next.
pub struct Draft<M: 'static, K, S> {
    vr: u32,
    name: &'static str,
    description: &'static str,
    causality: Causality,
    variability: Variability,
    attributes: Attributes,
    _row: Marker<M, K, S>,
}

/// A row with its getter that needs its setter next.
pub struct NeedsSet<M: 'static, K> {
    row: Variable<M>,
    _kind: PhantomData<K>,
}

/// An interpolated input that needs its derivative setter next.
pub struct NeedsDerivative<M: 'static> {
    row: Variable<M>,
}

const fn draft<M, K, S>(
    vr: u32,
    name: &'static str,
    causality: Causality,
    variability: Variability,
    attributes: Attributes,
) -> Draft<M, K, S> {
    assert!(!name.is_empty(), "a variable has a name");
    Draft { vr, name, description: "", causality, variability, attributes, _row: PhantomData }
}

const NO_UNIT: Attributes = Attributes::Real { unit: "", start: 0.0, min: None, max: None };

impl<M> Real<M> {
    /// A continuous output (calculated, no start).
    pub const fn output(vr: u32, name: &'static str) -> Draft<M, kind::RealOutput, next::Unit> {
        draft(vr, name, Causality::Output, Variability::Continuous, NO_UNIT)
    }

    /// A calculated parameter: fixed once the instance is initialized, computed by the model
    /// from its parameters (the values in force, for the host to read).
    pub const fn calculated(vr: u32, name: &'static str) -> Draft<M, kind::RealOutput, next::Unit> {
        draft(vr, name, Causality::CalculatedParameter, Variability::Fixed, NO_UNIT)
    }

    /// A fixed parameter: set before the run only.
    pub const fn parameter(vr: u32, name: &'static str) -> Draft<M, kind::RealSet, next::Unit> {
        draft(vr, name, Causality::Parameter, Variability::Fixed, NO_UNIT)
    }

    /// A tunable parameter: set between steps too.
    pub const fn tunable(vr: u32, name: &'static str) -> Draft<M, kind::RealSet, next::Unit> {
        draft(vr, name, Causality::Parameter, Variability::Tunable, NO_UNIT)
    }

    /// A continuous input held (sampled) over each step: it has no derivative setter, so a host
    /// that offers derivatives is refused.
    pub const fn held_input(vr: u32, name: &'static str) -> Draft<M, kind::RealSet, next::Unit> {
        draft(vr, name, Causality::Input, Variability::Continuous, NO_UNIT)
    }

    /// A continuous input interpolated over each step with the first derivative the host gives.
    pub const fn input(vr: u32, name: &'static str) -> Draft<M, kind::RealInterpolated, next::Unit> {
        draft(vr, name, Causality::Input, Variability::Continuous, NO_UNIT)
    }
}

impl<M> Integer<M> {
    /// A fixed parameter.
    pub const fn parameter(vr: u32, name: &'static str) -> Draft<M, kind::Integer, next::Start> {
        draft(vr, name, Causality::Parameter, Variability::Fixed, Attributes::Integer { start: 0, min: 0, max: 0 })
    }

    /// A tunable parameter (e.g. an operating mode switched between steps).
    pub const fn tunable(vr: u32, name: &'static str) -> Draft<M, kind::Integer, next::Start> {
        draft(vr, name, Causality::Parameter, Variability::Tunable, Attributes::Integer { start: 0, min: 0, max: 0 })
    }
}

impl<M> Boolean<M> {
    /// A fixed parameter.
    pub const fn parameter(vr: u32, name: &'static str) -> Draft<M, kind::Boolean, next::Start> {
        draft(vr, name, Causality::Parameter, Variability::Fixed, Attributes::Boolean { start: false })
    }

    /// A discrete output (calculated, no start).
    pub const fn output(vr: u32, name: &'static str) -> Draft<M, kind::BooleanOutput, next::Doc> {
        draft(vr, name, Causality::Output, Variability::Discrete, Attributes::Boolean { start: false })
    }
}

impl<M> Text<M> {
    /// A fixed parameter (file names and the like).
    pub const fn parameter(vr: u32, name: &'static str) -> Draft<M, kind::Text, next::Start> {
        draft(vr, name, Causality::Parameter, Variability::Fixed, Attributes::Text { start: "" })
    }
}

impl<M, K, S> Draft<M, K, S> {
    /// The same row, needing step `T` next.
    const fn then<T>(self) -> Draft<M, K, T> {
        let Draft { vr, name, description, causality, variability, attributes, .. } = self;
        Draft { vr, name, description, causality, variability, attributes, _row: PhantomData }
    }

    const fn with_getter(self, value: Value<M>) -> Variable<M> {
        Variable {
            vr: self.vr,
            name: self.name,
            description: self.description,
            causality: self.causality,
            variability: self.variability,
            value,
        }
    }

    const fn real(&self) -> (&'static str, f64, Option<f64>, Option<f64>) {
        match self.attributes {
            Attributes::Real { unit, start, min, max } => (unit, start, min, max),
            _ => panic!("only Real kinds reach a Real step"),
        }
    }

    const fn real_value(&self, get: fn(&M) -> f64) -> Value<M> {
        let (unit, start, min, max) = self.real();
        Value::Real { unit, start, min, max, get, set: None, derivative: None }
    }

    const fn set_unit(mut self, unit: &'static str) -> Self {
        assert!(!unit.is_empty(), "every Real has a unit (\"1\" is dimensionless)");
        let (_, start, min, max) = self.real();
        self.attributes = Attributes::Real { unit, start, min, max };
        self
    }

    const fn set_real_start(mut self, start: f64) -> Self {
        let (unit, _, min, max) = self.real();
        self.attributes = Attributes::Real { unit, start, min, max };
        self
    }
}

impl<M> Draft<M, kind::RealOutput, next::Unit> {
    /// The unit symbol (`"1"` for dimensionless quantities).
    pub const fn unit(self, unit: &'static str) -> Draft<M, kind::RealOutput, next::Doc> {
        self.set_unit(unit).then()
    }
}

impl<M, K: RealSettable> Draft<M, K, next::Unit> {
    /// The unit symbol (`"1"` for dimensionless quantities).
    pub const fn unit(self, unit: &'static str) -> Draft<M, K, next::Start> {
        self.set_unit(unit).then()
    }
}

impl<M, K: RealSettable> Draft<M, K, next::Start> {
    /// The value the instance starts with (and the model description declares).
    pub const fn start(self, start: f64) -> Draft<M, K, next::Doc> {
        self.set_real_start(start).then()
    }
}

impl<M, K: RealSettable> Draft<M, K, next::Doc> {
    /// Restricts the variable to `[lo, hi]` (which must hold its start); the host's setter
    /// refuses values outside.
    pub const fn range(mut self, lo: f64, hi: f64) -> Self {
        let (unit, start, _, _) = self.real();
        assert!(lo <= hi && lo <= start && start <= hi, "a range is not empty and holds its start");
        self.attributes = Attributes::Real { unit, start, min: Some(lo), max: Some(hi) };
        self
    }
}

impl<M> Draft<M, kind::Integer, next::Start> {
    /// The value the instance starts with.
    pub const fn start(mut self, start: i32) -> Draft<M, kind::Integer, next::Range> {
        self.attributes = Attributes::Integer { start, min: 0, max: 0 };
        self.then()
    }
}

impl<M> Draft<M, kind::Integer, next::Range> {
    /// The allowed values `[lo, hi]` (for an enumeration, exactly its codes), holding the start.
    pub const fn range(mut self, lo: i32, hi: i32) -> Draft<M, kind::Integer, next::Doc> {
        let Attributes::Integer { start, .. } = self.attributes else { panic!("an Integer row") };
        assert!(lo <= start && start <= hi, "a range is not empty and holds its start");
        self.attributes = Attributes::Integer { start, min: lo, max: hi };
        self.then()
    }
}

impl<M> Draft<M, kind::Boolean, next::Start> {
    /// The value the instance starts with.
    pub const fn start(mut self, start: bool) -> Draft<M, kind::Boolean, next::Doc> {
        self.attributes = Attributes::Boolean { start };
        self.then()
    }
}

impl<M> Draft<M, kind::Text, next::Start> {
    /// The value the instance starts with.
    pub const fn start(mut self, start: &'static str) -> Draft<M, kind::Text, next::Doc> {
        self.attributes = Attributes::Text { start };
        self.then()
    }
}

impl<M, K> Draft<M, K, next::Doc> {
    /// The description: what the variable is, with its frame and source.
    pub const fn doc(mut self, description: &'static str) -> Draft<M, K, next::Get> {
        assert!(!description.is_empty(), "every variable is described");
        self.description = description;
        self.then()
    }
}

impl<M> Draft<M, kind::RealOutput, next::Get> {
    /// Reads the output from the model; completes the row.
    pub const fn get(self, get: fn(&M) -> f64) -> Variable<M> {
        let value = self.real_value(get);
        self.with_getter(value)
    }
}

impl<M, K: RealSettable> Draft<M, K, next::Get> {
    /// Reads the variable from the model.
    pub const fn get(self, get: fn(&M) -> f64) -> NeedsSet<M, K> {
        let value = self.real_value(get);
        NeedsSet { row: self.with_getter(value), _kind: PhantomData }
    }
}

impl<M> Draft<M, kind::Integer, next::Get> {
    /// Reads the variable from the model.
    pub const fn get(self, get: fn(&M) -> i32) -> NeedsSet<M, kind::Integer> {
        let Attributes::Integer { start, min, max } = self.attributes else { panic!("an Integer row") };
        let value = Value::Integer { start, min: Some(min), max: Some(max), get, set: None };
        NeedsSet { row: self.with_getter(value), _kind: PhantomData }
    }
}

impl<M> Draft<M, kind::Boolean, next::Get> {
    /// Reads the variable from the model.
    pub const fn get(self, get: fn(&M) -> bool) -> NeedsSet<M, kind::Boolean> {
        let Attributes::Boolean { start } = self.attributes else { panic!("a Boolean row") };
        NeedsSet { row: self.with_getter(Value::Boolean { start, get, set: None }), _kind: PhantomData }
    }
}

impl<M> Draft<M, kind::BooleanOutput, next::Get> {
    /// Reads the output from the model; completes the row.
    pub const fn get(self, get: fn(&M) -> bool) -> Variable<M> {
        self.with_getter(Value::Boolean { start: false, get, set: None })
    }
}

impl<M> Draft<M, kind::Text, next::Get> {
    /// Reads the variable from the model.
    pub const fn get(self, get: fn(&M) -> &str) -> NeedsSet<M, kind::Text> {
        let Attributes::Text { start } = self.attributes else { panic!("a String row") };
        NeedsSet { row: self.with_getter(Value::String { start, get, set: None }), _kind: PhantomData }
    }
}

impl<M> NeedsSet<M, kind::RealInterpolated> {
    /// Writes a value the host set into the model.
    pub const fn set(mut self, set: fn(&mut M, f64)) -> NeedsDerivative<M> {
        if let Value::Real { set: slot, .. } = &mut self.row.value {
            *slot = Some(set);
        }
        NeedsDerivative { row: self.row }
    }
}

impl<M> NeedsDerivative<M> {
    /// Receives the input's first derivative for the coming step, or `None` when the host set a
    /// value without one (the input is then held); completes the row.
    pub const fn derivative(mut self, derivative: fn(&mut M, Option<f64>)) -> Variable<M> {
        if let Value::Real { derivative: slot, .. } = &mut self.row.value {
            *slot = Some(derivative);
        }
        self.row
    }
}

/// The setter step of the kinds whose setter completes the row: it stores the setter in the
/// value's variant and returns the row. One definition for the four kinds, which differ only in
/// the variant and the value type.
macro_rules! completing_setter {
    ($($kind:ident: $variant:ident($ty:ty), $doc:literal;)+) => {$(
        impl<M> NeedsSet<M, kind::$kind> {
            #[doc = $doc]
            pub const fn set(mut self, set: fn(&mut M, $ty)) -> Variable<M> {
                if let Value::$variant { set: slot, .. } = &mut self.row.value {
                    *slot = Some(set);
                }
                self.row
            }
        }
    )+};
}

completing_setter! {
    RealSet: Real(f64), "Writes a value the host set into the model; completes the row.";
    Integer: Integer(i32), "Writes a value the host set (within the range) into the model; completes the row.";
    Boolean: Boolean(bool), "Writes a value the host set into the model; completes the row.";
    Text: String(&str), "Writes a value the host set into the model; completes the row.";
}

/// One row that reads and writes a single place of the model and starts at the same place of the
/// constant the model is created with, so that the place is written once: `field: (m.root,
/// START).path` gives the builder's `.start(START.path)`, `.get(|m| m.root.path)` and
/// `.set(|m, v| m.root.path = v)`. The kind, unit (Reals), range (optional, also an Integer's) and
/// description are the builder's steps, in its order. A place whose start is not the same place
/// of a constant names its start and the place: `start: HOOK_MASS, field: m => m.hook_mass`. Rows
/// whose getter and setter differ (a conversion, a method) are written with the builder.
///
/// ```
/// # #[derive(Clone, Copy)]
/// # struct Config { gain: f64, steps: i32 }
/// # struct M { config: Config }
/// # type Real = fmu_model::Real<M>;
/// # type Integer = fmu_model::Integer<M>;
/// # type V = fmu_model::Variable<M>;
/// const CONFIG: Config = Config { gain: 0.5, steps: 2 };
/// static GAIN: V = fmu_model::field!(Real::tunable(0, "gain"), unit: "1", range: (0.0, 1.0),
///     doc: "Loop gain", field: (m.config, CONFIG).gain);
/// static STEPS: V = fmu_model::field!(Integer::parameter(0, "steps"), range: (1, 9),
///     doc: "Steps per sample", field: (m.config, CONFIG).steps);
/// static START: V = fmu_model::field!(Integer::parameter(1, "first"), start: 3, range: (1, 9),
///     doc: "First step", field: m => m.config.steps);
/// ```
#[macro_export]
macro_rules! field {
    (
        $($kind:ident)::+ ($vr:expr, $name:expr),
        $(unit: $unit:expr,)?
        $(range: ($lo:expr, $hi:expr),)?
        doc: $doc:expr,
        field: ($m:ident $(. $root:ident)*, $start:expr) $($path:tt)+
    ) => {
        $crate::field!($($kind)::+($vr, $name), $(unit: $unit,)? start: $start $($path)+, $(range: ($lo, $hi),)?
            doc: $doc, field: $m => $m $(.$root)* $($path)+)
    };
    (
        $($kind:ident)::+ ($vr:expr, $name:expr),
        $(unit: $unit:expr,)?
        start: $start:expr,
        $(range: ($lo:expr, $hi:expr),)?
        doc: $doc:expr,
        field: $m:ident => $place:expr
    ) => {
        $($kind)::+($vr, $name)
            $(.unit($unit))?
            .start($start)
            $(.range($lo, $hi))?
            .doc($doc)
            .get(|$m| $place)
            .set(|$m, v| $place = v)
    };
}

//! The toy models the tests drive: `Toy`, exported through `export_fmu!` exactly as an FMU crate
//! does (so the tests call the real `#[no_mangle]` entry points), `Other`, a second model
//! whose serialized state has the same bytes layout as `Toy`'s but a different GUID, and
//! `Sparse`, whose value references are too far apart for a dense lookup table.

use crate::variables::{Causality, Value, Variability, Variable};
use crate::{Environment, Model, ModelInfo};
use serde::{Deserialize, Serialize};

/// `impl Model` for a test model whose initialization and steps do nothing: its `ModelInfo`, its
/// variable table and the value `Model::new` returns.
macro_rules! inert_model {
    ($model:ident { info: $info:expr, variables: $variables:expr, new: $new:expr $(,)? }) => {
        impl $crate::Model for $model {
            const INFO: $crate::ModelInfo = $info;

            fn variables() -> &'static [$crate::Variable<Self>] {
                $variables
            }

            fn new(_env: &$crate::Environment) -> Self {
                $new
            }

            fn initialize(&mut self, _start_time: f64) -> Result<(), String> {
                Ok(())
            }

            fn do_step(&mut self, _t: f64, _h: f64) -> Result<(), String> {
                Ok(())
            }
        }
    };
}
pub(crate) use inert_model;

/// A first-order integrator `y' = gain·u + rate + w`, with one variable of each kind the
/// setters distinguish. `command = 99` makes a step panic (a model bug), and a large `rate`
/// or `u` overflows `y` to infinity (a non-finite output).
#[derive(Clone, Serialize, Deserialize)]
pub struct Toy {
    /// Parameter `gain` (1), fixed after initialization, in [0, 10].
    pub gain: f64,
    /// Tunable parameter `rate` (1), added to the derivative of `y`.
    pub rate: f64,
    /// Input `u` (1), interpolated over a step with `du`.
    pub u: f64,
    /// The derivative of `u` the host set with `fmi2SetRealInputDerivatives`, if any.
    pub du: Option<f64>,
    /// Input `w` (1), held over a step, in [-1, 1].
    pub w: f64,
    /// Output `y` (1), the integrated state.
    pub y: f64,
    /// Integer parameter `order`, fixed, in [1, 5].
    pub order: i32,
    /// Discrete input `command`: [`PANIC_COMMAND`] panics a step, [`SAMPLED_COMMAND`] makes the
    /// model sampled.
    pub command: i32,
    /// Boolean parameter `enabled`: whether `y` integrates at all.
    pub enabled: bool,
    /// Discrete Boolean input `hold`: freezes `y`.
    pub hold: bool,
    /// String parameter `label`, fixed.
    pub label: String,
    /// Discrete String input `note`, stored only.
    pub note: String,
}

pub mod vr {
    //! Value references of `Toy`: unique across types, as FMI 3.0 requires (FMI 2.0 would also
    //! allow Real 0 and Integer 0 to be different variables).
    pub const GAIN: u32 = 0;
    pub const RATE: u32 = 1;
    pub const U: u32 = 2;
    pub const Y: u32 = 3;
    pub const TWO: u32 = 4;
    pub const W: u32 = 5;

    pub const ORDER: u32 = 10;
    pub const COMMAND: u32 = 11;

    pub const ENABLED: u32 = 20;
    pub const POSITIVE: u32 = 21;
    pub const HOLD: u32 = 22;

    pub const LABEL: u32 = 30;
    pub const NOTE: u32 = 31;

    /// Not a value reference of any type.
    pub const UNKNOWN: u32 = 77;
}

/// The command value that makes `do_step` panic.
pub const PANIC_COMMAND: i32 = 99;

/// The command value that makes the toy a sampled model of period [`SAMPLE_PERIOD`] (s): its
/// largest sensible step.
pub const SAMPLED_COMMAND: i32 = 7;
pub const SAMPLE_PERIOD: f64 = 0.25;

/// The toy's cap on `communicationStepSize` (s).
pub const MAX_STEP_SIZE: f64 = 100.0;

impl Model for Toy {
    const INFO: ModelInfo = ModelInfo {
        model_identifier: "toy",
        description: "Test model of the fmi2 export crate",
        default_stop_time: 10.0,
        default_step_size: 0.1,
        can_interpolate_inputs: true,
        max_step_size: MAX_STEP_SIZE,
    };

    fn variables() -> &'static [Variable<Self>] {
        VARIABLES
    }

    fn new(_env: &Environment) -> Self {
        Toy {
            gain: f64::NAN,
            rate: f64::NAN,
            u: f64::NAN,
            du: None,
            w: f64::NAN,
            y: 0.0,
            order: 0,
            command: 0,
            enabled: false,
            hold: false,
            label: String::new(),
            note: String::new(),
        }
    }

    fn initialize(&mut self, _start_time: f64) -> Result<(), String> {
        self.y = self.gain * self.u;
        Ok(())
    }

    fn largest_sensible_step(&self) -> Option<f64> {
        (self.command == SAMPLED_COMMAND).then_some(SAMPLE_PERIOD)
    }

    fn do_step(&mut self, _t: f64, h: f64) -> Result<(), String> {
        if self.command == PANIC_COMMAND {
            panic!("toy: command {PANIC_COMMAND} reached a model bug");
        }
        if self.enabled && !self.hold {
            let du = self.du.unwrap_or(0.0);
            self.y += h * (self.gain * self.u + self.rate + self.w) + 0.5 * h * h * self.gain * du;
        }
        Ok(())
    }
}

type V = Variable<Toy>;
type Real = fmu_model::Real<Toy>;
type Integer = fmu_model::Integer<Toy>;
type Boolean = fmu_model::Boolean<Toy>;
type Text = fmu_model::Text<Toy>;
type SparseReal = fmu_model::Real<Sparse>;
type OtherReal = fmu_model::Real<Other>;

static VARIABLES: &[V] = &[
    Real::parameter(vr::GAIN, "gain")
        .unit("1")
        .start(1.0)
        .range(0.0, 10.0)
        .doc("Fixed, in [0, 10]")
        .get(|m| m.gain)
        .set(|m, v| m.gain = v),
    Real::tunable(vr::RATE, "rate").unit("1").start(0.0).doc("Tunable").get(|m| m.rate).set(|m, v| m.rate = v),
    Real::input(vr::U, "u")
        .unit("1")
        .start(0.0)
        .doc("Interpolated input")
        .get(|m| m.u)
        .set(|m, v| m.u = v)
        .derivative(|m, d| m.du = d),
    Real::output(vr::Y, "y").unit("1").doc("Integrated output").get(|m| m.y),
    Variable {
        vr: vr::TWO,
        name: "two",
        description: "A constant",
        causality: Causality::Local,
        variability: Variability::Constant,
        value: Value::Real { unit: "", start: 2.0, min: None, max: None, get: |_| 2.0, set: None, derivative: None },
    },
    Real::held_input(vr::W, "w")
        .unit("1")
        .start(0.0)
        .range(-1.0, 1.0)
        .doc("Held input in [-1, 1]")
        .get(|m| m.w)
        .set(|m, v| m.w = v),
    Integer::parameter(vr::ORDER, "order")
        .start(2)
        .range(1, 5)
        .doc("Fixed, in [1, 5]")
        .get(|m| m.order)
        .set(|m, v| m.order = v),
    Variable {
        vr: vr::COMMAND,
        name: "command",
        description: "Discrete input in [0, 99]",
        causality: Causality::Input,
        variability: Variability::Discrete,
        value: Value::Integer {
            start: 0,
            min: Some(0),
            max: Some(PANIC_COMMAND),
            get: |m| m.command,
            set: Some(|m, v| m.command = v),
        },
    },
    Boolean::parameter(vr::ENABLED, "enabled").start(true).doc("Fixed").get(|m| m.enabled).set(|m, v| m.enabled = v),
    Boolean::output(vr::POSITIVE, "positive").doc("y > 0").get(|m| m.y > 0.0),
    Variable {
        vr: vr::HOLD,
        name: "hold",
        description: "Discrete input: freeze y",
        causality: Causality::Input,
        variability: Variability::Discrete,
        value: Value::Boolean { start: false, get: |m| m.hold, set: Some(|m, v| m.hold = v) },
    },
    Text::parameter(vr::LABEL, "label").start("toy").doc("Fixed").get(|m| &m.label).set(|m, v| m.label = v.to_owned()),
    Variable {
        vr: vr::NOTE,
        name: "note",
        description: "Discrete string input",
        causality: Causality::Input,
        variability: Variability::Discrete,
        value: Value::String { start: "", get: |m| &m.note, set: Some(|m, v| m.note = v.to_owned()) },
    },
];

crate::export_fmu!(Toy);

/// The exported C entry points of `Toy` (`fmi2DoStep`, …), as a host would call them.
pub use __fmi2_export::*;
pub use __fmi3_export::*;

/// Another FMU (its own table, hence its own GUID) whose model serializes to exactly the bytes
/// of a `Toy` (a newtype is transparent to serde's formats): only the image's header (model
/// identifier and GUID) tells their states apart.
/// Driven through [`crate::fmi2::api`] directly, since the `#[no_mangle]` symbols are taken by `Toy`.
#[derive(Clone, Serialize, Deserialize)]
pub struct Other(pub Toy);

impl Model for Other {
    const INFO: ModelInfo = ModelInfo { model_identifier: "other", ..Toy::INFO };

    fn variables() -> &'static [Variable<Self>] {
        OTHER_VARIABLES
    }

    fn new(env: &Environment) -> Self {
        Other(crate::instance::with_start_values::<Toy>(env).unwrap_or_else(|_| Toy::new(env)))
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        self.0.initialize(start_time)
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        self.0.do_step(t, h)
    }
}

static OTHER_VARIABLES: &[Variable<Other>] = &[
    OtherReal::tunable(vr::RATE, "rate").unit("1").start(0.0).doc("Tunable").get(|m| m.0.rate).set(|m, v| m.0.rate = v),
    OtherReal::output(vr::Y, "y").unit("1").doc("Integrated output").get(|m| m.0.y),
];

/// Three tunable Reals at value references billions apart, so that the exporter's lookup falls
/// back from a dense table to bisection, and their weighted sum `s = a + 10·b + 100·c`.
/// Driven through [`crate::fmi2::api`] directly, like [`Other`].
#[derive(Clone, Serialize, Deserialize)]
pub struct Sparse {
    /// Tunable `a` (1) at [`sparse_vr::A`].
    pub a: f64,
    /// Tunable `b` (1) at [`sparse_vr::B`], weighted 10 in `s`.
    pub b: f64,
    /// Tunable `c` (1) at [`sparse_vr::C`], weighted 100 in `s`.
    pub c: f64,
}

pub mod sparse_vr {
    //! Value references of `Sparse` (all Real).
    pub const A: u32 = 7;
    pub const B: u32 = 123_456;
    pub const C: u32 = 3_000_000_000;
    pub const S: u32 = u32::MAX;
}

inert_model!(Sparse {
    info: ModelInfo { model_identifier: "sparse", ..Toy::INFO },
    variables: SPARSE_VARIABLES,
    new: Sparse { a: f64::NAN, b: f64::NAN, c: f64::NAN },
});

static SPARSE_VARIABLES: &[Variable<Sparse>] = &[
    SparseReal::tunable(sparse_vr::C, "c").unit("1").start(3.0).doc("Tunable").get(|m| m.c).set(|m, v| m.c = v),
    SparseReal::tunable(sparse_vr::A, "a").unit("1").start(1.0).doc("Tunable").get(|m| m.a).set(|m, v| m.a = v),
    SparseReal::output(sparse_vr::S, "s").unit("1").doc("a + 10 b + 100 c").get(|m| m.a + 10.0 * m.b + 100.0 * m.c),
    SparseReal::tunable(sparse_vr::B, "b").unit("1").start(2.0).doc("Tunable").get(|m| m.b).set(|m, v| m.b = v),
];

//! Driving a model in-process through its variable table, as an FMI host would, for the unit
//! tests of FMU crates. Misuse (an unknown name, a wrong type) panics with the name.

use crate::instance::{with_start_values, Core};
use crate::model::{Environment, Model};
use crate::state::State;
use crate::variables::{Value, Variable};

/// A model with every start value of its table applied (what `fmi2Instantiate` gives).
pub fn instantiate<M: Model>() -> M {
    with_start_values::<M>(&Environment::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The table row called `name`.
pub fn variable<M: Model>(name: &str) -> &'static Variable<M> {
    M::variables().iter().find(|v| v.name == name).unwrap_or_else(|| panic!("no variable {name}"))
}

pub fn set_real<M: Model>(m: &mut M, name: &str, value: f64) {
    match variable::<M>(name).value {
        Value::Real { set: Some(set), .. } => set(m, value),
        _ => panic!("{name} is not a settable Real"),
    }
}

pub fn set_integer<M: Model>(m: &mut M, name: &str, value: i32) {
    match variable::<M>(name).value {
        Value::Integer { set: Some(set), .. } => set(m, value),
        _ => panic!("{name} is not a settable Integer"),
    }
}

pub fn set_boolean<M: Model>(m: &mut M, name: &str, value: bool) {
    match variable::<M>(name).value {
        Value::Boolean { set: Some(set), .. } => set(m, value),
        _ => panic!("{name} is not a settable Boolean"),
    }
}

pub fn set_string<M: Model>(m: &mut M, name: &str, value: &str) {
    match variable::<M>(name).value {
        Value::String { set: Some(set), .. } => set(m, value),
        _ => panic!("{name} is not a settable String"),
    }
}

pub fn get_real<M: Model>(m: &M, name: &str) -> f64 {
    match variable::<M>(name).value {
        Value::Real { get, .. } => get(m),
        _ => panic!("{name} is not a Real"),
    }
}

/// The components of an x/y/z triple of Reals (the rows of `fmu_model::xyz!`): `prefix` followed
/// by `x`, `y` and `z`, as `[x, y, z]` (`Vec3::from` makes a vector of it).
pub fn get_xyz<M: Model>(m: &M, prefix: &str) -> [f64; 3] {
    ["x", "y", "z"].map(|axis| get_real(m, &format!("{prefix}{axis}")))
}

pub fn get_boolean<M: Model>(m: &M, name: &str) -> bool {
    match variable::<M>(name).value {
        Value::Boolean { get, .. } => get(m),
        _ => panic!("{name} is not a Boolean"),
    }
}

/// Checks that the Integer parameter `name` declares exactly the codes `from` accepts as its
/// range (`fmi2SetInteger` refuses anything outside the range, so the range must hold every
/// code and nothing else) and that every code round-trips through `from` and `to`.
pub fn assert_codes_are_the_range<M: Model, T: Copy + std::fmt::Debug>(
    name: &str,
    from: fn(i32) -> Option<T>,
    to: fn(T) -> i32,
) {
    let (lo, hi) = match variable::<M>(name).value {
        Value::Integer { min: Some(lo), max: Some(hi), .. } => (lo, hi),
        _ => panic!("{name} is not an Integer parameter with a range"),
    };
    for code in lo..=hi {
        let value = from(code).unwrap_or_else(|| panic!("{name} = {code} is in range but not a code"));
        assert_eq!(to(value), code, "{name} {value:?}");
    }
    assert!(from(lo - 1).is_none() && from(hi + 1).is_none(), "{name} has codes outside [{lo}, {hi}]");
}

/// `model` after a trip through the bytes of an FMU state image (what `fmi2SerializeFMUstate`
/// writes and `fmi2DeSerializeFMUstate` reads), as another instance of the FMU would get it.
pub fn round_trip<M: Model>(model: &M) -> M {
    let guid = crate::fmi2::xml::render::<M>().unwrap_or_else(|e| panic!("{e}")).guid;
    let identity = crate::image::Identity { model_identifier: M::INFO.model_identifier, guid: &guid };
    let core = Core { state: State::StepComplete, start_time: 0.0, stop_time: None, time: 0.0, model: model.clone() };
    let bytes = crate::image::encode(identity, &core).unwrap_or_else(|e| panic!("{e}"));
    crate::image::decode::<Core<M>>(identity, &bytes).unwrap_or_else(|e| panic!("{e}")).model
}

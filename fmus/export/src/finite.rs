//! Whether every floating-point number inside a serializable value is finite: a serializer that
//! writes nothing and fails at the first NaN or infinity, naming the fields that lead to it. A
//! model's state decoded from host-supplied bytes is checked with it before any use, so that
//! garbage cannot reach the physics (a NaN limit makes `f64::clamp` panic, for instance).

use serde::ser::{self, Serialize};
use std::fmt;

/// Where the first non-finite number is (field names and indices, outermost first) and its value.
pub fn check<T: Serialize>(value: &T) -> std::result::Result<(), String> {
    value.serialize(Finite).map_err(|e| e.to_string())
}

#[derive(Debug)]
struct NonFinite {
    path: Vec<String>,
    value: f64,
}

impl NonFinite {
    fn within(mut self, step: impl fmt::Display) -> Self {
        self.path.insert(0, step.to_string());
        self
    }
}

impl fmt::Display for NonFinite {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{} is {}", self.path.join("."), self.value)
    }
}

impl std::error::Error for NonFinite {}

impl ser::Error for NonFinite {
    /// Only for errors of `Serialize` implementations, which ours do not raise.
    fn custom<T: fmt::Display>(msg: T) -> Self {
        NonFinite { path: vec![msg.to_string()], value: f64::NAN }
    }
}

/// Serializer methods of values that hold no floating-point number (integers, text, unit
/// values): accepted without looking; `$arg` are the types after `self`.
macro_rules! leaves_without_floats {
    ($($method:ident($($arg:ty),*)),* $(,)?) => {$(
        fn $method(self, $(_: $arg),*) -> Result {
            Ok(())
        }
    )*};
}

/// Serializer methods that start a compound value (`$arg` are the types after `self`): the
/// checker of its elements or fields, `$start` of type `$checker` ([`Elements`] from index 0,
/// or [`Finite`]).
macro_rules! compounds {
    ($($method:ident($($arg:ty),*) -> $checker:ident = $start:expr),* $(,)?) => {$(
        fn $method(self, $(_: $arg),*) -> Result<$checker> {
            Ok($start)
        }
    )*};
}

/// The serializer; also the state of every compound value (it has none), counting elements.
#[derive(Clone, Copy)]
struct Finite;

/// A sequence, tuple or map being checked: the index of the next element.
struct Elements(usize);

type Result<T = ()> = std::result::Result<T, NonFinite>;

fn float(value: f64) -> Result {
    if value.is_finite() {
        Ok(())
    } else {
        Err(NonFinite { path: Vec::new(), value })
    }
}

impl ser::Serializer for Finite {
    type Ok = ();
    type Error = NonFinite;
    type SerializeSeq = Elements;
    type SerializeTuple = Elements;
    type SerializeTupleStruct = Elements;
    type SerializeTupleVariant = Elements;
    type SerializeMap = Elements;
    type SerializeStruct = Finite;
    type SerializeStructVariant = Finite;

    fn serialize_f64(self, v: f64) -> Result {
        float(v)
    }
    fn serialize_f32(self, v: f32) -> Result {
        float(v.into())
    }
    leaves_without_floats! {
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
    }
    fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> Result {
        value.serialize(self)
    }
    leaves_without_floats! {
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    }
    fn serialize_newtype_struct<T: ?Sized + Serialize>(self, _: &'static str, value: &T) -> Result {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result {
        value.serialize(self).map_err(|e| e.within(variant))
    }
    compounds! {
        serialize_seq(Option<usize>) -> Elements = Elements(0),
        serialize_tuple(usize) -> Elements = Elements(0),
        serialize_tuple_struct(&'static str, usize) -> Elements = Elements(0),
        serialize_tuple_variant(&'static str, u32, &'static str, usize) -> Elements = Elements(0),
        serialize_map(Option<usize>) -> Elements = Elements(0),
        serialize_struct(&'static str, usize) -> Finite = Finite,
        serialize_struct_variant(&'static str, u32, &'static str, usize) -> Finite = Finite,
    }
}

impl Elements {
    fn next<T: ?Sized + Serialize>(&mut self, value: &T) -> Result {
        let index = self.0;
        self.0 += 1;
        value.serialize(Finite).map_err(|e| e.within(index))
    }
}

macro_rules! elements {
    ($($trait:ident :: $method:ident),*) => {$(
        impl ser::$trait for Elements {
            type Ok = ();
            type Error = NonFinite;
            fn $method<T: ?Sized + Serialize>(&mut self, value: &T) -> Result {
                self.next(value)
            }
            fn end(self) -> Result {
                Ok(())
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl ser::SerializeMap for Elements {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_key<T: ?Sized + Serialize>(&mut self, key: &T) -> Result {
        key.serialize(Finite)
    }
    fn serialize_value<T: ?Sized + Serialize>(&mut self, value: &T) -> Result {
        self.next(value)
    }
    fn end(self) -> Result {
        Ok(())
    }
}

macro_rules! fields {
    ($($trait:ident),*) => {$(
        impl ser::$trait for Finite {
            type Ok = ();
            type Error = NonFinite;
            fn serialize_field<T: ?Sized + Serialize>(&mut self, key: &'static str, value: &T) -> Result {
                value.serialize(Finite).map_err(|e| e.within(key))
            }
            fn end(self) -> Result {
                Ok(())
            }
        }
    )*};
}

fields!(SerializeStruct, SerializeStructVariant);

#[cfg(test)]
mod tests {
    use super::check;
    use serde::Serialize;

    #[derive(Serialize)]
    struct Limits {
        low: f64,
        high: Option<f64>,
    }

    #[derive(Serialize)]
    struct State {
        count: u64,
        limits: [Limits; 2],
        trace: Vec<(f64, f32)>,
    }

    fn state() -> State {
        State {
            count: 3,
            limits: [Limits { low: -1.0, high: Some(1.0) }, Limits { low: 0.0, high: None }],
            trace: vec![(0.0, 1.0), (f64::MAX, f32::MIN)],
        }
    }

    #[test]
    fn the_first_non_finite_number_is_named_by_its_path() {
        assert_eq!(check(&state()), Ok(()));
        let mut s = state();
        s.limits[1].high = Some(f64::NAN);
        assert_eq!(check(&s), Err("limits.1.high is NaN".to_owned()));
        let mut s = state();
        s.trace[1].1 = f32::NEG_INFINITY;
        assert_eq!(check(&s), Err("trace.1.1 is -inf".to_owned()));
    }
}

//! The rows of an FMI 3.0 FMU that are not direct scalars ([`Fmi3Element`], listed by `crate::fmu`):
//! converted types and array elements, read and written through the FMI 3.0 function of their
//! own type. A call that touches none of them goes straight to the FMU (the adapter checks
//! [`Elements::touches`] first), so the FMUs without any pay nothing.
//!
//! Arrays are read whole and set whole (FMI 3.0 has no element access): the adapter keeps the
//! values it last set per array ([`Shadow`], from the start values on), so setting one element
//! sets the array with the others as they were.

use std::collections::BTreeMap;
use std::ffi::c_int;

use super::types::{Fmi3Element, Fmi3Type, Start};
use super::Functions;
use crate::fmi::ffi;

use fmi3_sys as f3;

/// Why an element access failed: the FMU's status, or the importer's refusal of a value.
pub(super) enum Failure {
    /// The FMU returned this status (worse than a warning); it logged why.
    Status(c_int),
    /// The importer refused (a value that does not convert, a function the FMU does not export).
    Refused(String),
}

/// The values last set of one FMI 3.0 variable, by element.
enum Shadow {
    Float(Vec<f64>),
    Int(Vec<i128>),
    Bool(Vec<bool>),
}

/// The converted and element rows of one instance.
pub(super) struct Elements {
    by_vr: BTreeMap<u32, Fmi3Element>,
    shadows: BTreeMap<u32, Shadow>,
}

impl Elements {
    pub(super) fn new(list: &[Fmi3Element]) -> Elements {
        let mut shadows = BTreeMap::new();
        for element in list {
            let shadow = shadows.entry(element.fmi3_value_reference).or_insert_with(|| match element.fmi3_type {
                Fmi3Type::Float64 | Fmi3Type::Float32 => Shadow::Float(vec![0.0; element.size]),
                Fmi3Type::Boolean => Shadow::Bool(vec![false; element.size]),
                _ => Shadow::Int(vec![0; element.size]),
            });
            match (shadow, element.start) {
                (Shadow::Float(values), Some(Start::Float(v))) => values[element.index] = v,
                (Shadow::Int(values), Some(Start::Integer(v))) => values[element.index] = v,
                (Shadow::Bool(values), Some(Start::Boolean(v))) => values[element.index] = v,
                _ => {}
            }
        }
        Elements { by_vr: list.iter().map(|e| (e.value_reference, e.clone())).collect(), shadows }
    }

    /// Whether any of `vrs` is a converted or element row.
    pub(super) fn touches(&self, vrs: &[u32]) -> bool {
        !self.by_vr.is_empty() && vrs.iter().any(|vr| self.by_vr.contains_key(vr))
    }

    pub(super) fn get(&self, vr: u32) -> Option<&Fmi3Element> {
        self.by_vr.get(&vr)
    }

    /// Sets element `element` to `value` in the shadow of its array and returns the whole array.
    fn shadow_with<T: Clone>(
        &mut self,
        element: &Fmi3Element,
        value: T,
        pick: fn(&mut Shadow) -> Option<&mut Vec<T>>,
    ) -> Vec<T> {
        let shadow = self.shadows.get_mut(&element.fmi3_value_reference).and_then(pick);
        match shadow {
            Some(values) => {
                values[element.index] = value;
                values.clone()
            }
            None => vec![value],
        }
    }

    pub(super) fn set_float(
        &mut self,
        f: &Functions,
        instance: f3::fmi3Instance,
        e: &Fmi3Element,
        value: f64,
    ) -> Result<(), Failure> {
        if e.fmi3_type == Fmi3Type::Float32 && f64::from(value as f32).to_bits() != value.to_bits() {
            return Err(Failure::Refused(format!(
                "{} is an FMI 3.0 Float32: {value:?} is not exactly a 32-bit float (the nearest is {:?})",
                e.name,
                f64::from(value as f32)
            )));
        }
        let values = self.shadow_with(e, value, |s| if let Shadow::Float(v) = s { Some(v) } else { None });
        write_floats(f, instance, e, &values)
    }

    pub(super) fn set_int(
        &mut self,
        f: &Functions,
        instance: f3::fmi3Instance,
        e: &Fmi3Element,
        value: i32,
    ) -> Result<(), Failure> {
        let (low, high) = e.fmi3_type.integer_range().unwrap_or((0, -1));
        let value = i128::from(value);
        if !(low..=high).contains(&value) {
            return Err(Failure::Refused(format!(
                "{} is an FMI 3.0 {}: {value} is outside [{low}, {high}]",
                e.name,
                e.fmi3_type.name()
            )));
        }
        let values = self.shadow_with(e, value, |s| if let Shadow::Int(v) = s { Some(v) } else { None });
        write_ints(f, instance, e, &values)
    }

    pub(super) fn set_bool(
        &mut self,
        f: &Functions,
        instance: f3::fmi3Instance,
        e: &Fmi3Element,
        value: bool,
    ) -> Result<(), Failure> {
        let values = self.shadow_with(e, value, |s| if let Shadow::Bool(v) = s { Some(v) } else { None });
        let vr = e.fmi3_value_reference;
        // SAFETY: the live instance; one value reference and `values.len()` C bools.
        status(unsafe { (f.fmi3SetBoolean)(instance, &vr, 1, values.as_ptr(), values.len()) })
    }
}

/// Ok for OK and Warning (a warning is logged by the FMU), else the status.
pub(super) fn status(raw: c_int) -> Result<(), Failure> {
    if raw <= ffi::fmi2Warning {
        Ok(())
    } else {
        Err(Failure::Status(raw))
    }
}

/// The function `name` of the FMU, or a refusal saying it does not export it.
fn exported<T>(function: Option<T>, name: &str) -> Result<T, Failure> {
    function.ok_or_else(|| Failure::Refused(format!("the FMU does not export {name}")))
}

/// Every element of the FMI 3.0 variable behind `e`, as Reals.
pub(super) fn read_floats(f: &Functions, instance: f3::fmi3Instance, e: &Fmi3Element) -> Result<Vec<f64>, Failure> {
    let vr = e.fmi3_value_reference;
    match e.fmi3_type {
        Fmi3Type::Float32 => {
            let get = exported(f.fmi3GetFloat32, "fmi3GetFloat32")?;
            let mut values = vec![0f32; e.size];
            // SAFETY: the live instance; one value reference and `size` writable values.
            status(unsafe { get(instance, &vr, 1, values.as_mut_ptr(), e.size) })?;
            Ok(values.into_iter().map(f64::from).collect())
        }
        _ => {
            let mut values = vec![0f64; e.size];
            // SAFETY: as above.
            status(unsafe { (f.fmi3GetFloat64)(instance, &vr, 1, values.as_mut_ptr(), e.size) })?;
            Ok(values)
        }
    }
}

fn write_floats(f: &Functions, instance: f3::fmi3Instance, e: &Fmi3Element, values: &[f64]) -> Result<(), Failure> {
    let vr = e.fmi3_value_reference;
    match e.fmi3_type {
        Fmi3Type::Float32 => {
            let set = exported(f.fmi3SetFloat32, "fmi3SetFloat32")?;
            // Exact: every value was checked to be a float32 when it was set (or is a start value).
            let narrow: Vec<f32> = values.iter().map(|v| *v as f32).collect();
            // SAFETY: the live instance; one value reference and `len` values.
            status(unsafe { set(instance, &vr, 1, narrow.as_ptr(), narrow.len()) })
        }
        // SAFETY: as above.
        _ => status(unsafe { (f.fmi3SetFloat64)(instance, &vr, 1, values.as_ptr(), values.len()) }),
    }
}

/// Reads `size` values of an integer type through `get` and widens them.
macro_rules! read_as {
    ($get:expr, $name:literal, $t:ty, $instance:expr, $vr:expr, $size:expr) => {{
        let get = exported($get, $name)?;
        let mut values: Vec<$t> = vec![0; $size];
        // SAFETY: the live instance; one value reference and `size` writable values.
        status(unsafe { get($instance, &$vr, 1, values.as_mut_ptr(), $size) })?;
        values.into_iter().map(i128::from).collect()
    }};
}

/// Every element of the FMI 3.0 integer variable behind `e`, widened.
pub(super) fn read_ints(f: &Functions, instance: f3::fmi3Instance, e: &Fmi3Element) -> Result<Vec<i128>, Failure> {
    let (vr, n) = (e.fmi3_value_reference, e.size);
    Ok(match e.fmi3_type {
        Fmi3Type::Int8 => read_as!(f.fmi3GetInt8, "fmi3GetInt8", i8, instance, vr, n),
        Fmi3Type::UInt8 => read_as!(f.fmi3GetUInt8, "fmi3GetUInt8", u8, instance, vr, n),
        Fmi3Type::Int16 => read_as!(f.fmi3GetInt16, "fmi3GetInt16", i16, instance, vr, n),
        Fmi3Type::UInt16 => read_as!(f.fmi3GetUInt16, "fmi3GetUInt16", u16, instance, vr, n),
        Fmi3Type::Int32 => read_as!(Some(f.fmi3GetInt32), "fmi3GetInt32", i32, instance, vr, n),
        Fmi3Type::UInt32 => read_as!(f.fmi3GetUInt32, "fmi3GetUInt32", u32, instance, vr, n),
        Fmi3Type::Int64 | Fmi3Type::Enumeration => read_as!(f.fmi3GetInt64, "fmi3GetInt64", i64, instance, vr, n),
        Fmi3Type::UInt64 => read_as!(f.fmi3GetUInt64, "fmi3GetUInt64", u64, instance, vr, n),
        other => return Err(Failure::Refused(format!("{} is an FMI 3.0 {}, not an integer", e.name, other.name()))),
    })
}

/// Narrows `values` (checked against the type's range when they were set) and sets them.
macro_rules! write_as {
    ($set:expr, $name:literal, $t:ty, $instance:expr, $vr:expr, $values:expr) => {{
        let set = exported($set, $name)?;
        let narrow: Vec<$t> = $values.iter().map(|v| <$t>::try_from(*v).unwrap_or_default()).collect();
        // SAFETY: the live instance; one value reference and `len` values.
        status(unsafe { set($instance, &$vr, 1, narrow.as_ptr(), narrow.len()) })
    }};
}

fn write_ints(f: &Functions, instance: f3::fmi3Instance, e: &Fmi3Element, values: &[i128]) -> Result<(), Failure> {
    let vr = e.fmi3_value_reference;
    match e.fmi3_type {
        Fmi3Type::Int8 => write_as!(f.fmi3SetInt8, "fmi3SetInt8", i8, instance, vr, values),
        Fmi3Type::UInt8 => write_as!(f.fmi3SetUInt8, "fmi3SetUInt8", u8, instance, vr, values),
        Fmi3Type::Int16 => write_as!(f.fmi3SetInt16, "fmi3SetInt16", i16, instance, vr, values),
        Fmi3Type::UInt16 => write_as!(f.fmi3SetUInt16, "fmi3SetUInt16", u16, instance, vr, values),
        Fmi3Type::Int32 => write_as!(Some(f.fmi3SetInt32), "fmi3SetInt32", i32, instance, vr, values),
        Fmi3Type::UInt32 => write_as!(f.fmi3SetUInt32, "fmi3SetUInt32", u32, instance, vr, values),
        Fmi3Type::Int64 | Fmi3Type::Enumeration => write_as!(f.fmi3SetInt64, "fmi3SetInt64", i64, instance, vr, values),
        Fmi3Type::UInt64 => write_as!(f.fmi3SetUInt64, "fmi3SetUInt64", u64, instance, vr, values),
        other => Err(Failure::Refused(format!("{} is an FMI 3.0 {}, not an integer", e.name, other.name()))),
    }
}

/// Element `e.index` of an integer variable as an Integer row's value, if it fits.
pub(super) fn int_element(e: &Fmi3Element, values: &[i128]) -> Result<i32, Failure> {
    let value = values[e.index];
    i32::try_from(value).map_err(|_| {
        Failure::Refused(format!(
            "{} (an FMI 3.0 {}) is {value}, outside the 32-bit range of an Integer",
            e.name,
            e.fmi3_type.name()
        ))
    })
}

/// Every element of the Boolean variable behind `e`.
pub(super) fn read_bools(f: &Functions, instance: f3::fmi3Instance, e: &Fmi3Element) -> Result<Vec<bool>, Failure> {
    let vr = e.fmi3_value_reference;
    let mut bytes = vec![0u8; e.size];
    // SAFETY: the live instance; `size` C bools (one byte each) written into `bytes`.
    status(unsafe { (f.fmi3GetBoolean)(instance, &vr, 1, bytes.as_mut_ptr().cast(), e.size) })?;
    Ok(bytes.into_iter().map(|b| b != 0).collect())
}

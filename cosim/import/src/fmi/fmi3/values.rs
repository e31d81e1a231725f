//! Get and set: a call that touches no converted or element row goes straight to the FMU
//! (Real ↔ Float64, Integer ↔ Int32, Boolean ↔ Boolean, String ↔ String); the others go through
//! [`super::elements`] row by row.

use std::collections::BTreeMap;
use std::ffi::c_int;

use super::adapter::{adapter, report, Adapter};
use super::elements::{self, Elements, Failure};
use super::types::Fmi3Element;
use super::Functions;
use crate::fmi::ffi;
use fmi3_sys as f3;

pub(super) unsafe extern "C" fn get_real(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *mut f64,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter; `n` elements in each array (the Slave checked the lengths).
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3GetFloat64)(a.instance, vr, n, v, n) };
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_float(*vr),
        Some(e) => {
            cached(&mut arrays, e, || elements::read_floats(&a.functions, a.instance, e)).map(|all| all[e.index])
        }
    });
    a.collect(values, out, |x| x)
}

pub(super) unsafe extern "C" fn get_integer(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *mut i32,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3GetInt32)(a.instance, vr, n, v, n) };
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_int(*vr),
        Some(e) => cached(&mut arrays, e, || elements::read_ints(&a.functions, a.instance, e))
            .and_then(|all| elements::int_element(e, &all)),
    });
    a.collect(values, out, |x| x)
}

pub(super) unsafe extern "C" fn get_boolean(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *mut c_int,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        let mut values = vec![0u8; n];
        // SAFETY: as above; the FMU writes `n` C bools (one byte each) into `values`.
        let status = unsafe { (a.functions.fmi3GetBoolean)(a.instance, vr, n, values.as_mut_ptr().cast(), n) };
        for (o, b) in out.iter_mut().zip(values) {
            *o = c_int::from(b != 0);
        }
        return status;
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_bool(*vr),
        Some(e) => cached(&mut arrays, e, || elements::read_bools(&a.functions, a.instance, e)).map(|all| all[e.index]),
    });
    a.collect(values, out, c_int::from)
}

pub(super) unsafe extern "C" fn get_string(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *mut ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { (adapter(c).functions.fmi3GetString)(adapter(c).instance, vr, n, v, n) }
}

pub(super) unsafe extern "C" fn set_real(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const f64,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { set_values(c, vr, n, v, |f| f.fmi3SetFloat64, Elements::set_float) }
}

pub(super) unsafe extern "C" fn set_integer(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const i32,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { set_values(c, vr, n, v, |f| f.fmi3SetInt32, Elements::set_int) }
}

pub(super) unsafe extern "C" fn set_boolean(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const c_int,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let values: Vec<bool> = unsafe { slice(v, n) }.iter().map(|b| *b != 0).collect();
    // SAFETY: as above; `values` holds the `n` values as C bools.
    unsafe { set_values(c, vr, n, values.as_ptr(), |f| f.fmi3SetBoolean, Elements::set_bool) }
}

/// An FMI 3.0 setter of one value type (`fmi3SetFloat64`, `fmi3SetInt32`, `fmi3SetBoolean`).
type Setter<T> = unsafe extern "C" fn(f3::fmi3Instance, *const u32, usize, *const T, usize) -> f3::fmi3Status;

/// Sets `n` values of a type FMI 3.0 takes as it is: all at once through `setter` when none is
/// a converted or element row, else row by row (`element` for those rows).
///
/// # Safety
/// `c` is a live adapter; `vr` and `v` have `n` elements each (as for `get_real`).
unsafe fn set_values<T: Copy>(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const T,
    setter: fn(&Functions) -> Setter<T>,
    element: fn(&mut Elements, &Functions, f3::fmi3Instance, &Fmi3Element, T) -> Result<(), Failure>,
) -> ffi::fmi2Status {
    // SAFETY: this function's contract.
    let (a, vrs, values) = unsafe { (adapter(c), slice(vr, n), slice(v, n)) };
    let set = setter(&a.functions);
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { set(a.instance, vr, n, v, n) };
    }
    a.set_each(
        vrs,
        values,
        |a, vr, value| {
            // SAFETY: the live instance; one value.
            elements::status(unsafe { set(a.instance, &vr, 1, &value, 1) })
        },
        element,
    )
}

pub(super) unsafe extern "C" fn set_string(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { (adapter(c).functions.fmi3SetString)(adapter(c).instance, vr, n, v, n) }
}

/// The values of the array behind `e`, read once per call (`read`) however many of its elements
/// the call asks for.
fn cached<T: Clone>(
    arrays: &mut BTreeMap<u32, Vec<T>>,
    e: &Fmi3Element,
    read: impl FnOnce() -> Result<Vec<T>, Failure>,
) -> Result<Vec<T>, Failure> {
    if let Some(values) = arrays.get(&e.fmi3_value_reference) {
        return Ok(values.clone());
    }
    let values = read()?;
    arrays.insert(e.fmi3_value_reference, values.clone());
    Ok(values)
}

/// `n` elements at `ptr` (none for a NULL pointer, which the Slave never passes with n > 0).
///
/// # Safety
/// A non-null `ptr` has `n` readable elements for `'a`.
unsafe fn slice<'a, T>(ptr: *const T, n: usize) -> &'a [T] {
    if ptr.is_null() || n == 0 {
        &[]
    } else {
        // SAFETY: this function's contract.
        unsafe { std::slice::from_raw_parts(ptr, n) }
    }
}

/// As [`slice`], writable.
///
/// # Safety
/// A non-null `ptr` has `n` writable elements for `'a`, referenced by nothing else.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize) -> &'a mut [T] {
    if ptr.is_null() || n == 0 {
        &mut []
    } else {
        // SAFETY: this function's contract.
        unsafe { std::slice::from_raw_parts_mut(ptr, n) }
    }
}

impl Adapter {
    /// A failed element access as a status: the FMU's, or `fmi2Error` with the refusal logged.
    fn fail(&self, failure: Failure) -> ffi::fmi2Status {
        match failure {
            Failure::Status(status) => status,
            Failure::Refused(message) => {
                report(self, ffi::fmi2Error, &message);
                ffi::fmi2Error
            }
        }
    }

    /// Writes `values` (converted by `to_c`) into `out`, or the first failure's status.
    fn collect<T, C>(
        &self,
        values: impl Iterator<Item = Result<T, Failure>>,
        out: &mut [C],
        to_c: impl Fn(T) -> C,
    ) -> ffi::fmi2Status {
        for (slot, value) in out.iter_mut().zip(values) {
            match value {
                Ok(value) => *slot = to_c(value),
                Err(failure) => return self.fail(failure),
            }
        }
        ffi::fmi2OK
    }

    /// Sets each value: `direct` for a direct row, `element` for a converted one or an element.
    fn set_each<T: Copy>(
        &mut self,
        vrs: &[u32],
        values: &[T],
        direct: impl Fn(&Adapter, u32, T) -> Result<(), Failure>,
        element: fn(&mut Elements, &Functions, f3::fmi3Instance, &Fmi3Element, T) -> Result<(), Failure>,
    ) -> ffi::fmi2Status {
        for (vr, value) in vrs.iter().zip(values) {
            let result = match self.elements.get(*vr).cloned() {
                None => direct(self, *vr, *value),
                Some(e) => element(&mut self.elements, &self.functions, self.instance, &e, *value),
            };
            if let Err(failure) = result {
                return self.fail(failure);
            }
        }
        ffi::fmi2OK
    }

    fn direct_float(&self, vr: u32) -> Result<f64, Failure> {
        let mut value = 0.0;
        // SAFETY: the live instance; one writable value.
        elements::status(unsafe { (self.functions.fmi3GetFloat64)(self.instance, &vr, 1, &mut value, 1) })?;
        Ok(value)
    }

    fn direct_int(&self, vr: u32) -> Result<i32, Failure> {
        let mut value = 0;
        // SAFETY: as above.
        elements::status(unsafe { (self.functions.fmi3GetInt32)(self.instance, &vr, 1, &mut value, 1) })?;
        Ok(value)
    }

    fn direct_bool(&self, vr: u32) -> Result<bool, Failure> {
        let mut byte = 0u8;
        // SAFETY: as above; one C bool (a byte).
        elements::status(unsafe {
            (self.functions.fmi3GetBoolean)(self.instance, &vr, 1, (&mut byte as *mut u8).cast(), 1)
        })?;
        Ok(byte != 0)
    }
}

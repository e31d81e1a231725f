//! Getting and setting variable values by value reference.

use std::ffi::{CStr, CString};
use std::ptr;

use super::{to_c_string, Slave, SlaveError};
use crate::fmi::ffi;
use crate::fmu::ScalarVariable;
use crate::value::{Value, VariableType};

/// A getter of the FMI 2.0 table (`fmi2GetReal`, …) of values of type `T`.
type Getter<T> = unsafe extern "C" fn(ffi::fmi2Component, *const u32, usize, *mut T) -> ffi::fmi2Status;
/// A setter of the FMI 2.0 table (`fmi2SetReal`, …) of values of type `T`.
type Setter<T> = unsafe extern "C" fn(ffi::fmi2Component, *const u32, usize, *const T) -> ffi::fmi2Status;

impl Slave {
    /// `name = value, ...` for the variables of a failed set call.
    fn describe_values(&self, abi_type: VariableType, vrs: &[u32], values: &[String]) -> String {
        const SHOWN: usize = 12;
        let mut parts: Vec<String> = vrs
            .iter()
            .zip(values)
            .take(SHOWN)
            .map(|(&vr, value)| match self.model.variable_by_reference(vr, abi_type) {
                Some(variable) => format!("{} = {value}", variable.name),
                None => format!("unknown valueReference {vr} = {value}"),
            })
            .collect();
        if vrs.len() > SHOWN {
            parts.push(format!("... {} more", vrs.len() - SHOWN));
        }
        parts.join(", ")
    }

    fn describe_references(&self, abi_type: VariableType, vrs: &[u32]) -> String {
        let names: Vec<String> = vrs
            .iter()
            .take(12)
            .map(|&vr| match self.model.variable_by_reference(vr, abi_type) {
                Some(variable) => variable.name.clone(),
                None => format!("unknown valueReference {vr}"),
            })
            .collect();
        let more = if vrs.len() > 12 { format!(", ... {} more", vrs.len() - 12) } else { String::new() };
        format!("{}{more}", names.join(", "))
    }

    /// One FMI 2.0 getter call (`call`, the table's `getter`) of the `T` values of `vrs` into
    /// `out`, checked; a failure names the variables as `abi_type` ones.
    fn get_raw<T>(
        &self,
        call: &'static str,
        abi_type: VariableType,
        getter: Getter<T>,
        vrs: &[u32],
        out: &mut [T],
    ) -> Result<(), SlaveError> {
        self.check_lengths(call, vrs.len(), out.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe { getter(self.component, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || Some(self.describe_references(abi_type, vrs)))
    }

    /// One FMI 2.0 setter call (`call`, the table's `setter`) of `vrs` to the `T` values `raw`,
    /// checked; a failure lists `name = value` of the variables (as `abi_type` ones), the values
    /// as `shown` spells them.
    fn set_raw<T>(
        &self,
        call: &'static str,
        abi_type: VariableType,
        setter: Setter<T>,
        vrs: &[u32],
        raw: &[T],
        shown: impl FnOnce() -> Vec<String>,
    ) -> Result<(), SlaveError> {
        self.check_lengths(call, vrs.len(), raw.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements (a string's pointer outlives the call).
        let status = unsafe { setter(self.component, vrs.as_ptr(), vrs.len(), raw.as_ptr()) };
        self.check(call, Some(self.time.get()), mark, status, || Some(self.describe_values(abi_type, vrs, &shown())))
    }

    /// `fmi2GetReal`: `values[i]` receives the value of `vrs[i]`.
    pub fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SlaveError> {
        self.get_raw("fmi2GetReal", VariableType::Real, self.functions.fmi2GetReal, vrs, values)
    }

    /// `fmi2GetInteger` (also for enumerations).
    pub fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SlaveError> {
        self.get_raw("fmi2GetInteger", VariableType::Integer, self.functions.fmi2GetInteger, vrs, values)
    }

    /// `fmi2GetBoolean` (any non-zero `fmi2Boolean` is `true`).
    pub fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SlaveError> {
        let call = "fmi2GetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mut raw_values = vec![ffi::fmi2False; vrs.len()];
        self.get_raw(call, VariableType::Boolean, self.functions.fmi2GetBoolean, vrs, &mut raw_values)?;
        for (value, raw) in values.iter_mut().zip(raw_values) {
            *value = raw != ffi::fmi2False;
        }
        Ok(())
    }

    /// `fmi2GetString`, copied into owned strings (invalid UTF-8 is replaced).
    pub fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SlaveError> {
        let call = "fmi2GetString";
        let mut pointers: Vec<ffi::fmi2String> = vec![ptr::null(); vrs.len()];
        self.get_raw(call, VariableType::String, self.functions.fmi2GetString, vrs, &mut pointers)?;
        pointers
            .into_iter()
            .zip(vrs)
            .map(|(pointer, vr)| {
                if pointer.is_null() {
                    Err(self.invalid(call, format!("the FMU returned NULL for valueReference {vr}")))
                } else {
                    // SAFETY: the FMU returned a NUL-terminated string valid until its next call.
                    Ok(unsafe { CStr::from_ptr(pointer) }.to_string_lossy().into_owned())
                }
            })
            .collect()
    }

    /// `fmi2SetReal`. On failure the error lists `name = value` of the variables.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SlaveError> {
        let shown = || values.iter().map(|v| format!("{v:?}")).collect();
        self.set_raw("fmi2SetReal", VariableType::Real, self.functions.fmi2SetReal, vrs, values, shown)
    }

    /// `fmi2SetInteger` (also for enumerations).
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SlaveError> {
        let shown = || values.iter().map(i32::to_string).collect();
        self.set_raw("fmi2SetInteger", VariableType::Integer, self.functions.fmi2SetInteger, vrs, values, shown)
    }

    /// `fmi2SetBoolean`.
    pub fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SlaveError> {
        let call = "fmi2SetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let raw_values: Vec<ffi::fmi2Boolean> = values.iter().map(|&v| ffi::fmi2Boolean::from(v)).collect();
        let shown = || values.iter().map(bool::to_string).collect();
        self.set_raw(call, VariableType::Boolean, self.functions.fmi2SetBoolean, vrs, &raw_values, shown)
    }

    /// `fmi2SetString`.
    pub fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SlaveError> {
        let call = "fmi2SetString";
        self.check_lengths(call, vrs.len(), values.len())?;
        let owned: Vec<CString> =
            values.iter().map(|v| to_c_string(&self.name, call, "value", v)).collect::<Result<_, _>>()?;
        let pointers: Vec<ffi::fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        let shown = || values.iter().map(|v| format!("{v:?}")).collect();
        self.set_raw(call, VariableType::String, self.functions.fmi2SetString, vrs, &pointers, shown)
    }

    /// Sets one value of any type on the variable `variable` (type-checked).
    pub fn set_value(&mut self, variable: &ScalarVariable, value: &Value) -> Result<(), SlaveError> {
        let vr = [variable.value_reference];
        match (variable.variable_type.abi_type(), value) {
            (VariableType::Real, Value::Real(v)) => self.set_real(&vr, &[*v]),
            (VariableType::Integer, Value::Integer(v)) => self.set_integer(&vr, &[*v]),
            (VariableType::Boolean, Value::Boolean(v)) => self.set_boolean(&vr, &[*v]),
            (VariableType::String, Value::String(v)) => self.set_string(&vr, &[v.as_str()]),
            (expected, value) => Err(SlaveError::TypeMismatch {
                instance: self.name.clone(),
                variable: variable.name.clone(),
                expected,
                actual: value.abi_type(),
            }),
        }
    }

    /// Reads one value of any type.
    pub fn get_value(&self, variable: &ScalarVariable) -> Result<Value, SlaveError> {
        let vr = [variable.value_reference];
        Ok(match variable.variable_type.abi_type() {
            VariableType::Real => {
                let mut v = [0.0];
                self.get_real(&vr, &mut v)?;
                Value::Real(v[0])
            }
            VariableType::Boolean => {
                let mut v = [false];
                self.get_boolean(&vr, &mut v)?;
                Value::Boolean(v[0])
            }
            VariableType::String => Value::String(self.get_string(&vr)?.into_iter().next().unwrap_or_default()),
            _ => {
                let mut v = [0];
                self.get_integer(&vr, &mut v)?;
                Value::Integer(v[0])
            }
        })
    }

    /// `fmi2SetRealInputDerivatives`: `values[i]` is the `orders[i]`-th time
    /// derivative of input `vrs[i]` (SI unit per second^order), valid from the
    /// current communication point.
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Result<(), SlaveError> {
        let call = "fmi2SetRealInputDerivatives";
        self.check_lengths(call, vrs.len(), values.len())?;
        self.check_lengths(call, vrs.len(), orders.len())?;
        if !self.model.co_simulation.can_interpolate_inputs {
            return Err(SlaveError::Unsupported {
                instance: self.name.clone(),
                call,
                capability: "canInterpolateInputs",
            });
        }
        let mark = self.log.mark();
        // SAFETY: all slices have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2SetRealInputDerivatives)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_ptr(),
            )
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = orders.iter().zip(values).map(|(o, v)| format!("{v:?} (order {o})")).collect();
            Some(self.describe_values(VariableType::Real, vrs, &shown))
        })
    }
}

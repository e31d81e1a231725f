//! Getting and setting variable values by value reference.

use std::ffi::{CStr, CString};
use std::ptr;

use super::{to_c_string, Slave, SlaveError};
use crate::fmi::ffi;
use crate::fmu::ScalarVariable;
use crate::value::{Value, VariableType};

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

    /// `fmi2GetReal`: `values[i]` receives the value of `vrs[i]`.
    pub fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SlaveError> {
        let call = "fmi2GetReal";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe { (self.functions.fmi2GetReal)(self.component, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || Some(self.describe_references(VariableType::Real, vrs)))
    }

    /// `fmi2GetInteger` (also for enumerations).
    pub fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SlaveError> {
        let call = "fmi2GetInteger";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw =
            unsafe { (self.functions.fmi2GetInteger)(self.component, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::Integer, vrs))
        })
    }

    /// `fmi2GetBoolean` (any non-zero `fmi2Boolean` is `true`).
    pub fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SlaveError> {
        let call = "fmi2GetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mut raw_values = vec![ffi::fmi2False; vrs.len()];
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw = unsafe {
            (self.functions.fmi2GetBoolean)(self.component, vrs.as_ptr(), vrs.len(), raw_values.as_mut_ptr())
        };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::Boolean, vrs))
        })?;
        for (value, raw) in values.iter_mut().zip(raw_values) {
            *value = raw != ffi::fmi2False;
        }
        Ok(())
    }

    /// `fmi2GetString`, copied into owned strings (invalid UTF-8 is replaced).
    pub fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SlaveError> {
        let call = "fmi2GetString";
        let mut pointers: Vec<ffi::fmi2String> = vec![ptr::null(); vrs.len()];
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw =
            unsafe { (self.functions.fmi2GetString)(self.component, vrs.as_ptr(), vrs.len(), pointers.as_mut_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            Some(self.describe_references(VariableType::String, vrs))
        })?;
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
        let call = "fmi2SetReal";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe { (self.functions.fmi2SetReal)(self.component, vrs.as_ptr(), vrs.len(), values.as_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            Some(self.describe_values(VariableType::Real, vrs, &shown))
        })
    }

    /// `fmi2SetInteger` (also for enumerations).
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SlaveError> {
        let call = "fmi2SetInteger";
        self.check_lengths(call, vrs.len(), values.len())?;
        let mark = self.log.mark();
        // SAFETY: both slices have `vrs.len()` elements.
        let raw = unsafe { (self.functions.fmi2SetInteger)(self.component, vrs.as_ptr(), vrs.len(), values.as_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(i32::to_string).collect();
            Some(self.describe_values(VariableType::Integer, vrs, &shown))
        })
    }

    /// `fmi2SetBoolean`.
    pub fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SlaveError> {
        let call = "fmi2SetBoolean";
        self.check_lengths(call, vrs.len(), values.len())?;
        let raw_values: Vec<ffi::fmi2Boolean> = values.iter().map(|&v| ffi::fmi2Boolean::from(v)).collect();
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements.
        let raw =
            unsafe { (self.functions.fmi2SetBoolean)(self.component, vrs.as_ptr(), vrs.len(), raw_values.as_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(bool::to_string).collect();
            Some(self.describe_values(VariableType::Boolean, vrs, &shown))
        })
    }

    /// `fmi2SetString`.
    pub fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SlaveError> {
        let call = "fmi2SetString";
        self.check_lengths(call, vrs.len(), values.len())?;
        let owned: Vec<CString> =
            values.iter().map(|v| to_c_string(&self.name, call, "value", v)).collect::<Result<_, _>>()?;
        let pointers: Vec<ffi::fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        let mark = self.log.mark();
        // SAFETY: both buffers have `vrs.len()` elements; the strings outlive the call.
        let raw = unsafe { (self.functions.fmi2SetString)(self.component, vrs.as_ptr(), vrs.len(), pointers.as_ptr()) };
        self.check(call, Some(self.time.get()), mark, raw, || {
            let shown: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            Some(self.describe_values(VariableType::String, vrs, &shown))
        })
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

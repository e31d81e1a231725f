//! Saved FMU states (`fmi2GetFMUstate` & co).

use std::ptr;

use super::{Slave, SlaveError};
use crate::fmi::ffi;

/// An opaque FMU state owned by the instance that created it.
///
/// Free it with [`Slave::free_fmu_state`]; states that are never freed are
/// released by the FMU when the instance is freed.
#[derive(Debug)]
pub struct FmuState {
    pointer: ffi::fmi2FMUstate,
    owner: ffi::fmi2Component,
}

impl Slave {
    fn require_state_support(&self, call: &'static str, serialize: bool) -> Result<(), SlaveError> {
        let cs = &self.model.co_simulation;
        let (supported, capability) = if serialize {
            (cs.can_serialize_fmu_state, "canSerializeFMUstate")
        } else {
            (cs.can_get_and_set_fmu_state, "canGetAndSetFMUstate")
        };
        if supported {
            Ok(())
        } else {
            Err(SlaveError::Unsupported { instance: self.name.clone(), call, capability })
        }
    }

    fn check_owner(&self, call: &'static str, state: &FmuState) -> Result<(), SlaveError> {
        if state.owner == self.component {
            Ok(())
        } else {
            Err(self.invalid(call, "the FMU state belongs to another instance"))
        }
    }

    /// `fmi2GetFMUstate`: a snapshot of the complete instance state.
    pub fn get_fmu_state(&mut self) -> Result<FmuState, SlaveError> {
        let call = "fmi2GetFMUstate";
        self.require_state_support(call, false)?;
        let mut pointer: ffi::fmi2FMUstate = ptr::null_mut();
        let mark = self.log.mark();
        // SAFETY: live component; `pointer` is a valid out-parameter (NULL: allocate new).
        let raw = unsafe { (self.functions.fmi2GetFMUstate)(self.component, &mut pointer) };
        self.check(call, Some(self.time.get()), mark, raw, || None)?;
        if pointer.is_null() {
            return Err(self.invalid(call, "the FMU returned a NULL state"));
        }
        Ok(FmuState { pointer, owner: self.component })
    }

    /// `fmi2SetFMUstate`: restores a snapshot taken from this instance. The
    /// tracked phase becomes step mode and the tracked time is unchanged;
    /// use [`Slave::set_time_hint`] if the state is from another time.
    pub fn set_fmu_state(&mut self, state: &FmuState) -> Result<(), SlaveError> {
        let call = "fmi2SetFMUstate";
        self.check_owner(call, state)?;
        let mark = self.log.mark();
        // SAFETY: live component and a state created by it.
        let raw = unsafe { (self.functions.fmi2SetFMUstate)(self.component, state.pointer) };
        self.check(call, Some(self.time.get()), mark, raw, || None)?;
        self.phase.set(super::Phase::StepMode);
        Ok(())
    }

    /// `fmi2FreeFMUstate`.
    pub fn free_fmu_state(&mut self, state: FmuState) -> Result<(), SlaveError> {
        let call = "fmi2FreeFMUstate";
        self.check_owner(call, &state)?;
        let mut pointer = state.pointer;
        let mark = self.log.mark();
        // SAFETY: live component and a state created by it, freed once (consumed).
        let raw = unsafe { (self.functions.fmi2FreeFMUstate)(self.component, &mut pointer) };
        self.check(call, None, mark, raw, || None)
    }

    /// `fmi2SerializedFMUstateSize` + `fmi2SerializeFMUstate`.
    pub fn serialize_fmu_state(&mut self, state: &FmuState) -> Result<Vec<u8>, SlaveError> {
        let call = "fmi2SerializeFMUstate";
        self.require_state_support(call, true)?;
        self.check_owner(call, state)?;
        let mut size = 0usize;
        let mark = self.log.mark();
        // SAFETY: live component, own state, valid out-parameter.
        let raw = unsafe { (self.functions.fmi2SerializedFMUstateSize)(self.component, state.pointer, &mut size) };
        self.check("fmi2SerializedFMUstateSize", None, mark, raw, || None)?;
        let mut bytes = Vec::new();
        bytes
            .try_reserve_exact(size)
            .map_err(|_| self.invalid(call, format!("cannot allocate the {size} bytes the FMU asked for")))?;
        bytes.resize(size, 0u8);
        let mark = self.log.mark();
        // SAFETY: the buffer has exactly `size` bytes.
        let raw = unsafe {
            (self.functions.fmi2SerializeFMUstate)(
                self.component,
                state.pointer,
                bytes.as_mut_ptr() as *mut ffi::fmi2Byte,
                size,
            )
        };
        self.check(call, None, mark, raw, || Some(format!("size = {size}")))?;
        Ok(bytes)
    }

    /// `fmi2DeSerializeFMUstate`: a state for this instance from bytes produced
    /// by [`Slave::serialize_fmu_state`] (possibly in another instance or process).
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<FmuState, SlaveError> {
        let call = "fmi2DeSerializeFMUstate";
        self.require_state_support(call, true)?;
        let mut pointer: ffi::fmi2FMUstate = ptr::null_mut();
        let mark = self.log.mark();
        // SAFETY: `bytes` is valid for `len` bytes; `pointer` is a valid out-parameter.
        let raw = unsafe {
            (self.functions.fmi2DeSerializeFMUstate)(
                self.component,
                bytes.as_ptr() as *const ffi::fmi2Byte,
                bytes.len(),
                &mut pointer,
            )
        };
        self.check(call, None, mark, raw, || Some(format!("size = {}", bytes.len())))?;
        if pointer.is_null() {
            return Err(self.invalid(call, "the FMU returned a NULL state"));
        }
        Ok(FmuState { pointer, owner: self.component })
    }

    /// Tells the wrapper which communication point the instance is at (used
    /// in error messages only), e.g. after restoring a state.
    pub fn set_time_hint(&mut self, time: f64) {
        self.time.set(time);
    }
}

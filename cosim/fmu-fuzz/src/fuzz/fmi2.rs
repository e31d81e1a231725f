//! FMI 2.0 call sequences: any `fmi2*` function in any order, arguments good or bad, on up to
//! two instances, and FMI 3.0 calls on FMI 2.0 instances (the other version's API), which must
//! be refused.

use super::{Common, CATEGORIES, START_TIMES, STRINGS};
use crate::fmu::Fmu;
use fmi2_sys::*;
use fmi3_sys::{fmi3Error, fmi3FMUState};
use fmu_import::fmi::{Functions, LogContext, LogEcho};
use std::ffi::c_char;
use std::ptr::{null, null_mut};
use std::sync::atomic::AtomicU64;
use std::time::Instant;

/// An FMU state the sequence holds, and the instance that created it (which frees it with
/// itself).
struct Held {
    state: fmi2FMUstate,
    owner: fmi2Component,
}

pub(super) struct Sequence<'a> {
    common: Common<'a>,
    f: Functions,
    /// Logger contexts of every instantiation, kept until the end of the sequence. Boxed: the
    /// FMU holds a pointer to each, which must not move when the vector grows.
    #[allow(clippy::vec_box)]
    logs: Vec<Box<LogContext>>,
    /// Live instances and the index of their logger context.
    instances: Vec<fmi2Component>,
    log_of: Vec<(fmi2Component, usize)>,
    states: Vec<Held>,
}

impl<'a> super::Sequence<'a> for Sequence<'a> {
    fn start(fmu: &'a Fmu, seed: u64, progress: &'a AtomicU64) -> Self {
        Sequence {
            common: Common::new(fmu, super::Api::Fmi2, seed, progress),
            f: *fmu.library.functions(),
            logs: Vec::new(),
            instances: Vec::new(),
            log_of: Vec::new(),
            states: Vec::new(),
        }
    }

    fn common(&self) -> &Common<'a> {
        &self.common
    }

    fn common_mut(&mut self) -> &mut Common<'a> {
        &mut self.common
    }

    fn begin_as_host(&mut self) -> Result<(), String> {
        self.instantiate()?;
        self.drive_to_step_mode()
    }

    fn one_call(&mut self) -> Result<(), String> {
        match self.common.rng.below(50) {
            40..=47 => self.drive_to_step_mode(),
            48..=49 => self.other_version(),
            0..=2 => self.instantiate(),
            3 => self.free_instance(),
            4..=5 => self.setup_experiment(),
            6..=7 => self.simple("fmi2EnterInitializationMode", self.f.fmi2EnterInitializationMode),
            8..=9 => self.simple("fmi2ExitInitializationMode", self.f.fmi2ExitInitializationMode),
            10 => self.simple("fmi2Terminate", self.f.fmi2Terminate),
            11 => self.simple("fmi2Reset", self.f.fmi2Reset),
            12..=13 => self.get_real(),
            14 => self.get_other(),
            15..=17 => self.set_real(),
            18..=19 => self.set_other(),
            20 => self.set_input_derivatives(),
            21..=27 => self.do_step(),
            28..=29 => self.get_state(),
            30 => self.set_state(),
            31 => self.free_state(),
            32..=33 => self.serialize(),
            34..=36 => self.deserialize(),
            37 => self.set_debug_logging(),
            38 => self.status(),
            _ => self.unsupported(),
        }
    }

    /// Frees what the sequence holds: most states explicitly, the rest with their instances.
    fn finish(&mut self) {
        let free_states = self.common.rng.chance(0.6);
        for held in std::mem::take(&mut self.states) {
            if free_states {
                let mut state = held.state;
                // SAFETY: a live instance and a live state it created.
                unsafe { (self.f.fmi2FreeFMUstate)(held.owner, &mut state) };
            }
        }
        for c in std::mem::take(&mut self.instances) {
            // SAFETY: a live instance, freed once.
            unsafe { (self.f.fmi2FreeInstance)(c) };
        }
    }

    /// No logger received a fatal message (a panic in `fmi2FreeInstance`, which returns no
    /// status, would show only there).
    fn check_logs(&self) -> Result<(), String> {
        for log in &self.logs {
            if let Some(m) = log.messages().iter().find(|m| m.status == fmu_import::fmi::Status::Fatal) {
                return Err(format!("fatal message logged: {m}"));
            }
        }
        Ok(())
    }
}

impl Sequence<'_> {
    /// A live instance, or (sometimes, or if there is none) NULL, and whether it is NULL.
    fn component(&mut self) -> (fmi2Component, bool) {
        if self.instances.is_empty() || self.common.rng.chance(0.05) {
            (null_mut(), true)
        } else {
            (self.common.rng.pick(&self.instances), false)
        }
    }

    /// The last message the logger of instance `c` received.
    fn last_message(&self, c: fmi2Component) -> String {
        let log = self.log_of.iter().find(|(i, _)| *i == c).map(|(_, log)| &self.logs[*log]);
        log.and_then(|log| log.last_message()).map_or_else(|| "(none)".into(), |m| m.to_string())
    }

    fn instantiate(&mut self) -> Result<(), String> {
        // One argument in three is bad, one bad argument at a time.
        let fault = if self.common.rng.chance(0.3) { 1 + self.common.rng.below(8) } else { 0 };
        let name = match fault {
            1 => c"".as_ptr(),
            2 => c" \t".as_ptr(),
            3 => null(),
            _ => self.common.rng.pick(&[c"fuzz", c"fuzz2"]).as_ptr(),
        };
        let guid = match fault {
            4 => c"{00000000-0000-0000-0000-000000000000}".as_ptr(),
            5 => null(),
            _ => self.common.fmu.guid.as_ptr(),
        };
        let kind = if fault == 6 { self.common.rng.pick(&[fmi2ModelExchange, 7]) } else { fmi2CoSimulation };
        let resources =
            self.common.rng.pick(&[null(), c"file:///nonexistent/resources".as_ptr(), c"not a uri".as_ptr()]);
        let log = LogContext::new(&self.common.fmu.model, LogEcho::Off);
        let mut callbacks = log.callbacks();
        if fault == 7 {
            callbacks.logger = None;
        }
        let functions: *const fmi2CallbackFunctions = if fault == 8 { null() } else { &callbacks };
        let logging_on = if self.common.rng.chance(0.2) { fmi2True } else { fmi2False };
        let bad = fault != 0;
        let started = Instant::now();
        // SAFETY: every pointer is NULL or valid for the call; the context outlives the instance.
        let c = unsafe { (self.f.fmi2Instantiate)(name, kind, guid, resources, functions, fmi2False, logging_on) };
        let status = if c.is_null() { fmi2Error } else { fmi2OK };
        self.logs.push(log);
        self.common.check(format!("fmi2Instantiate(bad = {bad})"), bad, status, started)?;
        if !bad && c.is_null() {
            return Err("fmi2Instantiate refused good arguments".into());
        }
        if !c.is_null() {
            self.instances.push(c);
            self.log_of.push((c, self.logs.len() - 1));
        }
        Ok(())
    }

    /// What a host does first: an instance (a new one if there is none) through the setup of
    /// the experiment and initialization into step mode, so that sequences spend most calls
    /// where the models compute. The calls are checked as any other (in a state that does not
    /// allow them they are refused).
    fn drive_to_step_mode(&mut self) -> Result<(), String> {
        if self.instances.is_empty() {
            return self.instantiate();
        }
        let c = self.common.rng.pick(&self.instances);
        let start = self.common.rng.pick(&[0.0, 0.0, 0.0, 1.0, 1e6]);
        let started = Instant::now();
        // SAFETY: a live instance.
        let status = unsafe { (self.f.fmi2SetupExperiment)(c, fmi2False, 0.0, start, fmi2False, 0.0) };
        self.common.check(format!("fmi2SetupExperiment(start {start:?})"), false, status, started)?;
        for (name, function) in [
            ("fmi2EnterInitializationMode", self.f.fmi2EnterInitializationMode),
            ("fmi2ExitInitializationMode", self.f.fmi2ExitInitializationMode),
        ] {
            let started = Instant::now();
            // SAFETY: a live instance.
            let status = unsafe { function(c) };
            self.common.check(name.into(), false, status, started)?;
        }
        Ok(())
    }

    fn free_instance(&mut self) -> Result<(), String> {
        let (c, _) = self.component();
        let started = Instant::now();
        // SAFETY: NULL or a live instance, forgotten below together with the states it frees.
        unsafe { (self.f.fmi2FreeInstance)(c) };
        self.instances.retain(|i| *i != c);
        self.log_of.retain(|(i, _)| *i != c);
        self.states.retain(|s| s.owner != c);
        self.common.check("fmi2FreeInstance".into(), false, fmi2OK, started)
    }

    fn simple(
        &mut self,
        name: &str,
        function: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    ) -> Result<(), String> {
        let (c, bad) = self.component();
        let started = Instant::now();
        // SAFETY: NULL or a live instance.
        let status = unsafe { function(c) };
        self.common.check(name.into(), bad, status, started)
    }

    fn setup_experiment(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let start = self.common.rng.pick(&START_TIMES);
        let stop_defined = self.common.rng.chance(0.5);
        let stop = self.common.rng.pick(&[start + 1.0, start - 1.0, f64::NAN, 1e300, start, f64::INFINITY]);
        let tolerance_defined = self.common.rng.chance(0.3);
        let tolerance = self.common.rng.pick(&[1e-6, 1e-4, 0.0, -1.0, f64::NAN, f64::INFINITY]);
        let bad = null_instance
            || !start.is_finite()
            || (stop_defined && !(stop >= start && stop.is_finite()))
            || (tolerance_defined && !(tolerance > 0.0 && tolerance.is_finite()));
        let started = Instant::now();
        // SAFETY: NULL or a live instance.
        let status = unsafe {
            (self.f.fmi2SetupExperiment)(
                c,
                if tolerance_defined { fmi2True } else { fmi2False },
                tolerance,
                start,
                if stop_defined { fmi2True } else { fmi2False },
                stop,
            )
        };
        let what = format!(
            "fmi2SetupExperiment(tolerance {tolerance_defined}/{tolerance:?}, start {start:?}, stop {stop_defined}/{stop:?})"
        );
        self.common.check(what, bad, status, started)
    }

    /// Value references of one type: mostly known ones, some of other types or random; and
    /// whether one of them is unknown for this type.
    fn references(&mut self, known: &[u32]) -> (Vec<u32>, bool) {
        let others = self.common.fmu.references.all();
        self.common.references(known, &others)
    }

    fn get_real(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let known = self.common.fmu.references.real.clone();
        let (vrs, unknown) = self.references(&known);
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let mut values = vec![0.0; vrs.len()];
        let null_values = self.common.rng.chance(0.05) && !values.is_empty();
        let out = if null_values { null_mut() } else { values.as_mut_ptr() };
        let bad = null_instance || unknown || null_vrs || null_values;
        let started = Instant::now();
        // SAFETY: the arrays have `vrs.len()` elements (or are NULL).
        let status = unsafe { (self.f.fmi2GetReal)(c, vr_ptr, vrs.len(), out) };
        self.common.check(format!("fmi2GetReal({vrs:?})"), bad, status, started)?;
        if status == fmi2OK && values.iter().any(|v| !v.is_finite()) {
            return Err(format!("fmi2GetReal returned {values:?} with fmi2OK"));
        }
        Ok(())
    }

    /// A type other than Real (`kind`: 0 Integer, 1 Boolean, 2 String) and value references
    /// for it, as [`Self::references`].
    fn other_references(&mut self) -> (usize, Vec<u32>, bool) {
        let references = self.common.fmu.references.clone();
        let kind = self.common.rng.below(3);
        let known = [&references.integer, &references.boolean, &references.string][kind];
        let (vrs, unknown) = self.references(known);
        (kind, vrs, unknown)
    }

    fn get_other(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let (kind, vrs, unknown) = self.other_references();
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let null_values = self.common.rng.chance(0.05) && !vrs.is_empty();
        let bad = null_instance || unknown || null_vrs || null_values;
        let mut numbers = vec![0i32; vrs.len()];
        let mut strings = vec![null::<c_char>(); vrs.len()];
        let n = vrs.len();
        let started = Instant::now();
        // SAFETY: the arrays have `n` elements (or are NULL).
        let status = unsafe {
            match kind {
                0 => (self.f.fmi2GetInteger)(c, vr_ptr, n, if null_values { null_mut() } else { numbers.as_mut_ptr() }),
                1 => (self.f.fmi2GetBoolean)(c, vr_ptr, n, if null_values { null_mut() } else { numbers.as_mut_ptr() }),
                _ => (self.f.fmi2GetString)(c, vr_ptr, n, if null_values { null_mut() } else { strings.as_mut_ptr() }),
            }
        };
        self.common.check(
            format!("fmi2Get{}({vrs:?})", ["Integer", "Boolean", "String"][kind]),
            bad,
            status,
            started,
        )?;
        if status == fmi2OK && kind == 2 && strings.iter().any(|s| s.is_null()) {
            return Err("fmi2GetString returned a NULL string with fmi2OK".into());
        }
        Ok(())
    }

    fn set_real(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let known = self.common.fmu.references.real.clone();
        let (vrs, unknown) = self.references(&known);
        let values: Vec<f64> = (0..vrs.len()).map(|_| self.common.real()).collect();
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let (value_ptr, null_values) = self.common.array(&values);
        let bad = null_instance || unknown || null_vrs || null_values || values.iter().any(|v| !v.is_finite());
        let started = Instant::now();
        // SAFETY: the arrays have `vrs.len()` elements (or are NULL).
        let status = unsafe { (self.f.fmi2SetReal)(c, vr_ptr, vrs.len(), value_ptr) };
        self.common.check(format!("fmi2SetReal({vrs:?}, {values:?})"), bad, status, started)
    }

    fn set_other(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let (kind, vrs, unknown) = self.other_references();
        let numbers: Vec<i32> =
            (0..vrs.len()).map(|_| self.common.rng.pick(&[0, 1, 2, 3, 5, -1, 99, i32::MAX, i32::MIN])).collect();
        let strings: Vec<*const c_char> = (0..vrs.len())
            .map(|_| if self.common.rng.chance(0.05) { null() } else { self.common.rng.pick(&STRINGS).as_ptr() })
            .collect();
        let null_string = kind == 2 && strings.iter().any(|s| s.is_null());
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let (number_ptr, null_numbers) = self.common.array(&numbers);
        let (string_ptr, null_strings) = self.common.array(&strings);
        let null_values = if kind == 2 { null_strings } else { null_numbers };
        let bad = null_instance || unknown || null_vrs || null_values || null_string;
        let n = vrs.len();
        let started = Instant::now();
        // SAFETY: the arrays have `n` elements (or are NULL); strings are NUL-terminated.
        let status = unsafe {
            match kind {
                0 => (self.f.fmi2SetInteger)(c, vr_ptr, n, number_ptr),
                1 => (self.f.fmi2SetBoolean)(c, vr_ptr, n, number_ptr),
                _ => (self.f.fmi2SetString)(c, vr_ptr, n, string_ptr),
            }
        };
        self.common.check(
            format!("fmi2Set{}({vrs:?}, {numbers:?})", ["Integer", "Boolean", "String"][kind]),
            bad,
            status,
            started,
        )
    }

    fn set_input_derivatives(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let known = self.common.fmu.references.real.clone();
        let (vrs, unknown) = self.references(&known);
        let orders: Vec<i32> = (0..vrs.len()).map(|_| self.common.rng.pick(&[1, 1, 1, 0, 2, -1])).collect();
        let values: Vec<f64> = (0..vrs.len()).map(|_| self.common.real()).collect();
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let (order_ptr, null_orders) = self.common.array(&orders);
        let (value_ptr, null_values) = self.common.array(&values);
        let bad = null_instance
            || unknown
            || null_vrs
            || null_orders
            || null_values
            || orders.iter().any(|o| *o != 1)
            || values.iter().any(|v| !v.is_finite());
        let started = Instant::now();
        // SAFETY: the arrays have `vrs.len()` elements (or are NULL).
        let status = unsafe { (self.f.fmi2SetRealInputDerivatives)(c, vr_ptr, vrs.len(), order_ptr, value_ptr) };
        self.common.check(format!("fmi2SetRealInputDerivatives({vrs:?}, {orders:?}, {values:?})"), bad, status, started)
    }

    fn do_step(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let mut t = 0.0;
        if !null_instance {
            // SAFETY: a live instance; `t` is written only on success.
            unsafe { (self.f.fmi2GetRealStatus)(c, fmi2LastSuccessfulTime, &mut t) };
        }
        if self.common.rng.chance(0.1) {
            t = self.common.rng.pick(&[t + 1e-3, t - 1.0, f64::NAN, 1e300]);
        }
        let h = self.common.step_size();
        let bad = null_instance || !(h > 0.0) || !h.is_finite() || !t.is_finite();
        let started = Instant::now();
        // SAFETY: NULL or a live instance.
        let status = unsafe { (self.f.fmi2DoStep)(c, t, h, fmi2True) };
        self.common.figures.steps += (status == fmi2OK) as u64;
        self.common.check(format!("fmi2DoStep({t:?}, {h:?})"), bad, status, started)
    }

    fn get_state(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let reuse = !self.states.is_empty() && self.common.rng.chance(0.3);
        let mut slot = if reuse { self.states[self.common.rng.below(self.states.len())].state } else { null_mut() };
        let null_slot = self.common.rng.chance(0.05);
        let started = Instant::now();
        // SAFETY: the slot is NULL, or holds NULL or a live state.
        let status = unsafe { (self.f.fmi2GetFMUstate)(c, if null_slot { null_mut() } else { &mut slot }) };
        self.common.check("fmi2GetFMUstate".into(), null_instance || null_slot, status, started)?;
        if status == fmi2OK && !reuse {
            self.states.push(Held { state: slot, owner: c });
        }
        Ok(())
    }

    /// A held state (sometimes NULL), and whether it is NULL.
    fn held(&mut self) -> (fmi2FMUstate, bool) {
        if self.states.is_empty() || self.common.rng.chance(0.05) {
            (null_mut(), true)
        } else {
            (self.states[self.common.rng.below(self.states.len())].state, false)
        }
    }

    fn set_state(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let (state, null_state) = self.held();
        let started = Instant::now();
        // SAFETY: NULL or a live instance and state.
        let status = unsafe { (self.f.fmi2SetFMUstate)(c, state) };
        self.common.check("fmi2SetFMUstate".into(), null_instance || null_state, status, started)
    }

    fn free_state(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        if self.states.is_empty() {
            return Ok(());
        }
        let i = self.common.rng.below(self.states.len());
        let mut state = self.states[i].state;
        let started = Instant::now();
        // SAFETY: NULL or a live instance; a live state of this FMU.
        let status = unsafe { (self.f.fmi2FreeFMUstate)(c, &mut state) };
        self.common.check("fmi2FreeFMUstate".into(), null_instance, status, started)?;
        if status == fmi2OK {
            self.states.swap_remove(i);
        }
        Ok(())
    }

    fn serialize(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let (state, null_state) = self.held();
        let mut size = 0;
        let started = Instant::now();
        // SAFETY: NULL or a live instance and state.
        let status = unsafe { (self.f.fmi2SerializedFMUstateSize)(c, state, &mut size) };
        self.common.check("fmi2SerializedFMUstateSize".into(), null_instance || null_state, status, started)?;
        if status != fmi2OK {
            if !(null_instance || null_state) {
                let message = self.last_message(c);
                self.common.count_unserializable(message);
            }
            return Ok(());
        }
        let mut bytes = vec![0 as fmi2Byte; size];
        let short = self.common.rng.chance(0.1) && size > 0;
        let started = Instant::now();
        // SAFETY: `bytes` has `size` bytes; a short size is announced as such.
        let status = unsafe { (self.f.fmi2SerializeFMUstate)(c, state, bytes.as_mut_ptr(), size - short as usize) };
        self.common.check("fmi2SerializeFMUstate".into(), short, status, started)?;
        if status != fmi2OK {
            return Ok(());
        }
        let image: Vec<u8> = bytes.iter().map(|b| *b as u8).collect();
        // Bytes the FMU serialized must always be accepted back.
        let mut restored = null_mut();
        let started = Instant::now();
        // SAFETY: a live instance; `image` has the announced size.
        let status = unsafe {
            (self.f.fmi2DeSerializeFMUstate)(c, image.as_ptr() as *const fmi2Byte, image.len(), &mut restored)
        };
        self.common.check("fmi2DeSerializeFMUstate(intact)".into(), false, status, started)?;
        if status != fmi2OK {
            return Err(format!("bytes the FMU serialized were refused: {}", self.last_message(c)));
        }
        self.states.push(Held { state: restored, owner: c });
        self.common.keep_image(image);
        Ok(())
    }

    fn deserialize(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let bytes = self.common.garbage();
        let null_bytes = self.common.rng.chance(0.05) && !bytes.is_empty();
        let reuse = !self.states.is_empty() && self.common.rng.chance(0.3);
        let mut slot = if reuse { self.states[self.common.rng.below(self.states.len())].state } else { null_mut() };
        let pointer = if null_bytes { null() } else { bytes.as_ptr() as *const fmi2Byte };
        let started = Instant::now();
        // SAFETY: `bytes` has the announced size (or is NULL); the slot holds NULL or a live state.
        let status = unsafe { (self.f.fmi2DeSerializeFMUstate)(c, pointer, bytes.len(), &mut slot) };
        self.common.check(
            format!("fmi2DeSerializeFMUstate({} bytes)", bytes.len()),
            null_instance || null_bytes,
            status,
            started,
        )?;
        if status == fmi2OK && !reuse {
            self.states.push(Held { state: slot, owner: c });
        }
        Ok(())
    }

    fn set_debug_logging(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let mut names: Vec<*const c_char> =
            (0..self.common.rng.below(3)).map(|_| self.common.rng.pick(&CATEGORIES).as_ptr()).collect();
        if self.common.rng.chance(0.05) && !names.is_empty() {
            names[0] = null();
        }
        let unknown = names.iter().any(|n| n.is_null() || *n == c"bogus".as_ptr());
        let (pointer, null_names) = self.common.array(&names);
        let on = if self.common.rng.chance(0.3) { fmi2True } else { fmi2False };
        let started = Instant::now();
        // SAFETY: the array has `names.len()` elements (or is NULL).
        let status = unsafe { (self.f.fmi2SetDebugLogging)(c, on, names.len(), pointer) };
        self.common.check("fmi2SetDebugLogging".into(), null_instance || unknown || null_names, status, started)
    }

    fn status(&mut self) -> Result<(), String> {
        let (c, null_instance) = self.component();
        let kind =
            self.common.rng.pick(&[fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated, 9]);
        let null_value = self.common.rng.chance(0.1);
        let (mut real, mut boolean) = (0.0, 0);
        let started = Instant::now();
        let real_asked = self.common.rng.chance(0.5);
        // SAFETY: NULL or a live instance; the value pointer is NULL or valid.
        let status = unsafe {
            if real_asked {
                (self.f.fmi2GetRealStatus)(c, kind, if null_value { null_mut() } else { &mut real })
            } else {
                (self.f.fmi2GetBooleanStatus)(c, kind, if null_value { null_mut() } else { &mut boolean })
            }
        };
        let wrong_kind = if real_asked { kind != fmi2LastSuccessfulTime } else { kind != fmi2Terminated };
        self.common.check(
            format!("fmi2Get{}Status({kind})", if real_asked { "Real" } else { "Boolean" }),
            null_instance || null_value || wrong_kind,
            status,
            started,
        )
    }

    /// Functions these Co-Simulation FMUs do not support: always refused.
    fn unsupported(&mut self) -> Result<(), String> {
        let (c, _) = self.component();
        let f = self.f;
        let which = self.common.rng.below(16);
        let started = Instant::now();
        // SAFETY: NULL or a live instance; every other pointer is NULL with zero lengths.
        let status = unsafe {
            match which {
                0 => (f.fmi2GetDirectionalDerivative)(c, null(), 0, null(), 0, null(), null_mut()),
                1 => exported(f.fmi2EnterEventMode)(c),
                2 => exported(f.fmi2NewDiscreteStates)(c, null_mut()),
                3 => exported(f.fmi2EnterContinuousTimeMode)(c),
                4 => exported(f.fmi2CompletedIntegratorStep)(c, fmi2True, null_mut(), null_mut()),
                5 => exported(f.fmi2SetTime)(c, 1.0),
                6 => exported(f.fmi2SetContinuousStates)(c, null(), 0),
                7 => exported(f.fmi2GetDerivatives)(c, null_mut(), 0),
                8 => exported(f.fmi2GetEventIndicators)(c, null_mut(), 0),
                9 => exported(f.fmi2GetContinuousStates)(c, null_mut(), 0),
                10 => exported(f.fmi2GetNominalsOfContinuousStates)(c, null_mut(), 0),
                11 => (f.fmi2GetRealOutputDerivatives)(c, null(), 0, null(), null_mut()),
                12 => (f.fmi2CancelStep)(c),
                13 => (f.fmi2GetStatus)(c, fmi2DoStepStatus, null_mut()),
                14 => (f.fmi2GetIntegerStatus)(c, fmi2DoStepStatus, null_mut()),
                _ => (f.fmi2GetStringStatus)(c, fmi2DoStepStatus, null_mut()),
            }
        };
        self.common.check(format!("unsupported function #{which}"), true, status, started)
    }
    /// An FMI 2.0 instance (and state) handed to the library's FMI 3.0 functions: each must
    /// answer fmi3Error without touching them, and `fmi3FreeInstance` must leave the instance
    /// alone (the calls that follow use it).
    fn other_version(&mut self) -> Result<(), String> {
        if self.instances.is_empty() {
            return self.instantiate();
        }
        let c = self.common.rng.pick(&self.instances);
        let g = *self.common.fmu.f3();
        let state: fmi3FMUState = if self.states.is_empty() {
            null_mut()
        } else {
            self.states[self.common.rng.below(self.states.len())].state
        };
        let vr = self.common.fmu.references.real.first().copied().unwrap_or(0);
        let (mut value, mut flags, mut time, mut size) = (0.0, [false; 3], 0.0, 0usize);
        let (mut taken, mut foreign) = (null_mut(), state);
        let which = self.common.rng.below(12);
        let started = Instant::now();
        // SAFETY: an FMI 2.0 instance and state of this library, which its FMI 3.0 functions must
        // recognise as not theirs; every other pointer is valid for its call.
        let status = unsafe {
            match which {
                0 => {
                    let [a, b, e] = &mut flags;
                    (g.fmi3DoStep)(c, 0.0, 0.01, true, a, b, e, &mut time)
                }
                1 => (g.fmi3GetFloat64)(c, &vr, 1, &mut value, 1),
                2 => (g.fmi3SetFloat64)(c, &vr, 1, &value, 1),
                3 => (g.fmi3EnterInitializationMode)(c, false, 0.0, 0.0, false, 0.0),
                4 => (g.fmi3ExitInitializationMode)(c),
                5 => (g.fmi3Terminate)(c),
                6 => (g.fmi3Reset)(c),
                7 => (g.fmi3GetFMUState)(c, &mut taken),
                8 => (g.fmi3SetFMUState)(c, state),
                9 => (g.fmi3FreeFMUState)(c, &mut foreign),
                10 => (g.fmi3SerializedFMUStateSize)(c, state, &mut size),
                _ => {
                    (g.fmi3FreeInstance)(c);
                    fmi3Error
                }
            }
        };
        self.common.figures.cross_version += 1;
        self.common.check(format!("FMI 3.0 function #{which} on an FMI 2.0 instance"), true, status, started)?;
        if status != fmi3Error {
            return Err(format!("an FMI 3.0 function returned {status}, not fmi3Error, for an FMI 2.0 instance"));
        }
        if !taken.is_null() || foreign != state {
            return Err("a refused FMI 3.0 call changed the state pointer it was given".into());
        }
        Ok(())
    }
}

/// A Model Exchange function, which the importer resolves only when present: this project's FMUs
/// export every function of the header.
fn exported<F>(function: Option<F>) -> F {
    function.expect("this project's FMUs export every fmi2 function")
}

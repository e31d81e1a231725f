//! FMI 3.0 call sequences: any `fmi3*` function in any order, arguments good or bad, on up to
//! two instances, each call on an instance checked against the FMI 3.0 state table
//! ([`crate::table`]) besides the checks every call gets ([`Common::check`]); and FMI 2.0 calls on
//! FMI 3.0 instances (the other version's API), which must be refused and leave the instance as
//! it was.

use super::{Common, CATEGORIES, START_TIMES, STRINGS};
use crate::fmi3::{log_message, Functions, Log};
use crate::fmu::Fmu;
use crate::table::{self, Call, Causality, State, States, STRICTLY_AFTER_ERROR};
use fmi3_sys::*;
use std::ffi::{c_char, CStr};
use std::ptr::{null, null_mut};
use std::sync::atomic::AtomicU64;
use std::time::Instant;

/// A live instance and where the state table says it is.
struct Instance {
    c: fmi3Instance,
    /// Its logger's index in `Sequence::logs`.
    log: usize,
    /// The states it may be in (see [`crate::table`]).
    states: States,
    /// The state it is in if fmi3Error puts it in Terminated, as FMI 3.0 §2.3.1 says (counts
    /// the calls these FMUs accept after an error, [`super::Figures::lenient`]).
    strict: States,
    /// False after it restored an FMU state from bytes the fuzzer corrupted and the FMU
    /// accepted: that state's state machine state is unknown, and nothing is checked against
    /// the table until a reset or a restore of a known state.
    known: bool,
    early_return_allowed: bool,
}

/// An FMU state the sequence holds, the instance that created it (which frees it with itself),
/// and the states the table says it holds.
struct Held {
    state: fmi3FMUState,
    owner: fmi3Instance,
    saved: States,
    known: bool,
}

/// The types other than Float64, in the order `get_other` and `set_other` number them: the
/// FMUs' own Int32, Boolean and String, then the three they have none of.
const OTHER_TYPES: [&str; 6] = ["Int32", "Boolean", "String", "Float32", "Int64", "Binary"];

pub(super) struct Sequence<'a> {
    common: Common<'a>,
    f: Functions,
    /// The same library's FMI 2.0 functions, called with FMI 3.0 instances.
    f2: fmu_import::fmi::Functions,
    /// Loggers of every instantiation, kept until the end of the sequence. Boxed: the FMU holds
    /// a pointer to each, which must not move when the vector grows.
    #[allow(clippy::vec_box)]
    logs: Vec<Box<Log>>,
    instances: Vec<Instance>,
    states: Vec<Held>,
    /// The value reference of the independent variable `time`.
    time_vr: Option<u32>,
}

impl<'a> super::Sequence<'a> for Sequence<'a> {
    fn start(fmu: &'a Fmu, seed: u64, progress: &'a AtomicU64) -> Self {
        let kinds = &fmu.variables3.kinds;
        let time_vr = kinds.iter().find(|(_, kind)| kind.causality == Causality::Independent).map(|(vr, _)| *vr);
        Sequence {
            common: Common::new(fmu, super::Api::Fmi3, seed, progress),
            f: *fmu.f3(),
            f2: *fmu.library.functions(),
            logs: Vec::new(),
            instances: Vec::new(),
            states: Vec::new(),
            time_vr,
        }
    }

    fn common(&self) -> &Common<'a> {
        &self.common
    }

    fn common_mut(&mut self) -> &mut Common<'a> {
        &mut self.common
    }

    fn check_version(&self) -> Result<(), String> {
        // SAFETY: takes no argument; returns a static string.
        let version = unsafe { CStr::from_ptr((self.f.fmi3GetVersion)()) };
        if version != c"3.0" {
            return Err(format!("fmi3GetVersion returned {version:?}"));
        }
        Ok(())
    }

    fn begin_as_host(&mut self) -> Result<(), String> {
        self.instantiate()?;
        self.drive_to_step_mode()
    }

    fn one_call(&mut self) -> Result<(), String> {
        match self.common.rng.below(53) {
            0..=2 => self.instantiate(),
            3 => self.free_instance(),
            4..=6 => self.enter_initialization(),
            7..=8 => self.simple(
                "fmi3ExitInitializationMode",
                Call::ExitInitializationMode,
                self.f.fmi3ExitInitializationMode,
            ),
            9 => self.simple("fmi3Terminate", Call::Terminate, self.f.fmi3Terminate),
            10 => self.simple("fmi3Reset", Call::Reset, self.f.fmi3Reset),
            11..=13 => self.get_float64(),
            14..=15 => self.get_other(),
            16..=19 => self.set_float64(),
            20..=21 => self.set_other(),
            22..=29 => self.do_step(),
            30..=31 => self.get_state(),
            32 => self.set_state(),
            33 => self.free_state(),
            34..=35 => self.serialize(),
            36..=38 => self.deserialize(),
            39 => self.set_debug_logging(),
            40..=41 => self.unsupported(),
            42..=43 => self.other_version(),
            _ => self.drive_to_step_mode(),
        }
    }

    fn finish(&mut self) {
        let free_states = self.common.rng.chance(0.6);
        for held in std::mem::take(&mut self.states) {
            if free_states {
                let mut state = held.state;
                // SAFETY: a live instance and a live state it created.
                unsafe { (self.f.fmi3FreeFMUState)(held.owner, &mut state) };
            }
        }
        for instance in std::mem::take(&mut self.instances) {
            // SAFETY: a live instance, freed once.
            unsafe { (self.f.fmi3FreeInstance)(instance.c) };
        }
    }

    fn check_logs(&self) -> Result<(), String> {
        match self.logs.iter().find_map(|log| log.fatal()) {
            Some(message) => Err(format!("fatal message logged: {message}")),
            None => Ok(()),
        }
    }
}

impl Sequence<'_> {
    /// A live instance and its index, or (sometimes, or if there is none) NULL and `None`.
    fn instance(&mut self) -> (fmi3Instance, Option<usize>) {
        if self.instances.is_empty() || self.common.rng.chance(0.05) {
            (null_mut(), None)
        } else {
            let i = self.common.rng.below(self.instances.len());
            (self.instances[i].c, Some(i))
        }
    }

    /// The last message instance `i`'s logger received.
    fn last_message(&self, i: Option<usize>) -> String {
        let log = i.map(|i| &self.logs[self.instances[i].log]);
        log.and_then(|log| log.last_message()).unwrap_or_else(|| "(none)".into())
    }

    /// Whether the table allows `call` in every state instance `i` may be in (so that a call
    /// with good arguments has no reason to be refused).
    fn certain(&self, i: Option<usize>, call: Call) -> bool {
        i.is_some_and(|i| self.instances[i].known && self.instances[i].states.within(call.allowed()))
    }

    /// Checks a call on instance `target` (`None`: NULL) as every call ([`Common::check`]; a
    /// NULL instance makes it bad), then against the state table, and follows its transition.
    /// `expected` is set when the arguments are good and the table allows the call in every
    /// state the instance may be in: then it must be accepted.
    #[allow(clippy::too_many_arguments)]
    fn checked(
        &mut self,
        target: Option<usize>,
        call: Call,
        what: String,
        bad: bool,
        expected: bool,
        status: fmi3Status,
        started: Instant,
    ) -> Result<(), String> {
        self.common.check(what, bad || target.is_none(), status, started)?;
        let Some(i) = target else { return Ok(()) };
        let accepted = status == fmi3OK || status == fmi3Warning;
        if expected && !bad && !accepted {
            let states = self.instances[i].states;
            return Err(format!(
                "refused ({status}) although the FMI 3.0 state table allows it in {states}, where the instance is, \
                 and its arguments are good: {}",
                self.last_message(target)
            ));
        }
        let instance = &mut self.instances[i];
        let allowed = call.allowed();
        let from = instance.states.and(allowed);
        if from.is_empty() {
            self.common.figures.forbidden += 1;
        }
        if accepted {
            if from.is_empty() && instance.known {
                return Err(format!(
                    "accepted in {}, but the FMI 3.0 state table allows it only in {allowed}",
                    instance.states
                ));
            }
            let strict_from = instance.strict.and(allowed);
            if strict_from.is_empty() && instance.known {
                self.common.figures.lenient += 1;
            }
            instance.states = call.after(if from.is_empty() { allowed } else { from });
            instance.strict = if strict_from.is_empty() { instance.states } else { call.after(strict_from) };
            if call == Call::Reset {
                instance.known = true;
            }
        } else if status == fmi3Discard {
            if from.is_empty() && instance.known {
                return Err(format!(
                    "fmi3Discard in {}, where the FMI 3.0 state table does not allow the call (§2.2.3: fmi3Error)",
                    instance.states
                ));
            }
        } else {
            instance.states = table::after_error(instance.states);
            instance.strict = STRICTLY_AFTER_ERROR;
        }
        Ok(())
    }

    fn instantiate(&mut self) -> Result<(), String> {
        // One call in three has a bad argument, one at a time; some are of another interface.
        let fault = if self.common.rng.chance(0.3) { 1 + self.common.rng.below(9) } else { 0 };
        let name = match fault {
            1 => c"".as_ptr(),
            2 => c" \t".as_ptr(),
            3 => null(),
            _ => self.common.rng.pick(&[c"fuzz", c"fuzz3"]).as_ptr(),
        };
        let token = match fault {
            4 => c"{00000000-0000-0000-0000-000000000000}".as_ptr(),
            5 => null(),
            // The GUID of the library's FMI 2.0 description, not this one's token.
            6 => self.common.fmu.guid.as_ptr(),
            _ => self.common.fmu.token.as_ptr(),
        };
        let event_mode_used = fault == 7;
        let required = self.common.fmu.variables3.by_type.real.first().copied().unwrap_or(0);
        let n_required = usize::from(fault == 8);
        let resources = self.common.rng.pick(&[null(), c"/nonexistent/resources/".as_ptr(), c"relative/".as_ptr()]);
        let (visible, logging_on, early_return_allowed) =
            (self.common.rng.chance(0.1), self.common.rng.chance(0.2), self.common.rng.chance(0.3));
        let log = Log::new();
        // FMI 3.0 lets a host pass no logger (§2.3.1): a good argument.
        let callback: fmi3LogMessageCallback = if self.common.rng.chance(0.1) { None } else { Some(log_message) };
        let f = self.f;
        let started = Instant::now();
        // SAFETY: every pointer is NULL or valid for the call; the log outlives the instance.
        let c = unsafe {
            match fault {
                9 if self.common.rng.chance(0.5) => (f.fmi3InstantiateModelExchange)(
                    name,
                    token,
                    resources,
                    visible,
                    logging_on,
                    log.environment(),
                    callback,
                ),
                9 => (f.fmi3InstantiateScheduledExecution)(
                    name,
                    token,
                    resources,
                    visible,
                    logging_on,
                    log.environment(),
                    callback,
                    None,
                    None,
                    None,
                ),
                _ => (f.fmi3InstantiateCoSimulation)(
                    name,
                    token,
                    resources,
                    visible,
                    logging_on,
                    event_mode_used,
                    early_return_allowed,
                    if n_required > 0 { &required } else { null() },
                    n_required,
                    log.environment(),
                    callback,
                    None,
                ),
            }
        };
        let status = if c.is_null() { fmi3Error } else { fmi3OK };
        self.logs.push(log);
        let bad = fault != 0;
        let what = if fault == 9 {
            "fmi3Instantiate(other interface)".into()
        } else {
            format!("fmi3InstantiateCoSimulation(fault {fault})")
        };
        let checked = self.common.check(what, bad, status, started);
        if !c.is_null() {
            self.instances.push(Instance {
                c,
                log: self.logs.len() - 1,
                states: States::of(&[State::Instantiated]),
                strict: States::of(&[State::Instantiated]),
                known: true,
                early_return_allowed,
            });
        }
        checked?;
        if !bad && c.is_null() {
            let message = self.logs.last().and_then(|log| log.last_message()).unwrap_or_default();
            return Err(format!("fmi3InstantiateCoSimulation refused good arguments: {message}"));
        }
        Ok(())
    }

    /// What a host does first: an instance (a new one if there is none) through
    /// `fmi3EnterInitializationMode` and `fmi3ExitInitializationMode` into Step Mode, so that
    /// sequences spend most calls where the models compute. The calls are checked as any other.
    fn drive_to_step_mode(&mut self) -> Result<(), String> {
        if self.instances.is_empty() {
            return self.instantiate();
        }
        let i = self.common.rng.below(self.instances.len());
        let c = self.instances[i].c;
        let start = self.common.rng.pick(&[0.0, 0.0, 0.0, 1.0, 1e6]);
        let expected = self.certain(Some(i), Call::EnterInitializationMode);
        let started = Instant::now();
        // SAFETY: a live instance.
        let status = unsafe { (self.f.fmi3EnterInitializationMode)(c, false, 0.0, start, false, 0.0) };
        let what = format!("fmi3EnterInitializationMode(start {start:?})");
        self.checked(Some(i), Call::EnterInitializationMode, what, false, expected, status, started)?;
        let started = Instant::now();
        // SAFETY: a live instance.
        let status = unsafe { (self.f.fmi3ExitInitializationMode)(c) };
        self.checked(
            Some(i),
            Call::ExitInitializationMode,
            "fmi3ExitInitializationMode".into(),
            false,
            false,
            status,
            started,
        )
    }

    fn free_instance(&mut self) -> Result<(), String> {
        let (c, _) = self.instance();
        let started = Instant::now();
        // SAFETY: NULL or a live instance, forgotten below together with the states it frees.
        unsafe { (self.f.fmi3FreeInstance)(c) };
        self.instances.retain(|i| i.c != c);
        self.states.retain(|s| s.owner != c);
        self.common.check("fmi3FreeInstance".into(), false, fmi3OK, started)
    }

    /// A call with no argument but the instance; `fmi3Reset` and `fmi3Terminate` have no reason
    /// to be refused where the table allows them.
    fn simple(
        &mut self,
        name: &str,
        call: Call,
        function: unsafe extern "C" fn(fmi3Instance) -> fmi3Status,
    ) -> Result<(), String> {
        let (c, target) = self.instance();
        let expected = matches!(call, Call::Reset | Call::Terminate) && self.certain(target, call);
        let started = Instant::now();
        // SAFETY: NULL or a live instance.
        let status = unsafe { function(c) };
        self.checked(target, call, name.into(), false, expected, status, started)
    }

    fn enter_initialization(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let rng = &mut self.common.rng;
        let start = rng.pick(&START_TIMES);
        let stop_defined = rng.chance(0.5);
        let stop = rng.pick(&[start + 1.0, start - 1.0, f64::NAN, 1e300, start, f64::INFINITY]);
        let tolerance_defined = rng.chance(0.3);
        let tolerance = rng.pick(&[1e-6, 1e-4, 0.0, -1.0, f64::NAN, f64::INFINITY]);
        let bad = !start.is_finite()
            || (stop_defined && !(stop >= start && stop.is_finite()))
            || (tolerance_defined && !(tolerance > 0.0 && tolerance.is_finite()));
        let expected = self.certain(target, Call::EnterInitializationMode);
        let started = Instant::now();
        // SAFETY: NULL or a live instance.
        let status =
            unsafe { (self.f.fmi3EnterInitializationMode)(c, tolerance_defined, tolerance, start, stop_defined, stop) };
        let what = format!(
            "fmi3EnterInitializationMode(tolerance {tolerance_defined}/{tolerance:?}, start {start:?}, stop {stop_defined}/{stop:?})"
        );
        self.checked(target, Call::EnterInitializationMode, what, bad, expected, status, started)
    }

    /// The current time of instance `i` as `fmi3GetFloat64` of `time` reads it where the table
    /// allows gets (a call checked as any other), else 0.
    fn time(&mut self, i: usize) -> Result<f64, String> {
        let Some(time_vr) = self.time_vr else { return Ok(0.0) };
        if !self.instances[i].states.contains(State::StepMode) {
            return Ok(0.0);
        }
        let mut t = f64::NAN;
        let started = Instant::now();
        // SAFETY: a live instance; one value reference and one value.
        let status = unsafe { (self.f.fmi3GetFloat64)(self.instances[i].c, &time_vr, 1, &mut t, 1) };
        self.checked(Some(i), Call::Get, "fmi3GetFloat64(time)".into(), false, false, status, started)?;
        if status != fmi3OK {
            return Ok(0.0);
        }
        if !t.is_finite() {
            return Err(format!("fmi3GetFloat64 returned time {t} with fmi3OK"));
        }
        Ok(t)
    }

    /// The number of values announced for `n` value references: mostly `n`, sometimes one more or
    /// one less (bad: every variable of these FMUs is a scalar).
    fn n_values(&mut self, n: usize) -> usize {
        if self.common.rng.chance(0.05) {
            if n > 0 && self.common.rng.chance(0.5) {
                n - 1
            } else {
                n + 1
            }
        } else {
            n
        }
    }

    fn get_float64(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let fmu = self.common.fmu;
        let variables = &fmu.variables3;
        let (known, all) = (variables.by_type.real.clone(), variables.by_type.all());
        let (vrs, unknown) = self.common.references(&known, &all);
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let n = vrs.len();
        let n_values = self.n_values(n);
        let mut values = vec![f64::NAN; n.max(n_values)];
        let null_values = self.common.rng.chance(0.05) && n_values > 0;
        let out = if null_values { null_mut() } else { values.as_mut_ptr() };
        let bad = unknown || null_vrs || null_values || n_values != n;
        let started = Instant::now();
        // SAFETY: the arrays have at least the announced lengths (or are NULL).
        let status = unsafe { (self.f.fmi3GetFloat64)(c, vr_ptr, n, out, n_values) };
        self.checked(
            target,
            Call::Get,
            format!("fmi3GetFloat64({vrs:?}, nValues {n_values})"),
            bad,
            false,
            status,
            started,
        )?;
        if status == fmi3OK && values[..n].iter().any(|v| !v.is_finite()) {
            return Err(format!("fmi3GetFloat64 returned {values:?} with fmi3OK"));
        }
        Ok(())
    }

    /// For a get or set of the other types: the type (an index into [`OTHER_TYPES`]), its
    /// value references, and the ones the call names and whether one of them is unknown.
    fn other_references(&mut self) -> (usize, Vec<u32>, Vec<u32>, bool) {
        let variables = &self.common.fmu.variables3;
        let kind = self.common.rng.below(OTHER_TYPES.len());
        let known = match kind {
            0 => variables.by_type.integer.clone(),
            1 => variables.by_type.boolean.clone(),
            2 => variables.by_type.string.clone(),
            _ => Vec::new(),
        };
        let (vrs, unknown) = self.common.references(&known, &variables.by_type.all());
        (kind, known, vrs, unknown)
    }

    /// Gets of the other types: Int32, Boolean and String (the FMUs' variables), Float32, Int64
    /// and Binary (of which they have none: an empty call is good, any value reference unknown).
    fn get_other(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let (kind, _, vrs, unknown) = self.other_references();
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let n = vrs.len();
        let n_values = self.n_values(n);
        let len = n.max(n_values);
        let null_values = self.common.rng.chance(0.05) && n_values > 0;
        let bad = unknown || null_vrs || null_values || n_values != n;
        // Booleans are read back as bytes: 2 marks one the FMU did not write.
        let (mut numbers, mut bytes, mut strings) = (vec![0i64; len], vec![2u8; len], vec![null::<c_char>(); len]);
        let (mut sizes, mut binaries) = (vec![0usize; len], vec![null::<u8>(); len]);
        let f = self.f;
        let out = |p: *mut u8| if null_values { null_mut() } else { p };
        let started = Instant::now();
        // SAFETY: the arrays have at least the announced lengths (or are NULL); an i64 buffer is
        // large enough and aligned for the i32 and f32 values; Booleans are written as bytes.
        let status = unsafe {
            match kind {
                0 => (f.fmi3GetInt32)(c, vr_ptr, n, out(numbers.as_mut_ptr() as *mut u8) as *mut i32, n_values),
                1 => (f.fmi3GetBoolean)(c, vr_ptr, n, out(bytes.as_mut_ptr()) as *mut bool, n_values),
                2 => (f.fmi3GetString)(c, vr_ptr, n, out(strings.as_mut_ptr() as *mut u8) as *mut fmi3String, n_values),
                3 => (f.fmi3GetFloat32)(c, vr_ptr, n, out(numbers.as_mut_ptr() as *mut u8) as *mut f32, n_values),
                4 => (f.fmi3GetInt64)(c, vr_ptr, n, out(numbers.as_mut_ptr() as *mut u8) as *mut i64, n_values),
                _ => (f.fmi3GetBinary)(
                    c,
                    vr_ptr,
                    n,
                    sizes.as_mut_ptr(),
                    out(binaries.as_mut_ptr() as *mut u8) as *mut fmi3Binary,
                    n_values,
                ),
            }
        };
        let name = OTHER_TYPES[kind];
        self.checked(
            target,
            Call::Get,
            format!("fmi3Get{name}({vrs:?}, nValues {n_values})"),
            bad,
            false,
            status,
            started,
        )?;
        if status == fmi3OK && kind == 1 && bytes[..n].iter().any(|b| *b > 1) {
            return Err(format!("fmi3GetBoolean returned the bytes {:?} with fmi3OK", &bytes[..n]));
        }
        if status == fmi3OK && kind == 2 && strings[..n].iter().any(|s| s.is_null()) {
            return Err("fmi3GetString returned a NULL string with fmi3OK".into());
        }
        Ok(())
    }

    /// The table's call for a set of `vrs` of a type whose value references are `known`.
    fn set_call(&self, vrs: &[u32], known: &[u32]) -> Call {
        let kinds = &self.common.fmu.variables3.kinds;
        Call::set(vrs.iter().filter(|vr| known.contains(vr)).filter_map(|vr| kinds.get(vr).copied()))
    }

    fn set_float64(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let fmu = self.common.fmu;
        let variables = &fmu.variables3;
        let (known, all) = (variables.by_type.real.clone(), variables.by_type.all());
        let (vrs, unknown) = self.common.references(&known, &all);
        let n = vrs.len();
        let n_values = self.n_values(n);
        let values: Vec<f64> = (0..n.max(n_values)).map(|_| self.common.real()).collect();
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let (value_ptr, null_values) = self.common.array(&values[..n_values]);
        let bad = unknown || null_vrs || null_values || n_values != n || values[..n].iter().any(|v| !v.is_finite());
        let call = self.set_call(&vrs, &known);
        let started = Instant::now();
        // SAFETY: the arrays have at least the announced lengths (or are NULL).
        let status = unsafe { (self.f.fmi3SetFloat64)(c, vr_ptr, n, value_ptr, n_values) };
        let what = format!("fmi3SetFloat64({vrs:?}, {:?})", &values[..n_values]);
        self.checked(target, call, what, bad, false, status, started)
    }

    /// Sets of the other types, as [`Self::get_other`].
    fn set_other(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let (kind, known, vrs, unknown) = self.other_references();
        let n = vrs.len();
        let n_values = self.n_values(n);
        let len = n.max(n_values);
        let rng = &mut self.common.rng;
        let numbers: Vec<i64> =
            (0..len).map(|_| rng.pick(&[0, 1, 2, 3, 5, -1, 99, i32::MAX, i32::MIN]) as i64).collect();
        let int32s: Vec<i32> = numbers.iter().map(|x| *x as i32).collect();
        let bytes: Vec<u8> = (0..len).map(|_| rng.pick(&[0, 1])).collect();
        let strings: Vec<*const c_char> =
            (0..len).map(|_| if rng.chance(0.05) { null() } else { rng.pick(&STRINGS).as_ptr() }).collect();
        let floats: Vec<f32> = (0..len).map(|_| rng.pick(&[0.0, 1.5, f32::NAN])).collect();
        let sizes: Vec<usize> = (0..len).map(|_| 3).collect();
        let binaries: Vec<*const u8> = (0..len).map(|_| b"abc".as_ptr()).collect();
        let null_string = kind == 2 && strings[..n].iter().any(|s| s.is_null());
        let (vr_ptr, null_vrs) = self.common.array(&vrs);
        let null_values = self.common.rng.chance(0.05) && n_values > 0;
        let bad = unknown || null_vrs || null_values || null_string || n_values != n;
        let call = self.set_call(&vrs, &known);
        let f = self.f;
        let values = |p: *const u8| if null_values { null() } else { p };
        let started = Instant::now();
        // SAFETY: the arrays have at least the announced lengths (or are NULL); strings are
        // NUL-terminated; Booleans are 0 or 1, as C's bool.
        let status = unsafe {
            match kind {
                0 => (f.fmi3SetInt32)(c, vr_ptr, n, values(int32s.as_ptr() as *const u8) as *const i32, n_values),
                1 => (f.fmi3SetBoolean)(c, vr_ptr, n, values(bytes.as_ptr()) as *const bool, n_values),
                2 => (f.fmi3SetString)(
                    c,
                    vr_ptr,
                    n,
                    values(strings.as_ptr() as *const u8) as *const fmi3String,
                    n_values,
                ),
                3 => (f.fmi3SetFloat32)(c, vr_ptr, n, values(floats.as_ptr() as *const u8) as *const f32, n_values),
                4 => (f.fmi3SetInt64)(c, vr_ptr, n, values(numbers.as_ptr() as *const u8) as *const i64, n_values),
                _ => (f.fmi3SetBinary)(
                    c,
                    vr_ptr,
                    n,
                    sizes.as_ptr(),
                    values(binaries.as_ptr() as *const u8) as *const fmi3Binary,
                    n_values,
                ),
            }
        };
        let name = OTHER_TYPES[kind];
        self.checked(target, call, format!("fmi3Set{name}({vrs:?}, nValues {n_values})"), bad, false, status, started)
    }

    fn do_step(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let mut t = match target {
            Some(i) => self.time(i)?,
            None => 0.0,
        };
        if self.common.rng.chance(0.1) {
            t = self.common.rng.pick(&[t + 1e-3, t - 1.0, f64::NAN, 1e300]);
        }
        let h = self.common.step_size();
        // The Boolean outputs are read back as bytes: 2 marks one the FMU did not write.
        let (mut flags, mut last) = ([2u8; 3], f64::NAN);
        let nulls: [bool; 4] = std::array::from_fn(|_| self.common.rng.chance(0.02));
        let flag = |i: usize, p: *mut u8| if nulls[i] { null_mut() } else { p as *mut bool };
        let [event, terminate, early] = &mut flags;
        let (event, terminate, early) = (flag(0, event), flag(1, terminate), flag(2, early));
        let last_ptr = if nulls[3] { null_mut() } else { &mut last as *mut f64 };
        let no_set_prior = self.common.rng.chance(0.5);
        let bad = nulls.iter().any(|n| *n) || !(h > 0.0) || !h.is_finite() || !t.is_finite();
        let started = Instant::now();
        // SAFETY: NULL or a live instance; each output NULL or a live local (Booleans as bytes).
        let status = unsafe { (self.f.fmi3DoStep)(c, t, h, no_set_prior, event, terminate, early, last_ptr) };
        self.common.figures.steps += (status == fmi3OK) as u64;
        self.checked(target, Call::DoStep, format!("fmi3DoStep({t:?}, {h:?})"), bad, false, status, started)?;
        if status != fmi3OK {
            return Ok(());
        }
        if flags.iter().any(|b| *b > 1) {
            return Err(format!("fmi3DoStep returned fmi3OK without writing its Boolean outputs: {flags:?}"));
        }
        let early_return_allowed = target.is_some_and(|i| self.instances[i].early_return_allowed);
        if flags[2] == 1 && !early_return_allowed {
            return Err("fmi3DoStep returned earlyReturn although earlyReturnAllowed was false".into());
        }
        let end = t + h;
        if !last.is_finite() || (flags[2] == 0 && (last - end).abs() > 1e-12 * end.abs().max(1.0)) {
            return Err(format!("fmi3DoStep from {t:?} by {h:?} returned lastSuccessfulTime {last:?} with fmi3OK"));
        }
        Ok(())
    }

    fn get_state(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let reuse = !self.states.is_empty() && self.common.rng.chance(0.3);
        let index = if reuse { Some(self.common.rng.below(self.states.len())) } else { None };
        let mut slot = index.map_or(null_mut(), |h| self.states[h].state);
        let null_slot = self.common.rng.chance(0.05);
        let expected = self.certain(target, Call::Anywhere);
        let started = Instant::now();
        // SAFETY: the slot is NULL, or holds NULL or a live state.
        let status = unsafe { (self.f.fmi3GetFMUState)(c, if null_slot { null_mut() } else { &mut slot }) };
        self.checked(target, Call::Anywhere, "fmi3GetFMUState".into(), null_slot, expected, status, started)?;
        if let Some(i) = target.filter(|_| status == fmi3OK) {
            let (saved, known) = (self.instances[i].states, self.instances[i].known);
            match index {
                Some(h) => (self.states[h].saved, self.states[h].known) = (saved, known),
                None => self.states.push(Held { state: slot, owner: c, saved, known }),
            }
        }
        Ok(())
    }

    /// A held state's index (sometimes, or if there is none, `None`: NULL).
    fn held(&mut self) -> Option<usize> {
        if self.states.is_empty() || self.common.rng.chance(0.05) {
            None
        } else {
            Some(self.common.rng.below(self.states.len()))
        }
    }

    fn set_state(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let held = self.held();
        let (state, saved, known) = held.map_or((null_mut(), States::ALL, false), |h| {
            (self.states[h].state, self.states[h].saved, self.states[h].known)
        });
        let call = Call::SetFmuState { saved };
        let expected = held.is_some() && self.certain(target, call);
        let started = Instant::now();
        // SAFETY: NULL or a live instance and state.
        let status = unsafe { (self.f.fmi3SetFMUState)(c, state) };
        self.checked(target, call, "fmi3SetFMUState".into(), held.is_none(), expected, status, started)?;
        if let Some(i) = target.filter(|_| status == fmi3OK) {
            self.instances[i].known = known;
        }
        Ok(())
    }

    fn free_state(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        if self.states.is_empty() {
            return Ok(());
        }
        let h = self.common.rng.below(self.states.len());
        let mut state = self.states[h].state;
        let expected = self.certain(target, Call::Anywhere);
        let started = Instant::now();
        // SAFETY: NULL or a live instance; a live state of this FMU.
        let status = unsafe { (self.f.fmi3FreeFMUState)(c, &mut state) };
        self.checked(target, Call::Anywhere, "fmi3FreeFMUState".into(), false, expected, status, started)?;
        if status == fmi3OK {
            if !state.is_null() {
                return Err("fmi3FreeFMUState returned fmi3OK without setting the state to NULL".into());
            }
            self.states.swap_remove(h);
        }
        Ok(())
    }

    fn serialize(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let held = self.held();
        let state = held.map_or(null_mut(), |h| self.states[h].state);
        let mut size = 0;
        let started = Instant::now();
        // SAFETY: NULL or a live instance and state.
        let status = unsafe { (self.f.fmi3SerializedFMUStateSize)(c, state, &mut size) };
        let bad = held.is_none();
        self.checked(target, Call::Anywhere, "fmi3SerializedFMUStateSize".into(), bad, false, status, started)?;
        let (Some(i), Some(h)) = (target, held) else { return Ok(()) };
        if status != fmi3OK {
            let message = self.last_message(target);
            self.common.count_unserializable(message);
            return Ok(());
        }
        let mut bytes = vec![0u8; size];
        let short = self.common.rng.chance(0.1) && size > 0;
        let started = Instant::now();
        // SAFETY: `bytes` has `size` bytes; a short size is announced as such.
        let status = unsafe { (self.f.fmi3SerializeFMUState)(c, state, bytes.as_mut_ptr(), size - short as usize) };
        self.checked(target, Call::Anywhere, "fmi3SerializeFMUState".into(), short, false, status, started)?;
        if status != fmi3OK {
            return Ok(());
        }
        // Bytes the FMU serialized must always be accepted back.
        let mut restored = null_mut();
        let expected = self.certain(target, Call::Anywhere);
        let started = Instant::now();
        // SAFETY: a live instance; `bytes` has the announced size.
        let status = unsafe { (self.f.fmi3DeserializeFMUState)(c, bytes.as_ptr(), bytes.len(), &mut restored) };
        self.checked(
            target,
            Call::Anywhere,
            "fmi3DeserializeFMUState(intact)".into(),
            false,
            expected,
            status,
            started,
        )?;
        if status != fmi3OK {
            return Err(format!("bytes the FMU serialized were refused: {}", self.last_message(target)));
        }
        let (saved, known) = (self.states[h].saved, self.states[h].known);
        self.states.push(Held { state: restored, owner: self.instances[i].c, saved, known });
        self.common.keep_image(bytes);
        Ok(())
    }

    fn deserialize(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let bytes = self.common.garbage();
        let null_bytes = self.common.rng.chance(0.05) && !bytes.is_empty();
        let reuse = !self.states.is_empty() && self.common.rng.chance(0.3);
        let index = if reuse { Some(self.common.rng.below(self.states.len())) } else { None };
        let mut slot = index.map_or(null_mut(), |h| self.states[h].state);
        let pointer = if null_bytes { null() } else { bytes.as_ptr() };
        let started = Instant::now();
        // SAFETY: `bytes` has the announced size (or is NULL); the slot holds NULL or a live state.
        let status = unsafe { (self.f.fmi3DeserializeFMUState)(c, pointer, bytes.len(), &mut slot) };
        let what = format!("fmi3DeserializeFMUState({} bytes)", bytes.len());
        self.checked(target, Call::Anywhere, what, null_bytes, false, status, started)?;
        if status == fmi3OK {
            // Garbage the FMU accepted holds some state of its state machine, which one the
            // fuzzer cannot tell.
            match index {
                Some(h) => (self.states[h].saved, self.states[h].known) = (States::ALL, false),
                None => self.states.push(Held { state: slot, owner: c, saved: States::ALL, known: false }),
            }
        }
        Ok(())
    }

    fn set_debug_logging(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let fmu = self.common.fmu;
        let categories = &fmu.variables3.categories;
        let mut names: Vec<*const c_char> = (0..self.common.rng.below(3))
            .map(|_| {
                if self.common.rng.chance(0.8) && !categories.is_empty() {
                    self.common.rng.pick(&categories.iter().map(|c| c.as_ptr()).collect::<Vec<_>>())
                } else {
                    self.common.rng.pick(&CATEGORIES).as_ptr()
                }
            })
            .collect();
        if self.common.rng.chance(0.05) && !names.is_empty() {
            names[0] = null();
        }
        let known = |name: &*const c_char| {
            // SAFETY: NULL or one of the NUL-terminated strings above.
            !name.is_null() && categories.iter().any(|c| c.as_c_str() == unsafe { CStr::from_ptr(*name) })
        };
        let unknown = !names.iter().all(known);
        let (pointer, null_names) = self.common.array(&names);
        let on = self.common.rng.chance(0.3);
        let bad = unknown || null_names;
        let expected = self.certain(target, Call::Anywhere);
        let started = Instant::now();
        // SAFETY: the array has `names.len()` elements (or is NULL).
        let status = unsafe { (self.f.fmi3SetDebugLogging)(c, on, names.len(), pointer) };
        self.checked(target, Call::Anywhere, "fmi3SetDebugLogging".into(), bad, expected, status, started)
    }

    /// Functions these Co-Simulation FMUs without Event Mode, clocks, structural parameters,
    /// derivatives or dependencies never allow: always refused.
    fn unsupported(&mut self) -> Result<(), String> {
        let (c, target) = self.instance();
        let f = self.f;
        let vr = self.common.fmu.variables3.by_type.real.first().copied().unwrap_or(0);
        let which = self.common.rng.below(24);
        let (mut b, mut out, seed, mut n) = ([false; 5], 0.0, 1.0, 0usize);
        let [b0, b1, b2, b3, b4] = &mut b;
        let started = Instant::now();
        // SAFETY: NULL or a live instance; every other pointer is NULL with zero lengths, or a
        // live local of the announced length.
        let status = unsafe {
            match which {
                0 => (f.fmi3EnterEventMode)(c),
                1 => (f.fmi3EnterStepMode)(c),
                2 => (f.fmi3EnterConfigurationMode)(c),
                3 => (f.fmi3ExitConfigurationMode)(c),
                4 => (f.fmi3GetClock)(c, null(), 0, null_mut()),
                5 => (f.fmi3SetClock)(c, null(), 0, null()),
                6 => (f.fmi3GetIntervalDecimal)(c, null(), 0, null_mut(), null_mut()),
                7 => (f.fmi3GetShiftFraction)(c, null(), 0, null_mut(), null_mut()),
                8 => (f.fmi3SetIntervalDecimal)(c, null(), 0, null()),
                9 => (f.fmi3EvaluateDiscreteStates)(c),
                10 => (f.fmi3UpdateDiscreteStates)(c, b0, b1, b2, b3, b4, &mut out),
                11 => (f.fmi3EnterContinuousTimeMode)(c),
                12 => (f.fmi3CompletedIntegratorStep)(c, true, b0, b1),
                13 => (f.fmi3SetTime)(c, 1.0),
                14 => (f.fmi3SetContinuousStates)(c, null(), 0),
                15 => (f.fmi3GetContinuousStateDerivatives)(c, null_mut(), 0),
                16 => (f.fmi3GetEventIndicators)(c, null_mut(), 0),
                17 => (f.fmi3GetNominalsOfContinuousStates)(c, null_mut(), 0),
                18 => (f.fmi3GetNumberOfContinuousStates)(c, &mut n),
                // maxOutputDerivativeOrder is 0.
                19 => (f.fmi3GetOutputDerivatives)(c, &vr, 1, &1, &mut out, 1),
                20 => (f.fmi3GetDirectionalDerivative)(c, &vr, 1, &vr, 1, &seed, 1, &mut out, 1),
                21 => (f.fmi3GetAdjointDerivative)(c, &vr, 1, &vr, 1, &seed, 1, &mut out, 1),
                22 => (f.fmi3GetNumberOfVariableDependencies)(c, vr, &mut n),
                _ => (f.fmi3ActivateModelPartition)(c, 0, 0.0),
            }
        };
        self.checked(target, Call::Never, format!("unsupported fmi3 function #{which}"), true, false, status, started)
    }

    /// An FMI 3.0 instance (and state) handed to the library's FMI 2.0 functions: each must
    /// answer fmi2Error without touching them, and leave the instance in the state it was in
    /// and usable (an FMU state is taken and freed right after, which must succeed), also after
    /// `fmi2FreeInstance`.
    fn other_version(&mut self) -> Result<(), String> {
        if self.instances.is_empty() {
            return self.instantiate();
        }
        let i = self.common.rng.below(self.instances.len());
        let c = self.instances[i].c;
        let g = self.f2;
        let state = self.held().map_or(null_mut(), |h| self.states[h].state);
        let vr = self.common.fmu.variables3.by_type.real.first().copied().unwrap_or(0);
        let (mut value, mut size, mut flag) = (0.0, 0usize, 0);
        let (mut taken, mut foreign) = (null_mut(), state);
        let which = self.common.rng.below(14);
        let started = Instant::now();
        // SAFETY: an FMI 3.0 instance and state of this library, which its FMI 2.0 functions must
        // recognise as not theirs; every other pointer is valid for its call.
        let status = unsafe {
            match which {
                0 => (g.fmi2DoStep)(c, 0.0, 0.01, 1),
                1 => (g.fmi2GetReal)(c, &vr, 1, &mut value),
                2 => (g.fmi2SetReal)(c, &vr, 1, &value),
                3 => (g.fmi2SetupExperiment)(c, 0, 0.0, 0.0, 0, 0.0),
                4 => (g.fmi2EnterInitializationMode)(c),
                5 => (g.fmi2ExitInitializationMode)(c),
                6 => (g.fmi2Terminate)(c),
                7 => (g.fmi2Reset)(c),
                8 => (g.fmi2GetFMUstate)(c, &mut taken),
                9 => (g.fmi2SetFMUstate)(c, state),
                10 => (g.fmi2FreeFMUstate)(c, &mut foreign),
                11 => (g.fmi2SerializedFMUstateSize)(c, state, &mut size),
                12 => (g.fmi2GetBooleanStatus)(c, fmi2_sys::fmi2Terminated, &mut flag),
                _ => {
                    (g.fmi2FreeInstance)(c);
                    fmi2_sys::fmi2Error
                }
            }
        };
        self.common.figures.cross_version += 1;
        self.common.check(format!("FMI 2.0 function #{which} on an FMI 3.0 instance"), true, status, started)?;
        if !taken.is_null() || foreign != state {
            return Err("a refused FMI 2.0 call changed the state pointer it was given".into());
        }
        // Still live and as it was: an FMU state taken and freed in any state.
        let mut probe = null_mut();
        let started = Instant::now();
        // SAFETY: the live instance; a live slot.
        let status = unsafe { (self.f.fmi3GetFMUState)(c, &mut probe) };
        let expected = self.instances[i].known;
        self.checked(Some(i), Call::Anywhere, "fmi3GetFMUState(probe)".into(), false, expected, status, started)?;
        if status == fmi3OK {
            let started = Instant::now();
            // SAFETY: the live instance and the state it just created.
            let status = unsafe { (self.f.fmi3FreeFMUState)(c, &mut probe) };
            self.checked(Some(i), Call::Anywhere, "fmi3FreeFMUState(probe)".into(), false, expected, status, started)?;
        }
        Ok(())
    }
}

//! What a watchdog thread needs to end a process whose FMU hangs or calls `exit()`: the FMU
//! call in progress, and the temporary folders to remove.
//!
//! The calling thread publishes each call with a few relaxed atomic stores (no lock, no clock
//! read), so the cost per call stays a handful of instructions. Another thread (a signal
//! watcher, a step timeout, an `atexit` handler) reads them and removes the folders before it
//! ends the process, since no destructor runs then.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU32, AtomicU64, AtomicU8, Ordering};
use std::sync::Mutex;

/// An FMI function that may not return.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Call {
    Instantiate = 1,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    DoStep,
    Terminate,
    FreeInstance,
}

impl Call {
    const ALL: [Call; 7] = [
        Call::Instantiate,
        Call::SetupExperiment,
        Call::EnterInitializationMode,
        Call::ExitInitializationMode,
        Call::DoStep,
        Call::Terminate,
        Call::FreeInstance,
    ];

    /// The name FMI 3.0 gives the call (its setup is part of entering initialization).
    pub fn fmi3_name(self) -> &'static str {
        match self {
            Call::Instantiate => "fmi3InstantiateCoSimulation",
            Call::SetupExperiment | Call::EnterInitializationMode => "fmi3EnterInitializationMode",
            Call::ExitInitializationMode => "fmi3ExitInitializationMode",
            Call::DoStep => "fmi3DoStep",
            Call::Terminate => "fmi3Terminate",
            Call::FreeInstance => "fmi3FreeInstance",
        }
    }

    /// The `fmi2*` name.
    pub fn name(self) -> &'static str {
        match self {
            Call::Instantiate => "fmi2Instantiate",
            Call::SetupExperiment => "fmi2SetupExperiment",
            Call::EnterInitializationMode => "fmi2EnterInitializationMode",
            Call::ExitInitializationMode => "fmi2ExitInitializationMode",
            Call::DoStep => "fmi2DoStep",
            Call::Terminate => "fmi2Terminate",
            Call::FreeInstance => "fmi2FreeInstance",
        }
    }
}

static SEQUENCE: AtomicU64 = AtomicU64::new(0);
static CALL: AtomicU8 = AtomicU8::new(0);
static INSTANCE: AtomicU32 = AtomicU32::new(0);
static TIME: AtomicU64 = AtomicU64::new(0);
static STEP: AtomicU64 = AtomicU64::new(0);
static NEXT_INSTANCE: AtomicU32 = AtomicU32::new(1);
/// Instance numbers, names and whether each is an FMI 3.0 instance, for the watchdog to name
/// the instance and the call.
static NAMES: Mutex<Vec<(u32, String, bool)>> = Mutex::new(Vec::new());
static TEMP_DIRS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Numbers a new instance `name` for [`enter`] (forgotten by [`forget_instance`]); `fmi3` if its
/// FMU is an FMI 3.0 one, whose calls are named as that standard names them.
pub fn register_instance(name: &str, fmi3: bool) -> u32 {
    let id = NEXT_INSTANCE.fetch_add(1, Ordering::Relaxed);
    NAMES.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push((id, name.to_string(), fmi3));
    id
}

/// Forgets an instance number once the instance is freed.
pub fn forget_instance(id: u32) {
    NAMES.lock().unwrap_or_else(std::sync::PoisonError::into_inner).retain(|(known, _, _)| *known != id);
}

/// Publishes that instance `instance` is entering `call` at `time` (s) over `step` (s; NaN: none).
#[inline]
pub fn enter(instance: u32, call: Call, time: f64, step: f64) {
    INSTANCE.store(instance, Ordering::Relaxed);
    TIME.store(time.to_bits(), Ordering::Relaxed);
    STEP.store(step.to_bits(), Ordering::Relaxed);
    SEQUENCE.fetch_add(1, Ordering::Relaxed);
    CALL.store(call as u8, Ordering::Relaxed);
}

/// Publishes that the call entered last returned.
#[inline]
pub fn leave() {
    CALL.store(0, Ordering::Relaxed);
}

/// Whether an FMU function is running: one relaxed atomic load, so a signal handler may ask.
pub fn in_call() -> bool {
    CALL.load(Ordering::Relaxed) != 0
}

/// An FMU call in progress.
#[derive(Debug, Clone, PartialEq)]
pub struct CurrentCall {
    /// Increases with every call: the same value seen twice is the same call.
    pub sequence: u64,
    pub instance: String,
    /// Whether the instance is an FMI 3.0 one.
    pub fmi3: bool,
    pub call: Call,
    pub time: f64,
    pub step: Option<f64>,
}

impl std::fmt::Display for CurrentCall {
    /// `instance 'h' ... fmi2DoStep(t = 5.0 s, h = 0.01 s)` is written as
    /// `fmi2DoStep(t = 5.0 s, h = 0.01 s)` (`fmi3DoStep(…)` for an FMI 3.0 instance); the
    /// instance is for the caller to place.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = if self.fmi3 { self.call.fmi3_name() } else { self.call.name() };
        // Instantiation has no time yet.
        if self.time.is_nan() {
            return write!(f, "{name}()");
        }
        write!(f, "{name}(t = {:?} s", self.time)?;
        if let Some(step) = self.step {
            write!(f, ", h = {step:?} s")?;
        }
        write!(f, ")")
    }
}

/// The call in progress, if an FMU function is running (read from any thread).
pub fn current() -> Option<CurrentCall> {
    let code = CALL.load(Ordering::Relaxed);
    let call = *Call::ALL.get(usize::from(code).checked_sub(1)?)?;
    let id = INSTANCE.load(Ordering::Relaxed);
    let names = NAMES.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let (instance, fmi3) = names
        .iter()
        .find(|(known, _, _)| *known == id)
        .map_or_else(|| ("?".to_string(), false), |(_, name, fmi3)| (name.clone(), *fmi3));
    let step = f64::from_bits(STEP.load(Ordering::Relaxed));
    Some(CurrentCall {
        sequence: SEQUENCE.load(Ordering::Relaxed),
        instance,
        fmi3,
        call,
        time: f64::from_bits(TIME.load(Ordering::Relaxed)),
        step: (!step.is_nan()).then_some(step),
    })
}

/// Notes a temporary folder to remove if the process must end without destructors.
pub fn register_temp_dir(path: PathBuf) {
    TEMP_DIRS.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(path);
}

/// Forgets a temporary folder that its owner removes itself.
pub fn forget_temp_dir(path: &std::path::Path) {
    TEMP_DIRS.lock().unwrap_or_else(std::sync::PoisonError::into_inner).retain(|known| known != path);
}

/// Removes every temporary folder still noted (the process is about to end without
/// destructors; a loaded library's file may go, the mapping stays).
pub fn remove_temp_dirs() {
    let dirs = std::mem::take(&mut *TEMP_DIRS.lock().unwrap_or_else(std::sync::PoisonError::into_inner));
    for dir in dirs {
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_published_call_is_read_back_with_its_instance_until_it_returns() {
        let id = register_instance("h", false);
        enter(id, Call::DoStep, 5.0, 0.01);
        let call = current().expect("a call in progress");
        assert_eq!((call.instance.as_str(), call.to_string()), ("h", "fmi2DoStep(t = 5.0 s, h = 0.01 s)".to_string()));
        assert!(in_call());
        leave();
        assert_eq!(current(), None);
        assert!(!in_call());
        forget_instance(id);
        // An FMI 3.0 instance's calls are named as FMI 3.0 names them.
        let id = register_instance("h3", true);
        enter(id, Call::Instantiate, f64::NAN, f64::NAN);
        assert_eq!(current().expect("a call").to_string(), "fmi3InstantiateCoSimulation()");
        leave();
        forget_instance(id);
    }
}

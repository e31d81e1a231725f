//! The Co-Simulation state machine as a bit mask per function: FMI 2.0's (FMI 2.0.x, §4.2.4),
//! which FMI 3.0's Co-Simulation without Event Mode (FMI 3.0.2, §4.2.1) follows state for state
//! under other names (Step Mode for Step Complete; no Step Failed, since steps never end early).

use serde::{Deserialize, Serialize};

/// Instance states. `StepCanceled` and pending steps do not occur: steps are synchronous.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum State {
    Instantiated = 1 << 0,
    InitializationMode = 1 << 1,
    StepComplete = 1 << 2,
    StepFailed = 1 << 3,
    Terminated = 1 << 4,
    Error = 1 << 5,
    Fatal = 1 << 6,
}

/// The FMI version an instance was created through: it names the states and entry points in
/// messages, and the instance refuses calls through the other version's API.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standard {
    Fmi2,
    Fmi3,
}

impl State {
    /// The state's name in the standard `standard`.
    pub fn name(self, standard: Standard) -> &'static str {
        match (self, standard) {
            (State::Instantiated, _) => "Instantiated",
            (State::InitializationMode, _) => "InitializationMode",
            (State::StepComplete, Standard::Fmi2) => "StepComplete",
            (State::StepComplete, Standard::Fmi3) => "StepMode",
            (State::StepFailed, _) => "StepFailed",
            (State::Terminated, _) => "Terminated",
            (State::Error, _) => "Error",
            (State::Fatal, _) => "Fatal",
        }
    }

    /// Every state, in the order of the standard's state diagram.
    pub const ALL: [State; 7] = [
        State::Instantiated,
        State::InitializationMode,
        State::StepComplete,
        State::StepFailed,
        State::Terminated,
        State::Error,
        State::Fatal,
    ];
}

/// A set of states in which a function may be called.
#[derive(Debug, Clone, Copy)]
pub struct Mask(u32);

impl Mask {
    /// No state at all (a variable that can never be set).
    pub const NONE: Mask = Mask(0);

    pub const fn of(states: &[State]) -> Mask {
        let mut bits = 0;
        let mut i = 0;
        while i < states.len() {
            bits |= states[i] as u32;
            i += 1;
        }
        Mask(bits)
    }

    #[inline]
    pub fn allows(self, state: State) -> bool {
        self.0 & state as u32 != 0
    }

    /// The allowed states, named as in `standard`, for error messages.
    pub fn describe(self, standard: Standard) -> String {
        let names: Vec<&str> = State::ALL.iter().filter(|s| self.allows(**s)).map(|s| s.name(standard)).collect();
        if names.is_empty() {
            "no state".into()
        } else {
            names.join(", ")
        }
    }
}

use State::*;

/// Every state but `Fatal`.
pub const ANY_BUT_FATAL: Mask =
    Mask::of(&[Instantiated, InitializationMode, StepComplete, StepFailed, Terminated, Error]);
pub const SETUP_EXPERIMENT: Mask = Mask::of(&[Instantiated]);
pub const ENTER_INITIALIZATION: Mask = Mask::of(&[Instantiated]);
pub const EXIT_INITIALIZATION: Mask = Mask::of(&[InitializationMode]);
pub const TERMINATE: Mask = Mask::of(&[StepComplete, StepFailed]);
pub const GET_VALUES: Mask = Mask::of(&[InitializationMode, StepComplete, StepFailed, Terminated, Error]);
/// Parameters with variability fixed, and inputs/tunables before the first step.
pub const SET_BEFORE_STEPPING: Mask = Mask::of(&[Instantiated, InitializationMode]);
/// Inputs and tunable parameters.
pub const SET_INPUTS: Mask = Mask::of(&[Instantiated, InitializationMode, StepComplete]);
pub const DO_STEP: Mask = Mask::of(&[StepComplete]);
pub const STATUS: Mask = Mask::of(&[StepComplete, StepFailed, Terminated]);
/// Every state: used for unsupported functions, which then report why they are unsupported.
pub const ANY: Mask = Mask::of(&[Instantiated, InitializationMode, StepComplete, StepFailed, Terminated, Error, Fatal]);

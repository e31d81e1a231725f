//! The FMI 3.0 state table the fuzzer holds the FMUs' `fmi3*` entry points to, written from the
//! standard (FMI 3.0, §2.2.3 "Status Returned by Functions", §2.3 "State Machine and Semantics"
//! and §4.2 "State Machine for Co-Simulation") for a Co-Simulation FMU without Event Mode,
//! clocks, structural parameters or intermediate update, instantiated with
//! `eventModeUsed = fmi3False`: which calls are allowed in which state, and which state a call
//! leads to. It is independent of the exporter's own masks (`fmu-export`'s `state` module), so
//! that a mask broken there contradicts this table.
//!
//! * Super state *FMU State Setable* (§2.3.1), every state below: `fmi3SetDebugLogging`,
//!   `fmi3Reset` (to *Instantiated*), `fmi3FreeInstance` and the six FMU-state functions.
//! * *Instantiated* (§2.3.2): `fmi3Set{VariableType}` for variables with variability ≠ constant
//!   and initial = exact or approx; `fmi3EnterInitializationMode` (to *Initialization Mode*).
//!   `fmi3Get{VariableType}` is not among its allowed calls.
//! * *Initialization Mode* (§2.3.3): `fmi3Set{VariableType}` for variables with variability ≠
//!   constant and initial = exact, and for inputs; `fmi3Get{VariableType}`;
//!   `fmi3ExitInitializationMode` (to *Step Mode*, since `eventModeUsed` is false).
//! * Super state *Initialized* (§2.3.4): `fmi3Terminate` (to *Terminated*).
//! * *Step Mode* (§4.2.1): `fmi3Set{VariableType}` for inputs and tunable parameters,
//!   `fmi3Get{VariableType}`, `fmi3DoStep` (stays in *Step Mode*).
//! * *Terminated* (§2.3): `fmi3Get{VariableType}`.
//! * Event Mode, clocks, configuration modes and Model Exchange functions are never allowed
//!   (`eventModeUsed` false, `hasEventMode`, `providesDirectionalDerivatives`, … false).
//!
//! A call the table does not allow in the instance's state must return `fmi3Error` (§2.2.3:
//! "When detecting illegal arguments or a function call not allowed in the current state
//! according to the respective state machine, the FMU must return fmi3Error"). A call that
//! returns `fmi3OK` or `fmi3Warning` takes its transition; `fmi3Discard` leaves the state as it
//! was (§2.2.3). After `fmi3Error`, §2.3.1 puts the instance in *Terminated*; the FMUs of this
//! project keep the state they were in when they refuse an argument or a call (the state only
//! moves to their error state, whose allowed calls are *Terminated*'s, when a computation
//! fails). The table therefore tracks a *set* of states an instance may be in: after
//! `fmi3Error` the state it was in or *Terminated*, and a later accepted call narrows the set to
//! the states that allow it. A call is a contradiction when it is accepted although no state of
//! the set allows it. The fuzzer counts separately the calls accepted that the strict reading
//! of §2.3.1 (only *Terminated* after an error) would have refused.

use std::fmt;

/// A state of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    Instantiated,
    InitializationMode,
    StepMode,
    Terminated,
}

impl State {
    pub const ALL: [State; 4] = [State::Instantiated, State::InitializationMode, State::StepMode, State::Terminated];

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of states: where an instance may be, or where a call is allowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct States(u8);

impl States {
    pub const NONE: States = States(0);
    pub const ALL: States = States(0b1111);

    pub const fn of(states: &[State]) -> States {
        let mut bits = 0;
        let mut i = 0;
        while i < states.len() {
            bits |= 1 << states[i] as u8;
            i += 1;
        }
        States(bits)
    }

    pub fn contains(self, state: State) -> bool {
        self.0 & state.bit() != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether every state of `self` is in `other`.
    pub fn within(self, other: States) -> bool {
        self.0 & !other.0 == 0
    }

    pub fn and(self, other: States) -> States {
        States(self.0 & other.0)
    }

    pub fn or(self, other: States) -> States {
        States(self.0 | other.0)
    }
}

impl fmt::Display for States {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<String> = State::ALL.iter().filter(|s| self.contains(**s)).map(|s| format!("{s:?}")).collect();
        if names.is_empty() {
            f.write_str("no state")
        } else {
            write!(f, "{{{}}}", names.join(", "))
        }
    }
}

use State::*;

/// The states in which `fmi3Set{VariableType}` may be called at all (for some variable).
const SET_ANY: States = States::of(&[Instantiated, InitializationMode, StepMode]);
const GET: States = States::of(&[InitializationMode, StepMode, Terminated]);

/// A variable's causality (FMI 3.0 §2.4.7.4), as the model description declares it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    StructuralParameter,
    Input,
    Output,
    Local,
    Independent,
}

/// A variable's variability and `initial` attribute: the same keywords in FMI 2.0 and 3.0, read
/// as the importer reads them.
pub use fmu_import::fmu::{Initial, Variability};

/// What the table needs to know of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Kind {
    pub causality: Causality,
    pub variability: Variability,
    /// As declared; `None` takes the standard's default for the causality.
    pub initial: Option<Initial>,
}

impl Kind {
    /// The variable's `initial`, with the defaults of FMI 3.0 §2.4.7.5 where absent (inputs and
    /// the independent variable have none).
    fn initial(self) -> Option<Initial> {
        self.initial.or(match self.causality {
            Causality::Parameter | Causality::StructuralParameter => Some(Initial::Exact),
            Causality::CalculatedParameter | Causality::Output | Causality::Local => Some(Initial::Calculated),
            Causality::Input | Causality::Independent => None,
        })
    }

    /// The states in which `fmi3Set{VariableType}` may set this variable. Inputs count as
    /// settable in *Instantiated* too: they have no `initial`, and §2.3.2 does not say.
    pub fn settable_in(self) -> States {
        if self.variability == Variability::Constant || self.causality == Causality::Independent {
            return States::NONE;
        }
        let input = self.causality == Causality::Input;
        let initial = self.initial();
        let mut states = States::NONE;
        if input || matches!(initial, Some(Initial::Exact | Initial::Approx)) {
            states = states.or(States::of(&[Instantiated]));
        }
        if input || initial == Some(Initial::Exact) {
            states = states.or(States::of(&[InitializationMode]));
        }
        if input || (self.causality == Causality::Parameter && self.variability == Variability::Tunable) {
            states = states.or(States::of(&[StepMode]));
        }
        states
    }
}

/// A call as the table sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    /// Allowed in every state, no transition: `fmi3SetDebugLogging` and the FMU-state functions
    /// other than `fmi3SetFMUState`.
    Anywhere,
    Reset,
    /// `fmi3SetFMUState` of a state saved in `saved` (the states its instance may have been in).
    SetFmuState {
        saved: States,
    },
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    DoStep,
    /// `fmi3Get{VariableType}`.
    Get,
    /// `fmi3Set{VariableType}` of variables settable in `settable` (the intersection of their
    /// [`Kind::settable_in`]).
    Set {
        settable: States,
    },
    /// A function the interface never allows (Event Mode, clocks, Model Exchange, …).
    Never,
}

impl Call {
    /// `fmi3Set{VariableType}` of variables of these kinds (of none: an empty call).
    pub fn set(kinds: impl IntoIterator<Item = Kind>) -> Call {
        Call::Set { settable: kinds.into_iter().fold(SET_ANY, |states, kind| states.and(kind.settable_in())) }
    }

    /// The states in which the call is allowed.
    pub fn allowed(self) -> States {
        match self {
            Call::Anywhere | Call::Reset | Call::SetFmuState { .. } => States::ALL,
            Call::EnterInitializationMode => States::of(&[Instantiated]),
            Call::ExitInitializationMode => States::of(&[InitializationMode]),
            Call::Terminate | Call::DoStep => States::of(&[StepMode]),
            Call::Get => GET,
            Call::Set { settable } => settable.and(SET_ANY),
            Call::Never => States::NONE,
        }
    }

    /// The states after the call succeeded from one of `from` (states that allow it).
    pub fn after(self, from: States) -> States {
        match self {
            Call::Reset => States::of(&[Instantiated]),
            Call::SetFmuState { saved } => saved,
            Call::EnterInitializationMode => States::of(&[InitializationMode]),
            Call::ExitInitializationMode => States::of(&[StepMode]),
            Call::Terminate => States::of(&[Terminated]),
            Call::Anywhere | Call::DoStep | Call::Get | Call::Set { .. } | Call::Never => from,
        }
    }
}

/// The states an instance that was in one of `from` may be in after a call returned
/// `fmi3Error`: *Terminated* (§2.3.1) or, as these FMUs do for refused arguments and calls, the
/// state it was in.
pub fn after_error(from: States) -> States {
    from.or(States::of(&[Terminated]))
}

/// The state §2.3.1 puts an instance in after `fmi3Error`.
pub const STRICTLY_AFTER_ERROR: States = States::of(&[Terminated]);

#[cfg(test)]
mod tests {
    use super::*;

    fn kind(causality: Causality, variability: Variability, initial: Option<Initial>) -> Kind {
        Kind { causality, variability, initial }
    }

    #[test]
    fn a_run_goes_through_the_states_of_the_standard() {
        let mut states = States::of(&[Instantiated]);
        for (call, expected) in [
            (Call::EnterInitializationMode, InitializationMode),
            (Call::Get, InitializationMode),
            (Call::ExitInitializationMode, StepMode),
            (Call::DoStep, StepMode),
            (Call::Terminate, Terminated),
            (Call::Get, Terminated),
            (Call::Reset, Instantiated),
        ] {
            let from = states.and(call.allowed());
            assert!(!from.is_empty(), "{call:?} in {states}");
            states = call.after(from);
            assert_eq!(states, States::of(&[expected]), "after {call:?}");
        }
    }

    #[test]
    fn calls_outside_their_states_are_not_allowed() {
        let instantiated = States::of(&[Instantiated]);
        for call in [Call::DoStep, Call::Get, Call::Terminate, Call::ExitInitializationMode, Call::Never] {
            assert!(instantiated.and(call.allowed()).is_empty(), "{call:?}");
        }
        let terminated = States::of(&[Terminated]);
        for call in [Call::DoStep, Call::EnterInitializationMode, Call::Terminate, Call::set([])] {
            assert!(terminated.and(call.allowed()).is_empty(), "{call:?}");
        }
        assert!(States::ALL.and(Call::Never.allowed()).is_empty());
        for call in [Call::Reset, Call::Anywhere, Call::SetFmuState { saved: terminated }] {
            assert!(States::ALL.within(call.allowed()), "{call:?}");
        }
    }

    #[test]
    fn after_an_error_the_instance_may_be_terminated_and_an_accepted_call_tells_where_it_was() {
        let states = after_error(States::of(&[StepMode]));
        assert_eq!(states, States::of(&[StepMode, Terminated]));
        let from = states.and(Call::DoStep.allowed());
        assert_eq!(Call::DoStep.after(from), States::of(&[StepMode]));
        assert!(!states.within(Call::Terminate.allowed()), "Terminate is not certain to be allowed");
        assert!(states.within(Call::Reset.allowed()));
    }

    #[test]
    fn variables_are_settable_where_their_causality_variability_and_initial_say() {
        use Causality as C;
        use Variability as V;
        let fixed = kind(C::Parameter, V::Fixed, Some(Initial::Exact));
        assert_eq!(fixed.settable_in(), States::of(&[Instantiated, InitializationMode]));
        let tunable = kind(C::Parameter, V::Tunable, None);
        assert_eq!(tunable.settable_in(), States::of(&[Instantiated, InitializationMode, StepMode]));
        let input = kind(C::Input, V::Continuous, None);
        assert_eq!(input.settable_in(), States::of(&[Instantiated, InitializationMode, StepMode]));
        for never in [
            kind(C::Output, V::Continuous, Some(Initial::Calculated)),
            kind(C::Output, V::Continuous, None),
            kind(C::Local, V::Discrete, None),
            kind(C::CalculatedParameter, V::Fixed, Some(Initial::Calculated)),
            kind(C::Independent, V::Continuous, None),
            kind(C::Parameter, V::Constant, Some(Initial::Exact)),
        ] {
            assert_eq!(never.settable_in(), States::NONE, "{never:?}");
        }
        let guess = kind(C::Output, V::Continuous, Some(Initial::Approx));
        assert_eq!(guess.settable_in(), States::of(&[Instantiated]));
        // A set is allowed where every one of its variables is settable; an empty one wherever
        // sets are allowed at all.
        assert_eq!(Call::set([fixed, input]).allowed(), States::of(&[Instantiated, InitializationMode]));
        assert_eq!(Call::set([]).allowed(), States::of(&[Instantiated, InitializationMode, StepMode]));
        assert_eq!(Call::set([tunable, guess]).allowed(), States::of(&[Instantiated]));
    }

    #[test]
    fn state_sets_print_their_states() {
        assert_eq!(States::of(&[StepMode, Terminated]).to_string(), "{StepMode, Terminated}");
        assert_eq!(States::NONE.to_string(), "no state");
    }
}

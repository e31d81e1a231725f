//! The macros that write one FMI 3.0 entry point a line in [`crate::export_fmu!`]: the ones
//! that only refuse (Model Exchange and Scheduled Execution, Event Mode, clocks, derivatives,
//! the value types these FMUs have no variables of) and the getters and setters of the value
//! types they have.
//!
//! Each expands to a `#[no_mangle] extern "C"` function with the C signature of
//! `fmi3FunctionTypes.h`: the FMU's own parameters come first, the ones the function never reads
//! are given by their types alone (`_` patterns). The body forwards to [`crate::fmi3::api`],
//! which holds the panic barrier, the state check and the message; the function's own name is
//! the name in that message. `export_fmu!` checks every one against its `fmi3…TYPE`.
//!
//! They expand inside `export_fmu!`'s FMI 3.0 module, where `M` is the model and the names of
//! `fmi3-sys` are in scope.

/// A function the FMU refuses with `fmi3Error` in any state it may be called in, for the reason
/// `$why` (a constant of [`crate::fmi3::api`]); `$arg` are the types after `instance`.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_unsupported {
    ($name:ident($($arg:ty),*) $why:ident) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: fmi3Instance, $(_: $arg),*) -> fmi3Status {
            // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
            unsafe { $crate::fmi3::api::unsupported::<M>(instance, stringify!($name), $crate::fmi3::api::$why) }
        }
    };
}

/// The getter `$get` and setter `$set` of a value type the FMU has no variables of
/// (`$type_name`): an unknown value reference unless the call names none. `$element` are the
/// element types of the arrays between `nValueReferences` and `nValues` (the values, and the
/// sizes of Binary values), written by the getter (allowed in `GET_VALUES` of
/// [`crate::state`]) and read by the setter (allowed in `SET_INPUTS`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_no_variables {
    ($get:ident, $set:ident($($element:ty),+) $type_name:literal) => {
        $crate::__fmi3_no_variables!(@one $get($(*mut $element),+) GET_VALUES $type_name);
        $crate::__fmi3_no_variables!(@one $set($(*const $element),+) SET_INPUTS $type_name);
    };
    (@one $name:ident($($values:ty),+) $mask:ident $type_name:literal) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            $(_: $values,)+
            nValues: usize,
        ) -> fmi3Status {
            // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
            unsafe {
                $crate::fmi3::api::no_variables_of_type::<M>(
                    instance,
                    stringify!($name),
                    $crate::state::$mask,
                    $type_name,
                    valueReferences,
                    nValueReferences,
                    nValues,
                )
            }
        }
    };
}

/// An instantiation of an interface type the FMU does not provide: NULL, with a message to the
/// host's logger. `$extra` are the types after `logMessage` (Scheduled Execution's callbacks).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_no_interface {
    ($name:ident($($extra:ty),*)) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instanceName: fmi3String,
            _: fmi3String,
            _: fmi3String,
            _: fmi3Boolean,
            _: fmi3Boolean,
            instanceEnvironment: fmi3InstanceEnvironment,
            logMessage: fmi3LogMessageCallback,
            $(_: $extra),*
        ) -> fmi3Instance {
            // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
            unsafe {
                $crate::fmi3::api::refuse_interface::<M>(stringify!($name), instanceName, instanceEnvironment, logMessage)
            }
        }
    };
}

/// The getter `$get` and setter `$set` of a value type the FMU has variables of, forwarded to
/// `api::get_values` and `api::set_values` for the value type `$kind` (a path in this crate: a
/// [`crate::calls::ValueArrays`] type); `$element` is the element type of the values array.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_values {
    ($get:ident, $set:ident($element:ty) $($kind:ident)::+) => {
        $crate::__fmi3_values!(@one $get(*mut $element) get_values $($kind)::+);
        $crate::__fmi3_values!(@one $set(*const $element) set_values $($kind)::+);
    };
    (@one $name:ident($values:ty) $api:ident $($kind:ident)::+) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: $values,
            nValues: usize,
        ) -> fmi3Status {
            // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
            unsafe {
                $crate::fmi3::api::$api::<M, $crate::$($kind)::+>(
                    instance,
                    stringify!($name),
                    valueReferences,
                    nValueReferences,
                    values,
                    nValues,
                )
            }
        }
    };
}

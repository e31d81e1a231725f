//! The FMI 3.0 functions the adapter calls ([`Functions`]), resolved from an FMI 3.0 library.

use std::path::Path;

use crate::fmi::library::{symbol, LibraryError};
use fmi3_sys as f3;

/// Declares [`Functions`] and [`Functions::resolve`] from one list of names and their
/// `fmi3…TYPE`: the required ones as plain pointers, the optional ones as `Option`s.
macro_rules! declare_functions {
    (
        required: $($required:ident: $required_type:ident),* ;
        optional: $($optional:ident: $optional_type:ident),* $(,)?
    ) => {
        /// The FMI 3.0 functions the adapter calls. Required ones are plain pointers; the other
        /// value types and the FMU-state functions are optional (an FMU without such variables,
        /// or one that cannot save its state, need not export them).
        #[allow(non_snake_case)]
        #[derive(Clone, Copy)]
        pub struct Functions {
            $(pub $required: f3::$required_type,)*
            $(pub $optional: Option<f3::$optional_type>,)*
        }

        impl Functions {
            /// Resolves the functions from `library`; reports every missing required one at once.
            #[allow(non_snake_case)]
            pub(in crate::fmi) fn resolve(library: &libloading::Library, path: &Path) -> Result<Self, LibraryError> {
                $(
                    let $required: Option<f3::$required_type> =
                        // SAFETY: the symbol is declared with this exact type in fmi3Functions.h.
                        unsafe { symbol(library, concat!(stringify!($required), "\0")) };
                )*
                $(
                    let $optional: Option<f3::$optional_type> =
                        // SAFETY: as above.
                        unsafe { symbol(library, concat!(stringify!($optional), "\0")) };
                )*
                let missing: Vec<&'static str> =
                    [$(($required.is_none(), stringify!($required))),*].into_iter().filter(|m| m.0).map(|m| m.1).collect();
                let resolved = (|| Some(Functions { $($required: $required?,)* $($optional,)* }))();
                resolved.ok_or_else(|| LibraryError::MissingSymbols { path: path.to_path_buf(), symbols: missing })
            }
        }
    };
}

declare_functions! {
    required:
        fmi3InstantiateCoSimulation: fmi3InstantiateCoSimulationTYPE,
        fmi3FreeInstance: fmi3FreeInstanceTYPE,
        fmi3SetDebugLogging: fmi3SetDebugLoggingTYPE,
        fmi3EnterInitializationMode: fmi3EnterInitializationModeTYPE,
        fmi3ExitInitializationMode: fmi3ExitInitializationModeTYPE,
        fmi3Terminate: fmi3TerminateTYPE,
        fmi3Reset: fmi3ResetTYPE,
        fmi3GetFloat64: fmi3GetFloat64TYPE,
        fmi3GetInt32: fmi3GetInt32TYPE,
        fmi3GetBoolean: fmi3GetBooleanTYPE,
        fmi3GetString: fmi3GetStringTYPE,
        fmi3SetFloat64: fmi3SetFloat64TYPE,
        fmi3SetInt32: fmi3SetInt32TYPE,
        fmi3SetBoolean: fmi3SetBooleanTYPE,
        fmi3SetString: fmi3SetStringTYPE,
        fmi3DoStep: fmi3DoStepTYPE;
    optional:
        fmi3GetFloat32: fmi3GetFloat32TYPE,
        fmi3GetInt8: fmi3GetInt8TYPE,
        fmi3GetUInt8: fmi3GetUInt8TYPE,
        fmi3GetInt16: fmi3GetInt16TYPE,
        fmi3GetUInt16: fmi3GetUInt16TYPE,
        fmi3GetUInt32: fmi3GetUInt32TYPE,
        fmi3GetInt64: fmi3GetInt64TYPE,
        fmi3GetUInt64: fmi3GetUInt64TYPE,
        fmi3SetFloat32: fmi3SetFloat32TYPE,
        fmi3SetInt8: fmi3SetInt8TYPE,
        fmi3SetUInt8: fmi3SetUInt8TYPE,
        fmi3SetInt16: fmi3SetInt16TYPE,
        fmi3SetUInt16: fmi3SetUInt16TYPE,
        fmi3SetUInt32: fmi3SetUInt32TYPE,
        fmi3SetInt64: fmi3SetInt64TYPE,
        fmi3SetUInt64: fmi3SetUInt64TYPE,
        fmi3GetFMUState: fmi3GetFMUStateTYPE,
        fmi3SetFMUState: fmi3SetFMUStateTYPE,
        fmi3FreeFMUState: fmi3FreeFMUStateTYPE,
        fmi3SerializedFMUStateSize: fmi3SerializedFMUStateSizeTYPE,
        fmi3SerializeFMUState: fmi3SerializeFMUStateTYPE,
        fmi3DeserializeFMUState: fmi3DeserializeFMUStateTYPE,
}

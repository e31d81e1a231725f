//! The `fmi3*` half of [`crate::export_fmu!`]: one `#[no_mangle] extern "C"` function per
//! entry of `fmi3Functions.h`, each forwarding to [`crate::fmi3::api`] and checked against its
//! `fmi3…TYPE` at compile time.

/// Expands the FMI 3.0 C API of `$model` (called by [`crate::export_fmu!`]).
#[doc(hidden)]
#[macro_export]
macro_rules! __export_fmi3 {
    ($model:ty) => {
        mod __fmi3_export {
            #![allow(non_snake_case, clippy::missing_safety_doc, clippy::too_many_arguments)]
            use super::*;
            use std::ffi::c_char;
            use $crate::ffi3::*;
            type M = $model;

            // Only the token is cached, inline (see `description::Guid`).
            static TOKEN: std::sync::OnceLock<$crate::description::Guid> = std::sync::OnceLock::new();

            /// Writes the FMI 3.0 `modelDescription.xml` of this FMU into `buffer` (see
            /// `fmi2rs_model_description`, which it mirrors).
            #[no_mangle]
            pub unsafe extern "C" fn fmi3rs_model_description(buffer: *mut c_char, size: usize) -> usize {
                // SAFETY: the caller's buffer, passed on: NULL or `size` writable bytes.
                unsafe { $crate::fmi3::api::model_description::<M>(buffer, size) }
            }

            #[no_mangle]
            pub extern "C" fn fmi3GetVersion() -> *const c_char {
                $crate::fmi3::api::version()
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetDebugLogging(
                instance: fmi3Instance,
                loggingOn: fmi3Boolean,
                nCategories: usize,
                categories: *const fmi3String,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::set_debug_logging::<M>(instance, loggingOn, nCategories, categories) }
            }
            $crate::__fmi3_no_interface!(fmi3InstantiateModelExchange());
            #[no_mangle]
            pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
                instanceName: fmi3String,
                instantiationToken: fmi3String,
                resourcePath: fmi3String,
                visible: fmi3Boolean,
                loggingOn: fmi3Boolean,
                eventModeUsed: fmi3Boolean,
                earlyReturnAllowed: fmi3Boolean,
                requiredIntermediateVariables: *const fmi3ValueReference,
                nRequiredIntermediateVariables: usize,
                instanceEnvironment: fmi3InstanceEnvironment,
                logMessage: fmi3LogMessageCallback,
                intermediateUpdate: fmi3IntermediateUpdateCallback,
            ) -> fmi3Instance {
                match $crate::fmi3::xml::cached_token::<M>(&TOKEN) {
                    Ok(ours) => {
                        let args = $crate::fmi3::api::CoSimulationArguments {
                            name: instanceName,
                            token: instantiationToken,
                            resource_path: resourcePath,
                            logging_on: loggingOn,
                            event_mode_used: eventModeUsed,
                            early_return_allowed: earlyReturnAllowed,
                            required_intermediate: requiredIntermediateVariables,
                            n_required_intermediate: nRequiredIntermediateVariables,
                            environment: instanceEnvironment,
                            log_message: logMessage,
                        };
                        // SAFETY: the host's strings and callback, passed on unchanged (contract 3 of `calls`).
                        unsafe { $crate::fmi3::api::instantiate_co_simulation::<M>(ours, args) }
                    }
                    Err(_) => {
                        let _ = (visible, intermediateUpdate);
                        std::ptr::null_mut()
                    }
                }
            }
            $crate::__fmi3_no_interface!(fmi3InstantiateScheduledExecution(fmi3ClockUpdateCallback, fmi3LockPreemptionCallback, fmi3UnlockPreemptionCallback));
            #[no_mangle]
            pub unsafe extern "C" fn fmi3FreeInstance(instance: fmi3Instance) {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::free_instance::<M>(instance) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EnterInitializationMode(
                instance: fmi3Instance,
                toleranceDefined: fmi3Boolean,
                tolerance: fmi3Float64,
                startTime: fmi3Float64,
                stopTimeDefined: fmi3Boolean,
                stopTime: fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::enter_initialization_mode::<M>(
                        instance,
                        toleranceDefined,
                        tolerance,
                        startTime,
                        stopTimeDefined,
                        stopTime,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::exit_initialization_mode::<M>(instance) }
            }
            $crate::__fmi3_unsupported!(fmi3EnterEventMode() NO_CLOCKS);
            #[no_mangle]
            pub unsafe extern "C" fn fmi3Terminate(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::terminate::<M>(instance) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3Reset(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::reset::<M>(instance) }
            }
            $crate::__fmi3_no_variables!(fmi3GetFloat32(*mut fmi3Float32) GET_VALUES "Float32");
            $crate::__fmi3_values!(fmi3GetFloat64(*mut fmi3Float64) get_float64);
            $crate::__fmi3_no_variables!(fmi3GetInt8(*mut fmi3Int8) GET_VALUES "Int8");
            $crate::__fmi3_no_variables!(fmi3GetUInt8(*mut fmi3UInt8) GET_VALUES "UInt8");
            $crate::__fmi3_no_variables!(fmi3GetInt16(*mut fmi3Int16) GET_VALUES "Int16");
            $crate::__fmi3_no_variables!(fmi3GetUInt16(*mut fmi3UInt16) GET_VALUES "UInt16");
            $crate::__fmi3_values!(fmi3GetInt32(*mut fmi3Int32) get_int32);
            $crate::__fmi3_no_variables!(fmi3GetUInt32(*mut fmi3UInt32) GET_VALUES "UInt32");
            $crate::__fmi3_no_variables!(fmi3GetInt64(*mut fmi3Int64) GET_VALUES "Int64");
            $crate::__fmi3_no_variables!(fmi3GetUInt64(*mut fmi3UInt64) GET_VALUES "UInt64");
            $crate::__fmi3_values!(fmi3GetBoolean(*mut fmi3Boolean) get_boolean);
            $crate::__fmi3_values!(fmi3GetString(*mut fmi3String) get_string);
            $crate::__fmi3_no_variables!(fmi3GetBinary(*mut usize, *mut fmi3Binary) GET_VALUES "Binary");
            $crate::__fmi3_unsupported!(fmi3GetClock(*const fmi3ValueReference, usize, *mut fmi3Clock) NO_CLOCKS);
            $crate::__fmi3_no_variables!(fmi3SetFloat32(*const fmi3Float32) SET_INPUTS "Float32");
            $crate::__fmi3_values!(fmi3SetFloat64(*const fmi3Float64) set_float64);
            $crate::__fmi3_no_variables!(fmi3SetInt8(*const fmi3Int8) SET_INPUTS "Int8");
            $crate::__fmi3_no_variables!(fmi3SetUInt8(*const fmi3UInt8) SET_INPUTS "UInt8");
            $crate::__fmi3_no_variables!(fmi3SetInt16(*const fmi3Int16) SET_INPUTS "Int16");
            $crate::__fmi3_no_variables!(fmi3SetUInt16(*const fmi3UInt16) SET_INPUTS "UInt16");
            $crate::__fmi3_values!(fmi3SetInt32(*const fmi3Int32) set_int32);
            $crate::__fmi3_no_variables!(fmi3SetUInt32(*const fmi3UInt32) SET_INPUTS "UInt32");
            $crate::__fmi3_no_variables!(fmi3SetInt64(*const fmi3Int64) SET_INPUTS "Int64");
            $crate::__fmi3_no_variables!(fmi3SetUInt64(*const fmi3UInt64) SET_INPUTS "UInt64");
            $crate::__fmi3_values!(fmi3SetBoolean(*const fmi3Boolean) set_boolean);
            $crate::__fmi3_values!(fmi3SetString(*const fmi3String) set_string);
            $crate::__fmi3_no_variables!(fmi3SetBinary(*const usize, *const fmi3Binary) SET_INPUTS "Binary");
            $crate::__fmi3_unsupported!(fmi3SetClock(*const fmi3ValueReference, usize, *const fmi3Clock) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetNumberOfVariableDependencies(fmi3ValueReference, *mut usize) NO_DERIVATIVES);
            $crate::__fmi3_unsupported!(fmi3GetVariableDependencies(fmi3ValueReference, *mut usize, *mut fmi3ValueReference, *mut usize, *mut fmi3DependencyKind, usize) NO_DERIVATIVES);
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetFMUState(
                instance: fmi3Instance,
                FMUState: *mut fmi3FMUState,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::get_fmu_state::<M>(instance, FMUState) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetFMUState(instance: fmi3Instance, FMUState: fmi3FMUState) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::set_fmu_state::<M>(instance, FMUState) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3FreeFMUState(
                instance: fmi3Instance,
                FMUState: *mut fmi3FMUState,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::free_fmu_state::<M>(instance, FMUState) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
                instance: fmi3Instance,
                FMUState: fmi3FMUState,
                size: *mut usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::serialized_fmu_state_size::<M>(instance, FMUState, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SerializeFMUState(
                instance: fmi3Instance,
                FMUState: fmi3FMUState,
                serializedState: *mut fmi3Byte,
                size: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::serialize_fmu_state::<M>(instance, FMUState, serializedState, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3DeserializeFMUState(
                instance: fmi3Instance,
                serializedState: *const fmi3Byte,
                size: usize,
                FMUState: *mut fmi3FMUState,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::deserialize_fmu_state::<M>(instance, serializedState, size, FMUState) }
            }
            $crate::__fmi3_unsupported!(fmi3GetDirectionalDerivative(*const fmi3ValueReference, usize, *const fmi3ValueReference, usize, *const fmi3Float64, usize, *mut fmi3Float64, usize) NO_DERIVATIVES);
            $crate::__fmi3_unsupported!(fmi3GetAdjointDerivative(*const fmi3ValueReference, usize, *const fmi3ValueReference, usize, *const fmi3Float64, usize, *mut fmi3Float64, usize) NO_DERIVATIVES);
            $crate::__fmi3_unsupported!(fmi3EnterConfigurationMode() NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3ExitConfigurationMode() NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetIntervalDecimal(*const fmi3ValueReference, usize, *mut fmi3Float64, *mut fmi3IntervalQualifier) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetIntervalFraction(*const fmi3ValueReference, usize, *mut fmi3UInt64, *mut fmi3UInt64, *mut fmi3IntervalQualifier) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetShiftDecimal(*const fmi3ValueReference, usize, *mut fmi3Float64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetShiftFraction(*const fmi3ValueReference, usize, *mut fmi3UInt64, *mut fmi3UInt64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3SetIntervalDecimal(*const fmi3ValueReference, usize, *const fmi3Float64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3SetIntervalFraction(*const fmi3ValueReference, usize, *const fmi3UInt64, *const fmi3UInt64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3SetShiftDecimal(*const fmi3ValueReference, usize, *const fmi3Float64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3SetShiftFraction(*const fmi3ValueReference, usize, *const fmi3UInt64, *const fmi3UInt64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3EvaluateDiscreteStates() NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3UpdateDiscreteStates(*mut fmi3Boolean, *mut fmi3Boolean, *mut fmi3Boolean, *mut fmi3Boolean, *mut fmi3Boolean, *mut fmi3Float64) NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3EnterContinuousTimeMode() NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3CompletedIntegratorStep(fmi3Boolean, *mut fmi3Boolean, *mut fmi3Boolean) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3SetTime(fmi3Float64) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3SetContinuousStates(*const fmi3Float64, usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetContinuousStateDerivatives(*mut fmi3Float64, usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetEventIndicators(*mut fmi3Float64, usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetContinuousStates(*mut fmi3Float64, usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetNominalsOfContinuousStates(*mut fmi3Float64, usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetNumberOfEventIndicators(*mut usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3GetNumberOfContinuousStates(*mut usize) NOT_MODEL_EXCHANGE);
            $crate::__fmi3_unsupported!(fmi3EnterStepMode() NO_CLOCKS);
            $crate::__fmi3_unsupported!(fmi3GetOutputDerivatives(*const fmi3ValueReference, usize, *const fmi3Int32, *mut fmi3Float64, usize) NO_DERIVATIVES);
            #[no_mangle]
            pub unsafe extern "C" fn fmi3DoStep(
                instance: fmi3Instance,
                currentCommunicationPoint: fmi3Float64,
                communicationStepSize: fmi3Float64,
                _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
                eventHandlingNeeded: *mut fmi3Boolean,
                terminateSimulation: *mut fmi3Boolean,
                earlyReturn: *mut fmi3Boolean,
                lastSuccessfulTime: *mut fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::do_step::<M>(
                        instance,
                        currentCommunicationPoint,
                        communicationStepSize,
                        $crate::fmi3::api::StepOutputs {
                            event_handling_needed: eventHandlingNeeded,
                            terminate_simulation: terminateSimulation,
                            early_return: earlyReturn,
                            last_successful_time: lastSuccessfulTime,
                        },
                    )
                }
            }
            $crate::__fmi3_unsupported!(fmi3ActivateModelPartition(fmi3ValueReference, fmi3Float64) NO_CLOCKS);

            // Every function of fmi3Functions.h is defined above, with its fmi3FunctionTypes.h type.
            $crate::ffi3::fmi3_functions!($crate::__assert_fmi3_signatures);
        }
    };
}

/// Compile-time check used by [`crate::export_fmu!`]: each `name` coerces to the function
/// pointer type `nameTYPE`.
#[doc(hidden)]
#[macro_export]
macro_rules! __assert_fmi3_signatures {
    ($($name:ident : $ty:ident),* $(,)?) => {
        const _: () = { $(let _: $ty = $name;)* };
    };
}

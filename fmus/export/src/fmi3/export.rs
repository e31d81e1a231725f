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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3InstantiateModelExchange(
                instanceName: fmi3String,
                _instantiationToken: fmi3String,
                _resourcePath: fmi3String,
                _visible: fmi3Boolean,
                _loggingOn: fmi3Boolean,
                instanceEnvironment: fmi3InstanceEnvironment,
                logMessage: fmi3LogMessageCallback,
            ) -> fmi3Instance {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::refuse_interface::<M>(
                        "fmi3InstantiateModelExchange",
                        instanceName,
                        instanceEnvironment,
                        logMessage,
                    )
                }
            }
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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
                instanceName: fmi3String,
                _instantiationToken: fmi3String,
                _resourcePath: fmi3String,
                _visible: fmi3Boolean,
                _loggingOn: fmi3Boolean,
                instanceEnvironment: fmi3InstanceEnvironment,
                logMessage: fmi3LogMessageCallback,
                _clockUpdate: fmi3ClockUpdateCallback,
                _lockPreemption: fmi3LockPreemptionCallback,
                _unlockPreemption: fmi3UnlockPreemptionCallback,
            ) -> fmi3Instance {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::refuse_interface::<M>(
                        "fmi3InstantiateScheduledExecution",
                        instanceName,
                        instanceEnvironment,
                        logMessage,
                    )
                }
            }
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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EnterEventMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3EnterEventMode", $crate::fmi3::api::NO_CLOCKS)
                }
            }
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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetFloat32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3Float32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetFloat32",
                        $crate::state::GET_VALUES,
                        "Float32",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetFloat64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *mut fmi3Float64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::get_float64::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetInt8(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3Int8,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetInt8",
                        $crate::state::GET_VALUES,
                        "Int8",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetUInt8(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3UInt8,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetUInt8",
                        $crate::state::GET_VALUES,
                        "UInt8",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetInt16(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3Int16,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetInt16",
                        $crate::state::GET_VALUES,
                        "Int16",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetUInt16(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3UInt16,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetUInt16",
                        $crate::state::GET_VALUES,
                        "UInt16",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetInt32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *mut fmi3Int32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::get_int32::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetUInt32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3UInt32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetUInt32",
                        $crate::state::GET_VALUES,
                        "UInt32",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetInt64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3Int64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetInt64",
                        $crate::state::GET_VALUES,
                        "Int64",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetUInt64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut fmi3UInt64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetUInt64",
                        $crate::state::GET_VALUES,
                        "UInt64",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetBoolean(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *mut fmi3Boolean,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::get_boolean::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetString(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *mut fmi3String,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::get_string::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetBinary(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _valueSizes: *mut usize,
                _values: *mut fmi3Binary,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3GetBinary",
                        $crate::state::GET_VALUES,
                        "Binary",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetClock(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _values: *mut fmi3Clock,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::unsupported::<M>(instance, "fmi3GetClock", $crate::fmi3::api::NO_CLOCKS) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetFloat32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3Float32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetFloat32",
                        $crate::state::SET_INPUTS,
                        "Float32",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetFloat64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *const fmi3Float64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::set_float64::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetInt8(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3Int8,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetInt8",
                        $crate::state::SET_INPUTS,
                        "Int8",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetUInt8(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3UInt8,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetUInt8",
                        $crate::state::SET_INPUTS,
                        "UInt8",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetInt16(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3Int16,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetInt16",
                        $crate::state::SET_INPUTS,
                        "Int16",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetUInt16(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3UInt16,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetUInt16",
                        $crate::state::SET_INPUTS,
                        "UInt16",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetInt32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *const fmi3Int32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::set_int32::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetUInt32(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3UInt32,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetUInt32",
                        $crate::state::SET_INPUTS,
                        "UInt32",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetInt64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3Int64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetInt64",
                        $crate::state::SET_INPUTS,
                        "Int64",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetUInt64(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _values: *const fmi3UInt64,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetUInt64",
                        $crate::state::SET_INPUTS,
                        "UInt64",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetBoolean(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *const fmi3Boolean,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::set_boolean::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetString(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                values: *const fmi3String,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::set_string::<M>(instance, valueReferences, nValueReferences, values, nValues)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetBinary(
                instance: fmi3Instance,
                valueReferences: *const fmi3ValueReference,
                nValueReferences: usize,
                _valueSizes: *const usize,
                _values: *const fmi3Binary,
                nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::no_variables_of_type::<M>(
                        instance,
                        "fmi3SetBinary",
                        $crate::state::SET_INPUTS,
                        "Binary",
                        valueReferences,
                        nValueReferences,
                        nValues,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetClock(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _values: *const fmi3Clock,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe { $crate::fmi3::api::unsupported::<M>(instance, "fmi3SetClock", $crate::fmi3::api::NO_CLOCKS) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
                instance: fmi3Instance,
                _valueReference: fmi3ValueReference,
                _nDependencies: *mut usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetNumberOfVariableDependencies",
                        $crate::fmi3::api::NO_DERIVATIVES,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetVariableDependencies(
                instance: fmi3Instance,
                _dependent: fmi3ValueReference,
                _elementIndicesOfDependent: *mut usize,
                _independents: *mut fmi3ValueReference,
                _elementIndicesOfIndependents: *mut usize,
                _dependencyKinds: *mut fmi3DependencyKind,
                _nDependencies: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetVariableDependencies",
                        $crate::fmi3::api::NO_DERIVATIVES,
                    )
                }
            }
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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
                instance: fmi3Instance,
                _unknowns: *const fmi3ValueReference,
                _nUnknowns: usize,
                _knowns: *const fmi3ValueReference,
                _nKnowns: usize,
                _seed: *const fmi3Float64,
                _nSeed: usize,
                _sensitivity: *mut fmi3Float64,
                _nSensitivity: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetDirectionalDerivative",
                        $crate::fmi3::api::NO_DERIVATIVES,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetAdjointDerivative(
                instance: fmi3Instance,
                _unknowns: *const fmi3ValueReference,
                _nUnknowns: usize,
                _knowns: *const fmi3ValueReference,
                _nKnowns: usize,
                _seed: *const fmi3Float64,
                _nSeed: usize,
                _sensitivity: *mut fmi3Float64,
                _nSensitivity: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetAdjointDerivative",
                        $crate::fmi3::api::NO_DERIVATIVES,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3EnterConfigurationMode",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3ExitConfigurationMode",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetIntervalDecimal(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _intervals: *mut fmi3Float64,
                _qualifiers: *mut fmi3IntervalQualifier,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetIntervalDecimal",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetIntervalFraction(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _counters: *mut fmi3UInt64,
                _resolutions: *mut fmi3UInt64,
                _qualifiers: *mut fmi3IntervalQualifier,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetIntervalFraction",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetShiftDecimal(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _shifts: *mut fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3GetShiftDecimal", $crate::fmi3::api::NO_CLOCKS)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetShiftFraction(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _counters: *mut fmi3UInt64,
                _resolutions: *mut fmi3UInt64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3GetShiftFraction", $crate::fmi3::api::NO_CLOCKS)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetIntervalDecimal(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _intervals: *const fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3SetIntervalDecimal",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetIntervalFraction(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _counters: *const fmi3UInt64,
                _resolutions: *const fmi3UInt64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3SetIntervalFraction",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetShiftDecimal(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _shifts: *const fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3SetShiftDecimal", $crate::fmi3::api::NO_CLOCKS)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetShiftFraction(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _counters: *const fmi3UInt64,
                _resolutions: *const fmi3UInt64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3SetShiftFraction", $crate::fmi3::api::NO_CLOCKS)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3EvaluateDiscreteStates",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
                instance: fmi3Instance,
                _discreteStatesNeedUpdate: *mut fmi3Boolean,
                _terminateSimulation: *mut fmi3Boolean,
                _nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
                _valuesOfContinuousStatesChanged: *mut fmi3Boolean,
                _nextEventTimeDefined: *mut fmi3Boolean,
                _nextEventTime: *mut fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3UpdateDiscreteStates",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3EnterContinuousTimeMode",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
                instance: fmi3Instance,
                _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
                _enterEventMode: *mut fmi3Boolean,
                _terminateSimulation: *mut fmi3Boolean,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3CompletedIntegratorStep",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetTime(instance: fmi3Instance, _time: fmi3Float64) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3SetTime", $crate::fmi3::api::NOT_MODEL_EXCHANGE)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetContinuousStates(
                instance: fmi3Instance,
                _continuousStates: *const fmi3Float64,
                _nContinuousStates: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3SetContinuousStates",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
                instance: fmi3Instance,
                _derivatives: *mut fmi3Float64,
                _nContinuousStates: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetContinuousStateDerivatives",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetEventIndicators(
                instance: fmi3Instance,
                _eventIndicators: *mut fmi3Float64,
                _nEventIndicators: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetEventIndicators",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetContinuousStates(
                instance: fmi3Instance,
                _continuousStates: *mut fmi3Float64,
                _nContinuousStates: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetContinuousStates",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
                instance: fmi3Instance,
                _nominals: *mut fmi3Float64,
                _nContinuousStates: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetNominalsOfContinuousStates",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(
                instance: fmi3Instance,
                _nEventIndicators: *mut usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetNumberOfEventIndicators",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(
                instance: fmi3Instance,
                _nContinuousStates: *mut usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetNumberOfContinuousStates",
                        $crate::fmi3::api::NOT_MODEL_EXCHANGE,
                    )
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3EnterStepMode(instance: fmi3Instance) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(instance, "fmi3EnterStepMode", $crate::fmi3::api::NO_CLOCKS)
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetOutputDerivatives(
                instance: fmi3Instance,
                _valueReferences: *const fmi3ValueReference,
                _nValueReferences: usize,
                _orders: *const fmi3Int32,
                _values: *mut fmi3Float64,
                _nValues: usize,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3GetOutputDerivatives",
                        $crate::fmi3::api::NO_DERIVATIVES,
                    )
                }
            }
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
            #[no_mangle]
            pub unsafe extern "C" fn fmi3ActivateModelPartition(
                instance: fmi3Instance,
                _clockReference: fmi3ValueReference,
                _activationTime: fmi3Float64,
            ) -> fmi3Status {
                // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
                unsafe {
                    $crate::fmi3::api::unsupported::<M>(
                        instance,
                        "fmi3ActivateModelPartition",
                        $crate::fmi3::api::NO_CLOCKS,
                    )
                }
            }

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

//! The `fmi3*` half of [`crate::export_fmu!`]: one `#[no_mangle] extern "C"` function per
//! entry of `fmi3Functions.h`, each forwarding to [`crate::fmi3::api`] and checked against its
//! `fmi3…TYPE` at compile time.

/// The FMI 3.0 C API of the model `M` but its model description entry point, expanded by
/// [`crate::export_fmu!`] inside the module [`crate::__export_module!`] opens for FMI 3.0.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_entries {
    () => {
        $crate::__static_string!(fmi3GetVersion => c"3.0");
        $crate::__forward!(fmi3SetDebugLogging(instance: fmi3Instance, loggingOn: fmi3Boolean, nCategories: usize, categories: *const fmi3String) -> fmi3Status => fmi3::set_debug_logging);
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
            match $crate::description::cached::<$crate::fmi3::xml::Fmi3, M>(&TOKEN) {
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
        $crate::__forward!(fmi3FreeInstance(instance: fmi3Instance) => fmi3::free_instance);
        $crate::__forward!(fmi3EnterInitializationMode(instance: fmi3Instance, toleranceDefined: fmi3Boolean, tolerance: fmi3Float64, startTime: fmi3Float64, stopTimeDefined: fmi3Boolean, stopTime: fmi3Float64) -> fmi3Status => fmi3::enter_initialization_mode);
        $crate::__forward!(fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status => fmi3::exit_initialization_mode);
        $crate::__fmi3_unsupported!(fmi3EnterEventMode() NO_CLOCKS);
        $crate::__forward!(fmi3Terminate(instance: fmi3Instance) -> fmi3Status => fmi3::terminate);
        $crate::__forward!(fmi3Reset(instance: fmi3Instance) -> fmi3Status => fmi3::reset);
        $crate::__fmi3_no_variables!(fmi3GetFloat32, fmi3SetFloat32(fmi3Float32) "Float32");
        $crate::__fmi3_values!(fmi3GetFloat64, fmi3SetFloat64(fmi3Float64) calls::Real);
        $crate::__fmi3_no_variables!(fmi3GetInt8, fmi3SetInt8(fmi3Int8) "Int8");
        $crate::__fmi3_no_variables!(fmi3GetUInt8, fmi3SetUInt8(fmi3UInt8) "UInt8");
        $crate::__fmi3_no_variables!(fmi3GetInt16, fmi3SetInt16(fmi3Int16) "Int16");
        $crate::__fmi3_no_variables!(fmi3GetUInt16, fmi3SetUInt16(fmi3UInt16) "UInt16");
        $crate::__fmi3_values!(fmi3GetInt32, fmi3SetInt32(fmi3Int32) calls::Integer);
        $crate::__fmi3_no_variables!(fmi3GetUInt32, fmi3SetUInt32(fmi3UInt32) "UInt32");
        $crate::__fmi3_no_variables!(fmi3GetInt64, fmi3SetInt64(fmi3Int64) "Int64");
        $crate::__fmi3_no_variables!(fmi3GetUInt64, fmi3SetUInt64(fmi3UInt64) "UInt64");
        $crate::__fmi3_values!(fmi3GetBoolean, fmi3SetBoolean(fmi3Boolean) fmi3::api::Boolean);
        $crate::__fmi3_values!(fmi3GetString, fmi3SetString(fmi3String) calls::Text);
        $crate::__fmi3_no_variables!(fmi3GetBinary, fmi3SetBinary(usize, fmi3Binary) "Binary");
        $crate::__fmi3_unsupported!(fmi3GetClock(*const fmi3ValueReference, usize, *mut fmi3Clock) NO_CLOCKS);
        $crate::__fmi3_unsupported!(fmi3SetClock(*const fmi3ValueReference, usize, *const fmi3Clock) NO_CLOCKS);
        $crate::__fmi3_unsupported!(fmi3GetNumberOfVariableDependencies(fmi3ValueReference, *mut usize) NO_DERIVATIVES);
        $crate::__fmi3_unsupported!(fmi3GetVariableDependencies(fmi3ValueReference, *mut usize, *mut fmi3ValueReference, *mut usize, *mut fmi3DependencyKind, usize) NO_DERIVATIVES);
        $crate::__fmu_state_entries!(
            fmi3(fmi3Instance, fmi3FMUState, fmi3Byte, fmi3Status):
            fmi3GetFMUState, fmi3SetFMUState, fmi3FreeFMUState,
            fmi3SerializedFMUStateSize, fmi3SerializeFMUState, fmi3DeserializeFMUState
        );
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
    };
}

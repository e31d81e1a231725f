/* A small FMI 3.0 Co-Simulation FMU in C, the FMI 3.0 counterpart of stair.c: `counter` counts the
 * half seconds reached, `level` = counter * `height`, `reached` says whether `end_time` (s) is
 * reached and `phase` is "climbing" until then and the `ending` after.
 *
 * The step that reaches `end_time` ends the run the FMI 3.0 way when the parameter `terminate` is
 * true, as the String parameter `ending` says:
 * - "terminate": the step is computed whole and fmi3DoStep returns fmi3OK with
 *   terminateSimulation = true (FMI 3.0 has no fmi3GetBooleanStatus: the request comes with the
 *   step);
 * - "early return": the step is computed up to `end_time` only and fmi3DoStep returns fmi3OK with
 *   earlyReturn = true and lastSuccessfulTime = end_time, whether or not the importer allowed an
 *   early return (a misbehaving FMU, for the importer's checks);
 * - "event": the step is computed whole and fmi3DoStep returns fmi3OK with
 *   eventHandlingNeeded = true, although the FMU has no Event Mode (misbehaving too).
 * With `terminate` false, that step is computed up to `end_time` and fmi3DoStep returns
 * fmi3Discard, which an importer must treat as an error; FMI 3.0 leaves the output arguments
 * undefined after fmi3Discard, and this FMU sets terminateSimulation as for the "terminate" ending
 * all the same (an importer that reads it would end the run cleanly). After that step the FMU
 * counts on.
 *
 * It exports every function of fmi3Functions.h (an importer may resolve them all, as FMPy does);
 * those of Model Exchange, Scheduled Execution, Event Mode, Configuration Mode, clocks, FMU states,
 * dependencies, derivatives and the types it has no variables of return fmi3Error with a message
 * (the typed getters and setters return fmi3OK when asked for no variable); most come from
 * fmi3_stubs.h, shared with types3.c. Built by tests/test_third_party_fmi3.py against FMPy's FMI
 * 3.0 headers. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmi3_stubs.h"

/* Value references (see stair3.xml). */
enum { VR_TIME, VR_LEVEL, VR_COUNTER, VR_HEIGHT, VR_END_TIME, VR_TERMINATE, VR_ENDING, VR_REACHED, VR_PHASE };

#define PERIOD 0.5
#define TOKEN "{3b0e6f52-9d4a-4c8e-b1f7-5a2c0d9e7f31}"

typedef enum { ENDING_TERMINATE, ENDING_EARLY_RETURN, ENDING_EVENT } Ending;

static const char *const ENDINGS[] = {"terminate", "early return", "event"};

typedef struct {
    Fmi3Callbacks callbacks; /* first: an fmi3Instance points to them */
    fmi3Float64 time, height, end_time;
    fmi3Int32 counter;
    fmi3Boolean terminate, reached;
    Ending ending;
} Stair;

/* Half seconds reached at `time` (1e-9 s early counts as reached). */
static fmi3Int32 counter_at(fmi3Float64 time) { return (fmi3Int32)floor(time / PERIOD + 1e-9); }

static void set_defaults(Stair *s) {
    s->time = 0;
    s->height = 0.5;
    s->end_time = 2.5;
    s->counter = 0;
    s->terminate = true;
    s->reached = false;
    s->ending = ENDING_TERMINATE;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate) {
    (void)instanceName, (void)resourcePath, (void)visible, (void)loggingOn, (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables, (void)intermediateUpdate;
    Fmi3Callbacks refused = {instanceEnvironment, logMessage};
    if (!instantiationToken || strcmp(instantiationToken, TOKEN) != 0) {
        log_message(&refused, fmi3Error, "logStatusError", "wrong instantiationToken");
        return NULL;
    }
    if (eventModeUsed || nRequiredIntermediateVariables > 0) {
        log_message(&refused, fmi3Error, "logStatusError", "this FMU has no Event Mode and no intermediate variables");
        return NULL;
    }
    Stair *s = calloc(1, sizeof(Stair));
    if (!s) return NULL;
    s->callbacks = refused;
    set_defaults(s);
    return s;
}

void fmi3FreeInstance(fmi3Instance instance) { free(instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    (void)toleranceDefined, (void)tolerance, (void)stopTimeDefined, (void)stopTime;
    ((Stair *)instance)->time = startTime;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
    Stair *s = instance;
    s->counter = counter_at(s->time);
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance) {
    (void)instance;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance) {
    set_defaults(instance);
    return fmi3OK;
}

/* Scalars only: one value per value reference. */
#define CHECK_SCALARS(name)                                                                                        \
    if (nValues != nValueReferences) {                                                                             \
        log_message(instance, fmi3Error, "logStatusError", name ": nValues differs from nValueReferences");      \
        return fmi3Error;                                                                                          \
    }

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Float64 values[], size_t nValues) {
    Stair *s = instance;
    CHECK_SCALARS("fmi3GetFloat64")
    for (size_t i = 0; i < nValueReferences; i++) {
        switch (valueReferences[i]) {
        case VR_TIME: values[i] = s->time; break;
        case VR_LEVEL: values[i] = s->counter * s->height; break;
        case VR_HEIGHT: values[i] = s->height; break;
        case VR_END_TIME: values[i] = s->end_time; break;
        default: return unsupported(instance, "fmi3GetFloat64 of this value reference");
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          const fmi3Float64 values[], size_t nValues) {
    Stair *s = instance;
    CHECK_SCALARS("fmi3SetFloat64")
    for (size_t i = 0; i < nValueReferences; i++) {
        switch (valueReferences[i]) {
        case VR_HEIGHT: s->height = values[i]; break;
        case VR_END_TIME: s->end_time = values[i]; break;
        default: return unsupported(instance, "fmi3SetFloat64 of this value reference");
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                        fmi3Int32 values[], size_t nValues) {
    CHECK_SCALARS("fmi3GetInt32")
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_COUNTER) return unsupported(instance, "fmi3GetInt32 of this value reference");
        values[i] = ((Stair *)instance)->counter;
    }
    return fmi3OK;
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                        const fmi3Int32 values[], size_t nValues) {
    (void)valueReferences, (void)values;
    CHECK_SCALARS("fmi3SetInt32")
    return nValueReferences == 0 ? fmi3OK : unsupported(instance, "fmi3SetInt32 of this value reference");
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Boolean values[], size_t nValues) {
    Stair *s = instance;
    CHECK_SCALARS("fmi3GetBoolean")
    for (size_t i = 0; i < nValueReferences; i++) {
        switch (valueReferences[i]) {
        case VR_TERMINATE: values[i] = s->terminate; break;
        case VR_REACHED: values[i] = s->reached; break;
        default: return unsupported(instance, "fmi3GetBoolean of this value reference");
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          const fmi3Boolean values[], size_t nValues) {
    CHECK_SCALARS("fmi3SetBoolean")
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_TERMINATE) return unsupported(instance, "fmi3SetBoolean of this value reference");
        ((Stair *)instance)->terminate = values[i];
    }
    return fmi3OK;
}

fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                         fmi3String values[], size_t nValues) {
    Stair *s = instance;
    CHECK_SCALARS("fmi3GetString")
    for (size_t i = 0; i < nValueReferences; i++) {
        switch (valueReferences[i]) {
        case VR_ENDING: values[i] = ENDINGS[s->ending]; break;
        case VR_PHASE: values[i] = s->reached ? ENDINGS[s->ending] : "climbing"; break;
        default: return unsupported(instance, "fmi3GetString of this value reference");
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                         const fmi3String values[], size_t nValues) {
    CHECK_SCALARS("fmi3SetString")
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_ENDING) return unsupported(instance, "fmi3SetString of this value reference");
        size_t k = 0;
        while (k < sizeof ENDINGS / sizeof ENDINGS[0] && (!values[i] || strcmp(values[i], ENDINGS[k]) != 0)) k++;
        if (k == sizeof ENDINGS / sizeof ENDINGS[0]) {
            log_message(instance, fmi3Error, "logStatusError",
                        "ending must be \"terminate\", \"early return\" or \"event\"");
            return fmi3Error;
        }
        ((Stair *)instance)->ending = (Ending)k;
    }
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn,
                      fmi3Float64 *lastSuccessfulTime) {
    (void)noSetFMUStatePriorToCurrentPoint;
    Stair *s = instance;
    const fmi3Float64 next = currentCommunicationPoint + communicationStepSize;
    fmi3Status status = fmi3OK;
    *eventHandlingNeeded = *terminateSimulation = *earlyReturn = false;
    s->time = next;
    if (!s->reached && s->end_time <= next + 1e-12) {
        /* The step reaches end_time. A step that ends on end_time is computed whole. */
        const fmi3Float64 end = currentCommunicationPoint > s->end_time ? currentCommunicationPoint : s->end_time;
        s->reached = true;
        if (!s->terminate) {
            /* The output arguments are undefined after fmi3Discard: an importer must not read
             * them. This FMU fills them in as for the "terminate" ending all the same. */
            s->time = end;
            status = fmi3Discard;
            *terminateSimulation = s->ending == ENDING_TERMINATE;
            log_message(s, fmi3Discard, "logStatusDiscard", "end_time reached");
        } else if (s->ending == ENDING_TERMINATE) {
            *terminateSimulation = true;
            log_message(s, fmi3OK, "logEvents", "end_time reached: the simulation should end");
        } else if (s->ending == ENDING_EARLY_RETURN) {
            s->time = end;
            *earlyReturn = true;
            log_message(s, fmi3OK, "logEvents", "end_time reached: returning early");
        } else {
            *eventHandlingNeeded = true;
            log_message(s, fmi3OK, "logEvents", "end_time reached: an event");
        }
    }
    s->counter = counter_at(s->time);
    *lastSuccessfulTime = s->time;
    return status;
}

/* The types the FMU has no variables of. */
FMI3_NO_VARIABLES_GET(fmi3GetFloat32, fmi3Float32)
FMI3_NO_VARIABLES_GET(fmi3GetInt8, fmi3Int8)
FMI3_NO_VARIABLES_GET(fmi3GetUInt8, fmi3UInt8)
FMI3_NO_VARIABLES_GET(fmi3GetInt16, fmi3Int16)
FMI3_NO_VARIABLES_GET(fmi3GetUInt16, fmi3UInt16)
FMI3_NO_VARIABLES_GET(fmi3GetUInt32, fmi3UInt32)
FMI3_NO_VARIABLES_GET(fmi3GetInt64, fmi3Int64)
FMI3_NO_VARIABLES_GET(fmi3GetUInt64, fmi3UInt64)
FMI3_NO_VARIABLES_SET(fmi3SetFloat32, fmi3Float32)
FMI3_NO_VARIABLES_SET(fmi3SetInt8, fmi3Int8)
FMI3_NO_VARIABLES_SET(fmi3SetUInt8, fmi3UInt8)
FMI3_NO_VARIABLES_SET(fmi3SetInt16, fmi3Int16)
FMI3_NO_VARIABLES_SET(fmi3SetUInt16, fmi3UInt16)
FMI3_NO_VARIABLES_SET(fmi3SetUInt32, fmi3UInt32)
FMI3_NO_VARIABLES_SET(fmi3SetInt64, fmi3Int64)
FMI3_NO_VARIABLES_SET(fmi3SetUInt64, fmi3UInt64)

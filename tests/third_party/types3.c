/* A small FMI 3.0 Co-Simulation FMU in C with variables of every FMI 3.0 numeric type and arrays
 * (see types3.xml):
 * - `u`, a Float64 input array of 3, integrated over each step into x (x_j += u_j h, u as set
 *   before the step), and held: `m`, a Float64 2x2 output matrix (row-major), is
 *   m = [[x_1 + offsets_1 t, x_2 t], [x_3 - sin t, held_1 held_3 + offsets_2]], with no direct
 *   feedthrough from u (the row recorded after a step does not depend on when the next input is set);
 * - `gain`, a Float32 parameter, and `scaled` = gain * (float)x_1, a Float32 output;
 * - Int8, UInt8, Int16 and UInt16 parameters `k_i8`, `k_u8`, `k_i16`, `k_u16` and outputs, k being
 *   the number of steps taken: y_i8 = k_i8 - k, y_u8 = k_u8 + k, y_i16 = k_i16 k,
 *   y_u16 = k_u16 + 1000 k;
 * - UInt32, Int64 and UInt64 outputs that stay within a 32-bit signed integer for 700 000 steps:
 *   y_u32 = 2 000 000 000 + 1000 k, y_i64 = -2^31 + 1000 k (-2^31 exactly at the start),
 *   y_u64 = 2^31 - 1 - 3 k (2^31 - 1 exactly at the start);
 * - `big`, an Int64 output: k until the time reaches the Float64 parameter `overflow_time`,
 *   3 000 000 000 + k from then on (beyond a 32-bit signed integer);
 * - `mode`, an Enumeration output (idle, rising, falling): 1 + k mod 3;
 * - `offsets`, an Int32 parameter array of 2.
 *
 * Arrays are read and written whole, row-major, one value reference each. Fixed parameters are
 * settable until fmi3ExitInitializationMode, the input always, outputs never. It exports every
 * function of fmi3Functions.h: those of what it does not have (Model Exchange, Scheduled
 * Execution, Event Mode, clocks, FMU states, Boolean, String and Binary variables, ...) come from
 * fmi3_stubs.h and return fmi3Error with a message. Built by tests/test_third_party_fmi3_types.py
 * against FMPy's FMI 3.0 headers. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmi3_stubs.h"

#define TOKEN "{8d7c2e41-5b3a-4f69-a0d1-3e9b7c6f2a58}"

typedef struct {
    Fmi3Callbacks callbacks; /* first: an fmi3Instance points to them */
    int initialized;         /* fmi3ExitInitializationMode was called */
    int64_t steps;           /* k */
    fmi3Float64 x[3], held[3];
    /* The variables, as the table VARIABLES maps value references to them. */
    fmi3Float64 time, u[3], m[4], overflow_time;
    fmi3Float32 gain, scaled;
    fmi3Int8 k_i8, y_i8;
    fmi3UInt8 k_u8, y_u8;
    fmi3Int16 k_i16, y_i16;
    fmi3UInt16 k_u16, y_u16;
    fmi3UInt32 y_u32;
    fmi3Int64 y_i64, big, mode;
    fmi3UInt64 y_u64;
    fmi3Int32 offsets[2];
} Types3;

typedef enum { FLOAT32, FLOAT64, INT8, UINT8, INT16, UINT16, INT32, UINT32, INT64, UINT64 } Type;
static const char *const TYPE_NAMES[] = {"Float32", "Float64", "Int8",   "UInt8", "Int16",
                                         "UInt16",  "Int32",   "UInt32", "Int64", "UInt64"};

typedef enum { CONSTANT, PARAMETER, INPUT } Settable;

typedef struct {
    const char *name;
    Type type;
    size_t offset, count, size; /* where in Types3, how many elements, of how many bytes */
    Settable settable;
} Variable;

#define VARIABLE(name, type, settable) {#name, type, offsetof(Types3, name), 1, sizeof(((Types3 *)0)->name), settable}
#define ARRAY(name, type, settable)                                                                                \
    {#name, type, offsetof(Types3, name), sizeof(((Types3 *)0)->name) / sizeof(((Types3 *)0)->name[0]),             \
     sizeof(((Types3 *)0)->name[0]), settable}

/* By value reference (see types3.xml). */
static const Variable VARIABLES[] = {
    VARIABLE(time, FLOAT64, CONSTANT),
    ARRAY(u, FLOAT64, INPUT),
    ARRAY(m, FLOAT64, CONSTANT),
    VARIABLE(gain, FLOAT32, PARAMETER),
    VARIABLE(scaled, FLOAT32, CONSTANT),
    VARIABLE(k_i8, INT8, PARAMETER),
    VARIABLE(y_i8, INT8, CONSTANT),
    VARIABLE(k_u8, UINT8, PARAMETER),
    VARIABLE(y_u8, UINT8, CONSTANT),
    VARIABLE(k_i16, INT16, PARAMETER),
    VARIABLE(y_i16, INT16, CONSTANT),
    VARIABLE(k_u16, UINT16, PARAMETER),
    VARIABLE(y_u16, UINT16, CONSTANT),
    VARIABLE(y_u32, UINT32, CONSTANT),
    VARIABLE(y_i64, INT64, CONSTANT),
    VARIABLE(y_u64, UINT64, CONSTANT),
    VARIABLE(overflow_time, FLOAT64, PARAMETER),
    VARIABLE(big, INT64, CONSTANT),
    VARIABLE(mode, INT64, CONSTANT),
    ARRAY(offsets, INT32, PARAMETER),
};
#define N_VARIABLES (sizeof VARIABLES / sizeof VARIABLES[0])

static void set_defaults(Types3 *s) {
    s->initialized = 0;
    s->steps = 0;
    s->time = 0;
    for (int j = 0; j < 3; j++) s->x[j] = s->held[j] = s->u[j] = 0;
    s->gain = 1.5f;
    s->k_i8 = -100;
    s->k_u8 = 200;
    s->k_i16 = -1000;
    s->k_u16 = 40000;
    s->overflow_time = 10;
    s->offsets[0] = 3;
    s->offsets[1] = -4;
}

/* The outputs from the state and the parameters. */
static void update_outputs(Types3 *s) {
    const int64_t k = s->steps;
    const fmi3Float64 t = s->time;
    s->m[0] = s->x[0] + s->offsets[0] * t;
    s->m[1] = s->x[1] * t;
    s->m[2] = s->x[2] - sin(t);
    s->m[3] = s->held[0] * s->held[2] + s->offsets[1];
    s->scaled = s->gain * (fmi3Float32)s->x[0];
    s->y_i8 = (fmi3Int8)(s->k_i8 - k);
    s->y_u8 = (fmi3UInt8)(s->k_u8 + k);
    s->y_i16 = (fmi3Int16)(s->k_i16 * k);
    s->y_u16 = (fmi3UInt16)(s->k_u16 + 1000 * k);
    s->y_u32 = (fmi3UInt32)(2000000000 + 1000 * k);
    s->y_i64 = INT32_MIN + 1000 * k;
    s->y_u64 = (fmi3UInt64)(INT32_MAX - 3 * k);
    s->big = t >= s->overflow_time - 1e-9 ? 3000000000 + k : k;
    s->mode = 1 + k % 3;
}

/* Copies the values of the variables `valueReferences` of `type` between `values` and the
 * instance (into `values` if `get`), arrays whole, row-major. */
static fmi3Status transfer(fmi3Instance instance, const char *function, Type type, int get,
                           const fmi3ValueReference valueReferences[], size_t nValueReferences, void *values,
                           size_t nValues) {
    Types3 *s = instance;
    char message[200];
    size_t total = 0;
    for (size_t i = 0; i < nValueReferences; i++) {
        const fmi3ValueReference vr = valueReferences[i];
        if (vr >= N_VARIABLES || VARIABLES[vr].type != type) {
            snprintf(message, sizeof message, "%s: value reference %u is no %s variable of this FMU", function,
                     (unsigned)vr, TYPE_NAMES[type]);
            log_message(s, fmi3Error, "logStatusError", message);
            return fmi3Error;
        }
        const Variable *v = &VARIABLES[vr];
        if (!get && (v->settable == CONSTANT || (v->settable == PARAMETER && s->initialized))) {
            snprintf(message, sizeof message, "%s: %s cannot be set now", function, v->name);
            log_message(s, fmi3Error, "logStatusError", message);
            return fmi3Error;
        }
        total += v->count;
    }
    if (total != nValues) {
        snprintf(message, sizeof message, "%s: nValues = %zu, but the variables asked for have %zu elements",
                 function, nValues, total);
        log_message(s, fmi3Error, "logStatusError", message);
        return fmi3Error;
    }
    if (get) update_outputs(s);
    size_t k = 0;
    for (size_t i = 0; i < nValueReferences; i++) {
        const Variable *v = &VARIABLES[valueReferences[i]];
        char *field = (char *)s + v->offset, *value = (char *)values + k * v->size;
        memcpy(get ? value : field, get ? field : value, v->count * v->size);
        k += v->count;
    }
    return fmi3OK;
}

#define GET(name, ctype, type)                                                                                     \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,     \
                    ctype values[], size_t nValues) {                                                              \
        return transfer(instance, #name, type, 1, valueReferences, nValueReferences, values, nValues);              \
    }
#define SET(name, ctype, type)                                                                                     \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,     \
                    const ctype values[], size_t nValues) {                                                        \
        return transfer(instance, #name, type, 0, valueReferences, nValueReferences, (void *)values, nValues);      \
    }

GET(fmi3GetFloat32, fmi3Float32, FLOAT32)
GET(fmi3GetFloat64, fmi3Float64, FLOAT64)
GET(fmi3GetInt8, fmi3Int8, INT8)
GET(fmi3GetUInt8, fmi3UInt8, UINT8)
GET(fmi3GetInt16, fmi3Int16, INT16)
GET(fmi3GetUInt16, fmi3UInt16, UINT16)
GET(fmi3GetInt32, fmi3Int32, INT32)
GET(fmi3GetUInt32, fmi3UInt32, UINT32)
GET(fmi3GetInt64, fmi3Int64, INT64)
GET(fmi3GetUInt64, fmi3UInt64, UINT64)
SET(fmi3SetFloat32, fmi3Float32, FLOAT32)
SET(fmi3SetFloat64, fmi3Float64, FLOAT64)
SET(fmi3SetInt8, fmi3Int8, INT8)
SET(fmi3SetUInt8, fmi3UInt8, UINT8)
SET(fmi3SetInt16, fmi3Int16, INT16)
SET(fmi3SetUInt16, fmi3UInt16, UINT16)
SET(fmi3SetInt32, fmi3Int32, INT32)
SET(fmi3SetUInt32, fmi3UInt32, UINT32)
SET(fmi3SetInt64, fmi3Int64, INT64)
SET(fmi3SetUInt64, fmi3UInt64, UINT64)

/* No Boolean or String variables. */
FMI3_NO_VARIABLES_GET(fmi3GetBoolean, fmi3Boolean)
FMI3_NO_VARIABLES_GET(fmi3GetString, fmi3String)
FMI3_NO_VARIABLES_SET(fmi3SetBoolean, fmi3Boolean)
FMI3_NO_VARIABLES_SET(fmi3SetString, fmi3String)

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
    Types3 *s = calloc(1, sizeof(Types3));
    if (!s) return NULL;
    s->callbacks = refused;
    set_defaults(s);
    return s;
}

void fmi3FreeInstance(fmi3Instance instance) { free(instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    (void)toleranceDefined, (void)tolerance, (void)stopTimeDefined, (void)stopTime;
    ((Types3 *)instance)->time = startTime;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
    ((Types3 *)instance)->initialized = 1;
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

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn,
                      fmi3Float64 *lastSuccessfulTime) {
    (void)noSetFMUStatePriorToCurrentPoint;
    Types3 *s = instance;
    if (!s->initialized) return unsupported(instance, "fmi3DoStep before fmi3ExitInitializationMode");
    for (int j = 0; j < 3; j++) {
        s->x[j] += s->u[j] * communicationStepSize;
        s->held[j] = s->u[j];
    }
    s->steps++;
    s->time = currentCommunicationPoint + communicationStepSize;
    *eventHandlingNeeded = *terminateSimulation = *earlyReturn = false;
    *lastSuccessfulTime = s->time;
    return fmi3OK;
}

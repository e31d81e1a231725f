/* A small FMI 2.0 Co-Simulation FMU in C that ends its run with fmi2Discard, like the Reference
 * FMU "Stair": `counter` counts the half seconds reached, `level` = counter * `height`. When a step
 * reaches `end_time` (s), the FMU computes it only up to `end_time` and returns fmi2Discard;
 * fmi2GetBooleanStatus(fmi2Terminated) then returns the parameter `terminate` (true: the FMU asks
 * to end the simulation; false: a discard without termination, which a master must treat as an
 * error) and fmi2GetRealStatus(fmi2LastSuccessfulTime) the time reached.
 *
 * It exports the common and Co-Simulation functions only (no Model Exchange functions), as a
 * Co-Simulation-only FMU may. Built by tests/test_third_party.py against the FMI 2.0 headers. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"

/* Value references (see the model description the test writes). */
enum { VR_LEVEL, VR_COUNTER, VR_HEIGHT, VR_END_TIME, VR_TERMINATE };

#define PERIOD 0.5

typedef struct {
    const fmi2CallbackFunctions *callbacks;
    char name[64];
    fmi2Real time, height, end_time;
    fmi2Integer counter;
    fmi2Boolean terminate, terminated;
} Stair;

static void log_message(Stair *s, fmi2Status status, const char *category, const char *message) {
    s->callbacks->logger(s->callbacks->componentEnvironment, s->name, status, category, "%s", message);
}

/* Half seconds reached at `time` (1e-9 s early counts as reached). */
static fmi2Integer counter_at(fmi2Real time) { return (fmi2Integer)floor(time / PERIOD + 1e-9); }

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                              const fmi2CallbackFunctions *callbacks, fmi2Boolean visible, fmi2Boolean logging) {
    (void)resources, (void)visible, (void)logging;
    if (type != fmi2CoSimulation || strcmp(guid, "{8c4e810f-3df3-4a00-8276-176fa3c9f000}") != 0) return NULL;
    Stair *s = callbacks->allocateMemory(1, sizeof(Stair));
    if (!s) return NULL;
    s->callbacks = callbacks;
    snprintf(s->name, sizeof s->name, "%s", name);
    s->height = 0.5;
    s->end_time = 2.5;
    s->terminate = fmi2True;
    return s;
}

void fmi2FreeInstance(fmi2Component c) {
    if (c) ((Stair *)c)->callbacks->freeMemory(c);
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String categories[]) {
    (void)c, (void)on, (void)n, (void)categories;
    return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean has_tolerance, fmi2Real tolerance, fmi2Real start,
                               fmi2Boolean has_stop, fmi2Real stop) {
    (void)has_tolerance, (void)tolerance, (void)has_stop, (void)stop;
    ((Stair *)c)->time = start;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Stair *s = c;
    s->counter = counter_at(s->time);
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
    Stair *s = c;
    for (size_t i = 0; i < n; i++) {
        switch (vr[i]) {
        case VR_LEVEL: value[i] = s->counter * s->height; break;
        case VR_HEIGHT: value[i] = s->height; break;
        case VR_END_TIME: value[i] = s->end_time; break;
        default: return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer value[]) {
    for (size_t i = 0; i < n; i++) {
        if (vr[i] != VR_COUNTER) return fmi2Error;
        value[i] = ((Stair *)c)->counter;
    }
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean value[]) {
    for (size_t i = 0; i < n; i++) {
        if (vr[i] != VR_TERMINATE) return fmi2Error;
        value[i] = ((Stair *)c)->terminate;
    }
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String value[]) {
    (void)c, (void)vr, (void)value;
    return n == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
    Stair *s = c;
    for (size_t i = 0; i < n; i++) {
        switch (vr[i]) {
        case VR_HEIGHT: s->height = value[i]; break;
        case VR_END_TIME: s->end_time = value[i]; break;
        default: return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer value[]) {
    (void)c, (void)vr, (void)value;
    return n == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean value[]) {
    for (size_t i = 0; i < n; i++) {
        if (vr[i] != VR_TERMINATE) return fmi2Error;
        ((Stair *)c)->terminate = value[i];
    }
    return fmi2OK;
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String value[]) {
    (void)c, (void)vr, (void)value;
    return n == 0 ? fmi2OK : fmi2Error;
}

/* Capabilities the model description does not declare. */
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state) { (void)c, (void)state; return fmi2Error; }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) { (void)c, (void)state; return fmi2Error; }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state) { (void)c, (void)state; return fmi2Error; }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size) {
    (void)c, (void)state, (void)size;
    return fmi2Error;
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
    (void)c, (void)state, (void)bytes, (void)size;
    return fmi2Error;
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate *state) {
    (void)c, (void)bytes, (void)size, (void)state;
    return fmi2Error;
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference unknown[], size_t n_unknown,
                                        const fmi2ValueReference known[], size_t n_known, const fmi2Real dv_known[],
                                        fmi2Real dv_unknown[]) {
    (void)c, (void)unknown, (void)n_unknown, (void)known, (void)n_known, (void)dv_known, (void)dv_unknown;
    return fmi2Error;
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    (void)c, (void)vr, (void)n, (void)order, (void)value;
    return fmi2Error;
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer order[], fmi2Real value[]) {
    (void)c, (void)vr, (void)n, (void)order, (void)value;
    return fmi2Error;
}
fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real current, fmi2Real h, fmi2Boolean no_prior_state) {
    (void)no_prior_state;
    Stair *s = c;
    if (s->end_time <= current + h + 1e-12) {
        /* The step reaches end_time: compute it up to there only. A step that ends on end_time
         * is computed whole, and the run still ends there, like the Reference FMUs' Stair. */
        s->time = current > s->end_time ? current : s->end_time;
        s->counter = counter_at(s->time);
        s->terminated = s->terminate;
        log_message(s, fmi2Discard, "logStatusDiscard",
                    s->terminate ? "end_time reached: the simulation should end" : "end_time reached");
        return fmi2Discard;
    }
    s->time = current + h;
    s->counter = counter_at(s->time);
    return fmi2OK;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Status *value) {
    (void)c, (void)kind, (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real *value) {
    if (kind != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = ((Stair *)c)->time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Integer *value) {
    (void)c, (void)kind, (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean *value) {
    if (kind != fmi2Terminated) return fmi2Discard;
    *value = ((Stair *)c)->terminated;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind kind, fmi2String *value) {
    (void)c, (void)kind, (void)value;
    return fmi2Discard;
}

/* A minimal FMI 2.0 co-simulation driver, compiled for x86_64 Linux (against <model>.so), for
 * Windows (against <model>.dll, run under Wine) and for aarch64 Linux (run under QEMU), so that the
 * builds of an FMU can be compared number for number with exactly the same calling sequence.
 *
 *   driver <library> <plan> <input.csv | -> <output.csv>
 *
 * The plan is plain text written by the test from the model description and the cross-check
 * files:
 *
 *   guid {…}
 *   experiment <start> <stop> <step>
 *   inputs <vr> …           value references of the Real inputs, in the input CSV's column order
 *   outputs <t><vr> …       t is r (Real), i (Integer) or b (Boolean), in the output CSV's order
 *
 * The sequence is the one FMPy's simulate_fmu uses (and the cross-check reference files assume):
 * instantiate, setup, set the inputs of t0, initialise, record t0; then at every communication
 * point t_k = start + k·step: set the inputs of row k (held over the step), doStep, record t_k+1.
 * Outputs are printed with 17 significant digits, so a text round trip loses nothing. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#define OPEN_LIBRARY(path) ((void *)LoadLibraryA(path))
#define SYMBOL(lib, name) ((void *)GetProcAddress((HMODULE)(lib), name))
#else
#include <dlfcn.h>
#define OPEN_LIBRARY(path) dlopen(path, RTLD_NOW | RTLD_LOCAL)
#define SYMBOL(lib, name) dlsym(lib, name)
#endif

/* The few fmi2 types this driver needs (FMI 2.0 fmi2TypesPlatform.h / fmi2FunctionTypes.h). */
typedef void *fmi2Component;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef int fmi2Status; /* fmi2OK = 0, fmi2Warning = 1, anything else fails the run */
typedef void (*fmi2CallbackLogger)(void *, const char *, fmi2Status, const char *, const char *, ...);
typedef struct {
    fmi2CallbackLogger logger;
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;
enum { fmi2CoSimulation = 1, MAX_VARS = 256, MAX_LINE = 65536 };

static struct {
    fmi2Component (*instantiate)(const char *, int, const char *, const char *, const fmi2CallbackFunctions *,
                                 fmi2Boolean, fmi2Boolean);
    fmi2Status (*setup)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
    fmi2Status (*enter_init)(fmi2Component);
    fmi2Status (*exit_init)(fmi2Component);
    fmi2Status (*set_real)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
    fmi2Status (*get_real)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
    fmi2Status (*get_integer)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Integer *);
    fmi2Status (*get_boolean)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Boolean *);
    fmi2Status (*do_step)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
    fmi2Status (*terminate)(fmi2Component);
    void (*free_instance)(fmi2Component);
} fmi;

typedef struct {
    char guid[128];
    double start, stop, step;
    size_t n_inputs, n_outputs;
    fmi2ValueReference inputs[MAX_VARS], outputs[MAX_VARS];
    char output_types[MAX_VARS];
} Plan;

static void fail(const char *what, const char *detail) {
    fprintf(stderr, "driver: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    exit(1);
}

static void check(fmi2Status status, const char *call) {
    if (status > 1) fail(call, "returned an error status");
}

static void logger(void *env, const char *instance, fmi2Status status, const char *category, const char *message,
                   ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s] %s (status %d): ", instance, category, status);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void *symbol(void *lib, const char *name) {
    void *f = SYMBOL(lib, name);
    if (!f) fail("missing symbol", name);
    return f;
}

static void load(const char *path) {
    void *lib = OPEN_LIBRARY(path);
    if (!lib) fail("cannot load", path);
    *(void **)&fmi.instantiate = symbol(lib, "fmi2Instantiate");
    *(void **)&fmi.setup = symbol(lib, "fmi2SetupExperiment");
    *(void **)&fmi.enter_init = symbol(lib, "fmi2EnterInitializationMode");
    *(void **)&fmi.exit_init = symbol(lib, "fmi2ExitInitializationMode");
    *(void **)&fmi.set_real = symbol(lib, "fmi2SetReal");
    *(void **)&fmi.get_real = symbol(lib, "fmi2GetReal");
    *(void **)&fmi.get_integer = symbol(lib, "fmi2GetInteger");
    *(void **)&fmi.get_boolean = symbol(lib, "fmi2GetBoolean");
    *(void **)&fmi.do_step = symbol(lib, "fmi2DoStep");
    *(void **)&fmi.terminate = symbol(lib, "fmi2Terminate");
    *(void **)&fmi.free_instance = symbol(lib, "fmi2FreeInstance");
}

/* Reads "inputs vr vr …" or "outputs rvr ivr …" (the rest of the line after the keyword). */
static size_t read_refs(char *rest, fmi2ValueReference *refs, char *types) {
    size_t n = 0;
    for (char *token = strtok(rest, " \t\r\n"); token; token = strtok(NULL, " \t\r\n")) {
        if (n == MAX_VARS) fail("too many variables in the plan", NULL);
        if (types) {
            if (!strchr("rib", token[0])) fail("output type is not r, i or b", token);
            types[n] = *token++;
        }
        refs[n++] = (fmi2ValueReference)strtoul(token, NULL, 10);
    }
    return n;
}

static void read_plan(const char *path, Plan *plan) {
    static char line[MAX_LINE];
    FILE *f = fopen(path, "r");
    if (!f) fail("cannot open", path);
    memset(plan, 0, sizeof *plan);
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "guid ", 5)) {
            sscanf(line + 5, "%127s", plan->guid);
        } else if (!strncmp(line, "experiment ", 11)) {
            if (sscanf(line + 11, "%lf %lf %lf", &plan->start, &plan->stop, &plan->step) != 3)
                fail("bad experiment line", line);
        } else if (!strncmp(line, "inputs", 6)) {
            plan->n_inputs = read_refs(line + 6, plan->inputs, NULL);
        } else if (!strncmp(line, "outputs", 7)) {
            plan->n_outputs = read_refs(line + 7, plan->outputs, plan->output_types);
        }
    }
    fclose(f);
    if (!plan->guid[0] || plan->step <= 0 || plan->stop < plan->start) fail("incomplete plan", path);
}

/* The next row of the input CSV into values[0..n]; its time must be the communication point. */
static void read_input_row(FILE *csv, double time, double *values, size_t n) {
    static char line[MAX_LINE];
    char *cursor = line;
    if (!fgets(line, sizeof line, csv)) fail("the input CSV ends before the stop time", NULL);
    double row_time = strtod(cursor, &cursor);
    if (row_time - time > 1e-9 || time - row_time > 1e-9) fail("input row time is not the communication point", line);
    for (size_t i = 0; i < n; i++) {
        if (*cursor++ != ',') fail("input row has too few columns", line);
        values[i] = strtod(cursor, &cursor);
    }
}

static void write_outputs(fmi2Component c, const Plan *plan, double time, FILE *out) {
    fprintf(out, "%.17g", time);
    for (size_t i = 0; i < plan->n_outputs; i++) {
        const fmi2ValueReference *vr = &plan->outputs[i];
        fmi2Real real;
        fmi2Integer integer;
        if (plan->output_types[i] == 'r') {
            check(fmi.get_real(c, vr, 1, &real), "fmi2GetReal");
            fprintf(out, ",%.17g", real);
        } else {
            check((plan->output_types[i] == 'i' ? fmi.get_integer : fmi.get_boolean)(c, vr, 1, &integer),
                  "fmi2GetInteger/Boolean");
            fprintf(out, ",%d", integer);
        }
    }
    fputc('\n', out);
}

static void set_inputs(fmi2Component c, const Plan *plan, FILE *csv, double time) {
    double values[MAX_VARS];
    if (!csv) return;
    read_input_row(csv, time, values, plan->n_inputs);
    check(fmi.set_real(c, plan->inputs, plan->n_inputs, values), "fmi2SetReal");
}

int main(int argc, char **argv) {
    static char header[MAX_LINE];
    Plan plan;
    if (argc != 5) fail("usage", "driver <library> <plan> <input.csv | -> <output.csv>");
    load(argv[1]);
    read_plan(argv[2], &plan);
    FILE *csv = strcmp(argv[3], "-") ? fopen(argv[3], "r") : NULL;
    if (strcmp(argv[3], "-") && (!csv || !fgets(header, sizeof header, csv))) fail("cannot read", argv[3]);
    FILE *out = fopen(argv[4], "w");
    if (!out) fail("cannot write", argv[4]);

    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = fmi.instantiate("driver", fmi2CoSimulation, plan.guid, NULL, &callbacks, 0, 0);
    if (!c) fail("fmi2Instantiate failed", plan.guid);
    check(fmi.setup(c, 0, 0.0, plan.start, 0, 0.0), "fmi2SetupExperiment");
    set_inputs(c, &plan, csv, plan.start);
    check(fmi.enter_init(c), "fmi2EnterInitializationMode");
    check(fmi.exit_init(c), "fmi2ExitInitializationMode");
    write_outputs(c, &plan, plan.start, out);
    /* Times from the step index, not by accumulation, as the reference files have them. */
    long steps = (long)((plan.stop - plan.start) / plan.step + 0.5);
    for (long k = 0; k < steps; k++) {
        double time = plan.start + (double)k * plan.step;
        if (k > 0) set_inputs(c, &plan, csv, time);
        check(fmi.do_step(c, time, plan.step, 1), "fmi2DoStep");
        write_outputs(c, &plan, plan.start + (double)(k + 1) * plan.step, out);
    }
    check(fmi.terminate(c), "fmi2Terminate");
    fmi.free_instance(c);
    if (fclose(out)) fail("cannot write", argv[4]);
    return 0;
}

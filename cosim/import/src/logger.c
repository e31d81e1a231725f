/*
 * Host side of the FMI 2.0 logger callback.
 *
 * fmi2CallbackLogger is variadic (printf-style), which stable Rust cannot
 * define. This function formats the message with vsnprintf and forwards the
 * result to a Rust sink. The sink is found through componentEnvironment, which
 * points to a structure whose first member is the sink function pointer
 * (LogContext in fmi/logger.rs), so this file has no link-time dependency on
 * the Rust side.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

typedef void (*cosim_log_sink)(void *environment, const char *instance_name, int status,
                               const char *category, const char *message);

typedef struct {
    cosim_log_sink sink;
} cosim_log_environment;

void crane_cosim_fmi2_logger(void *environment, const char *instance_name, int status,
                             const char *category, const char *message, ...)
{
    char stack_buffer[1024];
    char *heap_buffer = NULL;
    const char *text = stack_buffer;
    va_list args;
    int length;

    if (message == NULL) {
        text = "";
    } else {
        va_start(args, message);
        length = vsnprintf(stack_buffer, sizeof stack_buffer, message, args);
        va_end(args);
        if (length < 0) {
            text = message; /* formatting failed: pass the raw format string */
        } else if ((size_t)length >= sizeof stack_buffer) {
            heap_buffer = (char *)malloc((size_t)length + 1);
            if (heap_buffer != NULL) {
                va_start(args, message);
                vsnprintf(heap_buffer, (size_t)length + 1, message, args);
                va_end(args);
                text = heap_buffer;
            } /* else: keep the truncated text */
        }
    }

    if (environment != NULL && ((cosim_log_environment *)environment)->sink != NULL) {
        ((cosim_log_environment *)environment)->sink(environment, instance_name, status, category, text);
    } else {
        fprintf(stderr, "[%s] %s\n", instance_name != NULL ? instance_name : "(no instance name)", text);
    }
    free(heap_buffer);
}

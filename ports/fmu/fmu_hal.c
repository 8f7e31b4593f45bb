/*
 * The one HAL function the FMU's objects refer to: fmt_print()'s console
 * (util/fmt.h). An FMU has no console (its messages go to the master's
 * logger) and nothing it runs prints; this keeps the library free of
 * undefined symbols.
 */
#include <stddef.h>

#include "hal/hal.h"

void hal_console_write(const char *text, size_t n) {
    (void)text;
    (void)n;
}

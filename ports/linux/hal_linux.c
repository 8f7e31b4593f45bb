/*
 * The HAL on a Linux host: a desk loop in virtual time. The ticks are not
 * driven by a clock: hal_wait_for_tick() runs the next fast tick, and the
 * medium tick right after it when the fast tick released it, and the
 * control tick after that when the medium tick released it: exactly the
 * order in which a target's interrupts would run them when none overruns.
 * Inside a critical section the tick falls due but waits, as a masked
 * interrupt does, and runs at the outermost hal_critical_exit().
 * hal_cycles() counts virtual nanoseconds.
 */
#include "hal_linux.h"

#include <stdio.h>
#include <stdlib.h>

static struct {
    FILE *telemetry;       /* NULL: telemetry is discarded */
    FILE *input;           /* NULL: no scenario input */
    hal_ticks_config ticks;
    bool running;
    bool fast_pending;     /* a fast tick fell due inside a critical section */
    bool medium_pending;
    bool control_pending;
    uint64_t virtual_ns;
    int critical_depth;
} hal_linux;

void hal_linux_set_telemetry(FILE *out) { hal_linux.telemetry = out; }

void hal_linux_set_input(FILE *in) { hal_linux.input = in; }

void hal_console_write(const char *text, size_t n) { (void)fwrite(text, 1, n, stdout); }

void hal_telemetry_write(const uint8_t *data, size_t n) {
    if (hal_linux.telemetry != NULL) {
        (void)fwrite(data, 1, n, hal_linux.telemetry);
    }
}

size_t hal_input_read(uint8_t *buf, size_t n) {
    if (hal_linux.input == NULL) {
        return 0;
    }
    return fread(buf, 1, n, hal_linux.input);
}

uint32_t hal_cycles(void) { return (uint32_t)(hal_linux.virtual_ns & 0xffffffffu); }

static void hal_linux_run_ticks(void);

void hal_critical_enter(void) { hal_linux.critical_depth++; }

void hal_critical_exit(void) {
    if (hal_linux.critical_depth > 0) {
        hal_linux.critical_depth--;
        if (hal_linux.critical_depth == 0 && hal_linux.fast_pending) {
            hal_linux.fast_pending = false;
            hal_linux_run_ticks();
        }
    }
}

bool hal_ticks_start(const hal_ticks_config *config) {
    if (config == NULL || config->fast == NULL || config->fast_period_ns == 0u) {
        return false;
    }
    hal_linux.ticks = *config;
    hal_linux.fast_pending = false;
    hal_linux.medium_pending = false;
    hal_linux.control_pending = false;
    hal_linux.running = true;
    return true;
}

void hal_ticks_stop(void) {
    hal_linux.running = false;
    hal_linux.fast_pending = false;
}

void hal_medium_release(void) { hal_linux.medium_pending = true; }

void hal_control_release(void) { hal_linux.control_pending = true; }

/* The fast tick, and the medium and control ticks it released. */
static void hal_linux_run_ticks(void) {
    hal_linux.ticks.fast();
    if (hal_linux.medium_pending) {
        hal_linux.medium_pending = false;
        if (hal_linux.ticks.medium != NULL) {
            hal_linux.ticks.medium();
        }
    }
    if (hal_linux.control_pending) {
        hal_linux.control_pending = false;
        if (hal_linux.ticks.control != NULL) {
            hal_linux.ticks.control();
        }
    }
}

void hal_wait_for_tick(void) {
    if (!hal_linux.running) {
        return;
    }
    hal_linux.virtual_ns += hal_linux.ticks.fast_period_ns;
    if (hal_linux.critical_depth > 0) {
        hal_linux.fast_pending = true; /* masked: it runs at the outermost exit */
        return;
    }
    hal_linux_run_ticks();
}

void hal_exit(int status) {
    (void)fflush(stdout);
    if (hal_linux.telemetry != NULL) {
        (void)fflush(hal_linux.telemetry);
    }
    exit(status);
}

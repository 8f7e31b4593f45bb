/*
 * The hardware abstraction layer: the whole contract between src/ and a
 * port. src/ reaches its platform only through these functions; each port
 * (ports/linux, ports/cortexm) implements all of them in its own folder.
 *
 * Execution model. A port runs one background context (main and what it
 * calls) and three tick contexts:
 *   - the fast tick, at the highest priority, every `fast_period_ns` of the
 *     port's time base;
 *   - the medium tick, at a lower priority, released by the fast tick with
 *     hal_medium_release() and preemptible by the fast tick;
 *   - the control tick, lower again, released by the medium tick with
 *     hal_control_release() and preemptible by both.
 * On Cortex-M these are a hardware timer interrupt and two pended software
 * interrupts; on Linux a virtual-time loop calls them in the same order.
 * Results never depend on which of the two it is (see src/ executive).
 */
#ifndef UUV_HAL_H
#define UUV_HAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Called once by the port before main's own code runs; nothing to do here. */

/* ---- Console and telemetry -------------------------------------------- */

/* Writes n bytes of human-readable text (tests, reports). Never fails. */
void hal_console_write(const char *text, size_t n);

/* Writes n bytes to the telemetry channel (binary frames). Never fails. */
void hal_telemetry_write(const uint8_t *data, size_t n);

/*
 * Reads up to n bytes of scenario input into buf. Returns the number of
 * bytes read; 0 at the end of the input.
 */
size_t hal_input_read(uint8_t *buf, size_t n);

/* ---- Time -------------------------------------------------------------- */

/*
 * A free-running counter of the port's time base (instructions or cycles on
 * a target, virtual nanoseconds on the host). Wraps modulo 2^32; only
 * differences are meaningful.
 */
uint32_t hal_cycles(void);

/* ---- Critical sections ------------------------------------------------- */

/*
 * Masks the tick contexts; calls nest. On a bare-metal target this is a
 * nested interrupt mask; on the host it is a counter (one thread). A tick
 * that falls due inside runs at the outermost exit. An exit without an
 * enter does nothing.
 */
void hal_critical_enter(void);
void hal_critical_exit(void);

/* ---- Periodic ticks ---------------------------------------------------- */

typedef void (*hal_tick_fn)(void);

typedef struct {
    uint32_t fast_period_ns; /* [ns] period of the fast tick */
    hal_tick_fn fast;        /* fast tick handler, highest priority */
    hal_tick_fn medium;      /* medium tick handler, released by the fast one */
    hal_tick_fn control;     /* control tick handler, released by the medium one (may be NULL) */
} hal_ticks_config;

/*
 * Starts the periodic ticks. Returns false (and starts nothing) when the
 * port cannot meet the configuration (period out of its timer's range).
 */
bool hal_ticks_start(const hal_ticks_config *config);

/* Stops the periodic ticks; a tick already running completes. */
void hal_ticks_stop(void);

/* Releases one run of the medium tick (callable from the fast tick). */
void hal_medium_release(void);

/* Releases one run of the control tick (callable from the medium tick). */
void hal_control_release(void);

/*
 * Waits in the background context until a tick has run (sleep until the
 * next interrupt on a target; run the next fast tick on the host). Inside
 * a critical section it returns once a tick has fallen due, which then
 * runs at the section's exit: the way to sleep without missing a wake-up.
 */
void hal_wait_for_tick(void);

/* ---- Exit -------------------------------------------------------------- */

/*
 * Ends the program with a status (0 = success). On a target under an
 * emulator the status reaches the emulator's exit code. Does not return.
 */
__attribute__((noreturn)) void hal_exit(int status);

#endif /* UUV_HAL_H */

/*
 * What the Cortex-M port offers beyond src/hal/hal.h, for the programs of
 * this port (the firmware simulation): the fast tick's overrun count, a
 * stop from inside the fast tick, the emulator's command line and the
 * scenario input through semihosting. src/ never includes this file.
 */
#ifndef UUV_HAL_CORTEXM_H
#define UUV_HAL_CORTEXM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/*
 * Fast-tick overruns: the SysTick exception was pending again when its
 * handler ended, so the tick's work did not fit in its period. Each one is
 * counted. By default the late tick then runs at once; with
 * hal_cm_stop_on_overrun(true) the first overrun stops SysTick instead, as
 * a real-time program wants: a handler that keeps overrunning would
 * otherwise re-enter forever and starve everything below it. (The default
 * suits programs whose deadlines do not matter, such as the unit tests,
 * which run without -icount, where a host's hiccup can delay a tick.)
 */
uint32_t hal_cm_fast_overruns(void);
void hal_cm_stop_on_overrun(bool stop);

/*
 * Stops the fast tick from inside its handler after the run's last tick,
 * clearing a tick that fell due meanwhile (it is not a tick of the run, so
 * not an overrun). Unlike hal_ticks_stop() it leaves a medium tick that
 * step released pending, so that it still runs.
 */
void hal_cm_fast_stop(void);

/*
 * Holds the fast tick's timer (hold true) and lets it go on where it was
 * (false): the multi-party run's drive waits so for the slow segment's
 * answer, in lock-step whatever the other side's speed.
 */
void hal_cm_fast_hold(bool hold);

/* Reads n bytes from the first UART, waiting for each (the multi-party run's link). */
void hal_cm_link_read(uint8_t *buf, size_t n);

/* The emulator's command line (semihosting), NUL-terminated; -1 when none. */
int32_t hal_cm_cmdline(char *buf, size_t cap);

/* Opens the host file that hal_input_read() then reads (semihosting); false on failure. */
bool hal_cm_input_open(const char *path);

/* Closes that file. */
void hal_cm_input_close(void);

#endif /* UUV_HAL_CORTEXM_H */

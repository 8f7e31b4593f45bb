/*
 * The HAL contract as every port must keep it: periodic fast ticks, the
 * medium tick released by the fast one, a counter that advances, nesting
 * critical sections. Runs unchanged on the host's virtual-time loop and on
 * the Cortex-M interrupts.
 */
#include "hal/hal.h"
#include "ut.h"

void suite_hal(void);

static volatile uint32_t fast_count;
static volatile uint32_t medium_count;

static void fast_tick(void) {
    fast_count++;
    if (fast_count % 5u == 0u) {
        hal_medium_release();
    }
}

static void medium_tick(void) { medium_count++; }

/* Waits (bounded) until the fast tick has run n times since its count was reset. */
static void wait_ticks(uint32_t n) {
    for (uint32_t guard = 0; guard < 1000000u && fast_count < n; guard++) {
        hal_wait_for_tick();
    }
}

void suite_hal(void) {
    UT_TEST("ticks: a period the timer cannot make is refused");
    hal_ticks_config bad = {0u, fast_tick, medium_tick, NULL};
    UT_CHECK(!hal_ticks_start(&bad));
    UT_CHECK(!hal_ticks_start(NULL));

    UT_TEST("ticks: fast ticks run and release one medium tick per five");
    fast_count = 0u;
    medium_count = 0u;
    hal_ticks_config cfg = {100000u, fast_tick, medium_tick, NULL};
    uint32_t c0 = hal_cycles();
    UT_CHECK(hal_ticks_start(&cfg));
    wait_ticks(100u);
    hal_ticks_stop();
    uint32_t f = fast_count;
    uint32_t m = medium_count;
    UT_CHECK(f >= 100u);
    UT_CHECK(m + 1u >= f / 5u && m <= f / 5u);
    uint32_t elapsed = hal_cycles() - c0;
    UT_CHECK(elapsed > 0u);
    ut_info("%u fast, %u medium ticks; counter advanced by %u", (unsigned)f, (unsigned)m,
            (unsigned)elapsed);

    UT_TEST("ticks: nothing runs after hal_ticks_stop");
    uint32_t before = fast_count;
    for (int i = 0; i < 1000; i++) {
        hal_critical_enter();
        hal_critical_exit();
    }
    UT_EQ_INT(fast_count, before);

    UT_TEST("critical sections nest: a tick that falls due inside two of them waits past "
            "the inner exit and runs after the outer one; one exit too many leaves the next "
            "section masking");
    fast_count = 0u;
    UT_CHECK(hal_ticks_start(&cfg));
    wait_ticks(1u);
    hal_critical_enter();
    hal_critical_enter();
    uint32_t held = fast_count;
    hal_wait_for_tick(); /* a tick falls due; masked, it does not run */
    hal_critical_exit();
    hal_wait_for_tick();
    uint32_t inner = fast_count;
    hal_critical_exit();
    wait_ticks(held + 1u);
    UT_EQ_INT(inner, held);
    UT_CHECK(fast_count > held);
    hal_critical_exit(); /* one too many */
    hal_critical_enter();
    held = fast_count;
    hal_wait_for_tick();
    inner = fast_count;
    hal_critical_exit();
    wait_ticks(held + 1u);
    hal_ticks_stop();
    UT_EQ_INT(inner, held);
    UT_CHECK(fast_count > held);
}

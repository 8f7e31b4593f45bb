/*
 * The drive's phase-loss protection (protection.h) on rms phase currents
 * written down frame by frame: balanced currents never trip, one phase
 * below a tenth of the largest trips at the end of the second window in a
 * row, a healthy window between two bad ones starts the count again, small
 * currents (below the 10 A floor) never trip, and the window is the same
 * length whatever the frame. The references are the thresholds of the
 * header, applied by hand.
 */
#include "protection.h"
#include "ut.h"

void suite_protection(void);

static protection pr;

/* Feeds n frames of the currents (a, b, c); returns the frame (1-based) of the first trip, 0: none. */
static unsigned feed(unsigned n, double a, double b, double c) {
    const double i[3] = {a, b, c};
    unsigned first = 0u;
    for (unsigned k = 1u; k <= n; k++) {
        if (protection_step(&pr, i) == DRIVE_TRIP_PHASE_LOSS && first == 0u) {
            first = k;
        }
    }
    return first;
}

static void test_balanced(void) {
    UT_TEST("balanced phases (40 A each, and 40/35/30 A) run for 10 s without a trip");
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(100u, 40.0, 40.0, 40.0), 0);
    UT_EQ_INT(feed(100u, 40.0, 35.0, 30.0), 0);
    UT_EQ_INT(pr.windows, 0);
}

static void test_open_phase(void) {
    UT_TEST("phase b at 2 A beside 40 A: a trip at the end of the second 0.1 s window, "
            "and at every window after it");
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(1u, 40.0, 2.0, 40.0), 0);
    UT_EQ_INT(pr.windows, 1);
    UT_EQ_INT(feed(1u, 40.0, 2.0, 40.0), 1);
    UT_EQ_INT(feed(1u, 40.0, 2.0, 40.0), 1);
    UT_EQ_INT(pr.windows, 3);
    UT_TEST("the ratio's edge: a phase at 10.5 % of the largest does not trip, at 9.5 % it does");
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(5u, 0.105 * 50.0, 50.0, 45.0), 0);
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(5u, 0.095 * 50.0, 50.0, 45.0), 2);
}

static void test_interrupted(void) {
    UT_TEST("a healthy window between two that show a loss starts the count again");
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(1u, 0.0, 30.0, 30.0), 0);
    UT_EQ_INT(feed(1u, 30.0, 30.0, 30.0), 0);
    UT_EQ_INT(pr.windows, 0);
    UT_EQ_INT(feed(1u, 0.0, 30.0, 30.0), 0);
    UT_EQ_INT(feed(1u, 0.0, 30.0, 30.0), 1);
}

static void test_floor(void) {
    UT_TEST("below the floor (largest phase 9.5 A rms) an open phase does not trip; at 10.5 A "
            "it does");
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(20u, 9.5, 0.0, 9.5), 0);
    protection_init(&pr, 0.1);
    UT_EQ_INT(feed(20u, 10.5, 0.0, 10.5), 2);
}

static void test_frames(void) {
    UT_TEST("with 10 ms frames the windows are still 0.1 s: the trip at the 20th frame; "
            "the window sums the frames' mean squares, so one bad frame in ten is "
            "diluted (phase a at 0 A for one frame of each window: rms 38 A of 40 A)");
    protection_init(&pr, 0.01);
    UT_EQ_INT(feed(40u, 40.0, 0.0, 40.0), 20);
    protection_init(&pr, 0.01);
    bool tripped = false;
    for (unsigned w = 0u; w < 10u; w++) {
        tripped = tripped || feed(1u, 0.0, 40.0, 40.0) != 0u;
        tripped = tripped || feed(9u, 40.0, 40.0, 40.0) != 0u;
    }
    UT_CHECK(!tripped);
    UT_NEAR(pr.t_s, 0.0, 0.0);
}

void suite_protection(void) {
    test_balanced();
    test_open_phase();
    test_interrupted();
    test_floor();
    test_frames();
}

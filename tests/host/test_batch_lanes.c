/*
 * The lane step of uuvsim batch (ports/linux/batch_lanes.h) against the
 * desk's own runs of steps (drive_fast_run()), bit for bit: a step in two
 * places, pinned here.
 *
 *   test_batch_lanes
 *
 * For each modulator, 2 * batch_lanes + 3 drives (full vectors, a partial
 * one, and runs that start at different times of the bench start-up, so
 * that the lanes hold different states) are taken at motor-frame
 * boundaries of their runs over 240 frames; from each such state the frame's
 * run of steps (47, and 1, 7 and 49) goes once through batch_fast_run()
 * with all drives and once through drive_fast_run() for each, and the two
 * drives must be equal byte for byte (the whole drive_segment, copied from
 * one state). A last case starts every drive with its DC link at the
 * clamp and its filter currents beyond theirs, so that the clamps and
 * their counts act in every lane. The lanes' edge duty against
 * pwm_rt_edge_duty() on its extremes and a million random edges. Prints
 * each check and "N passed, N failed".
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "batch_lanes.h"
#include "executive.h"
#include "host_check.h"
#include "models/drive/pwm/pwm_rt.h"

#define MAX_DRIVES 40

static scenario scn;
static exec ex[MAX_DRIVES];
static drive_segment a[MAX_DRIVES], b[MAX_DRIVES];

/* Runs exec k to the start of its next run of steps (the tick after a frame's release). */
static void to_next_run(exec *e) {
    do {
        (void)exec_desk_run(e, 1u);
        exec_frame f;
        (void)exec_report_take(e, &f);
    } while (e->state == EXEC_RUNNING && (e->fast_gate != 0u || exec_desk_ahead(e, UINT32_MAX) < 40u));
}

/* From the drives' states now: n steps both ways; true when every drive agrees. */
static bool same_after(size_t count, uint32_t n, bool substep) {
    drive_segment *p[MAX_DRIVES];
    for (size_t i = 0; i < count; i++) {
        memcpy(&a[i], &ex[i].drive, sizeof a[i]);
        memcpy(&b[i], &ex[i].drive, sizeof b[i]);
        p[i] = &a[i];
    }
    batch_fast_run(p, count, n, substep);
    bool same = true;
    for (size_t i = 0; i < count; i++) {
        drive_fast_run(&b[i], n);
        same = same && memcmp(&a[i], &b[i], sizeof a[i]) == 0;
    }
    return same;
}

static void modulator_case(drive_modulator mod) {
    const size_t count = 2u * batch_lanes + 3u <= MAX_DRIVES ? 2u * batch_lanes + 3u : MAX_DRIVES;
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.modulator = mod;
    cfg.duration_s = 2.0;
    bool ready = true;
    for (size_t i = 0; i < count; i++) {
        ready = ready && exec_init(&ex[i], &cfg, &scn) == EXEC_OK;
        /* A different moment of the start-up in each lane: 0 to 0.1 s apart. */
        for (uint32_t k = 0u; ready && k < 40u + 250u * (uint32_t)i; k++) {
            to_next_run(&ex[i]);
        }
        ready = ready && batch_lane_ready(&ex[i].drive);
    }
    check(ready, "the drives are on the real-time path, each at its own time of the start-up");
    const bool substep = (mod == DRIVE_MODULATOR_SUBSTEP);
    static const uint32_t lengths[] = {47u, 1u, 7u, 49u};
    uint32_t frames = 0u, bad = 0u;
    for (uint32_t f = 0u; f < 240u; f++) {
        for (size_t k = 0; k < sizeof lengths / sizeof lengths[0]; k++) {
            bad += same_after(count, lengths[k], substep) ? 0u : 1u;
            frames++;
        }
        for (size_t i = 0; i < count; i++) {
            to_next_run(&ex[i]);
        }
    }
    char what[200];
    snprintf(what, sizeof what, "%s modulator, %zu drives in %u lanes (%s): %u runs of steps "
             "(47, 1, 7, 49) from frame starts, each drive equal byte for byte (%u differ)",
             substep ? "sub-step" : "sampled", count, batch_lanes, batch_lanes_isa, frames, bad);
    check(bad == 0u && frames == 960u, what);
    /* The clamps: the DC link above its range and the filter currents beyond theirs. */
    for (size_t i = 0; i < count; i++) {
        drive_segment *d = &ex[i].drive;
#if UUV_NUMERIC == UUV_NUMERIC_FLOAT
        d->ps.v_dc = 1023.5f + 0.1f * (float)i;
        d->ps.ph[0].i_l = 255.9f;
        d->ps.ph[1].i_d = -255.9f;
        d->in.battery.e_v = 1500.0f;
#else
        d->ps.v_dc = 268435455 - 1000 * (int32_t)i;
        d->ps.ph[0].v_c = 268435456 + 4000000; /* beyond 1024 V: clamped at the first step */
        d->ps.ph[1].i_d = -268435000;
        d->in.battery.e = 268435455;
#endif
        /* Odd drives' counts near their stop at UINT32_MAX, which the run passes. */
        d->ps.sat_count = ((i % 2u) == 1u) ? UINT32_MAX - (uint32_t)(i / 4u) : 0u;
    }
    uint32_t sat0 = ex[0].drive.ps.sat_count;
    bool same = same_after(count, 47u, substep);
    drive_fast_run(&ex[0].drive, 47u);
    snprintf(what, sizeof what, "%s modulator, the stage at its clamps: equal byte for byte, "
             "the clamps counted (%u), the counts near UINT32_MAX stopped there",
             substep ? "sub-step" : "sampled",
             (unsigned)(ex[0].drive.ps.sat_count - sat0));
    check(same && ex[0].drive.ps.sat_count > sat0, what);
}

/* xorshift64: a fixed sequence of test values. */
static uint64_t next(uint64_t *x) {
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
    return *x;
}

/*
 * The lanes' edge duty (its quotient in double) against pwm_rt_edge_duty()
 * on the edges' extremes and a million random edges: a comparison that
 * goes from e0 to e1 across zero (e0 > 0 >= e1 or e0 <= 0 < e1), |e| < 2^30,
 * shifts 0..15.
 */
static void edge_duty_case(void) {
    static const int32_t lim = (1 << 30) - 1;
    const int32_t ends[][2] = {
        {1, 0}, {0, 1}, {1, -1}, {-1, 1}, {lim, -lim}, {-lim, lim}, {lim, 0}, {0, lim},
        {1, -lim}, {-lim, 1}, {0xffff, 0}, {0x10000, 0}, {0x8000, -0x8000}, {0x7fff, -0x8001},
        {1, -0xfffe}, {1, -0xffff}, {3, -0x1fffd},
    };
    unsigned bad = 0u;
    unsigned n = 0u;
    for (size_t i = 0; i < sizeof ends / sizeof ends[0]; i++) {
        for (uint32_t sh = 0u; sh < 16u; sh++) {
            n++;
            bad += (batch_lanes_edge_duty(ends[i][0], ends[i][1], sh) !=
                    pwm_rt_edge_duty(ends[i][0], ends[i][1], sh)) ? 1u : 0u;
        }
    }
    uint64_t x = 0x9E3779B97F4A7C15u;
    for (unsigned i = 0u; i < 1000000u; i++) {
        const uint64_t r = next(&x);
        /* |e| below 2^30, but often small: a random size, then a value of that size. */
        const int32_t up = (int32_t)((r & 0x3ffffffeu) >> ((r >> 32) % 30u));
        const int32_t down = (int32_t)(((r >> 30) & 0x3fffffffu) >> ((r >> 40) % 30u));
        const bool rising = ((r >> 63) != 0u);
        const int32_t e0 = rising ? -down : up + 1;
        const int32_t e1 = rising ? up + 1 : -down;
        const uint32_t sh = (uint32_t)((r >> 50) % 16u);
        n++;
        bad += (batch_lanes_edge_duty(e0, e1, sh) != pwm_rt_edge_duty(e0, e1, sh)) ? 1u : 0u;
    }
    char what[160];
    snprintf(what, sizeof what, "edge duty in lanes = pwm_rt_edge_duty() on %u edges (%u differ)",
             n, bad);
    check(bad == 0u, what);
}

int main(void) {
    const char *text = "duration 2\nat 0 n_rpm=1000\nat 0.3 n_rpm=400\n";
    scenario_error err;
    if (!scenario_parse(&scn, text, strlen(text), &err)) {
        printf("the scenario did not parse\n0 passed, 1 failed\n");
        return 1;
    }
    printf("uuvsim batch's lane step against drive_fast_run(), %s build\n", UUV_NUMERIC_NAME);
    modulator_case(DRIVE_MODULATOR_SUBSTEP);
    modulator_case(DRIVE_MODULATOR_SAMPLED);
    edge_duty_case();
    return check_finish();
}

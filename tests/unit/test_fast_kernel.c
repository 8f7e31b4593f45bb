/*
 * A port's real-time fast step against the C's: in the fixed firmware
 * images (FW_FAST_KERNEL=1) the Thumb-2 kernel of ports/cortexm and
 * the drive segment's own step run side by side from the same random
 * states, and the whole drive must agree byte for byte after each step:
 * the modulator and its plan, the legs, the power stage (the clamps and
 * their count included), the motor's fast currents and the frame sums.
 * The states are drawn over the whole range the stage keeps them in, some
 * start at its edge, so that the clamps act, and the modulator's frames
 * are random ramps from random carrier phases, so that the steps with an
 * edge, the held ones and those the plan hands to single steps all run.
 * Builds without a kernel have nothing to compare and run no test.
 */
#include <stddef.h>
#include <stdint.h>

#include "drive_segment.h"
#include "params.h"
#include "models/propeller/propeller.h"
#include "ut.h"

#if defined(FW_FAST_KERNEL) && FW_FAST_KERNEL
#include "fast_kernel.h"
#endif

void suite_fast_kernel(void);

#if defined(FW_FAST_KERNEL) && FW_FAST_KERNEL

static drive_segment ref, ker;
static propeller_model prop;
static uint32_t rng = 0x2545F491u;

static uint32_t next(void) { return ut_rand_u32(&rng); }

/* Uniform in [-lim, lim]. */
static int32_t within(int32_t lim) { return ut_rand_within(&rng, lim); }

/* Byte copies and comparison of the whole drive, padding included. */
static void copy_all(drive_segment *dst, const drive_segment *src) {
    const unsigned char *p = (const unsigned char *)src;
    unsigned char *q = (unsigned char *)dst;
    for (size_t i = 0u; i < sizeof *src; i++) {
        q[i] = p[i];
    }
}

static bool same_all(const drive_segment *a, const drive_segment *b) {
    const unsigned char *p = (const unsigned char *)a;
    const unsigned char *q = (const unsigned char *)b;
    for (size_t i = 0u; i < sizeof *a; i++) {
        if (p[i] != q[i]) {
            return false;
        }
    }
    return true;
}

/*
 * A frame of the modulator with random references (up to m 0.95; steep:
 * slopes beyond the carrier's, which the plan hands to single steps) from
 * the carrier's phase now: prepared when the frame in force has run its
 * steps (as the motor task's), else planned at the apply.
 */
static void frame_random(drive_segment *d, bool steep) {
    pwm_rt_ramp r;
    for (int x = 0; x < 2; x++) {
        r.r0[x] = within(PWM_RT_ONE - PWM_RT_ONE / 20);
        r.dr[x] = steep ? within(1 << 20) : within(1 << 13);
    }
    if (d->rt.k == d->rt.n) {
        pwm_rt_prepare(&d->rt, &r);
    }
    pwm_rt_apply(&d->rt, &r);
}

/* A state of the range the stage keeps; at_edge: the filter at +-1 per unit. */
static void randomise(drive_segment *d, bool at_edge) {
    const int32_t one = PS_Q28_ONE;
    for (int x = 0; x < 2; x++) {
        ps_phase_q *ph = &d->ps.ph[x];
        if (at_edge) {
            int32_t sign = ((next() & 1u) != 0u) ? 1 : -1;
            ph->i_l = sign * one;
            ph->v_c = sign * (one - within(one / 64) - one / 64);
            ph->i_d = within(one);
        } else {
            ph->i_l = within(one);
            ph->v_c = within(one);
            ph->i_d = within(one);
        }
        ph->j_sh = within(one);
        d->i_fast[x] = within(one / 2);
        d->e[x] = within(one / 2);
        d->sums.v_cap[x] = (int64_t)within(one) * 40;
    }
    d->rt.fr[d->rt.cur].ph0 = next();
    d->rt.k = next() % (d->rt.n + 1u);
    frame_random(d, (next() % 8u) == 0u);
    d->ps.v_dc = (int32_t)(next() % (uint32_t)one);
    d->sums.v_dc = (int64_t)within(one) * 40;
    d->in.battery.e = (int32_t)(next() % (uint32_t)one);
    d->ps.sat_count = ((next() & 15u) == 0u) ? UINT32_MAX - 1u : next() % 1000u;
}

void suite_fast_kernel(void) {
    drive_config c = {0};
    c.inverter = DRIVE_INVERTER_SWITCHING;
    c.modulator = DRIVE_MODULATOR_SUBSTEP; /* the step the kernel computes (drive_segment.h) */
    c.down = COUPLE_ZOH;
    c.up = COUPLE_AVG;
    c.fast_ns = 2000u;
    c.fast_per_medium = 50u;
    c.medium_per_control = 8u;
    c.medium_per_slow = 8u;
    c.v_dc0_v = 600.0;
    c.stage = uuv_params_default.stage;
    c.pwm = uuv_params_default.pwm;
    c.motor = uuv_params_default.motor;
    c.control = uuv_params_default.control;
    UT_TEST("set-up: a switching drive on the real-time path");
    UT_CHECK(propeller_init(&prop, &propeller_params_default) == PROPELLER_OK);
    UT_CHECK(drive_init(&ref, &c, &prop) == DRIVE_OK);
    UT_CHECK(ref.rt_path);
    drive_battery bat = {.g_s = 0.25, .b_a = 150.0};
    drive_start(&ref, &bat);

    UT_TEST("the Thumb-2 step equals the C step bit for bit (the whole drive compared), 20 "
            "steps from each of 3000 random states (a quarter at the filter's clamp edge; "
            "random frames of the modulator, across frame ends)");
    uint32_t bad = 0u, clamps = 0u, steps = 0u, edge_steps = 0u, single = 0u;
    for (uint32_t trial = 0u; trial < 3000u; trial++) {
        randomise(&ref, (trial & 3u) == 0u);
        /* Some steps of the C into the frame, so that runs start anywhere in it. */
        for (uint32_t k = next() % 40u; k > 0u; k--) {
            drive_fast_tick(&ref);
        }
        copy_all(&ker, &ref);
        uint32_t sat0 = ref.ps.sat_count;
        for (int k = 0; k < 20; k++) {
            if (ref.rt.k == ref.rt.n) {
                /* The frame's end: the same next frame in both (the latch's work). */
                const uint32_t keep = rng;
                frame_random(&ref, false);
                rng = keep;
                frame_random(&ker, false);
            }
            const pwm_rt_event *v = &ref.rt.ev[ref.rt.next];
            const bool ev = ref.rt.k == ref.rt.next_at;
            edge_steps += (ev && v->kind == 1u) ? 1u : 0u;
            single += (ev && v->kind == (uint8_t)PWM_RT_PER_STEP) ? 1u : 0u;
            drive_fast_tick(&ref);
            drive_fast_kernel_v7m(&ker);
            steps++;
            if (!same_all(&ref, &ker)) {
                bad++;
                break;
            }
        }
        clamps += (ref.ps.sat_count != sat0) ? 1u : 0u;
    }
    ut_info("%u steps (%u with an edge, %u computed on their own), %u of 3000 runs clamped, "
            "%u differed", (unsigned)steps, (unsigned)edge_steps, (unsigned)single,
            (unsigned)clamps, (unsigned)bad);
    UT_EQ_INT(bad, 0);
    UT_CHECK(clamps > 100u && edge_steps > 1000u && single > 1000u);

    UT_TEST("drive_fast_step() takes the kernel on the real-time path only, the C off it "
            "or without a kernel");
    copy_all(&ker, &ref);
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.fast_now == drive_fast_kernel_v7m);
    drive_use_fast_kernel(&ker, NULL);
    UT_CHECK(ker.fast_now == NULL);
    ker.rt_path = false; /* as a fault or a trip leaves it */
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.fast_now == NULL);
    /* The sampled modulator is the C's only: no kernel for it. */
    c.modulator = DRIVE_MODULATOR_SAMPLED;
    UT_CHECK(drive_init(&ker, &c, &prop) == DRIVE_OK);
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.rt_path && ker.fast_now == NULL);
}

#else

void suite_fast_kernel(void) {}

#endif

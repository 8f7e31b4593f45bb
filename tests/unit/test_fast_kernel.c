/*
 * A port's real-time fast step against the C's: in the fixed firmware
 * images (FW_FAST_KERNEL=1) the Thumb-2 kernel of ports/cortexm and
 * drive_segment_fixed.c's own step run side by side from the same random
 * states, and every field either writes must agree bit for bit after each
 * step: the modulator, the legs, the power stage (the clamps and their
 * count included), the motor's fast currents and the frame sums. The
 * states are drawn over the whole range the stage keeps them in, and some
 * start at its edge, so that the clamps act. Builds without a kernel have
 * nothing to compare and run no test.
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

static uint32_t next(void) {
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* Uniform in [-lim, lim]. */
static int32_t within(int32_t lim) {
    return (int32_t)(next() % (2u * (uint32_t)lim + 1u)) - lim;
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
        d->rt.r[x] = within(PWM_RT_ONE);
        d->rt.dr[x] = within(1 << 16);
    }
    d->rt.ph_c = next();
    d->ps.v_dc = (int32_t)(next() % (uint32_t)one);
    d->sums.v_dc = (int64_t)within(one) * 40;
    d->in.battery.e = (int32_t)(next() % (uint32_t)one);
    d->ps.sat_count = ((next() & 15u) == 0u) ? UINT32_MAX - 1u : next() % 1000u;
}

/* Every field the real-time step writes, compared. */
static bool same(const drive_segment *a, const drive_segment *b) {
    bool ok = a->rt.ph_c == b->rt.ph_c && a->ps.v_dc == b->ps.v_dc &&
              a->ps.i_dc == b->ps.i_dc && a->ps.sat_count == b->ps.sat_count &&
              a->sums.v_dc == b->sums.v_dc;
    for (int x = 0; x < 3; x++) {
        ok = ok && a->s[x] == b->s[x];
    }
    for (int x = 0; x < 2; x++) {
        const ps_phase_q *p = &a->ps.ph[x];
        const ps_phase_q *q = &b->ps.ph[x];
        ok = ok && p->i_l == q->i_l && p->v_c == q->v_c && p->i_d == q->i_d &&
             p->j_sh == q->j_sh && a->ps.u[x] == b->ps.u[x] && a->i_fast[x] == b->i_fast[x] &&
             a->rt.r[x] == b->rt.r[x] && a->sums.v_cap[x] == b->sums.v_cap[x];
    }
    return ok;
}

void suite_fast_kernel(void) {
    drive_config c = {0};
    c.inverter = DRIVE_INVERTER_SWITCHING;
    c.modulator = DRIVE_MODULATOR_SAMPLED; /* the step the kernel computes (drive_segment.h) */
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
    UT_CHECK(ref.plain);
    drive_battery bat = {.g_s = 0.25, .b_a = 150.0};
    drive_start(&ref, &bat);

    UT_TEST("the Thumb-2 step equals the C step bit for bit, 20 steps from each of 3000 "
            "random states (a quarter at the filter's clamp edge)");
    uint32_t bad = 0u, clamps = 0u, steps = 0u;
    for (uint32_t trial = 0u; trial < 3000u; trial++) {
        randomise(&ref, (trial & 3u) == 0u);
        ker = ref;
        uint32_t sat0 = ref.ps.sat_count;
        for (int k = 0; k < 20; k++) {
            drive_fast_tick(&ref);
            drive_fast_kernel_v7m(&ker);
            steps++;
            if (!same(&ref, &ker)) {
                bad++;
                break;
            }
        }
        clamps += (ref.ps.sat_count != sat0) ? 1u : 0u;
    }
    ut_info("%u steps, %u of 3000 runs clamped, %u differed", (unsigned)steps, (unsigned)clamps,
            (unsigned)bad);
    UT_EQ_INT(bad, 0);
    UT_CHECK(clamps > 100u);

    UT_TEST("drive_fast_step() takes the kernel on the real-time path only, the C off it "
            "or without a kernel");
    ker = ref;
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.fast_now == drive_fast_kernel_v7m);
    drive_use_fast_kernel(&ker, NULL);
    UT_CHECK(ker.fast_now == NULL);
    ker.plain = false; /* as a fault or a trip leaves it */
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.fast_now == NULL);
    /* The sub-step modulator is the C's only: no kernel for it. */
    c.modulator = DRIVE_MODULATOR_SUBSTEP;
    UT_CHECK(drive_init(&ker, &c, &prop) == DRIVE_OK);
    drive_use_fast_kernel(&ker, drive_fast_kernel_v7m);
    UT_CHECK(ker.plain && ker.fast_now == NULL);
}

#else

void suite_fast_kernel(void) {}

#endif

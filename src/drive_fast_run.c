/*
 * drive_fast_run(): the desk's runs of fast steps (drive_segment.h), for
 * either numeric build. On the real-time path (switching inverter without
 * dead time, held EMF, mean or sampled coupling) the run goes in passes of
 * up to RT_SEGS segments, each in two halves:
 *
 *   modulator   the modulator is stepped ahead over the pass on its own
 *               (it does not depend on the stage there): the sub-step
 *               frame plan's held steps as runs (drive_rt_held(),
 *               pwm_rt_skip()), its event steps one by one with their
 *               duties;
 *   stage       the stage's steps over the segments (rt_stage_run()) on
 *               local copies of the fields the real-time step uses
 *               (drive_rt_step.h), a held run with its legs' factors
 *               formed once in whole units (ps_fast_held_legs_*), an
 *               event step with its duties.
 *
 * The stage's half calls nothing, so that its state stays in registers
 * from step to step. The sampled modulator, which is integer and calls
 * nothing, runs with the stage in one loop (rt_sampled_run()), each
 * step's states as held legs. Any other path takes n drive_fast_step()s.
 * tests/unit/test_executive.c checks that both give drive_fast_tick()'s
 * bits.
 */
#include <stdint.h>

#include "drive_rt_step.h"
#include "drive_segment.h"

#define RT_SEGS 16u /* segments a pass steps the modulator ahead */

/* One segment of a pass: m >= 1 steps on held states, or one step with duties. */
typedef struct {
    uint32_t m;        /* held steps, or 0: one step with the duties */
    int32_t v[3];      /* the held states (0 or 1), or the step's duties (Q15) */
} rt_seg;

/*
 * The stage's steps over the pass's ns segments, on local copies of the
 * drive's stage, currents and frame sums. Out of line and without calls,
 * so that the stage's state stays in registers over the pass.
 */
static void rt_stage_run(drive_segment *d, const rt_seg *seg, uint32_t ns)
    __attribute__((noinline));
static void rt_stage_run(drive_segment *d, const rt_seg *seg, uint32_t ns) {
    DRIVE_NUM(power_stage) ps = d->ps;
    const DRIVE_NUM(ps_battery) bat = d->in.battery;
    num_val i_fast[2] = {d->i_fast[0], d->i_fast[1]};
    const num_val e[2] = {d->e[0], d->e[1]};
    num_sum v_cap[2] = {d->sums.v_cap[0], d->sums.v_cap[1]};
    num_sum v_dc = d->sums.v_dc;
    drive_rt_on r = {&d->rt, d->s, false, &ps, &bat, i_fast, e, d->NUM_RT_GAIN, v_cap, &v_dc};
    for (uint32_t i = 0u; i < ns; i++) {
        DRIVE_NUM(ps_legs) l;
        if (seg[i].m == 0u) {
            DRIVE_NUM(ps_fast_legs)(seg[i].v, &l);
            drive_rt_stage(&r, &l, false);
        } else {
            DRIVE_NUM(ps_fast_held_legs)(seg[i].v, &l);
            for (uint32_t j = seg[i].m; j != 0u; j--) {
                drive_rt_stage(&r, &l, true);
            }
        }
    }
    d->ps = ps;
    d->sums.v_dc = v_dc;
    for (int x = 0; x < 2; x++) {
        d->i_fast[x] = i_fast[x];
        d->sums.v_cap[x] = v_cap[x];
    }
}

/*
 * n steps with the sampled modulator, which is integer and calls nothing:
 * modulator and stage in one loop, each step's states as held legs.
 */
static void rt_sampled_run(drive_segment *d, uint32_t n) __attribute__((noinline));
static void rt_sampled_run(drive_segment *d, uint32_t n) {
    DRIVE_NUM(power_stage) ps = d->ps;
    const DRIVE_NUM(ps_battery) bat = d->in.battery;
    int32_t s[3] = {d->s[0], d->s[1], d->s[2]};
    num_val i_fast[2] = {d->i_fast[0], d->i_fast[1]};
    const num_val e[2] = {d->e[0], d->e[1]};
    num_sum v_cap[2] = {d->sums.v_cap[0], d->sums.v_cap[1]};
    num_sum v_dc = d->sums.v_dc;
    drive_rt_on r = {&d->rt, s, true, &ps, &bat, i_fast, e, d->NUM_RT_GAIN, v_cap, &v_dc};
    for (uint32_t k = 0u; k < n; k++) {
        DRIVE_NUM(ps_legs) l;
        pwm_rt_step(&d->rt, s);
        DRIVE_NUM(ps_fast_held_legs)(s, &l);
        drive_rt_stage(&r, &l, true);
    }
    d->ps = ps;
    d->sums.v_dc = v_dc;
    for (int x = 0; x < 3; x++) {
        d->s[x] = s[x];
    }
    for (int x = 0; x < 2; x++) {
        d->i_fast[x] = i_fast[x];
        d->sums.v_cap[x] = v_cap[x];
    }
}

/*
 * The sub-step modulator's part of up to n steps as at most RT_SEGS segments;
 * returns the steps taken, at least 1.
 */
static uint32_t rt_modulator_ahead(drive_segment *d, uint32_t n, rt_seg *seg, uint32_t *ns) {
    pwm_rt *p = &d->rt;
    int32_t *s = d->s;
    uint32_t taken = 0u;
    uint32_t k = 0u;
    while ((taken < n) && (k < RT_SEGS)) {
        int32_t duty[3];
        const uint32_t held = drive_rt_held(p);
        const uint32_t m = (held < n - taken) ? held : n - taken;
        if (m == 0u) {
            pwm_rt_substep(p, s, duty);
            seg[k] = (rt_seg){0u, {duty[0], duty[1], duty[2]}};
            taken++;
        } else {
            seg[k] = (rt_seg){m, {s[0], s[1], s[2]}};
            pwm_rt_skip(p, m);
            taken += m;
        }
        k++;
    }
    *ns = k;
    return taken;
}

void drive_fast_run(drive_segment *d, uint32_t n) {
    if (!d->rt_path || d->fast_now != NULL) {
        for (uint32_t k = 0u; k < n; k++) {
            drive_fast_step(d);
        }
        return;
    }
    if (d->cfg.modulator == DRIVE_MODULATOR_SAMPLED) {
        rt_sampled_run(d, n);
    } else {
        uint32_t left = n;
        while (left > 0u) {
            rt_seg seg[RT_SEGS];
            uint32_t ns = 0u;
            const uint32_t taken = rt_modulator_ahead(d, left, seg, &ns);
            rt_stage_run(d, seg, ns);
            left -= taken;
        }
    }
}

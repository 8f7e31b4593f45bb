/*
 * drive_fast_run(): the desk's runs of fast steps (drive_segment.h), for
 * either numeric build. On the real-time path (switching inverter without
 * dead time, held EMF, mean or sampled coupling)
 * the fields the real-time step uses (drive_rt_step.h, the step
 * drive_fast_tick() takes) are copied into locals, stepped n times
 * and copied back, so that they stay in registers between the steps
 * instead of going through the drive in memory each step; with the
 * sub-step modulator the frame plan's held steps go as runs of their own
 * (drive_rt_held_on()), its event steps one by one. Any other path
 * takes n drive_fast_step()s. tests/unit/test_executive.c checks that
 * both give the same bits.
 */
#include <stdint.h>

#include "drive_rt_step.h"
#include "drive_segment.h"

/*
 * n real-time steps on local copies of the step's fields; sampled selects
 * the modulator (a constant at each call, inlined, so that each call is
 * its own loop). The modulator and the legs' states are copies of their own (the
 * plan's event step takes their address), the stage's fields others,
 * which then stay in registers.
 */
static inline void rt_run(drive_segment *d, uint32_t n, const bool sampled)
    __attribute__((always_inline));
static inline void rt_run(drive_segment *d, uint32_t n, const bool sampled) {
    pwm_rt rt = d->rt;
    int32_t s[3] = {d->s[0], d->s[1], d->s[2]};
    DRIVE_NUM(power_stage) ps = d->ps;
    const DRIVE_NUM(ps_battery) bat = d->in.battery;
    num_val i_fast[2] = {d->i_fast[0], d->i_fast[1]};
    const num_val e[2] = {d->e[0], d->e[1]};
    num_sum v_cap[2] = {d->sums.v_cap[0], d->sums.v_cap[1]};
    num_sum v_dc = d->sums.v_dc;
    drive_rt_on r = {&rt, s, sampled, &ps, &bat, i_fast, e, d->NUM_RT_GAIN, v_cap, &v_dc};
    if (sampled) {
        for (uint32_t k = 0u; k < n; k++) {
            drive_rt_step_on(&r);
        }
    } else {
        /* The plan's held steps as runs of them, its event steps one by one. */
        uint32_t k = 0u;
        while (k < n) {
            const uint32_t held = drive_rt_held(&rt);
            const uint32_t m = (held < n - k) ? held : n - k;
            if (m == 0u) {
                drive_rt_step_on(&r);
                k++;
            } else {
                drive_rt_held_on(&r, m);
                k += m;
            }
        }
    }
    d->rt = rt;
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

void drive_fast_run(drive_segment *d, uint32_t n) {
    if (!d->rt_path || d->fast_now != NULL) {
        for (uint32_t k = 0u; k < n; k++) {
            drive_fast_step(d);
        }
        return;
    }
    if (d->cfg.modulator == DRIVE_MODULATOR_SAMPLED) {
        rt_run(d, n, true);
    } else {
        rt_run(d, n, false);
    }
}

/*
 * drive_fast_run(): the desk's runs of fast steps (drive_segment.h), for
 * either numeric build. On the real-time path (switching inverter without
 * dead time, held EMF, mean or sampled coupling)
 * the fields the real-time step uses (drive_rt_step.h, the step
 * drive_fast_tick() takes) are copied into a local drive, stepped n times
 * and copied back, so that they stay in registers between the steps
 * instead of going through the drive in memory each step. Any other path
 * takes n drive_fast_step()s. tests/unit/test_executive.c checks that
 * both give the same bits.
 */
#include <stdint.h>

#include "drive_rt_step.h"
#include "drive_segment.h"

/*
 * n real-time steps on a local drive that holds the step's fields;
 * sampled selects the modulator (a constant at each call, so that each
 * call is its own loop).
 */
static inline void rt_run(drive_segment *d, uint32_t n, const bool sampled) {
    drive_segment r; /* only the fields drive_rt_step() uses are set and read */
    r.cfg.modulator = sampled ? DRIVE_MODULATOR_SAMPLED : DRIVE_MODULATOR_SUBSTEP;
    r.rt = d->rt;
    r.ps = d->ps;
    r.in.battery = d->in.battery;
    r.NUM_RT_GAIN = d->NUM_RT_GAIN;
    r.sums.v_dc = d->sums.v_dc;
    for (int x = 0; x < 3; x++) {
        r.s[x] = d->s[x];
    }
    for (int x = 0; x < 2; x++) {
        r.i_fast[x] = d->i_fast[x];
        r.e[x] = d->e[x];
        r.sums.v_cap[x] = d->sums.v_cap[x];
    }
    for (uint32_t k = 0u; k < n; k++) {
        drive_rt_step(&r);
    }
    d->rt = r.rt;
    d->ps = r.ps;
    d->sums.v_dc = r.sums.v_dc;
    for (int x = 0; x < 3; x++) {
        d->s[x] = r.s[x];
    }
    for (int x = 0; x < 2; x++) {
        d->i_fast[x] = r.i_fast[x];
        d->sums.v_cap[x] = r.sums.v_cap[x];
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

/*
 * The drive's real-time 2 us step, written once for both numeric builds
 * (the build's arithmetic from its numeric adapter, drive_num_q.h or
 * drive_num_f32.h): the switching inverter without dead time, the EMF
 * held over the frame, no faults (the drive's real-time path).
 *
 *   modulator   the real-time modulator's duties (pwm_rt.h): sub-step or sampled;
 *   stage       the power stage's step (power_stage_fast.h): the inverter,
 *               then per filter phase its states, at once followed by the
 *               motor's fast companion of that phase, i + (v - e) gain,
 *               and the frame sum of v, so that little of the phase stays
 *               alive in registers for the next; then the DC link and its
 *               frame sum.
 *
 * It reads and writes only these fields of the drive: cfg.modulator, rt,
 * s, ps, in.battery, i_fast, e, the gain (NUM_RT_GAIN), sums.v_cap,
 * sums.v_dc.
 * drive_fast_tick() (drive_segment.c) takes it on the drive itself, the
 * interrupt's work; drive_fast_run() (drive_fast_run.c) on a local drive
 * holding copies of these fields only, which the compiler keeps in
 * registers over a run of steps. The Thumb-2 kernel of the fixed M4 and
 * M7 images (ports/cortexm/fast_kernel_v7m.S) computes the same step with
 * the sub-step modulator and its frame plan, tested against it
 * (tests/unit/test_fast_kernel.c); with the sampled modulator the images
 * run this C.
 *
 * The other fast step, fast_tick_general() in drive_segment.c, takes every
 * other configuration: the event modulator, dead time, a moving EMF,
 * faults, the filter coupling, the energy audit. On the switching inverter
 * it runs the same power stage step (ps_fast_step_call_*()) on the duties
 * the faults leave, so that without faults it gives this step's bits. It
 * stays a step of its own, out of line, because its branches and the
 * state they need would cost the 2 us interrupt registers and
 * instructions on the path that has to meet the budget.
 */
#ifndef UUV_DRIVE_RT_STEP_H
#define UUV_DRIVE_RT_STEP_H

#include <stdbool.h>
#include <stdint.h>

#include "drive_segment.h"
#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/pwm/pwm_rt.h"

/* Filter phase x of the step, its fast companion and its frame sum. */
static inline void drive_rt_phase(drive_segment *d, DRIVE_NUM(ps_fast) *f, int x) {
    DRIVE_NUM(power_stage) *ps = &d->ps;
    DRIVE_NUM(ps_fast_phase)(ps, f, x, d->i_fast[x]);
    const num_val v = ps->ph[x].v_c;
    d->i_fast[x] = num_companion_rt(d->i_fast[x], v, d->e[x], d->NUM_RT_GAIN);
    d->sums.v_cap[x] += v;
}

/* The real-time modulator's duties for the step (pwm_rt.h): sampled or sub-step, as configured. */
static inline void drive_rt_duties(drive_segment *d, int32_t duty[3]) {
    pwm_rt_duties(&d->rt, d->cfg.modulator == DRIVE_MODULATOR_SAMPLED, d->s, duty);
}

/* One step. */
static inline void drive_rt_step(drive_segment *d) {
    DRIVE_NUM(power_stage) *ps = &d->ps;
    DRIVE_NUM(ps_fast) f;
    int32_t duty[3];
    drive_rt_duties(d, duty);
    DRIVE_NUM(ps_fast_begin)(ps, duty, &f);
    drive_rt_phase(d, &f, 0);
    drive_rt_phase(d, &f, 1);
    DRIVE_NUM(ps_fast_end)(ps, &d->in.battery, &f);
    d->sums.v_dc += ps->v_dc;
}

#endif /* UUV_DRIVE_RT_STEP_H */

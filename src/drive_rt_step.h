/*
 * The drive's real-time 2 us step, written once for both numeric builds
 * (the build's arithmetic from its numeric adapter, drive_num_q.h or
 * drive_num_f32.h): the switching inverter without dead time, the EMF
 * held over the frame, no faults (the drive's real-time path).
 *
 *   modulator   the real-time modulator's duties (pwm_rt.h): sub-step or sampled;
 *   stage       the power stage's step (power_stage_fast.h): the legs'
 *               factors of the duties and the inverter, then per filter
 *               phase its states, at once followed by the motor's fast
 *               companion of that phase, i + (v - e) gain, and the frame
 *               sum of v, so that little of the phase stays alive in
 *               registers for the next; then the DC link and its frame sum.
 *
 * It reads and writes only these fields of the drive (drive_rt_on):
 * cfg.modulator, rt, s, ps, in.battery, i_fast, e, the gain
 * (NUM_RT_GAIN), sums.v_cap, sums.v_dc.
 * drive_fast_tick() (drive_segment.c) takes it on the drive itself, the
 * interrupt's work; drive_fast_run() (drive_fast_run.c) takes its
 * modulator ahead over a pass of steps and then its stage part
 * (drive_rt_stage()) on local copies of the stage's fields, which the
 * compiler keeps in registers, the frame plan's held steps as runs with
 * their legs' factors formed once in whole units (ps_fast_held_legs_*:
 * the same bits; tests/unit/test_executive.c checks the run's). The Thumb-2 kernel of the fixed M4 and
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

/*
 * What the step works on: these fields of a drive (drive_rt_step()), or a
 * run's copies of them (drive_fast_run.c), in locals apart from the
 * modulator's, whose address the plan's event step takes, so that the
 * stage's stay in registers.
 */
typedef struct {
    pwm_rt *rt;
    int32_t *s;                       /* the legs' states, 3 */
    bool sampled;                     /* the modulator: sampled, or sub-step */
    DRIVE_NUM(power_stage) *ps;
    const DRIVE_NUM(ps_battery) *bat;
    num_val *i_fast;                  /* the fast companion's currents, 2 */
    const num_val *e;                 /* its EMF, 2 */
    num_val gain;                     /* its gain (NUM_RT_GAIN) */
    num_sum *v_cap;                   /* the frame sums, 2 ... */
    num_sum *v_dc;                    /* ... and 1 */
} drive_rt_on;

/*
 * Filter phase x of the step, its fast companion and its frame sum. The
 * phase and the stage are inlined wherever they are used (GCC takes them
 * out of line otherwise, the phase on the float targets, the stage in the
 * fixed desk's runs, passing r): r's pointers are then the drive's fields
 * or the run's locals.
 */
static inline void drive_rt_phase(drive_rt_on *r, DRIVE_NUM(ps_fast) *f,
                                  const DRIVE_NUM(ps_legs) *l, int x, bool whole)
    __attribute__((always_inline));
static inline void drive_rt_phase(drive_rt_on *r, DRIVE_NUM(ps_fast) *f,
                                  const DRIVE_NUM(ps_legs) *l, int x, bool whole) {
    if (whole) {
        DRIVE_NUM(ps_fast_phase_held)(r->ps, f, l, x, r->i_fast[x]); /* held legs' form */
    } else {
        DRIVE_NUM(ps_fast_phase)(r->ps, f, x, r->i_fast[x]);
    }
    const num_val v = r->ps->ph[x].v_c;
    r->i_fast[x] = num_companion_rt(r->i_fast[x], v, r->e[x], r->gain);
    r->v_cap[x] += v;
}

/*
 * The stage's part of a step with the legs' factors l (power_stage_fast.h);
 * whole: l->whole, as a constant at each call, so that each call compiles
 * to its one form.
 */
static inline void drive_rt_stage(drive_rt_on *r, const DRIVE_NUM(ps_legs) *l, bool whole)
    __attribute__((always_inline));
static inline void drive_rt_stage(drive_rt_on *r, const DRIVE_NUM(ps_legs) *l, bool whole) {
    DRIVE_NUM(power_stage) *ps = r->ps;
    DRIVE_NUM(ps_fast) f;
    DRIVE_NUM(ps_fast_begin)(ps, l, &f);
    drive_rt_phase(r, &f, l, 0, whole);
    drive_rt_phase(r, &f, l, 1, whole);
    DRIVE_NUM(ps_fast_end)(ps, r->bat, &f);
    *r->v_dc += ps->v_dc;
}

/* One step on r (inlined, as the phase and the stage are). */
static inline void drive_rt_step_on(drive_rt_on *r) __attribute__((always_inline));
static inline void drive_rt_step_on(drive_rt_on *r) {
    int32_t duty[3];
    DRIVE_NUM(ps_legs) l;
    pwm_rt_duties(r->rt, r->sampled, r->s, duty);
    DRIVE_NUM(ps_fast_legs)(duty, &l);
    drive_rt_stage(r, &l, false);
}

/* One step on the drive d. */
static inline void drive_rt_step(drive_segment *d) {
    const bool sampled = d->cfg.modulator == DRIVE_MODULATOR_SAMPLED;
    drive_rt_on r = {&d->rt,    d->s, sampled,         &d->ps,        &d->in.battery,
                     d->i_fast, d->e, d->NUM_RT_GAIN, d->sums.v_cap, &d->sums.v_dc};
    drive_rt_step_on(&r);
}

/*
 * The steps from now in which the sub-step modulator's frame plan applies
 * the legs' held states (pwm_rt_substep(): every step before the plan's
 * next event, none in a frame computed step by step), modulo 2^32 as the
 * plan counts them; 0 at an event step and in a lean image.
 */
static inline uint32_t drive_rt_held(const pwm_rt *p) {
    return (UUV_LEAN_IMAGE != 0) ? 0u : p->next_at - p->k;
}

#endif /* UUV_DRIVE_RT_STEP_H */

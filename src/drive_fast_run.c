/*
 * drive_fast_run(): the desk's runs of fast steps (drive_segment.h), for
 * either numeric build. On the real-time path (switching inverter without
 * dead time, held EMF, mean or sampled coupling: the drive's "plain" path)
 * the step's state is copied into locals, stepped n times and copied back, so that it
 * stays in registers between the steps instead of going through the drive
 * in memory each step. Any other path takes n drive_fast_step()s.
 *
 * The step is drive_fast_tick()'s real-time step (fast_tick_plain() in
 * drive_segment.c), composed of the same
 * pieces (models/drive/inverter/power_stage_fast.h, models/drive/pwm/pwm_rt.h) in the same order,
 * here on the locals. It is a copy, not a shared function, so that the
 * interrupt's step keeps the code the compiler gives it on its own
 * (measured per target in docs/firmware.md); tests/unit/test_executive.c
 * checks that both give the same bits.
 *
 * The names without a twin suffix are the build's (UUV_NUMERIC).
 */
#include <stdint.h>

#include "drive_segment.h"
#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/pwm/pwm_rt.h"

#if UUV_NUMERIC == UUV_NUMERIC_FIXED
typedef power_stage_q plain_stage;
typedef int32_t plain_val; /* Q3.28 */
typedef int64_t plain_sum; /* Q3.28 summed */
typedef ps_battery_q plain_bat;
typedef ps_fast_q plain_fast;
#define plain_begin ps_fast_begin_q
#define plain_phase ps_fast_phase_q
#define plain_end ps_fast_end_q

/* The motor's fast companion, i + round((v - e) k32 / 2^32). */
static inline int32_t plain_companion(int32_t i, int32_t v, int32_t e, int32_t k32) {
    return ps_hi_q(ps_mac_q(ps_acc_q(i), v - e, k32));
}

static inline int32_t plain_gain(const drive_segment *d) { return d->k32; }
#else
typedef power_stage_f32 plain_stage;
typedef float plain_val; /* [A], [V] */
typedef float plain_sum; /* [V] summed */
typedef ps_battery_f32 plain_bat;
typedef ps_fast_f32 plain_fast;
#define plain_begin ps_fast_begin_f32
#define plain_phase ps_fast_phase_f32
#define plain_end ps_fast_end_f32

/* The motor's fast companion, i + (v - e) k_l. */
static inline float plain_companion(float i, float v, float e, float k_l) {
    return i + (v - e) * k_l;
}

static inline float plain_gain(const drive_segment *d) { return d->k_l; }
#endif

/*
 * n real-time steps on the drive's state in locals; substep selects the
 * modulator (a constant at each call, so that each call is its own loop).
 */
static inline void plain_run(drive_segment *d, uint32_t n, const bool substep) {
    pwm_rt rt = d->rt;
    int32_t s[3] = {d->s[0], d->s[1], d->s[2]};
    plain_stage ps = d->ps;
    plain_val i_fast[2] = {d->i_fast[0], d->i_fast[1]};
    const plain_val e[2] = {d->e[0], d->e[1]};
    const plain_val gain = plain_gain(d);
    plain_sum v_cap[2] = {d->sums.v_cap[0], d->sums.v_cap[1]};
    plain_sum v_dc = d->sums.v_dc;
    const plain_bat bat = d->in.battery;
    for (uint32_t k = 0u; k < n; k++) {
        /* fast_tick_plain(): modulator, stage, then per filter phase its
         * companion and frame sum, then the DC link. */
        plain_fast f;
        int32_t duty[3];
        if (substep) {
            pwm_rt_substep(&rt, s, duty);
        } else {
            pwm_rt_sampled(&rt, s, duty);
        }
        plain_begin(&ps, duty, &f);
        for (int x = 0; x < 2; x++) {
            plain_phase(&ps, &f, x, i_fast[x]);
            const plain_val v = ps.ph[x].v_c;
            i_fast[x] = plain_companion(i_fast[x], v, e[x], gain);
            v_cap[x] += v;
        }
        plain_end(&ps, &bat, &f);
        v_dc += ps.v_dc;
    }
    d->rt = rt;
    for (int x = 0; x < 3; x++) {
        d->s[x] = s[x];
    }
    d->ps = ps;
    for (int x = 0; x < 2; x++) {
        d->i_fast[x] = i_fast[x];
        d->sums.v_cap[x] = v_cap[x];
    }
    d->sums.v_dc = v_dc;
}

void drive_fast_run(drive_segment *d, uint32_t n) {
    if (!d->plain || d->fast_now != NULL) {
        for (uint32_t k = 0u; k < n; k++) {
            drive_fast_step(d);
        }
        return;
    }
    if (d->cfg.modulator == DRIVE_MODULATOR_SAMPLED) {
        plain_run(d, n, false);
    } else {
        plain_run(d, n, true);
    }
}

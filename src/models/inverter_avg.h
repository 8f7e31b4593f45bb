/*
 * The averaged inverter: the layered alternative of the switching power
 * stage (paper section 3), runnable at the motor's 100 us frame. The same
 * terminals and the same DC link and LC filter (power_stage.h), driven by
 * the leg duty cycles d_x = (1 + m sin(theta_x)) / 2 of the modulator's
 * references (pwm_average_*, taken at the middle of each step) instead of
 * switching: no ripple, the same fundamental.
 *
 * Step. One call advances one frame of n_sub equal substeps; each substep
 * takes the duties and runs power_stage_step_* at frame / n_sub, with the
 * motor currents and the battery companion held over the frame. Why
 * substeps: the trapezoidal rule is A-stable, so the filter stays stable at
 * any step, but it maps the analogue resonance w0 to the digital one
 * (2/T) atan(w0 T / 2): at T = 100 us the 1.07 kHz corner lands 3.5 %
 * low, at 25 us (n_sub = 4) 0.24 %. The fundamental (<= 55 Hz) is within
 * 1e-4 either way; the DC link's forward Euler needs T G / C_dc < 2 (the
 * battery conversion keeps it below 0.5). docs/drive_power.md has the
 * measured comparison with the switching model.
 */
#ifndef UUV_INVERTER_AVG_H
#define UUV_INVERTER_AVG_H

#include <stdint.h>

#include "models/power_stage.h"
#include "models/pwm.h"

#define INVERTER_AVG_SUB_MAX 64u /* most substeps per frame */

typedef enum {
    INVERTER_AVG_OK = 0,
    INVERTER_AVG_ERR_NULL,   /* a pointer argument was NULL */
    INVERTER_AVG_ERR_SUB,    /* n_sub not in 1..INVERTER_AVG_SUB_MAX, or frame not a multiple */
    INVERTER_AVG_ERR_PWM,    /* the modulator rejected its parameters */
    INVERTER_AVG_ERR_STAGE   /* the power stage rejected its parameters */
} inverter_avg_status;

typedef struct {
    pwm_q mod;           /* references only (its carrier is not used) */
    power_stage_q stage; /* stepped at frame / n_sub */
    uint32_t n_sub;
} inverter_avg_q;

typedef struct {
    pwm_f32 mod;
    power_stage_f32 stage;
    uint32_t n_sub;
} inverter_avg_f32;

/*
 * Initialises the modulator (in mode PWM_AVERAGED whatever pp says; only
 * its reference phase is used) and the power stage at the substep
 * frame_ns / n_sub (frame_ns must be a multiple of n_sub). The power-stage
 * parameters must outlive the instance. On an error the instance may be
 * partly written.
 */
inverter_avg_status inverter_avg_init_q(inverter_avg_q *inv, const pwm_params *pp,
                                        const power_stage_params *sp, uint32_t frame_ns,
                                        uint32_t n_sub, double v_dc0_v);
inverter_avg_status inverter_avg_init_f32(inverter_avg_f32 *inv, const pwm_params *pp,
                                          const power_stage_params *sp, uint32_t frame_ns,
                                          uint32_t n_sub, double v_dc0_v);

/*
 * One frame: n_sub substeps. in->duty is ignored (the duties come from the
 * references); in->battery must come from power_stage_battery_*() of
 * inv->stage (it depends on the substep). Total; integer only in the fixed
 * twin.
 */
void inverter_avg_step_q(inverter_avg_q *inv, const power_stage_in_q *in);
void inverter_avg_step_f32(inverter_avg_f32 *inv, const power_stage_in_f32 *in);

#endif /* UUV_INVERTER_AVG_H */

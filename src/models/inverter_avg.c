/*
 * The averaged inverter, both twins (inverter_avg.h): the modulator's
 * averaged duties feeding the power stage, n_sub substeps per frame.
 */
#include "models/inverter_avg.h"

#include <stddef.h>

static int inverter_avg_sub_ok(uint32_t frame_ns, uint32_t n_sub) {
    return n_sub >= 1u && n_sub <= INVERTER_AVG_SUB_MAX && (frame_ns % n_sub) == 0u;
}

inverter_avg_status inverter_avg_init_q(inverter_avg_q *inv, const pwm_params *pp,
                                        const power_stage_params *sp, uint32_t frame_ns,
                                        uint32_t n_sub, double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL || sp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    if (!inverter_avg_sub_ok(frame_ns, n_sub)) {
        return INVERTER_AVG_ERR_SUB;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_q(&inv->mod, &mode, frame_ns / n_sub) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    if (power_stage_init_q(&inv->stage, sp, frame_ns / n_sub, v_dc0_v) != PS_OK) {
        return INVERTER_AVG_ERR_STAGE;
    }
    inv->n_sub = n_sub;
    return INVERTER_AVG_OK;
}

inverter_avg_status inverter_avg_init_f32(inverter_avg_f32 *inv, const pwm_params *pp,
                                          const power_stage_params *sp, uint32_t frame_ns,
                                          uint32_t n_sub, double v_dc0_v) {
    pwm_params mode;
    if (inv == NULL || pp == NULL || sp == NULL) {
        return INVERTER_AVG_ERR_NULL;
    }
    if (!inverter_avg_sub_ok(frame_ns, n_sub)) {
        return INVERTER_AVG_ERR_SUB;
    }
    mode = *pp;
    mode.edges = PWM_AVERAGED;
    if (pwm_init_f32(&inv->mod, &mode, frame_ns / n_sub) != PWM_OK) {
        return INVERTER_AVG_ERR_PWM;
    }
    if (power_stage_init_f32(&inv->stage, sp, frame_ns / n_sub, v_dc0_v) != PS_OK) {
        return INVERTER_AVG_ERR_STAGE;
    }
    inv->n_sub = n_sub;
    return INVERTER_AVG_OK;
}

void inverter_avg_step_q(inverter_avg_q *inv, const power_stage_in_q *in) {
    power_stage_in_q sub = *in;
    pwm_out_q d;
    uint32_t i;
    for (i = 0u; i < inv->n_sub; i++) {
        pwm_average_q(&inv->mod, &d);
        sub.duty[0] = d.duty[0];
        sub.duty[1] = d.duty[1];
        sub.duty[2] = d.duty[2];
        power_stage_step_q(&inv->stage, &sub);
    }
}

void inverter_avg_step_f32(inverter_avg_f32 *inv, const power_stage_in_f32 *in) {
    power_stage_in_f32 sub = *in;
    pwm_out_f32 d;
    uint32_t i;
    for (i = 0u; i < inv->n_sub; i++) {
        pwm_average_f32(&inv->mod, &d);
        sub.duty[0] = d.duty[0];
        sub.duty[1] = d.duty[1];
        sub.duty[2] = d.duty[2];
        power_stage_step_f32(&inv->stage, &sub);
    }
}

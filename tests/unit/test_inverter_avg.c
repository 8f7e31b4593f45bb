/*
 * Set-up of the averaged inverter (inverter_avg.h), both twins: each error
 * the header lists, in the order it is checked (NULL pointers, the substep
 * count, the modulator's step range of [100 ns, 1 ms], the power stage's
 * initial DC-link voltage range [0, 1024) V), and the accepted limits. Its
 * step is tested against the switching path in test_power_stage.c.
 */
#include <stddef.h>

#include "models/inverter_avg.h"
#include "ut.h"

void suite_inverter_avg(void);

/* Static: the instances hold a whole power stage, kept off the small target stacks. */
static inverter_avg_q inv_q;
static inverter_avg_f32 inv_f;

/* The status of both twins' init for the same arguments; -1 when they differ. */
static int init_both(bool null_inv, const pwm_params *pp, const power_stage_params *sp,
                     uint32_t frame_ns, uint32_t n_sub, double v_dc0_v) {
    inverter_avg_status q = inverter_avg_init_q(null_inv ? NULL : &inv_q, pp, sp, frame_ns, n_sub,
                                                v_dc0_v);
    inverter_avg_status f = inverter_avg_init_f32(null_inv ? NULL : &inv_f, pp, sp, frame_ns,
                                                  n_sub, v_dc0_v);
    return (q == f) ? (int)q : -1;
}

void suite_inverter_avg(void) {
    const pwm_params *pp = &pwm_params_default;
    const power_stage_params *sp = &power_stage_params_default;

    UT_TEST("init, both twins: a NULL instance, modulator or stage parameter set is ERR_NULL");
    UT_EQ_INT(init_both(true, pp, sp, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(init_both(false, NULL, sp, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);
    UT_EQ_INT(init_both(false, pp, NULL, 100000u, 50u, 500.0), INVERTER_AVG_ERR_NULL);

    UT_TEST("init, both twins: n_sub outside 1..64, or a frame it does not divide, is ERR_SUB");
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 0u, 500.0), INVERTER_AVG_ERR_SUB);
    UT_EQ_INT(init_both(false, pp, sp, 130000u, INVERTER_AVG_SUB_MAX + 1u, 500.0),
              INVERTER_AVG_ERR_SUB);
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 3u, 500.0), INVERTER_AVG_ERR_SUB);

    UT_TEST("init, both twins: a substep the modulator refuses (50 ns, below 100 ns) is "
            "ERR_PWM; an initial DC-link voltage the stage refuses (-1 V) is ERR_STAGE");
    UT_EQ_INT(init_both(false, pp, sp, 50u, 1u, 500.0), INVERTER_AVG_ERR_PWM);
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 50u, -1.0), INVERTER_AVG_ERR_STAGE);

    UT_TEST("init, both twins: 50 substeps of 2 us in 100 us and 64 substeps (the most) of "
            "2 us in 128 us are accepted and kept");
    UT_EQ_INT(init_both(false, pp, sp, 100000u, 50u, 500.0), INVERTER_AVG_OK);
    UT_EQ_INT(inv_q.n_sub, 50);
    UT_EQ_INT(inv_f.n_sub, 50);
    UT_EQ_INT(init_both(false, pp, sp, 128000u, INVERTER_AVG_SUB_MAX, 0.0), INVERTER_AVG_OK);
    UT_EQ_INT(inv_q.n_sub, 64);
    UT_EQ_INT(inv_f.n_sub, 64);
}

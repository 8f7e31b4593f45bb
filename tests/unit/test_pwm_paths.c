/*
 * The modulator's edges (pwm.h): the step range of the averaged mode, NULL
 * arguments, commands that are negative, not a number or beyond the
 * frequency range, the step functions' dispatch to the averaged modulator,
 * the averaged duties at full modulation, and a real-time ramp longer than
 * an int32 step count. The references are pwm.h's
 * documented clamps and statuses, wt_phase_inc_q16() for the increments,
 * and pwm_average_*() called directly.
 */
#include <stddef.h>

#include "fixedpoint/wavetable.h"
#include "math/umath.h"
#include "models/drive/pwm/pwm.h"
#include "models/drive/pwm/pwm_rt.h"
#include "ut.h"

void suite_pwm_paths(void);

static const pwm_params averaged = {5000.0, PWM_AVERAGED, 0u, 0u, 0u};

static void test_init(void) {
    UT_TEST("init: the averaged modulator has no carrier to check, so any step up to 1 ms "
            "is accepted and one nanosecond more is PWM_ERR_STEP; NULL is PWM_ERR_NULL");
    pwm_q q;
    pwm_f32 f;
    UT_EQ_INT(pwm_init_q(&q, &averaged, 1000000u), PWM_OK);
    UT_EQ_INT(pwm_init_f32(&f, &averaged, 1000000u), PWM_OK);
    UT_EQ_INT(pwm_init_q(&q, &averaged, 1000001u), PWM_ERR_STEP);
    UT_EQ_INT(pwm_init_f32(&f, &averaged, 1000001u), PWM_ERR_STEP);
    UT_EQ_INT(pwm_init_q(&q, NULL, 2000u), PWM_ERR_NULL);
    UT_EQ_INT(pwm_init_f32(NULL, &averaged, 2000u), PWM_ERR_NULL);
    UT_EQ_INT(pwm_init_f32(&f, NULL, 2000u), PWM_ERR_NULL);
}

static void test_commands_f32(void) {
    pwm_f32 f;
    UT_CHECK(pwm_init_f32(&f, &pwm_params_default, 2000u) == PWM_OK);
    pwm_cmd_f32 c = {0};

    UT_TEST("float commands: a negative or NaN modulation index gives 0, each counted once");
    c.m_index = -0.25f;
    c.freq_hz = 50.0f;
    pwm_command_f32(&f, &c);
    UT_NEAR(f.m, 0.0, 0.0);
    UT_EQ_INT(f.sat_count, 1);
    c.m_index = math_nan_f32();
    pwm_command_f32(&f, &c);
    UT_NEAR(f.m, 0.0, 0.0);
    UT_EQ_INT(f.sat_count, 2);
    c.m_index = 0.5f;
    pwm_command_f32(&f, &c);
    UT_NEAR(f.m, 0.5, 0.0);
    UT_EQ_INT(f.sat_count, 2);

    UT_TEST("float commands: a NaN frequency holds the reference (0 Hz); beyond +-32767 Hz "
            "the frequency is that limit; a negative one is the two's complement of the "
            "positive one's increment (wt_phase_inc_q16)");
    c.freq_hz = math_nan_f32();
    pwm_command_f32(&f, &c);
    UT_EQ_INT(f.inc_s, 0);
    c.freq_hz = 1.0e6f;
    pwm_command_f32(&f, &c);
    UT_EQ_INT(f.inc_s, wt_phase_inc_q16(32767 * 65536, 2000u));
    c.freq_hz = -1.0e6f;
    pwm_command_f32(&f, &c);
    UT_EQ_INT(f.inc_s, wt_phase_inc_q16(-32767 * 65536, 2000u));
    UT_EQ_INT(f.inc_s, 0u - wt_phase_inc_q16(32767 * 65536, 2000u));
    c.freq_hz = -50.0f;
    pwm_command_f32(&f, &c);
    UT_EQ_INT(f.inc_s, 0u - wt_phase_inc_q16(50 * 65536, 2000u));
}

static void test_dispatch(void) {
    UT_TEST("pwm_step on an averaged modulator is pwm_average, bit for bit (both twins, "
            "m 0.8, 50 Hz, 500 steps)");
    static pwm_q qa, qb;
    static pwm_f32 fa, fb;
    UT_CHECK(pwm_init_q(&qa, &averaged, 2000u) == PWM_OK);
    UT_CHECK(pwm_init_q(&qb, &averaged, 2000u) == PWM_OK);
    UT_CHECK(pwm_init_f32(&fa, &averaged, 2000u) == PWM_OK);
    UT_CHECK(pwm_init_f32(&fb, &averaged, 2000u) == PWM_OK);
    uint32_t inc = wt_phase_inc_q16(50 * 65536, 2000u);
    pwm_command_inc_q(&qa, 26214, inc);
    pwm_command_inc_q(&qb, 26214, inc);
    pwm_command_inc_f32(&fa, 0.8f, inc);
    pwm_command_inc_f32(&fb, 0.8f, inc);
    bool same = true;
    for (int k = 0; k < 500; k++) {
        pwm_out_q oa, ob;
        pwm_out_f32 pa, pb;
        pwm_step_q(&qa, &oa);
        pwm_average_q(&qb, &ob);
        pwm_step_f32(&fa, &pa);
        pwm_average_f32(&fb, &pb);
        for (int x = 0; x < 3; x++) {
            same = same && oa.duty[x] == ob.duty[x] && oa.state[x] == ob.state[x] &&
                   pa.duty[x] == pb.duty[x] && pa.state[x] == pb.state[x];
        }
    }
    UT_CHECK(same);
}

static void test_full_modulation(void) {
    UT_TEST("averaged duties at full modulation (m = 1) stay within [0, 1] and reach both "
            "ends within 1e-3 over a 50 Hz period at 20 us");
    pwm_f32 f;
    UT_CHECK(pwm_init_f32(&f, &averaged, 20000u) == PWM_OK);
    pwm_command_inc_f32(&f, 1.0f, wt_phase_inc_q16(50 * 65536, 20000u));
    float lo = 1.0f, hi = 0.0f;
    for (int k = 0; k < 1000; k++) {
        pwm_out_f32 o;
        pwm_step_f32(&f, &o);
        for (int x = 0; x < 3; x++) {
            lo = math_min_f32(lo, o.duty[x]);
            hi = math_max_f32(hi, o.duty[x]);
        }
    }
    ut_info("duties %.9f .. %.9f", (double)lo, (double)hi);
    UT_CHECK(lo >= 0.0f && hi <= 1.0f);
    UT_CHECK(lo < 1e-3f && hi > 1.0f - 1e-3f);
}

static void test_long_ramp(void) {
    UT_TEST("real-time ramp over 2^31 + 1 steps (more than an int32 counts): the change per "
            "step is the knots' difference over 2^31 - 1, rounded (0 for a quarter turn of a "
            "full-scale sine), from the same first knot as a one-step ramp");
    pwm_rt_ramp one, many;
    const uint32_t quarter = 0x40000000u;
    pwm_rt_ramp_q(&one, NULL, 32767, 0u, quarter, 1u);
    pwm_rt_ramp_q(&many, NULL, 32767, 0u, quarter, 0x80000001u); /* ends a quarter turn on too */
    UT_CHECK(one.dr[0] > (1 << 22));
    UT_EQ_INT(many.r0[0], one.r0[0]);
    UT_EQ_INT(many.r0[1], one.r0[1]);
    UT_EQ_INT(many.dr[0], 0);
    UT_EQ_INT(many.dr[1], 0);
}

void suite_pwm_paths(void) {
    test_init();
    test_commands_f32();
    test_dispatch();
    test_full_modulation();
    test_long_ramp();
}

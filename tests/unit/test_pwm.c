/*
 * Properties of the sine-triangle modulator (src/models/drive/pwm/pwm.h), both twins
 * in every build: switching once on and once off per leg and carrier
 * period; the fundamental of the inverter phase voltage against m Vdc / 2;
 * the spectrum's first cluster at the carrier; reversal and standstill;
 * the averaged duties against (1 + m sin) / 2 from the libm-free math
 * library; the twins against each other; commands and parameter checks.
 *
 * The phase voltage is the inverter's own (ps_inverter_q/_f32 of
 * power_stage_nodes.h: pole voltages minus their common mode) at a constant
 * DC-link voltage, sampled as the mean over each 2 us step.
 */
#include <stddef.h>

#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_nodes.h"
#include "models/drive/pwm/pwm.h"
#include "models/drive/pwm/pwm_rt.h"
#include "fixedpoint/wavetable.h"
#include "power_test_dft.h"
#include "ut.h"

void suite_pwm(void);

#define STEP_NS 2000u
#define VDC_V 540.0
#define STEPS_PER_50HZ 10000u   /* one 50 Hz period at 2 us */
#define STEPS_PER_CARRIER 100u  /* one 5 kHz period at 2 us */

static uint32_t inc_hz(double f_hz) {
    return wt_phase_inc_q16((int32_t)(f_hz * 65536.0 + ((f_hz >= 0.0) ? 0.5 : -0.5)), STEP_NS);
}

/* ---- One modulator step of either twin, with the phase voltages [V] ---- */

typedef struct {
    int fixed;          /* 1: pwm_q, 0: pwm_f32 */
    pwm_q q;
    pwm_f32 f;
    double u[3];        /* [V] phase voltages of the step (mean over the step) */
    double duty[3];     /* [-] */
    uint8_t state[3];
} tpwm;

static int tpwm_init(tpwm *t, int fixed, const pwm_params *p, uint32_t step_ns) {
    t->fixed = fixed;
    if (fixed) {
        return pwm_init_q(&t->q, p, step_ns) == PWM_OK;
    }
    return pwm_init_f32(&t->f, p, step_ns) == PWM_OK;
}

static void tpwm_command(tpwm *t, double m, uint32_t inc) {
    if (t->fixed) {
        pwm_command_inc_q(&t->q, fp_from_f64_q15(m), inc);
    } else {
        pwm_command_inc_f32(&t->f, (float)m, inc);
    }
}

/* Steps (average = 0: switching, 1: averaged duties) and forms the phase voltages. */
static void tpwm_step(tpwm *t, int average) {
    unsigned x;
    if (t->fixed) {
        pwm_out_q o;
        int32_t ua;
        int32_t ub;
        const int32_t vdc = (int32_t)(VDC_V / 1024.0 * (double)PS_Q28_ONE + 0.5);
        if (average) {
            pwm_average_q(&t->q, &o);
        } else {
            pwm_step_q(&t->q, &o);
        }
        ps_inverter_q(vdc, o.duty, &ua, &ub);
        t->u[0] = (double)ua * (1024.0 / (double)PS_Q28_ONE);
        t->u[1] = (double)ub * (1024.0 / (double)PS_Q28_ONE);
        for (x = 0u; x < 3u; x++) {
            t->duty[x] = (double)o.duty[x] / 32768.0;
            t->state[x] = o.state[x];
        }
    } else {
        pwm_out_f32 o;
        float ua;
        float ub;
        if (average) {
            pwm_average_f32(&t->f, &o);
        } else {
            pwm_step_f32(&t->f, &o);
        }
        ps_inverter_f32((float)VDC_V, o.duty, &ua, &ub);
        t->u[0] = (double)ua;
        t->u[1] = (double)ub;
        for (x = 0u; x < 3u; x++) {
            t->duty[x] = (double)o.duty[x];
            t->state[x] = o.state[x];
        }
    }
    t->u[2] = -t->u[0] - t->u[1];
}

static const char *twin_name(int fixed) { return fixed ? "fixed" : "float"; }

/* ---- Tests -------------------------------------------------------------- */

static void test_switching_rate(int fixed) {
    tpwm t;
    unsigned x;
    uint32_t k;
    uint32_t bad_windows = 0u;
    uint32_t total[3] = {0u, 0u, 0u};
    uint8_t prev[3] = {1u, 1u, 1u}; /* all upper switches on at the carrier valley */
    uint32_t in_window[3] = {0u, 0u, 0u};

    UT_CHECK(tpwm_init(&t, fixed, &pwm_params_default, STEP_NS));
    tpwm_command(&t, 0.9, inc_hz(50.0));
    for (k = 0u; k < STEPS_PER_50HZ; k++) {
        tpwm_step(&t, 0);
        for (x = 0u; x < 3u; x++) {
            if (t.state[x] != prev[x]) {
                in_window[x]++;
                total[x]++;
                prev[x] = t.state[x];
            }
        }
        if ((k + 1u) % STEPS_PER_CARRIER == 0u) {
            for (x = 0u; x < 3u; x++) {
                bad_windows += (in_window[x] != 2u);
                in_window[x] = 0u;
            }
        }
    }
    ut_info("%s: transitions per leg over 100 carrier periods: %u %u %u", twin_name(fixed),
            (unsigned)total[0], (unsigned)total[1], (unsigned)total[2]);
    UT_EQ_INT(bad_windows, 0);
    for (x = 0u; x < 3u; x++) {
        UT_EQ_INT(total[x], 2u * STEPS_PER_50HZ / STEPS_PER_CARRIER);
    }
}

/*
 * Amplitude and phase of the fundamental of u_a over one 50 Hz period; the
 * DFT basis is the reference phase at the middle of each step.
 */
static void fundamental(int fixed, pwm_edges edges, double m, double *amp, double *phase) {
    pwm_params p = pwm_params_default;
    tpwm t;
    tdft d;
    uint32_t k;
    const uint32_t inc = inc_hz(50.0);

    p.edges = edges;
    UT_CHECK(tpwm_init(&t, fixed, &p, STEP_NS));
    tpwm_command(&t, m, inc);
    tdft_init(&d, inc, inc / 2u);
    for (k = 0u; k < STEPS_PER_50HZ; k++) {
        tpwm_step(&t, 0);
        tdft_add(&d, t.u[0]);
    }
    *amp = tdft_amp(&d);
    *phase = tdft_phase_deg(&d);
}

static void test_fundamental(int fixed) {
    static const double m_list[3] = {0.2, 0.5, 0.9};
    unsigned i;
    for (i = 0u; i < 3u; i++) {
        double amp;
        double ph;
        const double expect = m_list[i] * VDC_V / 2.0;
        fundamental(fixed, PWM_EDGES_INTERPOLATED, m_list[i], &amp, &ph);
        ut_info("%s m=%.1f: fundamental %.4f V, m Vdc/2 = %.4f V, error %.4f %%, phase %.4f deg",
                twin_name(fixed), m_list[i], amp, expect, 100.0 * (amp / expect - 1.0),
                ph + 90.0);
        UT_NEAR(amp / expect, 1.0, 0.005);
        UT_NEAR(ph, -90.0, 0.1);
    }
}

/* The error of plain fixed-step switching, for the record (docs/drive_power.md). */
static void test_sampled_edges_info(void) {
    static const double m_list[3] = {0.2, 0.5, 0.9};
    unsigned i;
    for (i = 0u; i < 3u; i++) {
        double amp;
        double ph;
        const double expect = m_list[i] * VDC_V / 2.0;
        fundamental(1, PWM_EDGES_SAMPLED, m_list[i], &amp, &ph);
        ut_info("sampled edges m=%.1f: fundamental error %.3f %%, phase %.3f deg", m_list[i],
                100.0 * (amp / expect - 1.0), ph + 90.0);
        /* Quantised pulse widths: a few per cent, never more than 5 %. */
        UT_NEAR(amp / expect, 1.0, 0.05);
    }
}

static void test_carrier_cluster(int fixed, double m) {
    /* Bins: f1, f_c - 2 f1, f_c + 2 f1, then frequencies that must stay small. */
    static const double f_bin[] = {50.0, 4900.0, 5100.0, 5000.0, 2500.0, 150.0, 250.0, 350.0};
    enum { NB = sizeof f_bin / sizeof f_bin[0] };
    tdft d[NB];
    tpwm t;
    unsigned b;
    uint32_t k;
    double a[NB];
    double small_max = 0.0;

    UT_CHECK(tpwm_init(&t, fixed, &pwm_params_default, STEP_NS));
    tpwm_command(&t, m, inc_hz(50.0));
    for (b = 0u; b < NB; b++) {
        tdft_init(&d[b], inc_hz(f_bin[b]), inc_hz(f_bin[b]) / 2u);
    }
    for (k = 0u; k < STEPS_PER_50HZ; k++) {
        tpwm_step(&t, 0);
        for (b = 0u; b < NB; b++) {
            tdft_add(&d[b], t.u[0]);
        }
    }
    for (b = 0u; b < NB; b++) {
        a[b] = tdft_amp(&d[b]);
    }
    for (b = 3u; b < NB; b++) {
        small_max = (a[b] > small_max) ? a[b] : small_max;
    }
    ut_info("%s m=%.1f: |U| at 50 Hz %.2f V, 4900 Hz %.2f V, 5100 Hz %.2f V; 5000 Hz %.4f V, "
            "2500 Hz %.4f V, largest other %.4f V",
            twin_name(fixed), m, a[0], a[1], a[2], a[3], a[4], small_max);
    /* The sidebands f_c +- 2 f1 carry several per cent of the fundamental... */
    UT_CHECK(a[1] > 0.05 * a[0]);
    UT_CHECK(a[2] > 0.05 * a[0]);
    /* ...and dominate every other bin checked, including the carrier itself (common mode). */
    UT_CHECK(a[1] > 20.0 * small_max);
    UT_CHECK(a[2] > 20.0 * small_max);
}

static void test_reversal_and_standstill(int fixed) {
    tpwm t;
    tdft da;
    tdft db;
    pwm_params p = pwm_params_default;
    uint32_t k;
    const uint32_t inc = inc_hz(50.0);
    double lead;
    double mean[3] = {0.0, 0.0, 0.0};
    unsigned x;

    /* Forward: u_b lags u_a by 120 deg; reversed (f = -50 Hz): it leads. */
    UT_CHECK(tpwm_init(&t, fixed, &pwm_params_default, STEP_NS));
    tpwm_command(&t, 0.8, 0u - inc);
    tdft_init(&da, inc, 0u);
    tdft_init(&db, inc, 0u);
    for (k = 0u; k < STEPS_PER_50HZ; k++) {
        tpwm_step(&t, 0);
        tdft_add(&da, t.u[0]);
        tdft_add(&db, t.u[1]);
    }
    lead = tdft_wrap_deg(tdft_phase_deg(&db) - tdft_phase_deg(&da));
    ut_info("%s f=-50 Hz: phase of u_b relative to u_a %.3f deg, |U_a| %.3f V", twin_name(fixed),
            lead, tdft_amp(&da));
    UT_NEAR(lead, 120.0, 0.2);
    UT_NEAR(tdft_amp(&da) / (0.8 * VDC_V / 2.0), 1.0, 0.005);

    /* Standstill at theta = 90 deg: DC phase voltages m Vdc/2 (1, -1/2, -1/2). */
    p.ref_phase0 = WT_PHASE_QUARTER;
    UT_CHECK(tpwm_init(&t, fixed, &p, STEP_NS));
    tpwm_command(&t, 0.6, 0u);
    for (k = 0u; k < 10u * STEPS_PER_CARRIER; k++) {
        tpwm_step(&t, 0);
        for (x = 0u; x < 3u; x++) {
            mean[x] += t.u[x] / (10.0 * STEPS_PER_CARRIER);
        }
    }
    ut_info("%s f=0: mean phase voltages %.3f %.3f %.3f V", twin_name(fixed), mean[0], mean[1],
            mean[2]);
    UT_NEAR(mean[0], 0.6 * VDC_V / 2.0, 0.005 * VDC_V);
    UT_NEAR(mean[1], -0.6 * VDC_V / 4.0, 0.005 * VDC_V);
    UT_NEAR(mean[2], -0.6 * VDC_V / 4.0, 0.005 * VDC_V);
}

static void test_averaged_duties(int fixed) {
    tpwm t;
    uint32_t k;
    double worst = 0.0;
    unsigned x;
    uint32_t ph = 0u; /* reference phase at the start of the step */
    pwm_params p = pwm_params_default;

    p.edges = PWM_AVERAGED; /* a 100 us step: no carrier */
    UT_CHECK(tpwm_init(&t, fixed, &p, 100000u));
    tpwm_command(&t, 0.75, wt_phase_inc_q16((int32_t)(51.3 * 65536.0 + 0.5), 100000u));
    for (k = 0u; k < 500u; k++) {
        const uint32_t inc100 = t.fixed ? t.q.inc_s : t.f.inc_s;
        const double mid = MATH_TWO_PI_F64 * ((double)(ph + inc100 / 2u) / 4294967296.0);
        tpwm_step(&t, 1);
        for (x = 0u; x < 3u; x++) {
            const double r = 0.75 * math_sin_f64(mid - 2.0943951023931955 * (double)x);
            const double err = t.duty[x] - 0.5 * (1.0 + r);
            worst = (err > worst) ? err : (-err > worst) ? -err : worst;
        }
        ph += inc100;
    }
    ut_info("%s: averaged duties vs (1 + m sin)/2 at mid-step, worst %.2e", twin_name(fixed),
            worst);
    UT_CHECK(worst < 1.0e-4);
}

static void test_twins_agree(void) {
    tpwm a;
    tpwm b;
    uint32_t k;
    unsigned x;
    double worst = 0.0;
    uint32_t state_diff = 0u;

    UT_CHECK(tpwm_init(&a, 1, &pwm_params_default, STEP_NS));
    UT_CHECK(tpwm_init(&b, 0, &pwm_params_default, STEP_NS));
    tpwm_command(&a, 0.7, inc_hz(37.0));
    tpwm_command(&b, 0.7, inc_hz(37.0));
    for (k = 0u; k < STEPS_PER_50HZ; k++) {
        tpwm_step(&a, 0);
        tpwm_step(&b, 0);
        for (x = 0u; x < 3u; x++) {
            const double e = a.duty[x] - b.duty[x];
            worst = (e > worst) ? e : (-e > worst) ? -e : worst;
            state_diff += (a.state[x] != b.state[x]);
        }
    }
    ut_info("fixed vs float: worst duty difference %.2e of a step, %u differing states",
            worst, (unsigned)state_diff);
    /* A Q15 table value is within 1 LSB: about 2 LSB of e, 0.2 % of a step. */
    UT_CHECK(worst < 0.005);
    UT_CHECK(state_diff <= 3u);
}

static void test_commands(void) {
    pwm_q q;
    pwm_f32 f;
    pwm_cmd_q cq;
    pwm_cmd_f32 cf;
    pwm_params bad = pwm_params_default;

    UT_EQ_INT(pwm_init_q(&q, &pwm_params_default, STEP_NS), PWM_OK);
    UT_EQ_INT(pwm_init_f32(&f, &pwm_params_default, STEP_NS), PWM_OK);
    UT_EQ_INT(q.inc_c, 42949673u); /* round(2^32 * 5000 * 2e-6) */
    UT_EQ_INT(q.dc_abs, 1311);
    /* 50 Hz = 50/128 of the base: Q31 value 838860800 exactly. */
    cq.m_index = Q15_CONST(0.5);
    cq.freq = (q31_t)838860800;
    pwm_command_q(&q, &cq);
    UT_EQ_INT(q.inc_s, 429497u);
    cq.freq = -(q31_t)838860800;
    cq.m_index = Q15_CONST(-0.25);
    pwm_command_q(&q, &cq);
    UT_EQ_INT(q.inc_s, 0u - 429497u);
    UT_EQ_INT(q.m, 0);
    UT_EQ_INT(q.sat_count, 1u);
    cf.m_index = 1.5f;
    cf.freq_hz = 50.0f;
    pwm_command_f32(&f, &cf);
    UT_EQ_INT(f.inc_s, 429497u);
    UT_NEAR(f.m, 1.0, 0.0);
    UT_EQ_INT(f.sat_count, 1u);

    UT_EQ_INT(pwm_init_q(NULL, &pwm_params_default, STEP_NS), PWM_ERR_NULL);
    UT_EQ_INT(pwm_init_q(&q, &pwm_params_default, 50u), PWM_ERR_STEP);
    bad.carrier_hz = 100000.0;
    UT_EQ_INT(pwm_init_q(&q, &bad, STEP_NS), PWM_ERR_CARRIER);
    bad.carrier_hz = pwm_params_default.carrier_hz;
    UT_EQ_INT(pwm_init_f32(&f, &bad, 40000u), PWM_ERR_CARRIER); /* 5 steps per period */
    bad.edges = PWM_AVERAGED;
    UT_EQ_INT(pwm_init_f32(&f, &bad, 40000u), PWM_OK);
    bad.edges = (pwm_edges)7;
    UT_EQ_INT(pwm_init_q(&q, &bad, STEP_NS), PWM_ERR_EDGES);
    bad.edges = PWM_EDGES_SAMPLED;
    bad.carrier_hz = -1.0;
    UT_EQ_INT(pwm_init_f32(&f, &bad, STEP_NS), PWM_ERR_CARRIER);
}

/* ---- The real-time modulator (pwm_rt.h) ---------------------------------- */

/* Its closed-form carrier against the table triangle: within one Q15 count. */
static void test_rt_carrier(void) {
    int32_t worst = 0;
    for (uint32_t k = 0u; k < 1024u; k++) {
        for (uint32_t ph = (k << 22) - 640u; ph != (k << 22) + 640u; ph += 128u) {
            int32_t d = fp_shr_round_i32(pwm_rt_carrier(ph), 8u) - (int32_t)wt_tri_q15(ph);
            worst = (d < 0 ? -d : d) > worst ? (d < 0 ? -d : d) : worst;
        }
    }
    UT_EQ_INT(pwm_rt_carrier(0u), -PWM_RT_ONE);
    UT_EQ_INT(pwm_rt_carrier(0x80000000u), PWM_RT_ONE);
    UT_EQ_INT(pwm_rt_carrier(0x40000000u), 0);
    ut_info("real-time carrier against the table triangle: worst %d Q15 counts", (int)worst);
    UT_CHECK(worst <= 1);
}

/*
 * The real-time modulator against the exact sampled one of pwm.h at the
 * same m and 50 Hz (frames of 50 steps): the references at every knot equal
 * m sin to rounding, the chord stays within m (w N T)^2 / 8 of the sine,
 * the switch states agree except where the two references straddle the
 * carrier, and the fundamentals of u_a agree within 0.2 %.
 */
static void test_rt_against_exact(int fixed) {
    const pwm_params sampled = pwm_params_sampled;
    const uint32_t inc = inc_hz(50.0);
    const uint32_t n = 50u;
    const double m = 0.9;
    pwm_rt rt;
    tpwm t;
    tdft d_rt, d_ex;
    uint32_t differ = 0u;
    double chord_worst = 0.0;
    uint32_t ref_ph = 0u;
    UT_CHECK(pwm_rt_init(&rt, &sampled, STEP_NS) == PWM_OK);
    UT_CHECK(tpwm_init(&t, fixed, &sampled, STEP_NS));
    tpwm_command(&t, m, inc);
    tdft_init(&d_rt, inc, inc / 2u);
    tdft_init(&d_ex, inc, inc / 2u);
    for (uint32_t k = 0u; k < STEPS_PER_50HZ; k++) {
        if (k % n == 0u) {
            pwm_rt_ramp ramp;
            if (fixed) {
                pwm_rt_ramp_q(&ramp, NULL, fp_from_f64_q15(m), ref_ph, inc, n);
            } else {
                pwm_rt_ramp_f32(&ramp, NULL, (float)m, ref_ph, inc, n);
            }
            pwm_rt_apply(&rt, &ramp);
        }
        /* The reference of leg a now against m sin at this step's phase. */
        double exact = m * math_sin_f64(MATH_TWO_PI_F64 * (double)(ref_ph + (k % n) * inc) /
                                        4294967296.0);
        double dev = (double)pwm_rt_ref(&rt.fr[rt.cur], 0, rt.k) / PWM_RT_ONE - exact;
        chord_worst = (dev < 0 ? -dev : dev) > chord_worst ? (dev < 0 ? -dev : dev) : chord_worst;
        int32_t st[3];
        pwm_rt_step(&rt, st);
        if (k % n == n - 1u) {
            ref_ph += n * inc;
        }
        tpwm_step(&t, 0);
        for (unsigned x = 0u; x < 3u; x++) {
            differ += ((st[x] != 0) != (t.duty[x] > 0.5));
        }
        tdft_add(&d_rt, (double)(2 * st[0] - st[1] - st[2]) * VDC_V / 3.0);
        tdft_add(&d_ex, t.u[0]);
    }
    double wnt = MATH_TWO_PI_F64 * 50.0 * 1e-4;
    double amp_rt = tdft_amp(&d_rt);
    double amp_ex = tdft_amp(&d_ex);
    ut_info("%s real-time modulator, m 0.9, 50 Hz: chord deviation %.2e (bound %.2e), states "
            "differing %u of %u, fundamental %.4f V vs exact sampled %.4f V (%.4f %%)",
            twin_name(fixed), chord_worst, m * wnt * wnt / 8.0, (unsigned)differ,
            3u * STEPS_PER_50HZ, amp_rt, amp_ex, 100.0 * (amp_rt / amp_ex - 1.0));
    /* The chord's sag, plus the Q15 table's error and its 32767 peak (6e-5). */
    UT_CHECK(chord_worst <= m * wnt * wnt / 8.0 + 6e-5);
    UT_CHECK(differ * 100u <= 3u * STEPS_PER_50HZ);
    UT_NEAR(amp_rt / amp_ex, 1.0, 0.002);
    UT_NEAR(amp_rt / (m * VDC_V / 2.0), 1.0, 0.05);
}

/*
 * A 50 Hz period of the real-time modulator in frames of 50 steps (the
 * motor task's ramps, of the given twin), sub-step (dead time off) or
 * sampled: the fundamental of the pole voltage v_an = Vdc (d_a - 1/2),
 * each step's mean, against m Vdc / 2, and the legs' duty sums (Q15).
 */
static double rt_period(int fixed, int substep, double m, const int32_t *neg,
                        uint32_t dead_ns, int64_t sum[3]) {
    static const pwm_params sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u, 0u};
    const uint32_t inc = inc_hz(50.0);
    const uint32_t n = 50u;
    pwm_rt rt;
    tdft d;
    uint32_t ref_ph = 0u;
    (void)pwm_rt_init(&rt, &sampled, STEP_NS);
    (void)pwm_rt_dead_time(&rt, dead_ns, STEP_NS);
    tdft_init(&d, inc, inc / 2u);
    sum[0] = sum[1] = sum[2] = 0;
    for (uint32_t k = 0u; k < STEPS_PER_50HZ; k++) {
        if (k % n == 0u) {
            pwm_rt_ramp ramp;
            if (fixed) {
                pwm_rt_ramp_q(&ramp, NULL, fp_from_f64_q15(m), ref_ph, inc, n);
            } else {
                pwm_rt_ramp_f32(&ramp, NULL, (float)m, ref_ph, inc, n);
            }
            pwm_rt_apply(&rt, &ramp);
            ref_ph += n * inc;
        }
        int32_t st[3];
        int32_t duty[3];
        if (!substep) {
            pwm_rt_sampled(&rt, st, duty);
        } else if (neg != NULL) {
            pwm_rt_substep_dt(&rt, neg, st, duty);
        } else {
            pwm_rt_substep_each(&rt, st, duty);
        }
        for (unsigned x = 0u; x < 3u; x++) {
            sum[x] += duty[x];
        }
        tdft_add(&d, VDC_V * ((double)duty[0] / 32768.0 - 0.5));
    }
    return tdft_amp(&d) / (m * VDC_V / 2.0) - 1.0;
}

/* Sub-step switching: v_an's fundamental within 0.5 % of m Vdc / 2 for m = 0.1 .. 0.9. */
static void test_rt_substep_fundamental(int fixed) {
    double worst = 0.0;
    double worst_sampled = 0.0;
    int64_t sum[3];
    for (int k = 1; k <= 9; k++) {
        const double m = 0.1 * (double)k;
        const double e = rt_period(fixed, 1, m, NULL, 0u, sum);
        const double es = rt_period(fixed, 0, m, NULL, 0u, sum);
        ut_info("%s ramps, m %.1f: v_an fundamental %.4f %% of m Vdc/2 sub-step, %.3f %% "
                "sampled", twin_name(fixed), m, 100.0 * e, 100.0 * es);
        worst = math_max_f64(worst, math_fabs_f64(e));
        worst_sampled = math_max_f64(worst_sampled, math_fabs_f64(es));
        UT_CHECK(math_fabs_f64(e) <= 0.005);
    }
    ut_info("worst: sub-step %.4f %%, sampled %.3f %%", 100.0 * worst, 100.0 * worst_sampled);
    /* The sampled edges' quantisation is what the sub-step removes. */
    UT_CHECK(worst_sampled > 10.0 * worst);
}

/*
 * Dead time: with the currents' signs held (a out of the leg, b into it, c
 * out), every pulse of a leg with i >= 0 loses t_d and of one with i < 0
 * gains it: over a 50 Hz period (100 carrier periods) the mean duty moves
 * by -sign(i) t_d f_c, the classic mean error V_dc t_d f_c sign(i) of the
 * pole voltage; within 1 % of it, for t_d = 1 us and 3 us (longer than
 * the step: the delayed edge falls in the next step), m = 0.2 and 0.8.
 */
static void test_rt_dead_time(int fixed) {
    static const int32_t neg[3] = {0, 1, 0};
    static const uint32_t dead_ns[2] = {1000u, 3000u};
    static const double m_list[2] = {0.2, 0.8};
    for (unsigned j = 0u; j < 2u; j++) {
        for (unsigned i = 0u; i < 2u; i++) {
            int64_t ideal[3];
            int64_t dead[3];
            (void)rt_period(fixed, 1, m_list[j], NULL, 0u, ideal);
            (void)rt_period(fixed, 1, m_list[j], neg, dead_ns[i], dead);
            const double expect = 1e-9 * (double)dead_ns[i] * 5000.0;
            double err[3];
            for (unsigned x = 0u; x < 3u; x++) {
                err[x] = (double)(dead[x] - ideal[x]) / (32768.0 * (double)STEPS_PER_50HZ);
                const double sign = (neg[x] != 0) ? -1.0 : 1.0;
                UT_NEAR(err[x], -sign * expect, 0.01 * expect);
            }
            ut_info("%s, m %.1f, t_d %u ns: mean duty error %.6f %.6f %.6f (classic "
                    "-/+ t_d f_c = %.6f): %.2f / %.2f / %.2f V of Vdc t_d f_c sign(i) "
                    "at %.0f V", twin_name(fixed), m_list[j], (unsigned)dead_ns[i], err[0],
                    err[1], err[2], expect, VDC_V * err[0], VDC_V * err[1], VDC_V * err[2],
                    VDC_V);
        }
    }
    /* The set-up refuses a dead time over 10 us or over 8 steps. */
    pwm_rt rt;
    static const pwm_params sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u, 0u};
    UT_EQ_INT(pwm_rt_init(&rt, &sampled, STEP_NS), PWM_OK);
    UT_EQ_INT(pwm_rt_dead_time(&rt, 10001u, STEP_NS), PWM_ERR_STEP);
    UT_EQ_INT(pwm_rt_dead_time(&rt, 9000u, 1000u), PWM_ERR_STEP);
    UT_EQ_INT(pwm_rt_dead_time(NULL, 1000u, STEP_NS), PWM_ERR_NULL);
    UT_EQ_INT(pwm_rt_dead_time(&rt, 1000u, STEP_NS), PWM_OK);
    UT_EQ_INT(rt.kd, 32768);
}

/*
 * The duty of one step against the exact crossing of two straight lines:
 * within 2 counts of Q15 for crossings across the step, rising and
 * falling, with the carrier's change per step of 2 us and 5 us; no edge
 * gives 0 or 32768.
 */
static void test_rt_duty_exact(void) {
    static const uint32_t incs[2] = {42949673u, 107374182u};
    int32_t worst = 0;
    for (unsigned j = 0u; j < 2u; j++) {
        pwm_rt rt;
        static const pwm_params sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u, 0u};
        (void)pwm_rt_init(&rt, &sampled, j == 0u ? 2000u : 5000u);
        const int32_t de = (int32_t)(incs[j] >> 7) + 4000;
        for (int32_t k = 1; k < 1000; k++) {
            const int32_t e0 = -(int32_t)((int64_t)de * k / 1000);
            const int32_t e1 = e0 + de;
            const double on = (double)e1 / (double)de;
            int32_t d = pwm_rt_duty(e0, e1, rt.den_sh) - (int32_t)(on * 32768.0 + 0.5);
            int32_t d2 = pwm_rt_duty(e1, e0, rt.den_sh) - (int32_t)(on * 32768.0 + 0.5);
            d = (d < 0) ? -d : d;
            d2 = (d2 < 0) ? -d2 : d2;
            worst = (d > worst) ? d : worst;
            worst = (d2 > worst) ? d2 : worst;
        }
    }
    ut_info("sub-step duty against the exact crossing: worst %d Q15 counts", (int)worst);
    UT_CHECK(worst <= 2);
    UT_EQ_INT(pwm_rt_duty(5, 7, 4u), 32768);
    UT_EQ_INT(pwm_rt_duty(0, -7, 4u), 0);
    UT_EQ_INT(pwm_rt_duty(-5, 0, 4u), 0);
    UT_CHECK(pwm_rt_duty(0x3fffffff, -0x3fffffff, 0u) >= 16383 && pwm_rt_duty(0x3fffffff, -0x3fffffff, 0u) <= 16384);
}

/*
 * The ramps with the last frame's end kept (pwm_rt_knots) against the
 * ramps formed from nothing, both builds: frames that start where the last
 * ended (the drive's), the index changed every few frames, and frames
 * that start elsewhere; every ramp the same, and the kept end taken in
 * most frames.
 */
static void test_rt_ramp_knots(void) {
    uint32_t rng = 0x2545F491u;
    uint32_t bad = 0u, taken = 0u, frames = 0u;
    pwm_rt_knots kq = {0};
    pwm_rt_knots kf = {0};
    uint32_t ph = 0x12345678u;
    int32_t mq = 20000;
    float mf = 0.6f;
    for (uint32_t f = 0u; f < 4000u; f++) {
        const uint32_t inc = 1000000u + ut_rand_u32(&rng) % 4000000u;
        const uint32_t n = ((f % 13u) == 12u) ? 1u + ut_rand_u32(&rng) % 100u : 50u;
        if ((f % 8u) == 0u) {
            mq = (int32_t)(ut_rand_u32(&rng) % 32768u);
            mf = (float)mq / 32768.0f;
        }
        if ((f % 29u) == 28u) {
            ph = ut_rand_u32(&rng); /* a frame that starts elsewhere */
        }
        const bool hit = kq.valid && kq.ph == ph && kq.m_q15 == mq;
        pwm_rt_ramp a, b;
        pwm_rt_ramp_q(&a, &kq, mq, ph, inc, n);
        pwm_rt_ramp_q(&b, NULL, mq, ph, inc, n);
        bad += (a.r0[0] != b.r0[0] || a.r0[1] != b.r0[1] || a.dr[0] != b.dr[0] ||
                a.dr[1] != b.dr[1]) ? 1u : 0u;
        pwm_rt_ramp_f32(&a, &kf, mf, ph, inc, n);
        pwm_rt_ramp_f32(&b, NULL, mf, ph, inc, n);
        bad += (a.r0[0] != b.r0[0] || a.r0[1] != b.r0[1] || a.dr[0] != b.dr[0] ||
                a.dr[1] != b.dr[1]) ? 1u : 0u;
        taken += hit ? 1u : 0u;
        frames++;
        ph += inc * n;
    }
    ut_info("%u frames, the kept end taken in %u, %u ramps differing", (unsigned)frames,
            (unsigned)taken, (unsigned)bad);
    UT_EQ_INT(bad, 0);
    UT_CHECK(taken > frames / 2u && taken < frames);
}

/* The set-up refuses what pwm.h refuses, and the interpolated edge mode. */
static void test_rt_setup(void) {
    pwm_rt rt;
    pwm_params p = pwm_params_sampled;
    UT_EQ_INT(pwm_rt_init(NULL, &p, STEP_NS), PWM_ERR_NULL);
    UT_EQ_INT(pwm_rt_init(&rt, NULL, STEP_NS), PWM_ERR_NULL);
    p.edges = PWM_EDGES_INTERPOLATED;
    UT_EQ_INT(pwm_rt_init(&rt, &p, STEP_NS), PWM_ERR_EDGES);
    p.edges = PWM_EDGES_SAMPLED;
    p.carrier_hz = 1e6;
    UT_EQ_INT(pwm_rt_init(&rt, &p, STEP_NS), PWM_ERR_CARRIER);
    /* A ramp over one step ends on its knot; a negative slope rounds symmetrically. */
    pwm_rt_ramp r;
    pwm_rt_ramp_q(&r, NULL, 32767, 0u, 0x40000000u, 1u);
    UT_EQ_INT(r.r0[0], 0);
    UT_NEAR((double)(r.r0[0] + r.dr[0]) / PWM_RT_ONE, 1.0, 1e-4);
    pwm_rt_ramp_q(&r, NULL, 32767, 0x40000000u, 0x40000000u, 3u);
    UT_NEAR((double)r.dr[0] * 3.0 / PWM_RT_ONE, -1.0, 1e-4);
}


/*
 * The frame plans (pwm_rt.h) against every step computed on its own:
 * frames of n steps with random ramps (references up to the carrier's
 * peak, slopes up to beyond the carrier's, which cannot be planned), the
 * carrier from random phases, n from 1 to 400 (frames of several carrier
 * periods hand over to single steps), frames started by prepare and apply
 * or by apply alone, and frames run one step short or long of n; duties
 * and states compared after every step.
 */
static uint32_t rt_rng = 0x9E3779B9u;

static uint32_t rt_next(void) { return ut_rand_u32(&rt_rng); }

static int32_t rt_within(int32_t lim) { return ut_rand_within(&rt_rng, lim); }

static void test_rt_plan(void) {
    static const uint32_t ns[] = {1u, 7u, 25u, 50u, 51u, 99u, 100u, 400u};
    const pwm_params pp = pwm_params_sampled;
    uint32_t bad = 0u, steps = 0u, edges = 0u, per_step = 0u, planned = 0u, trials = 0u;
    for (uint32_t t = 0u; t < 400u; t++) {
        pwm_rt a, b;
        const uint32_t n = ns[t % 8u];
        UT_CHECK(pwm_rt_init(&a, &pp, STEP_NS) == PWM_OK);
        a.fr[0].ph0 = rt_next();
        a.fr[0].r0[0] = rt_within(PWM_RT_ONE / 2);
        a.fr[0].r0[1] = rt_within(PWM_RT_ONE / 2);
        b = a;
        pwm_rt_frames(&a, n);
        int32_t sa[3] = {0, 0, 0}, sb[3] = {0, 0, 0};
        for (uint32_t f = 0u; f < 12u; f++) {
            pwm_rt_ramp r;
            const int32_t big = ((t & 3u) == 1u) ? PWM_RT_ONE : PWM_RT_ONE / 2;
            const int32_t slope = ((f % 5u) == 4u) ? 400000 : 12000;
            r.r0[0] = rt_within(big);
            r.r0[1] = rt_within(big);
            r.dr[0] = rt_within(slope);
            r.dr[1] = rt_within(slope);
            /* Frame lengths of n, or one off (the plan prepared for n is then replanned). */
            const uint32_t len = ((f % 7u) == 6u) ? n + 1u : (((f % 11u) == 10u) ? n - 1u : n);
            if (f > 0u) {
                /* Every other frame prepared first (used when the last ran n steps). */
                if ((f & 1u) == 0u) {
                    pwm_rt_prepare(&a, &r);
                }
                pwm_rt_apply(&a, &r);
                pwm_rt_apply(&b, &r);
            }
            for (uint32_t k = 0u; k < len; k++) {
                int32_t da[3], db[3];
                const bool ev = a.k == a.next_at;
                per_step += (ev && a.ev[a.next].kind == (uint8_t)PWM_RT_PER_STEP) ? 1u : 0u;
                planned += (ev && a.ev[a.next].kind == 1u) ? 1u : 0u;
                pwm_rt_substep(&a, sa, da);
                pwm_rt_substep_each(&b, sb, db);
                steps++;
                for (int x = 0; x < 3; x++) {
                    bad += (da[x] != db[x] || sa[x] != sb[x]) ? 1u : 0u;
                    edges += (db[x] != 0 && db[x] != PWM_RT_DUTY_ONE) ? 1u : 0u;
                }
            }
        }
        trials++;
    }
    ut_info("%u runs of 12 frames, %u steps, %u leg edges, %u planned edge steps, %u steps "
            "handed over to single steps, %u differing", (unsigned)trials, (unsigned)steps,
            (unsigned)edges, (unsigned)planned, (unsigned)per_step, (unsigned)bad);
    UT_EQ_INT(bad, 0);
    if (UUV_LEAN_IMAGE != 0) {
        UT_CHECK(planned == 0u); /* a lean image plans nothing: every step is its own */
    } else {
        UT_CHECK(planned > 5000u && per_step > 1000u && per_step < steps);
    }
}

void suite_pwm(void) {
    int fixed;
    UT_TEST("pwm: each leg switches on and off once per 5 kHz carrier period (100 periods)");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_switching_rate(fixed);
    }
    UT_TEST("pwm: fundamental of the phase voltage within 0.5 % of m Vdc/2, m = 0.2 0.5 0.9");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_fundamental(fixed);
    }
    UT_TEST("pwm: sampled (unlocated) edges, error of fixed-step switching for the record");
    test_sampled_edges_info();
    UT_TEST("pwm: first harmonic cluster at f_c +- 2 f1, carrier itself absent (common mode)");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_carrier_cluster(fixed, 0.5);
        test_carrier_cluster(fixed, 0.9);
    }
    UT_TEST("pwm: negative frequency reverses the sequence; zero frequency gives DC");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_reversal_and_standstill(fixed);
    }
    UT_TEST("pwm: averaged duties equal (1 + m sin)/2 at mid-step (math_sin_f64)");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_averaged_duties(fixed);
    }
    UT_TEST("pwm: fixed and float twins give the same duties and states");
    test_twins_agree();
    UT_TEST("pwm: commands (frequency to increment, m clamped and counted), parameter checks");
    test_commands();
    UT_TEST("pwm_rt: closed-form carrier within one count of the table triangle");
    test_rt_carrier();
    UT_TEST("pwm_rt: ramped references within the chord bound, states and fundamental as the "
            "exact sampled modulator's");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_rt_against_exact(fixed);
    }
    UT_TEST("pwm_rt: set-up checks, ramps end on their knots");
    test_rt_setup();
    UT_TEST("pwm_rt: ramps with the last frame's end kept = ramps formed from nothing (both "
            "builds, index changes, frames started elsewhere)");
    test_rt_ramp_knots();
    UT_TEST("pwm_rt: sub-step duty of a step against the exact crossing, within 2 Q15 counts");
    test_rt_duty_exact();
    UT_TEST("pwm_rt: sub-step switching, v_an fundamental within 0.5 % of m Vdc/2 for m = 0.1 "
            "to 0.9 (the sampled one for the record, at least ten times further off)");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_rt_substep_fundamental(fixed);
    }
    UT_TEST("pwm_rt: frame plans give every step's duties and states bit for bit (random ramps, "
            "phases, frame lengths 1 to 400)");
    test_rt_plan();
    UT_TEST("pwm_rt: dead time, the mean duty off by -sign(i) t_d f_c per leg (the classic "
            "V_dc t_d f_sw sign(i)), within 1 %; set-up checks");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_rt_dead_time(fixed);
    }
}

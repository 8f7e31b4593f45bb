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
        const double mid = 6.283185307179586 * ((double)(ph + inc100 / 2u) / 4294967296.0);
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
    bad.carrier_hz = 5000.0;
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
    static const pwm_params sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u};
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
                pwm_rt_ramp_q(&ramp, fp_from_f64_q15(m), ref_ph, inc, n);
            } else {
                pwm_rt_ramp_f32(&ramp, (float)m, ref_ph, inc, n);
            }
            pwm_rt_apply(&rt, &ramp);
        }
        /* The reference of leg a now against m sin at this step's phase. */
        double exact = m * math_sin_f64(6.283185307179586 * (double)(ref_ph + (k % n) * inc) /
                                        4294967296.0);
        double dev = (double)rt.r[0] / PWM_RT_ONE - exact;
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
    double wnt = 6.283185307179586 * 50.0 * 1e-4;
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

/* The set-up refuses what pwm.h refuses, and the interpolated edge mode. */
static void test_rt_setup(void) {
    pwm_rt rt;
    pwm_params p = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u};
    UT_EQ_INT(pwm_rt_init(NULL, &p, STEP_NS), PWM_ERR_NULL);
    UT_EQ_INT(pwm_rt_init(&rt, NULL, STEP_NS), PWM_ERR_NULL);
    p.edges = PWM_EDGES_INTERPOLATED;
    UT_EQ_INT(pwm_rt_init(&rt, &p, STEP_NS), PWM_ERR_EDGES);
    p.edges = PWM_EDGES_SAMPLED;
    p.carrier_hz = 1e6;
    UT_EQ_INT(pwm_rt_init(&rt, &p, STEP_NS), PWM_ERR_CARRIER);
    /* A ramp over one step ends on its knot; a negative slope rounds symmetrically. */
    pwm_rt_ramp r;
    pwm_rt_ramp_q(&r, 32767, 0u, 0x40000000u, 1u);
    UT_EQ_INT(r.r0[0], 0);
    UT_NEAR((double)(r.r0[0] + r.dr[0]) / PWM_RT_ONE, 1.0, 1e-4);
    pwm_rt_ramp_q(&r, 32767, 0x40000000u, 0x40000000u, 3u);
    UT_NEAR((double)r.dr[0] * 3.0 / PWM_RT_ONE, -1.0, 1e-4);
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
}

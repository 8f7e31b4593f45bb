/*
 * Properties of the power stage (src/models/drive/inverter/power_stage.h, the pieces in
 * power_stage_nodes.h) and of the averaged inverter (inverter_avg.h), both
 * twins in every build:
 *   - the LC filter's companion model, driven by a sinusoidal source, against
 *     the analytic transfer function of the same circuit;
 *   - the forward-Euler DC link with the battery pack's companion (battery.h)
 *     against the circuit's steady state and exponential;
 *   - the switching stage feeding a resistive load: the energy balance;
 *   - averaged against switching inverter on the fundamentals;
 *   - fixed against float twin on the same stimulus;
 *   - a worst-case start (full modulation, cut-off battery, locked-rotor
 *     current) stays in range; no saturation anywhere in these runs;
 *   - driven out of range, the clamps act and are counted;
 *   - parameter checks, the battery conversion and the outputs.
 */
#include <stddef.h>

#include "models/battery/battery.h"
#include "models/drive/inverter/inverter_avg.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/inverter/power_stage_fast.h"
#include "models/drive/pwm/pwm_rt.h"
#include "models/drive/inverter/power_stage_nodes.h"
#include "models/drive/pwm/pwm.h"
#include "power_test_dft.h"
#include "ut.h"

void suite_power_stage(void);

#define STEP_NS 2000u
#define STEP_S 2.0e-6
#define FRAME_NS 100000u  /* motor frame: the load current is held this long */
#define STEPS_PER_FRAME 50u
#define Q28 ((double)PS_Q28_ONE)

static const char *twin_name(int fixed) { return fixed ? "fixed" : "float"; }

static double absd(double x) { return (x < 0.0) ? -x : x; }

/* ---- Complex arithmetic for the analytic transfer function ------------------ */

typedef struct {
    double re;
    double im;
} cplx;

static cplx c_make(double re, double im) {
    cplx z;
    z.re = re;
    z.im = im;
    return z;
}

static cplx c_add(cplx a, cplx b) { return c_make(a.re + b.re, a.im + b.im); }

static cplx c_mul(cplx a, cplx b) {
    return c_make(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}

static cplx c_div(cplx a, cplx b) {
    const double d = b.re * b.re + b.im * b.im;
    return c_make((a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d);
}

/*
 * The filter of one phase with no motor current: v_C / u = 1 / (1 + Z_s Y_sh),
 * Z_s = R_L + jwL, Y_sh = jwC + 1 / (R_d + 1 / (jwC_d)); and i_L / u = Y_sh v_C / u.
 */
static void filter_analytic(const power_stage_params *p, double f_hz, cplx *h_v, cplx *h_i) {
    const double w = 2.0 * MATH_PI_F64 * f_hz;
    const cplx one = c_make(1.0, 0.0);
    const cplx z_s = c_make(p->r_l_ohm, w * p->l_h);
    const cplx z_d = c_make(p->r_d_ohm, -1.0 / (w * p->c_d_f));
    const cplx y_sh = c_add(c_make(0.0, w * p->c_f), c_div(one, z_d));
    *h_v = c_div(one, c_add(one, c_mul(z_s, y_sh)));
    *h_i = c_mul(y_sh, *h_v);
}

/* ---- A. Filter frequency response ---------------------------------------------- */

/*
 * Drives one filter phase (companion, node solve, update) with the step
 * mean of u = U sin(w t) and zero motor current; after settle steps, takes
 * the DFT of v_C and i_L at the step ends over n steps (whole periods).
 * Returns the measured ratios to the input phasor -jU.
 */
static void filter_measure(int fixed, double f_hz, uint32_t settle, uint32_t n, cplx *h_v,
                           cplx *h_i, uint32_t *sat) {
    power_stage_q q;
    power_stage_f32 s;
    ps_phase_q xq = {0, 0, 0, 0};
    ps_phase_f32 xf = {0.0f, 0.0f, 0.0f, 0.0f};
    const double u_amp = 300.0;
    const double wt = 2.0 * MATH_PI_F64 * f_hz * STEP_S;
    const double c1 = math_cos_f64(wt);
    const double s1 = math_sin_f64(wt);
    double ck = 1.0; /* cos(w t_k), sin(w t_k) by rotation */
    double sk = 0.0;
    double vr = 0.0, vi = 0.0, ir = 0.0, ii = 0.0;
    uint32_t k;

    UT_EQ_INT(power_stage_init_q(&q, &power_stage_params_default, STEP_NS, 0.0), PS_OK);
    UT_EQ_INT(power_stage_init_f32(&s, &power_stage_params_default, STEP_NS, 0.0), PS_OK);
    *sat = 0u;
    for (k = 0u; k < settle + n; k++) {
        const double cn = ck * c1 - sk * s1;
        const double sn = sk * c1 + ck * s1;
        /* Mean of U sin over [t_k, t_k+1]: U (cos(w t_k) - cos(w t_k+1)) / (w T). */
        const double u_mean = u_amp * (ck - cn) / wt;
        double v;
        double i;
        if (fixed) {
            ps_hist_q h;
            const double u_q = u_mean / 1024.0 * Q28;
            const int32_t u = (int32_t)((u_q >= 0.0) ? u_q + 0.5 : u_q - 0.5);
            ps_filter_history_q(&q.k, &xq, u, &h);
            ps_filter_update_q(&q.k, &xq, &h, ps_filter_node_q(&q.k, &xq, &h, 0), 0, sat);
            v = (double)xq.v_c * (1024.0 / Q28);
            i = (double)xq.i_l * (256.0 / Q28);
        } else {
            ps_hist_f32 h;
            ps_filter_history_f32(&s.k, &xf, (float)u_mean, &h);
            ps_filter_update_f32(&s.k, &xf, &h, ps_filter_node_f32(&s.k, &xf, &h, 0.0f), 0.0f, sat);
            v = (double)xf.v_c;
            i = (double)xf.i_l;
        }
        ck = cn;
        sk = sn;
        if (k >= settle) { /* samples at t_k+1 against exp(-j w t_k+1) */
            vr += v * ck;
            vi -= v * sk;
            ir += i * ck;
            ii -= i * sk;
        }
    }
    /* X = (2/N) sum; input phasor -jU: H = X / (-jU) = j X / U. */
    *h_v = c_make(-2.0 * vi / (double)n / u_amp, 2.0 * vr / (double)n / u_amp);
    *h_i = c_make(-2.0 * ii / (double)n / u_amp, 2.0 * ir / (double)n / u_amp);
}

/* Relative amplitude error and phase error [deg] of meas against ref. */
static void compare_response(cplx meas, cplx ref, double *mag_err, double *ph_err_deg) {
    const cplx r = c_div(meas, ref);
    *mag_err = math_sqrt_f64(r.re * r.re + r.im * r.im) - 1.0;
    *ph_err_deg = math_atan2_f64(r.im, r.re) * (180.0 / MATH_PI_F64);
}

static void test_filter_response(int fixed) {
    /* Below, at and above the corner; whole periods fit the 5 ms window. */
    static const double f_list[3] = {200.0, 1000.0, 5000.0};
    unsigned i;
    for (i = 0u; i < 3u; i++) {
        cplx hv;
        cplx hi;
        cplx rv;
        cplx ri;
        double mv, pv, mi, pi_;
        uint32_t sat;
        filter_measure(fixed, f_list[i], 5000u, 2500u, &hv, &hi, &sat);
        filter_analytic(&power_stage_params_default, f_list[i], &rv, &ri);
        compare_response(hv, rv, &mv, &pv);
        compare_response(hi, ri, &mi, &pi_);
        ut_info("%s %4.0f Hz: |H| %.5f (analytic %.5f), amplitude error %.4f %%, phase error "
                "%.4f deg; i_L/u error %.4f %% %.4f deg",
                twin_name(fixed), f_list[i], math_sqrt_f64(hv.re * hv.re + hv.im * hv.im),
                math_sqrt_f64(rv.re * rv.re + rv.im * rv.im), 100.0 * mv, pv, 100.0 * mi, pi_);
        UT_NEAR(mv, 0.0, 0.005);
        UT_NEAR(pv, 0.0, 0.5);
        UT_NEAR(mi, 0.0, 0.005);
        UT_NEAR(pi_, 0.0, 0.5);
        UT_EQ_INT(sat, 0u);
    }
}

/* ---- A stage of either twin, in SI units at its boundary -------------------------- */

typedef struct {
    int fixed;
    power_stage_q q;
    power_stage_f32 f;
    ps_battery_q bq;
    ps_battery_f32 bf;
    double i_m[3];    /* [A] motor currents held */
    double duty[3];   /* [-] */
} tstage;

static int tstage_init(tstage *t, int fixed, uint32_t step_ns, double v_dc0) {
    unsigned x;
    t->fixed = fixed;
    for (x = 0u; x < 3u; x++) {
        t->i_m[x] = 0.0;
        t->duty[x] = 0.0;
    }
    if (fixed) {
        return power_stage_init_q(&t->q, &power_stage_params_default, step_ns, v_dc0) == PS_OK;
    }
    return power_stage_init_f32(&t->f, &power_stage_params_default, step_ns, v_dc0) == PS_OK;
}

static uint32_t tstage_battery(tstage *t, double g_s, double b_a) {
    if (t->fixed) {
        return power_stage_battery_q(&t->q, g_s, b_a, &t->bq);
    }
    return power_stage_battery_f32(&t->f, g_s, b_a, &t->bf);
}

static void tstage_step(tstage *t) {
    unsigned x;
    if (t->fixed) {
        power_stage_in_q in;
        for (x = 0u; x < 3u; x++) {
            in.duty[x] = (int32_t)(t->duty[x] * 32768.0 + 0.5);
            in.i_motor[x] = fp_pu_from_f64_q15(t->i_m[x], 256.0);
        }
        in.battery = t->bq;
        power_stage_step_q(&t->q, &in);
    } else {
        power_stage_in_f32 in;
        for (x = 0u; x < 3u; x++) {
            in.duty[x] = (float)t->duty[x];
            in.i_motor_a[x] = (float)t->i_m[x];
        }
        in.battery = t->bf;
        power_stage_step_f32(&t->f, &in);
    }
}

/* The states in SI units (phase c from a and b). */
typedef struct {
    double v_dc, i_dc;
    double u[3], v_c[3], i_l[3], v_d[3], i_d[3];
    double e_bat, g_bat;
    uint32_t sat;
} tstate;

/* Reads either twin's stage (the other pointer may be NULL). */
static void stage_read(const power_stage_q *q, const ps_battery_q *bq, const power_stage_f32 *f,
                       const ps_battery_f32 *bf, tstate *s) {
    unsigned x;
    if (q != NULL) {
        const double kv = 1024.0 / Q28;
        const double ki = 256.0 / Q28;
        s->v_dc = q->v_dc * kv;
        s->i_dc = q->i_dc * ki;
        for (x = 0u; x < 2u; x++) {
            s->u[x] = q->u[x] * kv;
            s->v_c[x] = q->ph[x].v_c * kv;
            s->i_l[x] = q->ph[x].i_l * ki;
            s->i_d[x] = q->ph[x].i_d * ki;
        }
        s->e_bat = bq->e * kv;
        s->g_bat = (double)bq->g / 16777216.0 / 4.0;
        s->sat = q->sat_count;
    } else {
        s->v_dc = (double)f->v_dc;
        s->i_dc = (double)f->i_dc;
        for (x = 0u; x < 2u; x++) {
            s->u[x] = (double)f->u[x];
            s->v_c[x] = (double)f->ph[x].v_c;
            s->i_l[x] = (double)f->ph[x].i_l;
            s->i_d[x] = (double)f->ph[x].i_d;
        }
        s->e_bat = (double)bf->e_v;
        s->g_bat = (double)bf->g_s;
        s->sat = f->sat_count;
    }
    s->u[2] = -s->u[0] - s->u[1];
    s->v_c[2] = -s->v_c[0] - s->v_c[1];
    s->i_l[2] = -s->i_l[0] - s->i_l[1];
    s->i_d[2] = -s->i_d[0] - s->i_d[1];
    for (x = 0u; x < 3u; x++) { /* the damping capacitor: v_d = v - R_d i_d */
        s->v_d[x] = s->v_c[x] - power_stage_params_default.r_d_ohm * s->i_d[x];
    }
}

static void tstage_read(const tstage *t, tstate *s) {
    if (t->fixed) {
        stage_read(&t->q, &t->bq, NULL, NULL, s);
    } else {
        stage_read(NULL, NULL, &t->f, &t->bf, s);
    }
}

/* The pack's companion from the battery model at a state of charge. */
static void pack_companion(double soc, double *g_s, double *b_a) {
    battery b;
    battery_companion c;
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, soc), BATTERY_OK);
    c = battery_companion_f64(&b);
    *g_s = c.g_s;
    *b_a = c.b_a;
}

/* ---- B. DC link ----------------------------------------------------------------------- */

static void test_dclink(int fixed) {
    tstage t;
    double g_s;
    double b_a;
    const double i_dc = 20.0;
    uint32_t k;
    uint32_t sat = 0u;
    double v = 0.0;
    double v_tau = 0.0;
    double e;
    double tau;
    uint32_t k_tau;

    pack_companion(1.0, &g_s, &b_a);
    e = b_a / g_s;
    tau = power_stage_params_default.c_dc_f / g_s;
    k_tau = (uint32_t)(tau / STEP_S + 0.5);
    UT_CHECK(tstage_init(&t, fixed, STEP_NS, e));
    UT_EQ_INT(tstage_battery(&t, g_s, b_a), 0u);
    /* A constant inverter current from a bus precharged to e: v -> e - i_dc / G. */
    for (k = 1u; k <= 20u * k_tau; k++) {
        if (fixed) {
            const int32_t idc = (int32_t)(i_dc / 256.0 * Q28);
            t.q.v_dc = ps_dclink_step_q(t.q.v_dc, &t.bq, t.q.k.neg_k_c, idc, &sat);
            v = t.q.v_dc * (1024.0 / Q28);
        } else {
            t.f.v_dc = ps_dclink_step_f32(t.f.v_dc, &t.bf, t.f.k.neg_k_c, 2.0f * (float)i_dc, &sat);
            v = (double)t.f.v_dc;
        }
        if (k == k_tau) {
            v_tau = v;
        }
    }
    {
        const double v_ss = e - i_dc / g_s;
        const double v_tau_ref =
            e - (i_dc / g_s) * (1.0 - math_exp_f64(-(double)k_tau * STEP_S / tau));
        ut_info("%s: e = %.3f V, R = %.4f ohm, tau = %.1f us; steady %.4f V (circuit %.4f V), "
                "battery current %.4f A; at t = tau %.4f V (exponential %.4f V)",
                twin_name(fixed), e, 1.0 / g_s, tau * 1.0e6, v, v_ss, g_s * (e - v), v_tau,
                v_tau_ref);
        UT_NEAR(v, v_ss, 0.01);
        UT_NEAR(g_s * (e - v), i_dc, 0.01);
        /* Forward Euler: the error of the drop at t = tau is of order T / tau. */
        UT_NEAR((e - v_tau) / (e - v_tau_ref), 1.0, 0.005);
        UT_EQ_INT(sat, 0u);
    }
}

/* ---- Switching and averaged runs with a load ------------------------------------------ */

typedef struct {
    int fixed;
    int averaged;      /* 0: pwm + stage at 2 us; 1: inverter_avg at 100 us */
    uint32_t n_sub;    /* averaged: substeps per call */
    uint32_t frame_ns; /* averaged: [ns] step of one call (the load is held 100 us anyway) */
    double m;
    double f_hz;
    double r_load;     /* [ohm] star resistance, load current held over 100 us */
    double soc;        /* battery state of charge for the companion */
} trun_cfg;

typedef struct {
    tstage st;
    pwm_q pq;
    pwm_f32 pf;
    inverter_avg_q aq;
    inverter_avg_f32 af;
    trun_cfg cfg;
    double t_s;        /* [s] time at the end of the last frame */
} trun;

static int trun_init(trun *r, const trun_cfg *cfg) {
    double g_s;
    double b_a;
    uint32_t inc;
    r->cfg = *cfg;
    r->t_s = 0.0;
    pack_companion(cfg->soc, &g_s, &b_a);
    if (cfg->averaged) {
        if (cfg->fixed) {
            if (inverter_avg_init_q(&r->aq, &pwm_params_default, &power_stage_params_default,
                                    cfg->frame_ns, cfg->n_sub, b_a / g_s) != INVERTER_AVG_OK) {
                return 0;
            }
            power_stage_battery_q(&r->aq.stage, g_s, b_a, &r->st.bq);
            inc = wt_phase_inc_q16((int32_t)(cfg->f_hz * 65536.0 + 0.5),
                                   cfg->frame_ns / cfg->n_sub);
            pwm_command_inc_q(&r->aq.mod, fp_from_f64_q15(cfg->m), inc);
        } else {
            if (inverter_avg_init_f32(&r->af, &pwm_params_default, &power_stage_params_default,
                                      cfg->frame_ns, cfg->n_sub, b_a / g_s) != INVERTER_AVG_OK) {
                return 0;
            }
            power_stage_battery_f32(&r->af.stage, g_s, b_a, &r->st.bf);
            inc = wt_phase_inc_q16((int32_t)(cfg->f_hz * 65536.0 + 0.5),
                                   cfg->frame_ns / cfg->n_sub);
            pwm_command_inc_f32(&r->af.mod, (float)cfg->m, inc);
        }
        r->st.fixed = cfg->fixed;
        return 1;
    }
    if (!tstage_init(&r->st, cfg->fixed, STEP_NS, b_a / g_s)) {
        return 0;
    }
    tstage_battery(&r->st, g_s, b_a);
    inc = wt_phase_inc_q16((int32_t)(cfg->f_hz * 65536.0 + 0.5), STEP_NS);
    if (cfg->fixed) {
        pwm_init_q(&r->pq, &pwm_params_default, STEP_NS);
        pwm_command_inc_q(&r->pq, fp_from_f64_q15(cfg->m), inc);
    } else {
        pwm_init_f32(&r->pf, &pwm_params_default, STEP_NS);
        pwm_command_inc_f32(&r->pf, (float)cfg->m, inc);
    }
    return 1;
}

/* The averaged instance's stage seen through tstage_read. */
static void trun_read(const trun *r, tstate *s) {
    if (!r->cfg.averaged) {
        tstage_read(&r->st, s);
    } else if (r->cfg.fixed) {
        stage_read(&r->aq.stage, &r->st.bq, NULL, NULL, s);
    } else {
        stage_read(NULL, NULL, &r->af.stage, &r->st.bf, s);
    }
}

/* One 2 us step of the switching run. */
static void trun_fast_step(trun *r) {
    unsigned x;
    if (r->cfg.fixed) {
        pwm_out_q o;
        pwm_step_q(&r->pq, &o);
        for (x = 0u; x < 3u; x++) {
            r->st.duty[x] = (double)o.duty[x] / 32768.0;
        }
    } else {
        pwm_out_f32 o;
        pwm_step_f32(&r->pf, &o);
        for (x = 0u; x < 3u; x++) {
            r->st.duty[x] = (double)o.duty[x];
        }
    }
    tstage_step(&r->st);
}

/* Sets the held load currents from the present capacitor voltages. */
static void trun_load(trun *r) {
    tstate s;
    unsigned x;
    trun_read(r, &s);
    for (x = 0u; x < 3u; x++) {
        r->st.i_m[x] = s.v_c[x] / r->cfg.r_load;
    }
}

/*
 * Sets the held load currents to a prescribed balanced set, amp [A] lagging
 * the modulator's reference by 30 deg, taken at t_s (the frame start).
 */
static void trun_load_prescribed(trun *r, double t_s, double amp) {
    unsigned x;
    for (x = 0u; x < 3u; x++) {
        const double th = 2.0 * MATH_PI_F64 * (r->cfg.f_hz * t_s - (double)x / 3.0 - 1.0 / 12.0);
        r->st.i_m[x] = amp * math_sin_f64(th);
    }
}

/* One call (frame_ns) of the averaged run. */
static void trun_avg_frame(trun *r) {
    if (r->cfg.fixed) {
        power_stage_in_q in;
        unsigned x;
        for (x = 0u; x < 3u; x++) {
            in.duty[x] = 0;
            in.i_motor[x] = fp_pu_from_f64_q15(r->st.i_m[x], 256.0);
        }
        in.battery = r->st.bq;
        inverter_avg_step_q(&r->aq, &in);
    } else {
        power_stage_in_f32 in;
        unsigned x;
        for (x = 0u; x < 3u; x++) {
            in.duty[x] = 0.0f;
            in.i_motor_a[x] = (float)r->st.i_m[x];
        }
        in.battery = r->st.bf;
        inverter_avg_step_f32(&r->af, &in);
    }
}

/* ---- C. Energy balance of the switching stage ------------------------------------------ */

typedef struct {
    double bus_in;   /* [J] sum T v_dc G (e - v_dc): delivered by the battery to the bus */
    double load;     /* [J] sum T v_C_mean i_m */
    double loss_rl;  /* [J] sum T R_L i_L_mean^2 */
    double loss_rd;  /* [J] sum T R_d i_d_mean^2 */
    double stored;   /* [J] change of the energy in C_dc, L, C, C_d */
} tenergy;

static double stored_energy(const tstate *s) {
    const power_stage_params *p = &power_stage_params_default;
    double e = 0.5 * p->c_dc_f * s->v_dc * s->v_dc;
    unsigned x;
    for (x = 0u; x < 3u; x++) {
        e += 0.5 * p->l_h * s->i_l[x] * s->i_l[x] + 0.5 * p->c_f * s->v_c[x] * s->v_c[x] +
             0.5 * p->c_d_f * s->v_d[x] * s->v_d[x];
    }
    return e;
}

static void test_energy_balance(int fixed) {
    const power_stage_params *p = &power_stage_params_default;
    trun_cfg cfg = {0, 0, 1u, FRAME_NS, 0.8, 50.0, 9.3, 1.0};
    trun r;
    tenergy en = {0.0, 0.0, 0.0, 0.0, 0.0};
    tstate s0;
    tstate s1;
    tstate start = {0};
    uint32_t k;
    const uint32_t settle = 2500u; /* the balance holds in transients too */
    const uint32_t window = 5000u;
    double balance;
    double v_min = 1.0e9;
    double v_max = 0.0;
    double i_max = 0.0;

    cfg.fixed = fixed;
    if (!UT_CHECK(trun_init(&r, &cfg))) {
        return;
    }
    for (k = 0u; k < settle + window; k++) {
        unsigned x;
        if (k % STEPS_PER_FRAME == 0u) {
            trun_load(&r);
        }
        trun_read(&r, &s0);
        if (k == settle) {
            start = s0;
        }
        trun_fast_step(&r);
        trun_read(&r, &s1);
        if (k >= settle) {
            v_min = (s1.v_dc < v_min) ? s1.v_dc : v_min;
            v_max = (s1.v_dc > v_max) ? s1.v_dc : v_max;
            i_max = (absd(s1.i_l[0]) > i_max) ? absd(s1.i_l[0]) : i_max;
            en.bus_in += STEP_S * s0.v_dc * s0.g_bat * (s0.e_bat - s0.v_dc);
            for (x = 0u; x < 3u; x++) {
                const double il = 0.5 * (s0.i_l[x] + s1.i_l[x]);
                const double id = 0.5 * (s0.i_d[x] + s1.i_d[x]);
                en.load += STEP_S * 0.5 * (s0.v_c[x] + s1.v_c[x]) * r.st.i_m[x];
                en.loss_rl += STEP_S * p->r_l_ohm * il * il;
                en.loss_rd += STEP_S * p->r_d_ohm * id * id;
            }
        }
    }
    en.stored = stored_energy(&s1) - stored_energy(&start);
    balance = en.bus_in - (en.load + en.loss_rl + en.loss_rd + en.stored);
    ut_info("%s, m 0.8, 50 Hz, 9.3 ohm, 10 ms: battery to bus %.3f J = load %.3f J + R_L %.4f J "
            "+ R_d %.4f J + stored %.4f J; residual %.2e of the input",
            twin_name(fixed), en.bus_in, en.load, en.loss_rl, en.loss_rd, en.stored,
            balance / en.bus_in);
    ut_info("%s: load power %.1f W, bus %.2f..%.2f V (ripple %.2f V p-p), peak i_L %.2f A",
            twin_name(fixed), en.load / 0.01, v_min, v_max, v_max - v_min, i_max);
    UT_NEAR(balance / en.bus_in, 0.0, 0.001);
    UT_EQ_INT(s1.sat, 0u);
}

/* ---- D. Averaged against switching inverter --------------------------------------------- */

typedef struct {
    double v_amp, v_ph, i_amp, i_ph, v_dc_mean;
    uint32_t sat;
} tfund;

/*
 * Runs cfg for settle_frames, then measures 50 Hz fundamentals over one
 * period, sampling after every call: 50 calls of 2 us per frame for the
 * switching stage, calls_per_frame calls of the averaged inverter (whose
 * frame is then 100 us / calls_per_frame, one substep each). The load is a
 * prescribed balanced current of 26 A (lagging 30 deg, about 9.3 kW at
 * these voltages), held over each 100 us frame as the executive will hold
 * the motor's currents: the same stimulus for both models. (A resistive
 * load fed from a sample of v_C per frame would alias the switching
 * model's ripple at 2 f_c +- f1 into the fundamental.)
 */
static void run_fundamentals(const trun_cfg *cfg, uint32_t calls_per_frame,
                             uint32_t settle_frames, tfund *out) {
    trun r;
    tdft dv;
    tdft di;
    const uint32_t frames = 200u; /* 20 ms */
    const uint32_t calls = cfg->averaged ? calls_per_frame : STEPS_PER_FRAME;
    const uint32_t inc = wt_phase_inc_q16((int32_t)(cfg->f_hz * 65536.0 + 0.5), FRAME_NS / calls);
    uint32_t fr;
    uint32_t k;
    double vdc_sum = 0.0;
    tstate s;

    if (!UT_CHECK(trun_init(&r, cfg))) {
        out->v_amp = out->v_ph = out->i_amp = out->i_ph = out->v_dc_mean = 0.0;
        out->sat = 1u;
        return;
    }
    /* Samples at the call ends: the basis starts one call after the window start. */
    tdft_init(&dv, inc, inc);
    tdft_init(&di, inc, inc);
    for (fr = 0u; fr < settle_frames + frames; fr++) {
        trun_load_prescribed(&r, (double)fr * (FRAME_NS * 1.0e-9), 26.0);
        for (k = 0u; k < calls; k++) {
            if (cfg->averaged) {
                trun_avg_frame(&r);
            } else {
                trun_fast_step(&r);
            }
            if (fr >= settle_frames) {
                trun_read(&r, &s);
                tdft_add(&dv, s.v_c[0]);
                tdft_add(&di, s.i_l[0]);
                vdc_sum += s.v_dc;
            }
        }
    }
    trun_read(&r, &s);
    out->v_amp = tdft_amp(&dv);
    out->v_ph = tdft_phase_deg(&dv);
    out->i_amp = tdft_amp(&di);
    out->i_ph = tdft_phase_deg(&di);
    out->v_dc_mean = vdc_sum / (double)(frames * calls);
    out->sat = s.sat;
}

/*
 * The averaged inverter at 25 us (four calls per frame, as its 100 us frame
 * with four substeps) and at 100 us without substeps. The inductor current
 * contains the frame-held load current; sampled only at the frame ends (the
 * 100 us run) that staircase appears half a frame later than in the dense
 * samples of the switching run, 0.9 deg at 50 Hz: hence the wider phase
 * tolerance of the current there.
 */
static void test_averaged_vs_switching(int fixed) {
    static const uint32_t calls[2] = {4u, 1u};
    static const double tol_ph_i[2] = {0.5, 1.5};
    trun_cfg sw = {0, 0, 1u, FRAME_NS, 0.8, 50.0, 9.3, 1.0};
    tfund fs;
    unsigned i;

    sw.fixed = fixed;
    run_fundamentals(&sw, 1u, 200u, &fs);
    ut_info("%s switching 2 us: v_C1 %.3f V %.3f deg, i_L1 %.3f A %.3f deg, mean v_dc %.3f V",
            twin_name(fixed), fs.v_amp, fs.v_ph, fs.i_amp, fs.i_ph, fs.v_dc_mean);
    UT_EQ_INT(fs.sat, 0u);
    for (i = 0u; i < 2u; i++) {
        trun_cfg av = sw;
        tfund fa;
        av.averaged = 1;
        av.frame_ns = FRAME_NS / calls[i];
        run_fundamentals(&av, calls[i], 200u, &fa);
        ut_info("%s averaged %u us: v_C1 %.3f V %.3f deg, i_L1 %.3f A %.3f deg, mean v_dc %.3f V; "
                "differences %.3f %% %.3f deg, %.3f %% %.3f deg, %.3f %%",
                twin_name(fixed), (unsigned)(av.frame_ns / 1000u), fa.v_amp, fa.v_ph, fa.i_amp,
                fa.i_ph, fa.v_dc_mean, 100.0 * (fa.v_amp / fs.v_amp - 1.0),
                tdft_wrap_deg(fa.v_ph - fs.v_ph), 100.0 * (fa.i_amp / fs.i_amp - 1.0),
                tdft_wrap_deg(fa.i_ph - fs.i_ph), 100.0 * (fa.v_dc_mean / fs.v_dc_mean - 1.0));
        UT_NEAR(fa.v_amp / fs.v_amp, 1.0, 0.005);
        UT_NEAR(tdft_wrap_deg(fa.v_ph - fs.v_ph), 0.0, 0.5);
        UT_NEAR(fa.i_amp / fs.i_amp, 1.0, 0.005);
        UT_NEAR(tdft_wrap_deg(fa.i_ph - fs.i_ph), 0.0, tol_ph_i[i]);
        UT_NEAR(fa.v_dc_mean / fs.v_dc_mean, 1.0, 0.005);
        UT_EQ_INT(fa.sat, 0u);
    }
}

/* ---- E. Fixed against float ----------------------------------------------------------------- */

static void test_fixed_vs_float(int averaged) {
    trun_cfg cfg = {1, 0, 4u, FRAME_NS, 0.8, 50.0, 9.3, 1.0};
    trun rq;
    trun rf;
    tstate sq;
    tstate sf;
    uint32_t fr;
    uint32_t k;
    double di = 0.0;
    double dv = 0.0;
    double ddc = 0.0;
    unsigned x;
    const uint32_t steps = averaged ? 1u : STEPS_PER_FRAME;

    cfg.averaged = averaged;
    if (!UT_CHECK(trun_init(&rq, &cfg))) {
        return;
    }
    cfg.fixed = 0;
    if (!UT_CHECK(trun_init(&rf, &cfg))) {
        return;
    }
    /* From rest (filter at zero, bus precharged), 15 ms, the load held per frame. */
    for (fr = 0u; fr < 150u; fr++) {
        trun_load(&rq);
        trun_load(&rf);
        for (k = 0u; k < steps; k++) {
            if (averaged) {
                trun_avg_frame(&rq);
                trun_avg_frame(&rf);
            } else {
                trun_fast_step(&rq);
                trun_fast_step(&rf);
            }
            trun_read(&rq, &sq);
            trun_read(&rf, &sf);
            for (x = 0u; x < 3u; x++) {
                di = (absd(sq.i_l[x] - sf.i_l[x]) > di) ? absd(sq.i_l[x] - sf.i_l[x]) : di;
                dv = (absd(sq.v_c[x] - sf.v_c[x]) > dv) ? absd(sq.v_c[x] - sf.v_c[x]) : dv;
            }
            ddc = (absd(sq.v_dc - sf.v_dc) > ddc) ? absd(sq.v_dc - sf.v_dc) : ddc;
        }
    }
    ut_info("%s, 15 ms from rest: largest differences i_L %.4f A (%.4f %% of 256 A), v_C %.4f V, "
            "v_dc %.4f V (%.4f %% of 1024 V)",
            averaged ? "averaged" : "switching", di, 100.0 * di / 256.0, dv, ddc,
            100.0 * ddc / 1024.0);
    UT_CHECK(di < 0.01 * 256.0);
    UT_CHECK(dv < 0.005 * 1024.0);
    UT_CHECK(ddc < 0.005 * 1024.0);
    UT_EQ_INT(sq.sat, 0u);
    UT_EQ_INT(sf.sat, 0u);
}

/* ---- F. Worst case of the range analysis --------------------------------------------------- */

/*
 * Start from rest with the battery at its 432 V cut-off (e = 450 V behind
 * the pack's 0.62 ohm), full modulation at 55 Hz, and a locked-rotor-like
 * motor current of 120 A peak lagging by 60 deg from the first step on. The
 * peaks must stay inside the +-1 per-unit range without a clamp.
 */
static void test_worst_case(int fixed) {
    tstage t;
    pwm_q pq;
    pwm_f32 pf;
    tstate s;
    const uint32_t inc = wt_phase_inc_q16((int32_t)(55.0 * 65536.0), STEP_NS);
    uint32_t ph = 0u;
    uint32_t k;
    unsigned x;
    double pk_i = 0.0, pk_v = 0.0, min_dc = 1.0e9, max_dc = 0.0, pk_idc = 0.0;

    UT_CHECK(tstage_init(&t, fixed, STEP_NS, 450.0));
    UT_EQ_INT(tstage_battery(&t, 1.0 / 0.62, 450.0 / 0.62), 0u);
    if (fixed) {
        pwm_init_q(&pq, &pwm_params_default, STEP_NS);
        pwm_command_inc_q(&pq, Q15_MAX, inc);
    } else {
        pwm_init_f32(&pf, &pwm_params_default, STEP_NS);
        pwm_command_inc_f32(&pf, 1.0f, inc);
    }
    for (k = 0u; k < 10000u; k++) {
        if (k % STEPS_PER_FRAME == 0u) {
            for (x = 0u; x < 3u; x++) {
                const uint32_t phx = ph - (uint32_t)x * WT_PHASE_120 - 0x2AAAAAABu; /* -60 deg */
                t.i_m[x] = 120.0 * (double)wt_sin_f32(phx);
            }
        }
        if (fixed) {
            pwm_out_q o;
            pwm_step_q(&pq, &o);
            for (x = 0u; x < 3u; x++) {
                t.duty[x] = (double)o.duty[x] / 32768.0;
            }
        } else {
            pwm_out_f32 o;
            pwm_step_f32(&pf, &o);
            for (x = 0u; x < 3u; x++) {
                t.duty[x] = (double)o.duty[x];
            }
        }
        ph += inc;
        tstage_step(&t);
        tstage_read(&t, &s);
        for (x = 0u; x < 3u; x++) {
            pk_i = (absd(s.i_l[x]) > pk_i) ? absd(s.i_l[x]) : pk_i;
            pk_v = (absd(s.v_c[x]) > pk_v) ? absd(s.v_c[x]) : pk_v;
        }
        pk_idc = (absd(s.i_dc) > pk_idc) ? absd(s.i_dc) : pk_idc;
        min_dc = (s.v_dc < min_dc) ? s.v_dc : min_dc;
        max_dc = (s.v_dc > max_dc) ? s.v_dc : max_dc;
    }
    ut_info("%s: peaks |i_L| %.1f A, |v_C| %.1f V, |i_dc| %.1f A, v_dc %.1f..%.1f V, sat %u",
            twin_name(fixed), pk_i, pk_v, pk_idc, min_dc, max_dc, (unsigned)s.sat);
    UT_CHECK(pk_i < 0.75 * 256.0);
    UT_CHECK(pk_v < 0.75 * 1024.0);
    UT_CHECK(max_dc < 0.75 * 1024.0);
    UT_EQ_INT(s.sat, 0u);
}

/* ---- G. Saturation ---------------------------------------------------------------------- */

/*
 * Driven far out of range (a 1020 V source, full duty on one leg, the
 * largest motor current the Q15 input can carry drawn from the same phase
 * for 2000 steps), both twins clamp, count, and keep every state within
 * +-1 per unit.
 */
static void test_saturation(int fixed) {
    tstage t;
    tstate s;
    uint32_t k;
    unsigned x;
    int inside = 1;

    UT_CHECK(tstage_init(&t, fixed, STEP_NS, 1000.0));
    tstage_battery(&t, 4.0, 4.0 * 1020.0);
    t.duty[0] = 1.0;
    t.i_m[0] = -255.9;
    t.i_m[1] = 127.9;
    for (k = 0u; k < 2000u; k++) {
        tstage_step(&t);
        tstage_read(&t, &s);
        for (x = 0u; x < 3u; x++) {
            inside = inside && absd(s.i_l[x]) <= 512.0 && absd(s.v_c[x]) <= 2048.0;
        }
        inside = inside && absd(s.v_dc) <= 1024.0;
    }
    ut_info("%s: %u clamps counted, v_dc %.1f V, v_C,a %.1f V, i_L,a %.1f A", twin_name(fixed),
            (unsigned)s.sat, s.v_dc, s.v_c[0], s.i_l[0]);
    UT_CHECK(s.sat > 0u);
    UT_CHECK(inside);
}

/* ---- H. Set-up, battery conversion, outputs ------------------------------------------------- */

static void test_setup_and_outputs(void) {
    power_stage_q q;
    power_stage_f32 f;
    power_stage_params bad = power_stage_params_default;
    ps_battery_q bq;
    ps_battery_f32 bf;
    power_stage_out_q oq;
    power_stage_out_f32 of;
    power_stage_in_q iq;
    power_stage_in_f32 inf;
    unsigned x;

    UT_EQ_INT(power_stage_init_q(NULL, &bad, STEP_NS, 500.0), PS_ERR_NULL);
    UT_EQ_INT(power_stage_init_q(&q, &bad, 50u, 500.0), PS_ERR_STEP);
    UT_EQ_INT(power_stage_init_f32(&f, &bad, STEP_NS, 1024.0), PS_ERR_VOLTAGE);
    UT_EQ_INT(power_stage_init_q(&q, &bad, 1000000u, 500.0), PS_ERR_FIXED_RANGE);
    UT_EQ_INT(power_stage_init_f32(&f, &bad, 1000000u, 500.0), PS_OK);
    bad.c_f = 0.0;
    UT_EQ_INT(power_stage_init_q(&q, &bad, STEP_NS, 500.0), PS_ERR_PARAM);
    bad = power_stage_params_default;
    bad.r_l_ohm = -0.1;
    UT_EQ_INT(power_stage_init_f32(&f, &bad, STEP_NS, 500.0), PS_ERR_PARAM);
    UT_EQ_INT(power_stage_init_q(&q, &power_stage_params_default, STEP_NS, 500.0), PS_OK);
    UT_EQ_INT(power_stage_init_f32(&f, &power_stage_params_default, STEP_NS, 500.0), PS_OK);

    /* Battery: e = b / G; an open contactor gives zeros; an absurd G is clamped and counted. */
    UT_EQ_INT(power_stage_battery_q(&q, 2.0, 1200.0, &bq), 0u);
    UT_NEAR((double)bq.e * 1024.0 / Q28, 600.0, 1e-5);
    UT_NEAR((double)bq.kg / 4294967296.0, STEP_S * 2.0 / 470.0e-6, 1e-9);
    UT_EQ_INT(power_stage_battery_f32(&f, 2.0, 1200.0, &bf), 0u);
    UT_NEAR(bf.e_v, 600.0, 1e-4);
    UT_EQ_INT(power_stage_battery_q(&q, 0.0, 0.0, &bq), 0u);
    UT_EQ_INT(bq.e, 0);
    UT_EQ_INT(bq.kg, 0);
    UT_CHECK(power_stage_battery_q(&q, 1.0e6, 6.0e8, &bq) >= 1u);
    UT_CHECK(power_stage_battery_f32(&f, -1.0, 6.0e8, &bf) >= 1u);
    UT_NEAR(bf.kg, 0.0, 0.0);

    /* Outputs: one step with leg a on, b and c off, from 500 V, 20 A into motor a. */
    power_stage_battery_q(&q, 2.0, 1200.0, &bq);
    power_stage_battery_f32(&f, 2.0, 1200.0, &bf);
    for (x = 0u; x < 3u; x++) {
        iq.duty[x] = (x == 0u) ? PWM_DUTY_ONE_Q : 0;
        inf.duty[x] = (x == 0u) ? 1.0f : 0.0f;
        iq.i_motor[x] = 0;
        inf.i_motor_a[x] = 0.0f;
    }
    iq.battery = bq;
    inf.battery = bf;
    power_stage_step_q(&q, &iq);
    power_stage_step_f32(&f, &inf);
    power_stage_output_q(&q, &bq, &oq);
    power_stage_output_f32(&f, &bf, &of);
    /* u = 500 V (2/3, -1/3, -1/3); the bus gains (T/C)(G(e - v)) = 0.85 V, less i_dc. */
    UT_NEAR(fp_pu_to_f64_q15(oq.v_inv[0], 1024.0), 1000.0 / 3.0, 0.04);
    UT_NEAR(fp_pu_to_f64_q15(oq.v_inv[1], 1024.0), -500.0 / 3.0, 0.04);
    UT_NEAR(fp_pu_to_f64_q15(oq.v_inv[2], 1024.0), -500.0 / 3.0, 0.04);
    UT_NEAR(of.v_inv_v[0], 1000.0 / 3.0, 1e-3);
    UT_NEAR(of.v_inv_v[2], -500.0 / 3.0, 1e-3);
    UT_NEAR(fp_pu_to_f64_q15(oq.v_dc, 1024.0), of.v_dc_v, 0.04);
    UT_NEAR(fp_pu_to_f64_q15(oq.i_l[0], 256.0), of.i_l_a[0], 0.01);
    UT_NEAR(fp_pu_to_f64_q15(oq.i_l[0], 256.0) + fp_pu_to_f64_q15(oq.i_l[1], 256.0) +
                fp_pu_to_f64_q15(oq.i_l[2], 256.0),
            0.0, 0.02);
    UT_NEAR(fp_pu_to_f64_q15(oq.i_dc, 256.0), of.i_dc_a, 0.01);
    UT_NEAR(of.i_dc_a, 0.5 * (double)of.i_l_a[0], 1e-4); /* mean of 0 and i_L,a: leg a alone */
    /* Battery current into the terminal: G (v - e), negative while discharging. */
    UT_NEAR(of.i_bat_a, 2.0 * ((double)of.v_dc_v - 600.0), 1e-3);
    UT_NEAR(fp_pu_to_f64_q15(oq.i_bat, 256.0), of.i_bat_a, 0.02);
    UT_CHECK(of.i_bat_a < 0.0f);
}

/*
 * The fast step (power_stage_fast.h) against the general step: duties from
 * the real-time modulator (pwm_rt.h, sampled or sub-step, m = 0.9 at 50 Hz,
 * ramps over 50-step frames), the general step given the same duties, on
 * two copies of the same instance with the same motor currents (a 50 Hz
 * set of the given amplitude); every state and the clamp count compared bit
 * for bit after every step.
 */
static void rt_duties(pwm_rt *rt, int substep, int32_t duty[3]) {
    int32_t st[3];
    if (substep) {
        pwm_rt_substep_each(rt, st, duty);
    } else {
        pwm_rt_sampled(rt, st, duty);
    }
}

static void test_fused_step(int fixed, int substep, double amp_a, uint32_t steps) {
    const pwm_params sampled = pwm_params_sampled;
    const uint32_t inc = wt_phase_inc_q16(50 * 65536, STEP_NS);
    uint32_t k;
    int same = 1;
    uint32_t sat = 0u;
    pwm_rt rt;
    uint32_t ref_ph = 0u;
    UT_CHECK(pwm_rt_init(&rt, &sampled, STEP_NS) == PWM_OK);
    if (fixed) {
        power_stage_q sa, sb;
        power_stage_in_q in = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        power_stage_init_q(&sa, &power_stage_params_default, STEP_NS, 600.0);
        power_stage_battery_q(&sa, 2.0, 1200.0, &in.battery);
        sb = sa;
        for (k = 0u; k < steps; k++) {
            int32_t st[3];
            double w = 2.0 * MATH_PI_F64 * 50.0 * STEP_S * (double)k;
            if (k % 50u == 0u) {
                pwm_rt_ramp ramp;
                pwm_rt_ramp_q(&ramp, NULL, 29491, ref_ph, inc, 50u);
                pwm_rt_apply(&rt, &ramp);
                ref_ph += 50u * inc;
            }
            in.i_motor[0] = fp_from_f64_q15(amp_a / 256.0 * math_sin_f64(w));
            in.i_motor[1] = fp_from_f64_q15(amp_a / 256.0 * math_sin_f64(w - 2.0 * MATH_PI_F64 / 3.0));
            rt_duties(&rt, substep, st);
            for (unsigned x = 0u; x < 3u; x++) {
                in.duty[x] = st[x];
            }
            power_stage_step_q(&sa, &in);
            ps_fast_step_q(&sb, &in.battery, st, (int32_t)in.i_motor[0] * 8192,
                           (int32_t)in.i_motor[1] * 8192);
            same &= sa.v_dc == sb.v_dc && sa.i_dc == sb.i_dc && sa.u[0] == sb.u[0] &&
                    sa.u[1] == sb.u[1] && sa.sat_count == sb.sat_count;
            for (unsigned x = 0u; x < 2u; x++) {
                same &= sa.ph[x].i_l == sb.ph[x].i_l && sa.ph[x].v_c == sb.ph[x].v_c &&
                        sa.ph[x].i_d == sb.ph[x].i_d && sa.ph[x].j_sh == sb.ph[x].j_sh;
            }
        }
        sat = sb.sat_count;
    } else {
        power_stage_f32 sa, sb;
        power_stage_in_f32 in = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
        power_stage_init_f32(&sa, &power_stage_params_default, STEP_NS, 600.0);
        power_stage_battery_f32(&sa, 2.0, 1200.0, &in.battery);
        sb = sa;
        for (k = 0u; k < steps; k++) {
            int32_t st[3];
            float w = (float)(2.0 * MATH_PI_F64 * 50.0 * STEP_S * (double)k);
            if (k % 50u == 0u) {
                pwm_rt_ramp ramp;
                pwm_rt_ramp_f32(&ramp, NULL, 0.9f, ref_ph, inc, 50u);
                pwm_rt_apply(&rt, &ramp);
                ref_ph += 50u * inc;
            }
            in.i_motor_a[0] = (float)amp_a * math_sin_f32(w);
            in.i_motor_a[1] = (float)amp_a * math_sin_f32(w - 2.0943951f);
            rt_duties(&rt, substep, st);
            for (unsigned x = 0u; x < 3u; x++) {
                in.duty[x] = (float)st[x] / 32768.0f;
            }
            power_stage_step_f32(&sa, &in);
            ps_fast_step_f32(&sb, &in.battery, st, in.i_motor_a[0], in.i_motor_a[1]);
            same &= sa.v_dc == sb.v_dc && sa.i_dc == sb.i_dc && sa.u[0] == sb.u[0] &&
                    sa.u[1] == sb.u[1] && sa.sat_count == sb.sat_count;
            for (unsigned x = 0u; x < 2u; x++) {
                same &= sa.ph[x].i_l == sb.ph[x].i_l && sa.ph[x].v_c == sb.ph[x].v_c &&
                        sa.ph[x].i_d == sb.ph[x].i_d && sa.ph[x].j_sh == sb.ph[x].j_sh;
            }
        }
        sat = sb.sat_count;
    }
    ut_info("fast step, %s modulator, %s, %u steps at %g A: identical %d, clamps %u",
            substep ? "sub-step" : "sampled", fixed ? "fixed" : "float", (unsigned)steps, amp_a,
            same, (unsigned)sat);
    UT_CHECK(same);
    UT_CHECK((amp_a > 256.0) == (sat > 0u));
}

/*
 * Held states (every duty 0 or 32768, the frame plan's held steps and the
 * sampled modulator's): the legs' factors the stage forms of them
 * (ps_fast_legs_*) are the held states' small integers, so its step is the
 * held-state arithmetic bit for bit: for all eight states, over v_dc from
 * -1 to 1 per unit (and 0, -0, 600 V), the inverter voltages are n_x v_dc / 3
 * (n_x = 2 s_x - s_y - s_c) with v_dc / 3 rounded as the stage rounds it,
 * and the DC-link current is floor((T + 1) / 2) of T = (s_a - s_c) S_a +
 * (s_b - s_c) S_b (fixed); the float factors are (float)n_x and
 * (float)(s_x - s_c) in every bit, zeros +0, and the voltages v3 n_x. The
 * held states' own factors (ps_fast_held_legs_*, whole units in the fixed
 * twin) give the same voltages, DC-link current and DC link.
 */
typedef union {
    float f;
    uint32_t u;
} f32_bits;

static bool same_f32(float a, float b) {
    const f32_bits x = {a};
    const f32_bits y = {b};
    return x.u == y.u;
}

static void test_held_legs(void) {
    static const int32_t v_q[] = {0, 1, -1, 3, -3, 0x5555555, PS_Q28_ONE, -PS_Q28_ONE,
                                  150994944 /* 576 V */, -150994943, 268435455, 12345679};
    static const float v_f[] = {0.0f, -0.0f, 1.0f, -1.0f, 3.0f, 600.0f, 600.0001f,
                                -599.99994f, 1024.0f, -1024.0f, 1e-30f, 333.33334f};
    bool same_q = true;
    bool same_f = true;
    for (uint32_t b = 0u; b < 8u; b++) {
        const int32_t st[3] = {(int32_t)(b & 1u), (int32_t)((b >> 1) & 1u),
                               (int32_t)((b >> 2) & 1u)};
        const int32_t duty[3] = {st[0] * PWM_RT_DUTY_ONE, st[1] * PWM_RT_DUTY_ONE,
                                 st[2] * PWM_RT_DUTY_ONE};
        const int32_t n_a = 2 * st[0] - st[1] - st[2];
        const int32_t n_b = 2 * st[1] - st[0] - st[2];
        const int32_t dd_a = st[0] - st[2];
        const int32_t dd_b = st[1] - st[2];
        ps_legs_q lq;
        ps_legs_f32 lf;
        ps_fast_legs_q(duty, &lq);
        ps_fast_legs_f32(duty, &lf);
        same_f = same_f && same_f32(lf.w[0], (float)n_a) && same_f32(lf.w[1], (float)n_b) &&
                 same_f32(lf.dd[0], (float)dd_a) && same_f32(lf.dd[1], (float)dd_b);
        for (size_t i = 0; i < sizeof v_q / sizeof v_q[0]; i++) {
            power_stage_q q;
            ps_battery_q bat;
            ps_fast_q fq;
            UT_CHECK(power_stage_init_q(&q, &power_stage_params_default, STEP_NS, 600.0) ==
                     PS_OK);
            power_stage_battery_q(&q, 2.0, 1200.0, &bat);
            q.v_dc = v_q[i];
            ps_fast_begin_q(&q, &lq, &fq);
            const int32_t v3 = ps_hi_q(ps_mac_q(ps_acc_q(0), v_q[i], 0x55555555));
            same_q = same_q && q.u[0] == n_a * v3 && q.u[1] == n_b * v3;
            /* The DC-link current of the phases' currents (S_x of up to +-2 per unit). */
            const int32_t i0[2] = {q.ph[0].i_l, q.ph[1].i_l};
            q.ph[0].i_l = v_q[i];
            q.ph[1].i_l = -v_q[(i + 5u) % (sizeof v_q / sizeof v_q[0])];
            const int32_t s_a = i0[0] + q.ph[0].i_l;
            const int32_t s_b = i0[1] + q.ph[1].i_l;
            power_stage_q w = q; /* the same step on the held states' whole-unit factors */
            ps_fast_q fw;
            ps_legs_q hq;
            ps_fast_held_legs_q(st, &hq);
            w.v_dc = v_q[i];
            ps_fast_begin_q(&w, &hq, &fw);
            /* Both filter phases on both forms, from states within +-1/2 per unit. */
            power_stage_q pa = q;
            power_stage_q pb = w;
            ps_fast_q fa = fq;
            ps_fast_q fb = fw;
            const size_t nv = sizeof v_q / sizeof v_q[0];
            for (int x = 0; x < 2; x++) {
                const ps_phase_q st0 = {v_q[(i + 3u + (size_t)x) % nv] / 2,
                                        -v_q[(i + 7u) % nv] / 2, v_q[(i + 1u) % nv] / 3,
                                        v_q[(i + 9u + (size_t)x) % nv] / 2};
                pa.ph[x] = st0;
                pb.ph[x] = st0;
                ps_fast_phase_q(&pa, &fa, x, v_q[(i + 4u) % nv] / 4);
                ps_fast_phase_held_q(&pb, &fb, &hq, x, v_q[(i + 4u) % nv] / 4);
                same_q = same_q && pa.ph[x].i_l == pb.ph[x].i_l && pa.ph[x].v_c == pb.ph[x].v_c &&
                         pa.ph[x].i_d == pb.ph[x].i_d && pa.ph[x].j_sh == pb.ph[x].j_sh;
            }
            same_q = same_q && fa.t == 32768 * fb.t && fa.sat == fb.sat;
            same_q = same_q && w.u[0] == q.u[0] && w.u[1] == q.u[1] && hq.w[0] == n_a &&
                     hq.w[1] == n_b && hq.dd[0] == dd_a && hq.dd[1] == dd_b;
            fq.t = (int64_t)fq.dd[0] * s_a + (int64_t)fq.dd[1] * s_b;
            fw.t = (int64_t)fw.dd[0] * s_a + (int64_t)fw.dd[1] * s_b;
            ps_fast_end_q(&q, &bat, &fq);
            ps_fast_end_q(&w, &bat, &fw);
            const int64_t t = (int64_t)dd_a * s_a + (int64_t)dd_b * s_b;
            same_q = same_q && (int64_t)q.i_dc == fp_shr_floor_i64(t + 1, 1u) &&
                     w.i_dc == q.i_dc && w.v_dc == q.v_dc;
        }
        for (size_t i = 0; i < sizeof v_f / sizeof v_f[0]; i++) {
            power_stage_f32 f;
            ps_fast_f32 ff;
            UT_CHECK(power_stage_init_f32(&f, &power_stage_params_default, STEP_NS, 600.0) ==
                     PS_OK);
            f.v_dc = v_f[i];
            ps_legs_f32 hf;
            ps_fast_held_legs_f32(st, &hf);
            same_f = same_f && same_f32(hf.w[0], lf.w[0]) && same_f32(hf.w[1], lf.w[1]) &&
                     same_f32(hf.dd[0], lf.dd[0]) && same_f32(hf.dd[1], lf.dd[1]);
            /* The DC link on the sum t with the halved coefficient: k_c (t / 2)'s bits. */
            ps_battery_f32 bf;
            uint32_t sat = 0u;
            power_stage_battery_f32(&f, 2.0, 1200.0, &bf);
            const float t = v_f[i] * 0.37f;
            const float dv_old = bf.kg * (bf.e_v - 600.0f) + (2.0f * f.k.neg_k_c) * (0.5f * t);
            same_f = same_f && same_f32(ps_dclink_step_f32(600.0f, &bf, f.k.neg_k_c, t, &sat),
                                        600.0f + dv_old);
            ps_fast_begin_f32(&f, &lf, &ff);
            const float v3 = v_f[i] * (1.0f / 3.0f);
            same_f = same_f && same_f32(f.u[0], v3 * (float)n_a) &&
                     same_f32(f.u[1], v3 * (float)n_b);
        }
    }
    UT_CHECK(same_q);
    UT_CHECK(same_f);
}

/*
 * The float clamp's one comparison (x^2 > lim^2) against the two it
 * stands for, at the limits, the floats next to them, far out, the
 * infinities, NaN and the zeros: the same value (in every bit) and the
 * same count.
 */
static float clamp_two_f32(float x, float lim, uint32_t *sat) {
    if (x > lim) {
        (*sat)++;
        return lim;
    }
    if (x < -lim) {
        (*sat)++;
        return -lim;
    }
    return x;
}

static void test_clamp_f32(void) {
    static const float lims[] = {PS_V_LIM_F32, PS_I_LIM_F32};
    bool same = true;
    uint32_t clamps = 0u;
    for (size_t l = 0; l < sizeof lims / sizeof lims[0]; l++) {
        const float lim = lims[l];
        f32_bits up = {lim};
        f32_bits down = {lim};
        up.u++;   /* the float after lim */
        down.u--; /* the float before it */
        f32_bits nan = {0.0f};
        nan.u = 0x7fc00000u;
        f32_bits inf = {0.0f};
        inf.u = 0x7f800000u;
        const float xs[] = {lim,     -lim,   up.f,   -up.f,  down.f,    -down.f,  0.0f,
                            -0.0f,   1e-40f, 2.0f * lim, -3.0f * lim, 1e30f, -1e30f,
                            inf.f,   -inf.f, nan.f,  0.5f * lim};
        for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
            uint32_t a = 0u;
            uint32_t b = 0u;
            const float ya = ps_clamp_f32(xs[i], lim, &a);
            const float yb = clamp_two_f32(xs[i], lim, &b);
            same = same && same_f32(ya, yb) && a == b;
            clamps += a;
        }
    }
    ut_info("clamped %u of 34 values, as the two comparisons", (unsigned)clamps);
    UT_CHECK(same);
    UT_EQ_INT(clamps, 16u);
}

void suite_power_stage(void) {
    int fixed;
    UT_TEST("filter companion: |H| within 0.5 % and phase within 0.5 deg of the analytic "
            "v_C/u and i_L/u at 200 Hz, 1 kHz, 5 kHz");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_filter_response(fixed);
    }
    UT_TEST("DC link: forward Euler with the pack's companion reaches e - i/G, follows the "
            "exponential");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_dclink(fixed);
    }
    UT_TEST("switching stage with a resistive load: battery energy = load + losses + stored "
            "(0.1 %)");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_energy_balance(fixed);
    }
    UT_TEST("averaged inverter (25 us, and 100 us without substeps) matches the switching one "
            "on the fundamentals");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_averaged_vs_switching(fixed);
    }
    UT_TEST("fixed and float twins: same stimulus, currents within 1 % of 256 A");
    test_fixed_vs_float(0);
    test_fixed_vs_float(1);
    UT_TEST("worst case (cut-off bus, m = 1, 55 Hz, 120 A locked-rotor current): no clamp");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_worst_case(fixed);
    }
    UT_TEST("driven out of range, both twins clamp to +-1 per unit and count the clamps");
    for (fixed = 1; fixed >= 0; fixed--) {
        test_saturation(fixed);
    }
    UT_TEST("parameter checks, battery conversion, outputs and sign conventions");
    test_setup_and_outputs();
    UT_TEST("fast stage step with the real-time modulator's duties (sampled: 0 or 1; "
            "sub-step) equals power_stage_step with the same duties, bit for bit, clamps "
            "included");
    for (fixed = 1; fixed >= 0; fixed--) {
        for (int substep = 0; substep <= 1; substep++) {
            test_fused_step(fixed, substep, 120.0, 20000u);
            test_fused_step(fixed, substep, 400.0, 2000u);
        }
    }
    UT_TEST("held states: the legs' factors of duties 0 and 32768 are the states' integers, "
            "the step the held-state arithmetic bit for bit (all eight states)");
    test_held_legs();
    UT_TEST("float clamp: x^2 > lim^2 acts and counts as x > lim or x < -lim, bit for bit");
    test_clamp_f32();
}

/*
 * The drive controller (src/models/drive/control/drive_control.h), both twins, against
 * plants simulated here in double precision at a finer step:
 *   - a balanced three-phase R-L load fed by a voltage vector of amplitude
 *     m Vdc / 2 turning at the commanded frequency. In the frame of the
 *     voltage vector it reads L di/dt = v - (R + j w L) i with v real and
 *     held over each controller frame, which is exact for a balanced
 *     sinusoidal supply whose phase runs on continuously; RK4 at T / 2
 *     (local error below 1e-6 of the current for the loads used here).
 *   - a shaft with inertia J, the propeller's quadratic load k w |w| and a
 *     torque proportional to the applied slip, K_T (f_s - p w / 2 pi),
 *     K_T the controller's own steady-state torque per slip hertz; RK4 at T.
 * References: the analytic step-response properties asked of the loops
 * (overshoot, final value), the limits of the parameters, and the other
 * twin on the same stimulus.
 */
#include <stdbool.h>
#include <stddef.h>

#include "fixedpoint/fixedpoint.h"
#include "fixedpoint/wavetable.h"
#include "math/umath.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/drive_units.h"
#include "models/drive/motor/induction_motor.h"
#include "ut.h"

void suite_drive_control(void);

#define TWO_PI (2.0 * MATH_PI_F64)
#define W_1500 (1500.0 * TWO_PI / 60.0) /* [rad/s] */
#define K_LOAD 0.0023681                /* [N m s^2] propeller: 58.4 N m at 1500 rpm */
#define J_SHAFT 0.113                   /* [kg m^2] rotor 0.102 + propeller 0.011 */
#define VDC_CUTOFF 432.0                /* [V] */

/* ---- One interface over both twins, in SI doubles -------------------------- */

typedef struct {
    bool fixed;
    drive_control_q q;
    drive_control_f32 f;
} ctl_t;

typedef struct {
    double m, freq_hz, slip_hz, i_demand_a, i_meas_a, v_demand_v, speed_ref;
    uint32_t phase_inc, flags;
} ctl_out_t;

typedef struct {
    double cmd, w, ia, ib, ic, vdc; /* [rad/s], [rad/s], [A] x 3, [V] */
} ctl_in_t;

static bool ctl_init(ctl_t *c, const drive_control_params *p, bool fixed) {
    c->fixed = fixed;
    if (fixed) {
        return drive_control_init_q(&c->q, p) == DRIVE_CONTROL_OK;
    }
    return drive_control_init_f32(&c->f, p) == DRIVE_CONTROL_OK;
}

/*
 * Per unit by multiplication with the reciprocal of the base (a power of
 * two, so exact): the set-up helper fp_pu_from_f64_q31 divides, which in
 * software double precision would dominate the suite's cost on the M3.
 */
static q31_t pu_q31(double value, double base) {
    return fp_from_f64_q31(value * (1.0 / base));
}

static drive_control_in_q in_q(const ctl_in_t *in) {
    drive_control_in_q q;
    q.speed_cmd = pu_q31(in->cmd, DRIVE_BASE_SPEED_RADPS);
    q.w = pu_q31(in->w, DRIVE_BASE_SPEED_RADPS);
    q.i_a = pu_q31(in->ia, DRIVE_BASE_CURRENT_A);
    q.i_b = pu_q31(in->ib, DRIVE_BASE_CURRENT_A);
    q.i_c = pu_q31(in->ic, DRIVE_BASE_CURRENT_A);
    q.vdc = pu_q31(in->vdc, DRIVE_BASE_VOLTAGE_V);
    return q;
}

static drive_control_in_f32 in_f(const ctl_in_t *in) {
    drive_control_in_f32 f;
    f.speed_cmd_radps = (float)in->cmd;
    f.w_radps = (float)in->w;
    f.i_a = (float)in->ia;
    f.i_b = (float)in->ib;
    f.i_c = (float)in->ic;
    f.vdc_v = (float)in->vdc;
    return f;
}

static void out_from_q(const drive_control_out_q *q, ctl_out_t *o) {
    o->m = fp_to_f64_q15(q->m);
    o->freq_hz = fp_pu_to_f64_q31(q->freq, DRIVE_BASE_FREQ_HZ);
    o->slip_hz = fp_pu_to_f64_q31(q->slip, DRIVE_BASE_FREQ_HZ);
    o->i_demand_a = fp_pu_to_f64_q31(q->i_demand, DRIVE_BASE_CURRENT_A);
    o->i_meas_a = fp_pu_to_f64_q31(q->i_meas, DRIVE_BASE_CURRENT_A);
    o->v_demand_v = fp_pu_to_f64_q31(q->v_demand, DRIVE_BASE_VOLTAGE_V);
    o->speed_ref = fp_pu_to_f64_q31(q->speed_ref, DRIVE_BASE_SPEED_RADPS);
    o->phase_inc = q->phase_inc;
    o->flags = q->flags;
}

static void out_from_f(const drive_control_out_f32 *f, ctl_out_t *o) {
    o->m = (double)f->m;
    o->freq_hz = (double)f->freq_hz;
    o->slip_hz = (double)f->slip_hz;
    o->i_demand_a = (double)f->i_demand_a;
    o->i_meas_a = (double)f->i_meas_a;
    o->v_demand_v = (double)f->v_demand_v;
    o->speed_ref = (double)f->speed_ref_radps;
    o->phase_inc = f->phase_inc;
    o->flags = f->flags;
}

static void ctl_step(ctl_t *c, const ctl_in_t *in, ctl_out_t *o) {
    if (c->fixed) {
        drive_control_in_q q = in_q(in);
        drive_control_out_q out;
        drive_control_step_q(&c->q, &q, &out);
        out_from_q(&out, o);
    } else {
        drive_control_in_f32 f = in_f(in);
        drive_control_out_f32 out;
        drive_control_step_f32(&c->f, &f, &out);
        out_from_f(&out, o);
    }
}

static void ctl_current(ctl_t *c, double i_dem, double freq, double slip, const ctl_in_t *in,
                        ctl_out_t *o) {
    if (c->fixed) {
        drive_control_in_q q = in_q(in);
        drive_control_out_q out;
        drive_control_current_step_q(&c->q, pu_q31(i_dem, DRIVE_BASE_CURRENT_A),
                                     pu_q31(freq, DRIVE_BASE_FREQ_HZ),
                                     pu_q31(slip, DRIVE_BASE_FREQ_HZ), &q, &out);
        out_from_q(&out, o);
    } else {
        drive_control_in_f32 f = in_f(in);
        drive_control_out_f32 out;
        drive_control_current_step_f32(&c->f, (float)i_dem, (float)freq, (float)slip, &f, &out);
        out_from_f(&out, o);
    }
}

/* The current integrator [V] of either twin. */
static double ctl_x_i(const ctl_t *c) {
    return c->fixed ? fp_pu_to_f64_q31(c->q.x_i, DRIVE_BASE_VOLTAGE_V) : (double)c->f.x_i;
}

static uint32_t ctl_sat(const ctl_t *c) {
    return c->fixed ? c->q.sat_count : 0u;
}

static const char *twin_name(bool fixed) {
    return fixed ? "fixed" : "float";
}

/*
 * A unit vector turned by a fixed angle each frame by complex multiplication
 * (one sine and cosine at set-up instead of one per frame, which software
 * double precision on the Cortex-M3 would make the bulk of the suite's cost).
 */
typedef struct {
    double c, s;    /* current direction */
    double dc, ds;  /* rotation per frame */
} rot_t;

static rot_t rot_make(double theta0, double step) {
    rot_t r;
    math_sincos_f64(theta0, &r.s, &r.c);
    math_sincos_f64(step, &r.ds, &r.dc);
    return r;
}

static void rot_advance(rot_t *r) {
    double c = r->c * r->dc - r->s * r->ds;
    r->s = r->s * r->dc + r->c * r->ds;
    r->c = c;
}

/* Phase currents of the vector (x + j y) e^(j theta), amplitude-invariant Clarke inverse. */
static void phase_currents_xy(double x, double y, const rot_t *r, ctl_in_t *in) {
    double alpha = x * r->c - y * r->s;
    double beta = x * r->s + y * r->c;
    in->ia = alpha;
    in->ib = -0.5 * alpha + 0.8660254037844386 * beta;
    in->ic = -0.5 * alpha - 0.8660254037844386 * beta;
}

/* Phase currents of a vector of amplitude mag at angle theta. */
static void phase_currents(double mag, double theta, ctl_in_t *in) {
    rot_t r = rot_make(theta, 0.0);
    phase_currents_xy(mag, 0.0, &r, in);
}

static double absd(double x) {
    return (x < 0.0) ? -x : x;
}

/* ---- R-L plant --------------------------------------------------------------- */

typedef struct {
    double r, l, f_hz;  /* [ohm], [H], [Hz] */
    double id, iq;      /* [A] current in the frame of the voltage vector */
    rot_t rot;          /* direction of the voltage vector, turned by 2 pi f T per frame */
} rl_t;

static rl_t rl_make(double r_ohm, double l_h, double f_hz, double theta0) {
    rl_t p = {r_ohm, l_h, f_hz, 0.0, 0.0, {0.0, 0.0, 0.0, 0.0}};
    p.rot = rot_make(theta0, TWO_PI * f_hz * drive_control_params_default.step_s);
    return p;
}

static void rl_deriv(const rl_t *p, double v, double id, double iq, double *did, double *diq) {
    double w = TWO_PI * p->f_hz;
    *did = (v - p->r * id + w * p->l * iq) / p->l;
    *diq = (-p->r * iq - w * p->l * id) / p->l;
}

/* Advances the load over one frame T with the voltage amplitude v held (RK4, 2 steps). */
static void rl_frame(rl_t *p, double v, double t) {
    const double h = t / 2.0;
    for (unsigned k = 0u; k < 2u; k++) {
        double d1, q1, d2, q2, d3, q3, d4, q4;
        rl_deriv(p, v, p->id, p->iq, &d1, &q1);
        rl_deriv(p, v, p->id + 0.5 * h * d1, p->iq + 0.5 * h * q1, &d2, &q2);
        rl_deriv(p, v, p->id + 0.5 * h * d2, p->iq + 0.5 * h * q2, &d3, &q3);
        rl_deriv(p, v, p->id + h * d3, p->iq + h * q3, &d4, &q4);
        p->id += h / 6.0 * (d1 + 2.0 * d2 + 2.0 * d3 + d4);
        p->iq += h / 6.0 * (q1 + 2.0 * q2 + 2.0 * q3 + q4);
    }
    rot_advance(&p->rot);
}

/* The load's phase currents at the frame end, in stationary coordinates. */
static void rl_currents(const rl_t *p, ctl_in_t *in) {
    phase_currents_xy(p->id, p->iq, &p->rot, in);
}

static double rl_mag(const rl_t *p) {
    return math_sqrt_f64(p->id * p->id + p->iq * p->iq);
}

/* Current-loop test parameters: the defaults without feedforward (the load is not the motor). */
static drive_control_params rl_params(void) {
    drive_control_params p = drive_control_params_default;
    p.ff_gain = 0.0;
    return p;
}

/*
 * Runs the current loop on the load for n frames at demand i_dem; records
 * the largest and smallest magnitude and the last frame outside +-band of
 * the demand (counted from the run's start). Returns false on a limit
 * violation (m outside [0, m_max]).
 */
typedef struct {
    double i_max, i_min, last_out_s, m_max_seen;
    bool m_sat_seen, m_ok;
} rl_run_t;

static void rl_run(ctl_t *c, rl_t *p, const ctl_in_t *base, double i_dem, unsigned n,
                   double band, rl_run_t *r) {
    const double t = drive_control_params_default.step_s;
    ctl_in_t in = *base;
    r->i_max = -1.0;
    r->i_min = 1e9;
    r->last_out_s = 0.0;
    r->m_max_seen = 0.0;
    r->m_sat_seen = false;
    r->m_ok = true;
    for (unsigned k = 0u; k < n; k++) {
        ctl_out_t o;
        rl_currents(p, &in);
        ctl_current(c, i_dem, p->f_hz, 0.0, &in, &o);
        r->m_ok = r->m_ok && (o.m >= 0.0) && (o.m <= 1.0);
        r->m_max_seen = (o.m > r->m_max_seen) ? o.m : r->m_max_seen;
        r->m_sat_seen = r->m_sat_seen || ((o.flags & DRIVE_CONTROL_FLAG_M_MAX) != 0u);
        rl_frame(p, o.m * in.vdc * 0.5, t);
        double mag = rl_mag(p);
        r->i_max = (mag > r->i_max) ? mag : r->i_max;
        r->i_min = (mag < r->i_min) ? mag : r->i_min;
        if (absd(mag - i_dem) > band) {
            r->last_out_s = (double)(k + 1u) * t;
        }
    }
}

static void test_current_step(bool fixed, double r_ohm, double l_h, double f_hz, unsigned n) {
    drive_control_params p = rl_params();
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    rl_t load = rl_make(r_ohm, l_h, f_hz, 0.3);
    ctl_in_t base = {0.0, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    rl_run_t r;
    rl_run(&c, &load, &base, 20.0, n, 0.4, &r);
    UT_NEAR(rl_mag(&load), 20.0, 0.2);
    rl_run(&c, &load, &base, 40.0, n, 0.4, &r);
    double over = (r.i_max - 40.0) / 20.0 * 100.0;
    UT_CHECK(over <= 5.0);
    UT_NEAR(rl_mag(&load), 40.0, 0.4);
    UT_CHECK(r.m_ok);
    UT_EQ_INT(ctl_sat(&c), 0);
    ut_info("%s, R %.3f ohm, L %.2f mH, %.0f Hz: 20 -> 40 A overshoot %.2f %%, "
            "settled within 2 %% after %.1f ms, final %.3f A",
            twin_name(fixed), r_ohm, l_h * 1e3, f_hz, over, r.last_out_s * 1e3, rl_mag(&load));
}

/* ---- Anti-windup ------------------------------------------------------------- */

/*
 * The comparison case: the same PI in double with plain integration (no
 * conditional integration, no clamp), m clamped only at the output.
 */
typedef struct {
    double x;
} pi_windup_t;

static double pi_windup_step(pi_windup_t *pi, const drive_control_params *p, double e,
                             double vdc) {
    double u = p->kp_current_v_per_a * e + pi->x;
    pi->x += p->ki_current_v_per_as * p->step_s * e;
    double m = 2.0 * u / vdc;
    return (m < 0.0) ? 0.0 : (m > p->m_max) ? p->m_max : m;
}

/* Seconds after the drop until the magnitude stays within 2 % of 30 A (window 0.5 s), plain PI. */
static double windup_recovery_s(const drive_control_params *p, rl_t load, double vdc) {
    pi_windup_t pi = {0.0};
    double last_out = 0.0;
    for (unsigned k = 0u; k < 1250u; k++) {
        double mag = rl_mag(&load);
        double i_dem = (k < 625u) ? 100.0 : 30.0;
        double m = pi_windup_step(&pi, p, i_dem - mag, vdc);
        rl_frame(&load, m * vdc * 0.5, p->step_s);
        if ((k >= 625u) && (absd(rl_mag(&load) - 30.0) > 0.6)) {
            last_out = (double)(k + 1u - 625u) * p->step_s;
        }
    }
    return last_out;
}

static void test_anti_windup(bool fixed) {
    drive_control_params p = rl_params();
    const double vdc = 300.0;
    const double t = p.step_s;
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    rl_t load = rl_make(3.0, 9e-3, 50.0, 0.0);
    ctl_in_t base = {0.0, 0.0, 0.0, 0.0, 0.0, vdc};
    rl_run_t r;
    rl_run(&c, &load, &base, 25.0, 300u, 0.5, &r);
    rl_t at_25 = load;
    /* 100 A needs 410 V of amplitude; the bus gives 150 V: m must sit at m_max. */
    rl_run(&c, &load, &base, 100.0, 625u, 2.0, &r);
    UT_CHECK(r.m_sat_seen);
    UT_NEAR(r.m_max_seen, p.m_max, 1e-4);
    UT_CHECK(absd(ctl_x_i(&c)) <= 0.5 * p.m_max * vdc + 1e-3);
    double i_sat = rl_mag(&load);
    /* The demand drops below what the bus can give: m leaves m_max at once. */
    ctl_in_t in = base;
    ctl_out_t o;
    rl_currents(&load, &in);
    ctl_current(&c, 30.0, load.f_hz, 0.0, &in, &o);
    UT_CHECK(o.m < p.m_max - 0.01);
    rl_frame(&load, o.m * vdc * 0.5, t);
    rl_run(&c, &load, &base, 30.0, 374u, 0.6, &r);
    double under = (30.0 - r.i_min) / (i_sat - 30.0) * 100.0;
    UT_CHECK(under <= 5.0);
    UT_CHECK(r.last_out_s <= 0.25);
    UT_NEAR(rl_mag(&load), 30.0, 0.3);
    UT_EQ_INT(ctl_sat(&c), 0);
    double windup_s = windup_recovery_s(&p, at_25, vdc);
    UT_CHECK(windup_s > r.last_out_s + 0.1);
    ut_info("%s: held at %.2f A, m %.4f, x_i %.1f V (bound %.1f V); drop to 30 A: lowest "
            "%.2f A, within 2 %% after %.1f ms; plain PI still outside at %.0f ms",
            twin_name(fixed), i_sat, r.m_max_seen, ctl_x_i(&c), 0.5 * p.m_max * vdc, r.i_min,
            (r.last_out_s + t) * 1e3, windup_s * 1e3);
}

/* ---- Mechanical plant ------------------------------------------------------------ */

typedef struct {
    double w;       /* [rad/s] */
    double kt;      /* [N m/Hz] */
    double fr;      /* [Hz per rad/s] p / 2 pi */
} shaft_t;

/* Torque only while the inverter modulates: an idle drive (m = 0) carries no current. */
static double shaft_accel(const shaft_t *s, double freq, double m, double w) {
    double torque = (m > 0.0) ? s->kt * (freq - s->fr * w) : 0.0;
    return (torque - K_LOAD * w * absd(w)) / J_SHAFT;
}

static void shaft_frame(shaft_t *s, const ctl_out_t *o, double t) {
    double a1 = shaft_accel(s, o->freq_hz, o->m, s->w);
    double a2 = shaft_accel(s, o->freq_hz, o->m, s->w + 0.5 * t * a1);
    double a3 = shaft_accel(s, o->freq_hz, o->m, s->w + 0.5 * t * a2);
    double a4 = shaft_accel(s, o->freq_hz, o->m, s->w + t * a3);
    s->w += t / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
}

/* What a run of the speed loop saw: extremes, the limits and the last frame. */
typedef struct {
    double w_max, w_min, w_end;
    double last_out_s;  /* end of the last frame outside +-0.5 % of the command */
    bool limits_ok;
    bool idle_seen;
    ctl_out_t last;
} shaft_run_t;

/* True when every output respects the limits of p and the ramp moved by at most one step. */
static bool limits_ok(const drive_control_params *p, const drive_control_design *d,
                      const ctl_out_t *o, double ref_prev) {
    /* 1e-6 covers the float twin's rounding of the limits; the reference, near 157 rad/s
     * in single precision, moves in steps rounded to 1.5e-5 rad/s, hence 1e-4 there. */
    const double tol = 1e-6;
    bool ok = (o->m >= 0.0) && (o->m <= p->m_max + tol);
    ok = ok && (absd(o->slip_hz) <= d->slip_lim_hz + tol);
    ok = ok && (absd(o->freq_hz) <= p->freq_max_hz + tol);
    ok = ok && (o->i_demand_a <= p->i_max_a + tol);
    ok = ok && (absd(o->speed_ref) <= p->speed_max_radps + tol);
    ok = ok && (((o->flags & DRIVE_CONTROL_FLAG_IDLE) != 0u) ||
                (absd(o->speed_ref - ref_prev) <= p->accel_max_radps2 * p->step_s + 1e-4));
    return ok;
}

/*
 * n frames of the full controller on the shaft at command cmd. The currents
 * fed back are a balanced set at the last demand (an ideal current loop), at
 * an angle that advances by 0.1 rad per frame.
 */
static void shaft_run(ctl_t *c, shaft_t *s, const drive_control_params *p, double cmd,
                      unsigned n, shaft_run_t *r) {
    drive_control_design d;
    (void)drive_control_design_f64(&d, p);
    ctl_in_t in = {cmd, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    rot_t rot = rot_make(0.0, 0.1);
    double i_fb = 0.0;
    double ref_prev = r->last.speed_ref;
    r->w_max = -1e9;
    r->w_min = 1e9;
    r->last_out_s = 0.0;
    r->limits_ok = true;
    r->idle_seen = false;
    for (unsigned k = 0u; k < n; k++) {
        in.w = s->w;
        phase_currents_xy(i_fb, 0.0, &rot, &in);
        rot_advance(&rot);
        ctl_step(c, &in, &r->last);
        r->limits_ok = r->limits_ok && limits_ok(p, &d, &r->last, ref_prev);
        r->idle_seen = r->idle_seen || ((r->last.flags & DRIVE_CONTROL_FLAG_IDLE) != 0u);
        ref_prev = r->last.speed_ref;
        i_fb = r->last.i_demand_a;
        shaft_frame(s, &r->last, p->step_s);
        r->w_max = (s->w > r->w_max) ? s->w : r->w_max;
        r->w_min = (s->w < r->w_min) ? s->w : r->w_min;
        if (absd(s->w - cmd) > 0.005 * W_1500) {
            r->last_out_s = (double)(k + 1u) * p->step_s;
        }
    }
    r->w_end = s->w;
}

static shaft_t shaft_for(const drive_control_params *p) {
    drive_control_design d;
    (void)drive_control_design_f64(&d, p);
    shaft_t s = {0.0, d.kt_nm_per_hz, d.fr_hz_per_radps};
    return s;
}

static void test_speed_start(bool fixed, bool ramp) {
    drive_control_params p = drive_control_params_default;
    if (!ramp) {
        p.accel_max_radps2 = 1e5; /* a step: the slip limit and anti-windup act */
    }
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    shaft_t s = shaft_for(&p);
    shaft_run_t r = {0};
    shaft_run(&c, &s, &p, W_1500, 1500u, &r);
    double over = (r.w_max - W_1500) / W_1500 * 100.0;
    double err = (r.w_end - W_1500) / W_1500 * 100.0;
    UT_CHECK(over <= 5.0);
    UT_CHECK(absd(err) <= 0.5);
    UT_CHECK(r.limits_ok);
    UT_EQ_INT(ctl_sat(&c), 0);
    ut_info("%s, %s: 0 -> 1500 rpm overshoot %.3f %%, within 0.5 %% after %.3f s, "
            "error at 1.2 s %.4f %%, slip %.3f Hz, I* %.2f A",
            twin_name(fixed), ramp ? "ramped 200 rad/s^2" : "step", over, r.last_out_s, err,
            r.last.slip_hz, r.last.i_demand_a);
}

static void test_speed_reverse_stop(bool fixed) {
    drive_control_params p = drive_control_params_default;
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    shaft_t s = shaft_for(&p);
    shaft_run_t r = {0};
    shaft_run(&c, &s, &p, W_1500, 1250u, &r);
    shaft_run(&c, &s, &p, -W_1500, 2750u, &r);
    double over = (-W_1500 - r.w_min) / W_1500 * 100.0;
    UT_CHECK(over <= 5.0);
    UT_NEAR(r.w_end, -W_1500, 0.005 * W_1500);
    UT_CHECK(r.limits_ok);
    UT_CHECK(r.last.freq_hz < 0.0);
    double t_rev = r.last_out_s;
    shaft_run(&c, &s, &p, 0.0, 1500u, &r);
    UT_CHECK(r.idle_seen);
    UT_CHECK((r.last.flags & DRIVE_CONTROL_FLAG_IDLE) != 0u);
    UT_CHECK((r.last.m == 0.0) && (r.last.freq_hz == 0.0) && (r.last.phase_inc == 0u));
    UT_CHECK(absd(r.w_end) <= p.idle_speed_radps);
    UT_CHECK(r.limits_ok);
    UT_EQ_INT(ctl_sat(&c), 0);
    ut_info("%s: +1500 -> -1500 rpm within 0.5 %% after %.3f s (overshoot %.3f %%); "
            "stop: idle at %.2f rad/s",
            twin_name(fixed), t_rev, over, r.w_end);
}

/* ---- Fixed against float ------------------------------------------------------- */

static void test_fixed_vs_float(void) {
    drive_control_params p = drive_control_params_default;
    ctl_t cq;
    ctl_t cf;
    UT_CHECK(ctl_init(&cq, &p, true) && ctl_init(&cf, &p, false));
    shaft_t sq = shaft_for(&p);
    shaft_t sf = shaft_for(&p);
    ctl_in_t iq = {0.0, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    ctl_in_t inf = iq;
    double dm = 0.0, df = 0.0, di = 0.0, dw = 0.0, dv = 0.0;
    ctl_out_t oq = {0};
    ctl_out_t of = {0};
    rot_t rot = rot_make(0.0, 0.1);
    for (unsigned k = 0u; k < 3000u; k++) {
        double cmd = (k < 1250u) ? W_1500 : -0.6 * W_1500;
        iq.cmd = cmd;
        inf.cmd = cmd;
        iq.w = sq.w;
        inf.w = sf.w;
        /* The current of a static 4.2 ohm load keeps the current PI working. */
        phase_currents_xy(oq.m * VDC_CUTOFF * 0.5 / 4.2, 0.0, &rot, &iq);
        phase_currents_xy(of.m * VDC_CUTOFF * 0.5 / 4.2, 0.0, &rot, &inf);
        rot_advance(&rot);
        ctl_step(&cq, &iq, &oq);
        ctl_step(&cf, &inf, &of);
        shaft_frame(&sq, &oq, p.step_s);
        shaft_frame(&sf, &of, p.step_s);
        dm = math_max_f64(dm, absd(oq.m - of.m));
        df = math_max_f64(df, absd(oq.freq_hz - of.freq_hz));
        di = math_max_f64(di, absd(oq.i_demand_a - of.i_demand_a));
        dv = math_max_f64(dv, absd(oq.v_demand_v - of.v_demand_v));
        dw = math_max_f64(dw, absd(sq.w - sf.w));
    }
    UT_TEST("fixed vs float, full controller on the shaft (start to 1500 rpm, reverse to "
            "-900 rpm, 2.4 s): m, frequency, current and voltage demand within 1 % of full "
            "scale, speed within 0.5 % of 1500 rpm, no saturation");
    UT_CHECK(dm <= 0.01);
    UT_CHECK(df <= 0.01 * DRIVE_BASE_FREQ_HZ);
    UT_CHECK(di <= 0.01 * DRIVE_BASE_CURRENT_A);
    UT_CHECK(dv <= 0.01 * DRIVE_BASE_VOLTAGE_V);
    UT_CHECK(dw <= 0.005 * W_1500);
    UT_EQ_INT(ctl_sat(&cq), 0);
    ut_info("largest differences: m %.2e, f %.2e Hz, I* %.2e A, v* %.2e V, speed %.2e rad/s",
            dm, df, di, dv, dw);

    UT_TEST("fixed vs float, current loop on the R-L load (20 -> 40 A, 50 Hz): currents "
            "within 1 % of 256 A at every frame");
    drive_control_params pr = rl_params();
    UT_CHECK(ctl_init(&cq, &pr, true) && ctl_init(&cf, &pr, false));
    rl_t lq = rl_make(3.0, 9e-3, 50.0, 0.0);
    rl_t lf = lq;
    double dimax = 0.0;
    for (unsigned k = 0u; k < 1000u; k++) {
        double i_dem = (k < 250u) ? 20.0 : 40.0;
        rl_currents(&lq, &iq);
        rl_currents(&lf, &inf);
        ctl_current(&cq, i_dem, 50.0, 0.0, &iq, &oq);
        ctl_current(&cf, i_dem, 50.0, 0.0, &inf, &of);
        rl_frame(&lq, oq.m * VDC_CUTOFF * 0.5, pr.step_s);
        rl_frame(&lf, of.m * VDC_CUTOFF * 0.5, pr.step_s);
        dimax = math_max_f64(dimax, absd(rl_mag(&lq) - rl_mag(&lf)));
    }
    UT_CHECK(dimax <= 0.01 * DRIVE_BASE_CURRENT_A);
    UT_EQ_INT(ctl_sat(&cq), 0);
    ut_info("largest current difference %.2e A", dimax);
}

/* ---- Parameters, measurement, outputs ---------------------------------------------- */

static void test_params(void) {
    UT_TEST("parameters: the default machine constants are the motor's (15 kW set in delta)");
    const drive_control_params *p = &drive_control_params_default;
    const induction_motor_params *mp = &induction_motor_params_15kw_delta;
    UT_NEAR(p->rs_ohm, mp->rs_ohm, 1e-15);
    UT_NEAR(p->rr_ohm, mp->rr_ohm, 1e-15);
    UT_NEAR(p->lls_h, mp->lls_h, 1e-15);
    UT_NEAR(p->llr_h, mp->llr_h, 1e-15);
    UT_NEAR(p->lm_h, mp->lm_h, 1e-15);
    UT_EQ_INT(p->pole_pairs, mp->pole_pairs);

    UT_TEST("parameters: derived k_q = 2 pi tau_r i_mag, K_T = 3 p psi_r^2 pi / Rr, slip "
            "limit min(slip_max, sqrt(i_max^2 - i_mag^2) / k_q) (hand formulas)");
    drive_control_design d;
    UT_CHECK(drive_control_design_f64(&d, p) == DRIVE_CONTROL_OK);
    double lr = p->llr_h + p->lm_h;
    double tau_r = lr / p->rr_ohm;
    UT_NEAR(d.tau_r_s, tau_r, 1e-12);
    UT_NEAR(d.kq_a_per_hz, TWO_PI * tau_r * p->i_mag_a, 1e-9);
    double psi = p->lm_h * p->i_mag_a;
    UT_NEAR(d.kt_nm_per_hz, 3.0 * 2.0 * psi * psi * MATH_PI_F64 / p->rr_ohm, 1e-9);
    UT_NEAR(d.slip_lim_hz, 1.2, 0.0);
    UT_NEAR(d.sigma_ls_h, (p->lls_h + p->lm_h) - p->lm_h * p->lm_h / lr, 1e-15);
    UT_EQ_INT(d.pwm_step_ns, 2000);
    ut_info("tau_r %.4f s, sigma Ls %.3f mH, k_q %.2f A/Hz, K_T %.2f N m/Hz, I*(slip limit) "
            "%.2f A, torque at the slip limit %.1f N m",
            d.tau_r_s, d.sigma_ls_h * 1e3, d.kq_a_per_hz, d.kt_nm_per_hz,
            math_sqrt_f64(p->i_mag_a * p->i_mag_a +
                          d.kq_a_per_hz * d.slip_lim_hz * d.kq_a_per_hz * d.slip_lim_hz),
            d.kt_nm_per_hz * d.slip_lim_hz);

    UT_TEST("parameters: init rejects NULL and each out-of-range field, in both twins");
    drive_control_q q;
    drive_control_f32 f;
    UT_CHECK(drive_control_init_q(NULL, p) == DRIVE_CONTROL_ERR_NULL);
    UT_CHECK(drive_control_init_q(&q, NULL) == DRIVE_CONTROL_ERR_NULL);
    UT_CHECK(drive_control_init_f32(NULL, p) == DRIVE_CONTROL_ERR_NULL);
    UT_CHECK(drive_control_init_f32(&f, NULL) == DRIVE_CONTROL_ERR_NULL);
    for (unsigned k = 0u; k < 12u; k++) {
        drive_control_params b = *p;
        switch (k) {
        case 0u: b.rs_ohm = -0.1; break;
        case 1u: b.i_max_a = b.i_mag_a; break;
        case 2u: b.i_max_a = 300.0; break;
        case 3u: b.m_max = 1.2; break;
        case 4u: b.freq_max_hz = 130.0; break;
        case 5u: b.speed_max_radps = 300.0; break;
        case 6u: b.pole_pairs = 0u; break;
        case 7u: b.pwm_step_s = 2.5e-10; break;
        case 8u: b.kp_current_v_per_a = -1.0; break;
        case 9u: b.step_s = math_nan_f64(); break;
        case 10u: b.idle_speed_radps = b.speed_max_radps; break;
        default: b.ff_gain = 1.5; break;
        }
        UT_CHECK(drive_control_init_q(&q, &b) == DRIVE_CONTROL_ERR_PARAM);
        UT_CHECK(drive_control_init_f32(&f, &b) == DRIVE_CONTROL_ERR_PARAM);
    }
    drive_control_params big = *p;
    big.kp_speed_hz_per_radps = 1e9; /* 4e9 per unit: no 30-bit mantissa */
    UT_CHECK(drive_control_init_q(&q, &big) == DRIVE_CONTROL_ERR_RANGE);
}

/*
 * The checks of drive_control_design_f64 one by one (drive_control.h gives
 * each field's range), and the constants that only the integer twin must
 * refuse: a gain whose mantissa needs more than 30 bits or is not finite, a
 * per-unit value of 1 or more, a ramp step below one LSB, Vdc_min below
 * 2^16 LSB (drive_control_q.c).
 */
static void test_params_limits(void) {
    UT_TEST("parameters: design rejects NULL, each field beyond its documented range, and "
            "a PWM step that is not whole ns; NULL design output is allowed");
    const drive_control_params *p = &drive_control_params_default;
    drive_control_design d;
    UT_CHECK(drive_control_design_f64(&d, NULL) == DRIVE_CONTROL_ERR_NULL);
    UT_CHECK(drive_control_design_f64(NULL, p) == DRIVE_CONTROL_OK);
    for (unsigned k = 0u; k < 9u; k++) {
        drive_control_params b = *p;
        switch (k) {
        case 0u: b.ki_speed_hz_per_rad = math_inf_f64(); break;
        case 1u: b.i_mag_a = -1.0; break;
        case 2u: b.slip_max_hz = 100.0; break; /* not below freq_max (80 Hz) */
        case 3u: b.vdc_min_v = 2000.0; break;  /* not below the 1024 V base */
        case 4u: b.step_s = 0.02; break;
        case 5u: b.pwm_step_s = 1e-3; break;   /* longer than the 800 us frame */
        case 6u: b.pole_pairs = 17u; break;
        case 7u: b.pwm_step_s = 2.0005e-6; break;
        default: b.accel_max_radps2 = 0.0; break;
        }
        if (!UT_CHECK(drive_control_design_f64(&d, &b) == DRIVE_CONTROL_ERR_PARAM)) {
            ut_info("case %u", k);
        }
    }

    UT_TEST("parameters: the slip limit is sqrt(i_max^2 - i_mag^2) / k_q when that is below "
            "slip_max (hand formula)");
    drive_control_params wide = *p;
    wide.slip_max_hz = 2.0;
    UT_CHECK(drive_control_design_f64(&d, &wide) == DRIVE_CONTROL_OK);
    double iq_max = math_sqrt_f64(p->i_max_a * p->i_max_a - p->i_mag_a * p->i_mag_a);
    UT_NEAR(d.slip_lim_hz, iq_max / d.kq_a_per_hz, 1e-12);
    UT_CHECK(d.slip_lim_hz < 2.0 && d.slip_lim_hz > 1.2);

    UT_TEST("parameters: the integer twin refuses constants that do not fit its formats "
            "(ERR_RANGE) which the float twin accepts");
    drive_control_q q;
    drive_control_f32 f;
    for (unsigned k = 0u; k < 11u; k++) {
        drive_control_params b = *p;
        switch (k) {
        case 0u: b.kp_speed_hz_per_radps = 1e308; break; /* 4e308 per unit: infinite */
        case 1u: b.ki_speed_hz_per_rad = 1e12; break;    /* k_i T = 3.2e9 per unit */
        case 2u: b.rr_ohm = 1e-12; break;                /* k_q of 2e12 per unit */
        case 3u: b.rs_ohm = 1e10; break;
        case 4u: b.lls_h = 1e9; break;                   /* 2 pi sigma Ls */
        case 5u: b.lm_h = 1e10; b.rr_ohm = 1e12; break;  /* 2 pi Ls alone */
        case 6u: b.kp_current_v_per_a = 1e10; break;
        case 7u: b.ki_current_v_per_as = 1e13; break;
        case 8u: b.accel_max_radps2 = 1e6; break;        /* ramp step of 800 rad/s */
        case 9u: b.accel_max_radps2 = 1e-5; break;       /* ramp step below one LSB */
        default: b.vdc_min_v = 0.01; break;              /* below 2^16 LSB of 1024 V */
        }
        bool ok = UT_CHECK(drive_control_init_q(&q, &b) == DRIVE_CONTROL_ERR_RANGE);
        ok = UT_CHECK(drive_control_init_f32(&f, &b) == DRIVE_CONTROL_OK) && ok;
        if (!ok) {
            ut_info("case %u", k);
        }
    }

    UT_TEST("parameters: a gain below 2^-32 keeps the largest shift, 62: ff_gain 1e-12 gives "
            "mantissa round(1e-12 2^62) = 4611686");
    drive_control_params tiny = *p;
    tiny.ff_gain = 1e-12;
    UT_CHECK(drive_control_init_q(&q, &tiny) == DRIVE_CONTROL_OK);
    UT_EQ_INT(q.k_ff.shift, 62);
    UT_EQ_INT(q.k_ff.mant, 4611686);
}

/* The speed integrator [Hz] of either twin. */
static double ctl_x_w(const ctl_t *c) {
    return c->fixed ? fp_pu_to_f64_q31(c->q.x_w, DRIVE_BASE_FREQ_HZ) : (double)c->f.x_w;
}

/*
 * The limits of drive_control.h in both directions: the stator frequency at
 * +-f_max (then the slip is what is left, clamped), the slip at +-f_sl_lim,
 * and the voltage clipped at zero. At each, the integrator is held when the
 * error pushes further into the limit (conditional integration).
 */
static void test_limits(bool fixed) {
    UT_TEST(fixed ? "limits (fixed): f_max = 40 Hz at +-150 rad/s (47.7 Hz of rotor "
                    "frequency): f_s = +-40 Hz, slip = -+f_sl_lim, speed integrator held"
                  : "limits (float): f_max = 40 Hz at +-150 rad/s (47.7 Hz of rotor "
                    "frequency): f_s = +-40 Hz, slip = -+f_sl_lim, speed integrator held");
    drive_control_params p = drive_control_params_default;
    p.freq_max_hz = 40.0;
    drive_control_design d;
    UT_CHECK(drive_control_design_f64(&d, &p) == DRIVE_CONTROL_OK);
    ctl_t c;
    ctl_out_t o;
    for (int k = 0; k < 2; k++) {
        double s = (k == 0) ? 1.0 : -1.0;
        UT_CHECK(ctl_init(&c, &p, fixed));
        ctl_in_t in = {s * 170.0, s * 150.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
        for (unsigned n = 0u; n < 5u; n++) {
            ctl_step(&c, &in, &o);
        }
        UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_FREQ_LIMIT) != 0u);
        UT_NEAR(o.freq_hz, s * 40.0, 1e-6);
        UT_NEAR(o.slip_hz, -s * d.slip_lim_hz, 1e-6);
        UT_NEAR(ctl_x_w(&c), 0.0, 0.0);
    }

    UT_TEST(fixed ? "limits (fixed): at f_max with the error pulling away from the limit "
                    "(command 100 rad/s, shaft 150 rad/s) the speed integrator integrates: "
                    "x_w = k_i T sum(e) = -k_i T 0.16 (1 + ... + 5) rad/s after 5 frames"
                  : "limits (float): at f_max with the error pulling away from the limit "
                    "(command 100 rad/s, shaft 150 rad/s) the speed integrator integrates: "
                    "x_w = k_i T sum(e) = -k_i T 0.16 (1 + ... + 5) rad/s after 5 frames");
    for (int k = 0; k < 2; k++) {
        double s = (k == 0) ? 1.0 : -1.0;
        UT_CHECK(ctl_init(&c, &p, fixed));
        ctl_in_t in = {s * 100.0, s * 150.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
        for (unsigned n = 0u; n < 5u; n++) {
            ctl_step(&c, &in, &o);
        }
        UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_FREQ_LIMIT) != 0u);
        UT_NEAR(o.freq_hz, s * 40.0, 1e-6);
        UT_NEAR(ctl_x_w(&c), -s * p.ki_speed_hz_per_rad * p.step_s * 0.16 * 15.0, 1e-7);
    }

    UT_TEST(fixed ? "limits (fixed): the shaft held at +-20 rad/s while the reference ramps "
                    "away: slip at +-f_sl_lim, speed integrator held from then on"
                  : "limits (float): the shaft held at +-20 rad/s while the reference ramps "
                    "away: slip at +-f_sl_lim, speed integrator held from then on");
    p = drive_control_params_default;
    UT_CHECK(drive_control_design_f64(&d, &p) == DRIVE_CONTROL_OK);
    for (int k = 0; k < 2; k++) {
        double s = (k == 0) ? 1.0 : -1.0;
        UT_CHECK(ctl_init(&c, &p, fixed));
        ctl_in_t in = {s * 170.0, s * 20.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
        double x_held = 0.0;
        /* kp e alone passes f_sl_lim once e > f_sl_lim / kp: 30 rad/s, or 188 frames of the
         * 0.16 rad/s ramp, with the default gains. */
        for (unsigned n = 0u; n < 300u; n++) {
            ctl_step(&c, &in, &o);
            if (n == 279u) {
                x_held = ctl_x_w(&c);
            }
        }
        UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_SLIP_LIMIT) != 0u);
        UT_NEAR(o.slip_hz, s * d.slip_lim_hz, 1e-6);
        UT_NEAR(ctl_x_w(&c), x_held, 0.0);
        UT_CHECK(s * x_held > 0.0 && absd(x_held) <= d.slip_lim_hz + 1e-6);
    }

    UT_TEST(fixed ? "idle band (fixed): a zero command with the shaft at +-50 rad/s keeps the "
                    "drive running (braking slip), with the shaft at 3 rad/s it idles"
                  : "idle band (float): a zero command with the shaft at +-50 rad/s keeps the "
                    "drive running (braking slip), with the shaft at 3 rad/s it idles");
    for (int k = 0; k < 2; k++) {
        double s = (k == 0) ? 1.0 : -1.0;
        UT_CHECK(ctl_init(&c, &p, fixed));
        ctl_in_t in = {0.0, s * 50.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
        ctl_step(&c, &in, &o);
        UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_IDLE) == 0u);
        UT_CHECK(s * o.slip_hz < 0.0);
        UT_NEAR(o.freq_hz, s * 50.0 * 2.0 / TWO_PI + o.slip_hz, 1e-5);
        in.w = 3.0;
        ctl_step(&c, &in, &o);
        UT_CHECK(o.flags == DRIVE_CONTROL_FLAG_IDLE);
    }

    UT_TEST(fixed ? "current loop (fixed): 200 A measured against a 5 A demand clips v* at "
                    "zero (m = 0, flag) and holds the current integrator"
                  : "current loop (float): 200 A measured against a 5 A demand clips v* at "
                    "zero (m = 0, flag) and holds the current integrator");
    UT_CHECK(ctl_init(&c, &p, fixed));
    ctl_in_t in = {0.0, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    phase_currents(200.0, 0.3, &in);
    ctl_current(&c, 5.0, 10.0, 0.5, &in, &o);
    UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_M_ZERO) != 0u);
    UT_CHECK(o.m == 0.0 && o.v_demand_v == 0.0);
    UT_NEAR(ctl_x_i(&c), 0.0, 0.0);

    UT_TEST(fixed ? "current loop (fixed): with v* clipped at zero by a negative integrator, "
                    "an error pulling out of the clip integrates: x_i += k_i T e (e = 1 A)"
                  : "current loop (float): with v* clipped at zero by a negative integrator, "
                    "an error pulling out of the clip integrates: x_i += k_i T e (e = 1 A)");
    /* 100 A against 5 A at 10 Hz winds x_i down until v* reaches zero (then it is held). */
    phase_currents(100.0, 0.3, &in);
    for (unsigned n = 0u; n < 10u; n++) {
        ctl_current(&c, 5.0, 10.0, 0.5, &in, &o);
    }
    UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_M_ZERO) != 0u);
    double x0 = ctl_x_i(&c);
    UT_CHECK(x0 < -5.0);
    phase_currents(4.0, 0.3, &in);
    ctl_current(&c, 5.0, 0.0, 0.0, &in, &o);
    UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_M_ZERO) != 0u);
    UT_NEAR(ctl_x_i(&c) - x0, p.ki_current_v_per_as * p.step_s * 1.0, 1e-5);
    UT_EQ_INT(ctl_sat(&c), 0);
}

static void test_measurement_outputs(bool fixed) {
    UT_TEST(fixed ? "measurement (fixed): |i| of a balanced set at 12 angles within 1e-4 A, "
                    "and of an unbalanced set by the Clarke formula; phase increment = "
                    "wt_phase_inc_q16(f, 2000 ns) within 1 count"
                  : "measurement (float): |i| of a balanced set at 12 angles within 1e-4 "
                    "relative; phase increment = wt_phase_inc_f32 at f");
    drive_control_params p = rl_params();
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    ctl_in_t in = {0.0, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    ctl_out_t o;
    for (unsigned k = 0u; k < 12u; k++) {
        phase_currents(41.25, 0.55 * (double)k - 3.0, &in);
        ctl_current(&c, 0.0, -37.5, 0.0, &in, &o);
        UT_NEAR(o.i_meas_a, 41.25, fixed ? 1e-4 : 41.25 * 1e-4);
    }
    in.ia = 10.0;
    in.ib = 4.0;
    in.ic = -20.0;
    ctl_current(&c, 0.0, 50.0, 0.0, &in, &o);
    double x = 2.0 * 10.0 - 4.0 + 20.0;
    double y = 4.0 + 20.0;
    UT_NEAR(o.i_meas_a, math_sqrt_f64(x * x + 3.0 * y * y) / 3.0, 1e-4);
    if (fixed) {
        uint32_t want = wt_phase_inc_q16(50 * 65536, 2000u);
        UT_CHECK((o.phase_inc - want <= 1u) || (want - o.phase_inc <= 1u));
        ctl_current(&c, 0.0, -37.5, 0.0, &in, &o);
        want = wt_phase_inc_q16(-(int32_t)(37.5 * 65536.0), 2000u);
        UT_CHECK((o.phase_inc - want <= 1u) || (want - o.phase_inc <= 1u));
    } else {
        UT_EQ_INT(o.phase_inc, wt_phase_inc_f32(50.0f, 2e-6f));
    }

    UT_TEST(fixed ? "normalisation (fixed): m = v* / (Vdc / 2) at 432 V and 605 V; Vdc below "
                    "vdc_min uses vdc_min"
                  : "normalisation (float): m = v* / (Vdc / 2) at 432 V and 605 V; Vdc below "
                    "vdc_min uses vdc_min");
    const double vdcs[3] = {432.0, 605.0, 20.0};
    for (unsigned k = 0u; k < 3u; k++) {
        ctl_t c2;
        UT_CHECK(ctl_init(&c2, &p, fixed));
        in.vdc = vdcs[k];
        phase_currents(10.0, 0.0, &in);
        ctl_current(&c2, 30.0, 50.0, 0.0, &in, &o);
        double vdc_eff = (vdcs[k] > p.vdc_min_v) ? vdcs[k] : p.vdc_min_v;
        UT_NEAR(o.v_demand_v, 0.3 * 20.0, 1e-3);
        UT_NEAR(o.m, o.v_demand_v / (0.5 * vdc_eff), 1e-4);
    }
    UT_EQ_INT(ctl_sat(&c), 0);
}

static void test_generating_hold(bool fixed) {
    UT_TEST(fixed ? "generating (fixed): slip against frequency holds the current integrator "
                    "and drops the P term (v* = v_ff + x_i), flag set"
                  : "generating (float): slip against frequency holds the current integrator "
                    "and drops the P term (v* = v_ff + x_i), flag set");
    drive_control_params p = drive_control_params_default;
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    ctl_in_t in = {0.0, 0.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    ctl_out_t o;
    phase_currents(30.0, 1.0, &in);
    for (unsigned k = 0u; k < 10u; k++) {
        ctl_current(&c, 40.0, 50.0, 0.5, &in, &o); /* motoring: integrates */
    }
    UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_GENERATING) == 0u);
    double x0 = ctl_x_i(&c);
    UT_CHECK(x0 > 0.0);
    ctl_out_t g1;
    ctl_out_t g2;
    ctl_current(&c, 40.0, 50.0, -0.5, &in, &g1);
    ctl_current(&c, 40.0, 50.0, -0.5, &in, &g2);
    UT_CHECK((g1.flags & DRIVE_CONTROL_FLAG_GENERATING) != 0u);
    UT_NEAR(ctl_x_i(&c), x0, 1e-9);
    UT_NEAR(g2.v_demand_v, g1.v_demand_v, 1e-9);
    /* v_ff by hand at i_d = i_mag, i_q = k_q (-0.5 Hz), 50 Hz. */
    drive_control_design d;
    (void)drive_control_design_f64(&d, &p);
    double iq = -0.5 * d.kq_a_per_hz;
    double ws = TWO_PI * 50.0;
    double vd = p.rs_ohm * p.i_mag_a - ws * d.sigma_ls_h * iq;
    double vq = p.rs_ohm * iq + ws * d.ls_h * p.i_mag_a;
    UT_NEAR(g1.v_demand_v, math_sqrt_f64(vd * vd + vq * vq) + x0, 2e-3);
    UT_EQ_INT(ctl_sat(&c), 0);
}

static void test_standstill(bool fixed) {
    UT_TEST(fixed ? "standstill (fixed): zero command at rest idles (m = 0, f = 0); a command "
                    "starts the reference at the shaft speed (flying start), speed over the "
                    "limit is clamped"
                  : "standstill (float): zero command at rest idles (m = 0, f = 0); a command "
                    "starts the reference at the shaft speed (flying start), speed over the "
                    "limit is clamped");
    drive_control_params p = drive_control_params_default;
    ctl_t c;
    UT_CHECK(ctl_init(&c, &p, fixed));
    ctl_in_t in = {0.0, 3.0, 0.0, 0.0, 0.0, VDC_CUTOFF};
    ctl_out_t o;
    ctl_step(&c, &in, &o);
    UT_CHECK(o.flags == DRIVE_CONTROL_FLAG_IDLE);
    UT_CHECK((o.m == 0.0) && (o.freq_hz == 0.0) && (o.i_demand_a == 0.0));
    in.cmd = 100.0;
    in.w = 60.0;
    ctl_step(&c, &in, &o);
    UT_CHECK((o.flags & DRIVE_CONTROL_FLAG_IDLE) == 0u);
    UT_NEAR(o.speed_ref, 60.0 + p.accel_max_radps2 * p.step_s, 1e-4);
    UT_CHECK(o.freq_hz > 60.0 * 2.0 / TWO_PI);
    in.cmd = 1000.0;
    for (unsigned k = 0u; k < 1000u; k++) {
        ctl_step(&c, &in, &o);
    }
    UT_NEAR(o.speed_ref, p.speed_max_radps, 1e-4);
    UT_EQ_INT(ctl_sat(&c), 0);
}

void suite_drive_control(void) {
    test_params();
    test_params_limits();
    for (unsigned k = 0u; k < 2u; k++) {
        bool fixed = (k == 0u);
        test_limits(fixed);
        test_measurement_outputs(fixed);
        test_generating_hold(fixed);
        test_standstill(fixed);
        UT_TEST(fixed ? "current loop (fixed), step 20 -> 40 A on R-L loads (running motor "
                        "3 ohm / 9 mH at 50 Hz; standstill 0.145 ohm / 0.66 mH at 2 Hz): "
                        "overshoot <= 5 %, final within 1 %, no saturation"
                      : "current loop (float), step 20 -> 40 A on R-L loads (running motor "
                        "3 ohm / 9 mH at 50 Hz; standstill 0.145 ohm / 0.66 mH at 2 Hz): "
                        "overshoot <= 5 %, final within 1 %");
        test_current_step(fixed, 3.0, 9e-3, 50.0, 900u);
        test_current_step(fixed, 0.145, 0.66e-3, 2.0, 150u);
        UT_TEST(fixed ? "anti-windup (fixed): unreachable demand saturates m, integrator "
                        "stays bounded; after the drop m leaves saturation at once, undershoot "
                        "<= 5 %, recovery faster than a plain PI"
                      : "anti-windup (float): unreachable demand saturates m, integrator "
                        "stays bounded; after the drop m leaves saturation at once, undershoot "
                        "<= 5 %, recovery faster than a plain PI");
        test_anti_windup(fixed);
        UT_TEST(fixed ? "speed loop (fixed) on the shaft (J, propeller load, torque ~ slip): "
                        "0 -> 1500 rpm overshoot <= 5 %, error <= 0.5 %, limits honoured"
                      : "speed loop (float) on the shaft (J, propeller load, torque ~ slip): "
                        "0 -> 1500 rpm overshoot <= 5 %, error <= 0.5 %, limits honoured");
        test_speed_start(fixed, true);
        test_speed_start(fixed, false);
        UT_TEST(fixed ? "speed loop (fixed): reversal to -1500 rpm within 0.5 %, overshoot "
                        "<= 5 %; zero command brakes and idles at standstill"
                      : "speed loop (float): reversal to -1500 rpm within 0.5 %, overshoot "
                        "<= 5 %; zero command brakes and idles at standstill");
        test_speed_reverse_stop(fixed);
    }
    test_fixed_vs_float();
}

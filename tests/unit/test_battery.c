/*
 * The battery model against references computed here, independently of
 * src/models/battery/battery.c: the published cell table itself, hand-written
 * Thevenin relations, closed-form solutions of the RC branch, and a
 * continuous-time simulation of the cell (RK4, SOC-dependent parameters
 * re-evaluated inside every stage, not frozen per frame as in the model).
 */
#include <stddef.h>

#include "math/umath.h"
#include "models/battery/battery.h"
#include "ut.h"

void suite_battery(void);

#define H_FRAME 0.1 /* [s] the slow frame of battery_params_uuv */

/* ---- Independent references -------------------------------------------- */

/* Linear interpolation by a plain scan, clamped at both ends. */
static double ref_interp(const double *x, const double *y, uint32_t n, double at) {
    if (at <= x[0]) {
        return y[0];
    }
    for (uint32_t k = 1u; k < n; k++) {
        if (at <= x[k]) {
            const double w = (at - x[k - 1u]) / (x[k] - x[k - 1u]);
            return (1.0 - w) * y[k - 1u] + w * y[k];
        }
    }
    return y[n - 1u];
}

typedef struct {
    double ocv, r0, r1, c1;
} ref_cell_values;

static ref_cell_values ref_cell_at(const battery_params *p, double soc) {
    const battery_cell_table *t = &p->cell;
    ref_cell_values v;
    v.ocv = ref_interp(t->soc, t->ocv_v, t->n_points, soc);
    v.r0 = ref_interp(t->soc, t->r0_ohm, t->n_points, soc);
    v.r1 = ref_interp(t->soc, t->r1_ohm, t->n_points, soc);
    v.c1 = ref_interp(t->soc, t->c1_f, t->n_points, soc);
    return v;
}

/* State of the continuous-time reference cell. */
typedef struct {
    double soc;
    double v1; /* [V] in the direction of the current into the cell */
} ref_state;

/*
 * Cell current [A] (into the cell) for a cell power demand p [W] delivered:
 * the smaller root of r0 i^2 + (ocv + v1) i + p = 0.
 */
static double ref_current_for_power(const battery_params *p, ref_state s, double p_cell) {
    const ref_cell_values c = ref_cell_at(p, s.soc);
    const double e = c.ocv + s.v1;
    return -2.0 * p_cell / (e + math_sqrt_f64(e * e - 4.0 * c.r0 * p_cell));
}

/* Derivative of the reference state; the current is a cell current or, with
 * by_power, a cell power demand. */
static ref_state ref_deriv(const battery_params *p, ref_state s, double drive, bool by_power) {
    const ref_cell_values c = ref_cell_at(p, s.soc);
    const double i = by_power ? ref_current_for_power(p, s, drive) : drive;
    ref_state d;
    d.soc = i / (p->capacity_ah * 3600.0);
    d.v1 = -s.v1 / (c.r1 * c.c1) + i / c.c1;
    return d;
}

static ref_state ref_rk4(const battery_params *p, ref_state s, double drive, bool by_power,
                         double h) {
    const ref_state k1 = ref_deriv(p, s, drive, by_power);
    const ref_state s2 = {s.soc + 0.5 * h * k1.soc, s.v1 + 0.5 * h * k1.v1};
    const ref_state k2 = ref_deriv(p, s2, drive, by_power);
    const ref_state s3 = {s.soc + 0.5 * h * k2.soc, s.v1 + 0.5 * h * k2.v1};
    const ref_state k3 = ref_deriv(p, s3, drive, by_power);
    const ref_state s4 = {s.soc + h * k3.soc, s.v1 + h * k3.v1};
    const ref_state k4 = ref_deriv(p, s4, drive, by_power);
    ref_state n;
    n.soc = s.soc + h / 6.0 * (k1.soc + 2.0 * k2.soc + 2.0 * k3.soc + k4.soc);
    n.v1 = s.v1 + h / 6.0 * (k1.v1 + 2.0 * k2.v1 + 2.0 * k3.v1 + k4.v1);
    return n;
}

/* Loaded cell voltage of the reference for cell current i. */
static double ref_cell_voltage(const battery_params *p, ref_state s, double i) {
    const ref_cell_values c = ref_cell_at(p, s.soc);
    return c.ocv + s.v1 + c.r0 * i;
}

static double abs_f64(double x) { return (x < 0.0) ? -x : x; }

/* One frame as the fast segment would report it for a constant current i. */
static void step_with_current(battery *b, double i) {
    const double v = battery_voltage_f64(b, i);
    const battery_frame_meas m = {i, i * i, v * i};
    battery_step_f64(b, &m);
}

/* ---- Tests -------------------------------------------------------------- */

static void test_ocv_curve(void) {
    UT_TEST("OCV(SOC): the published table at its breakpoints, linear between, "
            "non-decreasing, clamped outside [0, 1] (Huria et al. 2012, 20 degC)");
    const battery_params *p = &battery_params_uuv;
    const battery_cell_table *t = &p->cell;
    for (uint32_t k = 0u; k < t->n_points; k++) {
        UT_CHECK(battery_ocv_cell_f64(p, t->soc[k]) == t->ocv_v[k]);
    }
    for (uint32_t k = 0u; k + 1u < t->n_points; k++) {
        const double mid = 0.5 * (t->soc[k] + t->soc[k + 1u]);
        const double q = t->soc[k] + 0.25 * (t->soc[k + 1u] - t->soc[k]);
        UT_NEAR(battery_ocv_cell_f64(p, mid), 0.5 * (t->ocv_v[k] + t->ocv_v[k + 1u]), 1e-12);
        UT_NEAR(battery_ocv_cell_f64(p, q), 0.75 * t->ocv_v[k] + 0.25 * t->ocv_v[k + 1u],
                1e-12);
    }
    bool rising = true;
    double prev = battery_ocv_cell_f64(p, 0.0);
    for (uint32_t j = 1u; j <= 2000u; j++) {
        const double v = battery_ocv_cell_f64(p, (double)j / 2000.0);
        rising = rising && (v > prev);
        prev = v;
    }
    UT_CHECK(rising);
    UT_CHECK(battery_ocv_cell_f64(p, -0.2) == t->ocv_v[0]);
    UT_CHECK(battery_ocv_cell_f64(p, 1.3) == t->ocv_v[t->n_points - 1u]);
    ut_info("cell OCV %.4f V at SOC 0 .. %.4f V at SOC 1; strictly rising on a 2001-point grid",
            t->ocv_v[0], t->ocv_v[t->n_points - 1u]);
}

/* Brings the battery to a state with a polarisation voltage and an SOC off the breakpoints. */
static void prepare_loaded(battery *b, double soc0, double i, uint32_t frames) {
    UT_EQ_INT(battery_init(b, &battery_params_uuv, soc0), BATTERY_OK);
    for (uint32_t f = 0u; f < frames; f++) {
        step_with_current(b, i);
    }
}

static void test_companion_thevenin(void) {
    UT_TEST("companion: i = G v - b reproduces the frame-mean Thevenin relation "
            "v = ns (OCV + k v1) + ns/np (R0 + R1 (1 - k)) i, k = (1 - e^(-h/tau)) tau/h");
    const battery_params *p = &battery_params_uuv;
    battery b;
    prepare_loaded(&b, 0.55, -30.0, 300u);
    const ref_cell_values c = ref_cell_at(p, b.soc);
    const double tau = c.r1 * c.c1;
    const double k = (1.0 - math_exp_f64(-H_FRAME / tau)) * tau / H_FRAME;
    const double ns = (double)p->n_series;
    const double np = (double)p->n_parallel;
    const double e = ns * (c.ocv + k * b.v1_cell_v);
    const double r = ns / np * (c.r0 + c.r1 * (1.0 - k));
    const battery_companion cp = battery_companion_f64(&b);
    const double currents[6] = {-60.0, -22.0, -7.0, 0.0, 5.0, 30.0};
    double worst = 0.0;
    for (uint32_t j = 0u; j < 6u; j++) {
        const double v = e + r * currents[j];
        const double i_back = cp.g_s * v - cp.b_a;
        UT_NEAR(i_back, currents[j], 1e-9);
        UT_NEAR(battery_voltage_f64(&b, currents[j]), v, 1e-9);
        worst = (abs_f64(i_back - currents[j]) > worst) ? abs_f64(i_back - currents[j]) : worst;
    }
    /* The bus node with a 25 ohm load: v = b / (G + 1/25) must be the Thevenin divider. */
    const double v_node = cp.b_a / (cp.g_s + 1.0 / 25.0);
    UT_NEAR(v_node, e * 25.0 / (25.0 + r), 1e-9);
    ut_info("SOC %.4f, v1 %.3e V: G = %.6f S, b = %.4f A, largest |G v - b - i| %.2e A",
            b.soc, b.v1_cell_v, cp.g_s, cp.b_a, worst);
    ut_info("1 - k = %.3e (h / 2 tau = %.3e): the RC branch adds %.3e ohm to R0 over a frame",
            1.0 - k, H_FRAME / (2.0 * tau), c.r1 * (1.0 - k));
}

static void test_companion_frame_mean(void) {
    UT_TEST("companion: for a current held over one frame, battery_voltage equals the mean "
            "terminal voltage of the circuit with OCV and RC parameters frozen (1000 RK4 steps)");
    const battery_params *p = &battery_params_uuv;
    battery b;
    prepare_loaded(&b, 0.3, -40.0, 200u);
    const ref_cell_values c = ref_cell_at(p, b.soc);
    const double i_pack = -22.0;
    const double i_cell = i_pack / (double)p->n_parallel;
    const double hs = H_FRAME / 1000.0;
    double v1 = b.v1_cell_v;
    double sum = 0.5 * v1;
    for (uint32_t j = 0u; j < 1000u; j++) {
        const double k1 = -v1 / (c.r1 * c.c1) + i_cell / c.c1;
        const double k2 = -(v1 + 0.5 * hs * k1) / (c.r1 * c.c1) + i_cell / c.c1;
        const double k3 = -(v1 + 0.5 * hs * k2) / (c.r1 * c.c1) + i_cell / c.c1;
        const double k4 = -(v1 + hs * k3) / (c.r1 * c.c1) + i_cell / c.c1;
        v1 += hs / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        sum += (j + 1u < 1000u) ? v1 : 0.5 * v1;
    }
    const double v1_mean = sum / 1000.0;
    const double v_mean = (double)p->n_series * (c.ocv + v1_mean + c.r0 * i_cell);
    UT_NEAR(battery_voltage_f64(&b, i_pack), v_mean, 1e-9);
    ut_info("mean terminal voltage %.9f V, model %.9f V", v_mean,
            battery_voltage_f64(&b, i_pack));
}

static void test_charge_counting(void) {
    UT_TEST("charge counting: a constant current I for a time t changes SOC by I t / Q "
            "(Q = np x 27.63 A h)");
    const battery_params *p = &battery_params_uuv;
    battery b;
    UT_EQ_INT(battery_init(&b, p, 0.8), BATTERY_OK);
    const double q_pack = (double)p->n_parallel * p->capacity_ah * 3600.0;
    for (uint32_t f = 0u; f < 1200u; f++) {
        step_with_current(&b, -40.0);
    }
    const double d1 = b.soc - 0.8;
    UT_NEAR(d1, -40.0 * 120.0 / q_pack, 1e-13);
    UT_NEAR(b.q_out_c, 40.0 * 120.0, 1e-9);
    const double soc_mid = b.soc;
    for (uint32_t f = 0u; f < 300u; f++) {
        step_with_current(&b, 25.0);
    }
    const double d2 = b.soc - soc_mid;
    UT_NEAR(d2, 25.0 * 30.0 / q_pack, 1e-13);
    UT_NEAR(b.q_out_c, 40.0 * 120.0 - 25.0 * 30.0, 1e-9);
    UT_NEAR(battery_time_f64(&b), 150.0, 1e-12);
    ut_info("120 s at -40 A: dSOC %.15f, I t / Q = %.15f (error %.1e)", d1,
            -40.0 * 120.0 / q_pack, d1 + 40.0 * 120.0 / q_pack);
    ut_info("then 30 s at +25 A: dSOC %.15f, I t / Q = %.15f (error %.1e)", d2,
            25.0 * 30.0 / q_pack, d2 - 25.0 * 30.0 / q_pack);
}

/* Current of the mixed profile at time t: cruise, full power, rest, regeneration, part load. */
static double profile_current(double t) {
    const double ph = t - 120.0 * (double)(uint32_t)(t / 120.0);
    if (ph < 60.0) {
        return -7.0;
    }
    if (ph < 90.0) {
        return -22.0;
    }
    if (ph < 100.0) {
        return 0.0;
    }
    if (ph < 110.0) {
        return 5.0;
    }
    return -15.0;
}

static void test_energy(void) {
    UT_TEST("energy: delivered energy equals -integral(v i dt) of the continuous reference "
            "within 0.1 %, and source = delivered + R0 and R1 heat + C1 store");
    const battery_params *p = &battery_params_uuv;
    const double ns = (double)p->n_series;
    const double np = (double)p->n_parallel;
    battery b;
    UT_EQ_INT(battery_init(&b, p, 0.6), BATTERY_OK);
    ref_state s = {0.6, 0.0};
    double e_ref = 0.0;
    for (uint32_t f = 0u; f < 6000u; f++) {
        const double i = profile_current((double)f * H_FRAME);
        step_with_current(&b, i);
        /* One RK4 step per frame (h / tau < 3.4e-3) and the trapezoidal rule on the power. */
        const double p0 = ref_cell_voltage(p, s, i / np) * i;
        s = ref_rk4(p, s, i / np, false, H_FRAME);
        const double p1 = ref_cell_voltage(p, s, i / np) * i;
        e_ref -= ns * 0.5 * H_FRAME * (p0 + p1);
    }
    const double rel = (b.e_out_j - e_ref) / e_ref;
    UT_CHECK(abs_f64(rel) < 1e-3);
    UT_NEAR(b.soc, s.soc, 1e-9);
    const ref_cell_values c = ref_cell_at(p, b.soc);
    const double e_c1 = ns * np * 0.5 * c.c1 * b.v1_cell_v * b.v1_cell_v;
    const double balance = b.e_source_j - b.e_out_j - b.e_loss_r0_j - b.e_loss_r1_j - e_c1;
    UT_CHECK(abs_f64(balance) < 1e-4 * b.e_out_j);
    UT_CHECK(b.e_loss_r0_j > 0.0 && b.e_loss_r1_j > 0.0);
    ut_info("600 s profile: delivered %.3f kJ, reference %.3f kJ, relative error %.2e",
            b.e_out_j / 1e3, e_ref / 1e3, rel);
    ut_info("source %.3f kJ, R0 heat %.4f kJ, R1 heat %.4f kJ, C1 store %.4f kJ, "
            "balance residual %.2e J; SOC model %.9f, reference %.9f",
            b.e_source_j / 1e3, b.e_loss_r0_j / 1e3, b.e_loss_r1_j / 1e3, e_c1 / 1e3, balance,
            b.soc, s.soc);
}

static void test_rc_relaxation(void) {
    UT_TEST("RC branch: after a current step v1 = R1 i (1 - e^(-t/tau)); at rest it decays "
            "as e^(-t/tau), tau = R1 C1 (closed form)");
    static battery_params flat;
    flat = battery_params_uuv;
    for (uint32_t k = 0u; k < flat.cell.n_points; k++) {
        flat.cell.r1_ohm[k] = 0.002;
        flat.cell.c1_f[k] = 20000.0; /* tau = 40 s */
    }
    battery b;
    UT_EQ_INT(battery_init(&b, &flat, 0.7), BATTERY_OK);
    const double i_cell = -15.0;
    double worst = 0.0;
    for (uint32_t f = 1u; f <= 1200u; f++) {
        step_with_current(&b, i_cell * (double)flat.n_parallel);
        const double expect = 0.002 * i_cell * (1.0 - math_exp_f64(-(double)f * H_FRAME / 40.0));
        const double err = abs_f64(b.v1_cell_v - expect);
        worst = (err > worst) ? err : worst;
    }
    UT_CHECK(worst < 1e-12);
    ut_info("step of %.0f A per cell, 120 s: largest |v1 - R1 i (1 - e^(-t/tau))| = %.2e V",
            i_cell, worst);
    const double v1_0 = b.v1_cell_v;
    double worst_rest = 0.0;
    for (uint32_t f = 1u; f <= 400u; f++) {
        step_with_current(&b, 0.0);
        const double err = abs_f64(b.v1_cell_v - v1_0 * math_exp_f64(-(double)f * H_FRAME / 40.0));
        worst_rest = (err > worst_rest) ? err : worst_rest;
    }
    UT_CHECK(worst_rest < 1e-12);
    const double tau_meas = -40.0 / math_log_f64(b.v1_cell_v / v1_0);
    UT_NEAR(tau_meas, 40.0, 1e-6);
    ut_info("rest 40 s: largest error %.2e V, tau measured from the decay %.9f s (R1 C1 = 40 s)",
            worst_rest, tau_meas);

    /* The published table at SOC 0.5 (a breakpoint): tau = 0.0016 * 18721 = 29.95 s. */
    battery c;
    prepare_loaded(&c, 0.5, 0.0, 0u);
    c.v1_cell_v = -0.02; /* a polarisation as after a discharge; SOC stays at 0.5 at rest */
    battery_step_f64(&c, &(battery_frame_meas){0.0, 0.0, 0.0});
    const double v1_start = c.v1_cell_v;
    for (uint32_t f = 0u; f < 300u; f++) {
        step_with_current(&c, 0.0);
    }
    const double tau_tab = -30.0 / math_log_f64(c.v1_cell_v / v1_start);
    UT_NEAR(tau_tab, 0.0016 * 18721.0, 1e-6);
    ut_info("published table at SOC 0.5: tau measured %.6f s, R1 C1 = %.6f s", tau_tab,
            0.0016 * 18721.0);
}

/*
 * Runs the model at a constant delivered power until it cuts off; returns
 * false if it did not within max_frames.
 */
static bool run_constant_power(battery *b, double p_w, uint32_t max_frames) {
    for (uint32_t f = 0u; f < max_frames && !b->cut_off; f++) {
        step_with_current(b, battery_current_for_power_f64(b, p_w));
    }
    return b->cut_off;
}

/*
 * The reference at constant power: integrates until SOC reaches 0 or the
 * loaded cell voltage reaches v_cut, and returns the time, interpolated
 * linearly inside the last step, and the SOC there.
 */
static double ref_time_to_cutoff(const battery_params *p, double soc0, double p_w, double v_cut,
                                 double *soc_at) {
    const double p_cell = p_w / ((double)p->n_series * (double)p->n_parallel);
    const double h = 0.5;
    ref_state s = {soc0, 0.0};
    double v_prev = ref_cell_voltage(p, s, ref_current_for_power(p, s, p_cell));
    for (uint32_t n = 0u; n < 200000u; n++) {
        const ref_state next = ref_rk4(p, s, p_cell, true, h);
        const double v = ref_cell_voltage(p, next, ref_current_for_power(p, next, p_cell));
        double w = -1.0;
        if (next.soc <= 0.0) {
            w = s.soc / (s.soc - next.soc);
        } else if (v <= v_cut) {
            w = (v_prev - v_cut) / (v_prev - v);
        }
        if (w >= 0.0) {
            *soc_at = s.soc + w * (next.soc - s.soc);
            return ((double)n + w) * h;
        }
        s = next;
        v_prev = v;
    }
    *soc_at = s.soc;
    return -1.0;
}

static void check_disconnected(battery *b) {
    const battery_companion cp = battery_companion_f64(b);
    UT_CHECK(cp.g_s == 0.0 && cp.b_a == 0.0);
    const double soc = b->soc;
    const double q = b->q_out_c;
    const double t_cut = b->t_cutoff_s;
    for (uint32_t f = 0u; f < 100u; f++) {
        const double i_bus = cp.g_s * 480.0 - cp.b_a; /* whatever the bus voltage */
        const battery_frame_meas m = {i_bus, i_bus * i_bus, 480.0 * i_bus};
        battery_step_f64(b, &m);
    }
    UT_CHECK(b->soc == soc && b->q_out_c == q);
    UT_CHECK(b->cut_off && b->t_cutoff_s == t_cut);
    UT_CHECK(battery_current_for_power_f64(b, 5000.0) == 0.0);
    /* Even a current forced through an open contactor moves no charge. */
    const battery_frame_meas forced = {-20.0, 400.0, -9600.0};
    battery_step_f64(b, &forced);
    UT_CHECK(b->soc == soc && b->q_out_c == q);
}

static void test_cutoff_empty(void) {
    UT_TEST("cut-off on empty: 11 kW from SOC 0.06 trips at SOC 0 within one frame of the "
            "time of the continuous reference; then G = b = 0 and no charge moves");
    const battery_params *p = &battery_params_uuv;
    const double p_w = 11000.0;
    battery b;
    UT_EQ_INT(battery_init(&b, p, 0.06), BATTERY_OK);
    UT_CHECK(run_constant_power(&b, p_w, 20000u));
    double soc_ref = 0.0;
    const double t_ref = ref_time_to_cutoff(p, 0.06, p_w, p->v_cutoff_cell_v, &soc_ref);
    UT_EQ_INT(b.cutoff_cause, BATTERY_CUTOFF_EMPTY);
    UT_CHECK(b.t_cutoff_s >= t_ref - 0.02 && b.t_cutoff_s <= t_ref + H_FRAME + 0.02);
    const double dsoc_frame = 25.0 * H_FRAME / battery_capacity_pack_f64(p);
    UT_CHECK(b.soc_cutoff <= 0.0 && b.soc_cutoff > -dsoc_frame);
    UT_NEAR(b.e_out_j, p_w * b.t_cutoff_s, 1e-6 * p_w * b.t_cutoff_s);
    UT_CHECK(b.v_cell_end_v * (double)p->n_series > 410.0);
    ut_info("tripped at %.1f s (reference %.3f s), SOC %.2e, loaded cell %.4f V, "
            "bus %.2f V; delivered %.4f kWh", b.t_cutoff_s, t_ref, b.soc_cutoff,
            b.v_cell_end_v, b.v_cell_end_v * (double)p->n_series, b.e_out_j / 3.6e6);
    check_disconnected(&b);
}

static void test_cutoff_voltage(void) {
    UT_TEST("cut-off on voltage: with a 3.52 V cut-off, 11 kW from SOC 0.34 trips when the "
            "loaded cell voltage reaches it, at the reference's time and SOC");
    static battery_params high_cut;
    high_cut = battery_params_uuv;
    high_cut.v_cutoff_cell_v = 3.52;
    const double p_w = 11000.0;
    battery b;
    UT_EQ_INT(battery_init(&b, &high_cut, 0.34), BATTERY_OK);
    UT_CHECK(run_constant_power(&b, p_w, 20000u));
    double soc_ref = 0.0;
    const double t_ref = ref_time_to_cutoff(&high_cut, 0.34, p_w, 3.52, &soc_ref);
    UT_EQ_INT(b.cutoff_cause, BATTERY_CUTOFF_VOLTAGE);
    UT_CHECK(b.t_cutoff_s >= t_ref - 0.05 && b.t_cutoff_s <= t_ref + H_FRAME + 0.05);
    UT_NEAR(b.soc_cutoff, soc_ref, 2e-5);
    UT_CHECK(b.v_cell_end_v <= 3.52 && b.v_cell_end_v > 3.52 - 1e-3);
    ut_info("tripped at %.1f s (reference %.3f s), SOC %.6f (reference %.6f), cell %.5f V",
            b.t_cutoff_s, t_ref, b.soc_cutoff, soc_ref, b.v_cell_end_v);
    check_disconnected(&b);
}

/* Sets *b to a recognisable content, to see that a rejected init leaves it alone. */
static void mark(battery *b) {
    *b = (battery){0};
    b->soc = 0.123;
}

static void expect_rejected(const battery_params *p, double soc0, battery_status want) {
    battery b;
    mark(&b);
    const battery_status s = battery_init(&b, p, soc0);
    UT_EQ_INT(s, want);
    UT_CHECK(b.soc == 0.123 && b.p == NULL);
    if (s != want) {
        ut_info("got \"%s\"", battery_status_text(s));
    }
}

/* Rejection of one field changed from the vehicle's pack. */
#define REJECT(change, status)                \
    do {                                      \
        q = battery_params_uuv;               \
        change;                               \
        expect_rejected(&q, 0.5, status);     \
    } while (0)

static void test_params(void) {
    UT_TEST("parameters: each out-of-range field is rejected with its status and leaves the "
            "instance unchanged; the vehicle's pack is accepted");
    static battery_params q;
    volatile double zero = 0.0;
    const double nan = zero / zero;
    const double inf = 1.0 / zero;
    battery b;
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 1.0), BATTERY_OK);
    UT_EQ_INT(battery_init(NULL, &battery_params_uuv, 0.5), BATTERY_ERR_NULL);
    expect_rejected(NULL, 0.5, BATTERY_ERR_NULL);
    expect_rejected(&battery_params_uuv, -0.01, BATTERY_ERR_SOC);
    expect_rejected(&battery_params_uuv, 1.01, BATTERY_ERR_SOC);
    expect_rejected(&battery_params_uuv, nan, BATTERY_ERR_SOC);
    REJECT(q.cell.n_points = 1u, BATTERY_ERR_TABLE);
    REJECT(q.cell.n_points = 17u, BATTERY_ERR_TABLE);
    REJECT(q.cell.soc[0] = 0.05, BATTERY_ERR_TABLE);
    REJECT(q.cell.soc[6] = 0.99, BATTERY_ERR_TABLE);
    REJECT(q.cell.soc[3] = 0.2, BATTERY_ERR_TABLE);
    REJECT(q.cell.ocv_v[4] = 3.7, BATTERY_ERR_TABLE);
    REJECT(q.cell.r0_ohm[2] = 0.0, BATTERY_ERR_CELL);
    REJECT(q.cell.r1_ohm[5] = -1e-3, BATTERY_ERR_CELL);
    REJECT(q.cell.c1_f[1] = nan, BATTERY_ERR_CELL);
    REJECT(q.cell.ocv_v[6] = inf, BATTERY_ERR_CELL);
    REJECT(q.capacity_ah = 0.0, BATTERY_ERR_CELL);
    REJECT(q.n_series = 0u, BATTERY_ERR_PACK);
    REJECT(q.n_series = 1001u, BATTERY_ERR_PACK);
    REJECT(q.n_parallel = 0u, BATTERY_ERR_PACK);
    REJECT(q.v_cutoff_cell_v = 4.3, BATTERY_ERR_LIMITS);
    REJECT(q.v_cutoff_cell_v = -3.0, BATTERY_ERR_LIMITS);
    REJECT(q.v_max_cell_v = 2.9, BATTERY_ERR_LIMITS);
    REJECT(q.frame_s = 0.0, BATTERY_ERR_FRAME);
    REJECT(q.frame_s = 11.0, BATTERY_ERR_FRAME);
    REJECT(q.frame_s = nan, BATTERY_ERR_FRAME);
    UT_EQ_INT(battery_reset(&b, 2.0), BATTERY_ERR_SOC);
    UT_EQ_INT(battery_reset(&b, 0.25), BATTERY_OK);
    UT_CHECK(b.soc == 0.25 && !b.cut_off);
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.0), BATTERY_OK);
    UT_CHECK(b.cut_off && b.cutoff_cause == BATTERY_CUTOFF_EMPTY && b.t_cutoff_s == 0.0);
    /* A measurement that is not finite is counted and taken as no current. */
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.5), BATTERY_OK);
    battery_step_f64(&b, &(battery_frame_meas){nan, 0.0, 0.0});
    UT_CHECK(b.bad_input_frames == 1u && b.soc == 0.5);
}

static void test_edges(void) {
    static battery_params q;
    volatile double zero = 0.0;
    const double nan = zero / zero;
    const double inf = 1.0 / zero;
    battery b;

    UT_TEST("parameters: more than 1000 cells in parallel and a charge limit that is not "
            "finite are refused; reset needs an initialised battery and an SOC in [0, 1]");
    REJECT(q.n_parallel = 1001u, BATTERY_ERR_PACK);
    REJECT(q.v_max_cell_v = inf, BATTERY_ERR_LIMITS);
    UT_EQ_INT(battery_reset(NULL, 0.5), BATTERY_ERR_NULL);
    b = (battery){0};
    UT_EQ_INT(battery_reset(&b, 0.5), BATTERY_ERR_NULL);
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.5), BATTERY_OK);
    UT_EQ_INT(battery_reset(&b, -0.1), BATTERY_ERR_SOC);

    UT_TEST("measurement: a mean square or power that is not finite counts as bad input and "
            "moves no charge; a mean square below the squared mean is raised to it, so the "
            "R0 heat is (ns / np) R0 i^2 h");
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.5), BATTERY_OK);
    battery_step_f64(&b, &(battery_frame_meas){-10.0, nan, -4800.0});
    battery_step_f64(&b, &(battery_frame_meas){-10.0, 100.0, inf});
    UT_CHECK(b.bad_input_frames == 2u && b.soc == 0.5 && b.q_out_c == 0.0);
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.5), BATTERY_OK);
    const double r0 = b.r0_cell_ohm;
    battery_step_f64(&b, &(battery_frame_meas){-20.0, 0.0, -9600.0});
    UT_NEAR(b.e_loss_r0_j, 144.0 / 2.0 * r0 * 400.0 * H_FRAME, 1e-12);

    UT_TEST("overvoltage: 20 A into a full pack ends the frame above the 4.2 V charge limit "
            "(4.1928 V + 8.5 mOhm x 10 A per cell) and is counted, without a cut-off");
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 1.0), BATTERY_OK);
    step_with_current(&b, 20.0);
    UT_EQ_INT(b.overvoltage_frames, 1);
    UT_CHECK(b.v_cell_end_v > 4.2 && b.v_cell_end_v < 4.1928 + 0.085 + 0.01);
    UT_CHECK(!b.cut_off);

    UT_TEST("power beyond the largest e^2 / (4 r) gives the current of that largest power, "
            "-e / (2 r); a power that is not a number gives 0 A; a battery that is cut off "
            "drives no voltage (0 V)");
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.5), BATTERY_OK);
    const double e = b.e_eff_v;
    const double r = b.r_eff_ohm;
    const double i_max = battery_current_for_power_f64(&b, 1e9);
    UT_NEAR(i_max, -e / (2.0 * r), 1e-12 * e / r);
    UT_NEAR(-battery_voltage_f64(&b, i_max) * i_max, e * e / (4.0 * r), 1e-9 * e * e / r);
    UT_CHECK(battery_current_for_power_f64(&b, nan) == 0.0);
    UT_EQ_INT(battery_init(&b, &battery_params_uuv, 0.0), BATTERY_OK);
    UT_CHECK(b.cut_off && battery_voltage_f64(&b, -10.0) == 0.0);

    UT_TEST("status texts: every status has its own non-empty text, and so has an unknown "
            "value");
    const char *texts[9];
    for (int k = 0; k < 8; k++) {
        texts[k] = battery_status_text((battery_status)k);
    }
    texts[8] = battery_status_text((battery_status)99);
    bool ok = true;
    for (int k = 0; k < 9; k++) {
        ok = ok && texts[k] != NULL && texts[k][0] != '\0';
        for (int j = 0; j < k; j++) {
            ok = ok && !ut_text_equal(texts[j], texts[k]);
        }
    }
    UT_CHECK(ok);
}

static void test_pack_window(void) {
    UT_TEST("pack (144s2p): the bus stays above the inverter's 410 V at 11 kW down to empty, "
            "and the energy gives more than 4 h of cruise at 3.5 kW");
    const battery_params *p = &battery_params_uuv;
    battery b;
    UT_EQ_INT(battery_init(&b, p, 1e-6), BATTERY_OK);
    const double i_full = battery_current_for_power_f64(&b, 11000.0);
    const double v_empty = battery_voltage_f64(&b, i_full);
    UT_CHECK(v_empty > 410.0);
    UT_NEAR(-v_empty * i_full, 11000.0, 1e-6);
    UT_EQ_INT(battery_init(&b, p, 1.0), BATTERY_OK);
    const double v_full = battery_voltage_f64(&b, 0.0);
    UT_CHECK(v_full < 605.0);
    /* Stored energy: the integral of the pack OCV over the charge, exact for the linear table. */
    const battery_cell_table *t = &p->cell;
    double wh = 0.0;
    for (uint32_t k = 0u; k + 1u < t->n_points; k++) {
        wh += 0.5 * (t->ocv_v[k] + t->ocv_v[k + 1u]) * (t->soc[k + 1u] - t->soc[k]);
    }
    wh *= (double)p->n_series * (double)p->n_parallel * p->capacity_ah;
    UT_CHECK(wh / 3500.0 > 4.0);
    ut_info("open circuit %.1f V full; %.1f V at 11 kW and SOC 0 (%.1f A) before the RC branch "
            "charges; energy %.2f kWh, %.2f h at 3.5 kW", v_full, v_empty, -i_full, wh / 1e3,
            wh / 3500.0);
}

void suite_battery(void) {
    test_ocv_curve();
    test_companion_thevenin();
    test_companion_frame_mean();
    test_charge_counting();
    test_energy();
    test_rc_relaxation();
    test_cutoff_empty();
    test_cutoff_voltage();
    test_params();
    test_edges();
    test_pack_window();
}

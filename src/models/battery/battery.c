/*
 * The battery model (see battery.h for the equations and the conventions,
 * docs/battery.md for the derivation of the frame-average companion).
 *
 * Over one slow frame of length h the state of charge and the RC parameters
 * are frozen at their frame-start values. The polarisation branch is then a
 * linear first-order system driven by the frame-mean current, whose exact
 * solution is
 *
 *   v1(t) = a + (v1(0) - a) exp(-t / tau),   a = R1 * i_cell,  tau = R1 * C1
 *
 * and whose mean over the frame is k * v1(0) + (1 - k) * a with
 * k = (1 - exp(-h / tau)) * tau / h. The companion exported to the DC bus is
 * that mean, so a constant current over the frame gives exactly the mean
 * terminal voltage of the frozen-parameter circuit.
 */
#include "models/battery/battery.h"

#include <stddef.h>

#include "math/umath.h"

#define BATTERY_PACK_MAX 1000u
#define BATTERY_FRAME_MAX_S 10.0
#define BATTERY_SECONDS_PER_HOUR 3600.0

/* A position in the state-of-charge table: segment k and the fraction f in it. */
typedef struct {
    uint32_t k;
    double f;
} battery_pos;

static bool battery_is_finite(double x) { return math_isfinite_f64(x); }

static bool battery_is_positive(double x) { return battery_is_finite(x) && (x > 0.0); }

/*
 * Locates soc in the breakpoints, clamped to the table ends. A breakpoint
 * lands at the start of its segment with f = 0, so the tables are returned
 * exactly there; a NaN lands at the first breakpoint.
 */
static battery_pos battery_locate(const battery_cell_table *t, double soc) {
    battery_pos pos = {0u, 0.0};
    const uint32_t last = t->n_points - 1u;
    if (!(soc > t->soc[0])) {
        return pos;
    }
    if (soc >= t->soc[last]) {
        pos.k = last;
        return pos;
    }
    while ((pos.k + 1u < last) && (soc >= t->soc[pos.k + 1u])) {
        pos.k++;
    }
    pos.f = (soc - t->soc[pos.k]) / (t->soc[pos.k + 1u] - t->soc[pos.k]);
    return pos;
}

/* Linear interpolation written as y0 + f (y1 - y0), which is monotonic in f. */
static double battery_lerp(const double *y, battery_pos pos) {
    if (pos.f == 0.0) {
        return y[pos.k];
    }
    return y[pos.k] + pos.f * (y[pos.k + 1u] - y[pos.k]);
}

static battery_status battery_check_table(const battery_cell_table *t) {
    if ((t->n_points < 2u) || (t->n_points > BATTERY_TABLE_MAX)) {
        return BATTERY_ERR_TABLE;
    }
    const uint32_t last = t->n_points - 1u;
    if ((t->soc[0] != 0.0) || (t->soc[last] != 1.0)) {
        return BATTERY_ERR_TABLE;
    }
    for (uint32_t k = 0u; k < t->n_points; k++) {
        if (!battery_is_positive(t->ocv_v[k]) || !battery_is_positive(t->r0_ohm[k]) ||
            !battery_is_positive(t->r1_ohm[k]) || !battery_is_positive(t->c1_f[k])) {
            return BATTERY_ERR_CELL;
        }
        if ((k > 0u) && (!(t->soc[k] > t->soc[k - 1u]) || (t->ocv_v[k] < t->ocv_v[k - 1u]))) {
            return BATTERY_ERR_TABLE;
        }
    }
    return BATTERY_OK;
}

static battery_status battery_check_params(const battery_params *p) {
    const battery_status s = battery_check_table(&p->cell);
    if (s != BATTERY_OK) {
        return s;
    }
    if (!battery_is_positive(p->capacity_ah)) {
        return BATTERY_ERR_CELL;
    }
    if ((p->n_series < 1u) || (p->n_series > BATTERY_PACK_MAX) || (p->n_parallel < 1u) ||
        (p->n_parallel > BATTERY_PACK_MAX)) {
        return BATTERY_ERR_PACK;
    }
    const double ocv_full = p->cell.ocv_v[p->cell.n_points - 1u];
    if (!battery_is_positive(p->v_cutoff_cell_v) || !(p->v_cutoff_cell_v < ocv_full) ||
        !battery_is_finite(p->v_max_cell_v) || !(p->v_max_cell_v > p->v_cutoff_cell_v)) {
        return BATTERY_ERR_LIMITS;
    }
    if (!battery_is_positive(p->frame_s) || (p->frame_s > BATTERY_FRAME_MAX_S)) {
        return BATTERY_ERR_FRAME;
    }
    return BATTERY_OK;
}

/*
 * Builds the frame-average relation and the companion for the frame that
 * starts now, from the present state of charge and v1. Also used once cut
 * off, where the RC terms still drive the relaxation of v1.
 */
static void battery_prepare(battery *b) {
    const battery_params *p = b->p;
    const battery_pos pos = battery_locate(&p->cell, b->soc);
    const double r1 = battery_lerp(p->cell.r1_ohm, pos);
    const double ns = (double)p->n_series;
    b->ocv_cell_v = battery_lerp(p->cell.ocv_v, pos);
    b->r0_cell_ohm = battery_lerp(p->cell.r0_ohm, pos);
    b->r1_cell_ohm = r1;
    b->tau_s = r1 * battery_lerp(p->cell.c1_f, pos);
    const double x = p->frame_s / b->tau_s;
    b->alpha = math_exp_f64(-x);
    b->k_mean = (1.0 - b->alpha) / x;
    b->e_eff_v = ns * (b->ocv_cell_v + b->k_mean * b->v1_cell_v);
    b->r_eff_ohm = ns / (double)p->n_parallel * (b->r0_cell_ohm + r1 * (1.0 - b->k_mean));
    if (b->cut_off) {
        b->companion.g_s = 0.0;
        b->companion.b_a = 0.0;
    } else {
        b->companion.g_s = 1.0 / b->r_eff_ohm;
        b->companion.b_a = b->e_eff_v / b->r_eff_ohm;
    }
}

static void battery_trip(battery *b, battery_cutoff_cause cause) {
    b->cut_off = true;
    b->cutoff_cause = cause;
    b->t_cutoff_s = battery_time_f64(b);
    b->soc_cutoff = b->soc;
}

/* Cut-off check on the state at the end of a frame, with the loaded voltage. */
static void battery_check_cutoff(battery *b) {
    if (b->cut_off) {
        return;
    }
    if (!(b->soc > 0.0)) {
        battery_trip(b, BATTERY_CUTOFF_EMPTY);
    } else if (!(b->v_cell_end_v > b->p->v_cutoff_cell_v)) {
        battery_trip(b, BATTERY_CUTOFF_VOLTAGE);
    }
}

battery_status battery_reset(battery *b, double soc0) {
    if ((b == NULL) || (b->p == NULL)) {
        return BATTERY_ERR_NULL;
    }
    if (!(soc0 >= 0.0) || !(soc0 <= 1.0)) {
        return BATTERY_ERR_SOC;
    }
    const battery_params *p = b->p;
    *b = (battery){0};
    b->p = p;
    b->soc = soc0;
    b->v_cell_end_v = battery_ocv_cell_f64(p, soc0);
    battery_check_cutoff(b);
    battery_prepare(b);
    return BATTERY_OK;
}

battery_status battery_init(battery *b, const battery_params *p, double soc0) {
    if ((b == NULL) || (p == NULL)) {
        return BATTERY_ERR_NULL;
    }
    const battery_status s = battery_check_params(p);
    if (s != BATTERY_OK) {
        return s;
    }
    if (!(soc0 >= 0.0) || !(soc0 <= 1.0)) {
        return BATTERY_ERR_SOC;
    }
    b->p = p;
    return battery_reset(b, soc0);
}

battery_companion battery_companion_f64(const battery *b) { return b->companion; }

/*
 * Heat in the cell's R1 over one frame: the integral of v1(t)^2 / R1 for the
 * exact v1(t) = a + d exp(-t / tau), d = v1(0) - a.
 */
static double battery_r1_heat_cell_j(const battery *b, double a, double d) {
    const double h = b->p->frame_s;
    const double tau = b->tau_s;
    const double al = b->alpha;
    const double integral =
        a * a * h + 2.0 * a * d * tau * (1.0 - al) + 0.5 * d * d * tau * (1.0 - al * al);
    return integral / b->r1_cell_ohm;
}

void battery_step_f64(battery *b, const battery_frame_meas *m) {
    const battery_params *p = b->p;
    const double h = p->frame_s;
    const double ns = (double)p->n_series;
    const double np = (double)p->n_parallel;
    double i = m->i_avg_a;
    double i_sq = m->i_sq_avg_a2;
    double pw = m->p_avg_w;
    if (!battery_is_finite(i) || !battery_is_finite(i_sq) || !battery_is_finite(pw)) {
        b->bad_input_frames++;
        i = 0.0;
        i_sq = 0.0;
        pw = 0.0;
    }
    if (b->cut_off) {
        i = 0.0;
        i_sq = 0.0;
        pw = 0.0;
    }
    if (i_sq < i * i) {
        i_sq = i * i;
    }
    const double i_cell = i / np;
    const double a = b->r1_cell_ohm * i_cell;
    const double d = b->v1_cell_v - a;
    const double soc_old = b->soc;
    const double ocv_old = b->ocv_cell_v;
    b->e_loss_r1_j += ns * np * battery_r1_heat_cell_j(b, a, d);
    b->e_loss_r0_j += ns / np * b->r0_cell_ohm * i_sq * h;
    b->v1_cell_v = a + d * b->alpha;
    b->soc = soc_old + i_cell * h / (p->capacity_ah * BATTERY_SECONDS_PER_HOUR);
    b->q_out_c -= i * h;
    b->e_out_j -= pw * h;
    /* The source's energy uses the mean of the OCV at both ends: exact inside a segment. */
    const battery_pos pos = battery_locate(&p->cell, b->soc);
    const double ocv_new = battery_lerp(p->cell.ocv_v, pos);
    b->e_source_j -= ns * 0.5 * (ocv_old + ocv_new) * i * h;
    b->frames++;
    b->i_last_a = i;
    b->v_cell_end_v = ocv_new + b->v1_cell_v + battery_lerp(p->cell.r0_ohm, pos) * i_cell;
    if (b->v_cell_end_v > p->v_max_cell_v) {
        b->overvoltage_frames++;
    }
    battery_check_cutoff(b);
    battery_prepare(b);
}

double battery_voltage_f64(const battery *b, double i_a) {
    if (b->cut_off) {
        return 0.0;
    }
    return b->e_eff_v + b->r_eff_ohm * i_a;
}

/*
 * Solves r i^2 + e i + p = 0 (the delivered power -v i equal to p) for the
 * root of smaller magnitude, written as -2 p / (e + sqrt(e^2 - 4 r p)) so
 * that a small power loses no digits to cancellation.
 */
double battery_current_for_power_f64(const battery *b, double p_out_w) {
    const double e = b->e_eff_v;
    const double r = b->r_eff_ohm;
    if (b->cut_off || !(e > 0.0) || !battery_is_finite(p_out_w)) {
        return 0.0;
    }
    const double disc = e * e - 4.0 * r * p_out_w;
    if (!(disc > 0.0)) {
        return -e / (2.0 * r);
    }
    return -2.0 * p_out_w / (e + math_sqrt_f64(disc));
}

double battery_ocv_cell_f64(const battery_params *p, double soc) {
    return battery_lerp(p->cell.ocv_v, battery_locate(&p->cell, soc));
}

double battery_ocv_pack_f64(const battery *b) {
    return (double)b->p->n_series * battery_ocv_cell_f64(b->p, b->soc);
}

double battery_capacity_pack_f64(const battery_params *p) {
    return (double)p->n_parallel * p->capacity_ah * BATTERY_SECONDS_PER_HOUR;
}

double battery_time_f64(const battery *b) { return (double)b->frames * b->p->frame_s; }

const char *battery_status_text(battery_status s) {
    switch (s) {
    case BATTERY_OK:
        return "ok";
    case BATTERY_ERR_NULL:
        return "a pointer argument is NULL";
    case BATTERY_ERR_TABLE:
        return "cell table: breakpoint count, ends (0 and 1), order, or falling OCV";
    case BATTERY_ERR_CELL:
        return "cell: OCV, R0, R1, C1 and capacity must be positive and finite";
    case BATTERY_ERR_PACK:
        return "pack: series and parallel counts must be in 1..1000";
    case BATTERY_ERR_LIMITS:
        return "limits: need 0 < cut-off < full OCV and charge limit > cut-off";
    case BATTERY_ERR_FRAME:
        return "frame time must be in (0, 10] s";
    case BATTERY_ERR_SOC:
        return "initial state of charge must be in [0, 1]";
    default:
        return "unknown battery status";
    }
}

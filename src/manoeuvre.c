/*
 * Manoeuvre metrics (see manoeuvre.h).
 */
#include "manoeuvre.h"

#include "math/umath.h"

#define RAD_TO_DEG (180.0 / MATH_PI_F64)

static double abs_d(double v) { return v < 0.0 ? -v : v; }

void manoeuvre_init(manoeuvre *m, bool zigzag, double threshold_rad, double zigzag_start_s) {
    *m = (manoeuvre){0};
    m->r.zigzag = zigzag;
    m->zz_threshold_rad = threshold_rad;
    m->zz_start_s = zigzag_start_s;
}

/* Position relative to the execute point, along and across the approach heading. */
static void along_across(const manoeuvre *m, double x, double y, double *along, double *across) {
    double dx = x - m->x0;
    double dy = y - m->y0;
    *along = dx * m->cos0 + dy * m->sin0;
    *across = -dx * m->sin0 + dy * m->cos0;
}

static void turning_update(manoeuvre *m, double t, double x, double y, double psi,
                           double speed, double yaw_rate, double rudder_cmd) {
    if (m->r.turn_ended) {
        return;
    }
    if (m->r.turn_executed && rudder_cmd != m->rudder0) {
        /* The rudder left its execute angle: the turn is over, its figures final. */
        m->r.turn_ended = true;
        m->r.turn_end_s = t;
        return;
    }
    if (!m->r.turn_executed) {
        if (rudder_cmd == 0.0) {
            return;
        }
        m->r.turn_executed = true;
        m->rudder0 = rudder_cmd;
        m->t0 = t;
        m->x0 = x;
        m->y0 = y;
        m->psi0 = psi;
        m->cos0 = math_cos_f64(psi);
        m->sin0 = math_sin_f64(psi);
        m->speed0 = speed;
        m->have_prev = false;
    }
    double dpsi = abs_d(psi - m->psi0);
    if (m->have_prev) {
        /* Interpolate the crossing of 90 and 180 degrees between frames. */
        static const double marks[2] = {MATH_PI_F64 / 2.0, MATH_PI_F64};
        for (int k = 0; k < 2; k++) {
            bool done = (k == 0) ? m->r.has_advance : m->r.has_tactical;
            if (done || !(m->prev_dpsi < marks[k] && dpsi >= marks[k])) {
                continue;
            }
            double f = (marks[k] - m->prev_dpsi) / (dpsi - m->prev_dpsi);
            double xi = m->prev_x + f * (x - m->prev_x);
            double yi = m->prev_y + f * (y - m->prev_y);
            double along = 0.0;
            double across = 0.0;
            along_across(m, xi, yi, &along, &across);
            if (k == 0) {
                m->r.has_advance = true;
                m->r.advance_m = along;
                m->r.transfer_m = abs_d(across);
            } else {
                m->r.has_tactical = true;
                m->r.tactical_diameter_m = abs_d(across);
            }
        }
    }
    /* The floors keep both quotients finite (a yaw rate of 1e-6 rad/s is no turn). */
    if (dpsi >= 2.0 * MATH_PI_F64 && abs_d(yaw_rate) > 1e-6) {
        m->r.has_steady = true;
        m->r.steady_diameter_m = 2.0 * speed / abs_d(yaw_rate);
        m->r.speed_loss_pct = (m->speed0 > 1e-6) ? 100.0 * (1.0 - speed / m->speed0) : 0.0;
    }
    m->prev_x = x;
    m->prev_y = y;
    m->prev_dpsi = dpsi;
    m->have_prev = true;
}

static void zigzag_update(manoeuvre *m, double t, double psi, double rudder_cmd) {
    if (t < m->zz_start_s - 1e-9) {
        return;
    }
    if (!m->zz_started) {
        /* The heading when the zig-zag starts is its reference, as for the rule. */
        m->zz_started = true;
        m->zz_psi0 = psi;
    }
    double rel = psi - m->zz_psi0;
    bool reversed = (m->last_rudder != 0.0) && (rudder_cmd != 0.0) &&
                    ((m->last_rudder > 0.0) != (rudder_cmd > 0.0));
    if (reversed) {
        /* The swing before this reversal ends here; its overshoot is measured
         * when the heading turns back, below. */
        m->reversal_t[m->n_reversals % 3u] = t;
        m->n_reversals++;
        if (m->n_reversals >= 3u) {
            m->period_sum += t - m->reversal_t[(m->n_reversals - 3u) % 3u];
            m->period_count++;
            m->r.period_s = m->period_sum / (double)m->period_count;
        }
        m->swing = (rel > 0.0) ? 1 : -1;
        m->extreme_rad = rel;
    } else if (m->swing != 0) {
        bool further = (m->swing > 0) ? (rel > m->extreme_rad) : (rel < m->extreme_rad);
        if (further) {
            m->extreme_rad = rel;
        } else {
            /* The heading has turned back: the overshoot of this swing is final. */
            if (m->r.n_overshoots < MANOEUVRE_MAX_OVERSHOOTS) {
                m->r.overshoot_deg[m->r.n_overshoots++] =
                    (abs_d(m->extreme_rad) - m->zz_threshold_rad) * RAD_TO_DEG;
            }
            m->swing = 0;
        }
    }
    if (rudder_cmd != 0.0) {
        m->last_rudder = rudder_cmd;
    }
}

void manoeuvre_update(manoeuvre *m, double t, double x, double y, double psi, double speed,
                      double yaw_rate, double rudder_cmd) {
    if (m->r.zigzag) {
        zigzag_update(m, t, psi, rudder_cmd);
        return;
    }
    turning_update(m, t, x, y, psi, speed, yaw_rate, rudder_cmd);
}

const manoeuvre_result *manoeuvre_result_get(const manoeuvre *m) { return &m->r; }

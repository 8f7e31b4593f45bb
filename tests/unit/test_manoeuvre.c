/*
 * The manoeuvre metrics (manoeuvre.h) on synthetic runs whose figures are
 * known by construction: a turning circle of radius R flown exactly (advance
 * and transfer R at 90 degrees, tactical diameter 2R at 180 degrees, steady
 * diameter 2 U / |r| = 2R), and a zig-zag whose heading swings are written
 * down frame by frame (the overshoots and the period are read off the list).
 */
#include <stddef.h>

#include "manoeuvre.h"
#include "math/umath.h"
#include "ut.h"

void suite_manoeuvre(void);

#define DEG (MATH_PI_F64 / 180.0)

static manoeuvre mv;

/*
 * Flies a circle of radius r_m at speed u (the speed reported is the speed
 * the frame passes, the positions those of the exact circle), turning to
 * starboard when dir > 0 and to port when dir < 0, from the point (x0, y0)
 * on heading psi_a, after three straight frames with the rudder at zero.
 * The heading changes by 0.02 rad per 0.5 s frame, so neither 90 nor 180
 * degrees falls on a frame and the crossings are interpolated. Runs
 * n_turn frames of the turn; the speed falls linearly from u0 to u1 after
 * the execute frame, and the execute frame reports u_exec. Frame nan_frame
 * of the turn (when not 0) reports its heading as NaN, a dropped sample.
 */
typedef struct {
    double r_m, u_exec, u0, u1, psi_a, x0, y0;
    int dir;
    unsigned n_turn, nan_frame;
} circle_run;

static void fly_circle(const circle_run *c) {
    const double dpsi = 0.02;
    const double dt = 0.5;
    double cs = math_cos_f64(c->psi_a);
    double sn = math_sin_f64(c->psi_a);
    manoeuvre_init(&mv, false, 0.0, 0.0);
    /* The approach: straight on psi_a, ending at (x0, y0). */
    for (int k = -3; k < 0; k++) {
        double s = (double)k * c->u0 * dt;
        manoeuvre_update(&mv, (double)(k + 3) * dt, c->x0 + s * cs, c->y0 + s * sn, c->psi_a,
                         c->u0, 0.0, 0.0);
    }
    double d = (c->dir > 0) ? 1.0 : -1.0;
    for (unsigned k = 0u; k <= c->n_turn; k++) {
        double phi = (double)k * dpsi;
        double psi = c->psi_a + d * phi;
        /* Along R sin(phi), across d R (1 - cos(phi)), rotated to North-East. */
        double along = c->r_m * math_sin_f64(phi);
        double across = d * c->r_m * (1.0 - math_cos_f64(phi));
        double x = c->x0 + along * cs - across * sn;
        double y = c->y0 + along * sn + across * cs;
        double frac = (double)k / (double)c->n_turn;
        double u = (k == 0u) ? c->u_exec : c->u0 + (c->u1 - c->u0) * frac;
        double r = d * u / c->r_m;
        if (k != 0u && k == c->nan_frame) {
            psi = math_nan_f64();
        }
        manoeuvre_update(&mv, (double)(k + 3u) * dt, x, y, psi, u, r, d * 0.35);
    }
}

static void test_turning_circle(void) {
    UT_TEST("turning circle, starboard, R = 50 m from (100, -20) on 40 deg: advance = transfer "
            "= R, tactical diameter 2R (chord interpolation, within R dpsi^2 / 8 = 2.5 mm), "
            "steady diameter 2 U / r = 2R, speed loss 1 - 1.6 / 2 = 20 %");
    circle_run c = {50.0, 2.0, 2.0, 1.6, 40.0 * DEG, 100.0, -20.0, 1, 330u, 0u};
    fly_circle(&c);
    const manoeuvre_result *r = manoeuvre_result_get(&mv);
    UT_CHECK(r->turn_executed && r->has_advance && r->has_tactical && r->has_steady);
    UT_CHECK(!r->zigzag);
    UT_NEAR(r->advance_m, 50.0, 5e-3);
    UT_NEAR(r->transfer_m, 50.0, 5e-3);
    UT_NEAR(r->tactical_diameter_m, 100.0, 5e-3);
    UT_NEAR(r->steady_diameter_m, 100.0, 1e-9);
    UT_NEAR(r->speed_loss_pct, 20.0, 1e-9);
    ut_info("advance %.4f m, transfer %.4f m, tactical %.4f m", r->advance_m, r->transfer_m,
            r->tactical_diameter_m);

    UT_TEST("turning circle, port, the mirror image: the same positive figures; an execute "
            "frame at zero speed gives no speed loss (no division by zero)");
    circle_run p = {50.0, 0.0, 2.0, 1.6, -130.0 * DEG, -5.0, 7.0, -1, 330u, 0u};
    fly_circle(&p);
    r = manoeuvre_result_get(&mv);
    UT_CHECK(r->has_advance && r->has_tactical && r->has_steady);
    UT_NEAR(r->advance_m, 50.0, 5e-3);
    UT_NEAR(r->transfer_m, 50.0, 5e-3);
    UT_NEAR(r->tactical_diameter_m, 100.0, 5e-3);
    UT_NEAR(r->steady_diameter_m, 100.0, 1e-9);
    UT_NEAR(r->speed_loss_pct, 0.0, 0.0);

    UT_TEST("turning circle: a frame with zero yaw rate after 360 deg leaves the steady "
            "diameter as it was (2 U / |r| needs r != 0)");
    manoeuvre_update(&mv, 1000.0, 0.0, 0.0, -130.0 * DEG - 7.0, 1.0, 0.0, -0.35);
    r = manoeuvre_result_get(&mv);
    UT_NEAR(r->steady_diameter_m, 100.0, 1e-9);

    UT_TEST("turning circle: a run that stops short of 90 deg has only the execute flag");
    circle_run s = {50.0, 2.0, 2.0, 2.0, 0.0, 0.0, 0.0, 1, 60u, 0u};
    fly_circle(&s);
    r = manoeuvre_result_get(&mv);
    UT_CHECK(r->turn_executed && !r->has_advance && !r->has_tactical && !r->has_steady);
    UT_NEAR(r->advance_m, 0.0, 0.0);

    UT_TEST("turning circle: a NaN heading in one frame at 45 deg (a dropped sample) leaves "
            "every figure as it is without it");
    circle_run d = c;
    d.nan_frame = 40u;
    fly_circle(&d);
    r = manoeuvre_result_get(&mv);
    UT_CHECK(r->has_advance && r->has_tactical && r->has_steady);
    UT_NEAR(r->advance_m, 50.0, 5e-3);
    UT_NEAR(r->transfer_m, 50.0, 5e-3);
    UT_NEAR(r->tactical_diameter_m, 100.0, 5e-3);
    UT_NEAR(r->steady_diameter_m, 100.0, 1e-9);

    UT_TEST("turning circle: with the rudder at zero nothing is executed or measured");
    manoeuvre_init(&mv, false, 0.0, 0.0);
    for (int k = 0; k < 10; k++) {
        manoeuvre_update(&mv, (double)k, (double)k, 0.0, 4.0 * (double)k, 1.0, 0.5, 0.0);
    }
    r = manoeuvre_result_get(&mv);
    UT_CHECK(!r->turn_executed && !r->has_advance && !r->has_steady);
}

/*
 * A zig-zag at threshold 10 deg starting at t = 5 s: before then the
 * heading wanders (the reference is the heading at 5 s, 0.3 rad). Swing k
 * (sign s = +1 for even k, -1 for odd) takes four 1 s frames of the heading
 * relative to the reference: s 11 deg with the rudder reversed to -s 20
 * deg, s (10 + o_k), s (10 + o_k - 1) and 0, with o_k = k + 1 deg, so the
 * overshoot of swing k is o_k (for k = 0 the extreme is the reversal frame
 * itself, 11 deg). One frame of swing 2 has the rudder at zero, which does
 * not count as a reversal. Reversals come every 4 s, so those in one
 * direction come every 8 s.
 */
static void test_zigzag(void) {
    UT_TEST("zig-zag 10/20: overshoots 1, 2, ... 8 deg (the first 8 of 12 kept), period 8 s, "
            "reference heading taken at the start time, zero rudder frames ignored");
    const double psi0 = 0.3;
    manoeuvre_init(&mv, true, 10.0 * DEG, 5.0);
    for (int k = 0; k < 5; k++) {
        manoeuvre_update(&mv, (double)k, 0.0, 0.0, psi0 - 0.2 * (double)k, 1.0, 0.0, 0.35);
    }
    double t = 5.0;
    manoeuvre_update(&mv, t, 0.0, 0.0, psi0, 1.0, 0.0, 20.0 * DEG);
    for (int k = 0; k < 12; k++) {
        double s = (k % 2 == 0) ? 1.0 : -1.0;
        double o = (double)(k + 1);
        double rel[4] = {11.0, 10.0 + o, 10.0 + o - 1.0, 0.0};
        for (int f = 0; f < 4; f++) {
            double rudder = -s * 20.0 * DEG;
            if (k == 2 && f == 3) {
                rudder = 0.0;
            }
            t += 1.0;
            manoeuvre_update(&mv, t, 0.0, 0.0, psi0 + s * rel[f] * DEG, 1.0, 0.0, rudder);
        }
    }
    const manoeuvre_result *r = manoeuvre_result_get(&mv);
    UT_CHECK(r->zigzag && !r->turn_executed);
    UT_EQ_INT(r->n_overshoots, MANOEUVRE_MAX_OVERSHOOTS);
    for (size_t i = 0u; i < r->n_overshoots; i++) {
        if (!UT_NEAR(r->overshoot_deg[i], (double)(i + 1u), 1e-9)) {
            ut_info("overshoot %u", (unsigned)i);
        }
    }
    UT_NEAR(r->period_s, 8.0, 1e-12);

    UT_TEST("zig-zag: before two reversals in one direction the period is 0, and a run "
            "that never starts measures nothing");
    manoeuvre_init(&mv, true, 10.0 * DEG, 5.0);
    manoeuvre_update(&mv, 5.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.35);
    manoeuvre_update(&mv, 6.0, 0.0, 0.0, 11.0 * DEG, 1.0, 0.0, -0.35);
    manoeuvre_update(&mv, 7.0, 0.0, 0.0, -11.0 * DEG, 1.0, 0.0, 0.35);
    r = manoeuvre_result_get(&mv);
    UT_NEAR(r->period_s, 0.0, 0.0);
    UT_EQ_INT(r->n_overshoots, 0);
    manoeuvre_init(&mv, true, 10.0 * DEG, 50.0);
    manoeuvre_update(&mv, 6.0, 0.0, 0.0, 11.0 * DEG, 1.0, 0.0, -0.35);
    manoeuvre_update(&mv, 7.0, 0.0, 0.0, -11.0 * DEG, 1.0, 0.0, 0.35);
    r = manoeuvre_result_get(&mv);
    UT_EQ_INT(r->n_overshoots, 0);
    UT_NEAR(r->period_s, 0.0, 0.0);
}

void suite_manoeuvre(void) {
    test_turning_circle();
    test_zigzag();
}

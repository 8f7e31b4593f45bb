/*
 * Standard manoeuvre metrics, computed on line from the slow-frame states.
 *
 * Turning circle (ITTC terms), measured from the execute point, the first
 * frame at which the rudder command is non-zero:
 *   advance         distance along the approach heading when the heading
 *                   has changed by 90 degrees;
 *   transfer        distance across the approach heading at 90 degrees;
 *   tactical diam.  distance across the approach heading at 180 degrees;
 *   steady diameter 2 U / |r| at the end of the turn, once the heading has
 *                   changed by 360 degrees or more;
 *   speed loss      1 - U_end / U_execute.
 * The turn ends when the rudder command leaves its execute angle (or at the
 * end of the run); the figures stay those measured until then. Crossing
 * points are interpolated linearly between frames.
 *
 * Zig-zag: the overshoot angles (how far the heading goes beyond the
 * threshold after each rudder reversal) and the period (time between
 * reversals in the same direction, averaged).
 */
#ifndef UUV_MANOEUVRE_H
#define UUV_MANOEUVRE_H

#include <stdbool.h>
#include <stddef.h>

#define MANOEUVRE_MAX_OVERSHOOTS 8u

typedef struct {
    /* Turning circle; a flag says which figures the run reached. */
    bool turn_executed;
    bool turn_ended;       /* the rudder left its execute angle at turn_end_s */
    double turn_end_s;     /* [s] */
    bool has_advance;      /* heading changed by 90 deg */
    bool has_tactical;     /* heading changed by 180 deg */
    bool has_steady;       /* heading changed by 360 deg */
    double advance_m;
    double transfer_m;
    double tactical_diameter_m;
    double steady_diameter_m;
    double speed_loss_pct;
    /* Zig-zag. */
    bool zigzag;
    size_t n_overshoots;
    double overshoot_deg[MANOEUVRE_MAX_OVERSHOOTS];
    double period_s;       /* 0 until two reversals in one direction */
} manoeuvre_result;

typedef struct {
    manoeuvre_result r;
    /* Turning circle state. */
    double t0, x0, y0, psi0, speed0;
    double rudder0;       /* [rad] the rudder command at execute */
    double cos0, sin0;    /* approach heading, taken once at execute */
    double prev_x, prev_y, prev_dpsi;
    bool have_prev;
    /* Zig-zag state. */
    double zz_threshold_rad, zz_psi0, zz_start_s;
    bool zz_started;
    double last_rudder;
    int swing;            /* +1 heading increasing phase, -1 decreasing, 0 before first */
    double extreme_rad;   /* extreme of psi - psi0 in the current swing */
    double reversal_t[3]; /* the last reversal times */
    size_t n_reversals;
    double period_sum;
    size_t period_count;
} manoeuvre;

/*
 * zigzag: whether the run has a zig-zag (then threshold [rad] and its start
 * time [s] are used, and no turning circle is measured).
 */
void manoeuvre_init(manoeuvre *m, bool zigzag, double threshold_rad, double zigzag_start_s);

/*
 * Feeds one slow frame: time [s], North and East position [m], heading
 * [rad] (continuous, not wrapped), speed through the water [m/s], yaw rate
 * [rad/s] and the rudder command [rad] in force during the frame.
 */
void manoeuvre_update(manoeuvre *m, double t, double x, double y, double psi, double speed,
                      double yaw_rate, double rudder_cmd);

/* The figures so far. */
const manoeuvre_result *manoeuvre_result_get(const manoeuvre *m);

#endif /* UUV_MANOEUVRE_H */

/*
 * The drive's output phase-loss protection (see protection.h).
 */
#include "protection.h"

void protection_init(protection *p, double frame_s) {
    *p = (protection){0};
    p->frame_s = frame_s;
}

drive_trip protection_step(protection *p, const double i_phase_rms_a[3]) {
    for (int x = 0; x < 3; x++) {
        p->sq_a2s[x] += i_phase_rms_a[x] * i_phase_rms_a[x] * p->frame_s;
    }
    p->t_s += p->frame_s;
    if (p->t_s < PROTECTION_PHASE_LOSS_WINDOW_S * (1.0 - 1e-9)) {
        return DRIVE_TRIP_NONE;
    }
    double lo = p->sq_a2s[0];
    double hi = lo;
    for (int x = 1; x < 3; x++) {
        lo = (p->sq_a2s[x] < lo) ? p->sq_a2s[x] : lo;
        hi = (p->sq_a2s[x] > hi) ? p->sq_a2s[x] : hi;
    }
    /* On mean squares: the thresholds squared. */
    const double r = PROTECTION_PHASE_LOSS_RATIO;
    const double i_min = PROTECTION_PHASE_LOSS_MIN_A;
    bool lost = hi > i_min * i_min * p->t_s && lo < r * r * hi;
    p->windows = lost ? p->windows + 1u : 0u;
    p->sq_a2s[0] = p->sq_a2s[1] = p->sq_a2s[2] = 0.0;
    p->t_s = 0.0;
    return (p->windows >= 2u) ? DRIVE_TRIP_PHASE_LOSS : DRIVE_TRIP_NONE;
}

/*
 * The drive's output phase-loss protection, in the background on the slow
 * frames' measurements (drive_slow_meas.i_phase_rms_a). The drive's own
 * protections (the leg short's desaturation, the DC link's under-voltage)
 * act inside the drive segment, at its steps; this one needs windows of
 * several electrical periods, whatever the slow frame, so it sums the
 * frames' mean squares over windows of PROTECTION_PHASE_LOSS_WINDOW_S.
 *
 * A window shows a phase loss when one phase's rms current is below
 * PROTECTION_PHASE_LOSS_RATIO of the largest while that one carries more
 * than PROTECTION_PHASE_LOSS_MIN_A; two such windows in a row trip the
 * drive (DRIVE_TRIP_PHASE_LOSS, which the executive requests with
 * drive_trip_request(): the gates block at the next slow boundary). The
 * comparison is on mean squares, with the thresholds squared, so no
 * square root is taken.
 *
 * The no-load magnetising current is about 10 A rms; with a phase open the
 * healthy two carry 3 to 5 times that under load (docs/reliability.md).
 */
#ifndef UUV_PROTECTION_H
#define UUV_PROTECTION_H

#include <stdint.h>

#include "drive_segment.h"

#define PROTECTION_PHASE_LOSS_RATIO 0.1    /* [-] of the largest phase's rms current */
#define PROTECTION_PHASE_LOSS_MIN_A 10.0   /* [A] rms, the largest phase's least */
#define PROTECTION_PHASE_LOSS_WINDOW_S 0.1 /* [s] measuring window; two in a row trip */

typedef struct {
    double frame_s;     /* [s] one measurement per frame (the slow frame) */
    double sq_a2s[3];   /* [A^2 s] per phase, summed over the window so far */
    double t_s;         /* [s] the window so far */
    uint32_t windows;   /* windows in a row that showed a phase loss */
} protection;

/* A protection that has seen nothing, for measurements every frame_s [s]. */
void protection_init(protection *p, double frame_s);

/*
 * One frame's rms phase currents [A]. Returns DRIVE_TRIP_PHASE_LOSS at the
 * end of each window that is the second (or later) in a row to show a
 * phase loss, DRIVE_TRIP_NONE otherwise.
 */
drive_trip protection_step(protection *p, const double i_phase_rms_a[3]);

#endif /* UUV_PROTECTION_H */

/*
 * The fast steps of several runs in SIMD lanes (batch_lanes.h).
 */
#include "batch_lanes.h"

const unsigned batch_lanes = 1u;
const char batch_lanes_isa[] = "scalar";

bool batch_lane_ready(const drive_segment *d) { return d->plain && d->fast_now == NULL; }

void batch_fast_run(drive_segment *const *d, size_t count, uint32_t n, bool substep) {
    (void)substep;
    for (size_t i = 0; i < count; i++) {
        drive_fast_run(d[i], n);
    }
}

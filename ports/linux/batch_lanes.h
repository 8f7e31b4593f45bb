/*
 * The fast steps of several desk runs at once, in SIMD lanes (host only;
 * uuvsim batch, batch.c).
 *
 * batch_fast_run() takes the drives of up to any number of runs, each on
 * the real-time path (drive.rt_path, no port kernel) with the same modulator,
 * and steps each n times: the bits of drive_fast_run(d[i], n) for every i.
 * The drives' states are gathered into lanes (one run per lane, a vector
 * of BATCH_LANES lanes, the build's width), stepped together and scattered
 * back.
 *
 * Why a second copy of the step. The firmware's step (drive_fast_tick())
 * and the desk's runs of it (drive_fast_run()) work on one drive's
 * structures; a lane step works on vectors of the same quantities, which C
 * cannot express with the same functions. So batch_lanes.c holds the
 * real-time step (pwm_rt.h's modulator, power_stage_fast.h's stage, the
 * motor's fast companion and the frame sums) once more, written on lanes,
 * the same operations in the same order, with the same roundings: a step
 * in two places. tests/host/test_batch_lanes.c (a make test row, both
 * builds) pins it to drive_fast_run() bit for bit, over frames of running
 * drives of each modulator, and uuvsim batch's test
 * compares whole runs with their single runs (tests/host/test_batch.sh).
 * A change to the step must be made in both, or those tests fail.
 */
#ifndef UUV_BATCH_LANES_H
#define UUV_BATCH_LANES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "drive_segment.h"
#include "executive.h"

/* Runs per vector: chosen at build time from the target's vector width. */
extern const unsigned batch_lanes;

/* The lane path's name for reports: the vector width and the instruction set. */
extern const char batch_lanes_isa[];

/* True when drive_fast_run(d, n) takes the lane step's path (the real-time one, no kernel). */
bool batch_lane_ready(const drive_segment *d);

/*
 * For a run e just initialised (no step taken) that will step through
 * batch_step_all(): its modulator without frame plans (pwm_rt_frames(.., 0),
 * every step computed on its own, the plans' bits, pwm_rt.h). The lanes
 * form every step's duties themselves, so the motor task's plans would
 * only cost (plan_build(): 18 % of a batch's instructions); a run that
 * leaves the lanes (a fault, a trip) steps on as drive_fast_run() does
 * without plans. Exact leaps (leap_attach()) do the same already.
 */
void batch_lanes_attach(exec *e);

/*
 * n fast steps of each of the count drives d[i], each batch_lane_ready()
 * and with modulator substep (true) or sampled: drive_fast_run(d[i], n)'s
 * bits for every i.
 */
void batch_fast_run(drive_segment *const *d, size_t count, uint32_t n, bool substep);

/*
 * One pass of a batch: each of the count executives e[i] (running) through
 * exec_desk_run(e[i], most[i]), with the same results; the runs of steps
 * of those on the real-time path (and without a desk_run of their own) go
 * through batch_fast_run() together, grouped by their length and
 * modulator.
 */
void batch_step_all(exec *const *e, const uint32_t *most, size_t count);

/*
 * The lanes' form of pwm_rt_edge_duty() (its quotient as a truncated
 * double quotient) on one set of its arguments, for the test that pins the
 * two together (tests/host/test_batch_lanes.c).
 */
int32_t batch_lanes_edge_duty(int32_t e0, int32_t e1, uint32_t sh);

#endif /* UUV_BATCH_LANES_H */

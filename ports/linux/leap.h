/*
 * Exact leaps: the desk's runs of fast steps (exec_desk_run()) with each
 * stretch of steps between two switching events taken as one precomputed
 * map of the same discrete model (uuvsim --fast-path leap). Host only; the
 * firmware's step and the default desk path (--fast-path exact) are not
 * touched. Float build only: the fixed build's step (Q3.28 states, each
 * product sum rounded, integer clamps) has no tables here, so
 * leap_available() is false there and the command line refuses the option.
 *
 * What a leap is. On the real-time path (switching inverter without dead
 * time, sub-step modulator, held EMF and frame-mean coupling, no fault or
 * trip, no energy audit) a fast step with no leg edge holds the legs'
 * states over the whole step, and with the motor frame's EMF and the slow
 * frame's battery companion held, the step is affine in the state
 *   z = (i_L, v_C, i_d, j_sh of phases a and b, v_dc, the two companion
 *        currents, the EMFs e_a, e_b, the battery's source e_v)
 * (the inputs ride along as constant entries). k such steps are z_k =
 * P_k z with P_k = M_s^k for the switch state s; the frame sums of the
 * capacitor and DC-link voltages over them are C_k z, C_k = sum_{j<=k} of
 * the rows of P_j. The tables (P_k, C_k for k <= LEAP_K_MAX, per switch
 * state) are built in double from the step's own float coefficients, on
 * first use, and again whenever the DC-link coefficients or the
 * companion's gain change (the battery companion's conductance: at slow
 * boundaries). A leap is taken for a stretch of at least LEAP_K_MIN steps.
 * A step with an edge (the sub-step modulator's fractional duty) and a
 * stretch shorter than that are steps in double, one at a time: the same
 * step (the one the tables are built from) with the legs' duties the
 * modulator gives it, a held leg's 0 or 1, an edge's share of the step
 * (pwm_rt_ends(), pwm_rt_duty()), taken when none of its clamped
 * components comes within 0.1 % of its clamp. Where the build has
 * AVX-512, a step in which one leg has an edge takes that step's edge
 * map instead (per switch state and edge leg, built from the step on the
 * unit vectors like the tables): the step is linear in z and quadratic in
 * the edge's duty d, which enters only through the inverter voltages (the
 * v_dc column) and the DC-link current's sum of the phases, so it is one
 * product like a leap's and two small corrections, whose chain of
 * dependent operations is about half the step's; elsewhere the map was
 * measured slower than the step (AVX2: 660 against 632 ms on the default
 * mission; plain loops far more), so the step takes the edges there. The
 * map's values are the step's within rounding (leap_edge_check()). A run keeps z in double from
 * its start to its end: the drive's float state is formed once, at the
 * run's end, with the frame sums over the run and the last step's inverter
 * voltages and DC-link current. A step near a clamp (the exact path's
 * float step then clamps) is an ordinary step on the drive's state, and
 * anything off the path above runs ordinary steps (drive_fast_run()).
 *
 * Finding the stretches. At each of the run's grid points (up to 64 at a
 * time) the legs' signs of e = r - c are formed with the exact path's
 * integer carrier and references (pwm_rt_ends()'s sums): a step whose two
 * ends differ in some leg's sign has an edge, the steps between two edges
 * hold the legs' states.
 *
 * No clamp is crossed inside a leap (the bound). The stage clamps i_L, i_d
 * to 256 A and v_C, v_dc to 1024 V. For a leap of k steps and a clamped
 * component x_j (j = 0..k), x_j differs from the chord between x_0 and x_k
 * by at most D k^2 / 8, where D bounds its second difference x_{j+1} -
 * 2 x_j + x_{j-1} = Q_{j-1} z, Q_m = P_{m+2} - 2 P_{m+1} + P_m. So
 *   |x_j| <= max(|x_0|, |x_k|) + (k^2 / 8) sum_c max_{m <= k-2} |Q_m[x, c]| |z_c|
 * for every j, and the leap is taken only when this is below the limit
 * less 0.1 % (for the exact path's float rounding and the tables'); else
 * half the stretch is tried, down to steps in double. The bound holds for
 * the model's real arithmetic; what the leaps and the steps in double
 * compute differs from the exact path's float steps by rounding only.
 *
 * Results: the same run gives the same bytes every time (no threads, a
 * fixed order of operations); they are not the exact path's bits, but
 * within float rounding of them (docs/multirate.md, "Speed"). The vector
 * width is the compiler's for the build's flags (loops over padded rows;
 * any width, or none, is correct).
 */
#ifndef UUV_LEAP_H
#define UUV_LEAP_H

#include <stdbool.h>
#include <stdint.h>

#include "executive.h"

#define LEAP_K_MAX 32u /* longest leap in steps (longer stretches take two) */
#define LEAP_K_MIN 2u  /* shortest stretch taken as a leap */

/* Counts of one run, for the bench and the tests. */
typedef struct {
    uint64_t leaps;        /* leaps taken */
    uint64_t leap_steps;   /* fast steps they covered */
    uint64_t dsteps;       /* fast steps taken one at a time in double inside runs (edges) */
    uint64_t steps;        /* fast steps taken as ordinary steps inside runs */
    uint64_t bound_fails;  /* leaps refused by the clamp bound (shortened or stepped) */
    uint64_t rebuilds;     /* table invalidations (coefficient changes) */
    uint64_t entries;      /* table entries built */
} leap_stats;

typedef struct leap_tables leap_tables;

/* Whether this build has leaps (the float build). */
bool leap_available(void);

/*
 * Sets up leaps for the executive e (after exec_init()): allocates the
 * tables and sets e->desk_run. Returns false (e unchanged) if this build
 * has none or the memory is not there.
 */
bool leap_attach(exec *e);

/* Frees the tables and restores e->desk_run to drive_fast_run(). */
void leap_detach(exec *e);

/* The run's counts so far (zeros when e has no leaps). */
leap_stats leap_stats_of(const exec *e);

/*
 * The leap's product and bound in the build's two forms, 512-bit and
 * 256-bit (a float build with AVX-512 has both; the first takes the
 * leaps), on n entries and states of a fixed test sequence: the count of
 * those whose product (its bits) or verdict differ, and in *accepted the
 * verdicts that allowed the leap. -1 where the build has one form only.
 */
long leap_forms_check(uint32_t n, uint32_t *accepted);

/*
 * The edge maps (leap.c) against the step they are built from, on n
 * cases of a fixed test sequence (coefficients, switch state, edge leg,
 * duty and state): the largest difference of the map's new state and
 * outputs from the step's, relative to the largest of the step's. -1 in
 * the fixed build (no leaps) or without the memory.
 */
double leap_edge_check(uint32_t n);

#endif /* UUV_LEAP_H */

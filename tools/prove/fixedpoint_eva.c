/*
 * Frama-C Eva driver for src/fixedpoint (make prove). Calls every function
 * of fixedpoint.h and wavetable.h with each argument ranging over all the
 * values its contract allows (the whole type, or the documented range of a
 * shift or a base), so that Eva's "no alarm" covers every input. Doubles
 * and floats range over all finite values, the infinities and NaN.
 *
 * The Q15 table lookups are the one domain given as a union of cases
 * (together the whole domain), because Eva keeps an interval per variable
 * and no relation between variables: the bound on the difference of two
 * adjacent knots that wt_segment_q15() relies on is a property of the
 * table, not of the range of its entries. So the lookups run once per
 * segment, where the two entries are constants and the bound is evaluated,
 * not assumed; within a segment the fraction 0 is a case of its own, so
 * that each product (e1 - e0) * f has one sign (to Eva, the offset-binary
 * image of a product spanning 0 is the whole unsigned range). The loops are
 * unrolled (loop unroll annotations), so each case is analysed on its own.
 */
#include <float.h>
#include <stdint.h>

#include "__fc_builtin.h"
#include "fixedpoint/fixedpoint.h"
#include "fixedpoint/wavetable.h"

static int32_t any_i32(void) { return Frama_C_int_interval(INT32_MIN, INT32_MAX); }
static uint32_t any_u32(void) { return (uint32_t)Frama_C_unsigned_int_interval(0u, UINT32_MAX); }
static int64_t any_i64(void) { return Frama_C_long_long_interval(INT64_MIN, INT64_MAX); }
static uint64_t any_u64(void) { return Frama_C_unsigned_long_long_interval(0u, UINT64_MAX); }
static q15_t any_q15(void) { return (q15_t)Frama_C_int_interval(INT16_MIN, INT16_MAX); }
static unsigned shift(unsigned max) { return Frama_C_unsigned_int_interval(0u, max); }

/*
 * Any double: the finite ones, the two infinities and NaN (the IEEE
 * specials are values here, see -warn-special-float in tools/prove.sh).
 * The specials are computed in the variable's own type, so that a float
 * infinity is not a double constant out of the float range.
 */
static double any_f64(void) {
    const double max = DBL_MAX;
    switch (Frama_C_interval(0, 3)) {
    case 0:
        return Frama_C_double_interval(-DBL_MAX, DBL_MAX);
    case 1:
        return max * 2.0; /* +infinity */
    case 2:
        return -max * 2.0; /* -infinity */
    default:
        return (max * 2.0) - (max * 2.0); /* NaN */
    }
}

/* Any float, as any_f64(). */
static float any_f32(void) {
    const float max = FLT_MAX;
    switch (Frama_C_interval(0, 3)) {
    case 0:
        return Frama_C_float_interval(-FLT_MAX, FLT_MAX);
    case 1:
        return max * 2.0f;
    case 2:
        return -max * 2.0f;
    default:
        return (max * 2.0f) - (max * 2.0f);
    }
}

/* A per-unit base: any positive finite double, subnormals included. */
static double any_base(void) { return Frama_C_double_interval(0x1p-1074, DBL_MAX); }

volatile int32_t sink_i;
volatile uint32_t sink_u;
volatile int64_t sink_l;
volatile double sink_d;
volatile float sink_f;

static void integer_helpers(void) {
    uint32_t n = any_u32();
    sink_i = fp_from_u32_i32(any_u32());
    sink_l = fp_from_u64_i64(any_u64());
    sink_i = fp_shr_floor_i32(any_i32(), shift(31u));
    sink_i = fp_shr_round_i32(any_i32(), shift(31u));
    sink_l = fp_shr_floor_i64(any_i64(), shift(63u));
    sink_l = fp_shr_round_i64(any_i64(), shift(63u));
    sink_i = fp_sat_cnt_q15(any_i32(), &n);
    sink_i = fp_sat_cnt_q31(any_i64(), &n);
    sink_i = fp_mulshift_cnt_i32(any_i32(), any_i32(), shift(63u), &n);
    sink_i = fp_narrow_cnt_q15(any_i32(), &n);
    sink_i = fp_narrow_cnt_q31(any_i64(), shift(63u), &n);
    sink_i = fp_widen_q31(any_q15());
    sink_i = fp_shl_cnt_i32(any_i32(), shift(31u), &n);
    sink_i = fp_sat_q15(any_i32());
    sink_i = fp_sat_q31(any_i64());
    sink_i = fp_mulshift_i32(any_i32(), any_i32(), shift(63u));
    sink_i = fp_narrow_q15(any_i32());
    sink_i = fp_narrow_q31(any_i64(), shift(63u));
    sink_i = fp_shl_i32(any_i32(), shift(31u));
    sink_u = n;
}

static void q15_ops(void) {
    uint32_t n = any_u32();
    sink_i = fp_add_cnt_q15(any_q15(), any_q15(), &n);
    sink_i = fp_sub_cnt_q15(any_q15(), any_q15(), &n);
    sink_i = fp_mul_cnt_q15(any_q15(), any_q15(), &n);
    sink_i = fp_mac_cnt_q15(any_q15(), any_q15(), any_q15(), &n);
    sink_i = fp_neg_cnt_q15(any_q15(), &n);
    sink_i = fp_abs_cnt_q15(any_q15(), &n);
    sink_i = fp_add_q15(any_q15(), any_q15());
    sink_i = fp_sub_q15(any_q15(), any_q15());
    sink_i = fp_mul_q15(any_q15(), any_q15());
    sink_i = fp_mac_q15(any_q15(), any_q15(), any_q15());
    sink_i = fp_neg_q15(any_q15());
    sink_i = fp_abs_q15(any_q15());
    sink_f = fp_to_f32_q15(any_q15());
    sink_d = fp_to_f64_q15(any_q15());
}

static void q31_ops(void) {
    uint32_t n = any_u32();
    sink_i = fp_add_cnt_q31(any_i32(), any_i32(), &n);
    sink_i = fp_sub_cnt_q31(any_i32(), any_i32(), &n);
    sink_i = fp_mul_cnt_q31(any_i32(), any_i32(), &n);
    sink_i = fp_mac_cnt_q31(any_i32(), any_i32(), any_i32(), &n);
    sink_i = fp_neg_cnt_q31(any_i32(), &n);
    sink_i = fp_abs_cnt_q31(any_i32(), &n);
    sink_i = fp_add_q31(any_i32(), any_i32());
    sink_i = fp_sub_q31(any_i32(), any_i32());
    sink_i = fp_mul_q31(any_i32(), any_i32());
    sink_i = fp_mac_q31(any_i32(), any_i32(), any_i32());
    sink_i = fp_neg_q31(any_i32());
    sink_i = fp_abs_q31(any_i32());
    sink_f = fp_to_f32_q31(any_i32());
    sink_d = fp_to_f64_q31(any_i32());
}

static void conversions(void) {
    uint32_t n = any_u32();
    sink_i = fp_from_f32_cnt_q15(any_f32(), &n);
    sink_i = fp_from_f32_cnt_q31(any_f32(), &n);
    sink_i = fp_from_f64_cnt_q15(any_f64(), &n);
    sink_i = fp_from_f64_cnt_q31(any_f64(), &n);
    sink_i = fp_from_f32_q15(any_f32());
    sink_i = fp_from_f32_q31(any_f32());
    sink_i = fp_from_f64_q15(any_f64());
    sink_i = fp_from_f64_q31(any_f64());
    sink_i = fp_pu_from_f64_q15(any_f64(), any_base());
    sink_i = fp_pu_from_f64_q31(any_f64(), any_base());
    sink_d = fp_pu_to_f64_q15(any_q15(), any_f64());
    sink_d = fp_pu_to_f64_q31(any_i32(), any_f64());
}

/*
 * The Q15 lookups in segment k: phases k * 2^22 + low, low over the
 * segment's 2^22 phases, split into low < 2^7 (fraction 0) and the rest.
 */
static void lookups_in_segment(uint32_t k) {
    int part;

    /*@ loop unroll 2; */
    for (part = 0; part < 2; part++) {
        uint32_t low = (part == 0)
                           ? Frama_C_unsigned_int_interval(0u, (1u << WT_IGNORED_BITS) - 1u)
                           : Frama_C_unsigned_int_interval(1u << WT_IGNORED_BITS,
                                                           (1u << 22u) - 1u);
        uint32_t phase = (k << 22u) + low;
        sink_i = wt_sin_q15(phase);
        sink_i = wt_cos_q15(phase);
        sink_i = wt_tri_q15(phase);
    }
}

/*
 * Segments first to first + 31, each on its own. The unrolled iterations
 * stay apart until the function returns; nesting two loops of 32 instead
 * of one of 1024 keeps that number (and the run time) small.
 */
static void lookups_in_block(uint32_t first) {
    uint32_t i;

    /*@ loop unroll 32; */
    for (i = 0u; i < 32u; i++) {
        lookups_in_segment(first + i);
    }
}

/* Every segment of the tables. */
static void table_lookups_q15(void) {
    uint32_t block;

    /*@ loop unroll 32; */
    for (block = 0u; block < WT_TABLE_SIZE / 32u; block++) {
        lookups_in_block(block * 32u);
    }
}

static void wavetables(void) {
    uint32_t phase = any_u32();
    table_lookups_q15();
    sink_f = wt_sin_f32(phase);
    sink_f = wt_cos_f32(phase);
    sink_f = wt_tri_f32(phase);
    sink_u = wt_phase_inc_q16(any_i32(), any_u32());
    sink_u = wt_phase_inc_f32(any_f32(), any_f32());
    sink_u = wt_phase_inc_pu_q31(any_i32(), any_u32());
}

int main(void) {
    integer_helpers();
    q15_ops();
    q31_ops();
    conversions();
    wavetables();
    return 0;
}

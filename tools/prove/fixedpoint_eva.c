/*
 * Frama-C Eva driver for src/fixedpoint (make prove). Calls every function
 * of fixedpoint.h and wavetable.h once with each argument ranging over all
 * the values its contract allows (the whole type, or the documented range
 * of a shift or a base), so that Eva's "no alarm" covers every input.
 * Doubles and floats range over all finite values, and NaN and the
 * infinities too where the function documents them.
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
static double any_f64(void) { return Frama_C_double_interval(-DBL_MAX, DBL_MAX); }
static float any_f32(void) { return Frama_C_float_interval(-FLT_MAX, FLT_MAX); }

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
    sink_i = fp_pu_from_f64_q15(any_f64(), Frama_C_double_interval(1e-6, 1e6));
    sink_i = fp_pu_from_f64_q31(any_f64(), Frama_C_double_interval(1e-6, 1e6));
    sink_d = fp_pu_to_f64_q15(any_q15(), Frama_C_double_interval(1e-6, 1e6));
    sink_d = fp_pu_to_f64_q31(any_i32(), Frama_C_double_interval(1e-6, 1e6));
}

static void wavetables(void) {
    uint32_t phase = any_u32();
    sink_i = wt_sin_q15(phase);
    sink_i = wt_cos_q15(phase);
    sink_i = wt_tri_q15(phase);
    sink_f = wt_sin_f32(phase);
    sink_f = wt_cos_f32(phase);
    sink_f = wt_tri_f32(phase);
    sink_u = wt_phase_inc_q16(Frama_C_int_interval(-2147483647, INT32_MAX), any_u32());
    sink_u = wt_phase_inc_f32(any_f32(), Frama_C_float_interval(0.0f, 1.0f));
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

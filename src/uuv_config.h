/*
 * Build configuration of uuvsim: the numeric build and every option that a
 * build may choose, in one place. The build passes -D options; everything
 * not passed takes the default below. Impossible combinations stop the
 * build here, so that no source file needs to test for them.
 */
#ifndef UUV_CONFIG_H
#define UUV_CONFIG_H

/* Numeric builds of the fast models (PWM, inverter, motor, controller). */
#define UUV_NUMERIC_FIXED 1 /* integer arithmetic in per-unit Q formats */
#define UUV_NUMERIC_FLOAT 2 /* IEEE single precision */

#ifndef UUV_NUMERIC
#define UUV_NUMERIC UUV_NUMERIC_FIXED
#endif

#if (UUV_NUMERIC != UUV_NUMERIC_FIXED) && (UUV_NUMERIC != UUV_NUMERIC_FLOAT)
#error "UUV_NUMERIC must be UUV_NUMERIC_FIXED (1) or UUV_NUMERIC_FLOAT (2)"
#endif

/*
 * Whether the target has a single-precision FPU. The port sets it (through
 * its build flags); a host always has one. The float build on a core without
 * an FPU would run the 2 us path in software floating point, which can never
 * meet its deadline, so it is refused rather than built.
 */
#ifndef UUV_TARGET_HAS_FPU
#define UUV_TARGET_HAS_FPU 1
#endif

#if (UUV_NUMERIC == UUV_NUMERIC_FLOAT) && (UUV_TARGET_HAS_FPU == 0)
#error "the float build needs a target with a single-precision FPU; use UUV_NUMERIC_FIXED"
#endif

/*
 * Whether the target has an IEEE 754 square-root instruction in double
 * (UUV_HW_SQRT_F64) and in single precision (UUV_HW_SQRT_F32). The port
 * sets them with -fno-math-errno (the instruction then stands alone; see
 * src/math/sqrt.c): the Linux port both, the Cortex-M7 both (FPv5-D16),
 * the Cortex-M4F single only, the Cortex-M3 neither. The bits are the same
 * either way; only the cost differs.
 */
#ifndef UUV_HW_SQRT_F64
#define UUV_HW_SQRT_F64 0
#endif
#ifndef UUV_HW_SQRT_F32
#define UUV_HW_SQRT_F32 0
#endif

#if (UUV_HW_SQRT_F32 != 0) && (UUV_TARGET_HAS_FPU == 0)
#error "UUV_HW_SQRT_F32 needs a target with a single-precision FPU"
#endif

/*
 * Whether the fixed-point helpers (src/fixedpoint/fixedpoint.h) may use the
 * compiler's right shift of a negative integer and its conversion of an
 * out-of-range integer to a narrower signed type. C99 leaves both to the
 * implementation; GCC and Clang define them, on every target, as the
 * arithmetic shift (floor) and reduction modulo 2^N. The port sets 1 with
 * those compilers; the default, 0, keeps the portable forms (offset-binary
 * shifts, saturation by two comparisons), which make lint and make prove
 * analyse. The values are the same either way (test_fixedpoint holds each
 * form to one reference, on the host and on the LM3S6965 image, which
 * builds the portable forms); only the instruction count differs.
 */
#ifndef UUV_NATIVE_INT_OPS
#define UUV_NATIVE_INT_OPS 0
#endif
/*
 * Whether the target divides 64-bit integers in one instruction
 * (UUV_HW_DIV_64 1: x86-64 and AArch64, set by the Linux port). Without it
 * (0, the default; the Cortex-M cores, whose library division of a 64-bit
 * value takes about 70 instructions) a division of a 64-bit value by a
 * count below 2^16, as the drive's frame means make, is done as three
 * 32-bit divisions (fp_div_i64_u32(), src/fixedpoint/fixedpoint.h). The
 * quotient is the same either way; only the cost differs.
 */
#ifndef UUV_HW_DIV_64
#define UUV_HW_DIV_64 0
#endif
/*
 * A lean image (UUV_LEAN_IMAGE 1; 0 by default) leaves out what the
 * firmware never runs and a 64 KiB flash cannot also hold: the drive's
 * event and averaged inverter layers, its energy audit and its
 * extrapolating (FOH, DERIV) and filter couplings (drive_segment.h,
 * DRIVE_OPTIONAL), and the manoeuvre metrics, which only the desk reports
 * (executive.c). The port sets 1 for the Cortex-M3 images; drive_init()
 * then refuses the left-out options (DRIVE_ERR_LAYER) and the code that
 * serves them is dropped. The bits of what is built are the same either way.
 */
#ifndef UUV_LEAN_IMAGE
#define UUV_LEAN_IMAGE 0
#endif

/* Name of the numeric build, as reports print it. */
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
#define UUV_NUMERIC_NAME "fixed"
#else
#define UUV_NUMERIC_NAME "float"
#endif

#endif /* UUV_CONFIG_H */

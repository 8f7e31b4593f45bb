/*
 * The fixed build's real-time fast tick in Thumb-2 (ARMv7-M; linked into
 * the Cortex-M4 and M7 images): drive_rt_step() (src/drive_rt_step.h)
 * with the sub-step modulator's frame plan (pwm_rt.h), the same integer
 * operations in the same order, so the same bits. The C stays the
 * reference: the desk simulator runs it, tests/unit/test_fast_kernel.c
 * runs both side by side on the target (from random states, some at the
 * clamp edge, so the clamps act, and with edges in the steps), and make
 * test compares the firmware's telemetry with the desk's byte for byte.
 * What the kernel saves is the compiler's register spills and moves
 * around the two filter phases (docs/firmware.md section 9).
 *
 *   void drive_fast_kernel_v7m(drive_segment *d);
 *
 * One step (see src/models/drive/pwm/pwm_rt.h, power_stage_fast.h and
 * power_stage_nodes.h for the arithmetic and its bounds):
 *   - modulator: the frame's step count k against its next event. Outside
 *     the events the legs keep their states s_x (held), as whole-step
 *     duties; an event step takes its states and, when one is a share of
 *     the step, its duties d_x (Q15); a PWM_RT_PER_STEP event hands the
 *     whole step to the C, which computes it on its own;
 *   - inverter: v3 = hi(v_dc 0x55555555 + 2^31); held: u_x = n_x v3 with
 *     n_a = 2 s_a - s_b - s_c; with duties: u_x = hi(8 v3 w_x 2^14 + 2^31)
 *     with w_a = 2 d_a - d_b - d_c (ps_inverter_q());
 *   - per filter phase x: the companion j_L, the node's dv, the states
 *     i_L, i_d, v, clamped to +-1 per unit and counted, j_sh from the
 *     clamped states, T += dd_x (i_L(k) + i_L(k+1)) with dd_x = s_x - s_c
 *     (held, 32 bits) or d_x - d_c (duties, 64 bits); then the motor's
 *     fast current and the frame sum of v;
 *   - DC link: i_dc = floor((T + 1) / 2) (held: the duties' 2^15 scale
 *     divided out) or floor((T + 2^15) / 2^16), v_dc by forward Euler,
 *     clamped; the frame sum of v_dc.
 * Every rounded product sum is SMLAL on a 64-bit accumulator that starts
 * as base 2^32 + 2^31: its high word is base + round(sum / 2^32); a
 * single product is SMMLAR (base + round(x y / 2^32), the same bits) or,
 * without a base, SMMULR (ARMv7E-M: the Cortex-M4 and M7).
 *
 * The offsets come from fast_kernel_offsets.h, generated from the C
 * declarations (fast_kernel_offsets.c). The paired loads and stores
 * (LDRD, STRD) also need some fields next to each other, and the events
 * are indexed by a shift; the checks below stop the build if a
 * declaration breaks that.
 */
#include "fast_kernel_offsets.h"

#if D_RT_NEXT_AT != D_RT_K + 4 || PH_V_C != PH_I_L + 4 || PH_J_SH != PH_I_D + 4
#error "fast_kernel_v7m.S: the step count and the next event, or a filter phase's states, are not adjacent"
#endif
#if K_G_L2 != K_NEG_EPS_L + 4 || K_G_D != K_NEG_G_L + 4 || D_BAT_KG != D_BAT_E + 4
#error "fast_kernel_v7m.S: a pair of coefficients loaded together is not adjacent"
#endif
#if EV_SIZE != 16
#error "fast_kernel_v7m.S: an event of the modulator's plan is not 16 bytes"
#endif

    .syntax unified
    .thumb
    .text

/* 2^31, the rounding half of every accumulator. */
#define HALF 0x80000000

/*
 * Clamps x to [-1, 1] per unit and counts it in the stage's saturation
 * count (which stops at 2^32 - 1); t is a scratch register.
 */
    .macro CLAMP x, t
    add     \t, \x, #Q28_ONE
    cmp     \t, #(2 * Q28_ONE)
    bls     1f
    ldr     \t, [r0, #D_PS_SAT]
    adds    \t, \t, #1
    it      ne
    strne   \t, [r0, #D_PS_SAT]
    cmp     \x, #0
    ite     gt
    movgt   \x, #Q28_ONE
    movle   \x, #-Q28_ONE
1:
    .endm

/*
 * Filter phase X (0 or 1) with the inverter voltage in U and the leg
 * difference in DD; FIRST: T = DD S (phase a) else T += DD S, in r4 (WIDE
 * 0) or r1:r4 (WIDE 1, r1 the high word).
 * Registers: r0 d; r3 i_m; r6 i_L(k); r7 v; r8 i_d; r9 j_sh; lr j_L then
 * i_L(k+1); r10, r11 coefficients; r12 an accumulator's low word.
 */
    .macro PHASE x, u, dd, first, wide
    ldrd    r6, r7, [r0, #(D_PS_PH + \x * PH_SIZE + PH_I_L)]
    ldrd    r8, r9, [r0, #(D_PS_PH + \x * PH_SIZE + PH_I_D)]
    ldrd    r10, r11, [r0, #(D_PS_K + K_NEG_EPS_L)]
    /* j_L = hi((i_L 2^32 + 2^31) + i_L neg_eps_l + (u - v) g_l2) */
    mov     r12, #HALF
    mov     lr, r6
    smlal   r12, lr, r6, r10
    subs    \u, \u, r7
    smlal   r12, lr, \u, r11
    /* dv = hi(2^31 + (j_L + j_sh - i_m) k_node) */
    ldr     r3, [r0, #(D_IFAST + 4 * \x)]
    adds    r9, r9, lr
    subs    r9, r9, r3
    ldr     r10, [r0, #(D_PS_K + K_NODE)]
    smmulr  r11, r9, r10
    /* i_L(k+1) = hi((j_L 2^32 + 2^31) + dv neg_g_l) */
    ldrd    r9, r10, [r0, #(D_PS_K + K_NEG_G_L)]
    smmlar  lr, r11, r9, lr
    /* i_d(k+1) = hi((i_d 2^32 + 2^31) + i_d neg_a_d + dv g_d) */
    ldr     r9, [r0, #(D_PS_K + K_NEG_A_D)]
    mov     r12, #HALF
    smlal   r12, r8, r8, r9
    smlal   r12, r8, r11, r10
    /* v(k+1) = v + dv */
    adds    r7, r7, r11
    /* The three states within [-1, 1) per unit (the usual case), else clamped. */
    add     r10, lr, #Q28_ONE
    add     r11, r8, #Q28_ONE
    orrs    r10, r10, r11
    add     r11, r7, #Q28_ONE
    orrs    r10, r10, r11
    lsrs    r10, r10, #29
    beq     2f
    CLAMP   lr, r10
    CLAMP   r8, r10
    CLAMP   r7, r10
2:
    /* j_sh(k+1) = hi(((i_L - i_m - 2 i_d) 2^32 + 2^31) + i_d a_d), modulo 2^32 */
    subs    r9, lr, r3
    sub     r9, r9, r8, lsl #1
    ldr     r10, [r0, #(D_PS_K + K_A_D)]
    smmlar  r9, r8, r10, r9
    strd    lr, r7, [r0, #(D_PS_PH + \x * PH_SIZE + PH_I_L)]
    strd    r8, r9, [r0, #(D_PS_PH + \x * PH_SIZE + PH_I_D)]
    /* T: the DC-link current's sum */
    adds    r6, r6, lr
    .if \wide
    .if \first
    smull   r4, r1, \dd, r6
    .else
    smlal   r4, r1, \dd, r6
    .endif
    .else
    .if \first
    mul     r4, \dd, r6
    .else
    mla     r4, \dd, r6, r4
    .endif
    .endif
    /* The motor's fast current: i_m = hi((i_m 2^32 + 2^31) + (v - e) k32) */
    ldr     r10, [r0, #(D_E + 4 * \x)]
    ldr     r11, [r0, #D_K32]
    subs    r10, r7, r10
    smmlar  r3, r10, r11, r3
    str     r3, [r0, #(D_IFAST + 4 * \x)]
    /* The frame sum of v (64 bits) */
    ldrd    r10, r11, [r0, #(D_SUM_VCAP + 8 * \x)]
    adds    r10, r10, r7
    adc     r11, r11, r7, asr #31
    strd    r10, r11, [r0, #(D_SUM_VCAP + 8 * \x)]
    .endm

/* v3 = hi(v_dc 0x55555555 + 2^31) in r3 (r1, r7 scratch). */
    .macro THIRD
    ldr     r7, [r0, #D_PS_VDC]
    mov     r1, #0x55555555
    smmulr  r3, r7, r1
    .endm

    .global drive_fast_kernel_v7m
    .type   drive_fast_kernel_v7m, %function
    .thumb_func
drive_fast_kernel_v7m:
    push    {r4-r11, lr}
    /* Modulator: step k of the frame, its next event at next_at. */
    ldrd    r1, r2, [r0, #D_RT_K]
    cmp     r1, r2
    beq     .Levent
    adds    r1, r1, #1
    str     r1, [r0, #D_RT_K]
    /* Held legs: s_a (r4), s_b (r5), s_c (r6). */
    ldrd    r4, r5, [r0, #D_S]
    ldr     r6, [r0, #(D_S + 8)]
.Lheld:
    /* dd_a = s_a - s_c (r4), dd_b = s_b - s_c (r5) */
    subs    r4, r4, r6
    subs    r5, r5, r6
    /* Inverter: v3 (r3); u_a = n_a v3 (r1), u_b = n_b v3 (r2), with
     * n_a = 2 dd_a - dd_b, n_b = 2 dd_b - dd_a. */
    THIRD
    rsb     r1, r5, r4, lsl #1
    rsb     r2, r4, r5, lsl #1
    mul     r1, r3, r1
    mul     r2, r3, r2
    strd    r1, r2, [r0, #D_PS_U]
    PHASE   0, r1, r4, 1, 0
    PHASE   1, r2, r5, 0, 0
    /* DC-link current i_dc = floor((T + 1) / 2) */
    adds    r4, r4, #1
    asrs    r4, r4, #1
.Ldclink:
    str     r4, [r0, #D_PS_IDC]
    /* v_dc = hi((v_dc 2^32 + 2^31) + (e - v_dc) kg + i_dc neg_k_c), clamped */
    ldr     r6, [r0, #D_PS_VDC]
    ldrd    r7, r8, [r0, #D_BAT_E]
    ldr     r9, [r0, #(D_PS_K + K_NEG_K_C)]
    subs    r7, r7, r6
    mov     r12, #HALF
    smlal   r12, r6, r7, r8
    smlal   r12, r6, r4, r9
    CLAMP   r6, r7
    str     r6, [r0, #D_PS_VDC]
    ldrd    r7, r8, [r0, #D_SUM_VDC]
    adds    r7, r7, r6
    adc     r8, r8, r6, asr #31
    strd    r7, r8, [r0, #D_SUM_VDC]
    pop     {r4-r11, pc}

    /* An event step: ev[next] (r8), its kind (r9). */
.Levent:
    ldr     r4, [r0, #D_RT_NEXT]
    add     r8, r0, r4, lsl #4
    ldrb    r9, [r8, #(D_RT_EV + EV_KIND)]
    cmp     r9, #EV_PER_STEP
    beq     .Lper_step
    adds    r1, r1, #1
    str     r1, [r0, #D_RT_K]
    adds    r4, r4, #1
    str     r4, [r0, #D_RT_NEXT]
    ldrh    r7, [r8, #(D_RT_EV + EV_SIZE + EV_AT)]
    str     r7, [r0, #D_RT_NEXT_AT]
    /* Its states, the legs' from here on. */
    ldrb    r7, [r8, #(D_RT_EV + EV_S)]
    and     r4, r7, #1
    ubfx    r5, r7, #1, #1
    ubfx    r6, r7, #2, #1
    strd    r4, r5, [r0, #D_S]
    str     r6, [r0, #(D_S + 8)]
    cmp     r9, #0
    beq     .Lheld
    /* Duties d_a (r4), d_b (r5), d_c (r6), Q15. */
    ldr     r4, [r8, #(D_RT_EV + EV_DUTY)]
    ldr     r5, [r8, #(D_RT_EV + EV_DUTY + 4)]
    ldr     r6, [r8, #(D_RT_EV + EV_DUTY + 8)]
    /* dd_a = d_a - d_c (r4), dd_b = d_b - d_c (r5), Q15 units */
    subs    r4, r4, r6
    subs    r5, r5, r6
    /* Inverter: 8 v3 (r3); u_x = hi(8 v3 w_x 2^14 + 2^31) (r1, r2), with
     * w_a = 2 dd_a - dd_b, w_b = 2 dd_b - dd_a. */
    THIRD
    lsls    r3, r3, #3
    rsb     r1, r5, r4, lsl #1
    lsls    r1, r1, #14
    rsb     r2, r4, r5, lsl #1
    lsls    r2, r2, #14
    smmulr  r1, r3, r1
    smmulr  r2, r3, r2
    strd    r1, r2, [r0, #D_PS_U]
    PHASE   0, r1, r4, 1, 1
    PHASE   1, r2, r5, 0, 1
    /* DC-link current i_dc = floor((T + 2^15) / 2^16) */
    adds    r4, r4, #0x8000
    adc     r1, r1, #0
    lsrs    r4, r4, #16
    orr     r4, r4, r1, lsl #16
    b       .Ldclink

    /* A step the plan hands to the C (pwm_rt_event_take() computes it on its own). */
.Lper_step:
    bl      drive_fast_tick
    pop     {r4-r11, pc}
    .ltorg
    .size   drive_fast_kernel_v7m, . - drive_fast_kernel_v7m

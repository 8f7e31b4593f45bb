/*
 * The offsets and constants the fixed build's fast-tick kernel
 * (fast_kernel_v7m.S) uses, taken from the C declarations: compiled with
 * -S, each OFFSET line of the output becomes a #define of the generated
 * header fast_kernel_offsets.h (see the Makefile), so the kernel follows
 * the declarations; it checks the adjacency its paired loads need. Never
 * linked.
 */
#include <stddef.h>

#include "drive_segment.h"

#define OFFSET(name, value) __asm__ volatile("\n@OFFSET " #name " %c0" : : "i"(value))

void fast_kernel_offsets(void);
void fast_kernel_offsets(void) {
    OFFSET(D_RT_K, offsetof(drive_segment, rt.k));
    OFFSET(D_RT_NEXT_AT, offsetof(drive_segment, rt.next_at));
    OFFSET(D_RT_NEXT, offsetof(drive_segment, rt.next));
    OFFSET(D_RT_EV, offsetof(drive_segment, rt.ev));
    OFFSET(EV_AT, offsetof(pwm_rt_event, at));
    OFFSET(EV_S, offsetof(pwm_rt_event, s));
    OFFSET(EV_KIND, offsetof(pwm_rt_event, kind));
    OFFSET(EV_DUTY, offsetof(pwm_rt_event, duty));
    OFFSET(EV_SIZE, sizeof(pwm_rt_event));
    OFFSET(EV_PER_STEP, PWM_RT_PER_STEP);
    OFFSET(D_S, offsetof(drive_segment, s));
    OFFSET(D_PS_K, offsetof(drive_segment, ps.k));
    OFFSET(D_PS_PH, offsetof(drive_segment, ps.ph));
    OFFSET(D_PS_VDC, offsetof(drive_segment, ps.v_dc));
    OFFSET(D_PS_U, offsetof(drive_segment, ps.u));
    OFFSET(D_PS_IDC, offsetof(drive_segment, ps.i_dc));
    OFFSET(D_PS_SAT, offsetof(drive_segment, ps.sat_count));
    OFFSET(D_BAT_E, offsetof(drive_segment, in.battery.e));
    OFFSET(D_BAT_KG, offsetof(drive_segment, in.battery.kg));
    OFFSET(D_IFAST, offsetof(drive_segment, i_fast));
    OFFSET(D_E, offsetof(drive_segment, e));
    OFFSET(D_K32, offsetof(drive_segment, k32));
    OFFSET(D_SUM_VCAP, offsetof(drive_segment, sums.v_cap));
    OFFSET(D_SUM_VDC, offsetof(drive_segment, sums.v_dc));
    OFFSET(K_NEG_EPS_L, offsetof(ps_coef_q, neg_eps_l));
    OFFSET(K_G_L2, offsetof(ps_coef_q, g_l2));
    OFFSET(K_NEG_G_L, offsetof(ps_coef_q, neg_g_l));
    OFFSET(K_G_D, offsetof(ps_coef_q, g_d));
    OFFSET(K_A_D, offsetof(ps_coef_q, a_d));
    OFFSET(K_NEG_A_D, offsetof(ps_coef_q, neg_a_d));
    OFFSET(K_NODE, offsetof(ps_coef_q, k_node));
    OFFSET(K_NEG_K_C, offsetof(ps_coef_q, neg_k_c));
    OFFSET(PH_I_L, offsetof(ps_phase_q, i_l));
    OFFSET(PH_V_C, offsetof(ps_phase_q, v_c));
    OFFSET(PH_I_D, offsetof(ps_phase_q, i_d));
    OFFSET(PH_J_SH, offsetof(ps_phase_q, j_sh));
    OFFSET(PH_SIZE, sizeof(ps_phase_q));
    OFFSET(Q28_ONE, PS_Q28_ONE);
}

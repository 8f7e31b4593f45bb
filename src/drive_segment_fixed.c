/*
 * The drive segment of the fixed-point build (see drive_segment.h): every
 * signal per unit of the bases in models/drive/drive_units.h, integer arithmetic
 * only in the fast tick and the motor task. The slow exchange, once per
 * 100 ms, converts to SI in double.
 */
#include "drive_segment.h"

#if UUV_NUMERIC == UUV_NUMERIC_FIXED

#include <stddef.h>

#include "math/umath.h"
#include "models/drive/drive_units.h"
#include "models/drive/inverter/leg_fault.h"
#include "models/drive/inverter/power_stage_fast.h"

#define Q31_ONE 2147483648.0
#define Q28_ONE 268435456.0

/* round(sum * 2^shift / n) as Q31, saturating: a frame mean. */
static q31_t mean_q31(int64_t sum, unsigned shift, uint32_t n, uint32_t *sat) {
    int64_t scaled = sum * (int64_t)(1u << shift);
    int64_t half = (int64_t)(n / 2u);
    int64_t q = (scaled >= 0) ? (scaled + half) / (int64_t)n : -((-scaled + half) / (int64_t)n);
    return fp_sat_cnt_q31(q, sat);
}

/* Splits a positive factor into an int32 mantissa below 2^30 and a right shift. */
static void factor_split(double f, int32_t *mant, uint32_t *shift) {
    uint32_t sh = 0u;
    double scale = 1.0; /* 2^sh, exact */
    while (sh < 62u && f * (scale * 2.0) < 1073741824.0) {
        scale *= 2.0;
        sh++;
    }
    *mant = (int32_t)(f * scale + 0.5);
    *shift = sh;
}

drive_status drive_init(drive_segment *d, const drive_config *cfg, const propeller_model *prop) {
    if (!drive_options_built(cfg->inverter, cfg->down, cfg->up, cfg->energy_audit)) {
        return DRIVE_ERR_LAYER;
    }
    const bool averaged = DRIVE_OPTIONAL(cfg->inverter == DRIVE_INVERTER_AVERAGED);
    if (cfg->fast_ns < 100u || cfg->fast_per_medium == 0u || cfg->medium_per_control == 0u ||
        cfg->fast_per_medium > 100000u || cfg->medium_per_slow == 0u ||
        (averaged && cfg->fast_per_medium != 1u) ||
        (cfg->modulator != DRIVE_MODULATOR_SUBSTEP && cfg->modulator != DRIVE_MODULATOR_SAMPLED) ||
        (cfg->dead_time_ns != 0u && cfg->modulator != DRIVE_MODULATOR_SUBSTEP)) {
        return DRIVE_ERR_CONFIG;
    }
    *d = (drive_segment){0};
    d->cfg = *cfg;
    d->ps_params = *cfg->stage;
    /* Edges located inside the step (the general modulator), or switch
     * states held per step (the real-time one). */
    pwm_params pwm_p = *cfg->pwm;
    pwm_p.edges = PWM_EDGES_INTERPOLATED;
    d->fault.dc_cap_frac = 1.0;
    d->fault.load_factor = 1.0;
    double fast_s = 1e-9 * (double)cfg->fast_ns;
    double medium_s = fast_s * (double)cfg->fast_per_medium;
    uint32_t mod_ns = cfg->fast_ns;
    induction_motor_params mp = *cfg->motor;
    if (averaged) {
        if (inverter_qs_init_q(&d->qs, &pwm_p, cfg->fast_ns, cfg->v_dc0_v) !=
            INVERTER_AVG_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->qs.mod;
        d->stage = NULL;
        /* The filter's series branch joins the stator (inverter_avg.h). */
        mp.rs_ohm += d->ps_params.r_l_ohm;
        mp.lls_h += d->ps_params.l_h;
    } else {
        if (pwm_init_q(&d->pwm, &pwm_p, cfg->fast_ns) != PWM_OK) {
            return DRIVE_ERR_MODEL;
        }
        pwm_p.edges = PWM_EDGES_SAMPLED;
        if (pwm_rt_init(&d->rt, &pwm_p, cfg->fast_ns) != PWM_OK ||
            pwm_rt_dead_time(&d->rt, cfg->dead_time_ns, cfg->fast_ns) != PWM_OK ||
            power_stage_init_q(&d->ps, &d->ps_params, cfg->fast_ns,
                               cfg->v_dc0_v) != PS_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->pwm;
        d->stage = &d->ps;
    }
    if (induction_motor_init_q(&d->motor, &mp, prop, medium_s) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    /* The fast companion: a_ss h1 in Q3.28 current (256 A) per Q3.28 volt (1024 V). */
    double k_l = d->motor.c.a_ss * fast_s * 4.0;
    if (!(k_l > 1e-7 && k_l < 8.0)) {
        return DRIVE_ERR_CONFIG;
    }
    factor_split(k_l, &d->k_mant, &d->k_shift);
    /* The real-time path's form: k_l 2^32 (below 2^31, at least 2^20 for precision). */
    d->k32 = (k_l < 0.5 && k_l > 2.5e-4) ? (int32_t)(k_l * 4294967296.0 + 0.5) : 0;
    /* The EMF's current drop per Q31 (motor) current change: 1 / (8 k_l N). */
    factor_split(1.0 / (8.0 * k_l * (double)cfg->fast_per_medium), &d->e_mant, &d->e_shift);
    d->ctl_params = *cfg->control;
    d->ctl_params.step_s = medium_s * (double)cfg->medium_per_control;
    d->ctl_params.pwm_step_s = 1e-9 * (double)mod_ns;
    if (drive_control_init_q(&d->ctl, &d->ctl_params) != DRIVE_CONTROL_OK) {
        return DRIVE_ERR_MODEL;
    }
    /* First-order filter gain per fast step: step / frame, Q16. */
    d->filt_k = (uint32_t)(65536u / cfg->fast_per_medium);
    d->k_deriv = fp_from_f64_q31(MATH_TWO_PI_F64 * DRIVE_BASE_FREQ_HZ * fast_s /
                                 1.7320508075688772);
    d->plain_ok = (d->k32 != 0) && (cfg->inverter == DRIVE_INVERTER_SWITCHING) &&
               (cfg->dead_time_ns == 0u) &&
               (cfg->down == COUPLE_ZOH || cfg->down == COUPLE_STAGGER) &&
               (cfg->up != COUPLE_FILTER) && !cfg->energy_audit;
    d->kernel_ok = (cfg->modulator == DRIVE_MODULATOR_SAMPLED);
    d->plain = d->plain_ok;
    d->staggered = drive_staggered(cfg->down, cfg->fast_per_medium);
    /* Steps of a correction still to come at the next mark: from the latch on it
     * runs a frame, and the latch is at the boundary or, staggered, N / 2 steps later. */
    d->corr_pending = d->staggered ? cfg->fast_per_medium / 2u : cfg->fast_per_medium;
    if (induction_motor_load_q(&d->motor, 1.0, &d->load_next) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->uv_q28 = fp_from_f64_q31(DRIVE_UV_TRIP_V / DRIVE_BASE_VOLTAGE_V / 8.0);
    d->neg_k_c_next = averaged ? 0 : d->stage->k.neg_k_c;
    return DRIVE_OK;
}

/* The DC-link voltage of the stage in use (Q3.28), whichever it is. */
static int32_t stage_v_dc(const drive_segment *d) {
    return !DRIVE_AVERAGED(d) ? d->stage->v_dc : d->qs.v_dc;
}


/*
 * The fast companion's current step, Q3.28 of 256 A: i + round((v - e) k32
 * / 2^32) where k32 fits (the real-time path's form, so that both paths
 * give the same currents), else i + round((v - e) k_mant / 2^k_shift) for
 * any step length.
 */
static inline int32_t fast_current_next(const drive_segment *d, int32_t i, int32_t dv) {
    if (d->k32 != 0) {
        return ps_hi_q(ps_mac_q(ps_acc_q(i), dv, d->k32));
    }
    return i + (int32_t)fp_shr_round_i64((int64_t)dv * d->k_mant, d->k_shift);
}

/* The Q15 motor currents of the general power stage, from the Q3.28 companion. */
static inline q15_t stage_current_q15(int32_t i) {
    return fp_sat_q15(fp_shr_round_i32(i, 13u));
}

/*
 * An open motor phase (drive_faults) in the fast companion: the currents
 * a, b (c = -a - b) lose their component along the open phase, as the
 * motor's stator current does (induction_motor_open_phase_q()): phase a
 * open gives (0, i_b + i_a / 2), b open (i_a + i_b / 2, 0), c open
 * ((i_a - i_b) / 2, -(i_a - i_b) / 2). The sums are formed in 64 bits and
 * saturated.
 */
static void open_phase_fast(int32_t i[2], uint8_t phase) {
    if (phase == 1u) {
        i[1] = fp_sat_q31((int64_t)i[1] + fp_shr_round_i32(i[0], 1u));
        i[0] = 0;
    } else if (phase == 2u) {
        i[0] = fp_sat_q31((int64_t)i[0] + fp_shr_round_i32(i[1], 1u));
        i[1] = 0;
    } else {
        i[0] = (int32_t)fp_shr_round_i64((int64_t)i[0] - i[1], 1u);
        i[1] = -i[0];
    }
}

/*
 * The energy audit's fast sums: the squares of the three inductor and
 * damping currents, each rounded to A 2^8 first (Q3.28 of 256 A is A 2^20),
 * so that a slow frame of 50000 steps stays far below 2^63 (each square is
 * at most 2^32 with the states clamped to +-1 per unit).
 */
static void audit_fast(drive_segment *d) {
    const power_stage_q *ps = d->stage;
    int64_t l[3], r[3];
    for (int x = 0; x < 2; x++) {
        l[x] = fp_shr_round_i32(ps->ph[x].i_l, 12u);
        r[x] = fp_shr_round_i32(ps->ph[x].i_d, 12u);
    }
    l[2] = -l[0] - l[1];
    r[2] = -r[0] - r[1];
    d->sums.loss_l += l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    d->sums.loss_d += r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

/*
 * Filter phase x of the real-time step, then at once the motor's fast
 * companion of that phase and its frame sum, so that little of the phase
 * stays alive in registers for the next.
 */
static inline void fast_phase_plain(drive_segment *d, ps_fast_q *f, int x) {
    power_stage_q *ps = &d->ps;
    ps_fast_phase_q(ps, f, x, d->i_fast[x]);
    const int32_t v = ps->ph[x].v_c;
    /* i + round((v - e) k32 / 2^32): one multiply-accumulate per phase. */
    d->i_fast[x] = ps_hi_q(ps_mac_q(ps_acc_q(d->i_fast[x]), v - d->e[x], d->k32));
    d->sums.v_cap[x] += v;
}

/* The real-time modulator's duties for the step (pwm_rt.h): sub-step or sampled. */
static inline void rt_duties_plain(drive_segment *d, int32_t duty[3]) {
    pwm_rt_duties(&d->rt, d->cfg.modulator == DRIVE_MODULATOR_SAMPLED, d->s, duty);
}

/*
 * The same with the dead time, when there is one (the general path's): the
 * leg currents at t_k decide which edges it delays.
 */
static void rt_duties(drive_segment *d, int32_t duty[3]) {
    if (d->rt.kd == 0) {
        rt_duties_plain(d, duty);
    } else {
        const int32_t ia = d->ps.ph[0].i_l;
        const int32_t ib = d->ps.ph[1].i_l;
        const int32_t neg[3] = {ia < 0, ib < 0, ia + ib > 0};
        pwm_rt_substep_dt(&d->rt, neg, d->s, duty);
    }
}

/*
 * The real-time step (switching inverter, no dead time, mean or sampled
 * coupling, no faults): modulator, power stage, the motor's fast companion
 * and the frame sums, nothing else.
 */
static inline void fast_tick_plain(drive_segment *d) {
    power_stage_q *ps = &d->ps;
    ps_fast_q f;
    int32_t duty[3];
    rt_duties_plain(d, duty);
    ps_fast_begin_q(ps, duty, &f);
    fast_phase_plain(d, &f, 0);
    fast_phase_plain(d, &f, 1);
    ps_fast_end_q(ps, &d->in.battery, &f);
    d->sums.v_dc += ps->v_dc;
}

/* What the faults and a trip leave of each leg (leg_fault.h), by the filter currents. */
static void legs_faulted(const drive_segment *d, leg_state f[3]) {
    const int32_t i_l[3] = {d->ps.ph[0].i_l, d->ps.ph[1].i_l,
                            -d->ps.ph[0].i_l - d->ps.ph[1].i_l};
    const bool blocked = (d->trip != (uint8_t)DRIVE_TRIP_NONE);
    for (uint32_t x = 0u; x < 3u; x++) {
        f[x] = leg_fault_state(blocked, d->fault.switch_open, x, i_l[x] < 0);
    }
}

/* The real-time modulator's duties and leg states the faults leave (switching inverter). */
static void faulted_duties(drive_segment *d, int32_t duty[3]) {
    leg_state f[3];
    legs_faulted(d, f);
    for (uint32_t x = 0u; x < 3u; x++) {
        if (f[x] != LEG_MODULATED) {
            duty[x] = (f[x] == LEG_HIGH) ? PWM_RT_DUTY_ONE : 0;
        }
        if (duty[x] == 0 || duty[x] == PWM_RT_DUTY_ONE) {
            d->s[x] = (duty[x] != 0) ? 1 : 0;
        }
    }
}

/* The same on the general modulator's step (event inverter). */
static void faulted_pwm_out(const drive_segment *d, pwm_out_q *out) {
    leg_state f[3];
    legs_faulted(d, f);
    for (uint32_t x = 0u; x < 3u; x++) {
        if (f[x] != LEG_MODULATED) {
            out->duty[x] = (f[x] == LEG_HIGH) ? PWM_DUTY_ONE_Q : 0;
            out->state[x] = (f[x] == LEG_HIGH) ? 1u : 0u;
        }
    }
}

/*
 * Every other configuration: the general modulators, a moving EMF, the
 * filter coupling, faults, the energy audit. Kept out of line, so that its
 * registers do not crowd the real-time path's in drive_fast_tick().
 */
static void fast_tick_general(drive_segment *d) __attribute__((noinline));
static void fast_tick_general(drive_segment *d) {
    if (DRIVE_OPTIONAL(d->cfg.inverter == DRIVE_INVERTER_AVERAGED)) {
        return; /* the averaged layer's stage runs at the boundary (drive_medium_begin) */
    }
    if (!DRIVE_OPTIONAL(d->cfg.inverter == DRIVE_INVERTER_EVENT)) {
        /* The real-time step with the duties the faults leave: the
         * real-time path's results bit for bit when there are none. */
        int32_t duty[3];
        rt_duties(d, duty);
        faulted_duties(d, duty);
        ps_fast_step_call_q(&d->ps, &d->in.battery, duty, d->i_fast[0], d->i_fast[1]);
    } else {
        pwm_step_q(&d->pwm, &d->pout);
        faulted_pwm_out(d, &d->pout);
        d->in.duty[0] = d->pout.duty[0];
        d->in.duty[1] = d->pout.duty[1];
        d->in.duty[2] = d->pout.duty[2];
        d->in.i_motor[0] = stage_current_q15(d->i_fast[0]);
        d->in.i_motor[1] = stage_current_q15(d->i_fast[1]);
        power_stage_step_q(&d->ps, &d->in);
    }
    const power_stage_q *ps = d->stage;
    const int32_t va = ps->ph[0].v_c;
    const int32_t vb = ps->ph[1].v_c;
    /* The EMF moves in the extrapolating modes (e_step is zero otherwise). */
    d->e[0] += d->e_step[0];
    d->e[1] += d->e_step[1];
    d->i_fast[0] = fast_current_next(d, d->i_fast[0], va - d->e[0]);
    d->i_fast[1] = fast_current_next(d, d->i_fast[1], vb - d->e[1]);
    if (d->fault.phase_open != 0u) {
        open_phase_fast(d->i_fast, d->fault.phase_open);
    }
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        audit_fast(d);
    }
    d->sums.v_cap[0] += va;
    d->sums.v_cap[1] += vb;
    d->sums.v_dc += ps->v_dc;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        d->filt[0] += ((int64_t)va * 65536 - d->filt[0]) * (int64_t)d->filt_k / 65536;
        d->filt[1] += ((int64_t)vb * 65536 - d->filt[1]) * (int64_t)d->filt_k / 65536;
    }
}

void drive_fast_tick(drive_segment *d) {
    if (d->plain) {
        fast_tick_plain(d);
    } else {
        fast_tick_general(d);
    }
}

/* The real-time path on or off, and the step drive_fast_step() calls with it. */
static void plain_set(drive_segment *d, bool plain) {
    d->plain = plain;
    d->fast_now = (plain && d->kernel_ok) ? d->kernel : NULL;
}

void drive_use_fast_kernel(drive_segment *d, drive_fast_kernel *kernel) {
    d->kernel = kernel;
    plain_set(d, d->plain);
}

/* Applies requested faults at a slow boundary (fast context). */
static void faults_apply(drive_segment *d) {
    d->fault = d->fault_next;
    if (!DRIVE_AVERAGED(d)) {
        d->stage->k.neg_k_c = d->neg_k_c_next; /* the averaged layer's is in bus_next */
    }
    d->i_offset = d->i_offset_next;
    induction_motor_set_load_q(&d->motor, &d->load_next);
    if (d->fault.leg_short != 0u && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = (uint8_t)DRIVE_TRIP_LEG_SHORT;
    }
    d->fault_new = false;
}

/*
 * What the slow boundary changes besides the battery (fast context): the
 * faults and the trip the background requested. With neither requested
 * the real-time path stays as it is (plain is a function of plain_ok, the
 * faults and the trip, which only change here and in the latch).
 */
static void slow_boundary_apply(drive_segment *d) {
    if (!d->fault_new && d->trip_req == (uint8_t)DRIVE_TRIP_NONE) {
        return;
    }
    if (d->fault_new) {
        faults_apply(d);
    }
    if (d->trip_req != (uint8_t)DRIVE_TRIP_NONE && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = d->trip_req;
    }
    plain_set(d, d->plain_ok && d->fault.switch_open == 0u && d->fault.phase_open == 0u &&
                     d->trip == (uint8_t)DRIVE_TRIP_NONE);
}

/* What the motor task published takes effect (the latch; inline in the boundary's second half). */
static inline void latch_apply(drive_segment *d) {
    const drive_latch *o = &d->out;
    if (d->uv_req && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = (uint8_t)DRIVE_TRIP_UNDERVOLTAGE;
        plain_set(d, false);
    }
    pwm_rt_apply(&d->rt, &o->ramp);
    d->i_fast[0] += o->corr[0];
    d->i_fast[1] += o->corr[1];
    d->e[0] = o->e[0];
    d->e[1] = o->e[1];
    if (!d->plain) {
        d->e_step[0] = o->de[0];
        d->e_step[1] = o->de[1];
        if (d->out.cmd_new) {
            pwm_command_inc_q(d->mod, o->cmd.m, o->cmd.phase_inc);
            d->out.cmd_new = false;
        }
    }
}

void drive_medium_latch(drive_segment *d) { latch_apply(d); }

/* At a slow boundary: the battery companion waiting takes over (fast context). */
static inline void battery_take(drive_segment *d) {
    d->battery_new = false;
    d->battery_taken = true;
}

void drive_medium_publish(drive_segment *d) {
    if (DRIVE_AVERAGED(d)) {
        return; /* the averaged layer forms its frame in drive_medium_begin() */
    }
    drive_frame_sums *m = &d->medium_in;
    m->v_cap[0] = d->sums.v_cap[0];
    m->v_cap[1] = d->sums.v_cap[1];
    m->v_dc = d->sums.v_dc;
    m->v_mark[0] = d->stage->ph[0].v_c;
    m->v_mark[1] = d->stage->ph[1].v_c;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        m->filt_mark[0] = d->filt[0];
        m->filt_mark[1] = d->filt[1];
    }
    m->sat = d->stage->sat_count;
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        m->loss_l = d->sums.loss_l;
        m->loss_d = d->sums.loss_d;
        d->sums.loss_l = 0;
        d->sums.loss_d = 0;
    }
    d->sums.v_cap[0] = 0;
    d->sums.v_cap[1] = 0;
    d->sums.v_dc = 0;
}

/*
 * The averaged layer's frame: it is algebraic in what the latch just took
 * (the command, the motor currents at the frame's start), so the stage
 * runs here, ahead of the motor task that integrates it, then the slow
 * frame's battery changes; then the frame is published. With one step per
 * frame, the frame's mean, its last value and the filtered value coincide.
 * Kept out of line, so that its registers do not crowd the switching
 * path's boundary.
 */
__attribute__((noinline)) static void begin_averaged(drive_segment *d, bool slow_boundary) {
    inverter_qs_step_q(&d->qs, &d->bus, d->i_fast[0], d->i_fast[1]);
    if (slow_boundary && d->battery_new) {
        d->bus = d->bus_next;
        battery_take(d);
    }
    drive_frame_sums *m = &d->medium_in;
    for (int x = 0; x < 2; x++) {
        m->v_cap[x] = d->qs.u[x];
        m->v_mark[x] = d->qs.u[x];
        m->filt_mark[x] = (int64_t)d->qs.u[x] * 65536;
        m->i_mark[x] = d->i_fast[x];
    }
    m->v_dc = d->qs.v_dc;
    m->sat = d->qs.sat_count;
}

void drive_medium_begin(drive_segment *d, bool slow_boundary) {
    if (!d->staggered) {
        latch_apply(d);
    }
    if (slow_boundary) {
        slow_boundary_apply(d);
    }
    if (DRIVE_AVERAGED(d)) {
        begin_averaged(d, slow_boundary);
        return;
    }
    if (slow_boundary && d->battery_new) {
        /* One battery companion holds over each whole slow frame. */
        d->in.battery = d->battery_next;
        battery_take(d);
    }
    /* The fast current the frame starts from, corrections included. */
    d->medium_in.i_mark[0] = d->i_fast[0];
    d->medium_in.i_mark[1] = d->i_fast[1];
}

/*
 * The EMF of the frame just integrated and its change per fast step for
 * the extrapolating modes (see drive_segment.h), Q3.28 of 1024 V; the
 * value published is the one at the next frame's first step: extrapolated
 * modes start 1.5 frames after the centre of the frame it was computed
 * from, half a step early.
 */
static void emf_update(drive_segment *d, const q31_t v_mean[2], const q31_t i_end[2],
                       const int32_t corr[2]) {
    int32_t e[2];
    for (int x = 0; x < 2; x++) {
        int64_t di = (int64_t)i_end[x] - d->i_prev[x];
        int64_t drop = fp_shr_round_i64(di * d->e_mant, d->e_shift);
        e[x] = (int32_t)fp_sat_q31(fp_shr_round_i64(v_mean[x], 3u) - drop);
    }
    int32_t de[2] = {0, 0};
    if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_FOH)) {
        for (int x = 0; x < 2; x++) {
            de[x] = (int32_t)(((int64_t)e[x] - d->e_prev[x]) / (int64_t)d->cfg.fast_per_medium);
        }
    } else if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_DERIV)) {
        /* de/dt = w_s (e_c - e_b) / sqrt 3 for phase a, (e_a - e_c) / sqrt 3 for b. */
        q31_t g = fp_mul_q31(d->cmd.freq, d->k_deriv);
        de[0] = (int32_t)fp_shr_round_i64(((int64_t)-e[0] - 2 * (int64_t)e[1]) * g, 31u);
        de[1] = (int32_t)fp_shr_round_i64((2 * (int64_t)e[0] + (int64_t)e[1]) * g, 31u);
    }
    int64_t ahead = 3 * (int64_t)d->cfg.fast_per_medium / 2 - 1;
    for (int x = 0; x < 2; x++) {
        /* The drift correction, spread over the frame: corr / (k_l N) volts less. */
        int64_t steer = fp_shr_round_i64((int64_t)corr[x] * 8 * d->e_mant, d->e_shift);
        d->out.e[x] = (int32_t)fp_sat_q31((int64_t)e[x] + (int64_t)de[x] * ahead - steer);
        d->out.de[x] = de[x];
        d->e_prev[x] = e[x];
    }
}

/*
 * The energy audit's motor copper losses over one step [J], in double from
 * the observed state (the audit is a desk tool), with the currents at the
 * step's end. In the averaged layer the stator resistance includes the
 * filter's R_L (inverter_avg.h), so its filter losses count here. Out of
 * line: its observation stays off the motor task's frame when unused.
 */
static double motor_loss_j(const induction_motor_q *m) __attribute__((noinline));
static double motor_loss_j(const induction_motor_q *m) {
    induction_motor_obs o;
    induction_motor_observe_q(m, &o);
    return m->c.h_s * induction_motor_copper_loss_f64(&m->c, &o);
}

/* The slow frame's sums, one motor frame at a time. */
static void slow_sums_add(drive_segment *d, const drive_frame_sums *s, const q31_t i_end[2]) {
    drive_slow_sums *w = &d->slow;
    int64_t n = (int64_t)d->cfg.fast_per_medium;
    /* Frame mean of v_dc (Q3.28) and its square: the ripple's variance, about
     * 1e-6 of the square, is left out of the battery's power. */
    int64_t vdc_mean = s->v_dc / n;
    w->v_dc += s->v_dc;
    w->v_dc_sq += fp_shr_floor_i64(vdc_mean * vdc_mean, 28u) * n;
    w->fast_n += d->cfg.fast_per_medium;
    w->w += d->mout.w;
    w->te += d->mout.te;
    q15_t i15[3] = {fp_narrow_q15(i_end[0]), fp_narrow_q15(i_end[1]),
                    fp_narrow_q15(d->mout.i_c)};
    for (int x = 0; x < 3; x++) {
        w->i_sq[x] += (int64_t)i15[x] * i15[x];
    }
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        w->loss_l += s->loss_l;
        w->loss_d += s->loss_d;
        w->e_loss_motor_j += motor_loss_j(&d->motor);
    }
    w->p_mech += fp_shr_round_i64((int64_t)d->mout.te * (int64_t)d->mout.w, 31u);
    w->medium_n++;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        /* Time constant: the slow frame. */
        d->w_filt += (q31_t)(((int64_t)d->mout.w - d->w_filt) / (int64_t)d->cfg.medium_per_slow);
    }
}

void drive_medium_task(drive_segment *d, bool control_due, bool slow_boundary) {
    const drive_frame_sums *s = &d->medium_in;
    uint32_t n = d->cfg.fast_per_medium;
    uint32_t sat = 0u;
    /* Q3.28 sums to Q31 means: three bits up. */
    induction_motor_in_q min;
    if (d->cfg.up == COUPLE_AVG) {
        min.v_a = mean_q31(s->v_cap[0], 3u, n, &sat);
        min.v_b = mean_q31(s->v_cap[1], 3u, n, &sat);
    } else if (d->cfg.up == COUPLE_SAMPLE) {
        min.v_a = fp_sat_cnt_q31((int64_t)s->v_mark[0] * 8, &sat);
        min.v_b = fp_sat_cnt_q31((int64_t)s->v_mark[1] * 8, &sat);
    } else {
        min.v_a = fp_sat_cnt_q31(fp_shr_round_i64(s->filt_mark[0], 13u), &sat);
        min.v_b = fp_sat_cnt_q31(fp_shr_round_i64(s->filt_mark[1], 13u), &sat);
    }
    min.v_c = fp_sat_q31(-(int64_t)min.v_a - (int64_t)min.v_b);
    induction_motor_step_q(&d->motor, &min, &d->mout);
    if (d->fault.phase_open != 0u) {
        induction_motor_open_phase_q(&d->motor, d->fault.phase_open - 1u, &d->mout);
    }
    q31_t i_end[2] = {d->mout.i_a, d->mout.i_b};
    q31_t v_mean[2] = {min.v_a, min.v_b};
    /* Motor minus fast current at the frame end (Q31 to the companion's Q3.28:
     * three bits down): the fast companion steers it out over the next frame
     * through its EMF, the averaged layer (no companion) takes it at once. */
    int32_t corr[2];
    for (int x = 0; x < 2; x++) {
        corr[x] = fp_shr_round_i32(i_end[x], 3u) - s->i_mark[x];
        if (!DRIVE_AVERAGED(d)) {
            /* Less what the last correction has still to bring after the mark. */
            const int64_t pending = (int64_t)d->corr_prev[x] * (int64_t)d->corr_pending;
            corr[x] -= (int32_t)(pending / (int64_t)n);
            d->corr_prev[x] = corr[x];
        }
    }
    if (!DRIVE_AVERAGED(d)) {
        emf_update(d, v_mean, i_end, corr);
    }
    for (int x = 0; x < 2; x++) {
        d->out.corr[x] = !DRIVE_AVERAGED(d) ? 0 : corr[x];
        d->i_prev[x] = i_end[x];
    }
    slow_sums_add(d, s, i_end);
    if (control_due) {
        /* The controller's last result becomes the command; its next inputs are latched. */
        if (d->ctl_done) {
            d->cmd = d->ctl_out;
            d->ctl_sat_taken = d->ctl_sat;
            d->ctl_done = false;
            d->out.cmd = d->cmd;
            d->out.cmd_new = true;
        }
        if ((d->cmd.flags & DRIVE_CONTROL_FLAG_SLIP_LIMIT) != 0u) {
            d->slow.limit_n++;
        }
        d->ctl_in.speed_cmd = d->speed_cmd;
        d->ctl_in.w = d->mout.w;
        d->ctl_in.i_a = fp_sat_q31((int64_t)i_end[0] + d->i_offset);
        d->ctl_in.i_b = i_end[1];
        d->ctl_in.i_c = d->mout.i_c;
        d->ctl_in.vdc = mean_q31(s->v_dc, 3u, n, &sat);
    }
    /* Under-voltage protection on the frame's mean DC-link voltage. */
    if (s->v_dc < (int64_t)d->uv_q28 * (int64_t)n) {
        d->uv_req = true;
    }
    /* The next frame's references: exact at both ends, the chord between. */
    if (d->cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        pwm_rt_ramp_q(&d->out.ramp, d->cmd.m, d->ref_ph, d->cmd.phase_inc, n);
        d->ref_ph += d->cmd.phase_inc * n;
    }
    d->ps_clamps += sat;
    if (slow_boundary) {
        /* Which battery companion held over the slow frame just ended, and which holds now. */
        d->bat_done = d->bat_in_force;
        if (d->battery_taken) {
            d->bat_in_force = d->bat_next;
            d->battery_taken = false;
        }
        drive_slow_sums *w = &d->slow;
        w->w_filt = d->w_filt;
        w->w_end = d->mout.w;
        w->v_dc_end = stage_v_dc(d);
        w->cmd = d->cmd;
        w->trip = d->trip;
        w->saturations = s->sat + d->pwm.sat_count + d->qs.mod.sat_count + d->motor.sat_count +
                         d->ctl_sat_taken + d->ps_clamps;
        d->slow_out = *w;
        *w = (drive_slow_sums){0};
    }
}

void drive_control_task(drive_segment *d) {
    drive_control_step_q(&d->ctl, &d->ctl_in, &d->ctl_out);
    d->ctl_sat = d->ctl.sat_count;
    d->ctl_done = true;
}

void drive_slow_measure(const drive_segment *d, drive_slow_meas *meas) {
    const drive_slow_sums *w = &d->slow_out;
    meas->battery = d->bat_done;
    double nf = (w->fast_n > 0u) ? (double)w->fast_n : 1.0;
    double nm = (w->medium_n > 0u) ? (double)w->medium_n : 1.0;
    double medium_s = 1e-9 * (double)d->cfg.fast_ns * (double)d->cfg.fast_per_medium;
    meas->v_dc_mean_v = (double)w->v_dc / nf / Q28_ONE * DRIVE_BASE_VOLTAGE_V;
    meas->v_dc_sq_mean_v2 = (double)w->v_dc_sq / nf / Q28_ONE * DRIVE_BASE_VOLTAGE_V *
                            DRIVE_BASE_VOLTAGE_V;
    double w_avg = (double)w->w / nm / Q31_ONE * DRIVE_BASE_SPEED_RADPS;
    double w_now = (double)w->w_end / Q31_ONE * DRIVE_BASE_SPEED_RADPS;
    double w_filt = (double)w->w_filt / Q31_ONE * DRIVE_BASE_SPEED_RADPS;
    meas->shaft_radps = (d->cfg.up == COUPLE_AVG)      ? w_avg
                        : DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER) ? w_filt
                                                       : w_now;
    meas->shaft_end_radps = w_now;
    meas->te_nm = (double)w->te / nm / Q31_ONE * DRIVE_BASE_TORQUE_NM;
    double i_sq = 0.0;
    for (int x = 0; x < 3; x++) {
        double sq = (double)w->i_sq[x] / nm / (32768.0 * 32768.0);
        meas->i_phase_rms_a[x] = math_sqrt_f64(sq) * DRIVE_BASE_CURRENT_A;
        i_sq += sq / 3.0;
    }
    meas->i_rms_a = math_sqrt_f64(i_sq) * DRIVE_BASE_CURRENT_A;
    /* The audit's sums are of A^2 2^16 per fast step. */
    double fast_s = 1e-9 * (double)d->cfg.fast_ns;
    meas->e_loss_filter_j = (d->ps_params.r_l_ohm * (double)w->loss_l +
                             d->ps_params.r_d_ohm * (double)w->loss_d) / 65536.0 * fast_s;
    meas->e_loss_motor_j = w->e_loss_motor_j;
    meas->limit_s = (double)w->limit_n * medium_s * (double)d->cfg.medium_per_control;
    meas->v_dc_v = (double)w->v_dc_end / Q28_ONE * DRIVE_BASE_VOLTAGE_V;
    meas->m_index = (double)w->cmd.m / 32768.0;
    meas->f_hz = (double)w->cmd.freq / Q31_ONE * DRIVE_BASE_FREQ_HZ;
    meas->e_mech_j = (double)w->p_mech / Q31_ONE * DRIVE_BASE_TORQUE_NM *
                     DRIVE_BASE_SPEED_RADPS * medium_s;
    meas->saturations = w->saturations;
    meas->trip = (drive_trip)w->trip;
}

void drive_fault_request(drive_segment *d, const drive_faults *f) {
    power_stage_q scratch;
    power_stage_params faulted = d->ps_params;
    d->fault_next = *f;
    faulted.c_dc_f = d->cfg.stage->c_dc_f * f->dc_cap_frac;
    if (DRIVE_AVERAGED(d)) {
        /* The averaged layer: the bus constants fold the capacitance in;
         * they take effect at the next slow boundary, with the fault. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->ps_clamps += inverter_qs_battery_q(&d->qs, d->ps_params.c_dc_f, d->bat_next.g_s,
                                              d->bat_next.b_a, &d->bus_next);
        d->battery_new = true;
    } else if (power_stage_init_q(&scratch, &faulted, d->stage->step_ns, 600.0) == PS_OK) {
        /* The stage's set-up forms the DC-link coefficient for the new
         * capacitance; a capacitance it refuses leaves the one in force. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->neg_k_c_next = scratch.k.neg_k_c;
    } else {
        d->neg_k_c_next = d->stage->k.neg_k_c;
    }
    d->i_offset_next = fp_from_f64_q31(f->current_offset_a / DRIVE_BASE_CURRENT_A);
    if (induction_motor_load_q(&d->motor, f->load_factor, &d->load_next) != INDUCTION_MOTOR_OK) {
        (void)induction_motor_load_q(&d->motor, 1.0, &d->load_next);
    }
    d->fault_new = true;
}

void drive_trip_request(drive_segment *d, drive_trip why) {
    d->trip_req = (uint8_t)why;
}

void drive_battery_next(drive_segment *d, const drive_battery *next) {
    d->bat_next = *next;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += inverter_qs_battery_q(&d->qs, d->ps_params.c_dc_f, next->g_s, next->b_a,
                                              &d->bus_next);
    } else {
        d->ps_clamps += power_stage_battery_q(d->stage, next->g_s, next->b_a, &d->battery_next);
    }
    d->battery_new = true;
}

void drive_start(drive_segment *d, const drive_battery *battery) {
    d->bat_next = d->bat_in_force = d->bat_done = *battery;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += inverter_qs_battery_q(&d->qs, d->ps_params.c_dc_f, battery->g_s,
                                              battery->b_a, &d->bus);
        d->bus_next = d->bus;
        return;
    }
    d->ps_clamps +=
        power_stage_battery_q(d->stage, battery->g_s, battery->b_a, &d->in.battery);
    d->battery_next = d->in.battery;
}

void drive_speed_command(drive_segment *d, double speed_radps) {
    d->speed_cmd = fp_from_f64_q31(speed_radps / DRIVE_BASE_SPEED_RADPS);
}

/* The trace row of the averaged layer: no switching, the terminals are the inverter's. */
static void trace_averaged(const drive_segment *d, drive_trace_row *row) {
    const double v = DRIVE_BASE_VOLTAGE_V / Q28_ONE;
    const double a = DRIVE_BASE_CURRENT_A / Q28_ONE;
    row->s[0] = row->s[1] = row->s[2] = 0u;
    row->m_index = (double)d->cmd.m / 32768.0;
    row->f_hz = (double)d->cmd.freq / Q31_ONE * DRIVE_BASE_FREQ_HZ;
    row->v_dc = (double)d->qs.v_dc * v;
    for (int x = 0; x < 2; x++) {
        row->v_inv[x] = row->v_cap[x] = (double)d->qs.u[x] * v;
        row->i_motor[x] = (double)d->i_fast[x] * a;
    }
    row->v_inv[2] = row->v_cap[2] = -row->v_inv[0] - row->v_inv[1];
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->i_dc = (double)d->qs.i_dc * a;
    row->n_rpm = (double)d->mout.n_rpm_q16 / 65536.0;
    row->te_nm = (double)d->mout.te / Q31_ONE * DRIVE_BASE_TORQUE_NM;
}

void drive_trace(const drive_segment *d, drive_trace_row *row) {
    const power_stage_q *ps = d->stage;
    const double v = DRIVE_BASE_VOLTAGE_V / Q28_ONE;
    if (ps == NULL) {
        /* The averaged layer: inverter and terminal voltages are one. */
        trace_averaged(d, row);
        return;
    }
    bool rt = (d->cfg.inverter == DRIVE_INVERTER_SWITCHING);
    for (int x = 0; x < 3; x++) {
        row->s[x] = rt ? (uint8_t)d->s[x] : d->pout.state[x];
    }
    row->m_index = (double)d->cmd.m / 32768.0;
    row->f_hz = (double)d->cmd.freq / Q31_ONE * DRIVE_BASE_FREQ_HZ;
    row->v_dc = (double)ps->v_dc * v;
    row->v_inv[0] = (double)ps->u[0] * v;
    row->v_inv[1] = (double)ps->u[1] * v;
    row->v_inv[2] = -row->v_inv[0] - row->v_inv[1];
    row->v_cap[0] = (double)ps->ph[0].v_c * v;
    row->v_cap[1] = (double)ps->ph[1].v_c * v;
    row->v_cap[2] = -row->v_cap[0] - row->v_cap[1];
    for (int x = 0; x < 2; x++) {
        row->i_motor[x] = (double)d->i_fast[x] / Q28_ONE * DRIVE_BASE_CURRENT_A;
    }
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->i_dc = (double)ps->i_dc / Q28_ONE * DRIVE_BASE_CURRENT_A;
    row->n_rpm = (double)d->mout.n_rpm_q16 / 65536.0;
    row->te_nm = (double)d->mout.te / Q31_ONE * DRIVE_BASE_TORQUE_NM;
}

double drive_shaft_radps(const drive_segment *d) {
    return (double)d->motor.w / Q31_ONE * DRIVE_BASE_SPEED_RADPS;
}

#else
/* The float build uses drive_segment_float.c; ISO C wants a declaration here. */
typedef int drive_segment_fixed_unused;
#endif

/*
 * The drive segment of the float build (see drive_segment.h): the same
 * data flow as drive_segment_fixed.c, in single precision and SI units.
 * Sums over a motor frame (at most a few hundred fast steps) are float; the
 * motor task adds them into double sums for the slow frame.
 */
#include "drive_segment.h"

#if UUV_NUMERIC == UUV_NUMERIC_FLOAT

#include <stddef.h>

#include "math/umath.h"
#include "models/drive/inverter/leg_fault.h"
#include "models/drive/inverter/power_stage_fast.h"

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
        if (inverter_qs_init_f32(&d->qs, &pwm_p, cfg->fast_ns, cfg->v_dc0_v) !=
            INVERTER_AVG_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->qs.mod;
        d->stage = NULL;
        /* The filter's series branch joins the stator (inverter_avg.h). */
        mp.rs_ohm += d->ps_params.r_l_ohm;
        mp.lls_h += d->ps_params.l_h;
    } else {
        if (pwm_init_f32(&d->pwm, &pwm_p, cfg->fast_ns) != PWM_OK) {
            return DRIVE_ERR_MODEL;
        }
        pwm_p.edges = PWM_EDGES_SAMPLED;
        if (pwm_rt_init(&d->rt, &pwm_p, cfg->fast_ns) != PWM_OK ||
            pwm_rt_dead_time(&d->rt, cfg->dead_time_ns, cfg->fast_ns) != PWM_OK ||
            power_stage_init_f32(&d->ps, &d->ps_params, cfg->fast_ns,
                                 cfg->v_dc0_v) != PS_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->pwm;
        d->stage = &d->ps;
    }
    if (induction_motor_init_f32(&d->motor, &mp, prop, medium_s) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    double k_l = d->motor.c.a_ss * fast_s;
    if (!(k_l > 1e-6 / 32.0 && k_l < 2.0)) {
        return DRIVE_ERR_CONFIG;
    }
    d->k_l = (float)k_l;
    d->e_per_di = (float)(1.0 / (k_l * (double)cfg->fast_per_medium));
    d->ctl_params = *cfg->control;
    d->ctl_params.step_s = medium_s * (double)cfg->medium_per_control;
    d->ctl_params.pwm_step_s = 1e-9 * (double)mod_ns;
    if (drive_control_init_f32(&d->ctl, &d->ctl_params) != DRIVE_CONTROL_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->filt_k = 1.0f / (float)cfg->fast_per_medium;
    d->k_deriv = (float)(MATH_TWO_PI_F64 * fast_s / 1.7320508075688772);
    d->plain_ok = (cfg->inverter == DRIVE_INVERTER_SWITCHING) && (cfg->dead_time_ns == 0u) &&
               (cfg->down == COUPLE_ZOH || cfg->down == COUPLE_STAGGER) &&
               (cfg->up != COUPLE_FILTER) && !cfg->energy_audit;
    d->kernel_ok = (cfg->modulator == DRIVE_MODULATOR_SAMPLED);
    d->plain = d->plain_ok;
    d->staggered = drive_staggered(cfg->down, cfg->fast_per_medium);
    const uint32_t half = cfg->fast_per_medium / 2u;
    d->corr_pending = d->staggered ? (float)half / (float)cfg->fast_per_medium : 1.0f;
    if (induction_motor_load_f32(&d->motor, 1.0, &d->load_next) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->neg_k_c_next = averaged ? 0.0f : d->stage->k.neg_k_c;
    return DRIVE_OK;
}

/* The DC-link voltage of the stage in use [V], whichever it is. */
static float stage_v_dc(const drive_segment *d) {
    return !DRIVE_AVERAGED(d) ? d->stage->v_dc : d->qs.v_dc;
}


/* Filter phase x of the real-time step, its companion and its sum (as in the fixed twin). */
static inline void fast_phase_plain(drive_segment *d, ps_fast_f32 *f, int x) {
    power_stage_f32 *ps = &d->ps;
    ps_fast_phase_f32(ps, f, x, d->i_fast[x]);
    const float v = ps->ph[x].v_c;
    d->i_fast[x] += (v - d->e[x]) * d->k_l;
    d->sums.v_cap[x] += v;
}

/* The real-time modulator's duties for the step (pwm_rt.h): sub-step or sampled. */
static inline void rt_duties_plain(drive_segment *d, int32_t duty[3]) {
    pwm_rt_duties(&d->rt, d->cfg.modulator == DRIVE_MODULATOR_SAMPLED, d->s, duty);
}

/* The same with the dead time, when there is one (the general path's). */
static void rt_duties(drive_segment *d, int32_t duty[3]) {
    if (d->rt.kd == 0) {
        rt_duties_plain(d, duty);
    } else {
        const float ia = d->ps.ph[0].i_l;
        const float ib = d->ps.ph[1].i_l;
        const int32_t neg[3] = {ia < 0.0f, ib < 0.0f, -ia - ib < 0.0f};
        pwm_rt_substep_dt(&d->rt, neg, d->s, duty);
    }
}

/* The real-time step (as in drive_segment_fixed.c). */
static inline void fast_tick_plain(drive_segment *d) {
    power_stage_f32 *ps = &d->ps;
    ps_fast_f32 f;
    int32_t duty[3];
    rt_duties_plain(d, duty);
    ps_fast_begin_f32(ps, duty, &f);
    fast_phase_plain(d, &f, 0);
    fast_phase_plain(d, &f, 1);
    ps_fast_end_f32(ps, &d->in.battery, &f);
    d->sums.v_dc += ps->v_dc;
}

/* An open motor phase in the fast companion (as in drive_segment_fixed.c). */
static void open_phase_fast(float i[2], uint8_t phase) {
    if (phase == 1u) {
        i[1] += 0.5f * i[0];
        i[0] = 0.0f;
    } else if (phase == 2u) {
        i[0] += 0.5f * i[1];
        i[1] = 0.0f;
    } else {
        i[0] = 0.5f * (i[0] - i[1]);
        i[1] = -i[0];
    }
}

/* The energy audit's fast sums [A^2] (as in drive_segment_fixed.c). */
static void audit_fast(drive_segment *d) {
    const power_stage_f32 *ps = d->stage;
    const float l2 = -ps->ph[0].i_l - ps->ph[1].i_l;
    const float r2 = -ps->ph[0].i_d - ps->ph[1].i_d;
    d->sums.loss_l += ps->ph[0].i_l * ps->ph[0].i_l + ps->ph[1].i_l * ps->ph[1].i_l + l2 * l2;
    d->sums.loss_d += ps->ph[0].i_d * ps->ph[0].i_d + ps->ph[1].i_d * ps->ph[1].i_d + r2 * r2;
}

/* What the faults and a trip leave of each leg (leg_fault.h), by the filter currents. */
static void legs_faulted(const drive_segment *d, leg_state f[3]) {
    const float i_l[3] = {d->ps.ph[0].i_l, d->ps.ph[1].i_l, -d->ps.ph[0].i_l - d->ps.ph[1].i_l};
    const bool blocked = (d->trip != (uint8_t)DRIVE_TRIP_NONE);
    for (uint32_t x = 0u; x < 3u; x++) {
        f[x] = leg_fault_state(blocked, d->fault.switch_open, x, i_l[x] < 0.0f);
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
static void faulted_pwm_out(const drive_segment *d, pwm_out_f32 *out) {
    leg_state f[3];
    legs_faulted(d, f);
    for (uint32_t x = 0u; x < 3u; x++) {
        if (f[x] != LEG_MODULATED) {
            out->duty[x] = (f[x] == LEG_HIGH) ? 1.0f : 0.0f;
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
        /* As in drive_segment_fixed.c: the real-time step with the faults' duties. */
        int32_t duty[3];
        rt_duties(d, duty);
        faulted_duties(d, duty);
        ps_fast_step_call_f32(&d->ps, &d->in.battery, duty, d->i_fast[0], d->i_fast[1]);
    } else {
        pwm_step_f32(&d->pwm, &d->pout);
        faulted_pwm_out(d, &d->pout);
        d->in.duty[0] = d->pout.duty[0];
        d->in.duty[1] = d->pout.duty[1];
        d->in.duty[2] = d->pout.duty[2];
        d->in.i_motor_a[0] = d->i_fast[0];
        d->in.i_motor_a[1] = d->i_fast[1];
        power_stage_step_f32(&d->ps, &d->in);
    }
    const power_stage_f32 *ps = d->stage;
    const float va = ps->ph[0].v_c;
    const float vb = ps->ph[1].v_c;
    d->e[0] += d->e_step[0];
    d->e[1] += d->e_step[1];
    d->i_fast[0] += (va - d->e[0]) * d->k_l;
    d->i_fast[1] += (vb - d->e[1]) * d->k_l;
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
        d->filt[0] += (va - d->filt[0]) * d->filt_k;
        d->filt[1] += (vb - d->filt[1]) * d->filt_k;
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

static void faults_apply(drive_segment *d) {
    d->fault = d->fault_next;
    if (!DRIVE_AVERAGED(d)) {
        d->stage->k.neg_k_c = d->neg_k_c_next; /* the averaged layer's is in bus_next */
    }
    d->i_offset = d->i_offset_next;
    induction_motor_set_load_f32(&d->motor, &d->load_next);
    if (d->fault.leg_short != 0u && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = (uint8_t)DRIVE_TRIP_LEG_SHORT;
    }
    d->fault_new = false;
}

/* What the slow boundary changes besides the battery (as in drive_segment_fixed.c). */
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
            pwm_command_inc_f32(d->mod, o->cmd.m, o->cmd.phase_inc);
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
        d->sums.loss_l = 0.0f;
        d->sums.loss_d = 0.0f;
    }
    d->sums.v_cap[0] = 0.0f;
    d->sums.v_cap[1] = 0.0f;
    d->sums.v_dc = 0.0f;
}

/* The averaged layer's frame, as in drive_segment_fixed.c (out of line, as there). */
__attribute__((noinline)) static void begin_averaged(drive_segment *d, bool slow_boundary) {
    inverter_qs_step_f32(&d->qs, &d->bus, d->i_fast[0], d->i_fast[1]);
    if (slow_boundary && d->battery_new) {
        d->bus = d->bus_next;
        battery_take(d);
    }
    drive_frame_sums *m = &d->medium_in;
    for (int x = 0; x < 2; x++) {
        m->v_cap[x] = d->qs.u[x];
        m->v_mark[x] = d->qs.u[x];
        m->filt_mark[x] = d->qs.u[x];
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
    d->medium_in.i_mark[0] = d->i_fast[0];
    d->medium_in.i_mark[1] = d->i_fast[1];
}

/* As in drive_segment_fixed.c: the frame's EMF and its change per fast step [V]. */
static void emf_update(drive_segment *d, const float v_mean[2], const float i_end[2],
                       const float corr[2]) {
    float e[2];
    for (int x = 0; x < 2; x++) {
        e[x] = v_mean[x] - (i_end[x] - d->i_prev[x]) * d->e_per_di;
    }
    float de[2] = {0.0f, 0.0f};
    if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_FOH)) {
        float k = 1.0f / (float)d->cfg.fast_per_medium;
        de[0] = (e[0] - d->e_prev[0]) * k;
        de[1] = (e[1] - d->e_prev[1]) * k;
    } else if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_DERIV)) {
        float g = d->cmd.freq_hz * d->k_deriv;
        de[0] = (-e[0] - 2.0f * e[1]) * g;
        de[1] = (2.0f * e[0] + e[1]) * g;
    }
    float ahead = 1.5f * (float)d->cfg.fast_per_medium - 1.0f;
    for (int x = 0; x < 2; x++) {
        /* The drift correction, spread over the frame (drive_segment_fixed.c). */
        d->out.e[x] = (e[x] + de[x] * ahead) - corr[x] * d->e_per_di;
        d->out.de[x] = de[x];
        d->e_prev[x] = e[x];
    }
}

/* The energy audit's motor copper losses over one step [J] (as in drive_segment_fixed.c). */
static double motor_loss_j(const induction_motor_f32 *m) __attribute__((noinline));
static double motor_loss_j(const induction_motor_f32 *m) {
    induction_motor_obs o;
    induction_motor_observe_f32(m, &o);
    return m->c.h_s * induction_motor_copper_loss_f64(&m->c, &o);
}

static void slow_sums_add(drive_segment *d, const drive_frame_sums *s, const float i_end[2]) {
    drive_slow_sums *w = &d->slow;
    float n = (float)d->cfg.fast_per_medium;
    double vdc_mean = (double)(s->v_dc / n);
    w->v_dc += (double)s->v_dc;
    w->v_dc_sq += vdc_mean * vdc_mean * (double)n;
    w->fast_n += d->cfg.fast_per_medium;
    w->w += (double)d->mout.w_radps;
    w->te += (double)d->mout.te_nm;
    const float i3[3] = {i_end[0], i_end[1], d->mout.i_c};
    for (int x = 0; x < 3; x++) {
        const float sq = i3[x] * i3[x];
        w->i_sq[x] += (double)sq;
    }
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        w->loss_l += (double)s->loss_l;
        w->loss_d += (double)s->loss_d;
        w->e_loss_motor_j += motor_loss_j(&d->motor);
    }
    w->p_mech += (double)(d->mout.te_nm * d->mout.w_radps);
    w->medium_n++;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        d->w_filt += (d->mout.w_radps - d->w_filt) / (float)d->cfg.medium_per_slow;
    }
}

void drive_medium_task(drive_segment *d, bool control_due, bool slow_boundary) {
    const drive_frame_sums *s = &d->medium_in;
    uint32_t n = d->cfg.fast_per_medium;
    float inv_n = 1.0f / (float)n;
    induction_motor_in_f32 min;
    if (d->cfg.up == COUPLE_AVG) {
        min.v_a = s->v_cap[0] * inv_n;
        min.v_b = s->v_cap[1] * inv_n;
    } else if (d->cfg.up == COUPLE_SAMPLE) {
        min.v_a = s->v_mark[0];
        min.v_b = s->v_mark[1];
    } else {
        min.v_a = s->filt_mark[0];
        min.v_b = s->filt_mark[1];
    }
    min.v_c = -min.v_a - min.v_b;
    induction_motor_step_f32(&d->motor, &min, &d->mout);
    if (d->fault.phase_open != 0u) {
        induction_motor_open_phase_f32(&d->motor, d->fault.phase_open - 1u, &d->mout);
    }
    float i_end[2] = {d->mout.i_a, d->mout.i_b};
    float v_mean[2] = {min.v_a, min.v_b};
    /* Motor minus fast current at the frame end (as in drive_segment_fixed.c). */
    float corr[2];
    for (int x = 0; x < 2; x++) {
        corr[x] = i_end[x] - s->i_mark[x];
        if (!DRIVE_AVERAGED(d)) {
            /* Less what the last correction has still to bring (drive_segment_fixed.c). */
            corr[x] -= d->corr_prev[x] * d->corr_pending;
            d->corr_prev[x] = corr[x];
        }
    }
    if (!DRIVE_AVERAGED(d)) {
        emf_update(d, v_mean, i_end, corr);
    }
    for (int x = 0; x < 2; x++) {
        d->out.corr[x] = !DRIVE_AVERAGED(d) ? 0.0f : corr[x];
        d->i_prev[x] = i_end[x];
    }
    slow_sums_add(d, s, i_end);
    if (control_due) {
        if (d->ctl_done) {
            d->cmd = d->ctl_out;
            d->ctl_done = false;
            d->out.cmd = d->cmd;
            d->out.cmd_new = true;
        }
        if ((d->cmd.flags & DRIVE_CONTROL_FLAG_SLIP_LIMIT) != 0u) {
            d->slow.limit_n++;
        }
        d->ctl_in.speed_cmd_radps = d->speed_cmd;
        d->ctl_in.w_radps = d->mout.w_radps;
        d->ctl_in.i_a = i_end[0] + d->i_offset;
        d->ctl_in.i_b = i_end[1];
        d->ctl_in.i_c = d->mout.i_c;
        d->ctl_in.vdc_v = s->v_dc * inv_n;
    }
    if (s->v_dc * inv_n < (float)DRIVE_UV_TRIP_V) {
        d->uv_req = true;
    }
    if (d->cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        pwm_rt_ramp_f32(&d->out.ramp, d->cmd.m, d->ref_ph, d->cmd.phase_inc, n);
        d->ref_ph += d->cmd.phase_inc * n;
    }
    if (slow_boundary) {
        d->bat_done = d->bat_in_force;
        if (d->battery_taken) {
            d->bat_in_force = d->bat_next;
            d->battery_taken = false;
        }
        drive_slow_sums *w = &d->slow;
        w->w_filt = d->w_filt;
        w->w_end = d->mout.w_radps;
        w->v_dc_end = stage_v_dc(d);
        w->cmd = d->cmd;
        w->trip = d->trip;
        w->saturations = s->sat + d->pwm.sat_count + d->qs.mod.sat_count + d->ps_clamps;
        d->slow_out = *w;
        *w = (drive_slow_sums){0};
    }
}

void drive_control_task(drive_segment *d) {
    drive_control_step_f32(&d->ctl, &d->ctl_in, &d->ctl_out);
    d->ctl_done = true; /* the float controller counts no saturations */
}

void drive_slow_measure(const drive_segment *d, drive_slow_meas *meas) {
    const drive_slow_sums *w = &d->slow_out;
    meas->battery = d->bat_done;
    double nf = (w->fast_n > 0u) ? (double)w->fast_n : 1.0;
    double nm = (w->medium_n > 0u) ? (double)w->medium_n : 1.0;
    double medium_s = 1e-9 * (double)d->cfg.fast_ns * (double)d->cfg.fast_per_medium;
    meas->v_dc_mean_v = w->v_dc / nf;
    meas->v_dc_sq_mean_v2 = w->v_dc_sq / nf;
    meas->shaft_radps = (d->cfg.up == COUPLE_AVG)      ? w->w / nm
                        : DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER) ? (double)w->w_filt
                                                       : (double)w->w_end;
    meas->shaft_end_radps = (double)w->w_end;
    meas->te_nm = w->te / nm;
    double i_sq = 0.0;
    for (int x = 0; x < 3; x++) {
        meas->i_phase_rms_a[x] = math_sqrt_f64(w->i_sq[x] / nm);
        i_sq += w->i_sq[x] / nm / 3.0;
    }
    meas->i_rms_a = math_sqrt_f64(i_sq);
    double fast_s = 1e-9 * (double)d->cfg.fast_ns;
    meas->e_loss_filter_j =
        (d->ps_params.r_l_ohm * w->loss_l + d->ps_params.r_d_ohm * w->loss_d) * fast_s;
    meas->e_loss_motor_j = w->e_loss_motor_j;
    meas->limit_s = (double)w->limit_n * medium_s * (double)d->cfg.medium_per_control;
    meas->v_dc_v = (double)w->v_dc_end;
    meas->m_index = (double)w->cmd.m;
    meas->f_hz = (double)w->cmd.freq_hz;
    meas->e_mech_j = w->p_mech * medium_s;
    meas->saturations = w->saturations;
    meas->trip = (drive_trip)w->trip;
}

void drive_fault_request(drive_segment *d, const drive_faults *f) {
    power_stage_f32 scratch;
    power_stage_params faulted = d->ps_params;
    d->fault_next = *f;
    faulted.c_dc_f = d->cfg.stage->c_dc_f * f->dc_cap_frac;
    if (DRIVE_AVERAGED(d)) {
        /* As in drive_segment_fixed.c: the bus constants fold the capacitance in. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->ps_clamps += inverter_qs_battery_f32(&d->qs, d->ps_params.c_dc_f, d->bat_next.g_s,
                                                d->bat_next.b_a, &d->bus_next);
        d->battery_new = true;
    } else if (power_stage_init_f32(&scratch, &faulted, d->stage->step_ns, 600.0) == PS_OK) {
        /* As in drive_segment_fixed.c: a refused capacitance leaves the one in force. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->neg_k_c_next = scratch.k.neg_k_c;
    } else {
        d->neg_k_c_next = d->stage->k.neg_k_c;
    }
    d->i_offset_next = (float)f->current_offset_a;
    if (induction_motor_load_f32(&d->motor, f->load_factor, &d->load_next) != INDUCTION_MOTOR_OK) {
        (void)induction_motor_load_f32(&d->motor, 1.0, &d->load_next);
    }
    d->fault_new = true;
}

void drive_trip_request(drive_segment *d, drive_trip why) {
    d->trip_req = (uint8_t)why;
}

void drive_battery_next(drive_segment *d, const drive_battery *next) {
    d->bat_next = *next;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += inverter_qs_battery_f32(&d->qs, d->ps_params.c_dc_f, next->g_s,
                                                next->b_a, &d->bus_next);
    } else {
        d->ps_clamps +=
            power_stage_battery_f32(d->stage, next->g_s, next->b_a, &d->battery_next);
    }
    d->battery_new = true;
}

void drive_start(drive_segment *d, const drive_battery *battery) {
    d->bat_next = d->bat_in_force = d->bat_done = *battery;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += inverter_qs_battery_f32(&d->qs, d->ps_params.c_dc_f, battery->g_s,
                                                battery->b_a, &d->bus);
        d->bus_next = d->bus;
        return;
    }
    d->ps_clamps +=
        power_stage_battery_f32(d->stage, battery->g_s, battery->b_a, &d->in.battery);
    d->battery_next = d->in.battery;
}

void drive_speed_command(drive_segment *d, double speed_radps) { d->speed_cmd = (float)speed_radps; }

/* The trace row of the averaged layer: no switching, the terminals are the inverter's. */
static void trace_averaged(const drive_segment *d, drive_trace_row *row) {
    row->s[0] = row->s[1] = row->s[2] = 0u;
    row->m_index = (double)d->cmd.m;
    row->f_hz = (double)d->cmd.freq_hz;
    row->v_dc = (double)d->qs.v_dc;
    for (int x = 0; x < 2; x++) {
        row->v_inv[x] = row->v_cap[x] = (double)d->qs.u[x];
        row->i_motor[x] = (double)d->i_fast[x];
    }
    row->v_inv[2] = row->v_cap[2] = -row->v_inv[0] - row->v_inv[1];
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->i_dc = (double)d->qs.i_dc;
    row->n_rpm = (double)d->mout.n_rpm;
    row->te_nm = (double)d->mout.te_nm;
}

void drive_trace(const drive_segment *d, drive_trace_row *row) {
    const power_stage_f32 *ps = d->stage;
    if (ps == NULL) {
        trace_averaged(d, row);
        return;
    }
    bool rt = (d->cfg.inverter == DRIVE_INVERTER_SWITCHING);
    for (int x = 0; x < 3; x++) {
        row->s[x] = rt ? (uint8_t)d->s[x] : d->pout.state[x];
    }
    row->i_motor[0] = (double)d->i_fast[0];
    row->i_motor[1] = (double)d->i_fast[1];
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->m_index = (double)d->cmd.m;
    row->f_hz = (double)d->cmd.freq_hz;
    row->v_dc = (double)ps->v_dc;
    row->v_inv[0] = (double)ps->u[0];
    row->v_inv[1] = (double)ps->u[1];
    row->v_inv[2] = -row->v_inv[0] - row->v_inv[1];
    row->v_cap[0] = (double)ps->ph[0].v_c;
    row->v_cap[1] = (double)ps->ph[1].v_c;
    row->v_cap[2] = -row->v_cap[0] - row->v_cap[1];
    row->i_dc = (double)ps->i_dc;
    row->n_rpm = (double)d->mout.n_rpm;
    row->te_nm = (double)d->mout.te_nm;
}

double drive_shaft_radps(const drive_segment *d) { return (double)d->motor.w; }

#else
/* The fixed build uses drive_segment_fixed.c; ISO C wants a declaration here. */
typedef int drive_segment_float_unused;
#endif

/*
 * The drive segment (see drive_segment.h), for both numeric builds: the
 * flow once, the build's arithmetic and units from its numeric adapter
 * (drive_num_q.h or drive_num_f32.h: DRIVE_NUM() names a model's twin,
 * num_*() does the arithmetic that differs). The fixed build computes with
 * integers only in the fast tick and the motor task; the slow exchange,
 * once per slow frame, converts to SI in double.
 */
#include "drive_segment.h"
#include "drive_rt_step.h"

#include <stddef.h>

#include "math/umath.h"
#include "models/drive/inverter/leg_fault.h"
#include "models/drive/inverter/power_stage_fast.h"

typedef DRIVE_NUM(power_stage) stage_t;

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
        if (DRIVE_NUM(inverter_quasi_static_init)(&d->avg_stage, &pwm_p, cfg->fast_ns,
                                                  cfg->v_dc0_v) != INVERTER_AVG_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->avg_stage.mod;
        d->stage = NULL;
        /* The filter's series branch joins the stator (inverter_avg.h). */
        mp.rs_ohm += d->ps_params.r_l_ohm;
        mp.lls_h += d->ps_params.l_h;
    } else {
        if (DRIVE_NUM(pwm_init)(&d->pwm, &pwm_p, cfg->fast_ns) != PWM_OK) {
            return DRIVE_ERR_MODEL;
        }
        pwm_p.edges = PWM_EDGES_SAMPLED;
        if (pwm_rt_init(&d->rt, &pwm_p, cfg->fast_ns) != PWM_OK ||
            pwm_rt_dead_time(&d->rt, cfg->dead_time_ns, cfg->fast_ns) != PWM_OK ||
            DRIVE_NUM(power_stage_init)(&d->ps, &d->ps_params, cfg->fast_ns,
                                        cfg->v_dc0_v) != PS_OK) {
            return DRIVE_ERR_MODEL;
        }
        /* The sub-step modulator without dead time plans each frame (pwm_rt.h). */
        pwm_rt_frames(&d->rt, (cfg->modulator == DRIVE_MODULATOR_SUBSTEP && cfg->dead_time_ns == 0u)
                                  ? cfg->fast_per_medium : 0u);
        pwm_rt_prepare(&d->rt, &d->out.ramp); /* the first latch's */
        d->mod = &d->pwm;
        d->stage = &d->ps;
    }
    if (DRIVE_NUM(induction_motor_init)(&d->motor, &mp, prop, medium_s) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    /* The fast companion's gain a_ss h1 and the EMF's 1 / (a_ss h2). */
    if (!num_companion_init(&d->k, &d->NUM_RT_GAIN, d->motor.c.a_ss, fast_s,
                            cfg->fast_per_medium)) {
        return DRIVE_ERR_CONFIG;
    }
    d->ctl_params = *cfg->control;
    d->ctl_params.step_s = medium_s * (double)cfg->medium_per_control;
    d->ctl_params.pwm_step_s = 1e-9 * (double)mod_ns;
    if (DRIVE_NUM(drive_control_init)(&d->ctl, &d->ctl_params) != DRIVE_CONTROL_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->filt_k = num_filter_gain(cfg->fast_per_medium);
    d->k_deriv = num_deriv_gain(fast_s);
    d->rt_path_ok = num_rt_gain_ok(d->NUM_RT_GAIN) && (cfg->inverter == DRIVE_INVERTER_SWITCHING) &&
                    (cfg->dead_time_ns == 0u) &&
                    (cfg->down == COUPLE_ZOH || cfg->down == COUPLE_STAGGER) &&
                    (cfg->up != COUPLE_FILTER) && !cfg->energy_audit;
    d->kernel_ok = (cfg->modulator == DRIVE_MODULATOR_SUBSTEP);
    d->rt_path = d->rt_path_ok;
    d->staggered = drive_staggered(cfg->down, cfg->fast_per_medium);
    d->corr_pending = num_corr_pending(d->staggered, cfg->fast_per_medium);
    if (DRIVE_NUM(induction_motor_load)(&d->motor, 1.0, &d->load_next) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->uv = num_uv_trip();
    d->neg_k_c_next = averaged ? 0 : d->stage->k.neg_k_c;
    return DRIVE_OK;
}

/* The DC-link voltage of the stage in use, whichever it is. */
static num_val stage_v_dc(const drive_segment *d) {
    return !DRIVE_AVERAGED(d) ? d->stage->v_dc : d->avg_stage.v_dc;
}

/* The fast companion's current step on the general path (drive_num_*.h). */
static num_val fast_current_next(const drive_segment *d, num_val i, num_val dv) {
    return num_companion(&d->k, d->NUM_RT_GAIN, i, dv);
}

/*
 * The general path's: each step computed on its own (faults may force the
 * states), with the dead time when there is one (the leg currents at t_k
 * decide which edges it delays).
 */
static void rt_duties(drive_segment *d, int32_t duty[3]) {
    if (d->rt.kd == 0) {
        pwm_rt_duties_each(&d->rt, d->cfg.modulator == DRIVE_MODULATOR_SAMPLED, d->s, duty);
    } else {
        const num_val ia = d->ps.ph[0].i_l;
        const num_val ib = d->ps.ph[1].i_l;
        const int32_t neg[3] = {ia < (num_val)0, ib < (num_val)0, ia + ib > (num_val)0};
        pwm_rt_substep_dt(&d->rt, neg, d->s, duty);
    }
}

/* The real-time step (drive_rt_step.h) on the drive. */
static inline void fast_tick_rt(drive_segment *d) { drive_rt_step(d); }

/* What the faults and a trip leave of each leg (leg_fault.h), by the filter currents. */
static void legs_faulted(const drive_segment *d, leg_state f[3]) {
    const num_val i_l[3] = {d->ps.ph[0].i_l, d->ps.ph[1].i_l,
                            -d->ps.ph[0].i_l - d->ps.ph[1].i_l};
    const bool blocked = (d->trip != (uint8_t)DRIVE_TRIP_NONE);
    for (uint32_t x = 0u; x < 3u; x++) {
        f[x] = leg_fault_state(blocked, d->fault.switch_open, x, i_l[x] < (num_val)0);
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
static void faulted_pwm_out(const drive_segment *d, DRIVE_NUM(pwm_out) *out) {
    leg_state f[3];
    legs_faulted(d, f);
    for (uint32_t x = 0u; x < 3u; x++) {
        if (f[x] != LEG_MODULATED) {
            out->duty[x] = (f[x] == LEG_HIGH) ? NUM_PWM_DUTY_ONE : 0;
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
        DRIVE_NUM(ps_fast_step_call)(&d->ps, &d->in.battery, duty, d->i_fast[0], d->i_fast[1]);
    } else {
        DRIVE_NUM(pwm_step)(&d->pwm, &d->pout);
        faulted_pwm_out(d, &d->pout);
        d->in.duty[0] = d->pout.duty[0];
        d->in.duty[1] = d->pout.duty[1];
        d->in.duty[2] = d->pout.duty[2];
        num_stage_motor_in(&d->in, d->i_fast);
        DRIVE_NUM(power_stage_step)(&d->ps, &d->in);
    }
    const stage_t *ps = d->stage;
    const num_val va = ps->ph[0].v_c;
    const num_val vb = ps->ph[1].v_c;
    /* The EMF moves in the extrapolating modes (e_step is zero otherwise). */
    d->e[0] += d->e_step[0];
    d->e[1] += d->e_step[1];
    d->i_fast[0] = fast_current_next(d, d->i_fast[0], va - d->e[0]);
    d->i_fast[1] = fast_current_next(d, d->i_fast[1], vb - d->e[1]);
    if (d->fault.phase_open != 0u) {
        num_open_phase(d->i_fast, d->fault.phase_open);
    }
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        num_audit(d->stage, &d->sums.loss_l, &d->sums.loss_d);
    }
    d->sums.v_cap[0] += va;
    d->sums.v_cap[1] += vb;
    d->sums.v_dc += ps->v_dc;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        d->filt[0] = num_filter(d->filt[0], va, d->filt_k);
        d->filt[1] = num_filter(d->filt[1], vb, d->filt_k);
    }
}

void drive_fast_tick(drive_segment *d) {
    if (d->rt_path) {
        fast_tick_rt(d);
    } else {
        fast_tick_general(d);
    }
}

/* The real-time path on or off, and the step drive_fast_step() calls with it. */
static void rt_path_set(drive_segment *d, bool on) {
    if (on && !d->rt_path) {
        pwm_rt_states(&d->rt, d->s); /* the plan holds the states from here (pwm_rt.h) */
    }
    d->rt_path = on;
    d->fast_now = (on && d->kernel_ok) ? d->kernel : NULL;
}

void drive_use_fast_kernel(drive_segment *d, drive_fast_kernel *kernel) {
    d->kernel = kernel;
    rt_path_set(d, d->rt_path);
}

/* Applies requested faults at a slow boundary (fast context). */
static void faults_apply(drive_segment *d) {
    d->fault = d->fault_next;
    if (!DRIVE_AVERAGED(d)) {
        d->stage->k.neg_k_c = d->neg_k_c_next; /* the averaged layer's is in bus_next */
    }
    d->i_offset = d->i_offset_next;
    DRIVE_NUM(induction_motor_set_load)(&d->motor, &d->load_next);
    if (d->fault.leg_short != 0u && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = (uint8_t)DRIVE_TRIP_LEG_SHORT;
    }
    d->fault_new = false;
}

/*
 * What the slow boundary changes besides the battery (fast context): the
 * faults and the trip the background requested. With neither requested
 * the real-time path stays as it is (rt_path is a function of rt_path_ok, the
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
    rt_path_set(d, d->rt_path_ok && d->fault.switch_open == 0u && d->fault.phase_open == 0u &&
                       d->trip == (uint8_t)DRIVE_TRIP_NONE);
}

/* What the motor task published takes effect (the latch; inline in the boundary's second half). */
static inline void latch_apply(drive_segment *d) {
    const drive_latch *o = &d->out;
    if (d->uv_req && d->trip == (uint8_t)DRIVE_TRIP_NONE) {
        d->trip = (uint8_t)DRIVE_TRIP_UNDERVOLTAGE;
        rt_path_set(d, false);
    }
    pwm_rt_apply(&d->rt, &o->ramp);
    d->i_fast[0] += o->corr[0];
    d->i_fast[1] += o->corr[1];
    d->e[0] = o->e[0];
    d->e[1] = o->e[1];
    if (!d->rt_path) {
        d->e_step[0] = o->de[0];
        d->e_step[1] = o->de[1];
        if (d->out.cmd_new) {
            DRIVE_NUM(pwm_command_inc)(d->mod, o->cmd.m, o->cmd.phase_inc);
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
    DRIVE_NUM(inverter_quasi_static_step)(&d->avg_stage, &d->bus, d->i_fast[0], d->i_fast[1]);
    if (slow_boundary && d->battery_new) {
        d->bus = d->bus_next;
        battery_take(d);
    }
    drive_frame_sums *m = &d->medium_in;
    for (int x = 0; x < 2; x++) {
        m->v_cap[x] = d->avg_stage.u[x];
        m->v_mark[x] = d->avg_stage.u[x];
        m->filt_mark[x] = num_filt_of(d->avg_stage.u[x]);
        m->i_mark[x] = d->i_fast[x];
    }
    m->v_dc = d->avg_stage.v_dc;
    m->sat = d->avg_stage.sat_count;
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
 * the extrapolating modes (see drive_segment.h); the value published is
 * the one at the next frame's first step: extrapolated modes start 1.5
 * frames after the centre of the frame it was computed from, half a step
 * early.
 */
static void emf_update(drive_segment *d, const num_val v_mean[2], const num_val i_end[2],
                       const num_val corr[2]) {
    num_val e[2];
    for (int x = 0; x < 2; x++) {
        e[x] = num_emf(&d->k, v_mean[x], i_end[x], d->i_prev[x]);
    }
    num_val de[2] = {0, 0};
    if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_FOH)) {
        for (int x = 0; x < 2; x++) {
            de[x] = num_emf_slope(e[x], d->e_prev[x], d->cfg.fast_per_medium);
        }
    } else if (DRIVE_OPTIONAL(d->cfg.down == COUPLE_DERIV)) {
        const num_val g = num_emf_turn(&d->cmd, d->k_deriv);
        de[0] = num_emf_turn_a(g, e[0], e[1]);
        de[1] = num_emf_turn_b(g, e[0], e[1]);
    }
    const num_lead lead = num_emf_lead(d->cfg.fast_per_medium);
    for (int x = 0; x < 2; x++) {
        d->out.e[x] = num_emf_ahead(&d->k, e[x], de[x], corr[x], lead);
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
static double motor_loss_j(const DRIVE_NUM(induction_motor) *m) __attribute__((noinline));
static double motor_loss_j(const DRIVE_NUM(induction_motor) *m) {
    induction_motor_obs o;
    DRIVE_NUM(induction_motor_observe)(m, &o);
    return m->c.h_s * induction_motor_copper_loss_f64(&m->c, &o);
}

/* The slow frame's sums, one motor frame at a time. */
static void slow_sums_add(drive_segment *d, const drive_frame_sums *s, const num_val i_end[2]) {
    drive_slow_sums *w = &d->slow;
    num_vdc_sums(&w->v_dc, &w->v_dc_sq, s->v_dc, d->cfg.fast_per_medium);
    w->fast_n += d->cfg.fast_per_medium;
    w->w += (num_slow)num_motor_w(&d->mout);
    w->te += (num_slow)num_motor_te(&d->mout);
    const num_val i3[3] = {i_end[0], i_end[1], d->mout.i_c};
    for (int x = 0; x < 3; x++) {
        w->i_sq[x] += num_i_sq(i3[x]);
    }
    if (DRIVE_OPTIONAL(d->cfg.energy_audit)) {
        w->loss_l += (num_slow)s->loss_l;
        w->loss_d += (num_slow)s->loss_d;
        w->e_loss_motor_j += motor_loss_j(&d->motor);
    }
    w->p_mech += num_power(num_motor_te(&d->mout), num_motor_w(&d->mout));
    w->medium_n++;
    if (DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER)) {
        /* Time constant: the slow frame. */
        d->w_filt = num_lowpass(d->w_filt, num_motor_w(&d->mout), d->cfg.medium_per_slow);
    }
}

void drive_medium_task(drive_segment *d, bool control_due, bool slow_boundary) {
    const drive_frame_sums *s = &d->medium_in;
    uint32_t n = d->cfg.fast_per_medium;
    const num_count per_n = num_frame_count(n);
    uint32_t sat = 0u;
    /* The motor's terminal voltages over the frame, as the coupling reduces them. */
    DRIVE_NUM(induction_motor_in) min;
    if (d->cfg.up == COUPLE_AVG) {
        min.v_a = num_frame_mean(s->v_cap[0], per_n, &sat);
        min.v_b = num_frame_mean(s->v_cap[1], per_n, &sat);
    } else if (d->cfg.up == COUPLE_SAMPLE) {
        min.v_a = num_from_mark(s->v_mark[0], &sat);
        min.v_b = num_from_mark(s->v_mark[1], &sat);
    } else {
        min.v_a = num_from_filt(s->filt_mark[0], &sat);
        min.v_b = num_from_filt(s->filt_mark[1], &sat);
    }
    min.v_c = num_third(min.v_a, min.v_b);
    DRIVE_NUM(induction_motor_step)(&d->motor, &min, &d->mout);
    if (d->fault.phase_open != 0u) {
        DRIVE_NUM(induction_motor_open_phase)(&d->motor, d->fault.phase_open - 1u, &d->mout);
    }
    num_val i_end[2] = {d->mout.i_a, d->mout.i_b};
    num_val v_mean[2] = {min.v_a, min.v_b};
    /* Motor minus fast current at the frame end: the fast companion steers
     * it out over the next frame through its EMF, the averaged layer (no
     * companion) takes it at once. */
    num_val corr[2];
    for (int x = 0; x < 2; x++) {
        corr[x] = num_fast_of_motor(i_end[x]) - s->i_mark[x];
        if (!DRIVE_AVERAGED(d)) {
            /* Less what the last correction has still to bring after the mark. */
            corr[x] -= num_pending(d->corr_prev[x], d->corr_pending, n);
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
            NUM_CONTROL_TAKEN(d);
            d->ctl_done = false;
            d->out.cmd = d->cmd;
            d->out.cmd_new = true;
        }
        if ((d->cmd.flags & DRIVE_CONTROL_FLAG_SLIP_LIMIT) != 0u) {
            d->slow.limit_n++;
        }
        num_control_in(&d->ctl_in, d->speed_cmd, &d->mout, i_end, d->i_offset, s->v_dc, per_n,
                       &sat);
    }
    /* Under-voltage protection on the frame's mean DC-link voltage. */
    if (num_undervoltage(s->v_dc, per_n, d->uv)) {
        d->uv_req = true;
    }
    /* The next frame's references: exact at both ends, the chord between. */
    if (d->cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        DRIVE_NUM(pwm_rt_ramp)(&d->out.ramp, &d->ref_end, d->cmd.m, d->ref_ph, d->cmd.phase_inc, n);
        pwm_rt_prepare(&d->rt, &d->out.ramp);
        d->ref_ph += d->cmd.phase_inc * n;
    }
    num_count_sat(&d->ps_clamps, sat);
    if (slow_boundary) {
        /* Which battery companion held over the slow frame just ended, and which holds now. */
        d->bat_done = d->bat_in_force;
        if (d->battery_taken) {
            d->bat_in_force = d->bat_next;
            d->battery_taken = false;
        }
        drive_slow_sums *w = &d->slow;
        w->w_filt = d->w_filt;
        w->w_end = num_motor_w(&d->mout);
        w->v_dc_end = stage_v_dc(d);
        w->cmd = d->cmd;
        w->trip = d->trip;
        w->saturations = s->sat + d->pwm.sat_count + d->avg_stage.mod.sat_count + NUM_MODEL_SAT(d) +
                         d->ps_clamps;
        d->slow_out = *w;
        *w = (drive_slow_sums){0};
    }
}

void drive_control_task(drive_segment *d) {
    DRIVE_NUM(drive_control_step)(&d->ctl, &d->ctl_in, &d->ctl_out);
    NUM_CONTROL_STEPPED(d);
    d->ctl_done = true;
}

void drive_slow_measure(const drive_segment *d, drive_slow_meas *meas) {
    const drive_slow_sums *w = &d->slow_out;
    meas->battery = d->bat_done;
    double nf = (w->fast_n > 0u) ? (double)w->fast_n : 1.0;
    double nm = (w->medium_n > 0u) ? (double)w->medium_n : 1.0;
    double medium_s = 1e-9 * (double)d->cfg.fast_ns * (double)d->cfg.fast_per_medium;
    meas->v_dc_mean_v = num_si_volts((double)w->v_dc / nf);
    meas->v_dc_sq_mean_v2 = num_si_volts_sq((double)w->v_dc_sq / nf);
    double w_avg = num_si_speed((double)w->w / nm);
    double w_now = num_si_speed((double)w->w_end);
    double w_filt = num_si_speed((double)w->w_filt);
    meas->shaft_radps = (d->cfg.up == COUPLE_AVG)      ? w_avg
                        : DRIVE_OPTIONAL(d->cfg.up == COUPLE_FILTER) ? w_filt
                                                       : w_now;
    meas->shaft_end_radps = w_now;
    meas->te_nm = num_si_torque((double)w->te / nm);
    double i_sq = 0.0;
    for (int x = 0; x < 3; x++) {
        double sq = num_si_i_sq_pu((double)w->i_sq[x] / nm);
        meas->i_phase_rms_a[x] = num_si_rms_amps(math_sqrt_f64(sq));
        i_sq += sq / 3.0;
    }
    meas->i_rms_a = num_si_rms_amps(math_sqrt_f64(i_sq));
    double fast_s = 1e-9 * (double)d->cfg.fast_ns;
    meas->e_loss_filter_j = num_si_audit(d->ps_params.r_l_ohm * (double)w->loss_l +
                                         d->ps_params.r_d_ohm * (double)w->loss_d) * fast_s;
    meas->e_loss_motor_j = w->e_loss_motor_j;
    meas->limit_s = (double)w->limit_n * medium_s * (double)d->cfg.medium_per_control;
    meas->v_dc_v = num_si_volts((double)w->v_dc_end);
    meas->m_index = num_si_m(&w->cmd);
    meas->f_hz = num_si_f(&w->cmd);
    meas->e_mech_j = num_si_power((double)w->p_mech) * medium_s;
    meas->saturations = w->saturations;
    meas->trip = (drive_trip)w->trip;
}

void drive_fault_request(drive_segment *d, const drive_faults *f) {
    stage_t scratch;
    power_stage_params faulted = d->ps_params;
    d->fault_next = *f;
    faulted.c_dc_f = d->cfg.stage->c_dc_f * f->dc_cap_frac;
    if (DRIVE_AVERAGED(d)) {
        /* The averaged layer: the bus constants fold the capacitance in;
         * they take effect at the next slow boundary, with the fault. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->ps_clamps += DRIVE_NUM(inverter_quasi_static_battery)(
            &d->avg_stage, d->ps_params.c_dc_f, d->bat_next.g_s, d->bat_next.b_a, &d->bus_next);
        d->battery_new = true;
    } else if (DRIVE_NUM(power_stage_init)(&scratch, &faulted, d->stage->step_ns, 600.0) ==
               PS_OK) {
        /* The stage's set-up forms the DC-link coefficient for the new
         * capacitance; a capacitance it refuses leaves the one in force. */
        d->ps_params.c_dc_f = faulted.c_dc_f;
        d->neg_k_c_next = scratch.k.neg_k_c;
    } else {
        d->neg_k_c_next = d->stage->k.neg_k_c;
    }
    d->i_offset_next = num_from_amps(f->current_offset_a);
    if (DRIVE_NUM(induction_motor_load)(&d->motor, f->load_factor, &d->load_next) !=
        INDUCTION_MOTOR_OK) {
        (void)DRIVE_NUM(induction_motor_load)(&d->motor, 1.0, &d->load_next);
    }
    d->fault_new = true;
}

void drive_trip_request(drive_segment *d, drive_trip why) {
    d->trip_req = (uint8_t)why;
}

void drive_battery_next(drive_segment *d, const drive_battery *next) {
    d->bat_next = *next;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += DRIVE_NUM(inverter_quasi_static_battery)(
            &d->avg_stage, d->ps_params.c_dc_f, next->g_s, next->b_a, &d->bus_next);
    } else {
        d->ps_clamps += DRIVE_NUM(power_stage_battery)(d->stage, next->g_s, next->b_a,
                                                       &d->battery_next);
    }
    d->battery_new = true;
}

void drive_start(drive_segment *d, const drive_battery *battery) {
    d->bat_next = d->bat_in_force = d->bat_done = *battery;
    if (DRIVE_AVERAGED(d)) {
        d->ps_clamps += DRIVE_NUM(inverter_quasi_static_battery)(
            &d->avg_stage, d->ps_params.c_dc_f, battery->g_s, battery->b_a, &d->bus);
        d->bus_next = d->bus;
        return;
    }
    d->ps_clamps +=
        DRIVE_NUM(power_stage_battery)(d->stage, battery->g_s, battery->b_a, &d->in.battery);
    d->battery_next = d->in.battery;
}

void drive_speed_command(drive_segment *d, double speed_radps) {
    d->speed_cmd = num_from_speed(speed_radps);
}

/* The trace row of the averaged layer: no switching, the terminals are the inverter's. */
static void trace_averaged(const drive_segment *d, drive_trace_row *row) {
    row->s[0] = row->s[1] = row->s[2] = 0u;
    row->m_index = num_si_m(&d->cmd);
    row->f_hz = num_si_f(&d->cmd);
    row->v_dc = num_trace_volts(d->avg_stage.v_dc);
    for (int x = 0; x < 2; x++) {
        row->v_inv[x] = row->v_cap[x] = num_trace_volts(d->avg_stage.u[x]);
        row->i_motor[x] = num_si_amps_scaled(d->i_fast[x]);
    }
    row->v_inv[2] = row->v_cap[2] = -row->v_inv[0] - row->v_inv[1];
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->i_dc = num_si_amps_scaled(d->avg_stage.i_dc);
    row->n_rpm = num_motor_rpm(&d->mout);
    row->te_nm = num_si_torque((double)num_motor_te(&d->mout));
}

void drive_trace(const drive_segment *d, drive_trace_row *row) {
    const stage_t *ps = d->stage;
    if (ps == NULL) {
        /* The averaged layer: inverter and terminal voltages are one. */
        trace_averaged(d, row);
        return;
    }
    bool rt = (d->cfg.inverter == DRIVE_INVERTER_SWITCHING);
    for (int x = 0; x < 3; x++) {
        row->s[x] = rt ? (uint8_t)d->s[x] : d->pout.state[x];
    }
    row->m_index = num_si_m(&d->cmd);
    row->f_hz = num_si_f(&d->cmd);
    row->v_dc = num_trace_volts(ps->v_dc);
    row->v_inv[0] = num_trace_volts(ps->u[0]);
    row->v_inv[1] = num_trace_volts(ps->u[1]);
    row->v_inv[2] = -row->v_inv[0] - row->v_inv[1];
    row->v_cap[0] = num_trace_volts(ps->ph[0].v_c);
    row->v_cap[1] = num_trace_volts(ps->ph[1].v_c);
    row->v_cap[2] = -row->v_cap[0] - row->v_cap[1];
    for (int x = 0; x < 2; x++) {
        row->i_motor[x] = num_si_amps((double)d->i_fast[x]);
    }
    row->i_motor[2] = -row->i_motor[0] - row->i_motor[1];
    row->i_dc = num_si_amps((double)ps->i_dc);
    row->n_rpm = num_motor_rpm(&d->mout);
    row->te_nm = num_si_torque((double)num_motor_te(&d->mout));
}

double drive_shaft_radps(const drive_segment *d) { return num_si_speed((double)d->motor.w); }

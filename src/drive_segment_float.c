/*
 * The drive segment of the float build (see drive_segment.h): the same
 * data flow as drive_segment_fixed.c, in single precision and SI units.
 * Sums over a motor frame (at most a few hundred fast steps) are float; the
 * motor task adds them into double sums for the slow frame.
 */
#include "drive_segment.h"

#if UUV_NUMERIC == UUV_NUMERIC_FLOAT

#include "math/umath.h"
#include "models/power_stage_fast.h"

static const pwm_params pwm_sampled = {5000.0, PWM_EDGES_SAMPLED, 0u, 0u};
static const pwm_params pwm_located = {5000.0, PWM_EDGES_INTERPOLATED, 0u, 0u};

drive_status drive_init(drive_segment *d, const drive_config *cfg, const propeller_model *prop) {
    if (cfg->fast_ns < 100u || cfg->fast_per_medium == 0u || cfg->medium_per_control == 0u ||
        cfg->fast_per_medium > 100000u || cfg->averaged_substeps == 0u ||
        cfg->medium_per_slow == 0u) {
        return DRIVE_ERR_CONFIG;
    }
    *d = (drive_segment){0};
    d->cfg = *cfg;
    double fast_s = 1e-9 * (double)cfg->fast_ns;
    double medium_s = fast_s * (double)cfg->fast_per_medium;
    uint32_t mod_ns = cfg->fast_ns;
    if (cfg->inverter == DRIVE_INVERTER_AVERAGED) {
        if (inverter_avg_init_f32(&d->avg, &pwm_located, &power_stage_params_default,
                                  cfg->fast_ns, cfg->averaged_substeps,
                                  cfg->v_dc0_v) != INVERTER_AVG_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->avg.mod;
        d->stage = &d->avg.stage;
        mod_ns = cfg->fast_ns / cfg->averaged_substeps;
    } else {
        const pwm_params *pp =
            (cfg->inverter == DRIVE_INVERTER_EVENT) ? &pwm_located : &pwm_sampled;
        if (pwm_init_f32(&d->pwm, pp, cfg->fast_ns) != PWM_OK ||
            power_stage_init_f32(&d->ps, &power_stage_params_default, cfg->fast_ns,
                                 cfg->v_dc0_v) != PS_OK) {
            return DRIVE_ERR_MODEL;
        }
        d->mod = &d->pwm;
        d->stage = &d->ps;
    }
    if (induction_motor_init_f32(&d->motor, &induction_motor_params_15kw_delta, prop,
                                 medium_s) != INDUCTION_MOTOR_OK) {
        return DRIVE_ERR_MODEL;
    }
    double k_l = d->motor.c.a_ss * fast_s;
    if (!(k_l > 1e-6 / 32.0 && k_l < 2.0)) {
        return DRIVE_ERR_CONFIG;
    }
    d->k_l = (float)k_l;
    d->e_per_di = (float)(1.0 / (k_l * (double)cfg->fast_per_medium));
    d->ctl_params = drive_control_params_default;
    d->ctl_params.step_s = medium_s * (double)cfg->medium_per_control;
    d->ctl_params.pwm_step_s = 1e-9 * (double)mod_ns;
    if (drive_control_init_f32(&d->ctl, &d->ctl_params) != DRIVE_CONTROL_OK) {
        return DRIVE_ERR_MODEL;
    }
    d->filt_k = 1.0f / (float)cfg->fast_per_medium;
    d->e_moves = (cfg->down == COUPLE_FOH || cfg->down == COUPLE_DERIV);
    return DRIVE_OK;
}

/*
 * What every fast step does after the power stage: the motor's fast
 * companion and the frame sums (as in drive_segment_fixed.c; the EMF moves
 * only in the extrapolating modes).
 */
static inline void fast_companion_and_sums(drive_segment *d, const power_stage_f32 *ps) {
    const float va = ps->ph[0].v_c;
    const float vb = ps->ph[1].v_c;
    const float vdc = ps->v_dc;
    float ea = d->e[0];
    float eb = d->e[1];
    if (d->e_moves) {
        ea += d->e_step[0];
        eb += d->e_step[1];
        d->e[0] = ea;
        d->e[1] = eb;
    }
    const float ia = d->i_fast[0] + (va - ea) * d->k_l;
    const float ib = d->i_fast[1] + (vb - eb) * d->k_l;
    d->i_fast[0] = ia;
    d->i_fast[1] = ib;
    d->in.i_motor_a[0] = ia;
    d->in.i_motor_a[1] = ib;
    d->sums.v_cap[0] += va;
    d->sums.v_cap[1] += vb;
    d->sums.v_dc += vdc;
    d->sums.v_dc_sq += vdc * vdc;
    d->sums.n++;
}

void drive_fast_tick(drive_segment *d) {
    if (d->cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        /* The real-time path: modulator and power stage fused (power_stage_fast.h). */
        ps_fast_step_f32(&d->pwm, &d->ps, &d->in.battery, d->in.i_motor_a[0],
                         d->in.i_motor_a[1], d->pout.state);
        fast_companion_and_sums(d, &d->ps);
    } else {
        if (d->cfg.inverter == DRIVE_INVERTER_AVERAGED) {
            inverter_avg_step_f32(&d->avg, &d->in);
        } else {
            pwm_step_f32(&d->pwm, &d->pout);
            d->in.duty[0] = d->pout.duty[0];
            d->in.duty[1] = d->pout.duty[1];
            d->in.duty[2] = d->pout.duty[2];
            power_stage_step_f32(&d->ps, &d->in);
        }
        fast_companion_and_sums(d, d->stage);
    }
    if (d->cfg.up == COUPLE_FILTER) {
        d->filt[0] += (d->stage->ph[0].v_c - d->filt[0]) * d->filt_k;
        d->filt[1] += (d->stage->ph[1].v_c - d->filt[1]) * d->filt_k;
    }
}

void drive_medium_latch(drive_segment *d) {
    float ahead = 1.5f * (float)d->cfg.fast_per_medium - 1.0f;
    for (int x = 0; x < 2; x++) {
        d->i_fast[x] += d->out_corr[x];
        d->out_corr[x] = 0.0f;
        d->e_step[x] = d->out_de[x];
        d->e[x] = d->out_e[x] + d->out_de[x] * ahead;
    }
    d->in.i_motor_a[0] = d->i_fast[0];
    d->in.i_motor_a[1] = d->i_fast[1];
    d->in.i_motor_a[2] = -d->i_fast[0] - d->i_fast[1];
    if (d->ctl_new) {
        pwm_command_inc_f32(d->mod, d->ctl_out.m, d->ctl_out.phase_inc);
        d->ctl_last = d->ctl_out;
        d->ctl_new = false;
    }
}

void drive_medium_publish(drive_segment *d, bool slow_boundary) {
    if (slow_boundary) {
        d->bat_done = d->bat_in_force;
        if (d->battery_new) {
            d->in.battery = d->battery_next;
            d->bat_in_force = d->bat_next;
            d->battery_new = false;
        }
    }
    d->sums.i_mark[0] = d->i_fast[0];
    d->sums.i_mark[1] = d->i_fast[1];
    d->medium_in = d->sums;
    float n = (float)d->sums.n;
    if (d->cfg.up == COUPLE_SAMPLE) {
        d->medium_in.v_cap[0] = d->stage->ph[0].v_c * n;
        d->medium_in.v_cap[1] = d->stage->ph[1].v_c * n;
    } else if (d->cfg.up == COUPLE_FILTER) {
        d->medium_in.v_cap[0] = d->filt[0] * n;
        d->medium_in.v_cap[1] = d->filt[1] * n;
    }
    d->sums = (drive_frame_sums){{0.0f, 0.0f}, 0.0f, 0.0f, 0u, {0.0f, 0.0f}};
}

/* As in drive_segment_fixed.c: the frame's EMF and its change per fast step [V]. */
static void emf_update(drive_segment *d, const float v_mean[2], const float i_end[2]) {
    float e[2];
    for (int x = 0; x < 2; x++) {
        e[x] = v_mean[x] - (i_end[x] - d->i_prev[x]) * d->e_per_di;
    }
    float de[2] = {0.0f, 0.0f};
    if (d->cfg.down == COUPLE_FOH) {
        float k = 1.0f / (float)d->cfg.fast_per_medium;
        de[0] = (e[0] - d->e_prev[0]) * k;
        de[1] = (e[1] - d->e_prev[1]) * k;
    } else if (d->cfg.down == COUPLE_DERIV) {
        float g = 6.2831853f * d->ctl_last.freq_hz * 1e-9f * (float)d->cfg.fast_ns / 1.7320508f;
        de[0] = (-e[0] - 2.0f * e[1]) * g;
        de[1] = (2.0f * e[0] + e[1]) * g;
    }
    for (int x = 0; x < 2; x++) {
        d->out_e[x] = e[x];
        d->out_de[x] = de[x];
        d->e_prev[x] = e[x];
    }
}

void drive_medium_task(drive_segment *d, bool control_due) {
    const drive_frame_sums *s = &d->medium_in;
    float inv_n = 1.0f / (float)((s->n > 0u) ? s->n : 1u);
    induction_motor_in_f32 min;
    min.v_a = s->v_cap[0] * inv_n;
    min.v_b = s->v_cap[1] * inv_n;
    min.v_c = -min.v_a - min.v_b;
    induction_motor_step_f32(&d->motor, &min, &d->mout);
    float i_end[2] = {d->mout.i_a, d->mout.i_b};
    float v_mean[2] = {min.v_a, min.v_b};
    emf_update(d, v_mean, i_end);
    for (int x = 0; x < 2; x++) {
        d->out_corr[x] = i_end[x] - s->i_mark[x];
        d->i_prev[x] = i_end[x];
    }
    d->slow_v_dc += (double)s->v_dc;
    d->slow_v_dc_sq += (double)s->v_dc_sq;
    d->slow_fast_n += s->n;
    d->slow_w += (double)d->mout.w_radps;
    d->slow_te += (double)d->mout.te_nm;
    d->slow_i_sq += (double)(i_end[0] * i_end[0] + i_end[1] * i_end[1] +
                             d->mout.i_c * d->mout.i_c);
    d->slow_p_mech += (double)(d->mout.te_nm * d->mout.w_radps);
    d->slow_medium_n++;
    if (d->cfg.up == COUPLE_FILTER) {
        d->w_filt += (d->mout.w_radps - d->w_filt) / (float)d->cfg.medium_per_slow;
    }
    if (control_due) {
        d->ctl_in.speed_cmd_radps = d->speed_cmd;
        d->ctl_in.w_radps = d->mout.w_radps;
        d->ctl_in.i_a = i_end[0];
        d->ctl_in.i_b = i_end[1];
        d->ctl_in.i_c = d->mout.i_c;
        d->ctl_in.vdc_v = s->v_dc * inv_n;
        drive_control_step_f32(&d->ctl, &d->ctl_in, &d->ctl_out);
        d->ctl_new = true;
    }
}

void drive_slow_exchange(drive_segment *d, const drive_battery *next, drive_slow_meas *meas) {
    meas->battery = d->bat_done;
    double nf = (d->slow_fast_n > 0u) ? (double)d->slow_fast_n : 1.0;
    double nm = (d->slow_medium_n > 0u) ? (double)d->slow_medium_n : 1.0;
    double medium_s = 1e-9 * (double)d->cfg.fast_ns * (double)d->cfg.fast_per_medium;
    meas->v_dc_mean_v = d->slow_v_dc / nf;
    meas->v_dc_sq_mean_v2 = d->slow_v_dc_sq / nf;
    meas->shaft_radps = (d->cfg.up == COUPLE_AVG)      ? d->slow_w / nm
                        : (d->cfg.up == COUPLE_FILTER) ? (double)d->w_filt
                                                       : (double)d->mout.w_radps;
    meas->shaft_end_radps = (double)d->mout.w_radps;
    meas->te_nm = d->slow_te / nm;
    meas->i_rms_a = math_sqrt_f64(d->slow_i_sq / nm / 3.0);
    meas->v_dc_v = (double)d->stage->v_dc;
    meas->m_index = (double)d->ctl_last.m;
    meas->f_hz = (double)d->ctl_last.freq_hz;
    meas->e_mech_j = d->slow_p_mech * medium_s;
    meas->saturations = d->pwm.sat_count + d->stage->sat_count + d->avg.mod.sat_count +
                        d->ps_clamps;
    d->slow_v_dc = d->slow_v_dc_sq = d->slow_w = d->slow_te = d->slow_i_sq = 0.0;
    d->slow_p_mech = 0.0;
    d->slow_fast_n = d->slow_medium_n = 0u;

    d->bat_next = *next;
    d->ps_clamps += power_stage_battery_f32(d->stage, next->g_s, next->b_a, &d->battery_next);
    d->battery_new = true;
}

void drive_start(drive_segment *d, const drive_battery *battery) {
    d->bat_next = d->bat_in_force = d->bat_done = *battery;
    d->ps_clamps +=
        power_stage_battery_f32(d->stage, battery->g_s, battery->b_a, &d->in.battery);
    d->battery_next = d->in.battery;
}

void drive_speed_command(drive_segment *d, double speed_radps) { d->speed_cmd = (float)speed_radps; }

void drive_trace(const drive_segment *d, drive_trace_row *row) {
    const power_stage_f32 *ps = d->stage;
    for (int x = 0; x < 3; x++) {
        row->s[x] = d->pout.state[x];
        row->i_motor[x] = (double)d->in.i_motor_a[x];
    }
    row->m_index = (double)d->ctl_last.m;
    row->f_hz = (double)d->ctl_last.freq_hz;
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

/*
 * Single-precision twin of the drive controller (see drive_control.h): the
 * same algorithm as drive_control_q.c in SI units. Every literal is a float
 * and nothing is promoted to double after init.
 */
#include "models/drive/control/drive_control.h"

#include <stddef.h>

#include "fixedpoint/wavetable.h"
#include "math/umath.h"


drive_control_status drive_control_init_f32(drive_control_f32 *c,
                                            const drive_control_params *p) {
    drive_control_design d;
    if ((c == NULL) || (p == NULL)) {
        return DRIVE_CONTROL_ERR_NULL;
    }
    drive_control_status st = drive_control_design_f64(&d, p);
    if (st != DRIVE_CONTROL_OK) {
        return st;
    }
    c->d = d;
    c->kp_w = (float)p->kp_speed_hz_per_radps;
    c->ki_w_t = (float)(p->ki_speed_hz_per_rad * p->step_s);
    c->fr_per_w = (float)d.fr_hz_per_radps;
    c->kq = (float)d.kq_a_per_hz;
    c->rs = (float)p->rs_ohm;
    c->w_sls = (float)(MATH_TWO_PI_F64 * d.sigma_ls_h);
    c->w_ls = (float)(MATH_TWO_PI_F64 * d.ls_h);
    c->ff_gain = (float)p->ff_gain;
    c->kp_i = (float)p->kp_current_v_per_a;
    c->ki_i_t = (float)(p->ki_current_v_per_as * p->step_s);
    c->half_m_max = (float)(0.5 * p->m_max);
    c->speed_max = (float)p->speed_max_radps;
    c->ramp_step = (float)(p->accel_max_radps2 * p->step_s);
    c->idle_speed = (float)p->idle_speed_radps;
    c->slip_lim = (float)d.slip_lim_hz;
    c->freq_max = (float)p->freq_max_hz;
    c->i_mag = (float)p->i_mag_a;
    c->vdc_min = (float)p->vdc_min_v;
    c->m_max = (float)p->m_max;
    c->pwm_step = (float)p->pwm_step_s;
    drive_control_reset_f32(c);
    return DRIVE_CONTROL_OK;
}

void drive_control_reset_f32(drive_control_f32 *c) {
    c->speed_ref = 0.0f;
    c->x_w = 0.0f;
    c->x_i = 0.0f;
    c->idle = true;
}

/* Clamps x to [lo, hi]; a NaN gives lo, so every output stays finite. */
static float dc_clamp_f32(float x, float lo, float hi) {
    return (x > hi) ? hi : (x >= lo) ? x : lo;
}

/* |i| from the three phase currents, amplitude-invariant Clarke transform. */
static float dc_magnitude_f32(const drive_control_in_f32 *in) {
    float x = 2.0f * in->i_a - in->i_b - in->i_c;
    float y = in->i_b - in->i_c;
    return math_sqrt_f32(x * x + 3.0f * y * y) * (1.0f / 3.0f);
}

/* Steady-state voltage amplitude of the demand [V], weighted by ff_gain. */
static float dc_feedforward_f32(const drive_control_f32 *c, float freq, float iq) {
    float vd = c->rs * c->i_mag - c->w_sls * freq * iq;
    float vq = c->rs * iq + c->w_ls * freq * c->i_mag;
    return c->ff_gain * math_sqrt_f32(vd * vd + vq * vq);
}

/* The current loop proper; the measured magnitude is already in out. */
static void dc_current_loop_f32(drive_control_f32 *c, float i_dem, float freq, float slip,
                                float vdc_in, drive_control_out_f32 *out) {
    float e = i_dem - out->i_meas_a;
    float vff = dc_feedforward_f32(c, freq, c->kq * slip);
    float vdc = (vdc_in > c->vdc_min) ? vdc_in : c->vdc_min;
    float vmax = c->half_m_max * vdc;
    bool gen = ((slip > 0.0f) && (freq < 0.0f)) || ((slip < 0.0f) && (freq > 0.0f));
    float u = vff + c->x_i;
    if (!gen) {
        u += c->kp_i * e;
    }
    float v = dc_clamp_f32(u, 0.0f, vmax);
    int dir = (u > vmax) ? 1 : (u < 0.0f) ? -1 : 0;
    if (!gen && !((dir > 0) && (e > 0.0f)) && !((dir < 0) && (e < 0.0f))) {
        c->x_i = dc_clamp_f32(c->x_i + c->ki_i_t * e, -vmax, vmax);
    }
    out->m = dc_clamp_f32(2.0f * v / vdc, 0.0f, c->m_max);
    out->v_demand_v = v;
    out->i_demand_a = i_dem;
    out->freq_hz = freq;
    out->slip_hz = slip;
    out->phase_inc = wt_phase_inc_f32(freq, c->pwm_step);
    out->flags |= (dir > 0) ? DRIVE_CONTROL_FLAG_M_MAX : 0u;
    out->flags |= (dir < 0) ? DRIVE_CONTROL_FLAG_M_ZERO : 0u;
    out->flags |= gen ? DRIVE_CONTROL_FLAG_GENERATING : 0u;
}

void drive_control_current_step_f32(drive_control_f32 *c, float i_demand_a, float freq_hz,
                                    float slip_hz, const drive_control_in_f32 *in,
                                    drive_control_out_f32 *out) {
    out->flags = 0u;
    out->speed_ref_radps = c->speed_ref;
    out->i_meas_a = dc_magnitude_f32(in);
    dc_current_loop_f32(c, (i_demand_a > 0.0f) ? i_demand_a : 0.0f, freq_hz, slip_hz,
                        in->vdc_v, out);
}

/* Standstill: zero outputs, states cleared for the next start. */
static void dc_idle_f32(drive_control_f32 *c, drive_control_out_f32 *out) {
    c->idle = true;
    c->speed_ref = 0.0f;
    c->x_w = 0.0f;
    c->x_i = 0.0f;
    out->m = 0.0f;
    out->freq_hz = 0.0f;
    out->phase_inc = 0u;
    out->slip_hz = 0.0f;
    out->speed_ref_radps = 0.0f;
    out->i_demand_a = 0.0f;
    out->v_demand_v = 0.0f;
    out->flags = DRIVE_CONTROL_FLAG_IDLE;
}

/* Moves the reference towards the clamped command by at most one ramp step. */
static uint32_t dc_ramp_f32(drive_control_f32 *c, float cmd) {
    float d = cmd - c->speed_ref;
    if (d > c->ramp_step) {
        c->speed_ref += c->ramp_step;
        return DRIVE_CONTROL_FLAG_RAMP;
    }
    if (d < -c->ramp_step) {
        c->speed_ref -= c->ramp_step;
        return DRIVE_CONTROL_FLAG_RAMP;
    }
    c->speed_ref = cmd;
    return 0u;
}

/* Speed PI -> slip -> stator frequency; returns the limit flags. */
static uint32_t dc_speed_loop_f32(drive_control_f32 *c, float w, float *freq, float *slip) {
    uint32_t flags = 0u;
    float e = c->speed_ref - w;
    float u = c->kp_w * e + c->x_w;
    float slip_cmd = dc_clamp_f32(u, -c->slip_lim, c->slip_lim);
    int dir = (u > slip_cmd) ? 1 : (u < slip_cmd) ? -1 : 0;
    flags |= (dir != 0) ? DRIVE_CONTROL_FLAG_SLIP_LIMIT : 0u;
    float fr = c->fr_per_w * w;
    float fs = fr + slip_cmd;
    *freq = dc_clamp_f32(fs, -c->freq_max, c->freq_max);
    if (fs != *freq) {
        dir = (fs > *freq) ? 1 : -1;
        flags |= DRIVE_CONTROL_FLAG_FREQ_LIMIT;
    }
    *slip = dc_clamp_f32(*freq - fr, -c->slip_lim, c->slip_lim);
    if (!((dir > 0) && (e > 0.0f)) && !((dir < 0) && (e < 0.0f))) {
        c->x_w = dc_clamp_f32(c->x_w + c->ki_w_t * e, -c->slip_lim, c->slip_lim);
    }
    return flags;
}

void drive_control_step_f32(drive_control_f32 *c, const drive_control_in_f32 *in,
                            drive_control_out_f32 *out) {
    float cmd = dc_clamp_f32(in->speed_cmd_radps, -c->speed_max, c->speed_max);
    float w = in->w_radps;
    out->i_meas_a = dc_magnitude_f32(in);
    if ((math_fabs_f32(cmd) <= c->idle_speed) && (math_fabs_f32(w) <= c->idle_speed)) {
        dc_idle_f32(c, out);
        return;
    }
    if (c->idle) {
        /* Leaving standstill: start the reference where the shaft is. */
        c->idle = false;
        c->speed_ref = dc_clamp_f32(w, -c->speed_max, c->speed_max);
        c->x_w = 0.0f;
        c->x_i = 0.0f;
    }
    float freq;
    float slip;
    uint32_t flags = dc_ramp_f32(c, cmd);
    flags |= dc_speed_loop_f32(c, w, &freq, &slip);
    out->flags = flags;
    out->speed_ref_radps = c->speed_ref;
    float iq = c->kq * slip;
    float i_dem = math_sqrt_f32(c->i_mag * c->i_mag + iq * iq);
    dc_current_loop_f32(c, i_dem, freq, slip, in->vdc_v, out);
}

/*
 * Parameter sets on the desk (see params.h): the key table, the parser,
 * the printer, the firmware generator, the derived controller gains and
 * the fixed build's check of the per-unit bases.
 */
#include "paramset.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "math/umath.h"
#include "models/drive/drive_units.h"
#include "models/vessel/vessel.h"
#include "uuv_config.h"

#define MAX_SET_BYTES (1u << 20)
#define MAX_TOKENS (BATTERY_TABLE_MAX + 2u)

/* Design targets from which the controller's gains follow (docs/drive_control.md). */
typedef struct {
    double speed_crossover_radps; /* speed loop crossover */
    double speed_zero_ratio;      /* crossover / PI zero */
    double current_bw_radps;      /* current loop bandwidth (Kp = w L_sigma, Ki = w R) */
} design_targets;

typedef enum {
    SEC_VESSEL,
    SEC_PROPELLER,
    SEC_BATTERY,
    SEC_STAGE,
    SEC_PWM,
    SEC_MOTOR,
    SEC_CONTROL,
    SEC_AUTOPILOT,
    SEC_DESIGN,
} section;

static const char *const section_c_type[] = {
    "vessel_params", "propeller_params", "battery_params", "power_stage_params",
    "pwm_params", "induction_motor_params", "drive_control_params", "autopilot_params", NULL};
static const char *const section_c_name[] = {"vessel", "propeller", "battery", "stage",
                                             "pwm", "motor", "control", "autopilot", NULL};

typedef enum {
    K_F64,   /* a double */
    K_U32,   /* a whole number */
    K_TABLE, /* one double per battery breakpoint */
    K_GAIN,  /* a controller gain: a double or "auto" */
} kind;

typedef struct {
    const char *key;
    section sec;
    const char *field; /* C designator in the section's struct */
    size_t offset;
    kind kind;
    const char *unit;
    double min, max;   /* allowed range of the value as written */
    double scale;      /* struct value = written value * scale */
    const char *what;  /* meaning and source */
} param_key;

#define DEG MATH_DEG_TO_RAD_F64
#define E(k, s, type, f, kd, u, lo, hi, sc, w) {k, s, #f, offsetof(type, f), kd, u, lo, hi, sc, w}
#define VES(k, f, u, lo, hi, w) E("vessel." k, SEC_VESSEL, vessel_params, f, K_F64, u, lo, hi, 1.0, w)
#define HYD(c, f) E("vessel." #c "." #f, SEC_VESSEL, vessel_params, c.f, K_F64, "-", -10.0, 10.0, \
                    1.0, "hydrodynamic derivative (prime system); Healey and Lienard 1993, MSS npsauv.m")
#define PRO(k, f, u, lo, hi, w) E("propeller." k, SEC_PROPELLER, propeller_params, f, K_F64, u, lo, hi, 1.0, w)
#define BAT(k, f, kd, u, lo, hi, w) E("battery." k, SEC_BATTERY, battery_params, f, kd, u, lo, hi, 1.0, w)
#define STG(k, f, u, lo, hi, w) E("stage." k, SEC_STAGE, power_stage_params, f, K_F64, u, lo, hi, 1.0, w)
#define MOT(k, f, kd, u, lo, hi, w) E("motor." k, SEC_MOTOR, induction_motor_params, f, kd, u, lo, hi, 1.0, w)
#define CTL(k, f, kd, u, lo, hi, w) E("control." k, SEC_CONTROL, drive_control_params, f, kd, u, lo, hi, 1.0, w)
#define AUT(k, f, u, lo, hi, sc, w) E("autopilot." k, SEC_AUTOPILOT, autopilot_params, f, K_F64, u, lo, hi, sc, w)
#define DES(k, f, u, lo, hi, w) E("control." k, SEC_DESIGN, design_targets, f, K_F64, u, lo, hi, 1.0, w)


static const param_key keys[] = {
    VES("length", length_m, "m", 0.5, 50.0, "hull length L (prime-system length); NPS AUV II"),
    VES("gravity", gravity_mps2, "m/s^2", 9.7, 9.9, "gravitational acceleration"),
    VES("rho", rho_kgpm3, "kg/m^3", 990.0, 1050.0, "water density (sea water 1025)"),
    VES("weight", weight_n, "N", 100.0, 1e7, "weight W, the mass is W/g; NPS AUV II"),
    VES("buoyancy", buoyancy_n, "N", 100.0, 1e7, "nominal buoyancy B; NPS AUV II"),
    VES("r_g.x", r_g_m[0], "m", -10.0, 10.0, "centre of gravity x (body, from the CB)"),
    VES("r_g.y", r_g_m[1], "m", -10.0, 10.0, "centre of gravity y"),
    VES("r_g.z", r_g_m[2], "m", -10.0, 10.0, "centre of gravity z (below the CB > 0)"),
    VES("r_b.x", r_b_m[0], "m", -10.0, 10.0, "centre of buoyancy x"),
    VES("r_b.y", r_b_m[1], "m", -10.0, 10.0, "centre of buoyancy y"),
    VES("r_b.z", r_b_m[2], "m", -10.0, 10.0, "centre of buoyancy z"),
    VES("ix", ix_kgm2, "kg*m^2", 1.0, 1e8, "moment of inertia about x; NPS AUV II"),
    VES("iy", iy_kgm2, "kg*m^2", 1.0, 1e8, "moment of inertia about y"),
    VES("iz", iz_kgm2, "kg*m^2", 1.0, 1e8, "moment of inertia about z"),
    VES("ixy", ixy_kgm2, "kg*m^2", -1e6, 1e6, "product of inertia (entered with a minus sign)"),
    VES("iyz", iyz_kgm2, "kg*m^2", -1e6, 1e6, "product of inertia"),
    VES("ixz", ixz_kgm2, "kg*m^2", -1e6, 1e6, "product of inertia"),
    VES("cdy", cdy, "-", 0.0, 5.0, "cross-flow drag coefficient, sway; NPS AUV II"),
    VES("cdz", cdz, "-", 0.0, 5.0, "cross-flow drag coefficient, heave"),
    VES("hx", hx_m, "m", 0.01, 10.0, "mean height of the hull sections"),
    VES("bx", bx_m, "m", 0.01, 10.0, "mean width of the hull sections"),
    VES("hull_radius", hull_radius_m, "m", 0.01, 10.0,
        "radius of the hull's circular sections (free surface hydrostatics)"),
    VES("cd0", cd0, "-", 0.0, 0.1, "surge drag / propulsion coefficient"),
    E("vessel.fin_limit", SEC_VESSEL, vessel_params, fin_limit_rad, K_F64, "deg", 1.0, 60.0, DEG,
      "clamp of the four fin deflections; NPS AUV II 20 deg"),
    VES("shaft_limit", shaft_limit_rpm, "rpm", 10.0, 5000.0, "clamp of the commanded shaft speed"),
    VES("actuator_tau", actuator_tau_s, "s", 0.001, 10.0,
        "time constant of the fin, shaft and buoyancy lags (sets the fin rate)"),
    HYD(x, pp), HYD(x, qq), HYD(x, rr), HYD(x, pr), HYD(x, udot), HYD(x, wq), HYD(x, vp),
    HYD(x, vr), HYD(x, q_ds), HYD(x, q_db2), HYD(x, r_dr), HYD(x, vv), HYD(x, ww), HYD(x, v_dr),
    HYD(x, w_ds), HYD(x, w_db2), HYD(x, ds_ds), HYD(x, dr_dr), HYD(x, q_ds_n), HYD(x, w_ds_n),
    HYD(x, ds_ds_n),
    HYD(y, pdot), HYD(y, rdot), HYD(y, pq), HYD(y, qr), HYD(y, vdot), HYD(y, p), HYD(y, r),
    HYD(y, vq), HYD(y, wp), HYD(y, wr), HYD(y, v), HYD(y, vw), HYD(y, dr),
    HYD(z, qdot), HYD(z, pp), HYD(z, pr), HYD(z, rr), HYD(z, wdot), HYD(z, q), HYD(z, vp),
    HYD(z, vr), HYD(z, w), HYD(z, vv), HYD(z, ds), HYD(z, db2), HYD(z, q_n), HYD(z, w_n),
    HYD(z, ds_n),
    HYD(k, pdot), HYD(k, rdot), HYD(k, pq), HYD(k, qr), HYD(k, vdot), HYD(k, p), HYD(k, r),
    HYD(k, vq), HYD(k, wp), HYD(k, wr), HYD(k, v), HYD(k, vw), HYD(k, db2), HYD(k, p_n),
    HYD(k, prop),
    HYD(m, qdot), HYD(m, pp), HYD(m, pr), HYD(m, rr), HYD(m, wdot), HYD(m, uq), HYD(m, vp),
    HYD(m, vr), HYD(m, uw), HYD(m, vv), HYD(m, ds), HYD(m, db2), HYD(m, q_n), HYD(m, w_n),
    HYD(m, ds_n),
    HYD(n, pdot), HYD(n, rdot), HYD(n, pq), HYD(n, qr), HYD(n, vdot), HYD(n, p), HYD(n, r),
    HYD(n, vq), HYD(n, wp), HYD(n, wr), HYD(n, v), HYD(n, vw), HYD(n, dr), HYD(n, prop),
    AUT("heading_kp", heading_kp, "rad/rad", 0.0, 100.0, 1.0, "rudder per heading error; docs/vessel.md"),
    AUT("heading_kd", heading_kd_s, "s", 0.0, 100.0, 1.0, "rudder per yaw rate"),
    AUT("depth_kp", depth_kp, "rad/m", 0.0, 10.0, 1.0, "pitch reference per depth error"),
    AUT("depth_ki", depth_ki, "rad/(m*s)", 0.0, 10.0, 1.0, "pitch reference per integrated depth error"),
    AUT("depth_band", depth_band_m, "m", 0.0, 1000.0, 1.0, "the depth error is integrated only within this band"),
    AUT("pitch_max", pitch_max_rad, "deg", 0.0, 89.0, DEG, "limit of the pitch reference"),
    AUT("pitch_kp", pitch_kp, "rad/rad", 0.0, 100.0, 1.0, "stern plane per pitch error"),
    AUT("pitch_kd", pitch_kd_s, "s", 0.0, 100.0, 1.0, "stern plane per pitch rate"),
    AUT("fin_limit", fin_limit_rad, "deg", 0.0, 60.0, DEG, "limit of the autopilots' fin commands"),
    AUT("fin_rate", fin_rate_radps, "deg/s", 0.1, 1000.0, DEG, "limit of their rate of change"),
    PRO("diameter", diameter_m, "m", 0.05, 3.0, "propeller diameter D; the seed paper"),
    PRO("alpha1", alpha1, "-", 0.0, 1.0, "thrust coefficient of w|w| (w in rad/s); the seed paper"),
    PRO("alpha2", alpha2, "-", -10.0, 10.0, "thrust coefficient of |w|u; the seed paper"),
    PRO("efficiency", efficiency, "-", 0.01, 1.0, "surge force / ideal thrust"),
    PRO("rho", rho_kgpm3, "kg/m^3", 990.0, 1050.0, "water density at the propeller"),
    PRO("drag_coeff", drag_coeff, "-", 0.0, 1.0, "C_D of the rotating disc (load torque)"),
    PRO("inertia", inertia_kgm2, "kg*m^2", 0.0, 100.0,
        "propeller and shaft inertia I0 (added to the rotor's); docs/vessel.md"),
    BAT("soc", cell.soc, K_TABLE, "-", 0.0, 1.0,
        "breakpoints of the cell tables: 0 first, 1 last, rising; Huria et al. 2012 (Kokam cell)"),
    BAT("ocv", cell.ocv_v, K_TABLE, "V", 1.0, 5.0, "cell open-circuit voltage; Huria et al. 2012, 20 degC"),
    BAT("r0", cell.r0_ohm, K_TABLE, "ohm", 1e-5, 1.0, "cell series resistance; Huria et al. 2012"),
    BAT("r1", cell.r1_ohm, K_TABLE, "ohm", 1e-6, 1.0, "cell polarisation resistance; Huria et al. 2012"),
    BAT("c1", cell.c1_f, K_TABLE, "F", 1.0, 1e7, "cell polarisation capacitance; Huria et al. 2012"),
    BAT("capacity", capacity_ah, K_F64, "A*h", 0.1, 1000.0, "cell charge between soc 0 and 1"),
    BAT("n_series", n_series, K_U32, "-", 1.0, 1000.0, "cells in series (sets the DC bus)"),
    BAT("n_parallel", n_parallel, K_U32, "-", 1.0, 1000.0, "strings in parallel (sets the capacity)"),
    BAT("v_cutoff", v_cutoff_cell_v, K_F64, "V", 1.0, 5.0, "cell discharge cut-off (NMC 3.0 V)"),
    BAT("v_max", v_max_cell_v, K_F64, "V", 1.0, 5.0, "cell charge limit (NMC 4.2 V)"),
    STG("c_dc", c_dc_f, "F", 1e-6, 0.1, "DC-link capacitance; docs/drive_power.md"),
    STG("l", l_h, "H", 1e-5, 0.1, "filter inductance per phase; docs/drive_power.md"),
    STG("r_l", r_l_ohm, "ohm", 1e-4, 10.0, "filter inductor resistance (copper losses)"),
    STG("c", c_f, "F", 1e-7, 1e-2, "filter capacitance per phase"),
    STG("r_d", r_d_ohm, "ohm", 0.01, 1000.0, "damping resistance (R_d-C_d branch across C)"),
    STG("c_d", c_d_f, "F", 1e-7, 1e-2, "damping capacitance"),
    E("pwm.carrier", SEC_PWM, pwm_params, carrier_hz, K_F64, "Hz", 500.0, 25000.0, 1.0,
      "triangle carrier frequency; the seed paper 5 kHz"),
    E("pwm.carrier_phase0", SEC_PWM, pwm_params, carrier_phase0, K_U32, "-", 0.0, 4294967295.0, 1.0,
      "initial carrier phase (2^32 = one turn; 0 = valley)"),
    E("pwm.ref_phase0", SEC_PWM, pwm_params, ref_phase0, K_U32, "-", 0.0, 4294967295.0, 1.0,
      "initial reference phase of leg a (2^32 = one turn)"),
    E("pwm.dead_time", SEC_PWM, pwm_params, dead_time_ns, K_U32, "ns", 0.0, 10000.0, 1.0,
      "both switches of a leg off at every edge (switching inverter, sub-step edges; "
      "docs/drive_power.md); 0 = ideal switches, the seed paper's"),
    MOT("rs", rs_ohm, K_F64, "ohm", 1e-4, 100.0, "stator resistance, star equivalent; Simscape presets"),
    MOT("rr", rr_ohm, K_F64, "ohm", 1e-4, 100.0, "rotor resistance referred to the stator"),
    MOT("lls", lls_h, K_F64, "H", 1e-6, 1.0, "stator leakage inductance"),
    MOT("llr", llr_h, K_F64, "H", 1e-6, 1.0, "rotor leakage inductance"),
    MOT("lm", lm_h, K_F64, "H", 1e-4, 10.0, "magnetising inductance"),
    MOT("pole_pairs", pole_pairs, K_U32, "-", 1.0, 16.0, "pole pairs p"),
    MOT("j_rotor", j_rotor_kgm2, K_F64, "kg*m^2", 1e-4, 100.0, "rotor inertia"),
    MOT("v_rated", v_ll_rated_v, K_F64, "V", 10.0, 10000.0, "rated line-to-line rms voltage"),
    MOT("f_rated", f_rated_hz, K_F64, "Hz", 1.0, 1000.0, "rated frequency"),
    CTL("i_mag", i_mag_a, K_F64, "A", 0.1, 255.0, "peak magnetising current (rotor flux Lm i_mag)"),
    CTL("i_max", i_max_a, K_F64, "A", 0.2, 255.0, "peak current demand limit"),
    CTL("slip_max", slip_max_hz, K_F64, "Hz", 0.01, 20.0, "slip limit (torque limit)"),
    CTL("freq_max", freq_max_hz, K_F64, "Hz", 1.0, 127.0, "stator frequency limit"),
    CTL("speed_max", speed_max_radps, K_F64, "rad/s", 1.0, 255.0, "shaft speed command limit"),
    CTL("accel_max", accel_max_radps2, K_F64, "rad/s^2", 1.0, 10000.0, "speed reference ramp"),
    CTL("idle_speed", idle_speed_radps, K_F64, "rad/s", 0.0, 100.0, "standstill band"),
    DES("speed_crossover", speed_crossover_radps, "rad/s", 1.0, 1000.0,
        "design target: speed loop crossover (Kp = w J / K_T)"),
    DES("speed_zero_ratio", speed_zero_ratio, "-", 1.0, 100.0,
        "design target: crossover / speed PI zero (Ki = Kp w / ratio)"),
    DES("current_bandwidth", current_bw_radps, "rad/s", 1.0, 100000.0,
        "design target: current loop bandwidth (Kp = w L_sigma, Ki = w R)"),
    CTL("kp_speed", kp_speed_hz_per_radps, K_GAIN, "Hz/(rad/s)", 1e-6, 100.0,
        "speed PI proportional gain, or auto; docs/drive_control.md"),
    CTL("ki_speed", ki_speed_hz_per_rad, K_GAIN, "Hz/rad", 0.0, 1000.0,
        "speed PI integral gain, or auto"),
    CTL("kp_current", kp_current_v_per_a, K_GAIN, "V/A", 0.0, 100.0,
        "current PI proportional gain, or auto"),
    CTL("ki_current", ki_current_v_per_as, K_GAIN, "V/(A*s)", 0.0, 100000.0,
        "current PI integral gain, or auto"),
    CTL("ff_gain", ff_gain, K_F64, "-", 0.0, 1.0, "weight of the voltage feedforward"),
    CTL("m_max", m_max, K_F64, "-", 0.01, 1.0, "modulation index limit"),
    CTL("vdc_min", vdc_min_v, K_F64, "V", 1.0, 1000.0, "floor of the DC-link voltage used for m"),
};
#define N_KEYS (sizeof keys / sizeof keys[0])

struct param_store {
    vessel_params vessel;
    autopilot_params autopilot;
    propeller_params propeller;
    battery_params battery;
    power_stage_params stage;
    pwm_params pwm;
    induction_motor_params motor;
    drive_control_params control;
    design_targets design;
    uuv_params set;
    unsigned line[N_KEYS];     /* where each key was given (0: not given) */
    const char *where[N_KEYS]; /* in which file ("--set" for an override) */
    uint32_t n_table[N_KEYS];  /* values given for a table key */
    bool gain_auto[N_KEYS];
    char name[128];
    char label[1024];
};

static const design_targets design_default = {28.0, 8.0, 180.0};

static void *section_base(param_store *s, section sec) {
    switch (sec) {
    case SEC_VESSEL: return &s->vessel;
    case SEC_PROPELLER: return &s->propeller;
    case SEC_BATTERY: return &s->battery;
    case SEC_STAGE: return &s->stage;
    case SEC_PWM: return &s->pwm;
    case SEC_MOTOR: return &s->motor;
    case SEC_CONTROL: return &s->control;
    case SEC_AUTOPILOT: return &s->autopilot;
    case SEC_DESIGN: return &s->design;
    }
    return NULL;
}

static double *f64_at(param_store *s, size_t k) {
    return (double *)(void *)((char *)section_base(s, keys[k].sec) + keys[k].offset);
}

static uint32_t *u32_at(param_store *s, size_t k) {
    return (uint32_t *)(void *)((char *)section_base(s, keys[k].sec) + keys[k].offset);
}

static size_t key_index(const char *name) {
    for (size_t k = 0; k < N_KEYS; k++) {
        if (strcmp(keys[k].key, name) == 0) {
            return k;
        }
    }
    return N_KEYS;
}

param_store *params_new(void) {
    param_store *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return NULL;
    }
    s->vessel = vessel_params_npsauv2;
    s->autopilot = autopilot_params_default;
    s->propeller = propeller_params_default;
    s->battery = battery_params_uuv;
    s->stage = power_stage_params_default;
    s->pwm = pwm_params_default;
    s->motor = induction_motor_params_15kw_delta;
    s->control = drive_control_params_default;
    s->design = design_default;
    s->set = (uuv_params){&s->vessel, &s->autopilot, &s->propeller, &s->battery, &s->stage,
                          &s->pwm, &s->motor, &s->control};
    snprintf(s->name, sizeof s->name, "default");
    snprintf(s->label, sizeof s->label, "default");
    return s;
}

void params_free(param_store *s) { free(s); }

const uuv_params *params_set(const param_store *s) { return &s->set; }

const char *params_label(const param_store *s) { return s->label; }

/* ---- Messages ------------------------------------------------------------ */

static void range_text(const param_key *p, char *buf, size_t len) {
    if (p->kind == K_U32) {
        snprintf(buf, len, "a whole number in [%.10g, %.10g]%s%s", p->min, p->max,
                 strcmp(p->unit, "-") != 0 ? " " : "", strcmp(p->unit, "-") != 0 ? p->unit : "");
    } else {
        snprintf(buf, len, "%s in [%.10g, %.10g] %s", p->kind == K_TABLE ? "values" : "a value",
                 p->min, p->max, p->unit);
    }
}

static bool bad(const char *where, unsigned line, const char *key, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

static bool bad(const char *where, unsigned line, const char *key, const char *format, ...) {
    va_list args;
    va_start(args, format);
    if (line > 0u) {
        fprintf(stderr, "uuvsim: %s:%u: ", where, line);
    } else {
        fprintf(stderr, "uuvsim: %s: ", where);
    }
    if (key != NULL) {
        fprintf(stderr, "%s: ", key);
    }
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
    return false;
}

/* ---- Parsing ------------------------------------------------------------- */

static bool number_of(const char *t, double *v) {
    char *end = NULL;
    errno = 0;
    double x = strtod(t, &end);
    if (end == t || *end != '\0' || errno == ERANGE || !isfinite(x)) {
        return false;
    }
    *v = x;
    return true;
}

/*
 * Sets key k from its value tokens (unit already checked). line/where for
 * messages.
 */
static bool set_key(param_store *s, size_t k, char **tok, size_t n, const char *where,
                    unsigned line) {
    const param_key *p = &keys[k];
    char range[160];
    range_text(p, range, sizeof range);
    if (p->kind == K_TABLE) {
        if (n < 2u || n > BATTERY_TABLE_MAX) {
            return bad(where, line, p->key, "expected 2 to %u values (one per breakpoint), got %zu",
                       BATTERY_TABLE_MAX, n);
        }
    } else if (n != 1u) {
        return bad(where, line, p->key, "expected one value (%s), got %zu", range, n);
    }
    if (p->kind == K_GAIN && strcmp(tok[0], "auto") == 0) {
        s->gain_auto[k] = true;
        return true;
    }
    for (size_t i = 0; i < n; i++) {
        double v = 0.0;
        if (!number_of(tok[i], &v)) {
            return bad(where, line, p->key, "expected %s, got '%s'", range, tok[i]);
        }
        if (!(v >= p->min && v <= p->max)) {
            return bad(where, line, p->key, "expected %s, got %s (out of range)", range, tok[i]);
        }
        if (p->kind == K_U32) {
            if (v != floor(v)) {
                return bad(where, line, p->key, "expected %s, got %s (not whole)", range, tok[i]);
            }
            *u32_at(s, k) = (uint32_t)v;
        } else {
            f64_at(s, k)[i] = v * p->scale;
        }
    }
    s->n_table[k] = (uint32_t)n;
    s->gain_auto[k] = false;
    return true;
}

/* Splits text in place at spaces, tabs and (for --set) commas. */
static size_t split(char *text, char **tok, size_t max, bool commas) {
    size_t n = 0;
    char *p = text;
    for (;;) {
        while (*p == ' ' || *p == '\t' || (commas && *p == ',')) {
            p++;
        }
        if (*p == '\0') {
            return n;
        }
        if (n == max) {
            return max + 1u;
        }
        tok[n++] = p;
        while (*p != '\0' && *p != ' ' && *p != '\t' && !(commas && *p == ',')) {
            p++;
        }
        if (*p != '\0') {
            *p++ = '\0';
        }
    }
}

static bool is_value(const char *t) {
    double v;
    return number_of(t, &v) || strcmp(t, "auto") == 0;
}

/* One "KEY VALUE... UNIT" (file: unit required) or "VALUE...[ UNIT]" of KEY (--set). */
static bool apply(param_store *s, const char *keyname, char **tok, size_t n, bool unit_required,
                  const char *where, unsigned line) {
    size_t k = key_index(keyname);
    if (k == N_KEYS) {
        return bad(where, line, keyname, "unknown key (uuvsim params lists them)");
    }
    const param_key *p = &keys[k];
    if (s->line[k] != 0u && s->where[k] == where) {
        return bad(where, line, keyname, "duplicate key (first given on line %u)", s->line[k]);
    }
    if (n > 1u && !is_value(tok[n - 1u])) {
        if (strcmp(tok[n - 1u], p->unit) != 0) {
            return bad(where, line, keyname, "expected the unit %s, got '%s'", p->unit,
                       tok[n - 1u]);
        }
        n--;
    } else if (unit_required && (n < 2u || is_value(tok[n - 1u]))) {
        return bad(where, line, keyname, "expected the value followed by its unit %s", p->unit);
    }
    if (!set_key(s, k, tok, n, where, line)) {
        return false;
    }
    s->line[k] = (line > 0u) ? line : 1u;
    s->where[k] = where;
    return true;
}

static const char name_chars[] =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-";

static bool parse_text(param_store *s, char *text, const char *path) {
    unsigned line = 0;
    char *p = text;
    while (*p != '\0') {
        line++;
        char *end = strchr(p, '\n');
        char *next = (end != NULL) ? end + 1 : p + strlen(p);
        if (end != NULL) {
            *end = '\0';
        }
        char *hash = strchr(p, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        size_t len = strlen(p);
        if (len > 0u && p[len - 1u] == '\r') {
            p[len - 1u] = '\0';
        }
        char *tok[MAX_TOKENS + 1u];
        size_t n = split(p, tok, MAX_TOKENS, false);
        if (n > MAX_TOKENS) {
            return bad(path, line, NULL, "too many words on the line (at most %u)", MAX_TOKENS);
        }
        if (n > 0u) {
            if (strcmp(tok[0], "name") == 0) {
                if (n != 2u || strlen(tok[1]) >= sizeof s->name ||
                    strspn(tok[1], name_chars) != strlen(tok[1])) {
                    return bad(path, line, "name",
                               "expected one word of at most %zu letters, digits, '.', '_' or "
                               "'-'", sizeof s->name - 1u);
                }
                snprintf(s->name, sizeof s->name, "%s", tok[1]);
            } else if (!apply(s, tok[0], tok + 1, n - 1u, true, path, line)) {
                return false;
            }
        }
        p = next;
    }
    return true;
}

static bool load_file(param_store *s, const char *path) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return bad(path, 0u, NULL, "cannot open: %s", strerror(errno));
    }
    char *buf = malloc(MAX_SET_BYTES + 1u);
    size_t n = (buf != NULL) ? fread(buf, 1, MAX_SET_BYTES + 1u, f) : 0u;
    bool err = ferror(f) != 0;
    fclose(f);
    if (buf == NULL || err || n > MAX_SET_BYTES) {
        free(buf);
        return bad(path, 0u, NULL, "%s", n > MAX_SET_BYTES ? "larger than 1 MiB" : "cannot read");
    }
    if (memchr(buf, '\0', n) != NULL) {
        free(buf);
        return bad(path, 0u, NULL, "not a text file (holds a NUL byte)");
    }
    buf[n] = '\0';
    bool ok = parse_text(s, buf, path);
    free(buf);
    return ok;
}

static const char set_where[] = "--set";

static bool apply_override(param_store *s, const char *arg) {
    char text[2048];
    if (strlen(arg) >= sizeof text) {
        return bad(set_where, 0u, NULL, "'%.40s...': longer than %zu characters", arg,
                   sizeof text - 1u);
    }
    snprintf(text, sizeof text, "%s", arg);
    char *eq = strchr(text, '=');
    if (eq == NULL || eq == text) {
        return bad(set_where, 0u, NULL, "expected KEY=VALUE, got '%s'", arg);
    }
    *eq = '\0';
    char *tok[MAX_TOKENS + 1u];
    size_t n = split(eq + 1, tok, MAX_TOKENS, true);
    if (n == 0u || n > MAX_TOKENS) {
        return bad(set_where, 0u, text, "expected a value after '='");
    }
    /* Each override replaces what the file gave: not a duplicate. */
    size_t k = key_index(text);
    if (k < N_KEYS) {
        s->line[k] = 0u;
    }
    return apply(s, text, tok, n, false, set_where, 0u);
}

/* ---- Derived values ------------------------------------------------------ */

static bool given(const param_store *s, const char *prefix) {
    size_t len = strlen(prefix);
    for (size_t k = 0; k < N_KEYS; k++) {
        if (s->line[k] != 0u && strncmp(keys[k].key, prefix, len) == 0) {
            return true;
        }
    }
    return false;
}

/*
 * The controller gains that follow from the machine (docs/drive_control.md):
 * K_T = 3 p psi_r^2 pi / R_r [N m/Hz] with psi_r = Lm i_mag, J the rotor's
 * and the propeller's inertia; the speed PI Kp = w_c J / K_T, Ki = Kp w_c /
 * ratio; the current PI Kp = w_i L_sigma, Ki = w_i R with the winding's and
 * the filter's leakage inductance and resistance.
 */
static void derive_gains(param_store *s) {
    const induction_motor_params *m = &s->motor;
    drive_control_params *c = &s->control;
    const design_targets *d = &s->design;
    bool depends = given(s, "motor.") || given(s, "stage.l") || given(s, "stage.r_l") ||
                   given(s, "propeller.inertia") || given(s, "control.i_mag") ||
                   given(s, "control.speed_crossover") || given(s, "control.speed_zero_ratio") ||
                   given(s, "control.current_bandwidth");
    double psi_r = m->lm_h * c->i_mag_a;
    double k_t = 3.0 * (double)m->pole_pairs * psi_r * psi_r * MATH_PI_F64 / m->rr_ohm;
    double j = m->j_rotor_kgm2 + s->propeller.inertia_kgm2;
    double l_sigma = m->lls_h + m->llr_h + s->stage.l_h;
    double r = m->rs_ohm + m->rr_ohm + s->stage.r_l_ohm;
    double kp_w = d->speed_crossover_radps * j / k_t;
    struct {
        const char *key;
        double *field;
        double value;
    } g[] = {
        {"control.kp_speed", &c->kp_speed_hz_per_radps, kp_w},
        {"control.ki_speed", &c->ki_speed_hz_per_rad,
         kp_w * d->speed_crossover_radps / d->speed_zero_ratio},
        {"control.kp_current", &c->kp_current_v_per_a, d->current_bw_radps * l_sigma},
        {"control.ki_current", &c->ki_current_v_per_as, d->current_bw_radps * r},
    };
    for (size_t i = 0; i < sizeof g / sizeof g[0]; i++) {
        size_t k = key_index(g[i].key);
        if (s->gain_auto[k] || (s->line[k] == 0u && depends)) {
            *g[i].field = g[i].value;
        }
    }
    /* The controller's machine constants are the motor's. */
    c->pole_pairs = m->pole_pairs;
    c->rs_ohm = m->rs_ohm;
    c->rr_ohm = m->rr_ohm;
    c->lls_h = m->lls_h;
    c->llr_h = m->llr_h;
    c->lm_h = m->lm_h;
}

/* The battery tables: as many values in each as breakpoints. */
static bool check_tables(param_store *s, const char *path) {
    size_t k_soc = key_index("battery.soc");
    uint32_t n = (s->line[k_soc] != 0u) ? s->n_table[k_soc] : battery_params_uuv.cell.n_points;
    for (size_t k = 0; k < N_KEYS; k++) {
        if (keys[k].kind == K_TABLE && s->line[k] != 0u && s->n_table[k] != n) {
            return bad(s->where[k], s->where[k] == set_where ? 0u : s->line[k], keys[k].key,
                       "expected %u values (as many as battery.soc has), got %u", n,
                       s->n_table[k]);
        }
        if (keys[k].kind == K_TABLE && s->line[k] == 0u && n != battery_params_uuv.cell.n_points) {
            return bad(path, 0u, keys[k].key,
                       "expected %u values (battery.soc changed the breakpoints), got none", n);
        }
    }
    s->battery.cell.n_points = n;
    return true;
}

/* ---- Checks -------------------------------------------------------------- */

/* The line to blame for a check: the first of the keys given, else none. */
static bool blame(const param_store *s, const char *path, const char *const *names, size_t n,
                  const char *format, ...) __attribute__((format(printf, 5, 6)));

static bool blame(const param_store *s, const char *path, const char *const *names, size_t n,
                  const char *format, ...) {
    const char *where = path;
    unsigned line = 0u;
    const char *key = names[0];
    for (size_t i = 0; i < n; i++) {
        size_t k = key_index(names[i]);
        if (s->line[k] != 0u) {
            where = s->where[k];
            line = (where == set_where) ? 0u : s->line[k];
            key = names[i];
            break;
        }
    }
    char msg[512];
    va_list args;
    va_start(args, format);
    vsnprintf(msg, sizeof msg, format, args);
    va_end(args);
    return bad(where, line, key, "%s", msg);
}

#define NAMES(...) (const char *const[]){__VA_ARGS__}, \
    sizeof((const char *const[]){__VA_ARGS__}) / sizeof(const char *)

/* A worst-case signal against its per-unit base (drive_units.h). */
static bool fits(const param_store *s, const char *path, const char *const *names, size_t n,
                 const char *signal, double worst, double base, const char *unit,
                 const char *how) {
    if (worst < base) {
        return true;
    }
    return blame(s, path, names, n,
                 "the fixed build cannot hold this set: %s reaches %.4g %s (%s), %.1f %% above "
                 "its per-unit base %.4g %s (src/models/drive/drive_units.h)",
                 signal, worst, unit, how, 100.0 * (worst / base - 1.0), base, unit);
}

/*
 * The fixed build's per-unit bases against the set's worst cases
 * (docs/fixedpoint.md): the bus at the full charge, the phase current at
 * the controller's limit plus half the filter's ripple, the DC current
 * (two legs' currents at most), the electrical speed at the frequency
 * limit, the torque at the current limit and the propeller's at the speed
 * limit, the stator flux at the current limit, the frequency limit.
 */
static bool check_bases(const param_store *s, const char *path) {
    const battery_params *b = &s->battery;
    const drive_control_params *c = &s->control;
    const induction_motor_params *m = &s->motor;
    double v_bus = (double)b->n_series * b->v_max_cell_v;
    double ripple = v_bus / (8.0 * s->stage.l_h * s->pwm.carrier_hz);
    double i_peak = c->i_max_a + 0.5 * ripple;
    double w_el = 2.0 * MATH_PI_F64 * (c->freq_max_hz + c->slip_max_hz);
    double psi_r = m->lm_h * c->i_mag_a;
    double i_q = (c->i_max_a > c->i_mag_a) ? sqrt(c->i_max_a * c->i_max_a - c->i_mag_a * c->i_mag_a) : 0.0;
    double lr = m->lm_h + m->llr_h;
    double te = 1.5 * (double)m->pole_pairs * (m->lm_h / lr) * psi_r * i_q;
    double rad = 0.5 * s->propeller.diameter_m;
    double t_load = 0.5 * s->propeller.rho_kgpm3 * s->propeller.drag_coeff * rad * rad * rad *
                    c->speed_max_radps * c->speed_max_radps;
    double psi_s = (m->lm_h + m->lls_h) * c->i_max_a;
    char how[160];
    snprintf(how, sizeof how, "%u cells x %.4g V", b->n_series, b->v_max_cell_v);
    if (!fits(s, path, NAMES("battery.n_series", "battery.v_max"), "the DC link", v_bus,
              DRIVE_BASE_VOLTAGE_V, "V", how)) {
        return false;
    }
    snprintf(how, sizeof how, "limit %.4g A + half the filter ripple %.4g A", c->i_max_a,
             0.5 * ripple);
    if (!fits(s, path, NAMES("control.i_max", "stage.l", "pwm.carrier", "battery.n_series"),
              "the phase current", i_peak, DRIVE_BASE_CURRENT_A, "A", how)) {
        return false;
    }
    if (!fits(s, path, NAMES("control.i_max", "stage.l"), "the DC-link current", 2.0 * i_peak,
              DRIVE_BASE_CURRENT_A, "A", "two legs at the peak phase current")) {
        return false;
    }
    if (!fits(s, path, NAMES("control.freq_max", "control.slip_max"), "the electrical speed",
              w_el, DRIVE_BASE_SPEED_RADPS, "rad/s", "2 pi (frequency limit + slip limit)")) {
        return false;
    }
    if (!fits(s, path, NAMES("control.speed_max"), "the shaft speed", c->speed_max_radps,
              0.5 * DRIVE_BASE_SPEED_RADPS, "rad/s", "the command limit; half the base")) {
        return false;
    }
    if (!fits(s, path, NAMES("control.freq_max"), "the stator frequency", c->freq_max_hz,
              DRIVE_BASE_FREQ_HZ, "Hz", "the frequency limit")) {
        return false;
    }
    snprintf(how, sizeof how, "electromagnetic %.4g N m at the current limit, load %.4g N m at "
             "the speed limit", te, t_load);
    if (!fits(s, path, NAMES("control.i_max", "motor.lm", "propeller.diameter", "control.speed_max"),
              "the torque", fmax(te, t_load), DRIVE_BASE_TORQUE_NM, "N m", how)) {
        return false;
    }
    if (!fits(s, path, NAMES("control.i_max", "motor.lm", "motor.lls"), "the stator flux", psi_s,
              DRIVE_BASE_FLUX_WB, "Wb", "(Lm + Lls) at the current limit")) {
        return false;
    }
    return true;
}

/* The models' own checks, one model at a time, so that the message names it. */
static bool check_models(param_store *s, const char *path) {
    static vessel_model vm;
    battery bat;
    battery_params bp = s->battery;
    bp.frame_s = 0.1;
    if (battery_init(&bat, &bp, 1.0) != BATTERY_OK) {
        return bad(path, 0u, "battery", "the battery model refuses the set (tables rising from "
                   "soc 0 to 1, a non-falling OCV, cut-off below the full OCV, limit above it)");
    }
    propeller_model pm;
    if (propeller_init(&pm, &s->propeller) != PROPELLER_OK) {
        return bad(path, 0u, "propeller", "the propeller model refuses the set");
    }
    vessel_config vc;
    vessel_config_default(&vc);
    vc.params = &s->vessel;
    vc.propeller = &s->propeller;
    vc.step_s = 0.1;
    if (vessel_init(&vm, &vc) != VESSEL_OK) {
        return bad(path, 0u, "vessel", "the vessel model refuses the set (its mass matrix or a "
                   "coefficient)");
    }
    induction_motor_f64 mot;
    if (induction_motor_init_f64(&mot, &s->motor, &pm, 100e-6) != INDUCTION_MOTOR_OK) {
        return bad(path, 0u, "motor", "the motor model refuses the set");
    }
    power_stage_f32 ps;
    if (power_stage_init_f32(&ps, &s->stage, 2000u, 600.0) != PS_OK) {
        return bad(path, 0u, "stage", "the power stage refuses the set at the 2 us step");
    }
    pwm_f32 pw;
    if (pwm_init_f32(&pw, &s->pwm, 2000u) != PWM_OK) {
        return bad(path, 0u, "pwm", "the modulator refuses the carrier at the 2 us step (at "
                   "least 8 steps per period)");
    }
    drive_control_f32 ctl;
    drive_control_params cp = s->control;
    cp.step_s = 800e-6;
    cp.pwm_step_s = 2e-6;
    if (drive_control_init_f32(&ctl, &cp) != DRIVE_CONTROL_OK) {
        return bad(path, 0u, "control", "the controller refuses the set (i_mag < i_max, limits "
                   "inside the bases, idle below the speed limit)");
    }
    return true;
}

bool params_load(param_store *s, const char *path, const char *const *sets, int n_sets) {
    const char *label_path = (path != NULL) ? path : "default";
    if (path != NULL) {
        const char *base = strrchr(path, '/');
        base = (base != NULL) ? base + 1 : path;
        size_t len = strcspn(base, ".");
        snprintf(s->name, sizeof s->name, "%.*s", (int)(len < sizeof s->name ? len : 0), base);
        for (char *c = s->name; *c != '\0'; c++) {
            if (strchr(name_chars, *c) == NULL) {
                *c = '_';
            }
        }
        if (!load_file(s, path)) {
            return false;
        }
    }
    for (int i = 0; i < n_sets; i++) {
        if (!apply_override(s, sets[i])) {
            return false;
        }
    }
    const char *ctx = (path != NULL) ? path : set_where;
    if (!check_tables(s, ctx)) {
        return false;
    }
    derive_gains(s);
    if (!check_models(s, ctx)) {
        return false;
    }
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
    if (!check_bases(s, ctx)) {
        return false;
    }
#else
    (void)check_bases;
#endif
    size_t used = (size_t)snprintf(s->label, sizeof s->label, "%s", label_path);
    if (path != NULL && used < sizeof s->label) {
        used += (size_t)snprintf(s->label + used, sizeof s->label - used, " (%s)", s->name);
    }
    for (int i = 0; i < n_sets && used < sizeof s->label; i++) {
        used += (size_t)snprintf(s->label + used, sizeof s->label - used, "%s%s",
                                 i == 0 ? ", overrides " : " ", sets[i]);
    }
    return true;
}

bool params_check_run(const param_store *s, bool dead_time_modelled) {
    if (s->pwm.dead_time_ns == 0u || dead_time_modelled) {
        return true;
    }
    return blame(s, set_where, NAMES("pwm.dead_time"),
                 "a dead time of %u ns needs the switching inverter with sub-step edges "
                 "(--inverter switching --modulator substep, the defaults); for another "
                 "inverter or modulator give --set pwm.dead_time=0", s->pwm.dead_time_ns);
}

/* ---- Printing ------------------------------------------------------------ */

/* The shortest %g text of v / scale that reads back as v. */
static void value_text(double v, double scale, char *buf, size_t len) {
    double mag = fabs(v / scale);
    int digits = 1;
    while (digits < 16 && mag >= 10.0) { /* no exponent for the integer digits */
        mag /= 10.0;
        digits++;
    }
    for (; digits <= 17; digits++) {
        snprintf(buf, len, "%.*g", digits, v / scale);
        if (strtod(buf, NULL) * scale == v) {
            return;
        }
    }
    snprintf(buf, len, "%.17g", v / scale);
}

static const char *const section_title[] = {
    "Vessel: NPS AUV II (docs/vessel.md)", "Propeller (docs/vessel.md)",
    "Battery: cell tables over the state of charge, pack (docs/battery.md)",
    "Power stage: DC link and LC filter (docs/drive_power.md)",
    "PWM modulator (docs/drive_power.md)",
    "Induction motor, star equivalent (docs/drive_motor.md)",
    "Controller: limits, design targets and gains (docs/drive_control.md)",
    "Heading and depth autopilots (docs/vessel.md)", NULL};

void params_print(FILE *f, const param_store *s_in) {
    param_store *s = (param_store *)(uintptr_t)s_in; /* read only; the accessors take no const */
    fprintf(f, "# uuvsim parameter set: KEY VALUE... UNIT  (# starts a comment)\n"
               "# Each key's comment gives its allowed range, meaning and source.\n"
               "name %s\n", s->name);
    int last = -1;
    for (size_t k = 0; k < N_KEYS; k++) {
        const param_key *p = &keys[k];
        int sec = (p->sec == SEC_DESIGN) ? (int)SEC_CONTROL : (int)p->sec;
        if (sec != last) {
            fprintf(f, "\n# %s\n", section_title[sec]);
            last = sec;
        }
        char line[1024];
        size_t used = (size_t)snprintf(line, sizeof line, "%s", p->key);
        uint32_t n = (p->kind == K_TABLE) ? s->battery.cell.n_points : 1u;
        for (uint32_t i = 0; i < n; i++) {
            char v[64];
            if (p->kind == K_U32) {
                snprintf(v, sizeof v, "%u", *u32_at(s, k));
            } else {
                value_text(f64_at(s, k)[i], p->scale, v, sizeof v);
            }
            used += (size_t)snprintf(line + used, sizeof line - used, " %s", v);
        }
        snprintf(line + used, sizeof line - used, " %s", p->unit);
        char range[160];
        range_text(p, range, sizeof range);
        fprintf(f, "%-44s # %s; %s\n", line, range, p->what);
    }
}

void params_emit_c(FILE *f, const param_store *s_in, const char *source) {
    param_store *s = (param_store *)(uintptr_t)s_in;
    fprintf(f, "/* Generated by uuvsim params --emit-c from %s (%s): do not edit. */\n",
            source, s->name);
    fprintf(f, "#include \"fw_params.h\"\n");
    for (int sec = SEC_VESSEL; sec <= SEC_AUTOPILOT; sec++) {
        fprintf(f, "\nstatic const %s set_%s = {\n", section_c_type[sec], section_c_name[sec]);
        /* Every field of the struct, from the loaded copy: the keys and the derived ones. */
        for (size_t k = 0; k < N_KEYS; k++) {
            const param_key *p = &keys[k];
            if ((int)p->sec != sec) {
                continue;
            }
            uint32_t n = (p->kind == K_TABLE) ? s->battery.cell.n_points : 1u;
            for (uint32_t i = 0; i < n; i++) {
                if (p->kind == K_U32) {
                    fprintf(f, "    .%s = %uu,\n", p->field, *u32_at(s, k));
                } else if (p->kind == K_TABLE) {
                    fprintf(f, "    .%s[%u] = %a,\n", p->field, i, f64_at(s, k)[i]);
                } else {
                    fprintf(f, "    .%s = %a,\n", p->field, f64_at(s, k)[i]);
                }
            }
        }
        if (sec == SEC_BATTERY) {
            fprintf(f, "    .cell.n_points = %uu,\n    .frame_s = %a,\n", s->battery.cell.n_points,
                    s->battery.frame_s);
        } else if (sec == SEC_PWM) {
            fprintf(f, "    .edges = PWM_EDGES_INTERPOLATED,\n");
        } else if (sec == SEC_CONTROL) {
            const drive_control_params *c = &s->control;
            fprintf(f, "    .step_s = %a,\n    .pwm_step_s = %a,\n    .pole_pairs = %uu,\n"
                       "    .rs_ohm = %a,\n    .rr_ohm = %a,\n    .lls_h = %a,\n    .llr_h = %a,\n"
                       "    .lm_h = %a,\n",
                    c->step_s, c->pwm_step_s, c->pole_pairs, c->rs_ohm, c->rr_ohm, c->lls_h,
                    c->llr_h, c->lm_h);
        }
        fprintf(f, "};\n");
    }
    fprintf(f, "\nstatic const uuv_params set = {\n");
    fprintf(f, "    .vessel = &set_vessel,\n    .autopilot = &set_autopilot,\n    .propeller = &set_propeller,\n"
               "    .battery = &set_battery,\n    .stage = &set_stage,\n    .pwm = &set_pwm,\n"
               "    .motor = &set_motor,\n    .control = &set_control,\n};\n\n"
               "const uuv_params *const fw_params = &set;\n");
}

int params_command(const char *path, const char *const *sets, int n_sets, const char *emit_c) {
    param_store *s = params_new();
    if (s == NULL) {
        fprintf(stderr, "uuvsim: out of memory\n");
        return 1;
    }
    if (!params_load(s, path, sets, n_sets)) {
        params_free(s);
        return 2;
    }
    int status = 0;
    if (emit_c == NULL) {
        params_print(stdout, s);
        status = (fflush(stdout) == 0 && !ferror(stdout)) ? 0 : 2;
    } else {
        char partial[4200];
        snprintf(partial, sizeof partial, "%s.partial", emit_c);
        FILE *f = fopen(partial, "w");
        if (f == NULL) {
            fprintf(stderr, "uuvsim: %s: cannot write: %s\n", emit_c, strerror(errno));
            status = 2;
        } else {
            params_emit_c(f, s, path != NULL ? path : "the default set");
            bool ok = (ferror(f) == 0);
            ok = (fclose(f) == 0) && ok;
            if (!ok || rename(partial, emit_c) != 0) {
                fprintf(stderr, "uuvsim: %s: cannot write: %s\n", emit_c, strerror(errno));
                remove(partial);
                status = 2;
            }
        }
    }
    params_free(s);
    return status;
}

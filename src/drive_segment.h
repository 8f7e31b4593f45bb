/*
 * The electric drive as the executive runs it: the fast segment (PWM,
 * inverter, DC link and LC filter), the fast-medium segment (induction
 * motor) and the slow-medium segment (controller), with the data that cross
 * between them. One implementation (drive_segment.c) for both numeric
 * builds; what differs between them is the build's numeric adapter
 * (drive_num_q.h, drive_num_f32.h), chosen by UUV_NUMERIC.
 *
 * The motor's fast companion. The motor runs at its 100 us frame, but the
 * filter capacitors it loads are solved every 2 us; a motor current held
 * over a frame would reach the filter a frame late, and that delay inside
 * the LC resonance's loop makes it unstable. So the fast step carries the
 * motor's stator current itself, by the motor's own stator equation with
 * the slowly varying part frozen (paper section 3: the component exports
 * what its terminal current does for the next step):
 *   di_s/dt = a_ss (v_s - e_s),   a_ss = Lr / (Ls Lr - Lm^2) = 1 / (sigma Ls),
 * where the EMF e_s is the motor's resistive drop and rotor-flux term. The
 * motor task computes e for the frame it has just integrated as the value
 * that reproduces its own current change with the frame's mean voltage,
 *   e = vbar - (i_end - i_start) / (a_ss h),
 * and reports how far the fast current has drifted from its own at the
 * frame end; the fast step adds that difference at the next latch. The
 * slow-to-fast coupling modes act on e: held (ZOH), extrapolated from the
 * last two frames (FOH), extrapolated along its rotation de/dt = j w_s e
 * (DERIV), or latched half a frame after the release (STAGGER).
 *
 * Who calls what, and where the data wait (see executive.h for when):
 *   fast tick     drive_fast_tick() every fast step: one step of the power
 *                 stage with the inputs latched at the last boundary, and
 *                 the sums the slower segments need.
 *   boundary      drive_medium_publish() after a frame's last fast step
 *                 and drive_medium_begin() before the next frame's first
 *                 (the same fast tick or the next one): hands the frame's
 *                 sums to the motor (input buffer) and latches what the
 *                 motor and controller published (output buffers) as the
 *                 fast inputs of the next frame. Nothing a slower task
 *                 writes reaches the fast step except here, so results do
 *                 not depend on where a fast tick preempts the slower task.
 *   medium task   drive_medium_task(): one motor step on the frame's input
 *                 buffer, the next frame's reference ramps and EMF, the slow
 *                 sums; at a control boundary it takes the controller's last
 *                 result and latches its next inputs; at a slow boundary it
 *                 hands the slow frame's raw sums over.
 *   control task  drive_control_task(): the controller, below the medium
 *                 task; its result is due at the next control boundary.
 *   background    drive_slow_measure(), drive_battery_next(),
 *                 drive_fault_request(): the slow segment's side, in SI.
 */
#ifndef UUV_DRIVE_SEGMENT_H
#define UUV_DRIVE_SEGMENT_H

/* [V] under-voltage trip of the DC link (the pack's cut-off is 432 V). */
#define DRIVE_UV_TRIP_V 300.0

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "models/drive/control/drive_control.h"
#include "models/drive/motor/induction_motor.h"
#include "models/drive/inverter/inverter_avg.h"
#include "models/drive/inverter/power_stage.h"
#include "models/propeller/propeller.h"
#include "models/drive/pwm/pwm.h"
#include "models/drive/pwm/pwm_rt.h"
#include "uuv_config.h"

/* The build's numeric adapter: its types and arithmetic (DRIVE_NUM, num_*). */
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
#include "drive_num_q.h"
#else
#include "drive_num_f32.h"
#endif

/* Inverter model (the paper's layered model). */
typedef enum {
    DRIVE_INVERTER_SWITCHING = 0, /* six switches at the fast step (drive_modulator) */
    DRIVE_INVERTER_AVERAGED,      /* leg duty cycles, quasi-static filter and DC link, run
                                   * with the motor at one frame (inverter_avg.h) */
    DRIVE_INVERTER_EVENT          /* switching instants located inside the fast step */
} drive_inverter;

/* How the switching inverter's modulator forms a step's pole voltages (pwm_rt.h). */
typedef enum {
    DRIVE_MODULATOR_SUBSTEP = 0, /* each leg's on-time inside the step, the step's mean applied */
    DRIVE_MODULATOR_SAMPLED      /* the comparison at the step's start held over the step */
} drive_modulator;

/* How a slower segment's output is applied over the faster one's steps. */
typedef enum {
    COUPLE_ZOH = 0,  /* zero-order hold: the last value for the whole frame */
    COUPLE_FOH,      /* first-order hold: extrapolated from the last two values */
    COUPLE_DERIV,    /* extrapolated with the derivative the slower model computes */
    COUPLE_STAGGER   /* the slower segment runs half a frame later: values arrive mid-frame */
} coupling_down;

/* How a faster segment's output is reduced for a slower one. */
typedef enum {
    COUPLE_AVG = 0,  /* average over the frame */
    COUPLE_FILTER,   /* first-order filter at the fast rate, time constant = the frame */
    COUPLE_SAMPLE    /* the value at the boundary (aliases; kept for comparison) */
} coupling_up;

typedef struct {
    drive_inverter inverter;
    drive_modulator modulator; /* the switching inverter's (sub-step or sampled) */
    uint32_t dead_time_ns;    /* [ns] the legs' dead time (sub-step only; 0: ideal switches) */
    coupling_down down;       /* motor currents to the fast segment */
    coupling_up up;           /* capacitor voltages to the motor, measurements to the slow segment */
    uint32_t fast_ns;         /* [ns] power-stage step (the frame of the averaged layer) */
    uint32_t fast_per_medium; /* fast steps per motor frame */
    uint32_t medium_per_control; /* motor frames per controller frame */
    uint32_t medium_per_slow;    /* motor frames per slow frame (the speed filter's time constant) */
    bool energy_audit;        /* count the filter's and the motor's losses (general fast path) */
    double v_dc0_v;           /* [V] initial DC-link voltage */
    /* The models' parameters: a parameter set's (params.h), none NULL. */
    const power_stage_params *stage;      /* DC link and LC filter */
    const pwm_params *pwm;                /* carrier and phases; the edge mode is the inverter's */
    const induction_motor_params *motor;
    const drive_control_params *control;  /* its step_s and pwm_step_s come from the frames */
} drive_config;

/* The battery's companion i = G v - b (battery.h convention), in SI. */
typedef struct {
    double g_s; /* [S] */
    double b_a; /* [A] */
} drive_battery;

/*
 * Drive faults (scenario fault commands), requested by the slow segment and
 * applied at the next slow boundary, so that the fast step sees them at the
 * same step in every port.
 */
typedef struct {
    uint8_t switch_open;      /* 0: none; 1..6: a+ a- b+ b- c+ c- stuck open */
    uint8_t leg_short;        /* 0: none; 1..3: leg a, b, c shoot-through (trips) */
    double dc_cap_frac;       /* [-] DC-link capacitance left, (0, 1] */
    double current_offset_a;  /* [A] offset of the controller's phase-a measurement */
    uint8_t phase_open;       /* 0: none; 1..3: motor phase a, b, c disconnected */
    double load_factor;       /* [-] on the propeller's load torque (fouling), 1..10; 1: clean */
} drive_faults;

/* Why the drive's protection blocked the gates (0: it has not). */
typedef enum {
    DRIVE_TRIP_NONE = 0,
    DRIVE_TRIP_LEG_SHORT,     /* desaturation of a shorted leg */
    DRIVE_TRIP_UNDERVOLTAGE,  /* DC link below DRIVE_UV_TRIP_V */
    DRIVE_TRIP_PHASE_LOSS     /* a motor phase carries no current while the others do */
} drive_trip;


/* What the drive reports to the slow segment, once per slow frame. */
typedef struct {
    drive_battery battery;   /* the battery companion that was in force over the frame */
    double v_dc_mean_v;      /* [V] mean DC-link voltage over the frame */
    double v_dc_sq_mean_v2;  /* [V^2] mean of its square (battery current and power follow) */
    double shaft_radps;      /* [rad/s] shaft speed, reduced as the coupling says */
    double shaft_end_radps;  /* [rad/s] shaft speed at the boundary */
    double te_nm;            /* [N m] mean electromagnetic torque */
    double i_rms_a;          /* [A] rms phase current over the frame */
    double v_dc_v;           /* [V] DC-link voltage at the boundary */
    double m_index;          /* [-] modulation index in force */
    double f_hz;             /* [Hz] stator frequency in force */
    double e_mech_j;         /* [J] mechanical energy delivered to the shaft in the frame */
    double i_phase_rms_a[3]; /* [A] rms current of each motor phase over the frame */
    double e_loss_filter_j;  /* [J] filter losses in the frame (R_L, R_d; energy_audit only) */
    double e_loss_motor_j;   /* [J] motor copper losses in the frame (energy_audit only) */
    double limit_s;          /* [s] time the controller's torque (slip) limit acted in the frame */
    uint32_t saturations;    /* fixed-point saturation events so far (all drive models) */
    drive_trip trip;         /* the protection's state at the boundary */
} drive_slow_meas;

/* One row of the fast trace (SI units). */
typedef struct {
    uint8_t s[3];        /* leg states at the end of the step */
    double m_index, f_hz;
    double v_dc;         /* [V] */
    double v_inv[3];     /* [V] inverter phase voltages (common mode removed) */
    double v_cap[3];     /* [V] filter capacitor (motor terminal) voltages */
    double i_motor[3];   /* [A] phase currents into the motor, as the fast step used them */
    double i_dc;         /* [A] DC-link current into the inverter */
    double n_rpm;        /* [rpm] shaft speed */
    double te_nm;        /* [N m] electromagnetic torque */
} drive_trace_row;

typedef enum {
    DRIVE_OK = 0,
    DRIVE_ERR_CONFIG,   /* a rate, ratio or mode out of range */
    DRIVE_ERR_MODEL,    /* a model refused its parameters at these steps */
    DRIVE_ERR_LAYER     /* a layer, coupling or audit this build leaves out */
} drive_status;

/*
 * DRIVE_OPTIONAL(cond): cond, except in a lean image (UUV_LEAN_IMAGE,
 * uuv_config.h), where it is false and the code it guards is dropped: the
 * event and averaged layers, the energy audit, the extrapolating (FOH,
 * DERIV) and filter couplings.
 */
#define DRIVE_OPTIONAL(cond) ((UUV_LEAN_IMAGE == 0) && (cond))

/* The averaged layer runs (it has no switching stage: d->stage is NULL). */
#define DRIVE_AVERAGED(d) DRIVE_OPTIONAL((d)->stage == NULL)

/* Whether this build has what the options ask for (see DRIVE_OPTIONAL). */
static inline bool drive_options_built(drive_inverter inverter, coupling_down down,
                                       coupling_up up, bool energy_audit) {
    return UUV_LEAN_IMAGE == 0 ||
           (inverter == DRIVE_INVERTER_SWITCHING && !energy_audit &&
            (down == COUPLE_ZOH || down == COUPLE_STAGGER) && up != COUPLE_FILTER);
}

/*
 * The drive segment (its fields per numeric build, below), and a port's
 * implementation of its real-time fast step (drive_use_fast_kernel).
 */
typedef struct drive_segment drive_segment;
typedef void drive_fast_kernel(drive_segment *d);


/*
 * The fields below are in the build's units: the fixed build's per unit
 * (drive_num_q.h says which format), the float build's SI.
 */

/* Sums of one motor frame, from the fast steps. */
typedef struct {
    num_sum v_cap[2];  /* capacitor voltages a, b (c = -a - b) */
    num_sum v_dc;      /* DC-link voltage */
    num_val i_mark[2]; /* the fast motor currents a, b at the boundary */
    num_val v_mark[2]; /* capacitor voltages at the boundary (sampled coupling) */
    num_filt filt_mark[2]; /* filtered capacitor voltages at the boundary */
    num_sum loss_l, loss_d; /* energy audit: sums of i_L^2, i_d^2 over phases and steps */
    uint32_t sat;      /* the fast models' saturation count at the boundary */
} drive_frame_sums;

/* What the motor task publishes for the next frame, latched at its boundary. */
typedef struct {
    pwm_rt_ramp ramp;          /* references of the real-time modulator */
    num_val e[2];              /* EMF at the frame start */
    num_val de[2];             /* its change per fast step (FOH, DERIV) */
    num_val corr[2];           /* motor minus fast current at the last frame end */
    bool cmd_new;              /* a new command for the general modulators */
    DRIVE_NUM(drive_control_out) cmd;
} drive_latch;

/* The slow frame's raw sums, handed from the motor task to the background. */
typedef struct {
    num_slow v_dc, v_dc_sq, w, te, i_sq[3], p_mech;
    num_slow loss_l, loss_d;   /* the frames' loss sums (energy audit) */
    double e_loss_motor_j;     /* [J] motor copper losses (energy audit) */
    uint32_t fast_n, medium_n;
    uint32_t limit_n;          /* controller frames with the torque (slip) limit acting */
    num_val w_filt, w_end;     /* filtered and final shaft speed */
    num_val v_dc_end;          /* DC-link voltage at the boundary */
    DRIVE_NUM(drive_control_out) cmd; /* the command in force at the boundary */
    uint32_t saturations;
    uint8_t trip;              /* drive_trip at the boundary */
} drive_slow_sums;

struct drive_segment {
    drive_config cfg;
    bool rt_path; /* the real-time path: switching, ZOH or staggered, mean or sample */
    drive_fast_kernel *fast_now; /* kernel while rt_path, else NULL: what drive_fast_step() calls */
    /* Fast segment: the real-time modulator and power stage (switching), or the general ones. */
    pwm_rt rt;
    int32_t s[3];               /* leg states of the last step (switching) */
    DRIVE_NUM(pwm) pwm;
    DRIVE_NUM(power_stage) ps;
    DRIVE_NUM(inverter_quasi_static) avg_stage; /* the averaged layer's stage */
    /* The averaged stage's DC-link constants: in force, and for the next slow frame. */
    DRIVE_NUM(inverter_quasi_static_bus) bus, bus_next;
    DRIVE_NUM(pwm) *mod;        /* the general modulator in use (event or averaged) */
    DRIVE_NUM(power_stage) *stage; /* the power stage in use (ps; NULL in the averaged layer) */
    DRIVE_NUM(pwm_out) pout;    /* the general modulator's last step */
    DRIVE_NUM(power_stage_in) in; /* duties, motor currents, battery: the fast inputs */
    /* The motor's fast companion (see above): currents a, b, EMF. */
    num_val i_fast[2];          /* in the power stage's format */
    num_val e[2];               /* the EMF in force */
    num_val e_step[2];          /* its change per fast step (FOH, DERIV) */
    num_val NUM_RT_GAIN;        /* the companion's gain on the real-time path */
    num_consts k;               /* the companion's and the EMF's other constants */
    num_filt filt[2];           /* filtered capacitor voltages (COUPLE_FILTER) */
    num_frac filt_k;            /* filter gain per fast step */
    num_val k_deriv;            /* EMF rotation per fast step per unit frequency */
    drive_frame_sums sums;      /* the frame being summed */
    /* Buffers between the fast step and the motor task. */
    drive_frame_sums medium_in; /* published at the boundary, read by the motor task */
    drive_latch out;            /* written by the motor task, latched at the next boundary */
    /* Fast-medium segment: the motor. */
    DRIVE_NUM(induction_motor) motor;
    DRIVE_NUM(induction_motor_out) mout;
    num_val i_prev[2];          /* motor currents at the frame start */
    num_val e_prev[2];          /* EMF of the previous frame (FOH) */
    num_val corr_prev[2];       /* the last drift correction, steered out through the EMF */
    num_frac corr_pending;      /* how much of it is still to come at a frame's mark */
    uint32_t ref_ph;            /* reference phase at the start of the next frame to ramp */
    pwm_rt_knots ref_end;       /* the references at the end of the last frame ramped */
    DRIVE_NUM(drive_control_out) cmd; /* the controller command in force */
    /* Slow-medium segment: the controller, its own task. */
    drive_control_params ctl_params;
    DRIVE_NUM(drive_control) ctl;
    DRIVE_NUM(drive_control_in) ctl_in; /* latched by the motor task at the controller's release */
    DRIVE_NUM(drive_control_out) ctl_out; /* written by the controller task */
    bool ctl_done;              /* ctl_out holds a result not yet taken */
    NUM_CONTROL_SAT_FIELDS      /* the controller's saturation count, where it counts */
    num_val speed_cmd;          /* the shaft speed command */
    /* Slow sums, kept by the motor task. */
    drive_slow_sums slow;       /* the slow frame being summed */
    drive_slow_sums slow_out;   /* the last slow frame's, for the background */
    num_val w_filt;             /* filtered shaft speed (COUPLE_FILTER) */
    DRIVE_NUM(ps_battery) battery_next; /* battery companion waiting for the next slow boundary */
    bool battery_new;           /* battery_next is new (background -> fast tick) */
    bool battery_taken;         /* it took over at this slow boundary (fast tick -> motor task) */
    drive_battery bat_next, bat_in_force, bat_done; /* the same in SI: next, now, last frame
                                 * (the motor task's bookkeeping at a slow boundary) */
    uint32_t ps_clamps;         /* battery companion values clamped by the power stage */
    /* Faults: requested by the slow segment, applied at a slow boundary. */
    drive_faults fault, fault_next;
    bool fault_new;
    num_val neg_k_c_next;       /* the DC-link coefficient for fault_next */
    DRIVE_NUM(induction_motor_drag) load_next; /* the motor's drag rows for fault_next */
    num_val i_offset, i_offset_next; /* the current-sensor offset */
    num_val uv;                 /* DRIVE_UV_TRIP_V */
    power_stage_params ps_params; /* the stage's parameters, the capacitance as faulted */
    uint8_t trip;               /* drive_trip: written by the fast step only */
    uint8_t trip_req;           /* a trip the background requested, applied at a slow boundary */
    bool uv_req;                /* the motor task saw an under-voltage (latched next) */
    bool rt_path_ok;              /* the configuration allows the real-time path */
    bool staggered;             /* the latch comes half a frame after the release */
    bool kernel_ok;             /* the real-time path is the one a port's kernel computes */
    drive_fast_kernel *kernel;  /* a port's real-time step, or NULL (drive_use_fast_kernel) */
};

/* Checks the configuration and initialises every model at its step. */
drive_status drive_init(drive_segment *d, const drive_config *cfg, const propeller_model *prop);

/* One fast step (the 2 us interrupt's work). */
void drive_fast_tick(drive_segment *d);

/* n fast steps in a row (the desk's: the same results as n drive_fast_step() calls). */
void drive_fast_run(drive_segment *d, uint32_t n);

/*
 * Hands the real-time step to a port's kernel, or back to the C when
 * kernel is NULL: the drive's real-time path (switching inverter, no dead
 * time, held EMF, the mean or sampled coupling, no faults) with the
 * sub-step modulator by its frame plans (pwm_rt.h), the step such a
 * kernel computes. The kernel must compute what drive_fast_tick()
 * computes there, bit for bit (ports/cortexm's for ARMv7-M is tested
 * against it); every other path, the sampled modulator's included, stays
 * the C's. Call it after drive_init().
 */
void drive_use_fast_kernel(drive_segment *d, drive_fast_kernel *kernel);

/* The fast step as the executive takes it: the kernel on the real-time path, else the C. */
static inline void drive_fast_step(drive_segment *d) {
    if (d->fast_now != NULL) {
        d->fast_now(d);
    } else {
        drive_fast_tick(d);
    }
}

/*
 * The motor-frame boundary, called from the fast tick in two halves, with
 * no fast step between them; the motor task may start after the second.
 * - drive_medium_publish(), after the frame's last fast step, hands the
 *   frame's sums to the next motor task.
 * - drive_medium_begin(), before the next frame's first fast step, latches
 *   what the motor task published (the next frame's reference ramps, EMF
 *   and current correction; with staggering that comes half a frame later,
 *   drive_medium_latch()) and marks the fast current the frame starts
 *   from; at a slow boundary it applies the faults and trips requested and
 *   the next battery companion takes over. The averaged layer forms its
 *   frame here.
 * The halves may run in one fast tick or in two consecutive ones (the
 * executive's choice, to spread the boundary's work): the results are the
 * same. Each is a few copies: the motor task prepares everything.
 */
void drive_medium_publish(drive_segment *d);
void drive_medium_begin(drive_segment *d, bool slow_boundary);
void drive_medium_latch(drive_segment *d);

/* True when the motor task's results take effect half a frame after its release (stagger). */
static inline bool drive_staggered(coupling_down down, uint32_t fast_per_medium) {
    return down == COUPLE_STAGGER && fast_per_medium >= 2u;
}

/*
 * The motor task: one motor step, the next frame's references and EMF.
 * When control_due, it takes the controller's last result as the command
 * (the controller task released one control frame earlier must be done:
 * drive_control_pending() says if it is not) and latches the controller's
 * next inputs. When slow_boundary, it hands the slow frame's sums over.
 */
void drive_medium_task(drive_segment *d, bool control_due, bool slow_boundary);

/* The controller task, released by the motor task at each control frame. */
void drive_control_task(drive_segment *d);

/* Sets the battery companion and the speed command before the first tick. */
void drive_start(drive_segment *d, const drive_battery *battery);

/* Sets the shaft speed command [rad/s]; the controller task's caller sets it before each step. */
void drive_speed_command(drive_segment *d, double speed_radps);

/*
 * The slow segment's side, in the background after a slow boundary: the
 * measurements of the slow frame that ended (converted to SI here, not in
 * the motor task), and the battery companion for the next slow frame,
 * which the fast step applies from the next slow boundary on, so that one
 * companion holds over each whole slow frame.
 */
void drive_slow_measure(const drive_segment *d, drive_slow_meas *meas);
void drive_battery_next(drive_segment *d, const drive_battery *next);

/*
 * Requests faults (the slow segment, in the background): they replace the
 * ones in force at the next slow boundary. The DC-link coefficients are
 * computed here, not in the fast step.
 */
void drive_fault_request(drive_segment *d, const drive_faults *f);

/*
 * Requests a trip the slow segment's protection decided (background): the
 * gates are blocked from the next slow boundary on, as for a fault.
 */
void drive_trip_request(drive_segment *d, drive_trip why);

/* The fast signals now, in SI units, for the trace. */
void drive_trace(const drive_segment *d, drive_trace_row *row);

/* Shaft speed now [rad/s] (for the slow segment's first frame). */
double drive_shaft_radps(const drive_segment *d);

#endif /* UUV_DRIVE_SEGMENT_H */

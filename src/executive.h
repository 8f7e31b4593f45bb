/*
 * The multi-rate executive: owns every model instance and runs them at
 * their frames from a scenario (paper section 4; docs/multirate.md).
 *
 *   fast    2 us    PWM, inverter, DC link, LC filter        exec_fast_tick()
 *   medium  100 us  induction motor (+ the 800 us controller) exec_medium_tick()
 *   slow    100 ms  battery, vessel, scenario, telemetry     exec_slow_step()
 *
 * The frames are parameters (integer ratios checked at init). A port calls
 * exec_fast_tick() every fast step, from a loop (Linux) or from the highest
 * priority timer interrupt (Cortex-M). It returns true when it has released
 * the medium task, which the port then runs (at once on Linux; as a pended,
 * lower-priority interrupt on Cortex-M). When exec_slow_pending() is true
 * the background runs exec_slow_step().
 *
 * Determinism. Every datum that crosses between rates waits in a buffer of
 * the drive segment or of this executive: the fast tick latches the medium
 * task's outputs at a motor-frame boundary (or half a frame later when the
 * coupling is staggered), the medium task reads only what the fast tick
 * published at its release, and the slow segment's battery companion takes
 * effect at a slow boundary. A slower task that is still running when its
 * results are due is an overrun: it is counted and ends the run (the
 * results would otherwise depend on timing), never silently. On the desk,
 * where the tasks run in sequence, there are none. A boundary's work is
 * spread over the ticks around it (the publish after the frame's last
 * step, the latch before the next frame's first, the release after its
 * second; fast_event() in executive.c), so that no tick carries it all;
 * the results are those of doing it at once.
 *
 * The averaged layer (inverter averaged, inverter_avg.h) runs its
 * quasi-static stage and the motor together at the controller's frame
 * (800 us): one fast tick, one motor step and one controller step per
 * frame. The stage is algebraic in what the boundary's latch takes (the
 * command, the motor currents at the frame's start), so it runs at the
 * boundary, ahead of the motor task that integrates its frame; the
 * controller's result then acts one control frame after its inputs, as in
 * the single-rate reference (the switching model's pipeline adds a motor
 * frame, 100 us).
 *
 * In single-rate mode every segment that integrates runs at the fast frame
 * (the paper's baseline): the same code with the motor and slow ratios 1,
 * and telemetry still every 100 ms. The controller keeps its 800 us sample
 * period: it is a digital controller, whose sample rate belongs to the
 * drive's design, not an integration step of the simulation.
 */
#ifndef UUV_EXECUTIVE_H
#define UUV_EXECUTIVE_H

#include <stdbool.h>
#include <stdint.h>

#include "drive_segment.h"
#include "manoeuvre.h"
#include "models/battery/battery.h"
#include "models/propeller/propeller.h"
#include "models/vessel/vessel.h"
#include "protection.h"
#include "params.h"
#include "scenario.h"
#include "scenario_player.h"

typedef enum {
    EXEC_PLANT_VESSEL = 0, /* vessel alone, shaft speed commanded through its lag */
    EXEC_PLANT_FULL        /* battery, drive and vessel */
} exec_plant;

#define EXEC_NCMD 5 /* rudder, stern, bow_port, bow_stbd [rad], n [rpm] */

typedef struct {
    exec_plant plant;
    vessel_propulsion propulsion;
    drive_inverter inverter;
    drive_modulator modulator; /* the switching inverter's: sub-step (default) or sampled */
    coupling_down down;
    coupling_up up;
    bool single_rate;
    bool deep_water;       /* no free surface: the reference vessel of tests/vectors */
    bool energy_audit;     /* count the drive's losses (exec_counters; the general fast path) */
    double duration_s;     /* [s]; 0: the scenario's */
    double soc0;           /* [-] initial state of charge */
    uint32_t fast_ns;      /* [ns] fast frame (2000) */
    uint32_t fast_per_medium;    /* 50 */
    uint32_t medium_per_control; /* 8 */
    uint32_t medium_per_slow;    /* 1000 */
    const uuv_params *params;    /* the models' parameters; NULL: uuv_params_default */
} exec_config;

/* One telemetry record: the state at a reported slow boundary. */
typedef struct {
    uint32_t index;            /* reported frame number */
    double t_s;                /* [s] */
    double x[VESSEL_NSTATES];  /* vessel state (x[VESSEL_N_RPM]: the shaft speed) */
    double cmd[EXEC_NCMD];     /* commands held over the next step */
    /* Full plant, means over the reporting period (zero in vessel-only runs). */
    double te_nm;              /* [N m] electromagnetic torque */
    double i_rms_a;            /* [A] rms phase current */
    double v_dc_v;             /* [V] DC-link voltage */
    double i_batt_a;           /* [A] battery current, positive when discharging */
    double soc;                /* [-] state of charge */
    double m_index;            /* [-] modulation index */
    double f_hz;               /* [Hz] stator frequency */
    uint32_t faults;           /* active fault commands: bit k for command SCN_FIRST_FAULT + k */
    uint32_t trip;             /* drive_trip: the drive's protection */
} exec_frame;

typedef enum {
    EXEC_OK = 0,
    EXEC_ERR_CONFIG, /* a rate, ratio, duration or option out of range */
    EXEC_ERR_MODEL,  /* a model refused its parameters */
    EXEC_ERR_DURATION_SHORT, /* the duration rounds to no record (less than half a period) */
    EXEC_ERR_DURATION_LONG,  /* the duration needs more frames than the counters hold */
    EXEC_ERR_SLOW_FRAME,     /* the slow frame beyond 10 s, or below 1 ms for the vessel plant */
    EXEC_ERR_LAYER           /* an inverter layer, coupling or audit the build leaves out
                              * (UUV_LEAN_IMAGE, uuv_config.h) */
} exec_status;

/* Why a run ended early. */
typedef enum {
    EXEC_RUNNING = 0,
    EXEC_DONE,              /* the scenario's duration was reached */
    EXEC_STOP_OVERRUN,      /* a task missed its deadline */
    EXEC_STOP_NONFINITE     /* a state or a reported value became NaN or infinite, or a
                             * velocity diverged (beyond EXEC_DIVERGED) */
} exec_state;

/* [m/s, rad/s] A body velocity beyond this has diverged: 250 times the top speed. */
#define EXEC_DIVERGED 1e3

/* exec.nonfinite: bit i for vessel state i; this bit, 1 << VESSEL_NSTATES, for the
 * drive's and battery's values. */
#define EXEC_NONFINITE_DRIVE 0x20000u

typedef struct {
    double e_batt_j;      /* [J] energy delivered by the battery at its terminals */
    double e_mech_j;      /* [J] mechanical energy delivered to the shaft */
    double e_loss_filter_j; /* [J] LC filter losses (energy audit only) */
    double e_loss_motor_j;  /* [J] motor copper losses (energy audit only) */
    double limit_s;       /* [s] time the drive's torque (slip) limit acted, until a trip */
    uint64_t medium, control, slow; /* steps run (the fast ones: exec_fast_steps()) */
    uint32_t overruns_medium, overruns_control, overruns_slow;
    uint32_t saturations; /* fixed-point saturation events (fast models) */
} exec_counters;

/*
 * What a slow step hands the drive (the slow -> drive buffer), applied by
 * exec_drive_take(): all of it takes effect at the next slow boundary.
 */
typedef struct {
    drive_battery bat_next; /* the battery companion for the next slow frame */
    const drive_faults *faults; /* the fault set, when a fault command was applied at this
                                 * boundary (the player's); NULL: the faults stay */
    uint8_t trip;           /* drive_trip the protection requests (DRIVE_TRIP_NONE: none) */
    uint8_t state;          /* exec_state after the step: the run goes on or ends */
} exec_to_drive;

typedef struct {
    exec_state state;
    /* Schedule: the fast tick's counters first, near the start (short offsets). */
    volatile uint8_t fast_gate; /* EXEC_GATE_*: work before the next fast step (0: none) */
    uint32_t fast_phase;      /* fast steps since the last motor-frame boundary */
    uint32_t fast_event_at;   /* fast_phase of the tick's next event (fast_event()) */
    uint32_t medium_left;     /* motor frames of the run not yet ended */
    exec_config cfg;
    /* Frames. */
    uint32_t slow_per_report; /* slow frames per telemetry record */
    double slow_s;            /* [s] slow frame */
    double report_s;          /* [s] reporting period */
    double report_ns;         /* [ns] the same, a whole number */
    uint32_t frames;          /* slow frames in the run */
    /* Slow segment. */
    propeller_model prop;
    vessel_model vessel;
    double x[VESSEL_NSTATES];
    vessel_cmd cmd;
    battery_params bat_params;
    battery bat;
    uint32_t frame;           /* slow frames done */
    uint32_t nonfinite;       /* EXEC_STOP_NONFINITE: what became non-finite in frame `frame`;
                               * report then holds the last finite record */
    scenario_player player;   /* the scenario's commands, faults and autopilots (scenario_player.h) */
    protection prot;          /* the drive's phase-loss protection (protection.h) */
    bool drive_ready;         /* the drive is initialised (faults may be requested) */
    double trip_t_s;          /* [s] when the drive tripped (< 0: it has not) */
    manoeuvre man;
    /* Drive (full plant). */
    drive_segment drive;
    double speed_report_rpm;  /* the controller's speed command (player.speed_rpm) at the
                               * last slow boundary, for the record: the slow step must not
                               * read player.speed_rpm, which the controller task may change
                               * while a preempted slow step runs */
    double shaft_start_rpm;   /* [rpm] shaft speed at the start of the slow frame */
    /* Schedule (continued). */
    uint32_t stagger_at;      /* fast_phase of the staggered latch (0: not staggered) */
    bool split;               /* the boundary's halves run in two fast ticks (exec_fast_tick) */
    uint32_t medium_phase;    /* motor frames since the last controller frame */
    uint32_t slow_phase;      /* boundaries counted since the last slow one (slow_count) */
    volatile bool medium_busy;
    volatile bool control_busy;
    volatile bool slow_pending;
    bool slow_due;              /* the next motor-frame boundary is a slow one */
    bool rel_slow;              /* the released medium task is at a slow boundary */
    uint64_t control_time_ns;   /* release time of the controller task */
    drive_slow_meas meas;       /* the slow frame's measurements (medium task -> slow) */
    exec_to_drive down;         /* the slow step's results for the drive (slow -> drive) */
    /* Report accumulation over the reporting period. */
    double acc_te, acc_i_sq, acc_v_dc, acc_i_batt, acc_m, acc_f;
    uint32_t acc_n;
    exec_frame report;
    bool report_ready;
    exec_counters count;
    /* The desk's runs of fast steps (exec_desk_run()): NULL for drive_fast_run() on the
     * ticks before an event, or a port's runner called as desk_run(desk_ctx, drive, n)
     * on the ticks up to and including the event's (the Linux port's exact leaps,
     * ports/linux/leap.h). Set after exec_init(); the firmware never sets it. */
    void (*desk_run)(void *ctx, drive_segment *d, uint32_t n);
    void *desk_ctx;
} exec;

extern const char *const exec_command_names[EXEC_NCMD];

/*
 * Default: full plant, paper propulsion, switching inverter with the
 * sub-step modulator and no dead time, ZOH/average, 2 us/100 us/800 us/100 ms.
 */
void exec_config_default(exec_config *cfg);

/* Checks the configuration against the scenario and initialises every model. */
exec_status exec_init(exec *e, const exec_config *cfg, const scenario *scn);

/*
 * Whether the configuration models every command of the scenario. The
 * drive's faults need the full plant (the vessel plant has no drive), and
 * the faults that end in blocked gates (switch_open, leg_short, phase_open,
 * battery_cutoff) need an inverter with switches: the averaged layer has
 * none to fault or to block, so it would keep modulating through them.
 * Returns true, or false with *err naming the first such command (its
 * line and name, and what to choose instead). exec_init() does not call
 * it: a port that offers these options does, before it (the firmware runs
 * the default configuration, which models every command).
 */
bool exec_check_scenario(const exec_config *cfg, const scenario *scn, scenario_error *err);

/*
 * The fast tick's work besides a plain step: a boundary's half, a release,
 * the staggered latch, the run's end (exec_fast_tick() calls it).
 */
bool exec_fast_tick_event(exec *e);

/*
 * The fast tick; true when it released the medium task. Once the run's
 * last fast step and the release after it have run (exec_fast_ended(),
 * true right after that release) it does nothing: a port stops its timer
 * then. Inline, so that a tick with nothing but its step makes no call
 * besides the step's.
 */
static inline bool exec_fast_tick(exec *e) {
    if (e->fast_gate == 0u && e->fast_phase + 1u != e->fast_event_at) {
        drive_fast_step(&e->drive);
        e->fast_phase++;
        return false;
    }
    return exec_fast_tick_event(e);
}

/* Work a fast tick does before its step (exec.fast_gate). */
#define EXEC_GATE_STOP 1u  /* no more fast steps: the run ended or stopped */
#define EXEC_GATE_BEGIN 2u /* the second half of a motor-frame boundary */
#define EXEC_GATE_LAST 4u  /* that of the run's last boundary, without a step */

/* True once the run's fast ticks are over (or the run stopped). */
static inline bool exec_fast_ended(const exec *e) {
    return (e->fast_gate & EXEC_GATE_STOP) != 0u;
}

/* The medium (motor) task; true when it released the controller task. */
bool exec_medium_tick(exec *e);

/*
 * The controller task, at a lower priority than the motor task: its result
 * is taken by the motor task at the next control boundary, so it may take
 * up to a control frame.
 */
void exec_control_tick(exec *e);

/* The background's slow step, when exec_slow_pending(). */
bool exec_slow_pending(const exec *e);
void exec_slow_step(exec *e);

/*
 * The slow step in its two halves, for a port that runs the drive and the
 * slow segment in different processes (the multi-party run,
 * docs/cosimulation.md); exec_slow_step() is
 *   drive_slow_measure(&e->drive, &e->meas);  exec_slow_model(e);
 *   exec_drive_take(e, &e->down);
 * (the vessel plant: the model alone).
 * - exec_slow_model(): the slow segment (battery, protection, vessel,
 *   scenario, telemetry record) from e->meas, the drive's measurements of
 *   the frame that ended, and e->speed_report_rpm, the controller's speed
 *   command at that boundary (the medium task sets it; a port that runs the
 *   drive elsewhere sets both from what the drive sent). Its results for the
 *   drive are in e->down.
 * - exec_drive_take(): the drive's side, in the executive that runs the
 *   drive: applies what a slow step produced (its own, or another
 *   process's), ends the run if that step ended it, and clears the pending
 *   slow step.
 */
void exec_slow_model(exec *e);
void exec_drive_take(exec *e, const exec_to_drive *d);

/*
 * The desk loop's unit of work: one fast tick and whatever it released, in
 * the order a target's interrupts run them when none overruns. In
 * vessel-only runs, one slow step.
 */
void exec_desk_step(exec *e);

/*
 * The desk loop's fast way: up to max_ticks exec_desk_step()s, with the
 * same results, returning how many ran (none when max_ticks is 0). The
 * fast ticks before the next one with an event (a motor-frame boundary, a
 * release or a latch) only step, and step as one drive_fast_run(); the
 * event's tick follows as exec_desk_step(), and the call returns after it,
 * so that a report or the run's end is seen when it happens.
 */
uint32_t exec_desk_run(exec *e, uint32_t max_ticks);

/*
 * exec_desk_run() in its two halves, for a port that runs the steps of
 * several runs together (the desk's batches, ports/linux/batch.c):
 *   n = exec_desk_ahead(e, max_ticks);   the ticks that only step (0: none)
 *   drive_fast_run(&e->drive, n);        or the same steps computed elsewhere
 *   exec_desk_finish(e, n, max_ticks);   counts them; the event's tick
 * is exec_desk_run(e, max_ticks) without a desk_run and outside the
 * averaged layer's frames
 * (which exec_desk_ahead() leaves to exec_desk_run(): it returns 0 there,
 * as at any tick with work before its step).
 */
uint32_t exec_desk_ahead(const exec *e, uint32_t max_ticks);
uint32_t exec_desk_finish(exec *e, uint32_t stepped, uint32_t max_ticks);

/*
 * exec_desk_step() in its parts around the tick's fast step, for the same
 * ports, where exec_desk_step() would run next (with no exec_desk_ahead()
 * steps before it, or after them):
 *   if (exec_desk_tick_begin(e)) {     the work before the step (a latch)
 *       drive_fast_step(&e->drive);    or the same computed elsewhere
 *       exec_desk_tick_end(e);         the count, the event, the tasks
 *   } else {
 *       exec_desk_step(e);             a tick without a step, the vessel
 *   }                                  plant, the averaged layer's frames
 */
bool exec_desk_tick_begin(exec *e);
void exec_desk_tick_end(exec *e);

/*
 * A whole split motor frame as one run of its steps, for the same ports
 * and for a desk_run (the leaps): where exec_desk_tick_begin() has just
 * begun the frame's first tick (begin: the gate was EXEC_GATE_BEGIN
 * before it, the boundary's second half) and the frame fits in max_ticks
 * (exec_desk_frame_whole()),
 *   n = exec_desk_frame_begin(e);   the release's work, ahead of the steps
 *   drive_fast_run(&e->drive, n);   or the same steps computed elsewhere
 *   exec_desk_frame_end(e, n);      the boundary's first half, its tasks
 * gives the results of the frame's exec_desk_step()s (executive.c).
 */
bool exec_desk_frame_whole(const exec *e, bool begin, uint32_t max_ticks);
uint32_t exec_desk_frame_begin(exec *e);
void exec_desk_frame_end(exec *e, uint32_t n);

/*
 * A command given between slow steps, as a scenario event at the slow
 * boundary just reached would have been: a co-simulation master's input
 * at a communication point (ports/fmu). Call it after the boundary's slow
 * step and before the controller task released with it (exec_control_tick())
 * and the next fast tick: the controller then takes a shaft speed command
 * at the boundary, and the vessel the fins and buoyancy over the next slow
 * frame, exactly as from a scenario event at that time. Fault commands go
 * through the scenario only; this takes c < SCN_FIRST_FAULT.
 */
void exec_command(exec *e, scenario_command c, double value);

/* Takes the telemetry record made by the last slow step, if any. */
bool exec_report_take(exec *e, exec_frame *out);

/* Overruns at every rate the executive sees (the fast tick's are the port's). */
uint32_t exec_overruns(const exec *e);

/* Fast steps run so far. */
uint64_t exec_fast_steps(const exec *e);

/* Simulated time now [s]. */
double exec_time_s(const exec *e);

const manoeuvre_result *exec_manoeuvre(const exec *e);

#endif /* UUV_EXECUTIVE_H */

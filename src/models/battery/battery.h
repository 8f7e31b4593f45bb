/*
 * The battery of the vehicle: a pack of identical lithium-ion cells, each an
 * equivalent circuit with an open-circuit voltage that depends on the state
 * of charge, a series resistance R0 and one polarisation branch R1 || C1.
 * All cell parameters are tables over the state of charge, interpolated
 * linearly. docs/battery.md gives the equations, the pack sizing and the
 * sources of the numbers.
 *
 * Sign convention (the same for every component on the DC bus): the current
 * i is positive INTO the battery's positive terminal from the bus, so a
 * discharging battery carries a negative i, and the power v*i is negative
 * when the battery delivers energy. With every current counted into its
 * component, the bus solver writes sum(i_k) = 0.
 *
 * Cell equations, with v1 the voltage across R1 || C1 measured in the
 * direction of i (negative while discharging):
 *
 *   v_cell  = OCV(soc) + v1 + R0(soc) * i_cell
 *   dv1/dt  = -v1 / (R1 * C1) + i_cell / C1
 *   dsoc/dt = i_cell / Q
 *
 * and for the pack of n_series x n_parallel cells, i_cell = i / n_parallel
 * and v = n_series * v_cell.
 *
 * Natural coupling: before each slow frame the battery exports (G, b) such
 * that i = G*v - b over the whole frame, the frame-average form of the
 * equations above with the state of charge and the RC parameters of the
 * frame start (battery_companion_f64). The fast segment solves the DC bus
 * with it, then hands back the frame means of i, i^2 and v*i, with which
 * battery_step_f64 advances the state by charge counting and the exact
 * exponential solution of the RC branch.
 *
 * Cut-off: when the loaded cell voltage at the end of a frame is at or below
 * the cut-off voltage, or the state of charge reaches zero, a contactor
 * opens: from the next frame the battery exports G = 0, b = 0, so no current
 * can flow whatever the bus voltage, and the cut-off stays latched until
 * battery_init or battery_reset.
 */
#ifndef UUV_BATTERY_H
#define UUV_BATTERY_H

#include <stdbool.h>
#include <stdint.h>

/* Largest number of state-of-charge breakpoints a cell table may hold. */
#define BATTERY_TABLE_MAX 16u

/* One cell's parameters as tables over the state of charge. */
typedef struct {
    uint32_t n_points;                  /* number of breakpoints, 2..BATTERY_TABLE_MAX */
    double soc[BATTERY_TABLE_MAX];      /* [-] breakpoints: 0 first, 1 last, rising */
    double ocv_v[BATTERY_TABLE_MAX];    /* [V] open-circuit voltage, non-decreasing */
    double r0_ohm[BATTERY_TABLE_MAX];   /* [ohm] series resistance */
    double r1_ohm[BATTERY_TABLE_MAX];   /* [ohm] polarisation resistance */
    double c1_f[BATTERY_TABLE_MAX];     /* [F] polarisation capacitance */
} battery_cell_table;

typedef struct {
    battery_cell_table cell;
    double capacity_ah;       /* [A h] charge of one cell between soc = 0 and soc = 1 */
    uint32_t n_series;        /* [-] cells in series, 1..1000 */
    uint32_t n_parallel;      /* [-] strings in parallel, 1..1000 */
    double v_cutoff_cell_v;   /* [V] discharge cut-off of the loaded cell voltage */
    double v_max_cell_v;      /* [V] charge limit; frames above it are counted */
    double frame_s;           /* [s] slow frame h, (0, 10] */
} battery_params;

typedef enum {
    BATTERY_OK = 0,
    BATTERY_ERR_NULL,     /* a pointer argument was NULL */
    BATTERY_ERR_TABLE,    /* breakpoint count, ends, order, or an OCV that falls */
    BATTERY_ERR_CELL,     /* a resistance, capacitance, OCV or capacity not positive/finite */
    BATTERY_ERR_PACK,     /* series or parallel count out of 1..1000 */
    BATTERY_ERR_LIMITS,   /* cut-off not below the full OCV, or max not above cut-off */
    BATTERY_ERR_FRAME,    /* frame time not in (0, 10] s */
    BATTERY_ERR_SOC       /* initial state of charge not in [0, 1] */
} battery_status;

typedef enum {
    BATTERY_CUTOFF_NONE = 0,
    BATTERY_CUTOFF_VOLTAGE,   /* the loaded cell voltage reached v_cutoff_cell_v */
    BATTERY_CUTOFF_EMPTY      /* the state of charge reached 0 */
} battery_cutoff_cause;

/* Companion of the battery for one slow frame: i = g_s * v - b_a. */
typedef struct {
    double g_s;   /* [S] conductance, 0 when the contactor is open */
    double b_a;   /* [A] current source term, 0 when the contactor is open */
} battery_companion;

/* What the fast segment measured at the battery terminals over one frame. */
typedef struct {
    double i_avg_a;       /* [A] mean current into the + terminal (negative on discharge) */
    double i_sq_avg_a2;   /* [A^2] mean of i^2; pass i_avg_a^2 when not measured */
    double p_avg_w;       /* [W] mean of v*i into the terminal (negative on discharge) */
} battery_frame_meas;

typedef struct {
    const battery_params *p;
    /* State at the start of the next frame. */
    double soc;              /* [-] state of charge, by charge counting (not clamped) */
    double v1_cell_v;        /* [V] polarisation voltage of one cell, in the direction of i */
    uint32_t frames;         /* frames stepped since init or reset */
    /* Companion for the next frame and the terms it was built from. */
    double alpha;            /* [-] exp(-h / tau) of the RC branch over one frame */
    double k_mean;           /* [-] mean over the frame of exp(-t / tau), (1 - alpha) tau / h */
    double e_eff_v;          /* [V] pack source voltage of the frame-average relation */
    double r_eff_ohm;        /* [ohm] pack resistance of the frame-average relation */
    double ocv_cell_v;       /* [V] cell open-circuit voltage at the frame start */
    double r0_cell_ohm;      /* [ohm] cell R0 frozen over the frame */
    double r1_cell_ohm;      /* [ohm] cell R1 frozen over the frame */
    double tau_s;            /* [s] R1 * C1 frozen over the frame */
    battery_companion companion;
    /* Cut-off, latched. */
    bool cut_off;
    battery_cutoff_cause cutoff_cause;
    double t_cutoff_s;       /* [s] time of the end of the frame that tripped it */
    double soc_cutoff;       /* [-] state of charge when it tripped */
    /* Outputs of the last frame. */
    double i_last_a;         /* [A] mean current of the last frame (into the terminal) */
    double v_cell_end_v;     /* [V] loaded cell voltage at the end of the last frame */
    /* Counters since init or reset, positive while discharging. */
    double q_out_c;          /* [C] charge delivered to the bus, -integral(i dt) */
    double e_out_j;          /* [J] energy delivered to the bus, -integral(v i dt) */
    double e_source_j;       /* [J] energy taken from the open-circuit source */
    double e_loss_r0_j;      /* [J] heat in the series resistances, >= 0 */
    double e_loss_r1_j;      /* [J] heat in the polarisation resistances, >= 0 */
    uint32_t overvoltage_frames;  /* frames that ended above v_max_cell_v */
    uint32_t bad_input_frames;    /* frames whose measurement was not finite (taken as 0) */
} battery;

/*
 * The vehicle's pack: 144 series x 2 parallel high-power NMC pouch cells of
 * 27.63 A h (Huria et al. 2012, 20 degC), 0.1 s frame, 3.0 V cut-off,
 * 4.2 V charge limit. docs/battery.md explains the choice.
 */
extern const battery_params battery_params_uuv;

/*
 * Checks the parameters and the initial state of charge soc0 in [0, 1],
 * then starts the battery at rest (v1 = 0) with zeroed counters. A battery
 * that starts at or below its cut-off starts cut off. On an error the
 * instance is left unchanged. The battery keeps the pointer p: the
 * parameters must outlive it.
 */
battery_status battery_init(battery *b, const battery_params *p, double soc0);

/* Restarts an initialised battery at rest at soc0, keeping its parameters. */
battery_status battery_reset(battery *b, double soc0);

/* The companion (G, b) for the next frame; (0, 0) once cut off. */
battery_companion battery_companion_f64(const battery *b);

/*
 * Advances one slow frame with what the fast segment measured: charge
 * counting, exact RC update with the frame-mean current, energy counters,
 * cut-off check, and the companion for the next frame. Total: never fails.
 * Once cut off, the measured current is taken as zero (the contactor is
 * open) and only the RC branch relaxes.
 */
void battery_step_f64(battery *b, const battery_frame_meas *m);

/*
 * Frame-mean terminal voltage [V] for a constant current i_a [A] (into the
 * terminal) held over the next frame: the same relation as the companion,
 * v = (i + b) / G. 0 V once cut off (the bus side of an open contactor is
 * not driven by the battery).
 */
double battery_voltage_f64(const battery *b, double i_a);

/*
 * The current [A] (into the terminal, so negative) at which the battery
 * delivers the power p_out_w [W] over the next frame, on the same relation;
 * the root with the smaller magnitude. A demand beyond the largest power the
 * pack can deliver, e^2 / (4 r), gives the current of that largest power.
 * A negative p_out_w charges. 0 once cut off. For a simple DC bus (vessel-
 * only runs) and for tests.
 */
double battery_current_for_power_f64(const battery *b, double p_out_w);

/* Open-circuit voltage of one cell [V] at soc, clamped to the table ends. */
double battery_ocv_cell_f64(const battery_params *p, double soc);

/* Open-circuit voltage of the pack [V] at the present state of charge. */
double battery_ocv_pack_f64(const battery *b);

/* Charge of the pack between soc = 0 and soc = 1 [C]. */
double battery_capacity_pack_f64(const battery_params *p);

/* Elapsed simulated time [s]: frames stepped times the frame. */
double battery_time_f64(const battery *b);

/* A short English description of a status, for error messages. */
const char *battery_status_text(battery_status s);

#endif /* UUV_BATTERY_H */

/*
 * The executive's less travelled paths: configuration and model errors, the
 * vessel-only plant, the scenario player (fin commands, jammed fins, the
 * zig-zag rule, fault commands), every coupling and inverter option, the
 * single-rate reference, and the overrun of each rate. The full-plant runs
 * use 800 us slow frames and last a few milliseconds, so that the suite
 * stays cheap on a Cortex-M3 under QEMU; the references are the default
 * configuration's run, the scenario's own commands and the schedule's
 * arithmetic.
 */
#include "executive.h"
#include "math/umath.h"
#include "ut.h"

void suite_exec_paths(void);

static scenario scn;
static exec ex;

#define DEG (MATH_PI_F64 / 180.0)
#define MAX_RECS 12u

/* The records of the last run: the first MAX_RECS of them. */
static exec_frame recs[MAX_RECS];
static uint32_t n_recs;

static bool load(const char *text) {
    scenario_error err;
    return scenario_parse(&scn, text, ut_text_len(text), &err);
}

static void take_record(void) {
    exec_frame f;
    if (exec_report_take(&ex, &f) && n_recs < MAX_RECS) {
        recs[n_recs++] = f;
    }
}

/* Initialises and runs the desk loop to the end of the scenario, keeping the records. */
static exec_status run(const exec_config *c) {
    n_recs = 0u;
    exec_status st = exec_init(&ex, c, &scn);
    if (st != EXEC_OK) {
        return st;
    }
    take_record();
    for (uint32_t k = 0u; k < 1000000u && ex.state == EXEC_RUNNING; k++) {
        exec_desk_step(&ex);
        take_record();
    }
    return st;
}

/* Whether the build has the configuration's layer, couplings and audit (a lean image has not). */
static bool built(const exec_config *c) {
    return drive_options_built(c->inverter, c->down, c->up, c->energy_audit);
}

/* The full plant with 100 us motor frames and 800 us slow (and reporting) frames. */
static void config_small(exec_config *c) {
    exec_config_default(c);
    c->medium_per_slow = 8u;
}

static void config_vessel(exec_config *c) {
    exec_config_default(c);
    c->plant = EXEC_PLANT_VESSEL;
}

static uint32_t fault_bit(scenario_command k) {
    return 1u << ((uint32_t)k - (uint32_t)SCN_FIRST_FAULT);
}

/* ---- Configuration and model errors ------------------------------------- */

static void test_config_errors(void) {
    UT_TEST("exec_init: every rate, ratio, duration, state of charge and plant out of range "
            "is refused as a configuration error; the base configuration is accepted");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"));
    exec_config c;
    config_small(&c);
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    config_small(&c);
    c.fast_ns = 99u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.fast_per_medium = 0u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.medium_per_control = 0u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.medium_per_slow = 0u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.medium_per_slow = 12u; /* not a whole number of controller frames */
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.soc0 = 0.0;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    c.soc0 = 1.01;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.plant = (exec_plant)(EXEC_PLANT_FULL + 1);
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_CONFIG);
    config_small(&c);
    c.medium_per_slow = 200000u; /* a 20 s slow frame */
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_SLOW_FRAME);

    UT_TEST("exec_init: a duration that is missing, too long for the frame counter or "
            "shorter than half a reporting period is refused");
    exec_config_default(&c);
    c.duration_s = 0.01; /* a tenth of the 100 ms reporting period */
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_DURATION_SHORT);
    c.duration_s = 0.06; /* rounds to one reporting period */
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    UT_EQ_INT(ex.frames, 1);
    c.duration_s = 1.0e9;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_DURATION_LONG);
    /* Single-rate: 50000 slow frames per record, 1e5 records overflow 32 bits. */
    c.duration_s = 1.0e4;
    c.single_rate = true;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_DURATION_LONG);
    c.duration_s = 1.0e3;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    UT_CHECK(load("at 0 n_rpm=1000\n")); /* no duration line */
    exec_config_default(&c);
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_DURATION_SHORT);
    c.duration_s = 0.2;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);

    UT_TEST("exec_init: the vessel-only plant needs a slow frame of at least 1 ms and does "
            "not build the drive, so a fast frame the drive refuses is accepted there");
    UT_CHECK(load("duration 0.2\n"));
    config_vessel(&c);
    c.medium_per_slow = 8u; /* 0.8 ms */
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_SLOW_FRAME);
    config_vessel(&c);
    c.fast_ns = 30000u; /* 6.7 steps per 5 kHz carrier: the modulator refuses */
    c.fast_per_medium = 20u;
    c.medium_per_slow = 160u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    c.plant = EXEC_PLANT_FULL;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_MODEL);

    UT_TEST("exec_init: a model that refuses its parameters is a model error: the vessel "
            "with a 1.6 s step or an unknown propulsion law");
    exec_config_default(&c);
    c.medium_per_slow = 16000u;
    c.duration_s = 3.2;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_MODEL);
    c.plant = EXEC_PLANT_VESSEL;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_MODEL);
    config_vessel(&c);
    c.propulsion = (vessel_propulsion)7;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_MODEL);
}

/* ---- Vessel-only plant and the scenario player --------------------------- */

static void test_vessel_only(void) {
    UT_TEST("vessel-only plant: each command reaches the record at the first reporting "
            "boundary at or after its time, the shaft follows its 0.1 s lag, and the drive's "
            "fields stay zero");
    UT_CHECK(load("duration 1\n"
                  "init z_m=10\n"
                  "at 0 n_rpm=1000 buoyancy=200\n"
                  "at 0.3 rudder=10deg stern=-5deg\n"
                  "at 0.45 bow_port=3deg bow_stbd=-3deg\n"));
    exec_config c;
    config_vessel(&c);
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(ex.state, EXEC_DONE);
    UT_EQ_INT(n_recs, 11);
    UT_EQ_INT(ex.count.slow, 10);
    UT_EQ_INT(exec_fast_steps(&ex), 0);
    UT_NEAR(exec_time_s(&ex), 1.0, 1e-12);
    UT_NEAR(recs[2].cmd[0], 0.0, 0.0);
    UT_NEAR(recs[3].cmd[0], 10.0 * DEG, 1e-12);
    UT_NEAR(recs[3].cmd[1], -5.0 * DEG, 1e-12);
    UT_NEAR(recs[4].cmd[2], 0.0, 0.0);
    UT_NEAR(recs[5].cmd[2], 3.0 * DEG, 1e-12);
    UT_NEAR(recs[5].cmd[3], -3.0 * DEG, 1e-12);
    UT_NEAR(recs[10].cmd[4], 1000.0, 0.0);
    /* The lag integrated by RK4 with h = tau: 1 - (3/8)^k of the step. */
    UT_NEAR(recs[1].x[VESSEL_N_RPM], 625.0, 1.0);
    UT_NEAR(recs[10].x[VESSEL_N_RPM], 1000.0, 0.5);
    /* The fins follow the same lag from their command's time. */
    UT_CHECK(recs[10].x[VESSEL_DELTA_R_RAD] > 0.9 * 10.0 * DEG);
    UT_CHECK(recs[10].x[VESSEL_DELTA_BS_RAD] < -0.9 * 3.0 * DEG);
    /* Positive buoyancy: the vehicle rises (depth positive down). */
    UT_CHECK(recs[10].x[VESSEL_W_MPS] < 0.0);
    bool drive_zero = true;
    for (uint32_t k = 0u; k < n_recs; k++) {
        drive_zero = drive_zero && recs[k].te_nm == 0.0 && recs[k].i_rms_a == 0.0 &&
                     recs[k].v_dc_v == 0.0 && recs[k].trip == 0u && recs[k].faults == 0u;
    }
    UT_CHECK(drive_zero);

    UT_TEST("a finished run does nothing more: no fast tick, no slow step, no record");
    exec_slow_step(&ex);
    UT_CHECK(!exec_fast_tick(&ex));
    UT_EQ_INT(ex.count.slow, 10);
    exec_frame f;
    UT_CHECK(!exec_report_take(&ex, &f));
}

static void test_fin_jam(void) {
    UT_TEST("fin_jam: the jammed fin's command freezes at its actual angle and later "
            "commands to it are ignored, while the other fins still obey");
    UT_CHECK(load("duration 1\n"
                  "at 0 stern=10deg\n"
                  "at 0.5 fin_jam=stern rudder=5deg\n"
                  "at 0.8 stern=-10deg rudder=-5deg\n"));
    exec_config c;
    config_vessel(&c);
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(n_recs, 11);
    double jam = recs[5].cmd[1];
    UT_NEAR(jam, recs[5].x[VESSEL_DELTA_S_RAD], 0.0);
    UT_CHECK(jam > 5.0 * DEG && jam < 10.0 * DEG);
    UT_NEAR(recs[4].cmd[1], 10.0 * DEG, 1e-12);
    UT_NEAR(recs[10].cmd[1], jam, 0.0);
    UT_NEAR(recs[5].cmd[0], 5.0 * DEG, 1e-12);
    UT_NEAR(recs[8].cmd[0], -5.0 * DEG, 1e-12);
    UT_EQ_INT(recs[4].faults, 0);
    UT_EQ_INT(recs[5].faults, fault_bit(SCN_FAULT_FIN_JAM));
    UT_EQ_INT(recs[10].faults, fault_bit(SCN_FAULT_FIN_JAM));
}

/* What a zig-zag run did with its rudder command, record by record. */
typedef struct {
    uint32_t switches;     /* reversals of the rudder command */
    uint32_t bad_switches; /* reversals before the heading passed the threshold */
    double before_start;   /* largest |rudder| before the start */
    double after_stop;     /* the rudder command at the end */
    double jam_value;      /* the command at the jam's time */
    bool jam_held;         /* the command stayed at jam_value from then on */
} zigzag_log;

static void run_zigzag(const exec_config *c, double start_s, double threshold,
                       double jam_s, zigzag_log *log) {
    *log = (zigzag_log){0};
    log->jam_held = true;
    UT_EQ_INT(exec_init(&ex, c, &scn), EXEC_OK);
    double prev = 0.0, psi0 = 0.0;
    exec_frame f;
    for (uint32_t k = 0u; k < 100000u && ex.state == EXEC_RUNNING; k++) {
        exec_desk_step(&ex);
        if (!exec_report_take(&ex, &f)) {
            continue;
        }
        double r = f.cmd[0];
        double dpsi = f.x[VESSEL_PSI_RAD] - psi0;
        if (f.t_s < start_s - 1e-9) {
            log->before_start = math_max_f64(log->before_start, math_fabs_f64(r));
            psi0 = f.x[VESSEL_PSI_RAD];
        } else if (prev * r < 0.0) {
            log->switches++;
            /* A reversal to port needs the heading past the threshold to starboard, and back. */
            bool ok = (r < 0.0) ? (dpsi <= -threshold) : (dpsi >= threshold);
            log->bad_switches += ok ? 0u : 1u;
        }
        if (jam_s > 0.0 && f.t_s >= jam_s - 1e-9) {
            if (math_fabs_f64(f.t_s - jam_s) < 1e-9) {
                log->jam_value = r;
            }
            log->jam_held = log->jam_held && r == log->jam_value;
        }
        prev = r;
        log->after_stop = r;
    }
}

static void test_zigzag(void) {
    UT_TEST("zig-zag 20/5: the rudder is amidships before the start, reverses only once the "
            "heading has passed 5 degrees, and returns amidships at the stop");
    UT_CHECK(load("duration 11\n"
                  "init u_mps=1.5 n_rpm=1200\n"
                  "at 0 n_rpm=1200\n"
                  "zigzag rudder=20deg heading=5deg start=1 stop=10\n"));
    exec_config c;
    config_vessel(&c);
    zigzag_log log;
    run_zigzag(&c, 1.0, 5.0 * DEG, 0.0, &log);
    ut_info("%u reversals", (unsigned)log.switches);
    UT_NEAR(log.before_start, 0.0, 0.0);
    UT_CHECK(log.switches >= 2u);
    UT_EQ_INT(log.bad_switches, 0);
    UT_NEAR(log.after_stop, 0.0, 0.0);
    const manoeuvre_result *m = exec_manoeuvre(&ex);
    /* A lean image (UUV_LEAN_IMAGE) measures no manoeuvre metrics. */
    UT_CHECK(m->zigzag && (UUV_LEAN_IMAGE ? m->n_overshoots == 0u : m->n_overshoots >= 1u));

    UT_TEST("zig-zag without a stop: it holds to the end of the run, the rudder at +20 "
            "degrees until the heading first passes the threshold");
    UT_CHECK(load("duration 2\n"
                  "init u_mps=1.5 n_rpm=1200\n"
                  "at 0 n_rpm=1200\n"
                  "zigzag rudder=20deg heading=5deg start=1\n"));
    run_zigzag(&c, 1.0, 5.0 * DEG, 0.0, &log);
    UT_EQ_INT(log.switches, 0);
    UT_NEAR(log.after_stop, 20.0 * DEG, 1e-12);

    UT_TEST("zig-zag with the rudder jammed at 4 s: the rule no longer moves it, and the "
            "stop does not bring it amidships");
    UT_CHECK(load("duration 7\n"
                  "init u_mps=1.5 n_rpm=1200\n"
                  "at 0 n_rpm=1200\n"
                  "at 4 fin_jam=rudder\n"
                  "zigzag rudder=20deg heading=5deg start=1 stop=6\n"));
    run_zigzag(&c, 1.0, 5.0 * DEG, 4.0, &log);
    UT_CHECK(log.jam_held);
    UT_CHECK(math_fabs_f64(log.jam_value) > 1.0 * DEG);
    UT_NEAR(log.after_stop, log.jam_value, 0.0);
}

/* ---- Full plant: faults, couplings, inverters, single rate -------------- */

static void test_drive_faults(void) {
    exec_config c;
    config_small(&c);
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    double healthy_i = recs[10].i_rms_a;

    UT_TEST("leg_short at 0 s: requested before the drive starts, the protection trips at "
            "the first slow boundary and stays tripped; no current builds up");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000 leg_short=a\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(n_recs, 11);
    UT_EQ_INT(recs[0].faults, fault_bit(SCN_FAULT_LEG_SHORT));
    UT_EQ_INT(recs[0].trip, DRIVE_TRIP_NONE);
    bool tripped = true;
    for (uint32_t k = 1u; k < n_recs; k++) {
        tripped = tripped && recs[k].trip == (uint32_t)DRIVE_TRIP_LEG_SHORT;
    }
    UT_CHECK(tripped);
    UT_NEAR(ex.trip_t_s, 0.0, 0.0);
    ut_info("rms current %.3f A tripped, %.3f A healthy", recs[10].i_rms_a, healthy_i);
    UT_CHECK(healthy_i > 5.0);
    UT_CHECK(recs[10].i_rms_a < 0.1 * healthy_i);

    UT_TEST("switch_open, current_offset and dc_cap at 1.6 ms: recorded from their boundary, "
            "they change the currents without tripping the drive");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"
                  "at 0.0016 switch_open=a+ current_offset=5 dc_cap=0.5\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    uint32_t three = fault_bit(SCN_FAULT_SWITCH_OPEN) | fault_bit(SCN_FAULT_CURRENT_OFFSET) |
                     fault_bit(SCN_FAULT_DC_CAP);
    UT_EQ_INT(recs[1].faults, 0);
    UT_EQ_INT(recs[2].faults, three);
    UT_EQ_INT(recs[10].faults, three);
    UT_EQ_INT(recs[10].trip, DRIVE_TRIP_NONE);
    UT_CHECK(ex.trip_t_s < 0.0);
    ut_info("rms current %.3f A faulted", recs[10].i_rms_a);
    UT_CHECK(recs[10].i_rms_a != healthy_i);

    UT_TEST("battery_cutoff: from the second slow boundary after it, the pack delivers "
            "no current, its charge stays put and the DC link sags");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000 battery_cutoff=on\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(recs[10].faults, fault_bit(SCN_FAULT_BATTERY_CUTOFF));
    bool no_current = true;
    for (uint32_t k = 3u; k < n_recs; k++) {
        no_current = no_current && recs[k].i_batt_a == 0.0 && recs[k].soc == recs[3].soc;
    }
    UT_CHECK(no_current);
    UT_CHECK(recs[10].v_dc_v < recs[3].v_dc_v);
}

/* The motor's load coefficient in force [N m per (rad/s)^2], from its drag row. */
static double load_coefficient(void) {
#if UUV_NUMERIC == UUV_NUMERIC_FIXED
    const induction_motor_row_q *r = &ex.drive.motor.k_load;
    return (double)r->c[0] / (double)(1ull << r->shift);
#else
    return (double)ex.drive.motor.load_factor;
#endif
}

static void test_more_faults(void) {
    exec_config c;
    config_small(&c);
    UT_TEST("phase_open=b at 0.1 s: the phase-loss protection trips once two whole 100 ms "
            "windows (from 0 s) saw the fault; the records carry the fault and the trip");
    UT_CHECK(load("duration 0.45\nat 0 n_rpm=1000\nat 0.1 phase_open=b\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    ut_info("tripped at %.4f s, reason %u", ex.trip_t_s, (unsigned)ex.report.trip);
    UT_EQ_INT(ex.report.trip, DRIVE_TRIP_PHASE_LOSS);
    UT_EQ_INT(ex.report.faults, fault_bit(SCN_FAULT_PHASE_OPEN));
    UT_CHECK(ex.trip_t_s > 0.35 && ex.trip_t_s < 0.45);

    UT_TEST("prop_fouling=3: from its slow boundary the motor's load coefficient is three "
            "times the clean one");
    UT_CHECK(load("duration 0.004\nat 0 n_rpm=1000\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    double clean = load_coefficient();
    UT_CHECK(load("duration 0.004\nat 0 n_rpm=1000\nat 0.0016 prop_fouling=3\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    ut_info("load coefficient: clean %.6g, fouled %.6g", clean, load_coefficient());
    UT_NEAR(load_coefficient() / clean, 3.0, 1e-6);
    UT_EQ_INT(ex.report.faults, fault_bit(SCN_FAULT_PROP_FOULING));
    UT_EQ_INT(ex.report.trip, DRIVE_TRIP_NONE);

    UT_TEST("energy audit: the same records bit for bit, and positive filter and motor "
            "losses below the battery's energy");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    exec_frame plain = recs[n_recs - 1u];
    UT_CHECK(ex.count.e_loss_filter_j == 0.0 && ex.count.e_loss_motor_j == 0.0);
    c.energy_audit = true;
    if (!built(&c)) { /* a lean image has no energy audit */
        UT_EQ_INT(run(&c), EXEC_ERR_LAYER);
        return;
    }
    UT_EQ_INT(run(&c), EXEC_OK);
    exec_frame audit = recs[n_recs - 1u];
    bool same = plain.i_rms_a == audit.i_rms_a && plain.te_nm == audit.te_nm &&
                plain.v_dc_v == audit.v_dc_v;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        same = same && plain.x[i] == audit.x[i];
    }
    UT_CHECK(same);
    ut_info("battery %.4g J, filter losses %.4g J, motor losses %.4g J, shaft %.4g J",
            ex.count.e_batt_j, ex.count.e_loss_filter_j, ex.count.e_loss_motor_j,
            ex.count.e_mech_j);
    UT_CHECK(ex.count.e_loss_filter_j > 0.0 && ex.count.e_loss_motor_j > 0.0);
    UT_CHECK(ex.count.e_loss_filter_j + ex.count.e_loss_motor_j < ex.count.e_batt_j);
}

/* One option against the default run: the same time, no overrun, the current within 15 %. */
static void check_option(const exec_config *c, const char *name, double ref_i) {
    if (!built(c)) { /* left out of a lean image */
        UT_EQ_INT(run(c), EXEC_ERR_LAYER);
        return;
    }
    UT_EQ_INT(run(c), EXEC_OK);
    UT_EQ_INT(ex.state, EXEC_DONE);
    UT_EQ_INT(exec_overruns(&ex), 0);
    UT_EQ_INT(n_recs, 11);
    UT_NEAR(exec_time_s(&ex), 0.008, 1e-12);
    double i = recs[10].i_rms_a;
    ut_info("%-22s rms current %.4f A, battery %.4f A", name, i, recs[10].i_batt_a);
    UT_NEAR(i, ref_i, 0.15 * ref_i);
    UT_CHECK(recs[10].i_batt_a > 0.0);
}

static void test_options(void) {
    UT_TEST("every coupling and inverter option magnetises the motor like the default "
            "(switching, ZOH, average): rms current within 15 % after 8 ms, same time, "
            "no overrun");
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"));
    exec_config c;
    config_small(&c);
    UT_EQ_INT(run(&c), EXEC_OK);
    double ref_i = recs[10].i_rms_a;
    ut_info("%-22s rms current %.4f A", "default", ref_i);
    UT_CHECK(ref_i > 5.0);
    static const coupling_down downs[] = {COUPLE_FOH, COUPLE_DERIV, COUPLE_STAGGER};
    static const char *const down_names[] = {"first-order hold", "derivative", "staggered"};
    for (int k = 0; k < 3; k++) {
        config_small(&c);
        c.down = downs[k];
        check_option(&c, down_names[k], ref_i);
    }
    config_small(&c);
    c.up = COUPLE_FILTER;
    check_option(&c, "filter", ref_i);
    config_small(&c);
    c.up = COUPLE_SAMPLE;
    check_option(&c, "sample", ref_i);
    config_small(&c);
    c.inverter = DRIVE_INVERTER_EVENT;
    check_option(&c, "event inverter", ref_i);
    config_small(&c);
    c.inverter = DRIVE_INVERTER_AVERAGED;
    check_option(&c, "averaged inverter", ref_i);
    UT_EQ_INT(exec_fast_steps(&ex), built(&c) ? 10 : 0); /* at the controller's 800 us frame */

    UT_TEST("averaged inverter: with one step per motor frame, staggering has no half frame "
            "to delay by and gives the same bits as the zero-order hold");
    exec_frame zoh = recs[10];
    c.down = COUPLE_STAGGER;
    if (!built(&c)) {
        UT_EQ_INT(run(&c), EXEC_ERR_LAYER);
        return;
    }
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_CHECK(recs[10].i_rms_a == zoh.i_rms_a && recs[10].te_nm == zoh.te_nm &&
             recs[10].v_dc_v == zoh.v_dc_v && recs[10].x[VESSEL_N_RPM] == zoh.x[VESSEL_N_RPM]);
}

static void test_single_rate(void) {
    UT_TEST("single-rate reference: every step is a motor and a slow step, the controller "
            "keeps its frame, and records come at the multi-rate run's reporting times");
    UT_CHECK(load("at 0 n_rpm=1000\n"));
    exec_config c;
    config_small(&c);
    c.duration_s = 160e-6;
    c.fast_per_medium = 5u; /* records every 5 x 8 = 40 steps of 2 us */
    c.single_rate = true;
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(ex.state, EXEC_DONE);
    UT_EQ_INT(exec_fast_steps(&ex), 80);
    UT_EQ_INT(ex.count.medium, 80);
    UT_EQ_INT(ex.count.slow, 80);
    UT_EQ_INT(ex.count.control, 2);
    UT_EQ_INT(n_recs, 3);
    UT_NEAR(recs[1].t_s, 80e-6, 1e-15);
    UT_NEAR(recs[2].t_s, 160e-6, 1e-15);
    UT_NEAR(exec_time_s(&ex), 160e-6, 1e-15);
    UT_NEAR(recs[2].v_dc_v, recs[0].v_dc_v, 1.0);
}

/* Fast ticks without running what they release; returns the tick that released last. */
static uint32_t ticks_only(uint32_t n) {
    uint32_t released_at = 0u;
    for (uint32_t k = 1u; k <= n; k++) {
        if (exec_fast_tick(&ex)) {
            released_at = k;
        }
    }
    return released_at;
}

/* ---- The boundary's schedule -------------------------------------------- */

/* The run to its end in the desk's order, the boundaries as the executive splits them or
 * all in one tick; the last record. */
static exec_frame run_split(const exec_config *c, bool split) {
    exec_frame last = {0};
    if (exec_init(&ex, c, &scn) != EXEC_OK) {
        return last;
    }
    ex.split = ex.split && split;
    while (ex.state == EXEC_RUNNING) {
        exec_desk_step(&ex);
        (void)exec_report_take(&ex, &last);
    }
    return last;
}

static bool same_record(const exec_frame *a, const exec_frame *b) {
    bool same = a->index == b->index && a->te_nm == b->te_nm && a->i_rms_a == b->i_rms_a &&
                a->v_dc_v == b->v_dc_v && a->i_batt_a == b->i_batt_a && a->soc == b->soc &&
                a->m_index == b->m_index && a->f_hz == b->f_hz;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        same = same && a->x[i] == b->x[i];
    }
    return same;
}

static void test_split_boundary(void) {
    UT_CHECK(load("duration 0.0016\nat 0 n_rpm=1000\n"));
    exec_config c;
    config_small(&c);

    UT_TEST("split boundary: the publish after a frame's last step, the latch before the "
            "next frame's first, the motor task's release after its second");
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    UT_CHECK(ex.split);
    UT_EQ_INT(ticks_only(49u), 0);
    UT_CHECK(!exec_fast_tick(&ex)); /* step 50: the publish */
    UT_EQ_INT(ex.fast_gate, EXEC_GATE_BEGIN);
    UT_CHECK(!exec_fast_tick(&ex)); /* the latch, step 51 */
    UT_EQ_INT(ex.fast_gate, 0);
    UT_CHECK(!ex.medium_busy);
    UT_CHECK(exec_fast_tick(&ex)); /* step 52: the release */
    UT_CHECK(ex.medium_busy);
    UT_EQ_INT(exec_fast_steps(&ex), 52);

    UT_TEST("the run's last boundary: one more tick, without a step, runs the second half and "
            "releases the last motor task; then the fast ticks are over");
    (void)exec_medium_tick(&ex);
    uint32_t released = 1u;
    for (uint32_t k = 0u; k < 2000u && !exec_fast_ended(&ex); k++) {
        if (exec_fast_tick(&ex)) {
            released++;
            if (!exec_fast_ended(&ex) && exec_medium_tick(&ex)) {
                exec_control_tick(&ex);
            }
        }
        if (exec_slow_pending(&ex)) {
            exec_slow_step(&ex);
        }
    }
    UT_CHECK(exec_fast_ended(&ex));
    UT_EQ_INT(released, 16); /* every motor frame of 1.6 ms */
    UT_EQ_INT(exec_fast_steps(&ex), 800);
    UT_CHECK(ex.medium_busy);
    UT_CHECK(!exec_fast_tick(&ex));
    UT_EQ_INT(exec_fast_steps(&ex), 800);
    UT_CHECK(exec_medium_tick(&ex)); /* the last motor task: a controller frame too */
    exec_control_tick(&ex);
    UT_CHECK(exec_slow_pending(&ex));
    exec_slow_step(&ex);
    UT_EQ_INT(ex.state, EXEC_DONE);
    UT_EQ_INT(exec_overruns(&ex), 0);

    UT_TEST("split or in one tick, the boundary gives the same bits: default, staggered, "
            "first-order hold, sampled, event inverter, a fault");
    static const char *const names[] = {"default", "staggered", "first-order hold", "sampled",
                                        "event inverter", "switch_open at 4 ms"};
    for (int k = 0; k < 6; k++) {
        config_small(&c);
        c.down = (k == 1) ? COUPLE_STAGGER : (k == 2) ? COUPLE_FOH : COUPLE_ZOH;
        c.up = (k == 3) ? COUPLE_SAMPLE : COUPLE_AVG;
        c.inverter = (k == 4) ? DRIVE_INVERTER_EVENT : DRIVE_INVERTER_SWITCHING;
        UT_CHECK(load((k == 5) ? "duration 0.008\nat 0 n_rpm=1000\nat 0.004 switch_open=a+\n"
                               : "duration 0.008\nat 0 n_rpm=1000\n"));
        if (!built(&c)) { /* left out of a lean image */
            UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_ERR_LAYER);
            continue;
        }
        exec_frame a = run_split(&c, true);
        exec_frame b = run_split(&c, false);
        ut_info("%-22s i_rms %.6f A, v_dc %.4f V", names[k], a.i_rms_a, a.v_dc_v);
        UT_CHECK(a.index == 10u && a.i_rms_a > 5.0 && same_record(&a, &b));
    }
}

/* ---- Overruns ----------------------------------------------------------- */

static void test_overruns(void) {
    UT_CHECK(load("duration 0.008\nat 0 n_rpm=1000\n"));
    exec_config c;
    config_small(&c);

    UT_TEST("a motor task still running at the next boundary is a medium overrun: counted, "
            "the run stops and the fast tick does nothing more");
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    UT_CHECK(!exec_medium_tick(&ex)); /* nothing released yet */
    UT_EQ_INT(ticks_only(100u), 52); /* released two steps after the boundary */
    UT_EQ_INT(ex.state, EXEC_STOP_OVERRUN);
    UT_EQ_INT(ex.count.overruns_medium, 1);
    UT_EQ_INT(exec_overruns(&ex), 1);
    UT_EQ_INT(exec_fast_steps(&ex), 100);
    UT_EQ_INT(ticks_only(10u), 0);
    UT_EQ_INT(exec_fast_steps(&ex), 100);

    UT_TEST("staggered coupling: the motor task's results are due half a frame after its "
            "release, so a task still running then is already an overrun");
    c.down = COUPLE_STAGGER;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    UT_EQ_INT(ticks_only(80u), 50);
    UT_EQ_INT(ex.state, EXEC_STOP_OVERRUN);
    UT_EQ_INT(ex.count.overruns_medium, 1);
    UT_EQ_INT(exec_fast_steps(&ex), 75);

    UT_TEST("a controller task not done by the next control boundary is a control overrun; "
            "the motor task of that frame does not run");
    config_small(&c);
    c.medium_per_slow = 16u;
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    exec_control_tick(&ex); /* nothing released: no effect */
    UT_EQ_INT(ex.count.control, 0);
    for (uint32_t k = 0u; k < 50u * 20u && ex.state == EXEC_RUNNING; k++) {
        if (exec_fast_tick(&ex)) {
            (void)exec_medium_tick(&ex);
        }
        if (exec_slow_pending(&ex)) {
            exec_slow_step(&ex);
        }
    }
    UT_EQ_INT(ex.state, EXEC_STOP_OVERRUN);
    UT_EQ_INT(ex.count.overruns_control, 1);
    UT_EQ_INT(ex.count.medium, 15);
    UT_EQ_INT(ex.count.control, 0);
    UT_EQ_INT(exec_overruns(&ex), 1);

    UT_TEST("a slow step not done by the next slow boundary is a slow overrun; a slow step "
            "asked for after the stop does nothing");
    config_small(&c);
    UT_EQ_INT(exec_init(&ex, &c, &scn), EXEC_OK);
    for (uint32_t k = 0u; k < 50u * 20u && ex.state == EXEC_RUNNING; k++) {
        if (exec_fast_tick(&ex) && exec_medium_tick(&ex)) {
            exec_control_tick(&ex);
        }
    }
    UT_EQ_INT(ex.state, EXEC_STOP_OVERRUN);
    UT_EQ_INT(ex.count.overruns_slow, 1);
    UT_EQ_INT(ex.count.medium, 16);
    UT_EQ_INT(ex.count.control, 2);
    UT_CHECK(exec_slow_pending(&ex));
    exec_slow_step(&ex);
    UT_EQ_INT(ex.count.slow, 0);

    UT_TEST("the overruns' sum saturates at UINT32_MAX instead of wrapping to a small count");
    ex.count.overruns_medium = UINT32_MAX - 1u;
    ex.count.overruns_control = 1u;
    ex.count.overruns_slow = 0u;
    UT_CHECK(exec_overruns(&ex) == UINT32_MAX);
    ex.count.overruns_slow = 5u;
    UT_CHECK(exec_overruns(&ex) == UINT32_MAX);
    ex.count.overruns_medium = 3u;
    ex.count.overruns_control = UINT32_MAX;
    UT_CHECK(exec_overruns(&ex) == UINT32_MAX);
    ex.count.overruns_control = 4u;
    UT_CHECK(exec_overruns(&ex) == 12u);
}

/* ---- Autopilots ------------------------------------------------------------ */

/* When the heading and depth enter their bands and stay, and their extremes. */
typedef struct {
    double heading_in_s, depth_in_s; /* [s] last time outside the band (from the command) */
    double heading_max_deg, depth_max_m;
    double top_m;                    /* [m] highest point of the centre (most negative z) */
} step_log;

static void run_steps(const exec_config *c, double t_cmd, double psi_deg, double z_m,
                      step_log *log) {
    *log = (step_log){0};
    log->top_m = 1e9;
    UT_EQ_INT(exec_init(&ex, c, &scn), EXEC_OK);
    for (uint32_t k = 0u; k < 10000000u && ex.state == EXEC_RUNNING; k++) {
        exec_desk_step(&ex);
        exec_frame f;
        if (!exec_report_take(&ex, &f)) {
            continue;
        }
        const double psi = f.x[VESSEL_PSI_RAD] / DEG, z = f.x[VESSEL_Z_M];
        log->top_m = (z < log->top_m) ? z : log->top_m;
        if (f.t_s < t_cmd) {
            continue;
        }
        log->heading_max_deg = (psi > log->heading_max_deg) ? psi : log->heading_max_deg;
        log->depth_max_m = (z > log->depth_max_m) ? z : log->depth_max_m;
        if (!(psi > psi_deg - 1.0 && psi < psi_deg + 1.0)) {
            log->heading_in_s = f.t_s - t_cmd;
        }
        if (!(z > z_m - 0.1 && z < z_m + 0.1)) {
            log->depth_in_s = f.t_s - t_cmd;
        }
    }
}

static void test_autopilot_steps(void) {
    UT_TEST("autopilots: at 1200 rpm from the surface, heading 0 -> 90 deg and depth 15 m "
            "commanded at 30 s settle within 60 s (heading within 1 deg, depth within 0.1 m) "
            "and stay to 150 s; the centre never rises above the surface by its radius");
    UT_CHECK(load("duration 150\n"
                  "at 0 n_rpm=1200 heading=0\n"
                  "at 30 heading=90deg depth=15\n"));
    exec_config c;
    config_vessel(&c);
    step_log log;
    run_steps(&c, 30.0, 90.0, 15.0, &log);
    UT_EQ_INT(ex.state, EXEC_DONE);
    UT_CHECK(log.heading_in_s < 60.0);
    UT_CHECK(log.depth_in_s < 60.0);
    UT_CHECK(log.top_m > -vessel_params_npsauv2.hull_radius_m);
    ut_info("heading settled %.1f s after the command, overshoot %.2f deg; depth %.1f s, "
            "overshoot %.3f m", log.heading_in_s, log.heading_max_deg - 90.0, log.depth_in_s,
            log.depth_max_m - 15.0);

    UT_TEST("autopilots: 2000 N of positive buoyancy at 10 m: the depth integral removes the "
            "offset (within 0.1 m 60 s after the start, to 120 s, and within 1 cm at the end)");
    UT_CHECK(load("duration 120\n"
                  "init z_m=10 u_mps=3\n"
                  "at 0 n_rpm=1200 heading=0 depth=10 buoyancy=2000\n"));
    run_steps(&c, 0.0, 0.0, 10.0, &log);
    UT_CHECK(log.depth_in_s < 60.0);
    UT_CHECK(log.heading_in_s < 1.0);
    UT_NEAR(ex.x[VESSEL_Z_M], 10.0, 0.01);
    ut_info("depth within 0.1 m from %.1f s; %.4f m at the end", log.depth_in_s,
            ex.x[VESSEL_Z_M]);
}

static void test_autopilot_commands(void) {
    UT_TEST("autopilots: a manual rudder or stern command ends that axis's autopilot; "
            "autopilot=off ends both and puts the rudder and stern plane amidships");
    UT_CHECK(load("duration 1\n"
                  "init z_m=5\n"
                  "at 0 n_rpm=1000 heading=30deg depth=10\n"
                  "at 0.3 rudder=5deg\n"
                  "at 0.5 heading=-30deg stern=-2deg\n"
                  "at 0.7 heading=30deg depth=10\n"
                  "at 0.9 autopilot=off\n"));
    exec_config c;
    config_vessel(&c);
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_EQ_INT(n_recs, 11);
    UT_CHECK(recs[2].cmd[0] < 0.0); /* to starboard: negative rudder */
    UT_CHECK(recs[2].cmd[1] > 0.0); /* deeper: nose down */
    UT_NEAR(recs[3].cmd[0], 5.0 * DEG, 0.0);
    UT_NEAR(recs[4].cmd[0], 5.0 * DEG, 0.0);
    UT_CHECK(recs[5].cmd[0] > 5.0 * DEG); /* the heading autopilot again, to port */
    UT_NEAR(recs[5].cmd[1], -2.0 * DEG, 0.0);
    UT_NEAR(recs[6].cmd[1], -2.0 * DEG, 0.0);
    UT_CHECK(recs[8].cmd[1] > -2.0 * DEG);
    UT_NEAR(recs[9].cmd[0], 0.0, 0.0);
    UT_NEAR(recs[9].cmd[1], 0.0, 0.0);
    UT_NEAR(recs[10].cmd[0], 0.0, 0.0);

    UT_TEST("autopilots: a zig-zag drives the rudder over the heading autopilot; a jammed "
            "stern plane holds against the depth autopilot");
    UT_CHECK(load("duration 1\n"
                  "init z_m=5 u_mps=2\n"
                  "at 0 n_rpm=1000 heading=30deg depth=10\n"
                  "at 0.5 fin_jam=stern\n"
                  "zigzag rudder=10deg heading=10deg start=0.2\n"));
    UT_EQ_INT(run(&c), EXEC_OK);
    UT_CHECK(recs[1].cmd[0] < 0.0);
    UT_NEAR(recs[3].cmd[0], 10.0 * DEG, 0.0);
    UT_NEAR(recs[10].cmd[0], 10.0 * DEG, 0.0);
    UT_NEAR(recs[10].cmd[1], recs[5].cmd[1], 0.0);
    UT_CHECK(!ex.player.ap.heading_on);
}

void suite_exec_paths(void) {
    test_config_errors();
    test_vessel_only();
    test_fin_jam();
    test_zigzag();
    test_autopilot_steps();
    test_autopilot_commands();
    test_drive_faults();
    test_more_faults();
    test_options();
    test_single_rate();
    test_split_boundary();
    test_overruns();
}

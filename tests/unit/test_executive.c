/*
 * The executive with the whole plant: the closed loop from rest to
 * 1000 rpm against the propeller load (overshoot, settling, steady error),
 * determinism of a repeated run, the schedule's step counts, and the
 * desk's runs of steps against one tick at a time. Runs in the build's
 * numeric type, on the host and on every target.
 */
#include "executive.h"
#include "math/umath.h"
#include "ut.h"

void suite_executive(void);

static scenario scn;
static exec ex;

/* Documented settling time of the speed step (docs/multirate.md). */
#define SETTLE_LIMIT_S 1.0
#define RPM_PER_RADPS (30.0 / MATH_PI_F64)

typedef struct {
    double peak_rpm;
    double settle_s;       /* last time outside the 2 % band */
    double mean_err_pct;   /* mean error over the last 0.5 s */
    double final_x[VESSEL_NSTATES];
    double final_rpm;
    uint32_t saturations;
} step_result;

static void run_step(const exec_config *cfg, step_result *r) {
    UT_CHECK(exec_init(&ex, cfg, &scn) == EXEC_OK);
    *r = (step_result){0};
    double err_sum = 0.0;
    uint32_t err_n = 0u;
    exec_frame f;
    while (ex.state == EXEC_RUNNING) {
        exec_desk_step(&ex);
        if (ex.fast_phase != 0u) {
            continue;
        }
        double t = exec_time_s(&ex);
        double n = drive_shaft_radps(&ex.drive) * RPM_PER_RADPS;
        if (n > r->peak_rpm) {
            r->peak_rpm = n;
        }
        if (n < 980.0 || n > 1020.0) {
            r->settle_s = t;
        }
        if (t >= 1.5) {
            err_sum += n - 1000.0;
            err_n++;
        }
        (void)exec_report_take(&ex, &f);
    }
    UT_CHECK(ex.state == EXEC_DONE);
    r->mean_err_pct = (err_n > 0u) ? 100.0 * err_sum / (double)err_n / 1000.0 : 100.0;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        r->final_x[i] = ex.x[i];
    }
    r->final_rpm = drive_shaft_radps(&ex.drive) * RPM_PER_RADPS;
    r->saturations = ex.count.saturations;
}

/*
 * The records and the final state of a run, by the desk's runs of ticks
 * (max_ticks) or one tick at a time (0).
 */
#define DESK_RECORDS 4

typedef struct {
    exec_frame rec[DESK_RECORDS];
    uint32_t n;
    uint64_t fast;
    exec_counters count;
    double x[VESSEL_NSTATES];
    drive_trace_row drive;
} desk_result;

static void run_desk(const exec_config *cfg, uint32_t max_ticks, desk_result *r) {
    r->n = 0u;
    const exec_status st = exec_init(&ex, cfg, &scn);
    UT_CHECK(st == EXEC_OK);
    if (st != EXEC_OK) {
        return;
    }
    /* A tick more than the run has ends it too (a broken run would never end). */
    uint64_t left = (uint64_t)(cfg->duration_s * 1e9) / cfg->fast_ns + 2u;
    while (ex.state == EXEC_RUNNING && left > 0u) {
        uint32_t k = 1u;
        if (max_ticks == 0u) {
            exec_desk_step(&ex);
        } else {
            uint32_t most = (left < max_ticks) ? (uint32_t)left : max_ticks;
            k = exec_desk_run(&ex, most);
            UT_CHECK(k >= 1u && k <= most);
        }
        left = (k < left) ? left - k : 0u;
        if (ex.report_ready && r->n < DESK_RECORDS) {
            (void)exec_report_take(&ex, &r->rec[r->n++]);
        }
    }
    r->fast = exec_fast_steps(&ex);
    r->count = ex.count;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        r->x[i] = ex.x[i];
    }
    drive_trace(&ex.drive, &r->drive);
}

static bool same_results(const desk_result *a, const desk_result *b) {
    const drive_trace_row *p = &a->drive;
    const drive_trace_row *q = &b->drive;
    bool same = (a->n == b->n) && (a->fast == b->fast) &&
                (a->count.medium == b->count.medium) && (a->count.slow == b->count.slow) &&
                (a->count.control == b->count.control) &&
                (a->count.saturations == b->count.saturations) && p->v_dc == q->v_dc &&
                p->i_dc == q->i_dc && p->n_rpm == q->n_rpm && p->te_nm == q->te_nm;
    for (int i = 0; same && i < 3; i++) {
        same = p->s[i] == q->s[i] && p->v_inv[i] == q->v_inv[i] && p->v_cap[i] == q->v_cap[i] &&
               p->i_motor[i] == q->i_motor[i];
    }
    for (int i = 0; same && i < VESSEL_NSTATES; i++) {
        same = (a->x[i] == b->x[i]);
    }
    for (uint32_t k = 0u; same && k < a->n; k++) {
        const exec_frame *x = &a->rec[k];
        const exec_frame *y = &b->rec[k];
        same = x->t_s == y->t_s && x->te_nm == y->te_nm && x->i_rms_a == y->i_rms_a &&
               x->v_dc_v == y->v_dc_v && x->i_batt_a == y->i_batt_a && x->soc == y->soc &&
               x->m_index == y->m_index && x->f_hz == y->f_hz && x->trip == y->trip &&
               x->cmd[4] == y->cmd[4];
        for (int i = 0; same && i < VESSEL_NSTATES; i++) {
            same = (x->x[i] == y->x[i]);
        }
    }
    return same;
}

/*
 * exec_desk_run() against exec_desk_step(), the same bits: the real-time
 * path (runs of steps: with the sub-step modulator the frame plan's held
 * steps in runs of their own, cut where a run of ticks ends; the sampled
 * modulator), staggered, the filter coupling and the event
 * inverter (the general step), the averaged layer (its lean frames,
 * desk_run_averaged()), single-rate, with runs of 1, 7 and as many ticks as
 * it likes. 0.2 s, two slow frames, with a speed command at the first slow
 * boundary (the record takes the command in force before the controller's
 * moves on); single-rate, whose vessel steps every 2 us, 1.6 ms (records
 * every 0.8 ms).
 */
/* The averaged layer's start-up against the switching run a (its battery energy e_batt_sw). */
static void test_averaged(const exec_config *avg, const step_result *sw, double e_batt_sw) {
    static step_result c;
    const step_result a = *sw;
    run_step(avg, &c);
    ut_info("peak %.1f rpm, settled at %.3f s, steady error %.3f %%, final %.2f rpm "
            "(switching %.2f rpm)", c.peak_rpm, c.settle_s, c.mean_err_pct, c.final_rpm,
            a.final_rpm);
    UT_CHECK(c.peak_rpm <= 1050.0);
    UT_CHECK(c.settle_s <= SETTLE_LIMIT_S);
    UT_CHECK(math_fabs_f64(c.mean_err_pct) <= 0.5);
    UT_CHECK(math_fabs_f64(c.final_rpm - a.final_rpm) <= 0.002 * a.final_rpm);
    UT_CHECK(ex.count.e_batt_j > ex.count.e_mech_j && ex.count.e_mech_j > 0.0);
    UT_CHECK(math_fabs_f64(ex.count.e_batt_j / e_batt_sw - 1.0) <= 0.01);
    ut_info("battery %.1f J (switching %.1f J), shaft %.1f J", ex.count.e_batt_j, e_batt_sw,
            ex.count.e_mech_j);
    UT_EQ_INT(c.saturations, 0);
    UT_EQ_INT(exec_fast_steps(&ex), 2500);
    UT_EQ_INT(ex.count.medium, 2500);
    UT_EQ_INT(ex.count.control, 2500);
    UT_EQ_INT(ex.count.slow, 20);
    UT_EQ_INT(exec_overruns(&ex), 0);

}

static void test_desk_runs(const exec_config *base) {
    static const struct {
        drive_inverter inverter;
        coupling_down down;
        coupling_up up;
        bool single_rate;
        drive_modulator modulator;
    } cases[] = {
        {DRIVE_INVERTER_SWITCHING, COUPLE_ZOH, COUPLE_AVG, false, DRIVE_MODULATOR_SUBSTEP},
        {DRIVE_INVERTER_SWITCHING, COUPLE_ZOH, COUPLE_AVG, false, DRIVE_MODULATOR_SAMPLED},
        {DRIVE_INVERTER_SWITCHING, COUPLE_STAGGER, COUPLE_SAMPLE, false, DRIVE_MODULATOR_SUBSTEP},
        {DRIVE_INVERTER_SWITCHING, COUPLE_FOH, COUPLE_FILTER, false, DRIVE_MODULATOR_SUBSTEP},
        {DRIVE_INVERTER_EVENT, COUPLE_ZOH, COUPLE_AVG, false, DRIVE_MODULATOR_SUBSTEP},
        {DRIVE_INVERTER_AVERAGED, COUPLE_ZOH, COUPLE_AVG, false, DRIVE_MODULATOR_SUBSTEP},
        {DRIVE_INVERTER_SWITCHING, COUPLE_ZOH, COUPLE_AVG, true, DRIVE_MODULATOR_SUBSTEP},
    };
    static const uint32_t runs[] = {UINT32_MAX, 7u, 1u};
    static desk_result one, many;
    const char *text = "duration 2\nat 0 n_rpm=1000\nat 0.1 n_rpm=700\n";
    scenario_error err;
    UT_CHECK(scenario_parse(&scn, text, ut_text_len(text), &err));
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        exec_config cfg = *base;
        cfg.duration_s = 0.2;
        if (cases[c].single_rate) {
            cfg.duration_s = 0.0016;
            cfg.medium_per_slow = cfg.medium_per_control;
        }
        cfg.inverter = cases[c].inverter;
        cfg.down = cases[c].down;
        cfg.up = cases[c].up;
        cfg.single_rate = cases[c].single_rate;
        cfg.modulator = cases[c].modulator;
        if (!drive_options_built(cfg.inverter, cfg.down, cfg.up, cfg.energy_audit)) {
            UT_EQ_INT(exec_init(&ex, &cfg, &scn), EXEC_ERR_LAYER); /* not in a lean image */
            continue;
        }
        run_desk(&cfg, 0u, &one);
        UT_CHECK(ex.state == EXEC_DONE && one.n == 3u);
        UT_CHECK(cases[c].single_rate || one.rec[2].cmd[4] == 700.0);
        for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
            run_desk(&cfg, runs[k], &many);
            UT_CHECK(ex.state == EXEC_DONE);
            UT_CHECK(same_results(&one, &many));
        }
    }
}

/* Parses text into *s and checks it against cfg; *err says why not. */
static bool check_text(const exec_config *cfg, const char *text, scenario_error *err) {
    static scenario s;
    *err = (scenario_error){0};
    return scenario_parse(&s, text, ut_text_len(text), err) && exec_check_scenario(cfg, &s, err);
}

/*
 * exec_check_scenario(): every command in the default configuration and
 * with the event inverter; the drive's faults refused by the vessel plant,
 * the four that end in blocked gates by the averaged layer, an initial shaft
 * speed by the full plant (its motor starts at rest), each with its line and
 * name.
 */
static void test_scenario_check(void) {
    static const char *const all = "duration 1\n"
                                   "at 0 n_rpm=800 rudder=5deg fin_jam=rudder\n"
                                   "at 0.1 dc_cap=0.5 current_offset=1 prop_fouling=2\n"
                                   "at 0.2 switch_open=a+ leg_short=b\n"
                                   "at 0.3 phase_open=c battery_cutoff=on\n";
    scenario_error err;
    exec_config cfg;
    exec_config_default(&cfg);
    UT_CHECK(check_text(&cfg, all, &err));
    cfg.inverter = DRIVE_INVERTER_EVENT;
    UT_CHECK(check_text(&cfg, all, &err));

    cfg.inverter = DRIVE_INVERTER_AVERAGED;
    UT_CHECK(check_text(&cfg, "at 0 n_rpm=800 fin_jam=stern\n"
                              "at 0.1 dc_cap=0.5 current_offset=1 prop_fouling=2\n", &err));
    static const char *const refused[][2] = {
        {"at 0 n_rpm=800\nat 0.2 switch_open=a+\n", "switch_open"},
        {"at 0 n_rpm=800\nat 0.2 leg_short=b\n", "leg_short"},
        {"at 0 n_rpm=800\nat 0.2 phase_open=c\n", "phase_open"},
        {"at 0 n_rpm=800\nat 0.2 battery_cutoff=on\n", "battery_cutoff"},
    };
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        UT_CHECK(!check_text(&cfg, refused[k][0], &err));
        UT_EQ_INT(err.line, 2u);
        UT_CHECK(ut_text_equal(err.field, refused[k][1]) && err.message[0] != '\0');
    }

    /* The vessel plant: the first drive fault is line 3's dc_cap; fin_jam passes. */
    exec_config_default(&cfg);
    cfg.plant = EXEC_PLANT_VESSEL;
    UT_CHECK(!check_text(&cfg, all, &err));
    UT_EQ_INT(err.line, 3u);
    UT_CHECK(ut_text_equal(err.field, "dc_cap"));
    UT_CHECK(check_text(&cfg, "at 0 n_rpm=800 fin_jam=rudder\n", &err));

    /* An initial shaft speed: the vessel plant takes it, the full plant refuses it. */
    static const char *const spun = "duration 1\ninit u_mps=1\ninit n_rpm=1200\n";
    UT_CHECK(check_text(&cfg, spun, &err));
    exec_config_default(&cfg);
    UT_CHECK(!check_text(&cfg, spun, &err));
    UT_EQ_INT(err.line, 3u);
    UT_CHECK(ut_text_equal(err.field, "n_rpm") && err.message[0] != '\0');
}

/*
 * The guard: under `mss` a vehicle moving astern accelerates without bound
 * (the reference law's hull drag r2 C_d0 u^2 pushes astern, docs/vessel.md);
 * the run stops at the first non-finite state with EXEC_STOP_NONFINITE,
 * names it, keeps the last finite record and publishes no record after it.
 */
static void test_guard(void) {
    static scenario s;
    static exec g;
    const char *text = "duration 60\ninit u_mps=-5 z_m=50\n";
    scenario_error err;
    UT_CHECK(scenario_parse(&s, text, ut_text_len(text), &err));
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.plant = EXEC_PLANT_VESSEL;
    cfg.propulsion = VESSEL_PROP_MSS;
    UT_CHECK(exec_init(&g, &cfg, &s) == EXEC_OK);
    exec_frame f;
    bool finite = true;
    uint32_t records = 0u;
    while (g.state == EXEC_RUNNING) {
        exec_desk_step(&g);
        if (exec_report_take(&g, &f)) {
            records++;
            for (int i = 0; i < VESSEL_NSTATES; i++) {
                finite = finite && math_isfinite_f64(f.x[i]);
            }
        }
    }
    UT_EQ_INT(g.state, EXEC_STOP_NONFINITE);
    UT_EQ_INT(EXEC_NONFINITE_DRIVE, 1u << VESSEL_NSTATES);
    UT_CHECK((g.nonfinite & 1u) != 0u && (g.nonfinite & EXEC_NONFINITE_DRIVE) == 0u);
    UT_CHECK(finite && records + 1u == g.frame && g.frame < 600u);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        finite = finite && math_isfinite_f64(g.report.x[i]) && f.x[i] == g.report.x[i];
    }
    UT_CHECK(finite && math_fabs_f64(g.report.x[VESSEL_U_MPS]) <= EXEC_DIVERGED);
    ut_info("stopped in frame %u (t = %.1f s), %u records, all finite", (unsigned)g.frame,
            (double)g.frame * g.slow_s, (unsigned)records);
}

void suite_executive(void) {
    const char *text = "duration 2\nat 0 n_rpm=1000\n";
    scenario_error err;
    UT_CHECK(scenario_parse(&scn, text, ut_text_len(text), &err));
    exec_config cfg;
    exec_config_default(&cfg);

    UT_TEST("closed loop, rest to 1000 rpm with the propeller load: overshoot <= 5 %, "
            "settled (2 % band) within 1 s, steady error <= 0.5 %");
    static step_result a;
    run_step(&cfg, &a);
    ut_info("peak %.1f rpm (overshoot %.2f %%), settled at %.3f s, steady error %.3f %%",
            a.peak_rpm, (a.peak_rpm - 1000.0) / 10.0, a.settle_s, a.mean_err_pct);
    UT_CHECK(a.peak_rpm <= 1050.0);
    UT_CHECK(a.settle_s <= SETTLE_LIMIT_S);
    UT_CHECK(math_fabs_f64(a.mean_err_pct) <= 0.5);
    UT_EQ_INT(a.saturations, 0);

    UT_TEST("schedule: 2 s is 1e6 fast, 2e4 motor, 2500 controller and 20 slow steps");
    UT_EQ_INT(exec_fast_steps(&ex), 1000000);
    UT_EQ_INT(ex.count.medium, 20000);
    UT_EQ_INT(ex.count.control, 2500);
    UT_EQ_INT(ex.count.slow, 20);
    UT_EQ_INT(exec_overruns(&ex), 0);

    UT_TEST("the vehicle moves ahead and the battery delivers the shaft's energy plus losses");
    UT_CHECK(a.final_x[VESSEL_U_MPS] > 0.2 && a.final_x[VESSEL_U_MPS] < 0.5);
    UT_CHECK(ex.count.e_batt_j > ex.count.e_mech_j && ex.count.e_mech_j > 0.0);
    ut_info("battery %.1f J, shaft %.1f J (%.1f %%)", ex.count.e_batt_j, ex.count.e_mech_j,
            100.0 * ex.count.e_mech_j / ex.count.e_batt_j);
    const double e_batt_sw = ex.count.e_batt_j;

    UT_TEST("averaged layer (stage and motor at the controller's 800 us frame): the same "
            "start-up criteria; 2 s is 2500 frames, motor and controller steps and 20 slow "
            "steps; the final shaft speed within 0.2 % of the switching run's; the battery "
            "delivers the shaft's energy plus losses (within 1 % of the switching run's)");
    exec_config avg = cfg;
    avg.inverter = DRIVE_INVERTER_AVERAGED;
    if (UUV_LEAN_IMAGE) { /* no averaged layer in a lean image */
        UT_EQ_INT(exec_init(&ex, &avg, &scn), EXEC_ERR_LAYER);
    } else {
        test_averaged(&avg, &a, e_batt_sw);
    }

    UT_TEST("the desk's runs of ticks (exec_desk_run) give the bits of one tick at a time: "
            "switching (sub-step, sampled), staggered, filter coupling, event, averaged, "
            "single-rate");
    test_desk_runs(&cfg);
    UT_CHECK(scenario_parse(&scn, text, ut_text_len(text), &err));

    UT_TEST("the scenario check: the vessel plant refuses the drive's faults, the averaged "
            "layer the four that end in blocked gates, each with its line and name");
    test_scenario_check();

    UT_TEST("the guard: a state that becomes non-finite stops the run (EXEC_STOP_NONFINITE) "
            "with the last finite record kept and no record after it");
    test_guard();

    UT_TEST("determinism: the same run twice gives the same bits");
    static step_result b;
    cfg.duration_s = 0.5;
    run_step(&cfg, &a);
    run_step(&cfg, &b);
    bool same = true;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        same = same && (a.final_x[i] == b.final_x[i]);
    }
    UT_CHECK(same);
}

/*
 * The drive segment through its own interface (drive_segment.h), run on the
 * executive's schedule by a small loop of this file: configuration and
 * model errors, the measurement before any slow frame, the fast trace, and
 * each drive fault (a switch stuck open, a shorted leg, the under-voltage
 * trip, a reduced DC-link capacitance). The references are the power
 * electronics' own rules: an open switch conducts only through its diode,
 * blocked gates leave every leg at the state its diodes give, the inverter
 * voltage is the DC link switched by the leg states. Runs of a few
 * milliseconds, in the build's numeric type.
 */
#include <stddef.h>

#include "drive_segment.h"
#include "params.h"
#include "math/umath.h"
#include "models/battery/battery.h"
#include "ut.h"

void suite_drive_segment(void);

static drive_segment drv;
static propeller_model prop;
static battery pack;
static battery_params pack_params;
static drive_config cfg_in_use; /* the configuration of the drive being run */

/* Switching inverter, ZOH and average, 2 us / 100 us / 800 us controller and slow frames. */
static void config_base(drive_config *c) {
    *c = (drive_config){0};
    c->inverter = DRIVE_INVERTER_SWITCHING;
    c->down = COUPLE_ZOH;
    c->up = COUPLE_AVG;
    c->fast_ns = 2000u;
    c->fast_per_medium = 50u;
    c->medium_per_control = 8u;
    c->medium_per_slow = 8u;
    c->v_dc0_v = 600.0;
    c->stage = uuv_params_default.stage;
    c->pwm = uuv_params_default.pwm;
    c->motor = uuv_params_default.motor;
    c->control = uuv_params_default.control;
}

/* What a run saw, step by step (fast steps after the last log_reset only). */
typedef struct {
    uint32_t medium_phase, slow_phase;
    drive_battery bat;       /* the companion handed over at each slow boundary */
    drive_slow_meas meas;    /* the last slow frame's measurements */
    uint32_t steps;
    uint32_t high[3];        /* steps that ended with the leg high */
    uint32_t not_diode;      /* steps where leg a or b was not at its diodes' state */
    uint32_t upper_a_bad;    /* leg a high although its inductor current was not negative */
    uint32_t lower_b_bad;    /* leg b low although its inductor current was negative */
    double v_dc_min, v_dc_max, v_dc_end; /* [V] */
    double v_inv_err;        /* [V] largest |v_inv - v_dc (s - mean s)| (switching only) */
    uint32_t v_inv_off;      /* steps with some |v_inv - v_dc (s - mean s)| above 1 V */
    double v_inv_max;        /* [V] largest |v_inv| over v_dc */
} run_log;

static void log_reset(run_log *g) {
    g->steps = 0u;
    g->high[0] = g->high[1] = g->high[2] = 0u;
    g->not_diode = g->upper_a_bad = g->lower_b_bad = 0u;
    g->v_dc_min = 1e9;
    g->v_dc_max = -1e9;
    g->v_inv_err = 0.0;
    g->v_inv_off = 0u;
    g->v_inv_max = 0.0;
}

/* A fast step, with the inductor currents before it (what the diodes see) and the trace after. */
static void step_logged(drive_segment *d, run_log *g) {
    /* The averaged layer has no filter stage (inverter_avg.h): no diode states to check. */
    const bool neg_a = (d->stage != NULL) && d->stage->ph[0].i_l < 0;
    const bool neg_b = (d->stage != NULL) && d->stage->ph[1].i_l < 0;
    drive_fast_tick(d);
    drive_trace_row row;
    drive_trace(d, &row);
    g->steps++;
    for (int x = 0; x < 3; x++) {
        g->high[x] += (row.s[x] != 0u) ? 1u : 0u;
    }
    g->not_diode += ((row.s[0] != 0u) != neg_a || (row.s[1] != 0u) != neg_b) ? 1u : 0u;
    g->upper_a_bad += (row.s[0] != 0u && !neg_a) ? 1u : 0u;
    g->lower_b_bad += (row.s[1] == 0u && neg_b) ? 1u : 0u;
    g->v_dc_min = math_min_f64(g->v_dc_min, row.v_dc);
    g->v_dc_max = math_max_f64(g->v_dc_max, row.v_dc);
    g->v_dc_end = row.v_dc;
    double mean = ((double)row.s[0] + (double)row.s[1] + (double)row.s[2]) / 3.0;
    double off = 0.0;
    for (int x = 0; x < 3; x++) {
        double ideal = row.v_dc * ((double)row.s[x] - mean);
        off = math_max_f64(off, math_fabs_f64(row.v_inv[x] - ideal));
        g->v_inv_max = math_max_f64(g->v_inv_max, math_fabs_f64(row.v_inv[x]) / row.v_dc);
    }
    g->v_inv_err = math_max_f64(g->v_inv_err, off);
    g->v_inv_off += (off > 1.0) ? 1u : 0u;
}

/* Motor frames on the executive's schedule, in the order of a desk step. */
static void run_frames(drive_segment *d, run_log *g, uint32_t frames) {
    const drive_config *c = &cfg_in_use;
    for (uint32_t f = 0u; f < frames; f++) {
        for (uint32_t k = 0u; k < c->fast_per_medium; k++) {
            step_logged(d, g);
        }
        bool slow = (++g->slow_phase == c->medium_per_slow);
        bool control = (++g->medium_phase == c->medium_per_control);
        g->slow_phase = slow ? 0u : g->slow_phase;
        g->medium_phase = control ? 0u : g->medium_phase;
        drive_medium_publish(d);
        drive_medium_begin(d, slow);
        drive_medium_task(d, control, slow);
        if (control) {
            drive_control_task(d);
        }
        if (slow) {
            drive_slow_measure(d, &g->meas);
            drive_battery_next(d, &g->bat);
        }
    }
}

/* Starts a drive on the pack's companion (or an open contactor), commanding 1000 rpm. */
static bool start(const drive_config *c, run_log *g, bool contactor_open) {
    *g = (run_log){0};
    log_reset(g);
    if (drive_init(&drv, c, &prop) != DRIVE_OK) {
        return false;
    }
    cfg_in_use = *c;
    battery_companion bc = battery_companion_f64(&pack);
    g->bat.g_s = contactor_open ? 0.0 : bc.g_s;
    g->bat.b_a = contactor_open ? 0.0 : bc.b_a;
    drive_start(&drv, &g->bat);
    drive_speed_command(&drv, 1000.0 * MATH_PI_F64 / 30.0);
    return true;
}

static drive_faults no_faults(void) {
    drive_faults f = {0};
    f.dc_cap_frac = 1.0;
    return f;
}

static void test_errors(void) {
    drive_config c;
    UT_TEST("drive_init: a zero or out-of-range step, ratio or substep count is a "
            "configuration error; the base configuration is accepted");
    config_base(&c);
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_OK);
    c.fast_ns = 99u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_CONFIG);
    config_base(&c);
    c.fast_per_medium = 0u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_CONFIG);
    config_base(&c);
    c.fast_per_medium = 100001u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_CONFIG);
    config_base(&c);
    c.medium_per_control = 0u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_CONFIG);
    config_base(&c);
    c.medium_per_slow = 0u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_CONFIG);
    config_base(&c);
    c.inverter = DRIVE_INVERTER_AVERAGED;
    c.fast_per_medium = 2u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), UUV_LEAN_IMAGE ? DRIVE_ERR_LAYER : DRIVE_ERR_CONFIG);

    UT_TEST("drive_init: a lean image (UUV_LEAN_IMAGE) refuses the layers, couplings and "
            "audit it leaves out, and only those; a full build takes them all");
    {
        const drive_status left_out = UUV_LEAN_IMAGE ? DRIVE_ERR_LAYER : DRIVE_OK;
        config_base(&c);
        c.inverter = DRIVE_INVERTER_EVENT;
        UT_EQ_INT(drive_init(&drv, &c, &prop), left_out);
        config_base(&c);
        c.energy_audit = true;
        UT_EQ_INT(drive_init(&drv, &c, &prop), left_out);
        config_base(&c);
        c.down = COUPLE_FOH;
        UT_EQ_INT(drive_init(&drv, &c, &prop), left_out);
        config_base(&c);
        c.down = COUPLE_DERIV;
        UT_EQ_INT(drive_init(&drv, &c, &prop), left_out);
        config_base(&c);
        c.up = COUPLE_FILTER;
        UT_EQ_INT(drive_init(&drv, &c, &prop), left_out);
        config_base(&c);
        c.down = COUPLE_STAGGER;
        c.up = COUPLE_SAMPLE;
        c.modulator = DRIVE_MODULATOR_SAMPLED;
        UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_OK);
    }

    UT_TEST("drive_init: a model that refuses its step or state is a model error: the "
            "modulator (under 8 steps per carrier), the power stage (1100 V), the motor "
            "(2 ms frame), the controller (20 ms frame), the averaged layer (a 2 ms frame)");
    config_base(&c);
    c.fast_ns = 30000u;
    c.fast_per_medium = 20u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_MODEL);
    config_base(&c);
    c.v_dc0_v = 1100.0;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_MODEL);
    config_base(&c);
    c.fast_per_medium = 1000u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_MODEL);
    config_base(&c);
    c.medium_per_control = 200u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), DRIVE_ERR_MODEL);
    config_base(&c);
    c.inverter = DRIVE_INVERTER_AVERAGED;
    c.fast_ns = 100000u;
    c.fast_per_medium = 1u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), UUV_LEAN_IMAGE ? DRIVE_ERR_LAYER : DRIVE_OK);
    c.fast_ns = 2000000u;
    UT_EQ_INT(drive_init(&drv, &c, &prop), UUV_LEAN_IMAGE ? DRIVE_ERR_LAYER : DRIVE_ERR_MODEL);
}

static void test_first_frame(void) {
    UT_TEST("before the first slow boundary the measurement is empty, not a division by "
            "zero: zero means and the starting battery companion");
    drive_config c;
    config_base(&c);
    static run_log g;
    UT_CHECK(start(&c, &g, false));
    run_frames(&drv, &g, 3u);
    drive_slow_meas m;
    drive_slow_measure(&drv, &m);
    UT_NEAR(m.v_dc_mean_v, 0.0, 0.0);
    UT_NEAR(m.shaft_radps, 0.0, 0.0);
    UT_NEAR(m.i_rms_a, 0.0, 0.0);
    UT_NEAR(m.te_nm, 0.0, 0.0);
    UT_EQ_INT(m.trip, DRIVE_TRIP_NONE);
    UT_NEAR(m.battery.g_s, g.bat.g_s, 0.0);
    UT_NEAR(m.battery.b_a, g.bat.b_a, 0.0);

    UT_TEST("fast trace of the switching inverter, once the controller modulates: the "
            "leg states are 0 or 1, each inverter phase voltage (at most two thirds of the DC "
            "link) is the DC link switched by them with the common mode removed (within 1 V) "
            "in every step with the sampled modulator, and with the sub-step one in every "
            "step but those with an edge (some, at most 30 of 400); the DC link stays near the "
            "pack's 600 V");
    for (int sampled = 1; sampled >= 0; sampled--) {
        config_base(&c);
        c.modulator = sampled ? DRIVE_MODULATOR_SAMPLED : DRIVE_MODULATOR_SUBSTEP;
        UT_CHECK(start(&c, &g, false));
        run_frames(&drv, &g, 16u);
        log_reset(&g);
        run_frames(&drv, &g, 8u);
        ut_info("%s: v_dc %.3f .. %.3f V, largest |v_inv| / v_dc %.4f, error %.4f V, "
                "%u of %u steps off by more than 1 V", sampled ? "sampled" : "sub-step",
                g.v_dc_min, g.v_dc_max, g.v_inv_max, g.v_inv_err, (unsigned)g.v_inv_off,
                (unsigned)g.steps);
        if (sampled) {
            UT_CHECK(g.v_inv_err < 1.0);
        } else {
            UT_CHECK(g.v_inv_off > 0u && g.v_inv_off <= 30u);
        }
        UT_CHECK(g.v_inv_max > 0.3 && g.v_inv_max <= 2.0 / 3.0 + 1e-3);
        UT_CHECK(g.high[0] > 0u && g.high[0] < g.steps);
        UT_NEAR(g.v_dc_min, 600.0, 5.0);
        UT_NEAR(g.v_dc_max, 600.0, 5.0);
        UT_NEAR(drive_shaft_radps(&drv), g.meas.shaft_end_radps, 1e-9);
    }
}

static void test_trace_general(void) {
    UT_TEST("fast trace of the event-located and averaged inverters: no phase voltage "
            "exceeds two thirds of the DC link");
    drive_config c;
    config_base(&c);
    c.inverter = DRIVE_INVERTER_EVENT;
    static run_log g;
    if (UUV_LEAN_IMAGE) { /* neither layer is in a lean image (drive_init's test) */
        UT_CHECK(!start(&c, &g, false));
        return;
    }
    UT_CHECK(start(&c, &g, false));
    run_frames(&drv, &g, 24u);
    ut_info("event: largest |v_inv| / v_dc %.4f", g.v_inv_max);
    UT_CHECK(g.v_inv_max > 0.1 && g.v_inv_max <= 2.0 / 3.0 + 1e-3);
    c.inverter = DRIVE_INVERTER_AVERAGED;
    c.fast_ns = 100000u;
    c.fast_per_medium = 1u;
    UT_CHECK(start(&c, &g, false));
    run_frames(&drv, &g, 24u);
    ut_info("averaged: largest |v_inv| / v_dc %.4f", g.v_inv_max);
    UT_CHECK(g.v_inv_max > 0.0 && g.v_inv_max <= 2.0 / 3.0 + 1e-3);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_NONE);
}

/*
 * A fault requested after the first slow frame takes effect at the second
 * slow boundary; the run is logged over the two slow frames after it. With
 * f NULL, the healthy run to compare with.
 */
static void run_with_fault(const drive_config *c, const drive_faults *f, run_log *g,
                           bool contactor_open) {
    UT_CHECK(start(c, g, contactor_open));
    run_frames(&drv, g, 8u);
    if (f != NULL) {
        drive_fault_request(&drv, f);
    }
    run_frames(&drv, g, 8u);
    log_reset(g);
    run_frames(&drv, g, 16u);
}

static void test_switch_open(void) {
    static run_log healthy, faulted;
    drive_config c;
    drive_faults f = no_faults();

    UT_TEST("switch a+ stuck open: leg a is high only while its inductor current flows into "
            "the leg (the upper diode), so it is high less often than in the healthy drive");
    config_base(&c);
    run_with_fault(&c, NULL, &healthy, false);
    f.switch_open = 1u;
    run_with_fault(&c, &f, &faulted, false);
    ut_info("leg a high %u / %u steps (healthy %u)", (unsigned)faulted.high[0],
            (unsigned)faulted.steps, (unsigned)healthy.high[0]);
    UT_CHECK(healthy.upper_a_bad > 0u);
    UT_EQ_INT(faulted.upper_a_bad, 0);
    UT_CHECK(faulted.high[0] < healthy.high[0]);
    UT_EQ_INT(faulted.meas.trip, DRIVE_TRIP_NONE);

    UT_TEST("switch b- stuck open, first-order hold: leg b is low only while its inductor "
            "current flows out of the leg (the lower diode), so it is high more often");
    config_base(&c);
    c.down = UUV_LEAN_IMAGE ? COUPLE_ZOH : COUPLE_FOH; /* a lean image has no FOH */
    run_with_fault(&c, NULL, &healthy, false);
    f.switch_open = 4u;
    run_with_fault(&c, &f, &faulted, false);
    ut_info("leg b high %u / %u steps (healthy %u)", (unsigned)faulted.high[1],
            (unsigned)faulted.steps, (unsigned)healthy.high[1]);
    UT_CHECK(healthy.lower_b_bad > 0u);
    UT_EQ_INT(faulted.lower_b_bad, 0);
    UT_CHECK(faulted.high[1] > healthy.high[1]);
}

static void test_leg_short(void) {
    UT_TEST("leg short requested during a slow frame: the gates switch until the next slow "
            "boundary, then the protection blocks them (every leg at its diodes' state) "
            "and reports a leg-short trip");
    drive_config c;
    config_base(&c);
    static run_log g;
    UT_CHECK(start(&c, &g, false));
    run_frames(&drv, &g, 8u);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_NONE);
    drive_faults f = no_faults();
    f.leg_short = 2u;
    drive_fault_request(&drv, &f);
    log_reset(&g);
    run_frames(&drv, &g, 8u);
    UT_CHECK(g.not_diode > 0u);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_LEG_SHORT);
    log_reset(&g);
    run_frames(&drv, &g, 8u);
    UT_EQ_INT(g.not_diode, 0);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_LEG_SHORT);
}

static void test_undervoltage(void) {
    static run_log g;
    drive_config c;
    config_base(&c);

    UT_TEST("a DC link at 600 V with the contactor open stays above the 300 V trip for a "
            "slow frame: no trip");
    UT_CHECK(start(&c, &g, true));
    run_frames(&drv, &g, 8u);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_NONE);
    UT_CHECK(g.v_dc_min > DRIVE_UV_TRIP_V);

    UT_TEST("a DC link starting at 250 V: the first motor frame's mean is below the trip, "
            "the gates are blocked from the next boundary on and the slow frame reports an "
            "under-voltage trip; a leg short later keeps the first cause");
    c.v_dc0_v = 250.0;
    UT_CHECK(start(&c, &g, true));
    run_frames(&drv, &g, 2u);
    log_reset(&g);
    run_frames(&drv, &g, 6u);
    UT_EQ_INT(g.not_diode, 0);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_UNDERVOLTAGE);
    drive_faults f = no_faults();
    f.leg_short = 1u;
    drive_fault_request(&drv, &f);
    run_frames(&drv, &g, 16u);
    UT_EQ_INT(g.not_diode, 0);
    UT_EQ_INT(g.meas.trip, DRIVE_TRIP_UNDERVOLTAGE);
}

static void test_dc_cap(void) {
    static run_log healthy, faulted;
    drive_config c;
    config_base(&c);
    drive_faults f = no_faults();

    UT_TEST("dc_cap with the contactor open: a fraction the power stage refuses (0) leaves "
            "the DC link as it was, bit for bit");
    run_with_fault(&c, NULL, &healthy, true);
    f.dc_cap_frac = 0.0;
    run_with_fault(&c, &f, &faulted, true);
    UT_CHECK(faulted.v_dc_min == healthy.v_dc_min && faulted.v_dc_max == healthy.v_dc_max &&
             faulted.v_dc_end == healthy.v_dc_end);

    UT_TEST("dc_cap on the battery: 10 % of the capacitance makes the DC-link ripple larger");
    run_with_fault(&c, NULL, &healthy, false);
    f.dc_cap_frac = 0.1;
    run_with_fault(&c, &f, &faulted, false);
    double r_healthy = healthy.v_dc_max - healthy.v_dc_min;
    double r_faulted = faulted.v_dc_max - faulted.v_dc_min;
    ut_info("DC-link ripple %.4f V at 10 %% capacitance, %.4f V healthy", r_faulted, r_healthy);
    UT_CHECK(r_faulted > 2.0 * r_healthy);
}

void suite_drive_segment(void) {
    pack_params = battery_params_uuv;
    pack_params.frame_s = 0.0008;
    UT_TEST("set-up: the propeller and the battery pack accept their default parameters");
    UT_CHECK(propeller_init(&prop, &propeller_params_default) == PROPELLER_OK);
    UT_CHECK(battery_init(&pack, &pack_params, 1.0) == BATTERY_OK);
    test_errors();
    test_first_frame();
    test_trace_general();
    test_switch_open();
    test_leg_short();
    test_undervoltage();
    test_dc_cap();
}

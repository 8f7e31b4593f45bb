/*
 * The scenario player (scenario_player.h) on short scenarios whose commands
 * are known from their text: which event is due at which slow boundary,
 * where each command and fault goes, what a jammed fin holds, the zig-zag
 * rule on a heading written down boundary by boundary, which axes the
 * autopilots hold, a command between boundaries, and the controller's
 * speed command between boundaries. The references are the scenario's own
 * values.
 */
#include "math/umath.h"
#include "scenario_player.h"
#include "ut.h"

void suite_scenario_player(void);

#define DEG (MATH_PI_F64 / 180.0)
#define SLOW_S 0.1

static scenario scn;
static scenario_player pl;
static vessel_cmd cmd;
static double x[VESSEL_NSTATES];

static bool load(const char *text) {
    scenario_error err;
    if (!scenario_parse(&scn, text, ut_text_len(text), &err)) {
        return false;
    }
    player_init(&pl, &scn, SLOW_S);
    cmd = (vessel_cmd){0};
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        x[i] = 0.0;
    }
    return true;
}

/* Applies every event due at slow boundary k (t = k slow frames); returns how many, and the faults. */
static unsigned boundary(unsigned k, unsigned *faults) {
    unsigned n = 0u;
    *faults = 0u;
    double t = (double)k * SLOW_S;
    for (player_event ev = player_next(&pl, t, x, &cmd); ev != PLAYER_IDLE;
         ev = player_next(&pl, t, x, &cmd)) {
        n++;
        *faults += (ev == PLAYER_FAULT) ? 1u : 0u;
    }
    player_steer(&pl, t, x, SLOW_S, &cmd);
    return n;
}

static void test_start(void) {
    UT_TEST("a new player has applied nothing: no fault, the capacitance whole, a clean "
            "propeller, speed command 0");
    UT_CHECK(load("duration 1\nat 0.5 n_rpm=900\n"));
    UT_EQ_INT(pl.fault_mask, 0);
    UT_CHECK(!pl.battery_cut && !pl.fin_jammed[0] && !pl.fin_jammed[3]);
    UT_NEAR(pl.faults.dc_cap_frac, 1.0, 0.0);
    UT_NEAR(pl.faults.load_factor, 1.0, 0.0);
    UT_EQ_INT(pl.faults.switch_open + pl.faults.leg_short + pl.faults.phase_open, 0);
    UT_NEAR(player_speed_at(&pl, 0.0), 0.0, 0.0);
    unsigned f;
    UT_EQ_INT(boundary(0u, &f), 0);
    UT_NEAR(cmd.n_rpm, 0.0, 0.0);
}

static void test_due(void) {
    UT_TEST("an event applies at the first slow boundary at or after its time, within 1e-9 "
            "of a slow frame, in file order for equal times");
    UT_CHECK(load("duration 1\nat 0 n_rpm=500\nat 0.3 rudder=5deg\nat 0.3 rudder=7deg\n"
                  "at 0.30000000005 bow_port=1deg\nat 0.3000000002 bow_stbd=1deg\n"
                  "at 0.35 stern=3deg\n"));
    unsigned f;
    UT_EQ_INT(boundary(0u, &f), 1);
    UT_NEAR(cmd.n_rpm, 500.0, 0.0);
    UT_EQ_INT(boundary(1u, &f), 0);
    UT_EQ_INT(boundary(2u, &f), 0);
    UT_NEAR(cmd.rudder_rad, 0.0, 0.0);
    UT_EQ_INT(boundary(3u, &f), 3);
    UT_NEAR(cmd.rudder_rad, 7.0 * DEG, 1e-15);
    UT_NEAR(cmd.bow_port_rad, 1.0 * DEG, 1e-15);
    UT_NEAR(cmd.bow_stbd_rad, 0.0, 0.0);
    UT_NEAR(cmd.stern_rad, 0.0, 0.0);
    UT_EQ_INT(boundary(4u, &f), 2);
    UT_NEAR(cmd.bow_stbd_rad, 1.0 * DEG, 1e-15);
    UT_NEAR(cmd.stern_rad, 3.0 * DEG, 1e-15);
    UT_EQ_INT(f, 0);
    UT_EQ_INT(boundary(5u, &f), 0);
}

static void test_commands(void) {
    UT_TEST("each vessel command reaches its field: fins, shaft speed, buoyancy");
    UT_CHECK(load("duration 1\nat 0 rudder=1deg stern=2deg bow_port=3deg bow_stbd=4deg "
                  "n_rpm=1100 buoyancy=-20\n"));
    unsigned f;
    UT_EQ_INT(boundary(0u, &f), 6);
    UT_NEAR(cmd.rudder_rad, 1.0 * DEG, 1e-15);
    UT_NEAR(cmd.stern_rad, 2.0 * DEG, 1e-15);
    UT_NEAR(cmd.bow_port_rad, 3.0 * DEG, 1e-15);
    UT_NEAR(cmd.bow_stbd_rad, 4.0 * DEG, 1e-15);
    UT_NEAR(cmd.n_rpm, 1100.0, 0.0);
    UT_NEAR(cmd.delta_b_n, -20.0, 0.0);
    UT_EQ_INT(f, 0);
    UT_EQ_INT(pl.fault_mask, 0);
}

static uint32_t bit(scenario_command c) { return 1u << ((unsigned)c - (unsigned)SCN_FIRST_FAULT); }

static void test_faults(void) {
    UT_TEST("each fault command is reported as a fault, sets its bit in the mask and its "
            "field of the drive's fault set; battery_cutoff opens the contactor");
    UT_CHECK(load("duration 1\nat 0.1 switch_open=b- leg_short=c\n"
                  "at 0.2 dc_cap=0.25 current_offset=-2.5 phase_open=a prop_fouling=3\n"
                  "at 0.3 battery_cutoff=on\n"));
    unsigned f;
    UT_EQ_INT(boundary(0u, &f), 0);
    UT_EQ_INT(boundary(1u, &f), 2);
    UT_EQ_INT(f, 2);
    UT_EQ_INT(pl.fault_mask, bit(SCN_FAULT_SWITCH_OPEN) | bit(SCN_FAULT_LEG_SHORT));
    UT_EQ_INT(pl.faults.switch_open, 4); /* a+ a- b+ b-: the fourth */
    UT_EQ_INT(pl.faults.leg_short, 3);
    UT_EQ_INT(boundary(2u, &f), 4);
    UT_EQ_INT(f, 4);
    UT_NEAR(pl.faults.dc_cap_frac, 0.25, 0.0);
    UT_NEAR(pl.faults.current_offset_a, -2.5, 0.0);
    UT_EQ_INT(pl.faults.phase_open, 1);
    UT_NEAR(pl.faults.load_factor, 3.0, 0.0);
    UT_CHECK(!pl.battery_cut);
    UT_EQ_INT(boundary(3u, &f), 1);
    UT_EQ_INT(f, 1);
    UT_CHECK(pl.battery_cut);
    UT_EQ_INT(pl.fault_mask, bit(SCN_FAULT_SWITCH_OPEN) | bit(SCN_FAULT_LEG_SHORT) |
                                 bit(SCN_FAULT_DC_CAP) | bit(SCN_FAULT_CURRENT_OFFSET) |
                                 bit(SCN_FAULT_PHASE_OPEN) | bit(SCN_FAULT_PROP_FOULING) |
                                 bit(SCN_FAULT_BATTERY_CUTOFF));
    /* Commands do not touch the fault set. */
    UT_NEAR(cmd.n_rpm, 0.0, 0.0);
}

static void test_fin_jam(void) {
    UT_TEST("a jammed fin holds its actual angle (the vessel's state), ignores its later "
            "commands and the zig-zag rule; the other fins still move");
    UT_CHECK(load("duration 2\nat 0 rudder=10deg stern=4deg\nat 0.2 fin_jam=rudder\n"
                  "at 0.2 fin_jam=stern\nat 0.4 rudder=-10deg stern=-4deg bow_port=2deg\n"
                  "zigzag rudder=20deg heading=5deg start=0.6\n"));
    unsigned f;
    (void)boundary(0u, &f);
    (void)boundary(1u, &f);
    x[VESSEL_DELTA_R_RAD] = 6.5 * DEG; /* the rudder on its way to 10 deg */
    x[VESSEL_DELTA_R_RAD + 1] = 3.0 * DEG;
    UT_EQ_INT(boundary(2u, &f), 2);
    UT_EQ_INT(f, 2);
    UT_CHECK(pl.fin_jammed[0] && pl.fin_jammed[1] && !pl.fin_jammed[2]);
    UT_EQ_INT(pl.fault_mask, bit(SCN_FAULT_FIN_JAM));
    UT_NEAR(cmd.rudder_rad, 6.5 * DEG, 0.0);
    UT_NEAR(cmd.stern_rad, 3.0 * DEG, 0.0);
    UT_EQ_INT(boundary(4u, &f), 3);
    UT_NEAR(cmd.rudder_rad, 6.5 * DEG, 0.0);
    UT_NEAR(cmd.stern_rad, 3.0 * DEG, 0.0);
    UT_NEAR(cmd.bow_port_rad, 2.0 * DEG, 1e-15);
    (void)boundary(6u, &f);
    (void)boundary(7u, &f);
    UT_NEAR(cmd.rudder_rad, 6.5 * DEG, 0.0);
}

static void test_zigzag(void) {
    UT_TEST("zig-zag 20/5 from 0.5 s to 1.5 s: +20 deg from the start, reversed each time "
            "the heading has left the starting heading by 5 deg on the rudder's side, "
            "amidships at the stop; before the start the scenario's rudder holds");
    UT_CHECK(load("duration 3\nat 0 rudder=3deg\nzigzag rudder=20deg heading=5deg start=0.5 "
                  "stop=1.5\n"));
    /* The heading at boundaries 0..15, written down: a positive rudder turns the bow
     * to port (psi falls), a negative one to starboard. */
    static const double psi_deg[16] = {0, 0, 0, 0, 0, 10, 8, 6, 4, 3, 10, 16, 14, 12, 10, 9};
    static const double rudder_deg[16] = {3,   3,   3,  3,  3,  20, 20, 20,
                                          -20, -20, -20, 20, 20, 20, 20, 0};
    unsigned f;
    bool ok = true;
    for (unsigned k = 0u; k < 16u; k++) {
        x[VESSEL_PSI_RAD] = psi_deg[k] * DEG;
        (void)boundary(k, &f);
        bool same = math_fabs_f64(cmd.rudder_rad - rudder_deg[k] * DEG) < 1e-12;
        if (!same) {
            ut_info("boundary %u: rudder %.3f deg, expected %.0f", k, cmd.rudder_rad / DEG,
                    rudder_deg[k]);
        }
        ok = ok && same;
    }
    UT_CHECK(ok);
    UT_NEAR(pl.zz_psi0_rad, 10.0 * DEG, 1e-15);
    UT_NEAR(pl.zz_rudder_rad, 0.0, 0.0);
}

static void test_speed(void) {
    UT_TEST("the controller's speed command: the last n_rpm at or before t, between slow "
            "boundaries, whatever the background's place; other commands pass it by");
    UT_CHECK(load("duration 1\nat 0 n_rpm=400 rudder=2deg\nat 0.0104 n_rpm=800\n"
                  "at 0.5 stern=1deg\nat 0.5 n_rpm=1200\n"));
    UT_NEAR(player_speed_at(&pl, 0.0), 400.0, 0.0);
    UT_NEAR(player_speed_at(&pl, 0.0096), 400.0, 0.0);
    UT_NEAR(player_speed_at(&pl, 0.0104), 800.0, 0.0);
    unsigned f;
    UT_EQ_INT(boundary(0u, &f), 2); /* the background's own place: the speed cursor is apart */
    UT_NEAR(player_speed_at(&pl, 0.4992), 800.0, 0.0);
    UT_NEAR(player_speed_at(&pl, 0.5), 1200.0, 0.0);
    UT_NEAR(player_speed_at(&pl, 0.9), 1200.0, 0.0);
    UT_NEAR(cmd.n_rpm, 400.0, 0.0);
}

static void test_autopilots(void) {
    UT_TEST("autopilots: heading= and depth= turn them on, a manual rudder or stern command "
            "takes its axis back, autopilot=off puts both fins amidships, the zig-zag takes "
            "the rudder, a jammed fin is not moved");
    UT_CHECK(load("duration 3\nat 0 heading=30deg depth=5\nat 0.2 rudder=4deg\n"
                  "at 0.3 stern=2deg\nat 0.4 heading=10deg depth=8 fin_jam=stern\n"
                  "at 0.6 autopilot=off\nat 0.7 heading=0deg\n"
                  "zigzag rudder=10deg heading=5deg start=0.8\n"));
    unsigned f;
    (void)boundary(0u, &f);
    UT_CHECK(pl.ap.heading_on && pl.ap.depth_on);
    UT_NEAR(pl.ap.heading_ref_rad, 30.0 * DEG, 1e-15);
    UT_NEAR(pl.ap.depth_ref_m, 5.0, 0.0);
    UT_CHECK(cmd.rudder_rad != 0.0 && cmd.stern_rad != 0.0); /* they steer at once */
    (void)boundary(2u, &f);
    UT_CHECK(!pl.ap.heading_on && pl.ap.depth_on);
    UT_NEAR(cmd.rudder_rad, 4.0 * DEG, 1e-15);
    (void)boundary(3u, &f);
    UT_CHECK(!pl.ap.heading_on && !pl.ap.depth_on);
    UT_NEAR(cmd.stern_rad, 2.0 * DEG, 1e-15);
    x[VESSEL_DELTA_R_RAD + 1] = 1.5 * DEG;
    (void)boundary(4u, &f);
    UT_CHECK(pl.ap.heading_on && pl.ap.depth_on);
    UT_NEAR(cmd.stern_rad, 1.5 * DEG, 0.0); /* jammed: the depth autopilot does not move it */
    (void)boundary(5u, &f);
    UT_NEAR(cmd.stern_rad, 1.5 * DEG, 0.0);
    (void)boundary(6u, &f);
    UT_CHECK(!pl.ap.heading_on && !pl.ap.depth_on);
    UT_NEAR(cmd.rudder_rad, 0.0, 0.0);
    UT_NEAR(cmd.stern_rad, 1.5 * DEG, 0.0);
    (void)boundary(7u, &f);
    UT_CHECK(pl.ap.heading_on);
    (void)boundary(8u, &f);
    UT_CHECK(!pl.ap.heading_on);
    UT_NEAR(cmd.rudder_rad, 10.0 * DEG, 1e-15);

    UT_TEST("a command between boundaries (player_command) acts as an event would; a "
            "fault that way is refused; the speed reaches the controller's command at once");
    UT_CHECK(load("duration 1\nat 0 n_rpm=500\n"));
    player_command(&pl, SCN_BOW_PORT, 3.0 * DEG, &cmd);
    player_command(&pl, SCN_N_RPM, 900.0, &cmd);
    player_command(&pl, SCN_FAULT_DC_CAP, 0.5, &cmd);
    UT_NEAR(cmd.bow_port_rad, 3.0 * DEG, 1e-15);
    UT_NEAR(cmd.n_rpm, 900.0, 0.0);
    UT_NEAR(pl.speed_rpm, 900.0, 0.0);
    UT_NEAR(pl.faults.dc_cap_frac, 1.0, 0.0);
    UT_EQ_INT(pl.fault_mask, 0);
}

void suite_scenario_player(void) {
    test_start();
    test_due();
    test_commands();
    test_faults();
    test_fin_jam();
    test_zigzag();
    test_autopilots();
    test_speed();
}

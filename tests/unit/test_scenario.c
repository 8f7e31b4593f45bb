/*
 * The scenario parser: the grammar of scenario.h, and an error that names
 * the line and field for each kind of bad input.
 */
#include "scenario.h"
#include "math/umath.h"
#include "ut.h"

void suite_scenario(void);

static scenario scn;
static scenario_error err;

static bool parse(const char *text) { return scenario_parse(&scn, text, ut_text_len(text), &err); }

/* Expects parse failure at a line, naming a field. */
static void expect_error(const char *text, unsigned line, const char *field) {
    bool ok = parse(text);
    UT_CHECK(!ok);
    UT_EQ_INT(err.line, line);
    if (!UT_CHECK(ut_text_equal(err.field, field))) {
        ut_info("field '%s', expected '%s' (%s)", err.field, field, err.message);
    }
    UT_CHECK(err.message[0] != '\0');
}

/* True when the message of the last error contains word. */
static bool message_has(const char *word) {
    for (size_t i = 0; err.message[i] != '\0'; i++) {
        size_t k = 0;
        while (word[k] != '\0' && err.message[i + k] == word[k]) {
            k++;
        }
        if (word[k] == '\0') {
            return true;
        }
    }
    return false;
}

/*
 * The remaining forms of scenario.h's grammar and errors: pairs without a
 * name, a value or an '=', the hint at the deg suffix for angles only, tab
 * separators, a last line without a newline, and a NUL byte in the text.
 */
static void test_more_forms(void) {
    UT_TEST("scenario errors: a field without '=' or without a name, in init, at and zigzag; "
            "a zig-zag without rudder or with a bad value");
    expect_error("init u_mps\n", 1, "u_mps");
    expect_error("at 1 =5\n", 1, "=5");
    expect_error("zigzag rudder\n", 1, "rudder");
    expect_error("zigzag heading=10deg\n", 1, "zigzag");
    expect_error("zigzag rudder=abc heading=10deg\n", 1, "rudder");
    expect_error("zigzag rudder=10deg heading=5deg start=soon\n", 1, "start");

    UT_TEST("scenario errors: a malformed angle names the deg suffix in its message, a "
            "malformed speed does not");
    expect_error("at 1 rudder=x\n", 1, "rudder");
    UT_CHECK(message_has("suffix deg"));
    expect_error("at 1 n_rpm=x\n", 1, "n_rpm");
    UT_CHECK(!message_has("deg"));

    UT_TEST("scenario errors: an angle out of range is reported in the unit it was written "
            "in, and a plain number that fits in degrees gets 'did you mean 20deg?'");
    expect_error("at 1 rudder=20\n", 1, "rudder");
    UT_CHECK(message_has("value 20 rad") && message_has("did you mean 20deg?"));
    expect_error("at 1 rudder=46deg\n", 1, "rudder");
    UT_CHECK(message_has("value 46 deg out of range [-45, 45]") && !message_has("mean"));
    expect_error("at 1 rudder=100\n", 1, "rudder");
    UT_CHECK(!message_has("mean"));

    UT_TEST("scenario: the autopilot commands heading (rad or deg), depth [m] and "
            "autopilot=off; bad values are refused");
    UT_CHECK(parse("at 60 heading=90deg depth=15\nat 70 heading=-1.5\nat 80 autopilot=off\n"));
    UT_EQ_INT(scn.n_events, 4);
    UT_EQ_INT(scn.events[0].command, SCN_HEADING);
    UT_NEAR(scn.events[0].value, MATH_HALF_PI_F64, 1e-15);
    UT_EQ_INT(scn.events[1].command, SCN_DEPTH);
    UT_NEAR(scn.events[1].value, 15.0, 0.0);
    UT_NEAR(scn.events[2].value, -1.5, 0.0);
    UT_EQ_INT(scn.events[3].command, SCN_AUTOPILOT);
    expect_error("at 1 depth=-2\n", 1, "depth");
    expect_error("at 1 depth=5deg\n", 1, "depth");
    expect_error("at 1 heading=400deg\n", 1, "heading");
    expect_error("at 1 autopilot=on\n", 1, "autopilot");
    UT_CHECK(message_has("off"));

    UT_TEST("scenario: tabs separate fields, the last line needs no newline");
    UT_CHECK(parse("duration\t30\nat\t2\trudder=-5deg\tn_rpm=900"));
    UT_NEAR(scn.duration_s, 30.0, 0.0);
    UT_EQ_INT(scn.n_events, 2);
    UT_EQ_INT(scn.events[0].command, SCN_RUDDER);
    UT_NEAR(scn.events[0].value, -5.0 * MATH_DEG_TO_RAD_F64, 1e-15);
    UT_NEAR(scn.events[1].value, 900.0, 0.0);
    UT_EQ_INT(scn.events[1].line, 2);

    UT_TEST("scenario: the fault commands read their named parts as 1, 2, ... in the order "
            "of scenario.h (b- = 4, c = 3, stern = 2, on = 1) and their numbers in range");
    UT_CHECK(parse("at 7 switch_open=b- leg_short=c dc_cap=0.5 battery_cutoff=on "
                   "fin_jam=stern current_offset=-2.5 phase_open=b prop_fouling=3\n"));
    UT_EQ_INT(scn.n_events, 8);
    static const int want_cmd[8] = {SCN_FAULT_SWITCH_OPEN,    SCN_FAULT_LEG_SHORT,
                                    SCN_FAULT_DC_CAP,         SCN_FAULT_BATTERY_CUTOFF,
                                    SCN_FAULT_FIN_JAM,        SCN_FAULT_CURRENT_OFFSET,
                                    SCN_FAULT_PHASE_OPEN,     SCN_FAULT_PROP_FOULING};
    static const double want_val[8] = {4.0, 3.0, 0.5, 1.0, 2.0, -2.5, 2.0, 3.0};
    for (size_t i = 0; i < 8u && i < scn.n_events; i++) {
        UT_EQ_INT(scn.events[i].command, want_cmd[i]);
        UT_NEAR(scn.events[i].value, want_val[i], 0.0);
        UT_NEAR(scn.events[i].t_s, 7.0, 0.0);
    }

    UT_TEST("scenario errors: a fault part that does not exist names the field and lists "
            "the parts; a fault number out of its range");
    expect_error("at 1 switch_open=d+\n", 1, "switch_open");
    UT_CHECK(message_has("a+, a-, b+, b-, c+, c-") && message_has("d+"));
    expect_error("at 1 battery_cutoff=off\n", 1, "battery_cutoff");
    expect_error("at 1 fin_jam=keel\n", 1, "fin_jam");
    expect_error("at 1 dc_cap=0.01\n", 1, "dc_cap");
    expect_error("at 1 current_offset=60\n", 1, "current_offset");
    expect_error("at 1 phase_open=d\n", 1, "phase_open");
    expect_error("at 1 prop_fouling=0.5\n", 1, "prop_fouling");
    expect_error("at 1 prop_fouling=11\n", 1, "prop_fouling");

    UT_TEST("scenario errors: a NUL byte inside the text is a control character");
    static const char with_nul[] = "duration 10\nat 1 n_rpm=5\0\n";
    UT_CHECK(!scenario_parse(&scn, with_nul, sizeof with_nul - 1u, &err));
    UT_EQ_INT(err.line, 2);
    UT_CHECK(message_has("0x00"));
}

/* True when the field and the message of the last error hold no byte b. */
static bool error_lacks(unsigned char b) {
    const char *const texts[2] = {err.field, err.message};
    for (size_t t = 0; t < 2u; t++) {
        for (const char *c = texts[t]; *c != '\0'; c++) {
            if ((unsigned char)*c == b) {
                return false;
            }
        }
    }
    return true;
}

/*
 * Text as editors write it, and text meant to deceive: a byte-order mark,
 * old Mac line ends, bidi overrides and C1 controls (echoed escaped), a
 * field cut at a character boundary, and repeated initial states.
 */
static void test_text_forms(void) {
    UT_TEST("scenario: a UTF-8 byte-order mark at the start is skipped (line 1 is the "
            "first line after it)");
    UT_CHECK(parse("\xEF\xBB\xBF" "duration 5\nat 1 n_rpm=100\n"));
    UT_CHECK(scn.duration_s == 5.0 && scn.n_events == 1u && scn.events[0].line == 2u);
    expect_error("\xEF\xBB\xBF" "duration x\n", 1, "duration");
    expect_error("duration 5\n\xEF\xBB\xBF" "at 1 n_rpm=1\n", 2, "\\ufeffat");

    UT_TEST("scenario: CR alone ends a line as LF and CR LF do (old Mac files)");
    UT_CHECK(parse("duration 5\rat 1 n_rpm=100\rat 2 n_rpm=200"));
    UT_CHECK(scn.duration_s == 5.0 && scn.n_events == 2u && scn.events[1].line == 3u);
    UT_CHECK(parse("duration 5\r\nat 1 n_rpm=100\r\n\r\nat 2 n_rpm=200\r\n"));
    UT_CHECK(scn.n_events == 2u && scn.events[1].line == 4u);
    expect_error("duration 5\rat 1 n_rpm=x\r", 2, "n_rpm");

    UT_TEST("scenario errors: bidi overrides, C1 controls, DEL, stray bytes and backslashes "
            "are echoed escaped in the field and the message, never raw");
    expect_error("at 1 n_rpm=5\xE2\x80\xAE" "00\n", 1, "n_rpm");
    UT_CHECK(message_has("'5\\u202e00'") && error_lacks(0xE2u));
    expect_error("at 1 \xE2\x81\xA6rudder=1\n", 1, "\\u2066rudder");
    expect_error("at 1 n_rpm=1\xC2\x9B" "2\n", 1, "n_rpm");
    UT_CHECK(message_has("'1\\u009b2'") && error_lacks(0xC2u) && error_lacks(0x9Bu));
    expect_error("at 1 n_rpm=1\x7F" "\n", 1, "n_rpm");
    UT_CHECK(message_has("'1\\x7f'") && error_lacks(0x7Fu));
    expect_error("at 1 n_rpm=\xFF\xC3\n", 1, "n_rpm");
    UT_CHECK(message_has("'\\xff\\xc3'") && error_lacks(0xFFu));
    expect_error("at 1 a\\b=1\n", 1, "a\\\\b");
    UT_TEST("scenario errors: well-formed UTF-8 text is echoed as it is");
    expect_error("at 1 gr\xC3\xBC\xC3\x9F" "=1\n", 1, "gr\xC3\xBC\xC3\x9F");

    UT_TEST("scenario errors: a long field is cut at a character boundary, never inside a "
            "UTF-8 character or an escape");
    /* Eight 3-byte characters: 24 bytes, one more than the field holds. */
    expect_error("at 1 \xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0"
                 "\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0=1\n",
                 1, "\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0\xE4\xBD\xA0"
                    "\xE4\xBD\xA0");
    /* 20 ASCII bytes then a bidi control: its 6-byte escape does not fit the 3 left. */
    expect_error("at 1 abcdefghijklmnopqrst\xE2\x80\xAE=1\n", 1, "abcdefghijklmnopqrst");

    UT_TEST("scenario errors: an initial state given twice, on one line or two, names the "
            "second and the line of the first");
    expect_error("init u_mps=1 u_mps=2\n", 1, "u_mps");
    UT_CHECK(message_has("line 1"));
    expect_error("duration 5\ninit u_mps=1 psi_rad=0\ninit psi_rad=1\n", 3, "psi_rad");
    UT_CHECK(message_has("line 2"));
    UT_CHECK(parse("init u_mps=1\ninit v_mps=0.5\n"));
}

void suite_scenario(void) {
    UT_TEST("scenario: every keyword, units and comments are read");
    const char *good = "# a comment line\n"
                       "duration 120.5   # trailing comment\n"
                       "init u_mps=1e-6 n_rpm=1300 psi_rad=90deg\n"
                       "\n"
                       "at 0 n_rpm=1300\n"
                       "at 10 rudder=20deg stern=-0.1 buoyancy=250\r\n"
                       "at 5 bow_port=0.05 bow_stbd=-5deg\n"
                       "zigzag rudder=20deg heading=10deg start=60 stop=200\n";
    UT_CHECK(parse(good));
    UT_NEAR(scn.duration_s, 120.5, 0.0);
    UT_NEAR(scn.init[VESSEL_U_MPS], 1e-6, 0.0);
    UT_NEAR(scn.init[VESSEL_N_RPM], 1300.0, 0.0);
    UT_NEAR(scn.init[VESSEL_PSI_RAD], MATH_HALF_PI_F64, 1e-15);
    UT_NEAR(scn.init[VESSEL_V_MPS], 0.0, 0.0);
    UT_EQ_INT(scn.n_events, 6);
    UT_CHECK(scn.zigzag.enabled);
    UT_NEAR(scn.zigzag.rudder_rad, 0.3490658503988659, 1e-15);
    UT_NEAR(scn.zigzag.stop_s, 200.0, 0.0);

    UT_TEST("scenario: events are sorted by time, stable for equal times");
    UT_NEAR(scn.events[0].t_s, 0.0, 0.0);
    UT_NEAR(scn.events[1].t_s, 5.0, 0.0);
    UT_EQ_INT(scn.events[1].command, SCN_BOW_PORT);
    UT_EQ_INT(scn.events[2].command, SCN_BOW_STBD);
    UT_EQ_INT(scn.events[3].command, SCN_RUDDER);
    UT_EQ_INT(scn.events[4].command, SCN_STERN);
    UT_EQ_INT(scn.events[5].command, SCN_BUOYANCY);
    UT_EQ_INT(scn.events[5].line, 6);
    UT_NEAR(scn.events[5].value, 250.0, 0.0);

    UT_TEST("scenario: an empty file parses, with no duration");
    UT_CHECK(parse(""));
    UT_NEAR(scn.duration_s, 0.0, 0.0);
    UT_CHECK(!scn.zigzag.enabled);

    UT_TEST("scenario errors: unknown keyword, state, command");
    expect_error("duration 10\nspeed 3\n", 2, "speed");
    expect_error("init q_dot=1\n", 1, "q_dot");
    expect_error("at 1 throttle=3\n", 1, "throttle");

    UT_TEST("scenario errors: malformed numbers and units");
    expect_error("duration ten\n", 1, "duration");
    expect_error("at 1 rudder=5degs\n", 1, "rudder");
    expect_error("at 1 n_rpm=100deg\n", 1, "n_rpm");
    expect_error("at x n_rpm=100\n", 1, "at");
    expect_error("at 1 n_rpm=\n", 1, "n_rpm=");
    expect_error("at 1 n_rpm=1e\n", 1, "n_rpm");

    UT_TEST("scenario errors: values out of range");
    expect_error("at 1 n_rpm=1600\n", 1, "n_rpm");
    expect_error("at 1 rudder=50deg\n", 1, "rudder");
    expect_error("at -1 rudder=0\n", 1, "at");
    expect_error("duration 0\n", 1, "duration");
    expect_error("init theta_rad=85deg\n", 1, "theta_rad");
    expect_error("at 1 buoyancy=1e400\n", 1, "buoyancy");

    UT_TEST("scenario errors: incomplete lines and zig-zag rules");
    expect_error("duration\n", 1, "duration");
    expect_error("duration 1 2\n", 1, "duration");
    expect_error("init\n", 1, "init");
    expect_error("at 3\n", 1, "at");
    expect_error("zigzag rudder=10deg\n", 1, "zigzag");
    expect_error("zigzag rudder=10deg heading=5deg start=50 stop=40\n", 1, "zigzag");
    expect_error("zigzag rudder=1deg heading=1deg\nzigzag rudder=1deg heading=1deg\n", 2, "zigzag");
    expect_error("zigzag rudder=1deg heading=1deg gain=2\n", 1, "gain");

    UT_TEST("scenario errors: control bytes and too many fields or events");
    expect_error("duration 1\n\x01\n", 2, "");
    expect_error("at 1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 "
                 "n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 "
                 "n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1 "
                 "n_rpm=1 n_rpm=1 n_rpm=1 n_rpm=1\n",
                 1, "");
    static char many[SCENARIO_MAX_EVENTS * 16u + 64u];
    size_t n = 0;
    for (unsigned i = 0; i <= SCENARIO_MAX_EVENTS; i++) {
        const char *line = "at 1 n_rpm=10\n";
        for (size_t k = 0; line[k] != '\0'; k++) {
            many[n++] = line[k];
        }
    }
    many[n] = '\0';
    expect_error(many, SCENARIO_MAX_EVENTS + 1u, "n_rpm");
    test_more_forms();
    test_text_forms();
}

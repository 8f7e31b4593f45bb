/*
 * The scenario parser (see scenario.h). Line-based: each line is split into
 * at most a few dozen tokens; every error names the line, the field and what
 * was expected.
 */
#include "scenario.h"

#include <stdarg.h>

#include "math/umath.h"
#include "util/fmt.h"
#include "util/parse.h"

#define DEG_TO_RAD MATH_DEG_TO_RAD_F64
#define MAX_TOKENS 32u
#define MAX_TIME_S 1.0e6

const char *const scenario_command_names[SCN_COMMAND_COUNT] = {
    "rudder", "stern", "bow_port", "bow_stbd", "n_rpm", "buoyancy", "heading", "depth",
    "autopilot",
    "switch_open", "leg_short", "dc_cap", "battery_cutoff", "fin_jam", "current_offset",
    "phase_open", "prop_fouling",
};

/* Symbolic values of the fault commands that name a part: the k-th is k + 1. */
static const char *const switch_symbols[] = {"a+", "a-", "b+", "b-", "c+", "c-", NULL};
static const char *const leg_symbols[] = {"a", "b", "c", NULL};
static const char *const on_symbols[] = {"on", NULL};
static const char *const off_symbols[] = {"off", NULL};
static const char *const fin_symbols[] = {"rudder", "stern", "bow_port", "bow_stbd", NULL};

/* What a value may be: its unit, whether "deg" may follow, and its range. */
typedef struct {
    const char *unit;
    bool angle; /* [rad], and a "deg" suffix converts */
    double min;
    double max;
    const char *const *symbols; /* when not NULL: one of these names, read as 1, 2, ... */
} value_rule;

static const value_rule command_rules[SCN_COMMAND_COUNT] = {
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rpm", false, -1500.0, 1500.0, NULL},
    {"N", false, -5340.0, 5340.0, NULL},
    {"rad", true, -360.0 * DEG_TO_RAD, 360.0 * DEG_TO_RAD, NULL},
    {"m", false, 0.0, 1e4, NULL},
    {"", false, 1.0, 1.0, off_symbols},
    {"", false, 1.0, 6.0, switch_symbols},
    {"", false, 1.0, 3.0, leg_symbols},
    {"", false, 0.05, 1.0, NULL},
    {"", false, 1.0, 1.0, on_symbols},
    {"", false, 1.0, 4.0, fin_symbols},
    {"A", false, -50.0, 50.0, NULL},
    {"", false, 1.0, 3.0, leg_symbols},
    {"", false, 1.0, 10.0, NULL},
};

/*
 * Ranges of the initial states, in the order of vessel_state_names. The
 * velocities are those the vessel model is valid and its 0.1 s RK4 stable
 * for (docs/vessel.md, section 6): surge and roll up to 5 (m/s, rad/s),
 * sway, heave, pitch and yaw up to 3 (the top speed is 3.9 m/s).
 */
static const value_rule state_rules[VESSEL_NSTATES] = {
    {"m/s", false, -5.0, 5.0, NULL},       {"m/s", false, -3.0, 3.0, NULL},
    {"m/s", false, -3.0, 3.0, NULL},       {"rad/s", false, -5.0, 5.0, NULL},
    {"rad/s", false, -3.0, 3.0, NULL},     {"rad/s", false, -3.0, 3.0, NULL},
    {"m", false, -1e7, 1e7, NULL},         {"m", false, -1e7, 1e7, NULL},
    {"m", false, -1e4, 1e4, NULL},         {"rad", true, -MATH_PI_F64, MATH_PI_F64, NULL},
    {"rad", true, -80.0 * DEG_TO_RAD, 80.0 * DEG_TO_RAD, NULL},
    {"rad", true, -1e3, 1e3, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rad", true, -45.0 * DEG_TO_RAD, 45.0 * DEG_TO_RAD, NULL},
    {"rpm", false, -1500.0, 1500.0, NULL},
};

static const value_rule time_rule = {"s", false, 0.0, MAX_TIME_S, NULL};
static const value_rule angle_rule = {"rad", true, 1e-6, 45.0 * DEG_TO_RAD, NULL};

typedef struct {
    scenario *s;
    scenario_error *err;
    uint32_t line;
    uint32_t init_line[VESSEL_NSTATES]; /* the line that set each initial state (0: none) */
} parser;

static bool fail(parser *p, const parse_token *field, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static bool fail(parser *p, const parse_token *field, const char *format, ...) {
    p->err->line = p->line;
    /* The file's text is echoed escaped (fmt_text_safe): what a terminal shows is what is there. */
    if (field != NULL) {
        (void)fmt_text_safe(p->err->field, sizeof p->err->field, field->text, field->len);
    } else {
        p->err->field[0] = '\0';
    }
    char raw[sizeof p->err->message];
    va_list args;
    va_start(args, format);
    size_t n = fmt_vformat(raw, sizeof raw, format, args);
    va_end(args);
    (void)fmt_text_safe(p->err->message, sizeof p->err->message, raw,
                        (n < sizeof raw) ? n : sizeof raw - 1u);
    return false;
}

/* Reads a value by its rule; `field` names it in messages. */
static bool read_symbol(parser *p, const parse_token *field, const char *text, size_t n,
                        const value_rule *rule, double *out) {
    for (size_t k = 0; rule->symbols[k] != NULL; k++) {
        if (parse_word_is(text, n, rule->symbols[k])) {
            *out = (double)(k + 1u);
            return true;
        }
    }
    char list[64];
    size_t len = 0;
    for (size_t k = 0; rule->symbols[k] != NULL && len < sizeof list; k++) {
        len += fmt_format(list + len, sizeof list - len, "%s%s", (k > 0u) ? ", " : "",
                          rule->symbols[k]);
    }
    return fail(p, field, "expected one of %s, got '%.*s'", list, (int)n, text);
}

static bool read_value(parser *p, const parse_token *field, const char *text, size_t n,
                       const value_rule *rule, double *out) {
    if (rule->symbols != NULL) {
        return read_symbol(p, field, text, n, rule, out);
    }
    double v = 0.0;
    size_t used = 0;
    bool number = parse_number(text, n, &v, &used);
    const bool deg = number && used != n;
    if (deg) {
        number = rule->angle && parse_word_is(text + used, n - used, "deg");
    }
    if (!number) {
        return fail(p, field, "expected a number%s%s%s, got '%.*s'",
                    (rule->unit[0] != '\0') ? " in " : "", rule->unit,
                    rule->angle ? " (or with the suffix deg)" : "", (int)n, text);
    }
    const double scale = deg ? DEG_TO_RAD : 1.0;
    if (!(v * scale >= rule->min && v * scale <= rule->max)) {
        /* In the unit as written; an angle that fits in degrees gets the suffix suggested. */
        const bool hint = rule->angle && !deg && v * DEG_TO_RAD >= rule->min &&
                          v * DEG_TO_RAD <= rule->max;
        return fail(p, field, "value %g%s%s out of range [%g, %g]%s%.*s%s", v,
                    (rule->unit[0] != '\0') ? " " : "", deg ? "deg" : rule->unit,
                    rule->min / scale, rule->max / scale, hint ? " (did you mean " : "",
                    hint ? (int)n : 0, text, hint ? "deg?)" : "");
    }
    *out = v * scale;
    return true;
}

/* Splits "name=value"; false when there is no '=' or either side is empty. */
static bool split_pair(const parse_token *t, parse_token *name, parse_token *value) {
    for (size_t i = 0; i < t->len; i++) {
        if (t->text[i] == '=') {
            name->text = t->text;
            name->len = i;
            value->text = t->text + i + 1u;
            value->len = t->len - i - 1u;
            return name->len > 0u && value->len > 0u;
        }
    }
    return false;
}

static int find_name(const parse_token *name, const char *const *names, int count) {
    for (int i = 0; i < count; i++) {
        if (parse_word_is(name->text, name->len, names[i])) {
            return i;
        }
    }
    return -1;
}

static bool parse_duration(parser *p, const parse_token *tok, size_t n) {
    if (n != 2u) {
        return fail(p, &tok[0], "expected 'duration <seconds>'");
    }
    static const value_rule rule = {"s", false, 1e-3, MAX_TIME_S, NULL};
    if (p->s->duration_line != 0u) {
        return fail(p, &tok[0], "a second duration (the first is on line %lu)",
                    (unsigned long)p->s->duration_line);
    }
    p->s->duration_line = p->line;
    return read_value(p, &tok[0], tok[1].text, tok[1].len, &rule, &p->s->duration_s);
}

static bool parse_init(parser *p, const parse_token *tok, size_t n) {
    if (n < 2u) {
        return fail(p, &tok[0], "expected 'init <state>=<value> ...'");
    }
    for (size_t i = 1; i < n; i++) {
        parse_token name;
        parse_token value;
        if (!split_pair(&tok[i], &name, &value)) {
            return fail(p, &tok[i], "expected <state>=<value>, got '%.*s'", (int)tok[i].len,
                        tok[i].text);
        }
        int k = find_name(&name, vessel_state_names, VESSEL_NSTATES);
        if (k < 0) {
            return fail(p, &name, "unknown state (expected one of u_mps ... n_rpm, as in the "
                                  "reference CSV layout)");
        }
        if (p->init_line[k] != 0u) {
            return fail(p, &name, "a second initial %s (the first is on line %lu)",
                        vessel_state_names[k], (unsigned long)p->init_line[k]);
        }
        p->init_line[k] = p->line;
        if (!read_value(p, &name, value.text, value.len, &state_rules[k], &p->s->init[k])) {
            return false;
        }
        if (k == (int)VESSEL_N_RPM) {
            p->s->init_rpm_line = p->line;
        }
    }
    return true;
}

static bool add_event(parser *p, const parse_token *field, double t, int command, double v) {
    scenario *s = p->s;
    if (s->n_events >= SCENARIO_MAX_EVENTS) {
        return fail(p, field, "too many commands (at most %u per scenario)",
                    (unsigned)SCENARIO_MAX_EVENTS);
    }
    /* Insert after every event at or before t: a stable sort by time. */
    size_t k = s->n_events;
    while (k > 0u && s->events[k - 1u].t_s > t) {
        s->events[k] = s->events[k - 1u];
        k--;
    }
    s->events[k].t_s = t;
    s->events[k].value = v;
    s->events[k].command = (uint16_t)command;
    s->events[k].line = p->line;
    s->n_events++;
    return true;
}

static bool parse_at(parser *p, const parse_token *tok, size_t n) {
    if (n < 3u) {
        return fail(p, &tok[0], "expected 'at <time> <command>=<value> ...'");
    }
    double t = 0.0;
    if (!read_value(p, &tok[0], tok[1].text, tok[1].len, &time_rule, &t)) {
        return false;
    }
    for (size_t i = 2; i < n; i++) {
        parse_token name;
        parse_token value;
        if (!split_pair(&tok[i], &name, &value)) {
            return fail(p, &tok[i], "expected <command>=<value>, got '%.*s'", (int)tok[i].len,
                        tok[i].text);
        }
        int c = find_name(&name, scenario_command_names, SCN_COMMAND_COUNT);
        if (c < 0) {
            return fail(p, &name, "unknown command (expected rudder, stern, bow_port, "
                                  "bow_stbd, n_rpm, buoyancy, heading, depth, autopilot "
                                  "or a fault)");
        }
        double v = 0.0;
        if (!read_value(p, &name, value.text, value.len, &command_rules[c], &v) ||
            !add_event(p, &name, t, c, v)) {
            return false;
        }
    }
    return true;
}

static bool parse_zigzag(parser *p, const parse_token *tok, size_t n) {
    static const char *const keys[] = {"rudder", "heading", "start", "stop"};
    scenario_zigzag z = {true, 0.0, 0.0, 0.0, -1.0};
    bool seen[4] = {false, false, false, false};
    for (size_t i = 1; i < n; i++) {
        parse_token name;
        parse_token value;
        if (!split_pair(&tok[i], &name, &value)) {
            return fail(p, &tok[i], "expected <key>=<value>, got '%.*s'", (int)tok[i].len,
                        tok[i].text);
        }
        int k = find_name(&name, keys, 4);
        if (k < 0) {
            return fail(p, &name, "unknown zigzag key (expected rudder, heading, start, stop)");
        }
        double *dest[4] = {&z.rudder_rad, &z.heading_rad, &z.start_s, &z.stop_s};
        if (!read_value(p, &name, value.text, value.len, (k < 2) ? &angle_rule : &time_rule,
                        dest[k])) {
            return false;
        }
        seen[k] = true;
    }
    if (!seen[0] || !seen[1]) {
        return fail(p, &tok[0], "expected 'zigzag rudder=<amplitude> heading=<threshold>'");
    }
    if (seen[3] && z.stop_s <= z.start_s) {
        return fail(p, &tok[0], "stop (%g s) must come after start (%g s)", z.stop_s,
                    z.start_s);
    }
    if (p->s->zigzag.enabled) {
        return fail(p, &tok[0], "only one zigzag per scenario");
    }
    p->s->zigzag = z;
    return true;
}

static bool parse_line(parser *p, const char *line, size_t n) {
    /* Everything from '#' on is a comment. */
    for (size_t i = 0; i < n; i++) {
        if (line[i] == '#') {
            n = i;
            break;
        }
    }
    parse_token tok[MAX_TOKENS];
    size_t count = parse_tokens(line, n, tok, MAX_TOKENS);
    if (count == 0u) {
        return true;
    }
    if (count > MAX_TOKENS) {
        return fail(p, NULL, "too many fields on one line (at most %u)", (unsigned)MAX_TOKENS);
    }
    if (parse_word_is(tok[0].text, tok[0].len, "duration")) {
        return parse_duration(p, tok, count);
    }
    if (parse_word_is(tok[0].text, tok[0].len, "init")) {
        return parse_init(p, tok, count);
    }
    if (parse_word_is(tok[0].text, tok[0].len, "at")) {
        return parse_at(p, tok, count);
    }
    if (parse_word_is(tok[0].text, tok[0].len, "zigzag")) {
        return parse_zigzag(p, tok, count);
    }
    return fail(p, &tok[0], "unknown keyword (expected duration, init, at or zigzag)");
}

bool scenario_parse(scenario *s, const char *text, size_t n, scenario_error *err) {
    *s = (scenario){0};
    s->zigzag.stop_s = -1.0;
    *err = (scenario_error){0};
    parser p;
    p.s = s;
    p.err = err;
    p.line = 0u;
    for (size_t k = 0u; k < (size_t)VESSEL_NSTATES; k++) {
        p.init_line[k] = 0u;
    }
    /* A UTF-8 byte-order mark at the start is no text. */
    size_t start = 0u;
    if (n >= 3u && (unsigned char)text[0] == 0xEFu && (unsigned char)text[1] == 0xBBu &&
        (unsigned char)text[2] == 0xBFu) {
        start = 3u;
    }
    while (start < n) {
        /* A line ends at LF, CR LF or a CR alone. */
        size_t end = start;
        while (end < n && text[end] != '\n' && text[end] != '\r') {
            end++;
        }
        p.line++;
        for (size_t i = start; i < end; i++) {
            char c = text[i];
            if ((unsigned char)c < 0x20u && c != '\t') {
                return fail(&p, NULL, "unexpected control character (byte 0x%02x)",
                            (unsigned)(unsigned char)c);
            }
        }
        if (!parse_line(&p, text + start, end - start)) {
            return false;
        }
        start = end + ((end + 1u < n && text[end] == '\r' && text[end + 1u] == '\n') ? 2u : 1u);
    }
    return true;
}

/*
 * libFuzzer harness for the scenario parser (src/scenario.c).
 *
 * The input is scenario text of any bytes. The parser must never crash or
 * read out of bounds (the sanitizers watch that), and it must keep its
 * contract, which this harness checks and aborts on when broken:
 *   - a rejected input has an error on a real line (1 .. number of lines),
 *     a NUL-terminated message that is not empty, and a field that names
 *     the text at fault (empty only for the two line-wide errors: a control
 *     character or too many fields);
 *   - an accepted input gives finite values, within the event capacity, in
 *     the ranges the parser promises.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenario.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void broken(const char *what, const scenario_error *err) {
    fprintf(stderr, "contract broken: %s (line %u, field '%.*s', message '%.*s')\n", what,
            err->line, (int)sizeof err->field, err->field, (int)sizeof err->message,
            err->message);
    abort();
}

/* Lines end at LF, CR LF or a CR alone (scenario.h). */
static unsigned count_lines(const uint8_t *data, size_t size) {
    unsigned lines = 0u;
    size_t i = 0u;
    while (i < size) {
        lines++;
        while (i < size && data[i] != '\n' && data[i] != '\r') {
            i++;
        }
        i += (i + 1u < size && data[i] == '\r' && data[i + 1u] == '\n') ? 2u : 1u;
    }
    return lines;
}

static void check_rejected(const uint8_t *data, size_t size, const scenario_error *err) {
    if (memchr(err->message, '\0', sizeof err->message) == NULL ||
        memchr(err->field, '\0', sizeof err->field) == NULL) {
        broken("an unterminated field or message", err);
    }
    if (err->message[0] == '\0') {
        broken("an empty message", err);
    }
    if (err->line < 1u || err->line > count_lines(data, size)) {
        broken("a line number outside the text", err);
    }
    if (err->field[0] == '\0' && strstr(err->message, "control character") == NULL &&
        strstr(err->message, "too many fields") == NULL) {
        broken("an empty field for an error that is bound to one", err);
    }
}

static void check_accepted(const scenario *s) {
    static const scenario_error none;
    if (s->n_events > SCENARIO_MAX_EVENTS) {
        broken("more events than the capacity", &none);
    }
    if (!isfinite(s->duration_s) || s->duration_s < 0.0) {
        broken("a duration that is not finite and non-negative", &none);
    }
    for (size_t i = 0; i < VESSEL_NSTATES; i++) {
        if (!isfinite(s->init[i])) {
            broken("an initial state that is not finite", &none);
        }
    }
    for (size_t i = 0; i < s->n_events; i++) {
        const scenario_event *e = &s->events[i];
        if (!isfinite(e->t_s) || !isfinite(e->value) || e->command >= SCN_COMMAND_COUNT ||
            e->line < 1u) {
            broken("an event with a bad time, value, command or line", &none);
        }
    }
    if (s->zigzag.enabled && !(s->zigzag.rudder_rad > 0.0 && s->zigzag.heading_rad > 0.0)) {
        broken("a zig-zag without positive amplitudes", &none);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    /* The parser's structure is large: static, as it is on a target. */
    static scenario s;
    scenario_error err;
    /* A private copy, so that a read one byte past the end is caught. */
    char *text = malloc(size > 0u ? size : 1u);
    if (text == NULL) {
        return 0;
    }
    if (size > 0u) {
        memcpy(text, data, size);
    }
    if (scenario_parse(&s, text, size, &err)) {
        check_accepted(&s);
    } else {
        check_rejected(data, size, &err);
    }
    free(text);
    return 0;
}

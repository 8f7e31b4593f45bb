/*
 * Scenario files: what a run does, as timed commands. The parser reads text
 * (a file on the host, a built-in or semihosted file on a target) into a
 * fixed-size structure; no heap.
 *
 *   # comment                      anywhere on a line
 *   duration <s>
 *   init <state>=<value> ...       any of the 17 vessel states; unnamed ones start at 0
 *   at <t> <command>=<value> ...   rudder stern bow_port bow_stbd [rad, or NNdeg],
 *                                  n_rpm [rpm], buoyancy [N, the adjustment dB],
 *                                  heading [rad, or NNdeg] and depth [m]: the autopilots
 *                                  hold them (autopilot.h); autopilot=off ends both, and
 *                                  a rudder or stern command ends that axis's,
 *                                  and the faults (docs/reliability.md):
 *                                  switch_open=a+|a-|b+|b-|c+|c-   a switch stuck open
 *                                  leg_short=a|b|c                 shoot-through: trips
 *                                  dc_cap=<fraction>               DC-link capacitance left
 *                                  battery_cutoff=on               the pack at cut-off
 *                                  fin_jam=rudder|stern|bow_port|bow_stbd
 *                                  current_offset=<A>              phase-a sensor offset
 *                                  phase_open=a|b|c                a motor phase disconnected
 *                                  prop_fouling=<factor>           propeller load torque x 1..10
 *   zigzag rudder=<amp> heading=<threshold> [start=<s>] [stop=<s>]
 *
 * A command holds until changed. Events apply at the first slow-frame
 * boundary at or after their time, in file order for equal times. The
 * duration and each initial state may be given once. Lines end at LF,
 * CR LF or a CR alone; a UTF-8 byte-order mark at the start is skipped.
 * Errors echo the file's text escaped (fmt_text_safe), with 32-bit line
 * numbers.
 */
#ifndef UUV_SCENARIO_H
#define UUV_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "models/vessel/vessel.h"

/*
 * Capacity of a scenario's event list (24 bytes each). A build may set a
 * smaller one (-DSCENARIO_MAX_EVENTS=n): the firmware does, as its RAM is
 * counted in kilobytes. A longer scenario is refused with a message.
 */
#ifndef SCENARIO_MAX_EVENTS
#define SCENARIO_MAX_EVENTS 256u
#endif

#if (SCENARIO_MAX_EVENTS < 1) || (SCENARIO_MAX_EVENTS > 65535)
#error "SCENARIO_MAX_EVENTS must be between 1 and 65535"
#endif

typedef enum {
    SCN_RUDDER = 0,  /* [rad] */
    SCN_STERN,       /* [rad] */
    SCN_BOW_PORT,    /* [rad] */
    SCN_BOW_STBD,    /* [rad] */
    SCN_N_RPM,       /* [rpm] shaft speed command */
    SCN_BUOYANCY,    /* [N] buoyancy adjustment dB = B - W */
    SCN_HEADING,     /* [rad] heading the autopilot holds with the rudder */
    SCN_DEPTH,       /* [m] depth the autopilot holds with the stern plane */
    SCN_AUTOPILOT,   /* 1: off (both autopilots; rudder and stern plane amidships) */
    SCN_FAULT_SWITCH_OPEN,    /* switch 1..6: a+ a- b+ b- c+ c- (upper, lower) */
    SCN_FAULT_LEG_SHORT,      /* leg 1..3 */
    SCN_FAULT_DC_CAP,         /* [-] fraction of the DC-link capacitance left */
    SCN_FAULT_BATTERY_CUTOFF, /* 1: the pack's protection opens its contactor */
    SCN_FAULT_FIN_JAM,        /* fin 1..4: rudder, stern, bow_port, bow_stbd */
    SCN_FAULT_CURRENT_OFFSET, /* [A] offset of the phase-a current sensor */
    SCN_FAULT_PHASE_OPEN,     /* motor phase 1..3: a, b, c disconnected */
    SCN_FAULT_PROP_FOULING,   /* [-] factor on the propeller's load torque, 1..10 */
    SCN_COMMAND_COUNT
} scenario_command;

typedef struct {
    double t_s;       /* [s] time the command takes effect */
    double value;     /* in the command's unit (angles already in rad) */
    uint16_t command; /* scenario_command */
    uint32_t line;    /* source line, for messages */
} scenario_event;

typedef struct {
    bool enabled;
    double rudder_rad;    /* [rad] amplitude, > 0 */
    double heading_rad;   /* [rad] switching threshold, > 0 */
    double start_s;       /* [s] */
    double stop_s;        /* [s] (a negative value: until the end) */
} scenario_zigzag;

typedef struct {
    double duration_s;                    /* [s]; 0 when the file gave none */
    uint32_t duration_line;               /* its line (0: none) */
    double init[VESSEL_NSTATES];          /* initial vessel state */
    uint32_t init_rpm_line;               /* line of an init n_rpm=... (0: none) */
    scenario_event events[SCENARIO_MAX_EVENTS];
    size_t n_events;
    scenario_zigzag zigzag;
} scenario;

typedef struct {
    unsigned line;       /* 1-based line of the error (0: not line-bound) */
    char field[24];      /* the field or keyword at fault */
    char message[120];   /* what was expected, and what was found */
} scenario_error;

/* The first fault command; commands from here on are faults. */
#define SCN_FIRST_FAULT SCN_FAULT_SWITCH_OPEN

/* Name and unit of each command, as the file and reports write them. */
extern const char *const scenario_command_names[SCN_COMMAND_COUNT];

/*
 * Parses n bytes of scenario text. Returns true on success; otherwise
 * fills *err and returns false (the scenario is then unusable).
 */
bool scenario_parse(scenario *s, const char *text, size_t n, scenario_error *err);

#endif /* UUV_SCENARIO_H */

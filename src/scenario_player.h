/*
 * The scenario player: turns a parsed scenario (scenario.h) into the
 * commands in force during a run. The executive calls it; it knows
 * neither the drive nor the vessel model, only their command structs.
 *
 *   timed commands   player_next(): the next event due at a slow boundary,
 *                    applied to the vessel's commands (fins, shaft speed,
 *                    buoyancy) or to the fault set
 *   steering rules   player_steer(): at the same boundaries, after the
 *                    timed commands, the zig-zag rule (the rudder from the
 *                    heading), then the heading and depth autopilots
 *                    (autopilot.h) on the fins that are free
 *   fault requests   the fault set the drive is to apply (drive_faults),
 *                    the contactor (battery_cut), the jammed fins and the
 *                    mask the records carry (fault_mask)
 *   shaft speed      player_speed_at(): the speed command in force at any
 *                    time, for the controller's task, which reads it at
 *                    its own frame rather than a slow frame late
 *
 * A command given between slow steps (a co-simulation master's input,
 * player_command()) acts as an event due at that boundary would.
 *
 * Two tasks use one player: the background (slow step) calls player_next(),
 * player_steer() and player_command(); the controller's task calls
 * player_speed_at(). Each
 * keeps its own place in the (read-only) scenario and writes only its own
 * fields (speed_cursor and speed_rpm are the controller task's), so neither
 * waits for the other.
 *
 * A command event is due at the slow boundary t when its time is at most
 * t + 1e-9 of a slow frame (times written in the file land on the boundary
 * they name despite rounding); events of equal time apply in file order.
 * A jammed fin ignores its commands, the zig-zag rule and the autopilots
 * from the jam on. A manual rudder or stern command takes that axis from
 * its autopilot; the zig-zag rule, while active, takes the rudder.
 */
#ifndef UUV_SCENARIO_PLAYER_H
#define UUV_SCENARIO_PLAYER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "autopilot.h"
#include "drive_segment.h"
#include "models/vessel/vessel.h"
#include "scenario.h"

/* What player_next() applied. */
typedef enum {
    PLAYER_IDLE = 0, /* no event due: nothing changed */
    PLAYER_COMMAND,  /* a vessel command (or one a jammed fin ignored) */
    PLAYER_FAULT     /* a fault command: the drive is to be given faults again */
} player_event;

typedef struct {
    const scenario *scn;
    double slow_s;            /* [s] slow frame (the due tolerance) */
    size_t next_event;        /* the background's place in the scenario */
    /* Faults requested so far. */
    uint32_t fault_mask;      /* bit k for command SCN_FIRST_FAULT + k (exec_frame.faults) */
    bool fin_jammed[4];       /* rudder, stern, bow_port, bow_stbd */
    bool battery_cut;         /* the pack's contactor is open */
    drive_faults faults;      /* the drive's fault set (drive_fault_request) */
    /* Steering rules. */
    double zz_rudder_rad;     /* [rad] rudder the zig-zag commands (0: not active) */
    double zz_psi0_rad;       /* [rad] heading when it began */
    autopilot ap;             /* heading and depth hold (scenario commands) */
    /* The controller task's place and its shaft speed command in force. */
    size_t speed_cursor;
    double speed_rpm;         /* [rpm] */
} scenario_player;

/* A player at the scenario's start: no event applied, no fault, autopilots off, speed command 0. */
void player_init(scenario_player *p, const scenario *scn, double slow_s);

/*
 * Applies the next event due at the slow boundary t_s, if any: a fin,
 * shaft speed or buoyancy command to *cmd; a fault to the fault set, a
 * jammed fin holding its actual angle (x[VESSEL_DELTA_R_RAD + k], the
 * vessel's state) in *cmd from now on. Call it until it returns
 * PLAYER_IDLE; after each PLAYER_FAULT the executive passes p->faults to
 * the drive.
 */
player_event player_next(scenario_player *p, double t_s, const double x[VESSEL_NSTATES],
                         vessel_cmd *cmd);

/*
 * The steering rules at the slow boundary t_s, from the vessel's state x:
 * the zig-zag rule (while active, the rudder at the amplitude, reversed
 * when the heading has left the starting heading by the threshold on the
 * rudder's side; when it ends, the rudder amidships), then one step of dt_s
 * of the autopilots that are on.
 */
void player_steer(scenario_player *p, double t_s, const double x[VESSEL_NSTATES], double dt_s,
                  vessel_cmd *cmd);

/* A command (c < SCN_FIRST_FAULT) now, between slow steps; the controller's speed command too. */
void player_command(scenario_player *p, scenario_command c, double value, vessel_cmd *cmd);

/* The shaft speed command in force at t_s [rpm] (t_s not decreasing from call to call). */
double player_speed_at(scenario_player *p, double t_s);

#endif /* UUV_SCENARIO_PLAYER_H */

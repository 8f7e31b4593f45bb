/*
 * The scenario player (see scenario_player.h).
 */
#include "scenario_player.h"

void player_init(scenario_player *p, const scenario *scn, double slow_s) {
    *p = (scenario_player){0};
    p->scn = scn;
    p->slow_s = slow_s;
    p->faults.dc_cap_frac = 1.0;
    p->faults.load_factor = 1.0;
    autopilot_init(&p->ap);
}

/* The fin commands, in the order of the fin_jam values and the actual-angle states. */
static double *fin_command(vessel_cmd *c, int k) {
    double *fins[4] = {&c->rudder_rad, &c->stern_rad, &c->bow_port_rad, &c->bow_stbd_rad};
    return fins[k];
}

/* A fault command: into the mask and the fault set; a jammed fin holds its actual angle. */
static void apply_fault(scenario_player *p, const scenario_event *ev, const double *x,
                        vessel_cmd *cmd) {
    p->fault_mask |= 1u << (ev->command - (uint16_t)SCN_FIRST_FAULT);
    drive_faults *f = &p->faults;
    switch ((scenario_command)ev->command) {
    case SCN_FAULT_SWITCH_OPEN: f->switch_open = (uint8_t)ev->value; break;
    case SCN_FAULT_LEG_SHORT: f->leg_short = (uint8_t)ev->value; break;
    case SCN_FAULT_DC_CAP: f->dc_cap_frac = ev->value; break;
    case SCN_FAULT_CURRENT_OFFSET: f->current_offset_a = ev->value; break;
    case SCN_FAULT_PHASE_OPEN: f->phase_open = (uint8_t)ev->value; break;
    case SCN_FAULT_PROP_FOULING: f->load_factor = ev->value; break;
    case SCN_FAULT_BATTERY_CUTOFF: p->battery_cut = true; break;
    case SCN_FAULT_FIN_JAM: {
        int k = (int)ev->value - 1;
        p->fin_jammed[k] = true;
        *fin_command(cmd, k) = x[(int)VESSEL_DELTA_R_RAD + k];
        break;
    }
    default: break;
    }
}

static void apply_command(scenario_player *p, const scenario_event *ev, vessel_cmd *c) {
    if (ev->command <= (uint16_t)SCN_BOW_STBD && p->fin_jammed[ev->command]) {
        return; /* a jammed fin ignores its commands */
    }
    switch ((scenario_command)ev->command) {
    /* A manual rudder or stern command takes that axis from its autopilot. */
    case SCN_RUDDER:
        c->rudder_rad = ev->value;
        p->ap.heading_on = false;
        break;
    case SCN_STERN:
        c->stern_rad = ev->value;
        p->ap.depth_on = false;
        break;
    case SCN_BOW_PORT: c->bow_port_rad = ev->value; break;
    case SCN_BOW_STBD: c->bow_stbd_rad = ev->value; break;
    case SCN_N_RPM: c->n_rpm = ev->value; break;
    case SCN_BUOYANCY: c->delta_b_n = ev->value; break;
    case SCN_HEADING: autopilot_set_heading(&p->ap, ev->value); break;
    case SCN_DEPTH: autopilot_set_depth(&p->ap, ev->value); break;
    case SCN_AUTOPILOT:
        /* Both off, the fins they drove amidships (a jammed fin stays). */
        p->ap.heading_on = p->ap.depth_on = false;
        c->rudder_rad = p->fin_jammed[0] ? c->rudder_rad : 0.0;
        c->stern_rad = p->fin_jammed[1] ? c->stern_rad : 0.0;
        break;
    default: break;
    }
}

void player_command(scenario_player *p, scenario_command c, double value, vessel_cmd *cmd) {
    if (c < SCN_FIRST_FAULT) {
        scenario_event ev = {0};
        ev.value = value;
        ev.command = (uint16_t)c;
        apply_command(p, &ev, cmd);
        if (c == SCN_N_RPM) {
            p->speed_rpm = value; /* the controller's command in force (player_speed_at) */
        }
    }
}

player_event player_next(scenario_player *p, double t_s, const double x[VESSEL_NSTATES],
                         vessel_cmd *cmd) {
    double due = t_s + 1e-9 * p->slow_s;
    if (p->next_event >= p->scn->n_events || !(p->scn->events[p->next_event].t_s <= due)) {
        return PLAYER_IDLE;
    }
    const scenario_event *ev = &p->scn->events[p->next_event];
    p->next_event++;
    if (ev->command >= (uint16_t)SCN_FIRST_FAULT) {
        apply_fault(p, ev, x, cmd);
        return PLAYER_FAULT;
    }
    apply_command(p, ev, cmd);
    return PLAYER_COMMAND;
}

/* The zig-zag rule (scenario_player.h, player_steer()). */
static void zigzag(scenario_player *p, double t_s, double psi_rad, vessel_cmd *cmd) {
    const scenario_zigzag *z = &p->scn->zigzag;
    bool active = z->enabled && t_s >= z->start_s - 1e-9 && (z->stop_s < 0.0 || t_s < z->stop_s);
    if (!active) {
        if (p->zz_rudder_rad != 0.0 && !p->fin_jammed[0]) {
            cmd->rudder_rad = 0.0; /* the zig-zag ended: rudder amidships */
            p->zz_rudder_rad = 0.0;
        }
        return;
    }
    p->ap.heading_on = false; /* the zig-zag drives the rudder */
    if (p->zz_rudder_rad == 0.0) {
        p->zz_psi0_rad = psi_rad;
        p->zz_rudder_rad = z->rudder_rad;
    } else if (p->zz_rudder_rad > 0.0 && psi_rad - p->zz_psi0_rad <= -z->heading_rad) {
        p->zz_rudder_rad = -z->rudder_rad;
    } else if (p->zz_rudder_rad < 0.0 && psi_rad - p->zz_psi0_rad >= z->heading_rad) {
        p->zz_rudder_rad = z->rudder_rad;
    } else {
        /* The heading is within the threshold: the rudder holds. */
    }
    if (!p->fin_jammed[0]) {
        cmd->rudder_rad = p->zz_rudder_rad;
    }
}

void player_steer(scenario_player *p, double t_s, const double x[VESSEL_NSTATES], double dt_s,
                  vessel_cmd *cmd) {
    zigzag(p, t_s, x[VESSEL_PSI_RAD], cmd);
    /* The autopilots, on the fins that are free (a jammed fin holds). */
    double rudder = cmd->rudder_rad;
    double stern = cmd->stern_rad;
    autopilot_step(&p->ap, x, dt_s, &rudder, &stern);
    cmd->rudder_rad = p->fin_jammed[0] ? cmd->rudder_rad : rudder;
    cmd->stern_rad = p->fin_jammed[1] ? cmd->stern_rad : stern;
}

double player_speed_at(scenario_player *p, double t_s) {
    double due = t_s + 1e-12;
    while (p->speed_cursor < p->scn->n_events && p->scn->events[p->speed_cursor].t_s <= due) {
        const scenario_event *ev = &p->scn->events[p->speed_cursor];
        if (ev->command == (uint16_t)SCN_N_RPM) {
            p->speed_rpm = ev->value;
        }
        p->speed_cursor++;
    }
    return p->speed_rpm;
}

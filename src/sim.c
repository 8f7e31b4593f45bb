/*
 * The simulation executive (see sim.h).
 */
#include "sim.h"

#include "math/umath.h"

const char *const sim_command_names[SIM_NCMD] = {
    "delta_r_cmd_rad", "delta_s_cmd_rad", "delta_bp_cmd_rad", "delta_bs_cmd_rad", "n_cmd_rpm",
};

void sim_config_default(sim_config *cfg) {
    cfg->plant = SIM_PLANT_VESSEL;
    cfg->propulsion = VESSEL_PROP_PAPER;
    cfg->slow_frame_s = 0.1;
    cfg->duration_s = 0.0;
}

sim_status sim_init(sim *s, const sim_config *cfg, const scenario *scn) {
    *s = (sim){0};
    s->cfg = *cfg;
    s->scn = scn;
    if (cfg->plant != SIM_PLANT_VESSEL) {
        return SIM_ERR_PLANT;
    }
    double duration = (cfg->duration_s > 0.0) ? cfg->duration_s : scn->duration_s;
    if (!(cfg->slow_frame_s >= 1e-3 && cfg->slow_frame_s <= 1.0) || !(duration > 0.0) ||
        duration / cfg->slow_frame_s > 4.0e9) {
        return SIM_ERR_CONFIG;
    }
    /* Whole frames; a duration that is not a multiple rounds to the nearest. */
    s->frames = (uint32_t)(duration / cfg->slow_frame_s + 0.5);
    vessel_config vc;
    vessel_config_default(&vc);
    vc.propulsion = cfg->propulsion;
    vc.shaft = VESSEL_SHAFT_LAG;
    vc.step_s = cfg->slow_frame_s;
    if (vessel_init(&s->vessel, &vc) != VESSEL_OK) {
        return SIM_ERR_MODEL;
    }
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        s->x[i] = scn->init[i];
    }
    manoeuvre_init(&s->man, scn->zigzag.enabled, scn->zigzag.heading_rad);
    return SIM_OK;
}

bool sim_done(const sim *s) { return s->frame >= s->frames; }

static void apply_event(vessel_cmd *c, const scenario_event *e) {
    switch ((scenario_command)e->command) {
    case SCN_RUDDER: c->rudder_rad = e->value; break;
    case SCN_STERN: c->stern_rad = e->value; break;
    case SCN_BOW_PORT: c->bow_port_rad = e->value; break;
    case SCN_BOW_STBD: c->bow_stbd_rad = e->value; break;
    case SCN_N_RPM: c->n_rpm = e->value; break;
    case SCN_BUOYANCY: c->delta_b_n = e->value; break;
    case SCN_COMMAND_COUNT: break;
    }
}

/* The zig-zag rule, decided at the start of each slow step. */
static void zigzag_rule(sim *s, double t) {
    const scenario_zigzag *z = &s->scn->zigzag;
    bool active = z->enabled && t >= z->start_s - 1e-9 && (z->stop_s < 0.0 || t < z->stop_s);
    if (!active) {
        if (s->zz_rudder != 0.0) {
            s->cmd.rudder_rad = 0.0; /* the zig-zag ended: rudder amidships */
            s->zz_rudder = 0.0;
        }
        return;
    }
    double psi = s->x[VESSEL_PSI_RAD];
    if (s->zz_rudder == 0.0) {
        s->zz_psi0 = psi;
        s->zz_rudder = z->rudder_rad;
    } else if (s->zz_rudder > 0.0 && psi - s->zz_psi0 <= -z->heading_rad) {
        s->zz_rudder = -z->rudder_rad;
    } else if (s->zz_rudder < 0.0 && psi - s->zz_psi0 >= z->heading_rad) {
        s->zz_rudder = z->rudder_rad;
    }
    s->cmd.rudder_rad = s->zz_rudder;
}

static void apply_commands(sim *s) {
    double t = (double)s->frame * s->cfg.slow_frame_s;
    /* An event is due when its time is at or before this boundary. */
    double due = t + 1e-9 * s->cfg.slow_frame_s;
    while (s->next_event < s->scn->n_events && s->scn->events[s->next_event].t_s <= due) {
        apply_event(&s->cmd, &s->scn->events[s->next_event]);
        s->next_event++;
    }
    zigzag_rule(s, t);
    s->frame_ready = true;
}

void sim_frame_get(sim *s, sim_frame *out) {
    if (!s->frame_ready) {
        apply_commands(s);
    }
    out->index = s->frame;
    out->t_s = (double)s->frame * s->cfg.slow_frame_s;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        out->x[i] = s->x[i];
    }
    out->cmd[0] = s->cmd.rudder_rad;
    out->cmd[1] = s->cmd.stern_rad;
    out->cmd[2] = s->cmd.bow_port_rad;
    out->cmd[3] = s->cmd.bow_stbd_rad;
    out->cmd[4] = s->cmd.n_rpm;
}

void sim_step(sim *s) {
    if (!s->frame_ready) {
        apply_commands(s);
    }
    const double *x = s->x;
    double t = (double)s->frame * s->cfg.slow_frame_s;
    double speed2 = x[VESSEL_U_MPS] * x[VESSEL_U_MPS] + x[VESSEL_V_MPS] * x[VESSEL_V_MPS] +
                    x[VESSEL_W_MPS] * x[VESSEL_W_MPS];
    manoeuvre_update(&s->man, t, x[VESSEL_X_M], x[VESSEL_Y_M], x[VESSEL_PSI_RAD],
                     math_sqrt_f64(speed2), x[VESSEL_R_RADPS], s->cmd.rudder_rad);
    (void)vessel_step(&s->vessel, s->x, &s->cmd);
    s->frame++;
    s->frame_ready = false;
}

const manoeuvre_result *sim_manoeuvre(const sim *s) { return &s->man.r; }

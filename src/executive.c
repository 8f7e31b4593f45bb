/*
 * The multi-rate executive (see executive.h).
 */
#include "executive.h"

#include "math/umath.h"
#include "util/fmt.h"

#define RPM_TO_RADPS (MATH_PI_F64 / 30.0)

/*
 * The fast step after which a split boundary releases the motor task: the
 * frame's second, so that the boundary's work lies in three ticks (its
 * halves after the frame's last step and before the next frame's first,
 * the release after the second).
 */
#define EXEC_SPLIT_RELEASE_AT 2u

const char *const exec_command_names[EXEC_NCMD] = {
    "delta_r_cmd_rad", "delta_s_cmd_rad", "delta_bp_cmd_rad", "delta_bs_cmd_rad", "n_cmd_rpm",
};

void exec_config_default(exec_config *cfg) {
    *cfg = (exec_config){0};
    cfg->plant = EXEC_PLANT_FULL;
    cfg->propulsion = VESSEL_PROP_PAPER;
    cfg->inverter = DRIVE_INVERTER_SWITCHING;
    cfg->modulator = DRIVE_MODULATOR_SUBSTEP;
    cfg->down = COUPLE_ZOH;
    cfg->up = COUPLE_AVG;
    cfg->soc0 = 1.0;
    cfg->fast_ns = 2000u;
    cfg->fast_per_medium = 50u;
    cfg->medium_per_control = 8u;
    cfg->medium_per_slow = 1000u;
}

/* ---- Scenario commands (background) ------------------------------------- */

/*
 * Applies the commands due at the slow boundary t (scenario_player.h): the
 * timed events, each fault passed on to the drive, which applies it at the
 * next slow boundary; then the steering rules (zig-zag, autopilots) over
 * the reporting period that begins.
 */
static void apply_commands(exec *e, double t) {
    for (player_event ev = player_next(&e->player, t, e->x, &e->cmd); ev != PLAYER_IDLE;
         ev = player_next(&e->player, t, e->x, &e->cmd)) {
        if (ev == PLAYER_FAULT && e->cfg.plant == EXEC_PLANT_FULL && e->drive_ready) {
            e->down.faults = &e->player.faults;
        }
    }
    player_steer(&e->player, t, e->x, e->report_s, &e->cmd);
}

void exec_command(exec *e, scenario_command c, double value) {
    player_command(&e->player, c, value, &e->cmd);
}

/* ---- Initialisation ------------------------------------------------------ */

/* Counts a motor-frame boundary to come; true when it is a slow boundary too. */
static bool slow_count(exec *e) {
    bool slow = (++e->slow_phase == e->cfg.medium_per_slow);
    if (slow) {
        e->slow_phase = 0u;
    }
    return slow;
}

static exec_status init_frames(exec *e, const exec_config *cfg, double duration) {
    exec_config *c = &e->cfg;
    if (cfg->fast_ns < 100u || cfg->fast_per_medium == 0u || cfg->medium_per_control == 0u ||
        cfg->medium_per_slow == 0u || cfg->medium_per_slow % cfg->medium_per_control != 0u) {
        return EXEC_ERR_CONFIG;
    }
    e->slow_per_report = 1u;
    if (cfg->single_rate) {
        /* Every integrating segment at the fast frame; records still every 100 ms. */
        c->fast_per_medium = 1u;
        c->medium_per_control = cfg->fast_per_medium * cfg->medium_per_control;
        c->medium_per_slow = 1u;
        e->slow_per_report = cfg->fast_per_medium * cfg->medium_per_slow;
    } else if (cfg->inverter == DRIVE_INVERTER_AVERAGED) {
        /* The averaged layer runs its stage and the motor at the controller's
         * frame (inverter_avg.h): one frame per controller step. */
        uint64_t frame_ns =
            (uint64_t)cfg->fast_ns * cfg->fast_per_medium * cfg->medium_per_control;
        if (frame_ns > 0xFFFFFFFFu) {
            return EXEC_ERR_CONFIG;
        }
        c->fast_ns = (uint32_t)frame_ns;
        c->fast_per_medium = 1u;
        c->medium_per_slow = cfg->medium_per_slow / cfg->medium_per_control;
        c->medium_per_control = 1u;
    }
    double slow_ns = (double)c->fast_ns * (double)c->fast_per_medium * (double)c->medium_per_slow;
    e->slow_s = 1e-9 * slow_ns;
    e->report_ns = slow_ns * (double)e->slow_per_report;
    double report_s = 1e-9 * e->report_ns;
    e->report_s = report_s;
    if (!(e->slow_s <= 10.0) || (cfg->plant == EXEC_PLANT_VESSEL && !(e->slow_s >= 1e-3))) {
        return EXEC_ERR_SLOW_FRAME;
    }
    if (!(duration > 0.0) || duration / report_s > 4.0e9) {
        return (duration > 0.0) ? EXEC_ERR_DURATION_LONG : EXEC_ERR_DURATION_SHORT;
    }
    /* Whole reporting periods; a duration in between rounds to the nearest. */
    uint64_t reports = (uint64_t)(duration / report_s + 0.5);
    if (reports == 0u || reports * e->slow_per_report > 0xFFFFFFFFu) {
        return (reports == 0u) ? EXEC_ERR_DURATION_SHORT : EXEC_ERR_DURATION_LONG;
    }
    e->frames = (uint32_t)(reports * e->slow_per_report);
    uint64_t medium_frames = (uint64_t)e->frames * c->medium_per_slow;
    if (cfg->plant == EXEC_PLANT_FULL && medium_frames > 0xFFFFFFFFu) {
        return EXEC_ERR_DURATION_LONG;
    }
    e->medium_left = (uint32_t)medium_frames;
    e->stagger_at = drive_staggered(cfg->down, c->fast_per_medium) ? c->fast_per_medium / 2u : 0u;
    e->split = (e->stagger_at == 0u && c->fast_per_medium > EXEC_SPLIT_RELEASE_AT);
    e->fast_event_at = (e->stagger_at != 0u) ? e->stagger_at : c->fast_per_medium;
    e->slow_due = slow_count(e);
    return EXEC_OK;
}

static exec_status init_drive(exec *e) {
    const exec_config *c = &e->cfg;
    e->bat_params = *c->params->battery;
    e->bat_params.frame_s = e->slow_s;
    if (battery_init(&e->bat, &e->bat_params, c->soc0) != BATTERY_OK) {
        return EXEC_ERR_MODEL;
    }
    battery_companion bc = battery_companion_f64(&e->bat);
    drive_battery b0 = {bc.g_s, bc.b_a};
    drive_config dc;
    dc.inverter = c->inverter;
    dc.modulator = c->modulator;
    dc.dead_time_ns = c->params->pwm->dead_time_ns; /* the set's (sub-step only) */
    dc.down = c->down;
    dc.up = c->up;
    dc.fast_ns = c->fast_ns;
    dc.fast_per_medium = c->fast_per_medium;
    dc.medium_per_control = c->medium_per_control;
    dc.medium_per_slow = c->medium_per_slow;
    dc.v_dc0_v = battery_voltage_f64(&e->bat, 0.0);
    dc.energy_audit = c->energy_audit;
    dc.stage = c->params->stage;
    dc.pwm = c->params->pwm;
    dc.motor = c->params->motor;
    dc.control = c->params->control;
    const drive_status ds = drive_init(&e->drive, &dc, &e->prop);
    if (ds != DRIVE_OK) {
        return (ds == DRIVE_ERR_LAYER) ? EXEC_ERR_LAYER : EXEC_ERR_MODEL;
    }
    drive_start(&e->drive, &b0);
    e->drive_ready = true;
    if (e->player.fault_mask != 0u) {
        drive_fault_request(&e->drive, &e->player.faults);
    }
    e->down.bat_next = b0;
    e->speed_report_rpm = player_speed_at(&e->player, 0.0);
    drive_speed_command(&e->drive, e->speed_report_rpm * RPM_TO_RADPS);
    return EXEC_OK;
}

/* Why the configuration cannot model a command, or NULL when it can. */
static const char *unmodelled(const exec_config *cfg, uint16_t command) {
    if (command < (uint16_t)SCN_FIRST_FAULT || command == (uint16_t)SCN_FAULT_FIN_JAM) {
        return NULL;
    }
    if (cfg->plant != EXEC_PLANT_FULL) {
        return "a drive fault, and the vessel plant has no drive (use --plant full)";
    }
    if (cfg->inverter == DRIVE_INVERTER_AVERAGED &&
        (command == (uint16_t)SCN_FAULT_SWITCH_OPEN || command == (uint16_t)SCN_FAULT_LEG_SHORT ||
         command == (uint16_t)SCN_FAULT_PHASE_OPEN ||
         command == (uint16_t)SCN_FAULT_BATTERY_CUTOFF)) {
        return "the averaged inverter has no switches to fault or to block "
               "(use --inverter switching or event)";
    }
    return NULL;
}

bool exec_check_scenario(const exec_config *cfg, const scenario *scn, scenario_error *err) {
    if (cfg->plant == EXEC_PLANT_FULL && scn->init[VESSEL_N_RPM] != 0.0) {
        (void)fmt_format(err->field, sizeof err->field, "n_rpm");
        err->line = scn->init_rpm_line;
        (void)fmt_format(err->message, sizeof err->message,
                         "the full plant starts its motor at rest: command the speed with "
                         "'at 0 n_rpm=...' (or use --plant vessel)");
        return false;
    }
    for (size_t k = 0; k < scn->n_events; k++) {
        const scenario_event *ev = &scn->events[k];
        const char *why = unmodelled(cfg, ev->command);
        if (why != NULL) {
            (void)fmt_format(err->field, sizeof err->field, "%s",
                             scenario_command_names[ev->command]);
            err->line = ev->line;
            (void)fmt_format(err->message, sizeof err->message, "%s", why);
            return false;
        }
    }
    return true;
}

static void make_report(exec *e);

exec_status exec_init(exec *e, const exec_config *cfg, const scenario *scn) {
    *e = (exec){0};
    e->cfg = *cfg;
    if (cfg->params == NULL) {
        e->cfg.params = &uuv_params_default;
    }
    e->trip_t_s = -1.0;
    double duration = (cfg->duration_s > 0.0) ? cfg->duration_s : scn->duration_s;
    if (!(cfg->soc0 > 0.0 && cfg->soc0 <= 1.0) || cfg->plant > EXEC_PLANT_FULL) {
        return EXEC_ERR_CONFIG;
    }
    exec_status st = init_frames(e, cfg, duration);
    if (st != EXEC_OK) {
        return st;
    }
    const uuv_params *set = e->cfg.params;
    if (propeller_init(&e->prop, set->propeller) != PROPELLER_OK) {
        return EXEC_ERR_MODEL;
    }
    vessel_config vc;
    vessel_config_default(&vc);
    vc.params = set->vessel;
    vc.propeller = set->propeller;
    vc.propulsion = cfg->propulsion;
    vc.shaft = (cfg->plant == EXEC_PLANT_FULL) ? VESSEL_SHAFT_INPUT : VESSEL_SHAFT_LAG;
    vc.free_surface = !cfg->deep_water;
    vc.step_s = e->slow_s;
    if (vessel_init(&e->vessel, &vc) != VESSEL_OK) {
        return EXEC_ERR_MODEL;
    }
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        e->x[i] = scn->init[i];
    }
    player_init(&e->player, scn, e->slow_s);
    protection_init(&e->prot, e->slow_s);
    e->player.ap.p = *e->cfg.params->autopilot;
    manoeuvre_init(&e->man, scn->zigzag.enabled, scn->zigzag.heading_rad, scn->zigzag.start_s);
    apply_commands(e, 0.0);
    if (cfg->plant == EXEC_PLANT_FULL) {
        /* The shaft starts at rest with the motor; the state says so. */
        e->x[VESSEL_N_RPM] = 0.0;
        st = init_drive(e);
        if (st != EXEC_OK) {
            return st;
        }
    }
    make_report(e);
    return EXEC_OK;
}

/* ---- Fast and medium rates ----------------------------------------------- */

/* The run ends: the state says why, and the fast ticks do nothing more. */
static void exec_end(exec *e, exec_state why) {
    e->state = why;
    e->fast_gate = EXEC_GATE_STOP;
}

/* A slower task still running when its results are due ends the run. */
static void overrun(exec *e, uint32_t *counter) {
    (*counter)++;
    exec_end(e, EXEC_STOP_OVERRUN);
}

/* The boundary's second half (decided at the last release: slow_due). */
static inline void boundary_begin(exec *e) __attribute__((always_inline));
static inline void boundary_begin(exec *e) {
    e->rel_slow = e->slow_due;
    drive_medium_begin(&e->drive, e->slow_due);
}

/* The motor task's release, once both halves of the boundary have run. */
static bool medium_release(exec *e) {
    uint32_t n = e->cfg.fast_per_medium;
    e->fast_event_at = (e->stagger_at != 0u) ? e->stagger_at : n;
    e->slow_due = slow_count(e);
    e->medium_busy = true;
    return true;
}

/*
 * The second half and the release together: in the boundary's own tick,
 * or, split, in the tick of its own that follows the run's last step
 * (after which the fast ticks are over).
 */
static bool boundary_end(exec *e) {
    boundary_begin(e);
    if (e->medium_left == 0u) {
        e->fast_gate = EXEC_GATE_STOP;
    }
    return medium_release(e);
}

/*
 * A fast tick's event, after its step, out of the tick's common path:
 * - At a motor-frame boundary (fast_phase n): the boundary's first half,
 *   drive_medium_publish(). Its second half (boundary_begin()) and the
 *   motor task's release follow in the same tick, or, when split, before
 *   the next tick's step and after the one after that. Split, no tick
 *   carries the whole boundary, which on a Cortex-M is more than a fast
 *   frame's slack (docs/firmware.md); the results are the same, as no
 *   step runs between the halves and the motor task reads only what they
 *   wrote. After the run's last boundary one more tick runs the second
 *   half and the release, without a step (boundary_end()).
 * - Split, EXEC_SPLIT_RELEASE_AT steps into the frame: the release.
 * - Staggered, half a frame after the release: the latch.
 */
static bool fast_event(exec *e) {
    uint32_t n = e->cfg.fast_per_medium;
    if (e->fast_phase < n) {
        if (e->split) {
            return medium_release(e);
        }
        /* Staggered: the motor task's results arrive half a frame after its release. */
        e->fast_event_at = n;
        if (e->medium_busy) {
            overrun(e, &e->count.overruns_medium);
            return false;
        }
        drive_medium_latch(&e->drive);
        return false;
    }
    e->fast_phase = 0u;
    e->medium_left--;
    if (e->medium_busy) {
        overrun(e, &e->count.overruns_medium);
        return false;
    }
    drive_medium_publish(&e->drive);
    if (e->split) {
        e->fast_gate = (e->medium_left != 0u) ? EXEC_GATE_BEGIN : EXEC_GATE_LAST;
        e->fast_event_at = EXEC_SPLIT_RELEASE_AT;
        return false;
    }
    return boundary_end(e);
}

/*
 * The fast tick's count and event after its step (exec_fast_tick(), and
 * the desk's batches: exec_desk_tick_end()).
 */
/* Inlined in every build (the Cortex-M3's -Os too), so that exec_fast_tick()'s code is its own. */
static inline bool fast_tick_after(exec *e) __attribute__((always_inline));
static inline bool fast_tick_after(exec *e) {
    if (++e->fast_phase != e->fast_event_at) {
        return false;
    }
    return fast_event(e);
}

bool exec_fast_tick_event(exec *e) {
    uint8_t gate = e->fast_gate;
    if (gate != 0u) {
        /* Work before the step: the boundary's second half, or no step at all. */
        if (gate != EXEC_GATE_BEGIN) {
            return gate == EXEC_GATE_LAST && boundary_end(e);
        }
        e->fast_gate = 0u;
        boundary_begin(e);
    }
    drive_fast_step(&e->drive);
    return fast_tick_after(e);
}

bool exec_medium_tick(exec *e) {
    if (!e->medium_busy) {
        return false;
    }
    bool control = (++e->medium_phase == e->cfg.medium_per_control);
    if (control) {
        e->medium_phase = 0u;
        if (e->control_busy) {
            /* The controller released a control frame ago has not finished. */
            overrun(e, &e->count.overruns_control);
            e->medium_busy = false;
            return false;
        }
    }
    drive_medium_task(&e->drive, control, e->rel_slow);
    e->count.medium++;
    if (e->rel_slow) {
        if (e->slow_pending) {
            overrun(e, &e->count.overruns_slow);
        } else {
            e->speed_report_rpm = e->player.speed_rpm;
            e->slow_pending = true;
        }
    }
    if (control) {
        e->control_time_ns =
            e->count.medium * (uint64_t)e->cfg.fast_per_medium * (uint64_t)e->cfg.fast_ns;
        e->control_busy = true;
    }
    e->medium_busy = false;
    return control;
}

void exec_control_tick(exec *e) {
    if (!e->control_busy) {
        return;
    }
    double t = 1e-9 * (double)e->control_time_ns;
    drive_speed_command(&e->drive, player_speed_at(&e->player, t) * RPM_TO_RADPS);
    drive_control_task(&e->drive);
    e->count.control++;
    e->control_busy = false;
}

/* ---- Slow rate ----------------------------------------------------------- */

bool exec_slow_pending(const exec *e) { return e->slow_pending; }

/* The battery's frame from the bus voltage the drive measured (i = G v - b). */
static void battery_frame(exec *e) {
    const drive_slow_meas *m = &e->meas;
    double g = m->battery.g_s;
    double b = m->battery.b_a;
    double v = m->v_dc_mean_v;
    double v2 = m->v_dc_sq_mean_v2;
    battery_frame_meas bm;
    bm.i_avg_a = g * v - b;
    bm.i_sq_avg_a2 = g * g * v2 - 2.0 * g * b * v + b * b;
    if (bm.i_sq_avg_a2 < bm.i_avg_a * bm.i_avg_a) {
        bm.i_sq_avg_a2 = bm.i_avg_a * bm.i_avg_a; /* rounding of a near-constant current */
    }
    bm.p_avg_w = g * v2 - b * v;
    battery_step_f64(&e->bat, &bm);
    e->count.e_batt_j -= bm.p_avg_w * e->slow_s;
    e->count.e_mech_j += m->e_mech_j;
    e->count.e_loss_filter_j += m->e_loss_filter_j;
    e->count.e_loss_motor_j += m->e_loss_motor_j;
    /* Once tripped the gates are blocked: the limit the controller still reports acts on nothing. */
    e->count.limit_s += (e->trip_t_s < 0.0) ? m->limit_s : 0.0;
    e->count.saturations = m->saturations;
    e->acc_i_batt -= bm.i_avg_a;
    e->acc_te += m->te_nm;
    e->acc_i_sq += m->i_rms_a * m->i_rms_a;
    e->acc_v_dc += m->v_dc_mean_v;
    e->acc_m += m->m_index;
    e->acc_f += m->f_hz;
    e->acc_n++;
    battery_companion bc = battery_companion_f64(&e->bat);
    /* The contactor open (battery_cutoff): no current either way. */
    e->down.bat_next.g_s = e->player.battery_cut ? 0.0 : bc.g_s;
    e->down.bat_next.b_a = e->player.battery_cut ? 0.0 : bc.b_a;
    e->down.trip = (uint8_t)protection_step(&e->prot, m->i_phase_rms_a);
    if (m->trip != DRIVE_TRIP_NONE && e->trip_t_s < 0.0) {
        e->trip_t_s = (double)e->frame * e->slow_s;
    }
}

/*
 * Bit i set when state i is NaN or infinite, or, for the body velocities,
 * beyond EXEC_DIVERGED in magnitude: one integer comparison of the
 * magnitude's bit pattern each (NaN and infinity lie above every finite
 * bound), cheap where double is software.
 */
static uint32_t state_bad_bits(const double x[VESSEL_NSTATES]) {
    uint32_t bits = 0u;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        const uint64_t mag = math_bits_f64(x[i]) & 0x7fffffffffffffffu;
        const uint64_t lim = (i < VESSEL_X_M) ? math_bits_f64(EXEC_DIVERGED) : 0x7fefffffffffffffu;
        bits |= (mag > lim) ? (1u << (unsigned)i) : 0u;
    }
    return bits;
}

static void make_report(exec *e) {
    exec_frame *r = &e->report;
    r->index = e->frame / e->slow_per_report;
    /* The same times in every mode: whole reporting periods. */
    /* From whole nanoseconds, one rounding: 0.3 s is the double nearest 0.3. */
    r->t_s = ((double)r->index * e->report_ns) / 1e9;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        r->x[i] = e->x[i];
    }
    if (e->cfg.plant == EXEC_PLANT_FULL && e->frame > 0u) {
        /* The vessel integrated the frame with the mean shaft speed; the
         * record gives the speed at the boundary, like every other state. */
        r->x[VESSEL_N_RPM] = e->meas.shaft_end_radps / RPM_TO_RADPS;
    }
    r->cmd[0] = e->cmd.rudder_rad;
    r->cmd[1] = e->cmd.stern_rad;
    r->cmd[2] = e->cmd.bow_port_rad;
    r->cmd[3] = e->cmd.bow_stbd_rad;
    r->cmd[4] = (e->cfg.plant == EXEC_PLANT_FULL) ? e->speed_report_rpm : e->cmd.n_rpm;
    if (e->cfg.plant == EXEC_PLANT_FULL) {
        double n = (e->acc_n > 0u) ? (double)e->acc_n : 1.0;
        r->te_nm = e->acc_te / n;
        r->i_rms_a = math_sqrt_f64(e->acc_i_sq / n);
        r->v_dc_v = (e->acc_n > 0u) ? e->acc_v_dc / n : battery_voltage_f64(&e->bat, 0.0);
        r->i_batt_a = e->acc_i_batt / n;
        r->soc = e->bat.soc;
        r->m_index = e->acc_m / n;
        r->f_hz = e->acc_f / n;
        r->trip = (uint32_t)e->meas.trip;
        /* One sum: a NaN or an infinity in any term makes it non-finite. The
         * energy counters are made of these quantities, so they are finite too
         * (exec_slow_step restores them with the state when this trips). */
        const double sum = r->te_nm + r->i_rms_a + r->v_dc_v + r->i_batt_a + r->soc + r->m_index +
                           r->f_hz;
        e->nonfinite = math_isfinite_f64(sum) ? 0u : EXEC_NONFINITE_DRIVE;
    }
    r->faults = e->player.fault_mask;
    e->acc_te = e->acc_i_sq = e->acc_v_dc = e->acc_i_batt = e->acc_m = e->acc_f = 0.0;
    e->acc_n = 0u;
    e->report_ready = (e->nonfinite == 0u);
}

void exec_slow_model(exec *e) {
    if (e->state != EXEC_RUNNING) {
        return;
    }
    const exec_counters kept = e->count; /* restored by the guard below */
    e->down.faults = NULL;
    if (e->cfg.plant == EXEC_PLANT_FULL) {
        battery_frame(e);
        /* The shaft speed over the frame just measured: its start, and the
         * rate that brings it to the reduced value (mean, filtered or
         * sampled) at the frame's middle, a first-order hold. */
        double start = e->shaft_start_rpm;
        double reduced = e->meas.shaft_radps / RPM_TO_RADPS;
        e->cmd.shaft_rpm = start;
        e->cmd.shaft_rate_rpmps = 2.0 * (reduced - start) / e->slow_s;
        e->shaft_start_rpm = e->meas.shaft_end_radps / RPM_TO_RADPS;
    }
    const double *x = e->x;
    double t = (double)e->frame * e->slow_s;
    /* The manoeuvre metrics, which only the desk reports (not in a lean image). */
    if (UUV_LEAN_IMAGE == 0 && e->frame % e->slow_per_report == 0u) {
        double speed2 = x[VESSEL_U_MPS] * x[VESSEL_U_MPS] + x[VESSEL_V_MPS] * x[VESSEL_V_MPS] +
                        x[VESSEL_W_MPS] * x[VESSEL_W_MPS];
        manoeuvre_update(&e->man, t, x[VESSEL_X_M], x[VESSEL_Y_M], x[VESSEL_PSI_RAD],
                         math_sqrt_f64(speed2), x[VESSEL_R_RADPS],
                         e->player.ap.heading_on ? 0.0 : e->cmd.rudder_rad); /* manual turns only */
    }
    (void)vessel_step(&e->vessel, e->x, &e->cmd);
    e->frame++;
    e->count.slow++;
    e->nonfinite = state_bad_bits(e->x);
    t = (double)e->frame * e->slow_s;
    if (e->nonfinite == 0u && e->frame % e->slow_per_report == 0u) {
        /* Scenario commands and the zig-zag rule act on the reporting grid. */
        apply_commands(e, t);
        make_report(e);
    }
    /* The guard: a frame that makes a state or a reported value non-finite,
     * or a velocity diverge (beyond EXEC_DIVERGED), ends the run. Nothing
     * more is published and the counters are those of the frame before, so
     * no NaN reaches an output; e->report keeps the last finite record. */
    if (e->nonfinite != 0u) {
        e->count = kept;
        exec_end(e, EXEC_STOP_NONFINITE);
    } else if (e->frame >= e->frames) {
        exec_end(e, EXEC_DONE);
    }
    e->down.state = (uint8_t)e->state;
}

void exec_drive_take(exec *e, const exec_to_drive *d) {
    drive_battery_next(&e->drive, &d->bat_next);
    if (d->trip != (uint8_t)DRIVE_TRIP_NONE) {
        drive_trip_request(&e->drive, (drive_trip)d->trip);
    }
    if (d->faults != NULL) {
        drive_fault_request(&e->drive, d->faults);
    }
    if (d->state != (uint8_t)EXEC_RUNNING) {
        exec_end(e, (exec_state)d->state);
    }
    e->slow_pending = false;
}

void exec_slow_step(exec *e) {
    if ((e->state == EXEC_RUNNING) && (e->cfg.plant == EXEC_PLANT_FULL)) {
        drive_slow_measure(&e->drive, &e->meas);
        exec_slow_model(e);
        exec_drive_take(e, &e->down);
    } else if (e->state == EXEC_RUNNING) {
        exec_slow_model(e);
        e->slow_pending = false;
    } else {
        /* The run has ended: nothing more. */
    }
}

/* What a desk tick runs after its fast tick: the tasks it released, a slow step. */
static void desk_after_tick(exec *e, bool released) {
    if (released && exec_medium_tick(e)) {
        exec_control_tick(e);
    }
    if (e->slow_pending) {
        exec_slow_step(e);
    }
}

void exec_desk_step(exec *e) {
    if (e->cfg.plant == EXEC_PLANT_VESSEL) {
        exec_slow_step(e);
        return;
    }
    desk_after_tick(e, exec_fast_tick(e));
}


/*
 * The averaged layer's frames (inverter averaged: one fast tick, one motor
 * step and one controller step per frame, fast_per_medium and
 * medium_per_control 1), up to max_ticks of them and at most up to a slow
 * boundary's step: what exec_desk_step() runs for each, without the fast
 * tick's gate, phase and release machinery, which has nothing to do at
 * that frame (no fast step, no split, no stagger, no overrun on the desk).
 * The boundary's latch and the averaged stage (drive_medium_begin()), the
 * motor task (drive_medium_task()) and the controller task
 * (drive_control_task()) run as exec_fast_tick(), exec_medium_tick() and
 * exec_control_tick() run them, with the same counters, so the results are
 * the same bits (suite executive checks it).
 */
static uint32_t desk_run_averaged(exec *e, uint32_t max_ticks) {
    uint32_t n = 0u;
    while (n < max_ticks) {
        n++;
        e->medium_left--;
        const bool slow = e->slow_due;
        e->rel_slow = slow;
        drive_medium_begin(&e->drive, slow);
        if (e->medium_left == 0u) {
            e->fast_gate = EXEC_GATE_STOP;
        }
        e->slow_due = slow_count(e);
        drive_medium_task(&e->drive, true, slow);
        e->count.medium++;
        if (slow) {
            /* The motor task's hand-over (before the controller's command moves on). */
            e->speed_report_rpm = e->player.speed_rpm;
            e->slow_pending = true;
        }
        e->control_time_ns = e->count.medium * (uint64_t)e->cfg.fast_ns;
        const double t = 1e-9 * (double)e->control_time_ns;
        drive_speed_command(&e->drive, player_speed_at(&e->player, t) * RPM_TO_RADPS);
        drive_control_task(&e->drive);
        e->count.control++;
        if (slow) {
            exec_slow_step(e);
            break;
        }
    }
    return n;
}

/*
 * The averaged layer at its own frame (init_frames()), between two events,
 * with no record waiting to be taken (a lean run ends with a slow step,
 * whose record would replace it).
 */
static bool desk_averaged(const exec *e) {
    return DRIVE_OPTIONAL(e->cfg.inverter == DRIVE_INVERTER_AVERAGED) &&
           e->cfg.plant == EXEC_PLANT_FULL && e->cfg.fast_per_medium == 1u &&
           e->cfg.medium_per_control == 1u && e->fast_gate == 0u && !e->medium_busy &&
           !e->control_busy && !e->slow_pending && e->medium_phase == 0u && !e->report_ready;
}

uint32_t exec_desk_ahead(const exec *e, uint32_t max_ticks) {
    if (e->cfg.plant != EXEC_PLANT_FULL || e->fast_gate != 0u || desk_averaged(e)) {
        return 0u;
    }
    /* The ticks before the next event only step (exec_fast_tick()). */
    const uint32_t n = e->fast_event_at - e->fast_phase - 1u;
    return (n < max_ticks) ? n : max_ticks;
}

uint32_t exec_desk_finish(exec *e, uint32_t stepped, uint32_t max_ticks) {
    uint32_t n = stepped;
    e->fast_phase += n;
    if (n < max_ticks) {
        exec_desk_step(e);
        n++;
    }
    return n;
}

/* The event's tick's work after its step, if the run ended at the event, and a slow step. */
static void desk_event_after(exec *e) {
    desk_after_tick(e, (e->fast_phase == e->fast_event_at) && fast_event(e));
}

/*
 * A whole split motor frame (executive.h: exec_desk_frame_begin()), its
 * boundary's second half done: the release's work (the motor task, the
 * controller, a slow step) first, then the frame's steps as one run, then
 * the boundary's first half. The same results as the release
 * EXEC_SPLIT_RELEASE_AT steps into the frame: nothing those tasks write
 * reaches the fast steps before the next boundary (drive_segment.h), and
 * none of them reads the steps. If the release's slow step ends the run,
 * the frame's steps stop where they stop in exec_desk_step()'s order, at
 * the release.
 */

bool exec_desk_frame_whole(const exec *e, bool begin, uint32_t max_ticks) {
    return begin && e->split && (e->fast_phase == 0u) && (max_ticks >= e->cfg.fast_per_medium);
}

uint32_t exec_desk_frame_begin(exec *e) {
    const uint32_t rel = e->fast_event_at;
    e->fast_phase = rel;
    desk_event_after(e);
    e->fast_phase = 0u;
    return exec_fast_ended(e) ? rel : e->cfg.fast_per_medium;
}

void exec_desk_frame_end(exec *e, uint32_t n) {
    e->fast_phase = n;
    desk_event_after(e);
}

static uint32_t desk_frame_hooked(exec *e) {
    const uint32_t n = exec_desk_frame_begin(e);
    e->desk_run(e->desk_ctx, &e->drive, n);
    exec_desk_frame_end(e, n);
    return n;
}

/*
 * With a port's runner (e->desk_run): the ticks up to and including the
 * next event's as one run of steps, the event's tick's work before its
 * step (the boundary's second half, split) ahead of the run and its work
 * after the step behind it, in exec_desk_step()'s order (no slow step is
 * pending between events on the desk: the one a motor task releases runs
 * in that task's tick). Returns 0 where this does not apply (the ticks
 * without a step, the end).
 */
static uint32_t desk_run_hooked(exec *e, uint32_t max_ticks) {
    const bool begin = (e->fast_gate == EXEC_GATE_BEGIN);
    uint32_t n = 0u;
    if ((max_ticks != 0u) && !e->slow_pending && exec_desk_tick_begin(e)) {
        if (exec_desk_frame_whole(e, begin, max_ticks)) {
            n = desk_frame_hooked(e);
        } else {
            const uint32_t ahead = e->fast_event_at - e->fast_phase;
            n = (ahead < max_ticks) ? ahead : max_ticks;
            e->desk_run(e->desk_ctx, &e->drive, n);
            e->fast_phase += n;
            desk_event_after(e);
        }
    }
    return n;
}

bool exec_desk_tick_begin(exec *e) {
    if (e->cfg.plant != EXEC_PLANT_FULL || desk_averaged(e) ||
        (e->fast_gate != 0u && e->fast_gate != EXEC_GATE_BEGIN)) {
        return false;
    }
    if (e->fast_gate == EXEC_GATE_BEGIN) {
        /* exec_fast_tick()'s work before its step. */
        e->fast_gate = 0u;
        boundary_begin(e);
    }
    return true;
}

void exec_desk_tick_end(exec *e) { desk_after_tick(e, fast_tick_after(e)); }

uint32_t exec_desk_run(exec *e, uint32_t max_ticks) {
    uint32_t n;
    if (desk_averaged(e)) {
        n = desk_run_averaged(e, max_ticks);
    } else {
        n = (e->desk_run != NULL) ? desk_run_hooked(e, max_ticks) : 0u;
        if (n == 0u) {
            const uint32_t k = exec_desk_ahead(e, max_ticks);
            if (k > 0u) {
                drive_fast_run(&e->drive, k);
            }
            n = exec_desk_finish(e, k, max_ticks);
        }
    }
    return n;
}

bool exec_report_take(exec *e, exec_frame *out) {
    if (!e->report_ready) {
        return false;
    }
    *out = e->report;
    e->report_ready = false;
    return true;
}

double exec_time_s(const exec *e) {
    if (e->cfg.plant == EXEC_PLANT_VESSEL) {
        return (double)e->frame * e->slow_s;
    }
    return 1e-9 * (double)exec_fast_steps(e) * (double)e->cfg.fast_ns;
}

uint32_t exec_overruns(const exec *e) {
    /* Saturating: the sum of three counters must not wrap to a small number. */
    const uint32_t c[3] = {e->count.overruns_medium, e->count.overruns_control,
                           e->count.overruns_slow};
    uint32_t sum = 0u;
    for (int i = 0; i < 3; i++) {
        sum = (c[i] > UINT32_MAX - sum) ? UINT32_MAX : sum + c[i];
    }
    return sum;
}

uint64_t exec_fast_steps(const exec *e) {
    /* The motor frames ended: those of the run (as init_frames stored them) less those left. */
    uint32_t frames = (uint32_t)(e->frames * e->cfg.medium_per_slow) - e->medium_left;
    return (uint64_t)frames * e->cfg.fast_per_medium + e->fast_phase;
}

const manoeuvre_result *exec_manoeuvre(const exec *e) { return &e->man.r; }

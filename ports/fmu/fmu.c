/*
 * uuvsim as an FMI 2.0 co-simulation FMU: the whole vehicle (battery,
 * drive, vessel) behind the standard's C interface, driving the executive
 * through its public API (executive.h) as the desk simulator does.
 *
 * Time. A communication step is a whole number of slow frames (100 ms);
 * any other step is refused with fmi2Error and a logged reason. Within a
 * step the executive runs its frames exactly as the desk simulator does:
 * the fast ticks in runs, each boundary's tasks in their order. The
 * master's inputs at a communication point act there, as scenario events
 * at that time would (exec_command()): the step therefore ends after the
 * slow step of its last boundary, before the controller task released
 * with it, which runs at the start of the next step with the new shaft
 * speed command. The outputs at a communication point are the record the
 * desk simulator writes for that instant, so a master that plays a
 * scenario's commands at the communication points gets the desk's CSV
 * figures bit for bit (tests/host/fmu_import.c checks it).
 *
 * Instances. Everything an instance has lives in its struct, allocated
 * through the master's allocateMemory (src/ has no globals), so that any
 * number run in one process. fmi2GetFMUstate copies the simulation part of
 * the struct and fmi2SetFMUstate copies it back into the same instance:
 * the executive's models point at each other inside the struct, so a copy
 * is valid only in the instance it came from (canSerializeFMUstate is
 * false for the same reason).
 *
 * Messages go through the master's logger only; the FMU writes nothing to
 * stdout or stderr.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmi2.h"
#include "fmu_model.h"

/* The run's length when the master gives no stop time [s] (the executive's limit is ~119 h). */
#define FMU_OPEN_DURATION_S 400000.0

/* The tolerance on communication points and steps, in slow frames. */
#define FMU_TIME_TOL 1e-6

#define N_ENUMS 5

typedef enum { MODE_INSTANTIATED, MODE_INIT, MODE_STEP, MODE_TERMINATED, MODE_ERROR } fmu_mode;

/* What the master sets: parameters and inputs. */
typedef struct {
    int enums[N_ENUMS]; /* inverter, coupling_down, coupling_up, propulsion, plant */
    double soc0;
    double init[FMU_N_INIT];
    double u[FMU_N_INPUTS];
    double set[FMU_N_SET];  /* the autopilots' set points: heading, depth */
    int autopilot;          /* the holds on: bit 0 heading, bit 1 depth */
} fmu_values;

/* The simulation: what fmi2GetFMUstate saves. */
typedef struct {
    exec e;
    scenario scn;            /* the start inputs as events at t = 0, and the duration */
    exec_frame rec;          /* the record at the current communication point */
    double applied[FMU_N_INPUTS]; /* the inputs in force in the executive */
    double applied_set[FMU_N_SET];
    int applied_ap;
    /* The steering's inputs at the last boundary (before its steering step, run_to()):
     * inputs set there act as a scenario event at that time would, before the steering. */
    autopilot steer_ap;
    double steer_rudder_rad, steer_stern_rad;
    bool built;              /* e holds the run of the values set */
} fmu_sim;

typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory alloc;
    fmi2CallbackFreeMemory free_memory;
    fmi2ComponentEnvironment env;
    bool log_calls;
    char name[128];
    fmu_mode mode;
    double t0;               /* [s] the experiment's start time */
    double stop;             /* [s] its stop time (stop_defined) */
    bool stop_defined;
    fmu_values val;
    fmu_sim sim;
} fmu_instance;

typedef struct {
    const fmu_instance *owner;
    fmu_mode mode;
    fmu_values val;
    fmu_sim sim;
} fmu_saved;

/* ---- Logging --------------------------------------------------------------- */

/*
 * A message to the master's logger. The standard's logger takes a format
 * (with "#r<vr>#" for variable names): the text goes with '%' and '#'
 * doubled, so that it prints as written with or without formatting.
 */
static void logf_(const fmu_instance *c, fmi2Status st, const char *category, const char *fmt,
                  ...) __attribute__((format(printf, 4, 5)));
static void logf_(const fmu_instance *c, fmi2Status st, const char *category, const char *fmt,
                  ...) {
    char text[400];
    char escaped[2 * sizeof text];
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    size_t n = 0;
    for (const char *p = text; *p != '\0'; p++) {
        if (*p == '%' || *p == '#') {
            escaped[n++] = *p;
        }
        escaped[n++] = *p;
    }
    escaped[n] = '\0';
    c->logger(c->env, c->name, st, category, escaped);
}

#define FAIL(c, ...) (logf_((c), fmi2Error, "logStatusError", __VA_ARGS__), fmi2Error)

static const char *const mode_names[] = {"instantiated", "initialization", "step",
                                         "terminated", "error"};

/* The call is allowed in the instance's mode (a bit per mode in allowed). */
static bool allowed(const fmu_instance *c, unsigned allowed_modes, const char *call) {
    if ((allowed_modes & (1u << c->mode)) != 0u) {
        if (c->log_calls) {
            logf_(c, fmi2OK, "logCalls", "%s", call);
        }
        return true;
    }
    logf_(c, fmi2Error, "logStatusError", "%s: not allowed in %s mode", call,
          mode_names[c->mode]);
    return false;
}

#define M_INST (1u << MODE_INSTANTIATED)
#define M_INIT (1u << MODE_INIT)
#define M_STEP (1u << MODE_STEP)
#define M_TERM (1u << MODE_TERMINATED)
#define M_ERR (1u << MODE_ERROR)
#define M_ANY (M_INST | M_INIT | M_STEP | M_TERM | M_ERR)

/* ---- Values ------------------------------------------------------------------ */

static void values_default(fmu_values *v) {
    *v = (fmu_values){{0}, 0.0, {0.0}, {0.0}, {0.0}, 0};
    fmu_var var;
    for (size_t k = 0; fmu_var_at(k, &var); k++) {
        if (var.type == FMU_ENUM) {
            v->enums[var.vr - FMU_VR_INVERTER] = (int)var.start;
        }
    }
    v->soc0 = 1.0;
}

/* The run of the values set: the executive initialised at t = 0. */
static fmi2Status build(fmu_instance *c) {
    fmu_sim *s = &c->sim;
    const fmu_values *v = &c->val;
    memset(&s->scn, 0, sizeof s->scn);
    s->scn.duration_s = c->stop_defined ? c->stop - c->t0 : FMU_OPEN_DURATION_S;
    for (int i = 0; i < FMU_N_INIT; i++) {
        s->scn.init[i] = v->init[i];
    }
    for (int k = 0; k < FMU_N_INPUTS; k++) {
        scenario_event *ev = &s->scn.events[s->scn.n_events++];
        ev->t_s = 0.0;
        ev->value = v->u[k];
        ev->command = (uint16_t)k;
        s->applied[k] = v->u[k];
    }
    /* The holds on from the start, after the fins (as in a scenario's line). */
    for (int k = 0; k < FMU_N_SET; k++) {
        if ((v->autopilot & (1 << k)) != 0) {
            scenario_event *ev = &s->scn.events[s->scn.n_events++];
            ev->t_s = 0.0;
            ev->value = v->set[k];
            ev->command = (uint16_t)(SCN_HEADING + k);
        }
        s->applied_set[k] = v->set[k];
    }
    s->applied_ap = v->autopilot;
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.inverter = (drive_inverter)v->enums[0];
    cfg.down = (coupling_down)v->enums[1];
    cfg.up = (coupling_up)v->enums[2];
    cfg.propulsion = (vessel_propulsion)v->enums[3];
    cfg.plant = (exec_plant)v->enums[4];
    cfg.soc0 = v->soc0;
    exec_status st = exec_init(&s->e, &cfg, &s->scn);
    if (st != EXEC_OK) {
        s->built = false;
        return FAIL(c, "the executive refused the run: %s (stop time %.17g s)",
                    st != EXEC_ERR_MODEL ? "a frame, duration or option out of range"
                                         : "a model refused its parameters",
                    s->scn.duration_s);
    }
    (void)exec_report_take(&s->e, &s->rec);
    s->built = true;
    return fmi2OK;
}

static fmi2Status ensure_built(fmu_instance *c) {
    return c->sim.built ? fmi2OK : build(c);
}

/* Values of the parameters and inputs may change before the run is built. */
static void changed(fmu_instance *c) {
    if (c->mode != MODE_STEP) {
        c->sim.built = false;
    }
}

static bool finite(double x) { return x - x == 0.0; }

static fmi2Status set_real(fmu_instance *c, fmi2ValueReference vr, double x) {
    if (!finite(x)) {
        return FAIL(c, "fmi2SetReal: value reference %u: %g is not a finite number", vr, x);
    }
    if (vr >= FMU_VR_INPUT && vr < FMU_VR_INPUT + FMU_N_INPUTS) {
        c->val.u[vr - FMU_VR_INPUT] = x;
        changed(c);
        return fmi2OK;
    }
    if (vr >= FMU_VR_HEADING && vr < FMU_VR_HEADING + FMU_N_SET) {
        c->val.set[vr - FMU_VR_HEADING] = x;
        changed(c);
        return fmi2OK;
    }
    bool param = vr == FMU_VR_SOC0 || (vr >= FMU_VR_INIT && vr < FMU_VR_INIT + FMU_N_INIT);
    if (!param) {
        return FAIL(c, "fmi2SetReal: value reference %u is not a Real input or parameter", vr);
    }
    if (c->mode != MODE_INSTANTIATED && c->mode != MODE_INIT) {
        return FAIL(c, "fmi2SetReal: value reference %u is a fixed parameter: set it before "
                       "fmi2ExitInitializationMode", vr);
    }
    if (vr == FMU_VR_SOC0) {
        if (!(x > 0.0 && x <= 1.0)) {
            return FAIL(c, "fmi2SetReal: soc0 = %.17g: expected a state of charge in (0, 1]", x);
        }
        c->val.soc0 = x;
    } else {
        c->val.init[vr - FMU_VR_INIT] = x;
    }
    changed(c);
    return fmi2OK;
}

static fmi2Status get_real(fmu_instance *c, fmi2ValueReference vr, double *x) {
    const exec_frame *r = &c->sim.rec;
    if (vr >= FMU_VR_INPUT && vr < FMU_VR_INPUT + FMU_N_INPUTS) {
        *x = c->val.u[vr - FMU_VR_INPUT];
    } else if (vr >= FMU_VR_HEADING && vr < FMU_VR_HEADING + FMU_N_SET) {
        *x = c->val.set[vr - FMU_VR_HEADING];
    } else if (vr == FMU_VR_SOC0) {
        *x = c->val.soc0;
    } else if (vr >= FMU_VR_INIT && vr < FMU_VR_INIT + FMU_N_INIT) {
        *x = c->val.init[vr - FMU_VR_INIT];
    } else if (vr == FMU_VR_SLOW_FRAME) {
        *x = FMU_SLOW_FRAME_S;
    } else if (vr >= FMU_VR_STATE && vr < FMU_VR_DRIVE + FMU_N_DRIVE) {
        if (c->mode == MODE_INSTANTIATED) {
            return FAIL(c, "fmi2GetReal: the outputs exist from fmi2EnterInitializationMode on");
        }
        if (ensure_built(c) != fmi2OK) {
            return fmi2Error;
        }
        const double drive[FMU_N_DRIVE] = {r->te_nm, r->i_rms_a, r->v_dc_v, r->i_batt_a,
                                           r->soc,   r->m_index, r->f_hz};
        *x = (vr < FMU_VR_DRIVE) ? r->x[vr - FMU_VR_STATE] : drive[vr - FMU_VR_DRIVE];
    } else {
        return FAIL(c, "fmi2GetReal: value reference %u is not a Real variable", vr);
    }
    return fmi2OK;
}

/* ---- Common functions -------------------------------------------------------- */

const char *fmi2GetTypesPlatform(void) { return "default"; }

const char *fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    fmu_instance *c = comp;
    if (c == NULL) {
        return fmi2Error;
    }
    bool calls = (loggingOn != fmi2False && nCategories == 0u);
    for (size_t k = 0; k < nCategories; k++) {
        if (categories[k] == NULL) {
            return FAIL(c, "fmi2SetDebugLogging: category %zu is NULL", k);
        }
        if (strcmp(categories[k], "logCalls") == 0) {
            calls = (loggingOn != fmi2False);
        } else if (strcmp(categories[k], "logStatusError") != 0 &&
                   strcmp(categories[k], "logStatusWarning") != 0) {
            return FAIL(c, "fmi2SetDebugLogging: unknown category '%s'", categories[k]);
        }
    }
    c->log_calls = calls;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn) {
    (void)fmuResourceLocation;
    (void)visible;
    if (functions == NULL || functions->logger == NULL || functions->allocateMemory == NULL ||
        functions->freeMemory == NULL) {
        return NULL; /* no logger to tell */
    }
    fmu_instance probe = {0};
    probe.logger = functions->logger;
    probe.env = functions->componentEnvironment;
    (void)snprintf(probe.name, sizeof probe.name, "%s",
                   instanceName != NULL ? instanceName : "");
    if (instanceName == NULL || instanceName[0] == '\0') {
        (void)FAIL(&probe, "fmi2Instantiate: the instance needs a name");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        (void)FAIL(&probe, "fmi2Instantiate: this FMU is for co-simulation only");
        return NULL;
    }
    char guid[FMU_GUID_LEN];
    fmu_guid(guid);
    if (fmuGUID == NULL || strcmp(fmuGUID, guid) != 0) {
        (void)FAIL(&probe, "fmi2Instantiate: GUID '%s' is not this FMU's %s (%s build)",
                   fmuGUID != NULL ? fmuGUID : "(null)", guid, fmu_build_name);
        return NULL;
    }
    fmu_instance *c = functions->allocateMemory(1u, sizeof *c);
    if (c == NULL) {
        (void)FAIL(&probe, "fmi2Instantiate: no memory for an instance (%zu bytes)",
                   sizeof *c);
        return NULL;
    }
    memset(c, 0, sizeof *c);
    *c = probe;
    c->alloc = functions->allocateMemory;
    c->free_memory = functions->freeMemory;
    c->log_calls = (loggingOn != fmi2False);
    c->mode = MODE_INSTANTIATED;
    values_default(&c->val);
    return c;
}

void fmi2FreeInstance(fmi2Component comp) {
    fmu_instance *c = comp;
    if (c != NULL) {
        c->free_memory(c);
    }
}

fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    fmu_instance *c = comp;
    (void)toleranceDefined;
    (void)tolerance;
    if (c == NULL || !allowed(c, M_INST, "fmi2SetupExperiment")) {
        return fmi2Error;
    }
    if (!finite(startTime) || (stopTimeDefined != fmi2False &&
                               !(finite(stopTime) && stopTime > startTime))) {
        return FAIL(c, "fmi2SetupExperiment: start %g s, stop %g s: expected a finite start "
                       "and a later stop", startTime, stopTime);
    }
    c->t0 = startTime;
    c->stop_defined = (stopTimeDefined != fmi2False);
    c->stop = stopTime;
    c->sim.built = false;
    return fmi2OK;
}

/* A change of mode, from one of the modes allowed; the step mode needs the run built. */
static fmi2Status transition(fmi2Component comp, unsigned from, fmu_mode to, const char *call) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, from, call)) {
        return fmi2Error;
    }
    if (to == MODE_STEP && ensure_built(c) != fmi2OK) {
        return fmi2Error;
    }
    c->mode = to;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component comp) {
    return transition(comp, M_INST, MODE_INIT, "fmi2EnterInitializationMode");
}

fmi2Status fmi2ExitInitializationMode(fmi2Component comp) {
    return transition(comp, M_INIT, MODE_STEP, "fmi2ExitInitializationMode");
}

fmi2Status fmi2Terminate(fmi2Component comp) {
    return transition(comp, M_STEP, MODE_TERMINATED, "fmi2Terminate");
}

fmi2Status fmi2Reset(fmi2Component comp) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_ANY, "fmi2Reset")) {
        return fmi2Error;
    }
    c->mode = MODE_INSTANTIATED;
    c->t0 = 0.0;
    c->stop_defined = false;
    values_default(&c->val);
    c->sim.built = false;
    return fmi2OK;
}

/* ---- Get and set ------------------------------------------------------------- */

#define M_VALUES (M_INST | M_INIT | M_STEP | M_TERM | M_ERR)

fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_VALUES, "fmi2GetReal")) {
        return fmi2Error;
    }
    for (size_t k = 0; k < nvr; k++) {
        if (get_real(c, vr[k], &value[k]) != fmi2OK) {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_INST | M_INIT | M_STEP, "fmi2SetReal")) {
        return fmi2Error;
    }
    for (size_t k = 0; k < nvr; k++) {
        if (set_real(c, vr[k], value[k]) != fmi2OK) {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

/* The number of items of each enumeration (fmu_model.c). */
static const int enum_items[N_ENUMS] = {3, 4, 3, 2, 2};

fmi2Status fmi2GetInteger(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_VALUES, "fmi2GetInteger")) {
        return fmi2Error;
    }
    for (size_t k = 0; k < nvr; k++) {
        if (vr[k] >= FMU_VR_INVERTER && vr[k] < FMU_VR_INVERTER + N_ENUMS) {
            value[k] = c->val.enums[vr[k] - FMU_VR_INVERTER];
        } else if (vr[k] == FMU_VR_AUTOPILOT) {
            value[k] = c->val.autopilot;
        } else if (vr[k] == FMU_VR_TRIP && c->mode != MODE_INSTANTIATED) {
            if (ensure_built(c) != fmi2OK) {
                return fmi2Error;
            }
            value[k] = (fmi2Integer)c->sim.rec.trip;
        } else {
            return FAIL(c, "fmi2GetInteger: value reference %u is not an Integer or "
                           "Enumeration variable here", vr[k]);
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_INST | M_INIT | M_STEP, "fmi2SetInteger")) {
        return fmi2Error;
    }
    for (size_t k = 0; k < nvr; k++) {
        if (vr[k] == FMU_VR_AUTOPILOT) {
            if (value[k] < 0 || value[k] > 3) {
                return FAIL(c, "fmi2SetInteger: autopilot = %d: expected 0 (none), 1 (heading), "
                               "2 (depth) or 3 (both)", value[k]);
            }
            c->val.autopilot = value[k];
            changed(c);
            continue;
        }
        if (c->mode == MODE_STEP) {
            return FAIL(c, "fmi2SetInteger: value reference %u is a fixed parameter: set it "
                           "before fmi2ExitInitializationMode", vr[k]);
        }
        if (!(vr[k] >= FMU_VR_INVERTER && vr[k] < FMU_VR_INVERTER + N_ENUMS)) {
            return FAIL(c, "fmi2SetInteger: value reference %u is not an Enumeration "
                           "parameter", vr[k]);
        }
        int i = (int)(vr[k] - FMU_VR_INVERTER);
        if (value[k] < 0 || value[k] >= enum_items[i]) {
            return FAIL(c, "fmi2SetInteger: value reference %u: %d is not an item of its "
                           "enumeration (0 .. %d)", vr[k], value[k], enum_items[i] - 1);
        }
        c->val.enums[i] = value[k];
        changed(c);
    }
    return fmi2OK;
}

/* Get and set calls of a type the FMU has no variable of: only empty lists pass. */
static fmi2Status no_such(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          const char *call, const char *why) {
    if (comp == NULL) {
        return fmi2Error;
    }
    return nvr == 0u ? fmi2OK
                     : FAIL((fmu_instance *)comp, "%s: value reference %u: %s", call, vr[0], why);
}

/* A call of a capability the FMU declares it has not: fmi2Error and why. */
static fmi2Status refuse(fmi2Component comp, const char *call, const char *why) {
    return comp == NULL ? fmi2Error : FAIL((fmu_instance *)comp, "%s: %s", call, why);
}

fmi2Status fmi2GetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) {
    (void)value;
    return no_such(comp, vr, nvr, "fmi2GetBoolean", "this FMU has no Boolean variables");
}

fmi2Status fmi2SetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[]) {
    (void)value;
    return no_such(comp, vr, nvr, "fmi2SetBoolean", "this FMU has no Boolean variables");
}

fmi2Status fmi2GetString(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) {
    fmu_instance *c = comp;
    if (c == NULL || !allowed(c, M_VALUES, "fmi2GetString")) {
        return fmi2Error;
    }
    for (size_t k = 0; k < nvr; k++) {
        if (vr[k] != FMU_VR_BUILD) {
            return FAIL(c, "fmi2GetString: value reference %u is not a String variable", vr[k]);
        }
        value[k] = fmu_build_name;
    }
    return fmi2OK;
}

fmi2Status fmi2SetString(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) {
    (void)value;
    return no_such(comp, vr, nvr, "fmi2SetString", "the only String variable is a constant");
}

/* ---- FMU state ------------------------------------------------------------------ */

fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *state) {
    fmu_instance *c = comp;
    if (c == NULL || state == NULL || !allowed(c, M_INST | M_INIT | M_STEP | M_TERM,
                                               "fmi2GetFMUstate")) {
        return fmi2Error;
    }
    fmu_saved *s = *state;
    if (s == NULL) {
        s = c->alloc(1u, sizeof *s);
        if (s == NULL) {
            return FAIL(c, "fmi2GetFMUstate: no memory for a state (%zu bytes)", sizeof *s);
        }
    } else if (s->owner != c) {
        return FAIL(c, "fmi2GetFMUstate: the state to overwrite belongs to another instance");
    }
    s->owner = c;
    s->mode = c->mode;
    s->val = c->val;
    memcpy(&s->sim, &c->sim, sizeof s->sim);
    *state = s;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate state) {
    fmu_instance *c = comp;
    const fmu_saved *s = state;
    if (c == NULL || !allowed(c, M_INST | M_INIT | M_STEP | M_TERM | M_ERR, "fmi2SetFMUstate")) {
        return fmi2Error;
    }
    if (s == NULL || s->owner != c) {
        return FAIL(c, "fmi2SetFMUstate: the state is not one of this instance's (a state "
                       "holds addresses inside its instance)");
    }
    c->mode = s->mode;
    c->val = s->val;
    memcpy(&c->sim, &s->sim, sizeof c->sim);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate *state) {
    fmu_instance *c = comp;
    if (c == NULL || state == NULL) {
        return fmi2Error;
    }
    if (*state != NULL) {
        if (((const fmu_saved *)*state)->owner != c) {
            return FAIL(c, "fmi2FreeFMUstate: the state belongs to another instance");
        }
        c->free_memory(*state);
        *state = NULL;
    }
    return fmi2OK;
}

#define NO_SERIAL "canSerializeFMUstate is false: a state holds addresses inside its instance"

fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate state, size_t *size) {
    (void)state;
    (void)size;
    return refuse(comp, "fmi2SerializedFMUstateSize", NO_SERIAL);
}

fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate state, fmi2Byte bytes[],
                                 size_t size) {
    (void)state;
    (void)bytes;
    (void)size;
    return refuse(comp, "fmi2SerializeFMUstate", NO_SERIAL);
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte bytes[], size_t size,
                                   fmi2FMUstate *state) {
    (void)bytes;
    (void)size;
    (void)state;
    return refuse(comp, "fmi2DeSerializeFMUstate", NO_SERIAL);
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component comp, const fmi2ValueReference u[],
                                        size_t nu, const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real dz[], fmi2Real du[]) {
    (void)u;
    (void)nu;
    (void)z;
    (void)nz;
    (void)dz;
    (void)du;
    return refuse(comp, "fmi2GetDirectionalDerivative", "providesDirectionalDerivative is false");
}

/* ---- Co-simulation ------------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component comp, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[]) {
    (void)order;
    (void)value;
    return no_such(comp, vr, nvr, "fmi2SetRealInputDerivatives", "canInterpolateInputs is false");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component comp, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[]) {
    (void)order;
    (void)value;
    return no_such(comp, vr, nvr, "fmi2GetRealOutputDerivatives",
                   "maxOutputDerivativeOrder is 0");
}

/*
 * Runs the executive to the end of slow frame `target`: the fast ticks in
 * runs up to the last before its boundary, then tick by tick through the
 * boundary's tasks to its slow step, leaving the controller task released
 * with it for the next step (see the file's header).
 */
static void run_to(fmu_sim *s, uint32_t target) {
    exec *e = &s->e;
    if (e->cfg.plant == EXEC_PLANT_VESSEL) {
        while (e->state == EXEC_RUNNING && e->frame < target) {
            exec_desk_step(e);
        }
        return;
    }
    uint64_t boundary = (uint64_t)target * e->cfg.fast_per_medium * e->cfg.medium_per_slow;
    while (e->state == EXEC_RUNNING && exec_fast_steps(e) + 1u < boundary) {
        uint64_t left = boundary - 1u - exec_fast_steps(e);
        (void)exec_desk_run(e, left < UINT32_MAX ? (uint32_t)left : UINT32_MAX);
    }
    while (e->state == EXEC_RUNNING && e->frame < target) {
        if (exec_fast_tick(e) && exec_medium_tick(e) && !exec_slow_pending(e)) {
            exec_control_tick(e);
        }
        if (exec_slow_pending(e)) {
            s->steer_ap = e->player.ap;
            s->steer_rudder_rad = e->cmd.rudder_rad;
            s->steer_stern_rad = e->cmd.stern_rad;
            exec_slow_step(e);
        }
    }
}

/* Whether an input differs from the one in force (bit for bit: a NaN is refused when set). */
static bool differs(const double *a, const double *b) { return memcmp(a, b, sizeof *a) != 0; }

/*
 * The inputs set at the boundary just reached, as scenario events at that
 * time: the steering's inputs as they were before the boundary's steering
 * step, then the commands that changed (the fins, the shaft speed, the
 * buoyancy; a fin under a hold ignores its input), the holds that began,
 * ended (the fin's input takes it back) or got a new set point, and then
 * the steering step again.
 */
static void apply_inputs(fmu_sim *s, const fmu_values *v) {
    exec *e = &s->e;
    e->player.ap = s->steer_ap;
    e->cmd.rudder_rad = s->steer_rudder_rad;
    e->cmd.stern_rad = s->steer_stern_rad;
    for (int i = 0; i < FMU_N_INPUTS; i++) {
        bool held = (i == SCN_RUDDER || i == SCN_STERN) && (v->autopilot & (1 << i)) != 0;
        if (!held && differs(&v->u[i], &s->applied[i])) {
            exec_command(e, (scenario_command)i, v->u[i]);
            s->applied[i] = v->u[i];
        }
    }
    for (int k = 0; k < FMU_N_SET; k++) {
        bool on = (v->autopilot & (1 << k)) != 0;
        bool was = (s->applied_ap & (1 << k)) != 0;
        if (on && (!was || differs(&v->set[k], &s->applied_set[k]))) {
            exec_command(e, (scenario_command)(SCN_HEADING + k), v->set[k]);
        } else if (!on && was) {
            exec_command(e, (scenario_command)k, v->u[k]); /* the rudder, the stern plane */
            s->applied[k] = v->u[k];
        }
        s->applied_set[k] = v->set[k];
    }
    s->applied_ap = v->autopilot;
    player_steer(&e->player, (double)e->frame * e->slow_s, e->x, e->report_s, &e->cmd);
}

static bool inputs_changed(const fmu_sim *s, const fmu_values *v) {
    bool any = (v->autopilot != s->applied_ap);
    for (int i = 0; i < FMU_N_INPUTS; i++) {
        any = any || differs(&v->u[i], &s->applied[i]);
    }
    for (int k = 0; k < FMU_N_SET; k++) {
        any = any || differs(&v->set[k], &s->applied_set[k]);
    }
    return any;
}

fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real t, fmi2Real h, fmi2Boolean noSetPrior) {
    fmu_instance *c = comp;
    (void)noSetPrior;
    if (c == NULL || !allowed(c, M_STEP, "fmi2DoStep")) {
        return fmi2Error;
    }
    fmu_sim *s = &c->sim;
    exec *e = &s->e;
    const double frame = e->slow_s;
    double now = c->t0 + (double)e->frame * frame;
    if (!(fabs(t - now) <= FMU_TIME_TOL * frame)) {
        c->mode = MODE_ERROR;
        return FAIL(c, "fmi2DoStep: communication point %.17g s is not the FMU's time %.17g s",
                    t, now);
    }
    double k = floor(h / frame + 0.5);
    if (!(h > 0.0) || !(fabs(h - k * frame) <= FMU_TIME_TOL * frame) || k < 1.0) {
        c->mode = MODE_ERROR;
        return FAIL(c, "fmi2DoStep: communication step %.17g s is not a whole number of slow "
                       "frames (%.17g s)", h, frame);
    }
    if ((double)e->frame + k > (double)e->frames || e->state != EXEC_RUNNING) {
        c->mode = MODE_ERROR;
        return FAIL(c, "fmi2DoStep: the step to %.17g s ends past the stop time %.17g s", t + h,
                    c->t0 + (double)e->frames * frame);
    }
    if (inputs_changed(s, &c->val)) {
        if (e->frame == 0u) {
            /* Still at the start: the run of the values now set, from their start values. */
            if (build(c) != fmi2OK) {
                c->mode = MODE_ERROR;
                return fmi2Error;
            }
        } else {
            apply_inputs(s, &c->val);
        }
    }
    exec_control_tick(e); /* the last boundary's controller task, with the new command */
    run_to(s, e->frame + (uint32_t)k);
    (void)exec_report_take(e, &s->rec);
    if (e->state == EXEC_STOP_OVERRUN) {
        c->mode = MODE_ERROR;
        return FAIL(c, "fmi2DoStep: a task overran its frame at %.17g s", c->t0 + s->rec.t_s);
    }
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component comp) {
    return refuse(comp, "fmi2CancelStep", "fmi2DoStep never returns fmi2Pending");
}

fmi2Status fmi2GetStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Status *value) {
    (void)s;
    (void)value;
    return refuse(comp, "fmi2GetStatus", "fmi2DoStep never returns fmi2Pending");
}

fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real *value) {
    fmu_instance *c = comp;
    if (c == NULL || value == NULL) {
        return fmi2Error;
    }
    if (s != fmi2LastSuccessfulTime || !c->sim.built) {
        return FAIL(c, "fmi2GetRealStatus: only fmi2LastSuccessfulTime, once initialised");
    }
    *value = c->t0 + (double)c->sim.e.frame * c->sim.e.slow_s;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component comp, const fmi2StatusKind s,
                                fmi2Integer *value) {
    (void)s;
    (void)value;
    return refuse(comp, "fmi2GetIntegerStatus", "no such status");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s,
                                fmi2Boolean *value) {
    fmu_instance *c = comp;
    if (c == NULL || value == NULL) {
        return fmi2Error;
    }
    if (s != fmi2Terminated || !c->sim.built) {
        return FAIL(c, "fmi2GetBooleanStatus: only fmi2Terminated, once initialised");
    }
    *value = (c->sim.e.state != EXEC_RUNNING) ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component comp, const fmi2StatusKind s, fmi2String *value) {
    (void)s;
    (void)value;
    return refuse(comp, "fmi2GetStringStatus", "no such status");
}

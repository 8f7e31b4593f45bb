/*
 * The FMU's variables and its model description (see fmu_model.h).
 */
#include "fmu_model.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "uuv_config.h"

const char fmu_build_name[] = UUV_NUMERIC_NAME;

/* The unit of each vessel state (the reference layout's, vessel.h). */
static const char *const state_units[VESSEL_NSTATES] = {
    "m/s", "m/s", "m/s", "rad/s", "rad/s", "rad/s", "m", "m", "m",
    "rad", "rad", "rad", "rad", "rad", "rad", "rad", "rpm",
};

static const char *const state_text[VESSEL_NSTATES] = {
    "surge velocity (body)", "sway velocity (body)", "heave velocity (body)",
    "roll rate", "pitch rate", "yaw rate",
    "position North", "position East", "depth (positive down)",
    "roll angle", "pitch angle", "yaw angle (unwrapped)",
    "rudder angle, actual", "stern plane angle, actual", "port bow plane angle, actual",
    "starboard bow plane angle, actual", "propeller shaft speed",
};

static const char *const input_units[FMU_N_INPUTS] = {"rad", "rad", "rad", "rad", "rpm", "N"};
static const char *const input_names[FMU_N_INPUTS] = {
    "delta_r_cmd_rad", "delta_s_cmd_rad", "delta_bp_cmd_rad",
    "delta_bs_cmd_rad", "n_cmd_rpm",       "buoyancy_cmd_n",
};
static const char *const input_text[FMU_N_INPUTS] = {
    "rudder command (positive turns to port)", "stern plane command (positive dives)",
    "port bow plane command", "starboard bow plane command", "shaft speed command",
    "buoyancy adjustment B - W",
};

static const char *const drive_names[FMU_N_DRIVE] = {
    "te_nm", "i_rms_a", "v_dc_v", "i_batt_a", "soc", "m_index", "f_hz",
};
static const char *const drive_units[FMU_N_DRIVE] = {"N.m", "A", "V", "A", "1", "1", "Hz"};
static const char *const drive_text[FMU_N_DRIVE] = {
    "electromagnetic torque, mean over the slow frame",
    "rms motor phase current over the slow frame",
    "DC-link voltage, mean over the slow frame",
    "battery current, mean over the slow frame (positive discharging)",
    "battery state of charge",
    "modulation index, mean over the slow frame",
    "stator frequency, mean over the slow frame",
};

static const char *const param_names[5] = {"inverter", "coupling_down", "coupling_up",
                                           "propulsion", "plant"};
static const char *const param_types[5] = {"Inverter", "CouplingDown", "CouplingUp",
                                           "Propulsion", "Plant"};
static const char *const param_text[5] = {
    "inverter layer", "slow-to-fast coupling", "fast-to-slow coupling",
    "propeller thrust law", "plant: the vessel alone, or battery, drive and vessel",
};

/* The enumerations: type name, then its items in value order (0, 1, ...). */
typedef struct {
    const char *type;
    const char *items[4];
    const char *text[4];
} fmu_enum;

static const fmu_enum enums[5] = {
    {"Inverter", {"switching", "averaged", "event", NULL},
     {"six switches at the 2 us step", "averaged legs at the 800 us controller frame",
      "switching instants located inside the step", NULL}},
    {"CouplingDown", {"zoh", "foh", "deriv", "stagger"},
     {"zero-order hold", "first-order hold", "derivative-assisted extrapolation",
      "staggered: the slower segment half a frame later"}},
    {"CouplingUp", {"avg", "filter", "sample", NULL},
     {"average over the frame", "first-order filter", "the value at the boundary", NULL}},
    {"Propulsion", {"mss", "paper", NULL, NULL},
     {"the MSS model's law", "the paper's bilinear thruster", NULL, NULL}},
    {"Plant", {"vessel", "full", NULL, NULL},
     {"the vessel alone, shaft speed through its lag", "battery, drive and vessel", NULL, NULL}},
};

/* Defaults of the parameters: exec_config_default()'s. */
static double param_start(int k) {
    exec_config c;
    exec_config_default(&c);
    const unsigned v[5] = {(unsigned)c.inverter, (unsigned)c.down, (unsigned)c.up,
                           (unsigned)c.propulsion, (unsigned)c.plant};
    return (double)v[k];
}

static const char *const set_names[FMU_N_SET] = {"heading_cmd_rad", "depth_cmd_m"};
static const char *const set_units[FMU_N_SET] = {"rad", "m"};
static const char *const set_text[FMU_N_SET] = {
    "heading the autopilot holds with the rudder (while autopilot bit 0 is set)",
    "depth the autopilot holds with the stern plane (while autopilot bit 1 is set)",
};

enum {
    K_INPUT = 0,
    K_SET = K_INPUT + FMU_N_INPUTS,
    K_AP = K_SET + FMU_N_SET,
    K_STATE = K_AP + 1,
    K_DRIVE = K_STATE + VESSEL_NSTATES,
    K_TRIP = K_DRIVE + FMU_N_DRIVE,
    K_PARAM = K_TRIP + 1,
    K_SOC0 = K_PARAM + 5,
    K_INIT = K_SOC0 + 1,
    K_BUILD = K_INIT + FMU_N_INIT,
    K_FRAME,
    K_COUNT
};

size_t fmu_var_count(void) { return (size_t)K_COUNT; }

/* The initial-state parameters: "init_" and the state's name (vessel.c). */
static const char *const init_names[FMU_N_INIT] = {
    "init_u_mps", "init_v_mps", "init_w_mps", "init_p_radps", "init_q_radps", "init_r_radps",
    "init_x_m",   "init_y_m",   "init_z_m",   "init_phi_rad", "init_theta_rad", "init_psi_rad",
};

bool fmu_var_at(size_t k, fmu_var *v) {
    *v = (fmu_var){0};
    int i = (int)k;
    if (i < K_SET) {
        *v = (fmu_var){input_names[i], FMU_VR_INPUT + (unsigned)i, FMU_REAL, FMU_INPUT,
                       input_units[i], NULL, 0.0, input_text[i]};
    } else if (i < K_AP) {
        i -= K_SET;
        *v = (fmu_var){set_names[i], FMU_VR_HEADING + (unsigned)i, FMU_REAL, FMU_INPUT,
                       set_units[i], NULL, 0.0, set_text[i]};
    } else if (i == K_AP) {
        *v = (fmu_var){"autopilot", FMU_VR_AUTOPILOT, FMU_INTEGER, FMU_INPUT, NULL, NULL, 0.0,
                       "the holds on: 0 none, 1 heading, 2 depth, 3 both; a hold that ends "
                       "gives its fin back to its command input"};
    } else if (i < K_DRIVE) {
        i -= K_STATE;
        *v = (fmu_var){vessel_state_names[i], FMU_VR_STATE + (unsigned)i, FMU_REAL, FMU_OUTPUT,
                       state_units[i], NULL, 0.0, state_text[i]};
    } else if (i < K_TRIP) {
        i -= K_DRIVE;
        *v = (fmu_var){drive_names[i], FMU_VR_DRIVE + (unsigned)i, FMU_REAL, FMU_OUTPUT,
                       drive_units[i], NULL, 0.0, drive_text[i]};
    } else if (i == K_TRIP) {
        *v = (fmu_var){"trip", FMU_VR_TRIP, FMU_INTEGER, FMU_OUTPUT, NULL, NULL, 0.0,
                       "the drive's protection: 0 none, 1 leg short, 2 under-voltage, "
                       "3 phase loss"};
    } else if (i < K_SOC0) {
        i -= K_PARAM;
        *v = (fmu_var){param_names[i], FMU_VR_INVERTER + (unsigned)i, FMU_ENUM, FMU_PARAMETER,
                       NULL, param_types[i], param_start(i), param_text[i]};
    } else if (i == K_SOC0) {
        *v = (fmu_var){"soc0", FMU_VR_SOC0, FMU_REAL, FMU_PARAMETER, "1", NULL, 1.0,
                       "initial state of charge, (0, 1]"};
    } else if (i < K_BUILD) {
        i -= K_INIT;
        *v = (fmu_var){init_names[i], FMU_VR_INIT + (unsigned)i, FMU_REAL, FMU_PARAMETER,
                       state_units[i], NULL, 0.0, "initial value of the vessel state"};
    } else if (i == K_BUILD) {
        *v = (fmu_var){"build", FMU_VR_BUILD, FMU_STRING, FMU_CONSTANT, NULL, NULL, 0.0,
                       "numeric build of the drive (fixed or float; make fmu NUM=...)"};
    } else if (i == K_FRAME) {
        *v = (fmu_var){"slow_frame_s", FMU_VR_SLOW_FRAME, FMU_REAL, FMU_CONSTANT, "s", NULL,
                       FMU_SLOW_FRAME_S,
                       "slow frame: a communication step is a whole number of them"};
    } else {
        return false;
    }
    return true;
}

/* ---- modelDescription.xml ------------------------------------------------ */

static void putf(fmu_put_fn *put, void *ctx, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void putf(fmu_put_fn *put, void *ctx, const char *fmt, ...) {
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    put(ctx, line);
}

/* Unit definitions: name, then the SI base-unit exponents and factor. */
static void describe_units(fmu_put_fn *put, void *ctx) {
    static const struct {
        const char *name;
        const char *base;
    } units[] = {
        {"m/s", "m=\"1\" s=\"-1\""},
        {"rad/s", "s=\"-1\" rad=\"1\""},
        {"m", "m=\"1\""},
        {"rad", "rad=\"1\""},
        {"rpm", "s=\"-1\" rad=\"1\" factor=\"0.10471975511965977\""},
        {"N", "kg=\"1\" m=\"1\" s=\"-2\""},
        {"N.m", "kg=\"1\" m=\"2\" s=\"-2\""},
        {"A", "A=\"1\""},
        {"V", "kg=\"1\" m=\"2\" s=\"-3\" A=\"-1\""},
        {"Hz", "s=\"-1\""},
        {"s", "s=\"1\""},
        {"1", ""},
    };
    put(ctx, "  <UnitDefinitions>\n");
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++) {
        putf(put, ctx, "    <Unit name=\"%s\"><BaseUnit %s/></Unit>\n", units[k].name,
             units[k].base);
    }
    put(ctx, "  </UnitDefinitions>\n");
}

static void describe_types(fmu_put_fn *put, void *ctx) {
    put(ctx, "  <TypeDefinitions>\n");
    for (size_t k = 0; k < sizeof enums / sizeof enums[0]; k++) {
        putf(put, ctx, "    <SimpleType name=\"%s\">\n      <Enumeration>\n", enums[k].type);
        for (int i = 0; i < 4 && enums[k].items[i] != NULL; i++) {
            putf(put, ctx, "        <Item name=\"%s\" value=\"%d\" description=\"%s\"/>\n",
                 enums[k].items[i], i, enums[k].text[i]);
        }
        put(ctx, "      </Enumeration>\n    </SimpleType>\n");
    }
    put(ctx, "  </TypeDefinitions>\n");
}

static void describe_variable(fmu_put_fn *put, void *ctx, const fmu_var *v) {
    static const char *const causality[] = {"input", "output", "parameter", "local"};
    static const char *const type[] = {"Real", "Integer", "Enumeration", "String"};
    const char *variability = "continuous";
    const char *initial = "";
    if (v->causality == FMU_PARAMETER) {
        variability = "fixed";
        initial = " initial=\"exact\"";
    } else if (v->causality == FMU_CONSTANT) {
        variability = "constant";
        initial = " initial=\"exact\"";
    } else if (v->type != FMU_REAL) {
        variability = "discrete";
    }
    putf(put, ctx,
         "    <ScalarVariable name=\"%s\" valueReference=\"%u\" description=\"%s\"\n"
         "        causality=\"%s\" variability=\"%s\"%s>\n",
         v->name, v->vr, v->description, causality[v->causality], variability, initial);
    char attrs[160] = "";
    size_t n = 0;
    if (v->unit != NULL) {
        n += (size_t)snprintf(attrs + n, sizeof attrs - n, " unit=\"%s\"", v->unit);
    }
    if (v->type == FMU_ENUM) {
        n += (size_t)snprintf(attrs + n, sizeof attrs - n, " declaredType=\"%s\"", v->enum_type);
    }
    if (v->causality != FMU_OUTPUT) {
        if (v->type == FMU_STRING) {
            (void)snprintf(attrs + n, sizeof attrs - n, " start=\"%s\"", fmu_build_name);
        } else if (v->type == FMU_REAL) {
            (void)snprintf(attrs + n, sizeof attrs - n, " start=\"%.17g\"", v->start);
        } else {
            (void)snprintf(attrs + n, sizeof attrs - n, " start=\"%d\"", (int)v->start);
        }
    }
    putf(put, ctx, "      <%s%s/>\n    </ScalarVariable>\n", type[v->type], attrs);
}

void fmu_describe(fmu_put_fn *put, void *ctx, const char *guid, const char *const *sources) {
    put(ctx, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    putf(put, ctx,
         "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"uuvsim\" guid=\"%s\"\n"
         "    description=\"NPS AUV II with an all-electric drive, multi-rate "
         "(%s build of the drive)\"\n"
         "    generationTool=\"uuvsim make fmu\" variableNamingConvention=\"flat\" "
         "numberOfEventIndicators=\"0\">\n",
         guid, fmu_build_name);
    put(ctx, "  <CoSimulation modelIdentifier=\"uuvsim\" needsExecutionTool=\"false\"\n"
             "      canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\"\n"
             "      maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\"\n"
             "      canBeInstantiatedOnlyOncePerProcess=\"false\" "
             "canNotUseMemoryManagementFunctions=\"false\"\n"
             "      canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"false\"\n"
             "      providesDirectionalDerivative=\"false\">\n");
    if (sources != NULL && sources[0] != NULL) {
        put(ctx, "    <SourceFiles>\n");
        for (size_t k = 0; sources[k] != NULL; k++) {
            putf(put, ctx, "      <File name=\"%s\"/>\n", sources[k]);
        }
        put(ctx, "    </SourceFiles>\n");
    }
    put(ctx, "  </CoSimulation>\n");
    describe_units(put, ctx);
    describe_types(put, ctx);
    put(ctx, "  <LogCategories>\n"
             "    <Category name=\"logStatusError\" description=\"errors: refused calls and "
             "values, with the reason\"/>\n"
             "    <Category name=\"logStatusWarning\" description=\"warnings\"/>\n"
             "    <Category name=\"logCalls\" description=\"each call of the interface\"/>\n"
             "  </LogCategories>\n");
    putf(put, ctx, "  <DefaultExperiment startTime=\"0\" stopTime=\"240\" stepSize=\"%.17g\"/>\n",
         FMU_SLOW_FRAME_S);
    put(ctx, "  <ModelVariables>\n");
    fmu_var v;
    for (size_t k = 0; fmu_var_at(k, &v); k++) {
        putf(put, ctx, "    <!-- %zu -->\n", k + 1u);
        describe_variable(put, ctx, &v);
    }
    put(ctx, "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    for (size_t k = 0; fmu_var_at(k, &v); k++) {
        if (v.causality == FMU_OUTPUT) {
            putf(put, ctx, "      <Unknown index=\"%zu\"/>\n", k + 1u);
        }
    }
    put(ctx, "    </Outputs>\n    <InitialUnknowns>\n");
    for (size_t k = 0; fmu_var_at(k, &v); k++) {
        if (v.causality == FMU_OUTPUT) {
            putf(put, ctx, "      <Unknown index=\"%zu\"/>\n", k + 1u);
        }
    }
    put(ctx, "    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
}

/* ---- GUID ------------------------------------------------------------------ */

/*
 * Two FNV-1a hashes (different offsets) of the description without its GUID
 * and its list of source files (which do not change the interface).
 */
typedef struct {
    uint64_t h[2];
} guid_hash;

static void hash_put(void *ctx, const char *text) {
    guid_hash *g = ctx;
    for (const unsigned char *p = (const unsigned char *)text; *p != 0u; p++) {
        for (int k = 0; k < 2; k++) {
            g->h[k] = (g->h[k] ^ *p) * 0x100000001b3ull;
        }
    }
}

void fmu_guid(char guid[FMU_GUID_LEN]) {
    guid_hash g = {{0xcbf29ce484222325ull, 0x84222325cbf29ce4ull}};
    fmu_describe(hash_put, &g, "", NULL);
    (void)snprintf(guid, FMU_GUID_LEN, "{%016llx%016llx}", (unsigned long long)g.h[0],
                   (unsigned long long)g.h[1]);
}

/*
 * The FMU's variables, in one table: their value references, names,
 * types, causalities and units. The FMU (fmu.c) reads and writes them by
 * value reference; the model description (modelDescription.xml) is written
 * from the same table (fmu_describe()), and its GUID is a hash of that
 * text, so that the binary and the description it came with always agree.
 */
#ifndef UUV_FMU_MODEL_H
#define UUV_FMU_MODEL_H

#include <stdbool.h>
#include <stddef.h>

#include "executive.h"

/* Value references (docs/cosimulation.md lists them). */
enum {
    /* Inputs, the scenario's commands: 1 + scenario_command (rudder .. buoyancy). */
    FMU_VR_INPUT = 1,
    FMU_N_INPUTS = SCN_BUOYANCY + 1,
    /* The autopilots' inputs: the set points, and which hold is on (Integer: bit 0 the
     * heading hold on the rudder, bit 1 the depth hold on the stern plane). */
    FMU_VR_HEADING = FMU_VR_INPUT + SCN_HEADING,
    FMU_VR_DEPTH = FMU_VR_INPUT + SCN_DEPTH,
    FMU_VR_AUTOPILOT = FMU_VR_INPUT + SCN_AUTOPILOT,
    FMU_N_SET = 2,
    /* Outputs: the record's 17 vessel states, then the drive's means. */
    FMU_VR_STATE = 100,
    FMU_VR_DRIVE = FMU_VR_STATE + VESSEL_NSTATES,
    FMU_N_DRIVE = 7, /* te, i_rms, v_dc_v, i_batt, soc, m_index, f_hz */
    FMU_VR_TRIP = 200,
    /* Parameters (fixed: set before the end of initialisation). */
    FMU_VR_INVERTER = 300,
    FMU_VR_DOWN,
    FMU_VR_UP,
    FMU_VR_PROPULSION,
    FMU_VR_PLANT,
    FMU_VR_SOC0 = 310,
    FMU_VR_INIT = 320, /* 320 .. 331: the initial values of the first 12 vessel states */
    FMU_N_INIT = 12,
    /* Constants. */
    FMU_VR_BUILD = 400,
    FMU_VR_SLOW_FRAME = 401
};

/* The slow frame [s]: a communication step is a whole number of them. */
#define FMU_SLOW_FRAME_S 0.1

typedef enum { FMU_REAL, FMU_INTEGER, FMU_ENUM, FMU_STRING } fmu_type;

typedef enum { FMU_INPUT, FMU_OUTPUT, FMU_PARAMETER, FMU_CONSTANT } fmu_causality;

typedef struct {
    const char *name;
    unsigned vr;
    fmu_type type;
    fmu_causality causality;
    const char *unit;        /* NULL: none */
    const char *enum_type;   /* FMU_ENUM: the declared type */
    double start;            /* inputs, parameters and constants */
    const char *description;
} fmu_var;

/* The number of variables, and the k-th (false past the end). */
size_t fmu_var_count(void);
bool fmu_var_at(size_t k, fmu_var *v);

/* The numeric build's name ("fixed" or "float"). */
extern const char fmu_build_name[];

/*
 * Writes modelDescription.xml piecewise through put(): guid is its GUID,
 * sources (NULL-terminated, or NULL) the C files of sources/ it lists.
 */
typedef void fmu_put_fn(void *ctx, const char *text);
void fmu_describe(fmu_put_fn *put, void *ctx, const char *guid, const char *const *sources);

/* The GUID of this build's description, "{...}" (FMU_GUID_LEN bytes with the NUL). */
#define FMU_GUID_LEN 36u
void fmu_guid(char guid[FMU_GUID_LEN]);

#endif /* UUV_FMU_MODEL_H */

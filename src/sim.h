/*
 * The simulation executive: owns the model instances and advances them
 * frame by frame from a scenario. This first version runs the slow segment
 * (the vessel, shaft speed through its lag); the electric drive joins it at
 * the fast rates in the full plant.
 *
 * A frame k starts at t_k = k * slow_frame_s. At its start the scenario's
 * commands due by t_k are applied (and the zig-zag rule decides the rudder
 * from the heading); sim_frame() then describes the state at t_k and the
 * commands held during the step that starts there, which is the layout of
 * the reference trajectories; sim_step() integrates to t_{k+1}.
 */
#ifndef UUV_SIM_H
#define UUV_SIM_H

#include <stdbool.h>
#include <stdint.h>

#include "manoeuvre.h"
#include "models/vessel.h"
#include "scenario.h"

typedef enum {
    SIM_PLANT_VESSEL = 0, /* vessel alone, shaft speed commanded through the lag */
    SIM_PLANT_FULL        /* battery, drive and vessel (not in this version) */
} sim_plant;

#define SIM_NCMD 5 /* rudder, stern, bow_port, bow_stbd [rad], n [rpm] */

typedef struct {
    sim_plant plant;
    vessel_propulsion propulsion;
    double slow_frame_s; /* [s] */
    double duration_s;   /* [s]; 0: the scenario's */
} sim_config;

/* What one slow frame reports (the telemetry record). */
typedef struct {
    uint32_t index;              /* frame number k */
    double t_s;                  /* [s] k * slow_frame_s */
    double x[VESSEL_NSTATES];    /* vessel state at t_s */
    double cmd[SIM_NCMD];        /* commands held over the step from t_s */
} sim_frame;

typedef enum {
    SIM_OK = 0,
    SIM_ERR_CONFIG,   /* a configuration value is out of range */
    SIM_ERR_PLANT,    /* the plant is not available in this build */
    SIM_ERR_MODEL     /* a model refused its parameters */
} sim_status;

typedef struct {
    sim_config cfg;
    const scenario *scn;
    vessel_model vessel;
    double x[VESSEL_NSTATES];
    vessel_cmd cmd;
    uint32_t frame;        /* k */
    uint32_t frames;       /* frames in the run: duration / slow frame */
    size_t next_event;
    double zz_rudder;      /* [rad] current zig-zag rudder, 0 before it starts */
    double zz_psi0;        /* [rad] heading when the zig-zag started */
    manoeuvre man;
    bool frame_ready;      /* commands of frame k applied */
} sim;

extern const char *const sim_command_names[SIM_NCMD];

void sim_config_default(sim_config *cfg);

sim_status sim_init(sim *s, const sim_config *cfg, const scenario *scn);

/* True when the current frame is the run's last (its state ends the run). */
bool sim_done(const sim *s);

/* Applies the commands due at the current frame and describes it. */
void sim_frame_get(sim *s, sim_frame *out);

/* Advances one slow frame. */
void sim_step(sim *s);

const manoeuvre_result *sim_manoeuvre(const sim *s);

#endif /* UUV_SIM_H */

/*
 * A parameter set: every model's parameters for one run, by pointer to the
 * models' own parameter structs (each model keeps its one home for its
 * parameters, units and sources). The executive and the drive segment take
 * their models' parameters from the set in exec_config.params; NULL means
 * uuv_params_default, the compiled-in set. The desk simulator loads sets
 * from files (ports/linux/params.c); a firmware image links a set the desk
 * generated as constant data (make firmware PARAMS=FILE).
 *
 * The controller's machine constants are the motor's (the set's loader
 * copies them); its step and PWM step are set from the frames by the drive.
 */
#ifndef UUV_PARAMS_H
#define UUV_PARAMS_H

#include "autopilot.h"
#include "models/battery/battery.h"
#include "models/drive/control/drive_control.h"
#include "models/drive/inverter/power_stage.h"
#include "models/drive/motor/induction_motor.h"
#include "models/drive/pwm/pwm.h"
#include "models/propeller/propeller.h"
#include "models/vessel/vessel_params.h"

typedef struct {
    const vessel_params *vessel;
    const autopilot_params *autopilot;  /* heading and depth autopilots */
    const propeller_params *propeller;
    const battery_params *battery;       /* its frame_s is replaced by the slow frame */
    const power_stage_params *stage;     /* DC link and LC filter */
    const pwm_params *pwm;               /* carrier and phases (the edge mode is the inverter's) */
    const induction_motor_params *motor;
    const drive_control_params *control; /* step_s and pwm_step_s come from the frames */
} uuv_params;

/* The 15 kW drive, the 144s2p battery and the NPS AUV II. */
extern const uuv_params uuv_params_default;

#endif /* UUV_PARAMS_H */

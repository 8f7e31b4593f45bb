/* The firmware's parameter set when the build names none (fw_params.h). */
#include "fw_params.h"

const uuv_params *const fw_params = &uuv_params_default;

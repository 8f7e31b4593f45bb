/*
 * The parameter set a firmware image runs (src/params.h): the default one
 * (fw_params_default.c), or one the desk program wrote as constant data
 * (uuvsim params --params FILE --emit-c; make firmware PARAMS=FILE). The
 * target has no parser: the set is part of the image.
 */
#ifndef UUV_FW_PARAMS_H
#define UUV_FW_PARAMS_H

#include "params.h"

extern const uuv_params *const fw_params;

#endif /* UUV_FW_PARAMS_H */

/*
 * What the Linux port adds to the HAL contract: where telemetry goes and
 * where scenario input comes from. Only host programs call these.
 */
#ifndef UUV_HAL_LINUX_H
#define UUV_HAL_LINUX_H

#include <stdio.h>

#include "hal/hal.h"

void hal_linux_set_telemetry(FILE *out);
void hal_linux_set_input(FILE *in);

#endif /* UUV_HAL_LINUX_H */

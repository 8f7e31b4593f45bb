/*
 * The fixed build's real-time fast step in Thumb-2 (fast_kernel_v7m.S),
 * for drive_use_fast_kernel(): bit for bit what the C's real-time step
 * computes, in fewer instructions. Linked into the fixed images when
 * FW_FAST_KERNEL is 1 (the Makefile's default for them).
 */
#ifndef UUV_FAST_KERNEL_H
#define UUV_FAST_KERNEL_H

#include "drive_segment.h"

void drive_fast_kernel_v7m(drive_segment *d);

#endif /* UUV_FAST_KERNEL_H */

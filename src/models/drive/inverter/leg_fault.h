/*
 * What the drive's faults and its protection leave of an inverter leg over
 * one step, on every layer that has switches: the switching inverter (the
 * real-time modulator's duties) and the event inverter (the general
 * modulator's) take the same decision here, then each applies it to its
 * own duties. The averaged layer has no switches to fault or to block.
 *
 * Leg x (0..2 for a, b, c) carries i_L,x from the inverter towards the
 * filter; its sign at the step's start says which diode conducts when the
 * leg's switch does not:
 *   - gates blocked (the protection tripped): both switches off, the pole
 *     sits where the current's diode puts it, high (the upper diode) while
 *     i_L,x < 0, low (the lower diode) otherwise;
 *   - the upper switch stuck open (switch_open 2x + 1, drive_faults): low
 *     while i_L,x >= 0, the lower diode carrying the current; while
 *     i_L,x < 0 the upper diode conducts wherever the upper switch would,
 *     so the modulator's duty holds;
 *   - the lower switch stuck open (2x + 2): high while i_L,x < 0, the
 *     modulator's duty otherwise.
 * No arithmetic: the twins share it as it is.
 */
#ifndef UUV_LEG_FAULT_H
#define UUV_LEG_FAULT_H

#include <stdbool.h>
#include <stdint.h>

typedef enum {
    LEG_MODULATED = 0, /* the modulator's duty over the step */
    LEG_LOW,           /* the lower rail over the whole step (duty 0) */
    LEG_HIGH           /* the upper rail over the whole step (duty 1) */
} leg_state;

/* Leg x's state with the gates blocked or not, switch_open as drive_faults has it. */
static inline leg_state leg_fault_state(bool blocked, uint8_t switch_open, uint32_t x,
                                        bool i_negative) {
    if (blocked) {
        return i_negative ? LEG_HIGH : LEG_LOW;
    }
    if (switch_open == 2u * x + 1u && !i_negative) {
        return LEG_LOW;
    }
    if (switch_open == 2u * x + 2u && i_negative) {
        return LEG_HIGH;
    }
    return LEG_MODULATED;
}

#endif /* UUV_LEG_FAULT_H */

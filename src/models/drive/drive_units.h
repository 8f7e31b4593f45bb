/*
 * Per-unit bases of the electric drive: the one place that says what 1.0
 * (Q15 full scale, 32768 LSB) means for each kind of signal that crosses
 * between the drive models. The fixed-point build represents a quantity x
 * as round(x / BASE * 32768) in Q15, or * 2^31 in Q31; the float build uses
 * SI units directly. Each base is chosen above the worst case of its signal
 * (start from rest at full load, 1500 rpm, battery from full to cut-off;
 * docs/drive.md gives the range analysis), with a power-of-two-friendly
 * value so that scalings stay exact shifts where possible.
 *
 * Models may keep internal states in other Q formats (documented in their
 * headers), but every signal in their input and output structs uses these
 * bases.
 */
#ifndef UUV_DRIVE_UNITS_H
#define UUV_DRIVE_UNITS_H

#define DRIVE_BASE_VOLTAGE_V 1024.0    /* [V] DC link, pole, phase and capacitor voltages */
#define DRIVE_BASE_CURRENT_A 256.0     /* [A] phase, filter, DC-link and battery currents */
#define DRIVE_BASE_SPEED_RADPS 512.0   /* [rad/s] electrical and mechanical angular speeds */
#define DRIVE_BASE_TORQUE_NM 512.0     /* [N m] electromagnetic and load torque */
#define DRIVE_BASE_FLUX_WB 4.0         /* [Wb] stator and rotor flux linkages */
#define DRIVE_BASE_FREQ_HZ 128.0       /* [Hz] stator frequency command */

/* The same bases in single precision, for conversions in the float build. */
#define DRIVE_BASE_VOLTAGE_F32 1024.0f
#define DRIVE_BASE_CURRENT_F32 256.0f
#define DRIVE_BASE_SPEED_F32 512.0f
#define DRIVE_BASE_TORQUE_F32 512.0f
#define DRIVE_BASE_FLUX_F32 4.0f
#define DRIVE_BASE_FREQ_F32 128.0f

#endif /* UUV_DRIVE_UNITS_H */

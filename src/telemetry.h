/*
 * Telemetry frames: how a target streams the executive's slow-rate records
 * to a host, which decodes them to the desk simulator's CSV. The same code
 * encodes on the target and decodes on the host, so the two cannot drift.
 *
 * A frame, every multi-byte field little-endian:
 *
 *   offset  size  field
 *   0       2     sync: 0xA5 0x5A
 *   2       1     type: TLM_START, TLM_RECORD or TLM_END
 *   3       2     payload length L (the type fixes it, see below)
 *   5       2     sequence number: 0 for the first frame, +1 per frame (mod 2^16)
 *   7       L     payload
 *   7 + L   4     CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of bytes 2 .. 6 + L
 *
 * Payloads (doubles as their IEEE-754 bit patterns, so a record decodes to
 * the very values the target computed):
 *   TLM_START   what the run is: build, plant, frames, duration, machine name;
 *   TLM_RECORD  one exec_frame: index (u32), then t_s, x[17], cmd[5], te_nm,
 *               i_rms_a, v_dc_v, i_batt_a, soc, m_index, f_hz (30 doubles);
 *   TLM_END     how the run ended: state, steps, overruns, energies, stack.
 * A stream is START, the records in order (index 0, 1, ...), END.
 *
 * The multi-party run's link (docs/cosimulation.md) uses the same frames:
 * the drive's side sends START, then at each slow boundary LINK_UP, and
 * END; the slow segment's side answers each LINK_UP with a LINK_DOWN.
 *   TLM_LINK_UP    slow frame number k (u32, 1 for the first frame), the
 *                  drive's measurements of frame k (drive_slow_meas: 18
 *                  doubles, saturations u32, trip u8 + 3 reserved) and the
 *                  controller's speed command at its end (a double);
 *   TLM_LINK_DOWN  k (u32), then exec_to_drive: the battery companion g, b,
 *                  the faults' dc_cap_frac, current_offset_a, load_factor
 *                  (5 doubles), switch_open, leg_short, phase_open,
 *                  faults new (1: apply this fault set), trip, state (u8
 *                  each) + 2 reserved.
 */
#ifndef UUV_TELEMETRY_H
#define UUV_TELEMETRY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "executive.h"

#define TLM_SYNC0 0xA5u
#define TLM_SYNC1 0x5Au
#define TLM_HEADER_BYTES 7u
#define TLM_CRC_BYTES 4u
#define TLM_MACHINE_CHARS 24u /* machine name field, NUL-padded */

#define TLM_START_PAYLOAD (4u + 5u * 4u + 8u + TLM_MACHINE_CHARS)
#define TLM_RECORD_PAYLOAD (4u + 30u * 8u + 2u * 4u)
#define TLM_END_PAYLOAD (4u + 4u * 8u + 5u * 4u + 2u * 8u + 4u)
#define TLM_LINK_UP_PAYLOAD (4u + (19u * 8u) + (2u * 4u))
#define TLM_LINK_DOWN_PAYLOAD (4u + (5u * 8u) + 8u)
#define TLM_FRAME_MAX (TLM_HEADER_BYTES + TLM_RECORD_PAYLOAD + TLM_CRC_BYTES)

#define TLM_VERSION 2u

typedef enum {
    TLM_START = 1,
    TLM_RECORD = 2,
    TLM_END = 3,
    TLM_LINK_UP = 4,  /* drive -> slow segment, multi-party run */
    TLM_LINK_DOWN = 5 /* slow segment -> drive, multi-party run */
} tlm_type;

/* What the run is. */
typedef struct {
    uint8_t version;            /* TLM_VERSION */
    uint8_t numeric;            /* UUV_NUMERIC of the target's build */
    uint8_t plant;              /* exec_plant */
    uint32_t fast_ns;           /* [ns] fast frame */
    uint32_t fast_per_medium;
    uint32_t medium_per_control;
    uint32_t medium_per_slow;
    uint32_t frames;            /* slow frames in the run */
    double duration_s;          /* [s] */
    char machine[TLM_MACHINE_CHARS]; /* NUL-terminated when shorter than the field */
} tlm_start;

/* How the run ended. */
typedef struct {
    uint8_t state;              /* exec_state */
    uint8_t exit_status;        /* the status the target exits with */
    uint64_t fast, medium, control, slow;  /* steps run */
    uint32_t overruns_fast;     /* the fast tick still pending at the end of its handler */
    uint32_t overruns_medium;   /* the motor task still busy at the next boundary */
    uint32_t overruns_control;  /* the controller task still busy when its result is due */
    uint32_t overruns_slow;     /* the slow step still pending at the next slow boundary */
    uint32_t saturations;
    double e_batt_j;            /* [J] */
    double e_mech_j;            /* [J] */
    uint32_t stack_used_bytes;  /* high-water mark of the stack, measured (0: unknown) */
} tlm_end;

/* The link's frames (multi-party run). */
typedef struct {
    uint32_t frame;        /* the slow frame measured, 1 for the first */
    drive_slow_meas meas;
    double speed_rpm;      /* [rpm] the controller's speed command at the frame's end */
} tlm_link_up;

typedef struct {
    uint32_t frame;        /* the slow frame whose step this answers */
    exec_to_drive down;    /* decoded: down.faults points at faults when new */
    drive_faults faults;
} tlm_link_down;

/*
 * Encoders: write one whole frame into buf (at least TLM_FRAME_MAX bytes)
 * and return its length. Total functions.
 */
size_t tlm_encode_start(uint8_t *buf, uint16_t seq, const tlm_start *s);
size_t tlm_encode_record(uint8_t *buf, uint16_t seq, const exec_frame *f);
size_t tlm_encode_end(uint8_t *buf, uint16_t seq, const tlm_end *e);
size_t tlm_encode_link_up(uint8_t *buf, uint16_t seq, const tlm_link_up *u);
size_t tlm_encode_link_down(uint8_t *buf, uint16_t seq, const tlm_link_down *d);

typedef enum {
    TLM_OK = 0,
    TLM_TRUNCATED,   /* the bytes end inside the frame */
    TLM_BAD_SYNC,    /* no sync bytes where a frame must start */
    TLM_BAD_TYPE,    /* an unknown frame type */
    TLM_BAD_LENGTH,  /* a payload length that does not match its type */
    TLM_BAD_CRC      /* the CRC does not match: the frame is corrupt */
} tlm_status;

/* The header and checks of the frame at buf[0 .. avail). */
typedef struct {
    uint8_t type;
    uint16_t seq;
    uint16_t payload_len;
    const uint8_t *payload;
    size_t frame_len;           /* header + payload + CRC */
} tlm_frame;

/*
 * Checks the frame that starts at buf (avail bytes available): sync, type,
 * the length its type requires, and the CRC. Fills *f on TLM_OK.
 */
tlm_status tlm_frame_check(const uint8_t *buf, size_t avail, tlm_frame *f);

/* Payload decoders for a frame that passed tlm_frame_check with that type. */
void tlm_decode_start(const tlm_frame *f, tlm_start *s);
void tlm_decode_record(const tlm_frame *f, exec_frame *r);
void tlm_decode_end(const tlm_frame *f, tlm_end *e);
void tlm_decode_link_up(const tlm_frame *f, tlm_link_up *u);
void tlm_decode_link_down(const tlm_frame *f, tlm_link_down *d);

/* A short description of a status, for messages. */
const char *tlm_status_text(tlm_status st);

/* CRC-32 (IEEE 802.3 reflected polynomial 0xEDB88320): crc32(0, ...) starts a new one. */
uint32_t tlm_crc32(uint32_t crc, const uint8_t *p, size_t n);

#endif /* UUV_TELEMETRY_H */

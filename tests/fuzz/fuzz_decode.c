/*
 * libFuzzer harness for the telemetry decoder (src/telemetry.c), the code the
 * host runs on a byte stream a target sent.
 *
 * The first input byte chooses how the rest is read:
 *   even: as a raw byte stream, scanned the way a host reads a serial line
 *         (check a frame at each position; on success decode it and skip
 *         it, otherwise skip one byte);
 *   odd:  as a list of frame bodies (type, sequence, payload) that the
 *         harness wraps in valid headers and CRCs, so that the payload
 *         decoders see arbitrary payloads, which random bytes with a
 *         32-bit CRC would almost never reach.
 * Checked, with an abort when broken: a frame never reaches past the bytes
 * available; every status has a message; a decoded frame encodes back to a
 * frame that decodes to the same values (a record to the very same bytes).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "telemetry.h"

#define STREAM_MAX 65536u

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void broken(const char *what) {
    fprintf(stderr, "contract broken: %s\n", what);
    abort();
}

/* Re-encodes a decoded frame and checks that it decodes to the same values. */
static void check_round_trip(const uint8_t *frame, const tlm_frame *f) {
    uint8_t again[TLM_FRAME_MAX];
    size_t n = 0u;
    tlm_frame g;
    if (f->type == TLM_START) {
        tlm_start a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        tlm_decode_start(f, &a);
        n = tlm_encode_start(again, f->seq, &a);
        if (tlm_frame_check(again, n, &g) != TLM_OK) {
            broken("a decoded start frame does not encode to a valid frame");
        }
        tlm_decode_start(&g, &b);
        /* The encoder writes zeros after the end of the machine name, by design. */
        size_t end = strlen(a.machine);
        memset(a.machine + end, 0, sizeof a.machine - end);
        if (memcmp(&a, &b, sizeof a) != 0) {
            broken("a start frame does not survive a round trip");
        }
    } else if (f->type == TLM_RECORD) {
        exec_frame a;
        memset(&a, 0, sizeof a);
        tlm_decode_record(f, &a);
        n = tlm_encode_record(again, f->seq, &a);
        if (n != f->frame_len || memcmp(again, frame, n) != 0) {
            broken("a record does not encode back to the same bytes");
        }
    } else if (f->type == TLM_END) {
        tlm_end a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        tlm_decode_end(f, &a);
        n = tlm_encode_end(again, f->seq, &a);
        if (tlm_frame_check(again, n, &g) != TLM_OK) {
            broken("a decoded end frame does not encode to a valid frame");
        }
        tlm_decode_end(&g, &b);
        if (memcmp(&a, &b, sizeof a) != 0) {
            broken("an end frame does not survive a round trip");
        }
    } else {
        broken("a frame of unknown type passed the check");
    }
}

static void scan(const uint8_t *buf, size_t n) {
    size_t pos = 0u;
    while (pos < n) {
        tlm_frame f;
        tlm_status st = tlm_frame_check(buf + pos, n - pos, &f);
        const char *text = tlm_status_text(st);
        if (text == NULL || text[0] == '\0') {
            broken("a status without a message");
        }
        if (st == TLM_OK) {
            if (f.frame_len > n - pos || f.frame_len < TLM_HEADER_BYTES + TLM_CRC_BYTES ||
                f.payload != buf + pos + TLM_HEADER_BYTES) {
                broken("a frame that reaches past the bytes available");
            }
            check_round_trip(buf + pos, &f);
            pos += f.frame_len;
        } else {
            pos++;
        }
    }
}

static void put_le(uint8_t *p, uint32_t v, size_t bytes) {
    for (size_t i = 0; i < bytes; i++) {
        p[i] = (uint8_t)(v >> (8u * i));
    }
}

/* Wraps bodies from the input into valid frames; returns the stream length. */
static size_t build_stream(const uint8_t *data, size_t size, uint8_t *out) {
    static const uint16_t lengths[3] = {TLM_START_PAYLOAD, TLM_RECORD_PAYLOAD, TLM_END_PAYLOAD};
    size_t in = 0u;
    size_t len = 0u;
    while (in + 3u <= size && len + TLM_FRAME_MAX <= STREAM_MAX) {
        uint8_t type = (uint8_t)(1u + data[in] % 3u);
        uint16_t payload = lengths[type - 1u];
        uint8_t *fr = out + len;
        fr[0] = TLM_SYNC0;
        fr[1] = TLM_SYNC1;
        fr[2] = type;
        put_le(fr + 3, payload, 2u);
        fr[5] = data[in + 1u];
        fr[6] = data[in + 2u];
        in += 3u;
        size_t take = size - in < payload ? size - in : payload;
        memset(fr + TLM_HEADER_BYTES, 0, payload);
        memcpy(fr + TLM_HEADER_BYTES, data + in, take);
        in += take;
        put_le(fr + TLM_HEADER_BYTES + payload,
               tlm_crc32(0u, fr + 2, (size_t)TLM_HEADER_BYTES - 2u + payload), 4u);
        len += (size_t)TLM_HEADER_BYTES + payload + TLM_CRC_BYTES;
    }
    return len;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1u) {
        return 0;
    }
    if ((data[0] & 1u) == 0u) {
        /* A private copy, so that a read one byte past the end is caught. */
        uint8_t *copy = malloc(size - 1u + 1u);
        if (copy == NULL) {
            return 0;
        }
        memcpy(copy, data + 1, size - 1u);
        scan(copy, size - 1u);
        free(copy);
    } else {
        uint8_t *stream = malloc(STREAM_MAX);
        if (stream == NULL) {
            return 0;
        }
        size_t n = build_stream(data + 1, size - 1u, stream);
        uint8_t *exact = malloc(n > 0u ? n : 1u);
        if (exact != NULL) {
            memcpy(exact, stream, n);
            scan(exact, n);
            free(exact);
        }
        free(stream);
    }
    return 0;
}

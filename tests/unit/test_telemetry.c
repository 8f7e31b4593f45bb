/*
 * Telemetry frames: the CRC against its published check value, every
 * frame type through encode and decode bit for bit, and each kind of
 * damage (truncation, a flipped bit, a wrong sync, type or length) caught.
 */
#include "telemetry.h"
#include "ut.h"

void suite_telemetry(void);

static uint8_t buf[TLM_FRAME_MAX + 8u];

/* Bit-exact comparison of two doubles (NaN payloads and signed zeros included). */
static bool same_bits(double a, double b) {
    union {
        double d;
        uint64_t u;
    } x, y;
    x.d = a;
    y.d = b;
    return x.u == y.u;
}

/* A record with awkward values: signed zero, subnormal, NaN, huge, tiny. */
static void sample_record(exec_frame *f) {
    union {
        double d;
        uint64_t u;
    } nan;
    nan.u = 0x7FF8000000000123ull;
    *f = (exec_frame){0};
    f->index = 0xDEADBEEFu;
    f->t_s = 12.3;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        f->x[i] = (double)(i + 1) * 1.0000000000000002 - 7.0;
    }
    f->x[0] = -0.0;
    f->x[1] = 4.9406564584124654e-324;
    f->x[2] = nan.d;
    f->cmd[0] = 1.7976931348623157e308;
    f->cmd[4] = 1400.0;
    f->te_nm = -2.2250738585072014e-308;
    f->i_rms_a = 31.25;
    f->v_dc_v = 597.125;
    f->i_batt_a = -3.5;
    f->soc = 0.99999999999999989;
    f->m_index = 0.5;
    f->f_hz = 50.000000000000007;
}

static bool records_equal(const exec_frame *a, const exec_frame *b) {
    bool same = a->index == b->index && same_bits(a->t_s, b->t_s);
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        same = same && same_bits(a->x[i], b->x[i]);
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        same = same && same_bits(a->cmd[i], b->cmd[i]);
    }
    return same && same_bits(a->te_nm, b->te_nm) && same_bits(a->i_rms_a, b->i_rms_a) &&
           same_bits(a->v_dc_v, b->v_dc_v) && same_bits(a->i_batt_a, b->i_batt_a) &&
           same_bits(a->soc, b->soc) && same_bits(a->m_index, b->m_index) &&
           same_bits(a->f_hz, b->f_hz);
}

static void test_crc(void) {
    UT_TEST("CRC-32 of \"123456789\" is the published check value 0xCBF43926; chunks chain");
    const uint8_t check[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
    UT_EQ_INT(tlm_crc32(0u, check, 9u), 0xCBF43926u);
    UT_EQ_INT(tlm_crc32(tlm_crc32(0u, check, 4u), check + 4, 5u), 0xCBF43926u);
    UT_EQ_INT(tlm_crc32(0u, check, 0u), 0u);
}

static void test_record(void) {
    UT_TEST("record: encode then decode gives every double bit for bit, layout as documented");
    exec_frame in, out;
    sample_record(&in);
    size_t n = tlm_encode_record(buf, 0xFFFFu, &in);
    UT_EQ_INT(n, TLM_HEADER_BYTES + TLM_RECORD_PAYLOAD + TLM_CRC_BYTES);
    UT_EQ_INT(buf[0], 0xA5);
    UT_EQ_INT(buf[1], 0x5A);
    UT_EQ_INT(buf[2], TLM_RECORD);
    UT_EQ_INT(buf[3] | (buf[4] << 8), TLM_RECORD_PAYLOAD);
    UT_EQ_INT(buf[5] | (buf[6] << 8), 0xFFFF);
    /* index 0xDEADBEEF little-endian, then t_s = 12.3 = 0x402899999999999A. */
    UT_EQ_INT(buf[7], 0xEF);
    UT_EQ_INT(buf[10], 0xDE);
    UT_EQ_INT(buf[11], 0x9A);
    UT_EQ_INT(buf[18], 0x40);
    tlm_frame f;
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_OK);
    UT_EQ_INT(f.type, TLM_RECORD);
    UT_EQ_INT(f.seq, 0xFFFF);
    UT_EQ_INT(f.frame_len, n);
    tlm_decode_record(&f, &out);
    UT_CHECK(records_equal(&in, &out));
}

static void test_start_end(void) {
    UT_TEST("start and end frames: every field survives encode and decode");
    tlm_start s = {TLM_VERSION, 2u, 1u, 2000u, 50u, 8u, 1000u, 20u, 2.0, "mps2-an386"};
    tlm_start s2;
    size_t n = tlm_encode_start(buf, 0u, &s);
    tlm_frame f;
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_OK);
    UT_EQ_INT(f.type, TLM_START);
    tlm_decode_start(&f, &s2);
    UT_CHECK(s2.version == TLM_VERSION && s2.numeric == 2u && s2.plant == 1u);
    UT_CHECK(s2.fast_ns == 2000u && s2.fast_per_medium == 50u && s2.medium_per_control == 8u);
    UT_CHECK(s2.medium_per_slow == 1000u && s2.frames == 20u && same_bits(s2.duration_s, 2.0));
    UT_CHECK(s2.machine[0] == 'm' && s2.machine[9] == '6' && s2.machine[10] == '\0');

    tlm_end e = {1u, 0u, 1000000u, 20000u, 2500u, 20u, 1u, 2u, 5u, 3u, 4u, -1.5e6, 2.5e5, 1234u};
    tlm_end e2;
    e.fast = 0x0123456789ABCDEFull;
    n = tlm_encode_end(buf, 7u, &e);
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_OK);
    UT_CHECK(f.type == TLM_END && f.seq == 7u);
    tlm_decode_end(&f, &e2);
    UT_CHECK(e2.state == 1u && e2.exit_status == 0u && e2.fast == 0x0123456789ABCDEFull);
    UT_CHECK(e2.medium == 20000u && e2.control == 2500u && e2.slow == 20u);
    UT_CHECK(e2.overruns_fast == 1u && e2.overruns_medium == 2u && e2.overruns_control == 5u &&
             e2.overruns_slow == 3u);
    UT_CHECK(e2.saturations == 4u && same_bits(e2.e_batt_j, -1.5e6));
    UT_CHECK(same_bits(e2.e_mech_j, 2.5e5) && e2.stack_used_bytes == 1234u);
}

static void test_damage(void) {
    UT_TEST("damage: every truncation, every single flipped bit, bad sync/type/length are refused");
    exec_frame in;
    tlm_frame f;
    sample_record(&in);
    size_t n = tlm_encode_record(buf, 3u, &in);
    bool all = true;
    for (size_t k = 0; k < n; k++) {
        all = all && tlm_frame_check(buf, k, &f) == TLM_TRUNCATED;
    }
    UT_CHECK(all);
    unsigned caught = 0u;
    for (size_t byte = 0; byte < n; byte++) {
        for (unsigned bit = 0; bit < 8u; bit++) {
            buf[byte] = (uint8_t)(buf[byte] ^ (1u << bit));
            caught += (tlm_frame_check(buf, n, &f) != TLM_OK) ? 1u : 0u;
            buf[byte] = (uint8_t)(buf[byte] ^ (1u << bit));
        }
    }
    UT_EQ_INT(caught, 8u * n);
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_OK);
    buf[0] = 0x00u;
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_BAD_SYNC);
    buf[0] = TLM_SYNC0;
    buf[2] = 9u;
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_BAD_TYPE);
    buf[2] = TLM_END;
    UT_EQ_INT(tlm_frame_check(buf, n, &f), TLM_BAD_LENGTH);
    UT_CHECK(tlm_status_text(TLM_BAD_CRC)[0] != '\0');
}

static void test_status_text(void) {
    UT_TEST("status texts: each of the six statuses has its own non-empty text, and so has "
            "an unknown value");
    const tlm_status all[6] = {TLM_OK,          TLM_TRUNCATED,  TLM_BAD_SYNC,
                               TLM_BAD_TYPE,    TLM_BAD_LENGTH, TLM_BAD_CRC};
    const char *texts[7];
    for (size_t k = 0u; k < 6u; k++) {
        texts[k] = tlm_status_text(all[k]);
    }
    texts[6] = tlm_status_text((tlm_status)99);
    bool ok = true;
    for (size_t k = 0u; k < 7u; k++) {
        ok = ok && texts[k] != NULL && texts[k][0] != '\0';
        for (size_t j = 0u; j < k; j++) {
            ok = ok && !ut_text_equal(texts[j], texts[k]);
        }
    }
    UT_CHECK(ok);
}

void suite_telemetry(void) {
    UT_TEST("frame sizes as docs/firmware.md gives them: payloads 56, 252 and 76 bytes, a "
            "record frame 263 bytes");
    UT_EQ_INT(TLM_START_PAYLOAD, 56);
    UT_EQ_INT(TLM_RECORD_PAYLOAD, 252);
    UT_EQ_INT(TLM_END_PAYLOAD, 76);
    UT_EQ_INT(TLM_FRAME_MAX, 263);
    test_crc();
    test_record();
    test_start_end();
    test_damage();
    test_status_text();
}

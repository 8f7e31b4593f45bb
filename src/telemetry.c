/*
 * Telemetry frames (see telemetry.h). Every field is written and read a
 * byte at a time, so the layout is the same whatever the byte order of
 * the machine that runs this code.
 */
#include "telemetry.h"

#define RECORD_DOUBLES 30u

/* ---- Byte cursors ------------------------------------------------------ */

typedef struct {
    uint8_t *p;
} tlm_writer;

typedef struct {
    const uint8_t *p;
} tlm_reader;

static void put_u8(tlm_writer *w, uint32_t v) { *w->p++ = (uint8_t)(v & 0xFFu); }

static void put_u16(tlm_writer *w, uint32_t v) {
    put_u8(w, v);
    put_u8(w, v >> 8);
}

static void put_u32(tlm_writer *w, uint32_t v) {
    put_u16(w, v & 0xFFFFu);
    put_u16(w, v >> 16);
}

static void put_u64(tlm_writer *w, uint64_t v) {
    put_u32(w, (uint32_t)(v & 0xFFFFFFFFu));
    put_u32(w, (uint32_t)(v >> 32));
}

/* A double travels as its bit pattern (C99 allows reading the other member of a union). */
static void put_f64(tlm_writer *w, double v) {
    union {
        double d;
        uint64_t u;
    } bits;
    bits.d = v;
    put_u64(w, bits.u);
}

static uint32_t get_u8(tlm_reader *r) { return *r->p++; }

static uint32_t get_u16(tlm_reader *r) {
    uint32_t lo = get_u8(r);
    return lo | (get_u8(r) << 8);
}

static uint32_t get_u32(tlm_reader *r) {
    uint32_t lo = get_u16(r);
    return lo | (get_u16(r) << 16);
}

static uint64_t get_u64(tlm_reader *r) {
    uint64_t lo = get_u32(r);
    return lo | ((uint64_t)get_u32(r) << 32);
}

static double get_f64(tlm_reader *r) {
    union {
        double d;
        uint64_t u;
    } bits;
    bits.u = get_u64(r);
    return bits.d;
}

/* ---- CRC and framing --------------------------------------------------- */

uint32_t tlm_crc32(uint32_t crc, const uint8_t *p, size_t n) {
    /* Bitwise: 8 steps per byte is a few thousand instructions per frame,
     * once per 100 ms, and needs no table in flash. */
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++) {
            uint32_t mask = 0u - (crc & 1u);
            crc = (crc >> 1) ^ (0xEDB88320u & mask);
        }
    }
    return ~crc;
}

/* Writes the header; the payload follows at the returned writer. */
static tlm_writer frame_begin(uint8_t *buf, tlm_type type, uint32_t len, uint16_t seq) {
    tlm_writer w = {buf};
    put_u8(&w, TLM_SYNC0);
    put_u8(&w, TLM_SYNC1);
    put_u8(&w, (uint32_t)type);
    put_u16(&w, len);
    put_u16(&w, seq);
    return w;
}

/* Appends the CRC of everything after the sync bytes; returns the frame length. */
static size_t frame_end(uint8_t *buf, tlm_writer *w) {
    size_t covered = (size_t)(w->p - buf) - 2u;
    put_u32(w, tlm_crc32(0u, buf + 2, covered));
    return (size_t)(w->p - buf);
}

/* The payload length of each type (tlm_type's values); 0: no such type. */
static uint32_t payload_length(uint32_t type) {
    static const uint32_t length[] = {
        0u, TLM_START_PAYLOAD, TLM_RECORD_PAYLOAD, TLM_END_PAYLOAD, TLM_LINK_UP_PAYLOAD,
        TLM_LINK_DOWN_PAYLOAD};
    return (type <= (uint32_t)TLM_LINK_DOWN) ? length[type] : 0u;
}

/* ---- Encoders ---------------------------------------------------------- */

size_t tlm_encode_start(uint8_t *buf, uint16_t seq, const tlm_start *s) {
    tlm_writer w = frame_begin(buf, TLM_START, TLM_START_PAYLOAD, seq);
    put_u8(&w, s->version);
    put_u8(&w, s->numeric);
    put_u8(&w, s->plant);
    put_u8(&w, 0u); /* reserved */
    put_u32(&w, s->fast_ns);
    put_u32(&w, s->fast_per_medium);
    put_u32(&w, s->medium_per_control);
    put_u32(&w, s->medium_per_slow);
    put_u32(&w, s->frames);
    put_f64(&w, s->duration_s);
    bool ended = false;
    for (size_t i = 0; i < TLM_MACHINE_CHARS; i++) {
        ended = ended || s->machine[i] == '\0';
        put_u8(&w, ended ? 0u : (uint32_t)(unsigned char)s->machine[i]);
    }
    return frame_end(buf, &w);
}

/* The record's doubles in their transmitted order. */
static void record_to_array(const exec_frame *f, double v[RECORD_DOUBLES]) {
    size_t k = 0;
    v[k++] = f->t_s;
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        v[k++] = f->x[i];
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        v[k++] = f->cmd[i];
    }
    v[k++] = f->te_nm;
    v[k++] = f->i_rms_a;
    v[k++] = f->v_dc_v;
    v[k++] = f->i_batt_a;
    v[k++] = f->soc;
    v[k++] = f->m_index;
    v[k] = f->f_hz;
}

static void record_from_array(const double v[RECORD_DOUBLES], exec_frame *f) {
    size_t k = 0;
    f->t_s = v[k++];
    for (int i = 0; i < VESSEL_NSTATES; i++) {
        f->x[i] = v[k++];
    }
    for (int i = 0; i < EXEC_NCMD; i++) {
        f->cmd[i] = v[k++];
    }
    f->te_nm = v[k++];
    f->i_rms_a = v[k++];
    f->v_dc_v = v[k++];
    f->i_batt_a = v[k++];
    f->soc = v[k++];
    f->m_index = v[k++];
    f->f_hz = v[k];
}

size_t tlm_encode_record(uint8_t *buf, uint16_t seq, const exec_frame *f) {
    tlm_writer w = frame_begin(buf, TLM_RECORD, TLM_RECORD_PAYLOAD, seq);
    double v[RECORD_DOUBLES];
    record_to_array(f, v);
    put_u32(&w, f->index);
    for (size_t i = 0; i < RECORD_DOUBLES; i++) {
        put_f64(&w, v[i]);
    }
    put_u32(&w, f->faults);
    put_u32(&w, f->trip);
    return frame_end(buf, &w);
}

size_t tlm_encode_end(uint8_t *buf, uint16_t seq, const tlm_end *e) {
    tlm_writer w = frame_begin(buf, TLM_END, TLM_END_PAYLOAD, seq);
    put_u8(&w, e->state);
    put_u8(&w, e->exit_status);
    put_u16(&w, 0u); /* reserved */
    put_u64(&w, e->fast);
    put_u64(&w, e->medium);
    put_u64(&w, e->control);
    put_u64(&w, e->slow);
    put_u32(&w, e->overruns_fast);
    put_u32(&w, e->overruns_medium);
    put_u32(&w, e->overruns_control);
    put_u32(&w, e->overruns_slow);
    put_u32(&w, e->saturations);
    put_f64(&w, e->e_batt_j);
    put_f64(&w, e->e_mech_j);
    put_u32(&w, e->stack_used_bytes);
    return frame_end(buf, &w);
}

/* The link's measurement doubles in their transmitted order, as pointers into u. */
#define LINK_UP_DOUBLES 19u

static void link_up_fields(tlm_link_up *u, double *v[LINK_UP_DOUBLES]) {
    drive_slow_meas *m = &u->meas;
    double *const p[LINK_UP_DOUBLES] = {
        &m->battery.g_s,     &m->battery.b_a,        &m->v_dc_mean_v, &m->v_dc_sq_mean_v2,
        &m->shaft_radps,     &m->shaft_end_radps,    &m->te_nm,       &m->i_rms_a,
        &m->v_dc_v,          &m->m_index,            &m->f_hz,        &m->e_mech_j,
        &m->i_phase_rms_a[0], &m->i_phase_rms_a[1],  &m->i_phase_rms_a[2],
        &m->e_loss_filter_j, &m->e_loss_motor_j,     &m->limit_s,     &u->speed_rpm};
    for (size_t i = 0; i < LINK_UP_DOUBLES; i++) {
        v[i] = p[i];
    }
}

size_t tlm_encode_link_up(uint8_t *buf, uint16_t seq, const tlm_link_up *u) {
    tlm_writer w = frame_begin(buf, TLM_LINK_UP, TLM_LINK_UP_PAYLOAD, seq);
    tlm_link_up copy = *u;
    double *v[LINK_UP_DOUBLES];
    link_up_fields(&copy, v);
    put_u32(&w, u->frame);
    for (size_t i = 0; i < LINK_UP_DOUBLES; i++) {
        put_f64(&w, *v[i]);
    }
    put_u32(&w, u->meas.saturations);
    put_u32(&w, (uint32_t)u->meas.trip & 0xFFu);
    return frame_end(buf, &w);
}

size_t tlm_encode_link_down(uint8_t *buf, uint16_t seq, const tlm_link_down *d) {
    tlm_writer w = frame_begin(buf, TLM_LINK_DOWN, TLM_LINK_DOWN_PAYLOAD, seq);
    const exec_to_drive *x = &d->down;
    const drive_faults none = {0};
    const drive_faults *f = (x->faults != NULL) ? x->faults : &none;
    put_u32(&w, d->frame);
    put_f64(&w, x->bat_next.g_s);
    put_f64(&w, x->bat_next.b_a);
    put_f64(&w, f->dc_cap_frac);
    put_f64(&w, f->current_offset_a);
    put_f64(&w, f->load_factor);
    put_u8(&w, f->switch_open);
    put_u8(&w, f->leg_short);
    put_u8(&w, f->phase_open);
    put_u8(&w, (x->faults != NULL) ? 1u : 0u);
    put_u8(&w, x->trip);
    put_u8(&w, x->state);
    put_u16(&w, 0u); /* reserved */
    return frame_end(buf, &w);
}

/* ---- Decoders ---------------------------------------------------------- */

tlm_status tlm_frame_check(const uint8_t *buf, size_t avail, tlm_frame *f) {
    if (avail < 1u) {
        return TLM_TRUNCATED;
    }
    if (buf[0] != TLM_SYNC0 || (avail >= 2u && buf[1] != TLM_SYNC1)) {
        return TLM_BAD_SYNC;
    }
    if (avail < TLM_HEADER_BYTES) {
        return TLM_TRUNCATED;
    }
    tlm_reader r = {buf + 2};
    uint32_t type = get_u8(&r);
    uint32_t len = get_u16(&r);
    uint32_t seq = get_u16(&r);
    uint32_t want = payload_length(type);
    if (want == 0u) {
        return TLM_BAD_TYPE;
    }
    if (len != want) {
        return TLM_BAD_LENGTH;
    }
    size_t total = TLM_HEADER_BYTES + len + TLM_CRC_BYTES;
    if (avail < total) {
        return TLM_TRUNCATED;
    }
    tlm_reader c = {buf + TLM_HEADER_BYTES + len};
    if (get_u32(&c) != tlm_crc32(0u, buf + 2, total - 2u - TLM_CRC_BYTES)) {
        return TLM_BAD_CRC;
    }
    f->type = (uint8_t)type;
    f->seq = (uint16_t)seq;
    f->payload_len = (uint16_t)len;
    f->payload = buf + TLM_HEADER_BYTES;
    f->frame_len = total;
    return TLM_OK;
}

void tlm_decode_start(const tlm_frame *f, tlm_start *s) {
    tlm_reader r = {f->payload};
    s->version = (uint8_t)get_u8(&r);
    s->numeric = (uint8_t)get_u8(&r);
    s->plant = (uint8_t)get_u8(&r);
    (void)get_u8(&r);
    s->fast_ns = get_u32(&r);
    s->fast_per_medium = get_u32(&r);
    s->medium_per_control = get_u32(&r);
    s->medium_per_slow = get_u32(&r);
    s->frames = get_u32(&r);
    s->duration_s = get_f64(&r);
    for (size_t i = 0; i < TLM_MACHINE_CHARS; i++) {
        s->machine[i] = (char)get_u8(&r);
    }
    s->machine[TLM_MACHINE_CHARS - 1u] = '\0';
}

void tlm_decode_record(const tlm_frame *f, exec_frame *rec) {
    tlm_reader r = {f->payload};
    double v[RECORD_DOUBLES];
    rec->index = get_u32(&r);
    for (size_t i = 0; i < RECORD_DOUBLES; i++) {
        v[i] = get_f64(&r);
    }
    record_from_array(v, rec);
    rec->faults = get_u32(&r);
    rec->trip = get_u32(&r);
}

void tlm_decode_end(const tlm_frame *f, tlm_end *e) {
    tlm_reader r = {f->payload};
    e->state = (uint8_t)get_u8(&r);
    e->exit_status = (uint8_t)get_u8(&r);
    (void)get_u16(&r);
    e->fast = get_u64(&r);
    e->medium = get_u64(&r);
    e->control = get_u64(&r);
    e->slow = get_u64(&r);
    e->overruns_fast = get_u32(&r);
    e->overruns_medium = get_u32(&r);
    e->overruns_control = get_u32(&r);
    e->overruns_slow = get_u32(&r);
    e->saturations = get_u32(&r);
    e->e_batt_j = get_f64(&r);
    e->e_mech_j = get_f64(&r);
    e->stack_used_bytes = get_u32(&r);
}

void tlm_decode_link_up(const tlm_frame *f, tlm_link_up *u) {
    tlm_reader r = {f->payload};
    double *v[LINK_UP_DOUBLES];
    *u = (tlm_link_up){0};
    link_up_fields(u, v);
    u->frame = get_u32(&r);
    for (size_t i = 0; i < LINK_UP_DOUBLES; i++) {
        *v[i] = get_f64(&r);
    }
    u->meas.saturations = get_u32(&r);
    const uint8_t trip = (uint8_t)(get_u32(&r) & 0xFFu);
    u->meas.trip = (drive_trip)trip;
}

void tlm_decode_link_down(const tlm_frame *f, tlm_link_down *d) {
    tlm_reader r = {f->payload};
    exec_to_drive *x = &d->down;
    d->frame = get_u32(&r);
    x->bat_next.g_s = get_f64(&r);
    x->bat_next.b_a = get_f64(&r);
    d->faults.dc_cap_frac = get_f64(&r);
    d->faults.current_offset_a = get_f64(&r);
    d->faults.load_factor = get_f64(&r);
    d->faults.switch_open = (uint8_t)get_u8(&r);
    d->faults.leg_short = (uint8_t)get_u8(&r);
    d->faults.phase_open = (uint8_t)get_u8(&r);
    x->faults = (get_u8(&r) != 0u) ? &d->faults : NULL;
    x->trip = (uint8_t)get_u8(&r);
    x->state = (uint8_t)get_u8(&r);
}

const char *tlm_status_text(tlm_status st) {
    switch (st) {
    case TLM_OK: return "ok";
    case TLM_TRUNCATED: return "truncated frame (the data ends inside it)";
    case TLM_BAD_SYNC: return "no frame start (sync bytes A5 5A expected)";
    case TLM_BAD_TYPE: return "unknown frame type";
    case TLM_BAD_LENGTH: return "payload length does not match the frame type";
    case TLM_BAD_CRC: return "CRC mismatch (corrupt frame)";
    }
    return "unknown status";
}

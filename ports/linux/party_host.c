/*
 * uuvsim party: the slow segment of the multi-party run (docs/cosimulation.md).
 *
 *   uuvsim party --link SOCKET --scenario FILE [--duration S] [--csv FILE]
 *                [--timeout S] [--corrupt-down K] [--drop-down K] [--corrupt-up K]
 *
 * The drive runs as firmware (the multi-party image, uuvsim_party.elf)
 * under QEMU, whose UART is connected to SOCKET, a Unix socket this
 * program listens on; tools/qemu-party.sh starts both. This program runs
 * the executive's slow segment (battery, protection, vessel, scenario,
 * telemetry: exec_slow_model()) on the measurements the drive sends at
 * each slow boundary, and sends back what the slow step gives the drive
 * (exec_to_drive), in lock-step. The telemetry CSV is the desk's
 * (uuvsim --csv) byte for byte.
 *
 * Every frame is checked (src/telemetry.h: sync, type, length, CRC-32,
 * sequence number, the slow frame it belongs to). A frame that fails, a
 * frame that does not come within the timeout (default 600 s of wall
 * time, a guard against a hung emulator, not a part of the results) or a
 * link that closes early ends the run with a message naming the frame,
 * exit status 2 and no CSV. For the tests, --corrupt-down K flips a bit of
 * this side's frame K, --drop-down K does not send it (the next frame goes
 * out in its place), and --corrupt-up K flips a bit of the drive's frame K
 * as it arrives.
 *
 * Exit status: 0 the run completed; 1 the drive stopped on an overrun; 2
 * bad input or a link failure; 3 a state became non-finite (as uuvsim).
 */
#include "party_host.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "csv_out.h"
#include "out_file.h"
#include "telemetry.h"
#include "uuv_config.h"

#define PARTY_NONE UINT32_MAX

typedef struct {
    const char *link_path, *scenario_path, *csv_path;
    double duration_s;   /* 0: the scenario's */
    double timeout_s;    /* wall-clock guard per frame */
    uint32_t corrupt_down, drop_down, corrupt_up; /* frame numbers, PARTY_NONE: none */
} party_options;

typedef struct {
    int fd;
    double timeout_s;
    uint16_t rx_seq, tx_seq;   /* the next frame from the drive, to the drive */
    uint32_t corrupt_up;
    uint8_t buf[TLM_FRAME_MAX];
} party_link;

static const char party_usage[] =
    "usage: uuvsim party --link SOCKET --scenario FILE [--duration S] [--csv FILE]\n"
    "                    [--timeout S] [--corrupt-down K] [--drop-down K] [--corrupt-up K]\n";

static bool party_number(const char *opt, const char *text, double lo, double hi, double *out) {
    char *end = NULL;
    errno = 0;
    double v = strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !(v >= lo && v <= hi)) {
        fprintf(stderr, "uuvsim party: option %s: expected a number in [%g, %g], got '%s'\n",
                opt, lo, hi, text);
        return false;
    }
    *out = v;
    return true;
}

static bool party_parse(int argc, char **argv, party_options *o) {
    *o = (party_options){NULL, NULL, NULL, 0.0, 600.0, PARTY_NONE, PARTY_NONE, PARTY_NONE};
    for (int i = 2; i < argc; i += 2) {
        const char *a = argv[i];
        if (i + 1 >= argc) {
            fprintf(stderr, "uuvsim party: option %s needs a value\n%s", a, party_usage);
            return false;
        }
        const char *v = argv[i + 1];
        double x = 0.0;
        uint32_t *frame = strcmp(a, "--corrupt-down") == 0 ? &o->corrupt_down
                          : strcmp(a, "--drop-down") == 0  ? &o->drop_down
                          : strcmp(a, "--corrupt-up") == 0 ? &o->corrupt_up
                                                           : NULL;
        if (strcmp(a, "--link") == 0) {
            o->link_path = v;
        } else if (strcmp(a, "--scenario") == 0) {
            o->scenario_path = v;
        } else if (strcmp(a, "--csv") == 0) {
            o->csv_path = v;
        } else if (strcmp(a, "--duration") == 0) {
            if (!party_number(a, v, 1e-3, 1e6, &o->duration_s)) {
                return false;
            }
        } else if (strcmp(a, "--timeout") == 0) {
            if (!party_number(a, v, 1.0, 1e5, &o->timeout_s)) {
                return false;
            }
        } else if (frame != NULL) {
            if (!party_number(a, v, 0.0, 65535.0, &x)) {
                return false;
            }
            if (x != (double)(uint32_t)x) {
                fprintf(stderr, "uuvsim party: option %s: expected a frame number, got '%s'\n",
                        a, v);
                return false;
            }
            *frame = (uint32_t)x;
        } else {
            fprintf(stderr, "uuvsim party: unknown option '%s'\n%s", a, party_usage);
            return false;
        }
    }
    if (o->link_path == NULL || o->scenario_path == NULL) {
        fprintf(stderr, "uuvsim party: --link and --scenario are required\n%s", party_usage);
        return false;
    }
    if (strlen(o->link_path) >= sizeof(((struct sockaddr_un *)NULL)->sun_path) - 8u) {
        fprintf(stderr, "uuvsim party: option --link: the socket path is longer than %zu bytes\n",
                sizeof(((struct sockaddr_un *)NULL)->sun_path) - 8u);
        return false;
    }
    return true;
}

/*
 * Listens on the socket: bound and listening under a temporary name, then
 * renamed to the path, so that the path exists only once it can be
 * connected to (tools/qemu-party.sh waits for it). Waits for one
 * connection.
 */
static int party_listen(const char *path, double timeout_s) {
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    (void)snprintf(a.sun_path, sizeof a.sun_path, "%s.%ld", path, (long)getpid());
    struct stat st;
    if (lstat(path, &st) == 0) {
        fprintf(stderr, "uuvsim party: --link %s: already exists (remove it first)\n", path);
        return -1;
    }
    int s = socket(AF_UNIX, SOCK_STREAM, 0);
    if (s < 0 || bind(s, (const struct sockaddr *)&a, sizeof a) != 0 || listen(s, 1) != 0 ||
        rename(a.sun_path, path) != 0) {
        fprintf(stderr, "uuvsim party: --link %s: %s\n", path, strerror(errno));
        if (s >= 0) {
            close(s);
        }
        (void)unlink(a.sun_path);
        return -1;
    }
    struct pollfd p = {s, POLLIN, 0};
    int ready = poll(&p, 1, (int)(timeout_s * 1000.0));
    int c = (ready == 1) ? accept(s, NULL, NULL) : -1;
    if (c < 0) {
        fprintf(stderr, "uuvsim party: --link %s: %s\n", path,
                ready == 0 ? "no connection from the drive within the timeout" : strerror(errno));
    }
    close(s);
    (void)unlink(path);
    return c;
}

/* Reads n bytes; false on end of stream, error or timeout (*why says which). */
static bool party_read(party_link *l, uint8_t *p, size_t n, const char **why) {
    while (n > 0u) {
        struct pollfd q = {l->fd, POLLIN, 0};
        int ready = poll(&q, 1, (int)(l->timeout_s * 1000.0));
        if (ready == 0) {
            *why = "not received within the timeout (lost)";
            return false;
        }
        ssize_t got = (ready > 0) ? read(l->fd, p, n) : -1;
        if (got < 0 && errno == EINTR) {
            continue;
        }
        if (got <= 0) {
            *why = got == 0 ? "the drive closed the link before it" : strerror(errno);
            return false;
        }
        p += got;
        n -= (size_t)got;
    }
    return true;
}

/*
 * Receives the drive's next frame, checked (framing, CRC, sequence), of
 * one of the types the caller accepts; prints the failure naming the frame.
 */
static bool party_receive(party_link *l, const char *expected, uint8_t type_a, uint8_t type_b,
                          tlm_frame *f) {
    const char *why = NULL;
    bool ok = party_read(l, l->buf, TLM_HEADER_BYTES, &why);
    tlm_status st = ok ? tlm_frame_check(l->buf, TLM_HEADER_BYTES, f) : TLM_OK;
    if (ok && st == TLM_TRUNCATED) {
        size_t len = (size_t)l->buf[3] | ((size_t)l->buf[4] << 8);
        ok = party_read(l, l->buf + TLM_HEADER_BYTES, len + TLM_CRC_BYTES, &why);
        if (ok && l->rx_seq == l->corrupt_up) {
            l->buf[TLM_HEADER_BYTES + len / 2u] ^= 0x10u; /* the test's corruption */
        }
        st = ok ? tlm_frame_check(l->buf, TLM_HEADER_BYTES + len + TLM_CRC_BYTES, f) : TLM_OK;
    }
    if (ok && st != TLM_OK) {
        why = tlm_status_text(st);
    } else if (ok && f->type != type_a && f->type != type_b) {
        why = "a frame of another type";
    } else if (ok && f->seq != l->rx_seq) {
        why = "out of sequence (a frame was lost)";
    }
    if (why != NULL || !ok) {
        fprintf(stderr, "uuvsim party: link: frame %u from the drive (%s): %s\n",
                (unsigned)l->rx_seq, expected, why);
        return false;
    }
    l->rx_seq++;
    return true;
}

static bool party_send(party_link *l, const tlm_link_down *d, const party_options *o) {
    uint8_t buf[TLM_FRAME_MAX];
    if (l->tx_seq == o->drop_down) {
        l->tx_seq++; /* the test's lost frame: the next one goes out in its place */
    }
    size_t n = tlm_encode_link_down(buf, l->tx_seq, d);
    if (l->tx_seq == o->corrupt_down) {
        buf[TLM_HEADER_BYTES + 8u] ^= 0x01u; /* the test's corruption: a bit of g */
    }
    l->tx_seq++;
    size_t done = 0;
    while (done < n) {
        ssize_t put = write(l->fd, buf + done, n - done);
        if (put < 0 && errno == EINTR) {
            continue;
        }
        if (put <= 0) {
            fprintf(stderr, "uuvsim party: link: frame %u to the drive: %s\n",
                    (unsigned)(l->tx_seq - 1u), strerror(errno));
            return false;
        }
        done += (size_t)put;
    }
    return true;
}

/* The drive's START must describe the run this side runs. */
static bool party_check_start(const tlm_frame *f, const exec *e) {
    tlm_start s;
    tlm_decode_start(f, &s);
    const exec_config *c = &e->cfg;
    const char *what = s.version != TLM_VERSION                 ? "the stream's version"
                       : s.numeric != (uint8_t)UUV_NUMERIC       ? "the numeric build"
                       : s.plant != (uint8_t)c->plant            ? "the plant"
                       : s.fast_ns != c->fast_ns ||
                               s.fast_per_medium != c->fast_per_medium ||
                               s.medium_per_control != c->medium_per_control ||
                               s.medium_per_slow != c->medium_per_slow ? "the frames"
                       : s.frames != e->frames                   ? "the number of slow frames"
                                                                 : NULL;
    if (what != NULL) {
        fprintf(stderr, "uuvsim party: link: the drive (%s, %s build, %u slow frames) runs "
                "another configuration than this side (%s build, %u slow frames): %s differ\n",
                s.machine, s.numeric == (uint8_t)UUV_NUMERIC_FIXED ? "fixed" : "float",
                (unsigned)s.frames, UUV_NUMERIC_NAME, (unsigned)e->frames, what);
        return false;
    }
    return true;
}

/* The run over the link; returns the exit status (the CSV is written as records come). */
static int party_run(party_link *l, exec *e, FILE *csv, const party_options *o) {
    tlm_frame f;
    if (!party_receive(l, "START", TLM_START, TLM_START, &f) || !party_check_start(&f, e)) {
        return 2;
    }
    char expected[64];
    while (e->state == EXEC_RUNNING) {
        (void)snprintf(expected, sizeof expected, "LINK_UP of slow frame %u",
                       (unsigned)(e->frame + 1u));
        if (!party_receive(l, expected, TLM_LINK_UP, TLM_END, &f)) {
            return 2;
        }
        if (f.type == TLM_END) {
            break; /* the drive stopped (an overrun): its END says so */
        }
        tlm_link_up up;
        tlm_decode_link_up(&f, &up);
        if (up.frame != e->frame + 1u) {
            fprintf(stderr, "uuvsim party: link: frame %u from the drive (%s): it measured "
                    "slow frame %u\n", (unsigned)f.seq, expected, (unsigned)up.frame);
            return 2;
        }
        e->meas = up.meas;
        e->speed_report_rpm = up.speed_rpm;
        exec_slow_model(e);
        exec_frame r;
        if (exec_report_take(e, &r) && csv != NULL) {
            csv_row(csv, &r, true);
        }
        tlm_link_down d;
        d.frame = up.frame;
        d.down = e->down; /* its faults, when new, are the player's */
        if (!party_send(l, &d, o)) {
            return 2;
        }
    }
    if (f.type != TLM_END && !party_receive(l, "END", TLM_END, TLM_END, &f)) {
        return 2;
    }
    tlm_end end;
    tlm_decode_end(&f, &end);
    if (e->state == EXEC_RUNNING) {
        fprintf(stderr, "uuvsim party: the drive stopped at slow frame %u of %u: %u fast, %u "
                "motor, %u control overruns\n", (unsigned)e->frame, (unsigned)e->frames,
                (unsigned)end.overruns_fast, (unsigned)end.overruns_medium,
                (unsigned)end.overruns_control);
        return 1;
    }
    printf("uuvsim party: %u slow frames exchanged with the drive (%llu fast steps), %s\n",
           (unsigned)e->frame, (unsigned long long)end.fast,
           e->state == EXEC_DONE ? "completed" : "stopped: a state became non-finite");
    return e->state == EXEC_DONE ? 0 : 3;
}

int party_main(int argc, char **argv) {
    party_options o;
    out_program("uuvsim party");
    if (!party_parse(argc, argv, &o)) {
        return 2;
    }
    static scenario scn;
    if (!uuvsim_load_scenario(o.scenario_path, &scn)) {
        return 2;
    }
    if (o.duration_s <= 0.0 && scn.duration_s <= 0.0) {
        fprintf(stderr, "uuvsim party: %s: no duration (give 'duration <s>' or --duration)\n",
                o.scenario_path);
        return 2;
    }
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.duration_s = o.duration_s;
    scenario_error err;
    if (!exec_check_scenario(&cfg, &scn, &err)) {
        fprintf(stderr, "uuvsim party: %s:%u: field '%s': %s\n", o.scenario_path, err.line,
                err.field, err.message);
        return 2;
    }
    static exec e;
    if (exec_init(&e, &cfg, &scn) != EXEC_OK) {
        fprintf(stderr, "uuvsim party: %s: the duration or the scenario is out of range\n",
                o.scenario_path);
        return 2;
    }
    const out_spec outs[1] = {{"--csv", o.csv_path}};
    const out_spec ins[1] = {{"--scenario", o.scenario_path}};
    if (!out_check(outs, 1, ins, 1)) {
        return 2;
    }
    out_guard_signals();
    static out_file csv;
    if (o.csv_path != NULL && !out_open(&csv, o.csv_path)) {
        return 2;
    }
    if (csv.f != NULL) {
        exec_frame r0;
        csv_header(csv.f, true);
        if (exec_report_take(&e, &r0)) {
            csv_row(csv.f, &r0, true);
        }
    }
    static party_link link;
    link.fd = party_listen(o.link_path, o.timeout_s);
    link.timeout_s = o.timeout_s;
    link.corrupt_up = o.corrupt_up;
    int status = (link.fd >= 0) ? party_run(&link, &e, csv.f, &o) : 2;
    if (link.fd >= 0) {
        close(link.fd);
    }
    /* A link failure leaves no CSV; a run that ended (completed or stopped) commits it. */
    if (status == 2 || !out_finish(&csv) || !out_stdout_ok() || !out_commit(&csv)) {
        out_abort(&csv);
        return 2;
    }
    return status;
}

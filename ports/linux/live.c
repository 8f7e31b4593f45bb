/*
 * The live view (uuvsim --view): a small HTTP server on 127.0.0.1 that the
 * paced run serves while it waits for the wall clock (live_wait instead of
 * sleeping). GET / gives the mission page (view.c) with the frames made so
 * far; GET /events?from=K streams frame K and the following ones as
 * server-sent events, one CSV row each ("id: K" lets a reconnecting
 * browser resume), then the JSON summary and the end. The server only
 * watches: the run's results and files are the same with or without it.
 */
#include "live.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "csv_out.h"
#include "view.h"

#define LIVE_CLIENTS 16
#define REQUEST_BYTES 4096

typedef enum { CLIENT_FREE, CLIENT_READING, CLIENT_STREAM } client_state;

typedef struct {
    client_state state;
    int fd;
    size_t used;          /* bytes of the request read */
    size_t next;          /* CLIENT_STREAM: the next frame to send */
    char req[REQUEST_BYTES + 1];
} live_client;

struct live_server {
    int listen_fd;
    bool full_plant;
    view_text three;
    char *csv;            /* header and rows so far */
    size_t csv_len, csv_cap;
    size_t *row_at;       /* offset of each row in csv */
    size_t rows, rows_cap;
    live_client clients[LIVE_CLIENTS];
};

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Appends text to the CSV buffer; false when out of memory. */
static bool csv_append(live_server *l, const char *s, size_t n) {
    if (l->csv_len + n + 1u > l->csv_cap) {
        size_t cap = l->csv_cap ? l->csv_cap : 65536u;
        while (cap < l->csv_len + n + 1u) {
            cap *= 2u;
        }
        char *grown = realloc(l->csv, cap);
        if (grown == NULL) {
            return false;
        }
        l->csv = grown;
        l->csv_cap = cap;
    }
    memcpy(l->csv + l->csv_len, s, n);
    l->csv_len += n;
    l->csv[l->csv_len] = '\0';
    return true;
}

/* Sends all of buf on a blocking socket (with its send timeout); false on failure. */
static bool send_all(int fd, const char *buf, size_t n) {
    while (n > 0u) {
        ssize_t k = send(fd, buf, n, MSG_NOSIGNAL);
        if (k <= 0) {
            return false;
        }
        buf += k;
        n -= (size_t)k;
    }
    return true;
}

static void client_close(live_client *c) {
    if (c->state != CLIENT_FREE) {
        close(c->fd);
    }
    c->state = CLIENT_FREE;
}

/* The client's socket blocking, with a send timeout: a stalled browser is dropped. */
static void client_blocking(live_client *c, long timeout_ms) {
    int flags = fcntl(c->fd, F_GETFL);
    if (flags >= 0) {
        (void)fcntl(c->fd, F_SETFL, flags & ~O_NONBLOCK);
    }
    struct timeval tv = {timeout_ms / 1000, (timeout_ms % 1000) * 1000};
    (void)setsockopt(c->fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
}

/* Sends the stream's frames from c->next on. */
static void stream_rows(live_server *l, live_client *c) {
    char head[48];
    for (; c->next < l->rows; c->next++) {
        size_t start = l->row_at[c->next];
        size_t end = (c->next + 1u < l->rows) ? l->row_at[c->next + 1u] : l->csv_len;
        int n = snprintf(head, sizeof head, "id: %zu\ndata: ", c->next);
        /* The row without its newline, then the event's blank line. */
        if (!send_all(c->fd, head, (size_t)n) ||
            !send_all(c->fd, l->csv + start, end - start - 1u) || !send_all(c->fd, "\n\n", 2u)) {
            client_close(c);
            return;
        }
    }
}

/* A whole number at s (digits only); false if none. */
static bool read_index(const char *s, size_t *v) {
    if (*s < '0' || *s > '9') {
        return false;
    }
    size_t x = 0u;
    for (; *s >= '0' && *s <= '9' && x < ((size_t)1 << 40); s++) {
        x = x * 10u + (size_t)(*s - '0');
    }
    *v = x;
    return true;
}

static void respond(live_client *c, const char *status, const char *body) {
    char buf[256];
    int n = snprintf(buf, sizeof buf, "HTTP/1.1 %s\r\nContent-Type: text/plain\r\n"
                     "Connection: close\r\n\r\n%s\n", status, body);
    client_blocking(c, 1000);
    (void)send_all(c->fd, buf, (size_t)n);
    client_close(c);
}

/* Answers a complete request: the page, the event stream, or an error. */
static void handle(live_server *l, live_client *c) {
    char *path = c->req + 4;
    if (strncmp(c->req, "GET ", 4) != 0) {
        respond(c, "405 Method Not Allowed", "only GET");
        return;
    }
    size_t plen = strcspn(path, " \r\n");
    if (plen == 1u || (plen == 13u && strncmp(path, "/mission.html", 13) == 0)) {
        static const char head[] = "HTTP/1.1 200 OK\r\nContent-Type: text/html; charset=utf-8\r\n"
                                   "Cache-Control: no-store\r\nConnection: close\r\n\r\n";
        client_blocking(c, 5000);
        FILE *f = fdopen(c->fd, "w");
        if (f == NULL) {
            client_close(c);
            return;
        }
        view_text csv = {l->csv, l->csv_len};
        fputs(head, f);
        view_write_page(f, &l->three, &csv, NULL, true);
        fclose(f); /* closes the socket */
        c->state = CLIENT_FREE;
        return;
    }
    if (plen >= 7u && strncmp(path, "/events", 7) == 0) {
        size_t from = 0u;
        const char *q = strstr(path, "?from=");
        if (q != NULL && q < path + plen) {
            (void)read_index(q + 6, &from);
        }
        /* A reconnecting EventSource names the last frame it has. */
        const char *last = strstr(c->req, "\nLast-Event-ID: ");
        size_t id = 0u;
        if (last != NULL && read_index(last + 16, &id)) {
            from = id + 1u;
        }
        static const char head[] = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n"
                                   "Cache-Control: no-store\r\n\r\n";
        client_blocking(c, 1000);
        if (!send_all(c->fd, head, sizeof head - 1u)) {
            client_close(c);
            return;
        }
        c->state = CLIENT_STREAM;
        c->next = from < l->rows ? from : l->rows;
        stream_rows(l, c);
        return;
    }
    respond(c, "404 Not Found", "the live view has / and /events");
}

live_server *live_open(unsigned port, bool full_plant) {
    live_server *l = calloc(1u, sizeof *l);
    if (l == NULL) {
        fprintf(stderr, "uuvsim: --view: out of memory\n");
        return NULL;
    }
    l->listen_fd = -1;
    l->full_plant = full_plant;
    if (!view_read_three(&l->three)) {
        live_close(l);
        return NULL;
    }
    l->listen_fd = socket(AF_INET, SOCK_STREAM, 0);
    int one = 1;
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK); /* this machine only */
    socklen_t alen = sizeof a;
    if (l->listen_fd < 0 ||
        setsockopt(l->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(l->listen_fd, (struct sockaddr *)&a, sizeof a) != 0 || listen(l->listen_fd, 8) != 0 ||
        fcntl(l->listen_fd, F_SETFL, O_NONBLOCK) != 0 ||
        getsockname(l->listen_fd, (struct sockaddr *)&a, &alen) != 0) {
        fprintf(stderr, "uuvsim: --view: cannot listen on 127.0.0.1:%u: %s\n", port,
                strerror(errno));
        live_close(l);
        return NULL;
    }
    char *head = NULL;
    size_t head_len = 0u;
    FILE *m = open_memstream(&head, &head_len);
    if (m != NULL) {
        csv_header(m, full_plant);
        fclose(m);
    }
    bool ok = head != NULL && csv_append(l, head, head_len);
    free(head);
    if (!ok) {
        fprintf(stderr, "uuvsim: --view: out of memory\n");
        live_close(l);
        return NULL;
    }
    fprintf(stderr, "uuvsim: live view on http://127.0.0.1:%u/ (the run starts when a browser "
            "opens it)\n", (unsigned)ntohs(a.sin_port));
    return l;
}

void live_frame(live_server *l, const exec_frame *f) {
    char *row = NULL;
    size_t len = 0u;
    FILE *m = open_memstream(&row, &len);
    if (m == NULL) {
        return;
    }
    csv_row(m, f, l->full_plant);
    fclose(m);
    if (l->rows == l->rows_cap) {
        size_t cap = l->rows_cap ? 2u * l->rows_cap : 4096u;
        size_t *grown = realloc(l->row_at, cap * sizeof *grown);
        if (grown == NULL) {
            free(row);
            return; /* the view misses frames; the run goes on */
        }
        l->row_at = grown;
        l->rows_cap = cap;
    }
    size_t at = l->csv_len;
    if (row != NULL && csv_append(l, row, len)) {
        l->row_at[l->rows++] = at;
        for (int k = 0; k < LIVE_CLIENTS; k++) {
            if (l->clients[k].state == CLIENT_STREAM) {
                stream_rows(l, &l->clients[k]);
            }
        }
    }
    free(row);
}

/* Accepts a connection into a free slot (or turns it away). */
static void accept_one(live_server *l) {
    int fd = accept(l->listen_fd, NULL, NULL);
    if (fd < 0) {
        return;
    }
    for (int k = 0; k < LIVE_CLIENTS; k++) {
        live_client *c = &l->clients[k];
        if (c->state == CLIENT_FREE) {
            (void)fcntl(fd, F_SETFL, O_NONBLOCK);
            c->state = CLIENT_READING;
            c->fd = fd;
            c->used = 0u;
            return;
        }
    }
    close(fd);
}

/* Reads what a client sent; answers once the request's header is complete. */
static void read_request(live_server *l, live_client *c) {
    ssize_t k = recv(c->fd, c->req + c->used, REQUEST_BYTES - c->used, 0);
    if (k <= 0) {
        if (k == 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) {
            client_close(c);
        }
        return;
    }
    c->used += (size_t)k;
    c->req[c->used] = '\0';
    if (strstr(c->req, "\r\n\r\n") != NULL) {
        handle(l, c);
    } else if (c->used == REQUEST_BYTES) {
        respond(c, "431 Request Header Fields Too Large", "request too large");
    }
}

void live_wait(live_server *l, double seconds) {
    double end = now_s() + seconds;
    do {
        struct pollfd p[1 + LIVE_CLIENTS];
        int who[1 + LIVE_CLIENTS];
        nfds_t n = 0u;
        p[n].fd = l->listen_fd;
        p[n].events = POLLIN;
        who[n++] = -1;
        for (int k = 0; k < LIVE_CLIENTS; k++) {
            if (l->clients[k].state != CLIENT_FREE) {
                p[n].fd = l->clients[k].fd;
                p[n].events = POLLIN; /* a request, or a stream's close */
                who[n++] = k;
            }
        }
        double left = end - now_s();
        int ms = left > 0.0 ? (int)(left * 1000.0 + 0.5) : 0;
        if (poll(p, n, ms) <= 0) {
            continue;
        }
        for (nfds_t i = 0u; i < n; i++) {
            if ((p[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) {
                continue;
            }
            if (who[i] < 0) {
                accept_one(l);
                continue;
            }
            live_client *c = &l->clients[who[i]];
            if (c->state == CLIENT_READING) {
                read_request(l, c);
            } else if (c->state == CLIENT_STREAM) {
                char sink[256];
                if (recv(c->fd, sink, sizeof sink, MSG_DONTWAIT) <= 0) {
                    client_close(c); /* the browser went away */
                }
            }
        }
    } while (now_s() < end);
}

void live_wait_browser(live_server *l) {
    for (;;) {
        for (int k = 0; k < LIVE_CLIENTS; k++) {
            if (l->clients[k].state == CLIENT_STREAM) {
                return;
            }
        }
        live_wait(l, 0.2);
    }
}

void live_end(live_server *l, const char *summary, size_t len) {
    for (int k = 0; k < LIVE_CLIENTS; k++) {
        live_client *c = &l->clients[k];
        if (c->state != CLIENT_STREAM) {
            continue;
        }
        /* The summary's lines as the event's data lines; then the end. */
        bool ok = send_all(c->fd, "event: summary\n", 15u);
        for (size_t i = 0; ok && i < len;) {
            size_t j = i;
            while (j < len && summary[j] != '\n') {
                j++;
            }
            ok = send_all(c->fd, "data: ", 6u) && send_all(c->fd, summary + i, j - i) &&
                 send_all(c->fd, "\n", 1u);
            i = j + 1u;
        }
        ok = ok && send_all(c->fd, "\nevent: end\ndata: end\n\n", 23u);
        client_close(c);
    }
}

void live_close(live_server *l) {
    if (l == NULL) {
        return;
    }
    for (int k = 0; k < LIVE_CLIENTS; k++) {
        client_close(&l->clients[k]);
    }
    if (l->listen_fd >= 0) {
        close(l->listen_fd);
    }
    free(l->three.data);
    free(l->csv);
    free(l->row_at);
    free(l);
}

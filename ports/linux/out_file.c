/*
 * Output files (see out_file.h).
 */
/* realpath() is an XSI function. */
#define _XOPEN_SOURCE 700

#include "out_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define OUT_MAX_LIVE 8
#define OUT_MAX_CHECKED 8

static const char *prog = "uuvsim";

/* The temporary files not yet committed or removed, for the signal handler. */
static char *volatile live[OUT_MAX_LIVE];

void out_program(const char *name) { prog = name; }

static void live_add(char *tmp) {
    for (int i = 0; i < OUT_MAX_LIVE; i++) {
        if (live[i] == NULL) {
            live[i] = tmp;
            return;
        }
    }
}

static void live_remove(const char *tmp) {
    for (int i = 0; i < OUT_MAX_LIVE; i++) {
        if (live[i] == tmp) {
            live[i] = NULL;
        }
    }
}

/* Async-signal-safe: unlink() only, then the signal's default action (SA_RESETHAND). */
static void on_signal(int sig) {
    for (int i = 0; i < OUT_MAX_LIVE; i++) {
        char *t = live[i];
        if (t != NULL) {
            (void)unlink(t);
        }
    }
    (void)raise(sig);
}

void out_guard_signals(void) {
    static const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = (int)SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; i++) {
        (void)sigaddset(&sa.sa_mask, sigs[i]);
    }
    for (int i = 0; i < 3; i++) {
        (void)sigaction(sigs[i], &sa, NULL);
    }
}

/* The directory part of path ("." when it has none) and where the last name starts. */
static bool split_path(const char *path, char *dir, size_t cap, const char **base) {
    const char *slash = strrchr(path, '/');
    *base = (slash != NULL) ? slash + 1 : path;
    size_t n = (slash == NULL) ? 0u : (slash == path ? 1u : (size_t)(slash - path));
    if (n + 2u > cap) {
        return false;
    }
    if (n == 0u) {
        strcpy(dir, ".");
    } else {
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    return true;
}

/* The path with its directory resolved (the file itself need not exist). */
static bool canonical(const char *path, char *out, size_t cap) {
    char dir[PATH_MAX];
    char real[PATH_MAX];
    const char *base = NULL;
    if (!split_path(path, dir, sizeof dir, &base) || realpath(dir, real) == NULL) {
        return false;
    }
    return (size_t)snprintf(out, cap, "%s/%s", real, base) < cap;
}

static const char *kind_of(mode_t m) {
    return S_ISLNK(m)                    ? "a symbolic link"
           : (S_ISCHR(m) || S_ISBLK(m))  ? "a device"
           : S_ISFIFO(m)                 ? "a FIFO"
           : S_ISDIR(m)                  ? "a directory"
           : S_ISSOCK(m)                 ? "a socket"
                                         : "not a regular file";
}

typedef struct {
    const char *option;
    const char *path;
    char canon[PATH_MAX + 256];
    bool exists;
    dev_t dev;
    ino_t ino;
} checked;

/* Resolves one path; an output must be a regular file or not exist. */
static bool check_one(const out_spec *s, bool output, checked *c) {
    c->option = s->option;
    c->path = s->path;
    c->exists = false;
    struct stat st;
    const char *base = strrchr(s->path, '/');
    base = (base != NULL) ? base + 1 : s->path;
    if (output && (base[0] == '\0' || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)) {
        fprintf(stderr, "%s: %s: %s: a directory, not a file to write\n", prog, s->option,
                s->path);
        return false;
    }
    if ((output ? lstat(s->path, &st) : stat(s->path, &st)) == 0) {
        if (output && !S_ISREG(st.st_mode)) {
            fprintf(stderr, "%s: %s: %s: %s, not a regular file: refusing to replace it\n",
                    prog, s->option, s->path, kind_of(st.st_mode));
            return false;
        }
        c->exists = true;
        c->dev = st.st_dev;
        c->ino = st.st_ino;
    }
    if (!canonical(s->path, c->canon, sizeof c->canon)) {
        fprintf(stderr, "%s: %s: %s: cannot write: %s\n", prog, s->option, s->path,
                strerror(errno != 0 ? errno : ENAMETOOLONG));
        return false;
    }
    return true;
}

static bool same_file(const checked *a, const checked *b) {
    return strcmp(a->canon, b->canon) == 0 ||
           (a->exists && b->exists && a->dev == b->dev && a->ino == b->ino);
}

bool out_check(const out_spec *outputs, int n_out, const out_spec *inputs, int n_in) {
    static checked c[OUT_MAX_CHECKED];
    int n = 0;
    for (int k = 0; k < n_out + n_in; k++) {
        const bool output = k < n_out;
        const out_spec *s = output ? &outputs[k] : &inputs[k - n_out];
        if (s->path == NULL || n >= OUT_MAX_CHECKED) {
            continue;
        }
        errno = 0;
        if (!check_one(s, output, &c[n])) {
            return false;
        }
        for (int j = 0; j < n; j++) {
            if (same_file(&c[j], &c[n])) {
                fprintf(stderr, "%s: %s %s and %s %s are the same file: %s\n", prog, c[j].option,
                        c[j].path, c[n].option, c[n].path,
                        output ? "give each output its own file"
                               : "an output must not replace an input");
                return false;
            }
        }
        n++;
    }
    return true;
}

bool out_open(out_file *o, const char *path) {
    *o = (out_file){0};
    if (strlen(path) >= sizeof o->path) {
        fprintf(stderr, "%s: %s: path too long\n", prog, path);
        return false;
    }
    strcpy(o->path, path);
    /* The process id makes the name unique among runs; O_EXCL | O_NOFOLLOW
     * make sure it is a new file of ours, never one planted there. */
    snprintf(o->tmp, sizeof o->tmp, "%s.partial.%ld", path, (long)getpid());
    int fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
        int e = errno;
        fprintf(stderr, "%s: %s: cannot create the temporary file %s: %s%s\n", prog, path,
                o->tmp, strerror(e), e == EEXIST ? " (refusing to replace or follow it)" : "");
        o->tmp[0] = '\0';
        return false;
    }
    o->f = fdopen(fd, "w");
    if (o->f == NULL) {
        int e = errno;
        (void)close(fd);
        (void)unlink(o->tmp);
        fprintf(stderr, "%s: %s: cannot write: %s\n", prog, path, strerror(e));
        return false;
    }
    live_add(o->tmp);
    return true;
}

bool out_finish(out_file *o) {
    if (o->f == NULL) {
        return true;
    }
    errno = 0;
    bool ok = fflush(o->f) == 0 && !ferror(o->f);
    ok = ok && fsync(fileno(o->f)) == 0;
    int e = errno;
    ok = (fclose(o->f) == 0) && ok;
    e = (e != 0) ? e : errno;
    o->f = NULL;
    if (!ok) {
        fprintf(stderr, "%s: %s: cannot write: %s\n", prog, o->path,
                strerror(e != 0 ? e : EIO));
        out_abort(o);
        return false;
    }
    o->finished = true;
    return true;
}

bool out_commit(out_file *o) {
    if (!o->finished) {
        return true;
    }
    o->finished = false;
    if (rename(o->tmp, o->path) != 0) {
        fprintf(stderr, "%s: %s: cannot write: %s\n", prog, o->path, strerror(errno));
        (void)unlink(o->tmp);
        live_remove(o->tmp);
        o->tmp[0] = '\0';
        return false;
    }
    live_remove(o->tmp);
    o->tmp[0] = '\0';
    return true;
}

void out_abort(out_file *o) {
    if (o->f != NULL) {
        (void)fclose(o->f);
        o->f = NULL;
    }
    if (o->tmp[0] != '\0') {
        (void)unlink(o->tmp);
        live_remove(o->tmp);
        o->tmp[0] = '\0';
    }
    o->finished = false;
}

bool out_stdout_ok(void) {
    errno = 0;
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "%s: standard output: write error: %s\n", prog,
                strerror(errno != 0 ? errno : EIO));
        return false;
    }
    return true;
}

/*
 * A QEMU TCG plugin that counts, exactly and deterministically, the guest
 * instructions each invocation of a piece of firmware executes: the tick
 * handlers, the background step, a model's step. Build it with the host
 * compiler (gcc -shared -fPIC) and load it with
 *
 *   qemu-system-arm ... -plugin qemu_insn_plugin.so,out=FILE,region=SPEC,...
 *
 * Arguments (no commas inside values):
 *   out=FILE                       where the counts go (default: stderr)
 *   region=NAME:KIND:ENTRY:EXITS   a piece of code, by address (hex):
 *                                  ENTRY its first instruction, EXITS its
 *                                  return instructions separated by '/';
 *                                  KIND isr (an exception handler: what it
 *                                  executes is not counted in the code it
 *                                  preempted) or call (a function: counted
 *                                  in its caller too)
 *   mark=NAME:MARK:ADDR            classifies NAME's invocations by whether
 *                                  they executed ADDR (at most 3 marks each)
 *
 * Every instruction adds one to a global count (an inline add, cheap); the
 * entry, exit and mark instructions call back instead and keep a stack of
 * active invocations, which is how preemption and nesting are accounted.
 * The file then has, per region and per class of marks:
 *   stat NAME[.MARK...] count C min A max B sum S
 * and "total N" (every instruction of the run) and "errors N" (exits with
 * no matching entry: a region whose exits were not all given).
 *
 * The plugin API is declared here, the few functions this file uses, as
 * QEMU 7.2 defines them (plugin API version 1); no QEMU header is needed.
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- The QEMU plugin API (include/qemu/qemu-plugin.h, version 1) ------- */

typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS = 0 };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 = 0 };
typedef void (*qemu_plugin_tb_trans_cb)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_insn_cb)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_exit_cb)(qemu_plugin_id_t id, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_tb_trans_cb cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn, qemu_plugin_insn_cb cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_exit_cb cb, void *userdata);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;
__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                              const void *info, int argc,
                                                              char **argv);

/* ---- Regions, marks and the invocation stack --------------------------- */

#define MAX_REGIONS 16
#define MAX_MARKS 3
#define MAX_POINTS 128
#define MAX_DEPTH 32
#define MAX_NAME 48

typedef struct {
    uint64_t count, min, max, sum;
} stat;

typedef struct {
    char name[MAX_NAME];
    bool isr;
    char mark_name[MAX_MARKS][MAX_NAME];
    int n_marks;
    stat by_class[1 << MAX_MARKS];
} region;

typedef enum { POINT_ENTRY, POINT_EXIT, POINT_MARK } point_kind;

/* An address with something to do when it executes. */
typedef struct {
    uint64_t addr;
    point_kind kind;
    int region;
    int mark;
} point;

typedef struct {
    int region;
    uint64_t start;  /* instruction count at entry */
    uint64_t hidden; /* instructions of preempting handlers since entry */
    unsigned marks;
} frame;

static region regions[MAX_REGIONS];
static int n_regions;
static point points[MAX_POINTS];
static int n_points;
static frame stack[MAX_DEPTH];
static int depth;
static uint64_t n_insns;
static uint64_t n_errors;
static char out_path[4096];

static void record(int r, unsigned cls, uint64_t n) {
    stat *s = &regions[r].by_class[cls];
    if (s->count == 0 || n < s->min) {
        s->min = n;
    }
    if (n > s->max) {
        s->max = n;
    }
    s->count++;
    s->sum += n;
}

static void enter(int r) {
    if (depth >= MAX_DEPTH) {
        n_errors++;
        return;
    }
    stack[depth++] = (frame){r, n_insns, 0, 0u};
}

/* Ends the innermost invocation of region r; frames above it had no exit seen. */
static void leave(int r) {
    int k = depth - 1;
    while (k >= 0 && stack[k].region != r) {
        k--;
    }
    if (k < 0) {
        n_errors++;
        return;
    }
    if (k != depth - 1) {
        n_errors++;
    }
    frame f = stack[k];
    depth = k;
    uint64_t inclusive = n_insns - f.start;
    record(r, f.marks, inclusive - f.hidden);
    if (regions[r].isr) {
        /* Hidden from the frames it preempted, down to the handler it
         * preempted: that one's own count includes this one's, and passes
         * it on to the frames below when it ends. */
        for (int i = depth - 1; i >= 0; i--) {
            stack[i].hidden += inclusive;
            if (regions[stack[i].region].isr) {
                break;
            }
        }
    }
}

static void mark(int r, int m) {
    for (int k = depth - 1; k >= 0; k--) {
        if (stack[k].region == r) {
            stack[k].marks |= 1u << m;
            return;
        }
    }
}

/* The callback of an address with points: entries, then the instruction, then exits. */
static void on_point(unsigned int vcpu, void *userdata) {
    (void)vcpu;
    uint64_t addr = *(const uint64_t *)userdata;
    for (int i = 0; i < n_points; i++) {
        if (points[i].addr == addr && points[i].kind == POINT_ENTRY) {
            enter(points[i].region);
        } else if (points[i].addr == addr && points[i].kind == POINT_MARK) {
            mark(points[i].region, points[i].mark);
        }
    }
    n_insns++;
    for (int i = 0; i < n_points; i++) {
        if (points[i].addr == addr && points[i].kind == POINT_EXIT) {
            leave(points[i].region);
        }
    }
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb) {
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t addr = qemu_plugin_insn_vaddr(insn);
        const point *p = NULL;
        for (int k = 0; k < n_points && p == NULL; k++) {
            p = (points[k].addr == addr) ? &points[k] : NULL;
        }
        if (p != NULL) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_point, QEMU_PLUGIN_CB_NO_REGS,
                                                   (void *)&p->addr);
        } else {
            qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                       &n_insns, 1);
        }
    }
}

/* ---- Output ------------------------------------------------------------- */

static void write_stat(FILE *f, const char *name, const stat *s) {
    fprintf(f, "stat %s count %" PRIu64 " min %" PRIu64 " max %" PRIu64 " sum %" PRIu64 "\n",
            name, s->count, s->min, s->max, s->sum);
}

static void on_exit_qemu(qemu_plugin_id_t id, void *userdata) {
    (void)id;
    (void)userdata;
    FILE *f = out_path[0] ? fopen(out_path, "w") : stderr;
    if (f == NULL) {
        fprintf(stderr, "qemu_insn_plugin: %s: cannot write\n", out_path);
        return;
    }
    for (int r = 0; r < n_regions; r++) {
        const region *g = &regions[r];
        stat all = {0, 0, 0, 0};
        for (unsigned c = 0; c < (1u << g->n_marks); c++) {
            const stat *s = &g->by_class[c];
            if (s->count == 0) {
                continue;
            }
            all.min = (all.count == 0 || s->min < all.min) ? s->min : all.min;
            all.max = s->max > all.max ? s->max : all.max;
            all.count += s->count;
            all.sum += s->sum;
            if (g->n_marks > 0) {
                char name[MAX_NAME * (MAX_MARKS + 1) + 8];
                int len = snprintf(name, sizeof name, "%s", g->name);
                if (c == 0) {
                    len += snprintf(name + len, sizeof name - (size_t)len, ".step_only");
                }
                for (int m = 0; m < g->n_marks; m++) {
                    if (c & (1u << m)) {
                        len += snprintf(name + len, sizeof name - (size_t)len, ".%s",
                                        g->mark_name[m]);
                    }
                }
                write_stat(f, name, s);
            }
        }
        write_stat(f, g->name, &all);
    }
    fprintf(f, "total %" PRIu64 "\nerrors %" PRIu64 "\n", n_insns, n_errors + (uint64_t)depth);
    if (f != stderr) {
        fclose(f);
    }
}

/* ---- Arguments ---------------------------------------------------------- */

static int find_region(const char *name) {
    for (int r = 0; r < n_regions; r++) {
        if (strcmp(regions[r].name, name) == 0) {
            return r;
        }
    }
    return -1;
}

static bool add_point(uint64_t addr, point_kind kind, int r, int m) {
    if (n_points >= MAX_POINTS) {
        return false;
    }
    points[n_points++] = (point){addr & ~(uint64_t)1, kind, r, m};
    return true;
}

/* Splits s at the separator into at most n fields, in place. */
static int split(char *s, char sep, char **fields, int n) {
    int k = 0;
    while (k < n) {
        fields[k++] = s;
        char *p = strchr(s, sep);
        if (p == NULL) {
            break;
        }
        *p = '\0';
        s = p + 1;
    }
    return k;
}

static bool parse_region(char *spec) {
    char *f[4];
    if (split(spec, ':', f, 4) != 4 || n_regions >= MAX_REGIONS || strlen(f[0]) >= MAX_NAME ||
        (strcmp(f[1], "isr") != 0 && strcmp(f[1], "call") != 0) || find_region(f[0]) >= 0) {
        return false;
    }
    int r = n_regions++;
    snprintf(regions[r].name, MAX_NAME, "%s", f[0]);
    regions[r].isr = strcmp(f[1], "isr") == 0;
    if (!add_point(strtoull(f[2], NULL, 16), POINT_ENTRY, r, 0)) {
        return false;
    }
    char *exits[32];
    int n = split(f[3], '/', exits, 32);
    for (int i = 0; i < n; i++) {
        if (exits[i][0] == '\0' || !add_point(strtoull(exits[i], NULL, 16), POINT_EXIT, r, 0)) {
            return false;
        }
    }
    return true;
}

static bool parse_mark(char *spec) {
    char *f[3];
    if (split(spec, ':', f, 3) != 3) {
        return false;
    }
    int r = find_region(f[0]);
    if (r < 0 || regions[r].n_marks >= MAX_MARKS || strlen(f[1]) >= MAX_NAME) {
        return false;
    }
    int m = regions[r].n_marks++;
    snprintf(regions[r].mark_name[m], MAX_NAME, "%s", f[1]);
    return add_point(strtoull(f[2], NULL, 16), POINT_MARK, r, m);
}

int qemu_plugin_install(qemu_plugin_id_t id, const void *info, int argc, char **argv) {
    (void)info;
    for (int i = 0; i < argc; i++) {
        char *arg = argv[i];
        bool ok = false;
        if (strncmp(arg, "out=", 4) == 0 && strlen(arg + 4) < sizeof out_path) {
            snprintf(out_path, sizeof out_path, "%s", arg + 4);
            ok = true;
        } else if (strncmp(arg, "region=", 7) == 0) {
            ok = parse_region(arg + 7);
        } else if (strncmp(arg, "mark=", 5) == 0) {
            ok = parse_mark(arg + 5);
        }
        if (!ok) {
            fprintf(stderr, "qemu_insn_plugin: bad argument '%s'\n", argv[i]);
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, on_exit_qemu, NULL);
    return 0;
}

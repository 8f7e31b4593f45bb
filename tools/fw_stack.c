/*
 * fw_stack: the worst-case stack of a Cortex-M image, from the compiler's
 * per-function frame sizes (-fstack-usage, the .su files) and the call
 * graph of the linked code (arm-none-eabi-objdump -d on stdin).
 *
 *   arm-none-eabi-objdump -d --no-show-raw-insn IMAGE.elf |
 *       fw_stack [--frame N] [--call CALLER=CALLEE]... ROOT... -- FILE.su...
 *
 * Each ROOT is an execution level that can preempt the ones before it
 * (thread mode's Reset_Handler, then the exception handlers in increasing
 * priority). The worst case is the sum of each level's deepest call chain
 * plus N bytes of exception frame per preempting level: on a core with an
 * FPU, 104 bytes with the floating-point context and 4 of alignment.
 * Functions without a .su entry (the compiler's support library) are sized
 * from their code: every push, vpush and sub from sp, summed. Indirect
 * calls must be named with --call; an unnamed one, a recursion or a frame
 * of dynamic size is an error, since the worst case would then be unknown.
 *
 * Output, one line per root and a total:
 *   stack ROOT BYTES: ROOT > callee > ...
 *   stack worst BYTES
 * Exit status 0, or 1 when the worst case is unknown, 2 on bad usage.
 */
#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_FUNCS 4096
#define MAX_EDGES 32768
#define MAX_NAME 128

typedef struct {
    char name[MAX_NAME];
    unsigned long addr;
    long code_frame;   /* bytes from the code's pushes and sub sp */
    long su_frame;     /* bytes from the .su files, -1 when absent */
    bool su_dynamic;
    bool indirect;     /* makes a call through a register */
    int first_edge, n_edges;
    int state;         /* 0 new, 1 on the current path, 2 done */
    long depth;        /* deepest chain from here (bytes) */
    int next;          /* the callee on that chain, or -1 */
} func;

static func funcs[MAX_FUNCS];
static int n_funcs;
static unsigned long edge_addr[MAX_EDGES];
static bool edge_tail[MAX_EDGES];
static int edge_from[MAX_EDGES];
static int edge_to[MAX_EDGES];
static int n_edges;
static bool unknown;

/* Copies a name, cut to MAX_NAME - 1 characters. */
static void copy_name(char *dst, const char *src) {
    size_t n = strlen(src);
    n = n < MAX_NAME - 1 ? n : MAX_NAME - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static int find_func(const char *name) {
    for (int i = 0; i < n_funcs; i++) {
        if (strcmp(funcs[i].name, name) == 0) {
            return i;
        }
    }
    return -1;
}

/* The name a .su file gives a compiler clone: "f.constprop.0" is listed as "f.constprop". */
static void su_key(const char *name, char *key) {
    copy_name(key, name);
    char *dot = strrchr(key, '.');
    if (dot != NULL && dot[1] != '\0' && strspn(dot + 1, "0123456789") == strlen(dot + 1)) {
        *dot = '\0';
    }
}

/* Registers in a list such as "{r4, r5, lr}" or "{d8-d15}", weighted by their size. */
static long reglist_bytes(const char *s) {
    const char *open = strchr(s, '{');
    long bytes = 0;
    for (const char *p = open ? open + 1 : s; *p != '\0' && *p != '}';) {
        while (*p == ' ' || *p == ',') {
            p++;
        }
        char kind = *p;
        int a = 0, b = 0;
        if ((kind == 'd' || kind == 's') && sscanf(p + 1, "%d-%*c%d", &a, &b) == 2) {
            bytes += (long)(b - a + 1) * (kind == 'd' ? 8 : 4);
        } else if (*p != '\0' && *p != '}') {
            bytes += (kind == 'd' && isdigit((unsigned char)p[1])) ? 8 : 4;
        }
        while (*p != '\0' && *p != ',' && *p != '}') {
            p++;
        }
    }
    return bytes;
}

static bool is_cond(const char *s) {
    static const char *const conds[] = {"",   "eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl",
                                        "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le", "al"};
    for (size_t i = 0; i < sizeof conds / sizeof conds[0]; i++) {
        if (strcmp(s, conds[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* A call (or, when tail, a branch that may leave the function) to an address. */
static void add_edge(int from, unsigned long addr, bool tail) {
    if (n_edges >= MAX_EDGES) {
        fprintf(stderr, "fw_stack: too many calls\n");
        exit(2);
    }
    edge_from[n_edges] = from;
    edge_addr[n_edges] = addr;
    edge_tail[n_edges] = tail;
    n_edges++;
}

/* The target address of a direct branch ("1234 <name+0x12>"); false for a register. */
static bool target_address(const char *ops, unsigned long *addr) {
    char *end = NULL;
    *addr = strtoul(ops, &end, 16);
    return end != ops && strchr(ops, '<') != NULL;
}

/* The function whose code holds addr (functions are in address order), or -1. */
static int func_at(unsigned long addr) {
    int lo = 0, hi = n_funcs - 1, found = -1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (funcs[mid].addr <= addr) {
            found = mid;
            lo = mid + 1;
        } else {
            hi = mid - 1;
        }
    }
    return found;
}

static void instruction(int f, const char *mn, const char *ops) {
    char m[32];
    snprintf(m, sizeof m, "%s", mn);
    char *suffix = strstr(m, ".n");
    if (suffix == NULL) {
        suffix = strstr(m, ".w");
    }
    if (suffix != NULL && suffix[2] == '\0') {
        *suffix = '\0';
    }
    unsigned long target = 0;
    if (strcmp(m, "push") == 0 || strcmp(m, "vpush") == 0 ||
        (strncmp(m, "stmdb", 5) == 0 && strncmp(ops, "sp!", 3) == 0)) {
        funcs[f].code_frame += reglist_bytes(ops);
    } else if ((strcmp(m, "sub") == 0 || strcmp(m, "subw") == 0) && strncmp(ops, "sp,", 3) == 0) {
        const char *hash = strchr(ops, '#');
        if (hash != NULL) {
            funcs[f].code_frame += strtol(hash + 1, NULL, 0);
        } else {
            funcs[f].su_dynamic = true; /* sub sp by a register: a variable frame */
        }
    } else if (strcmp(m, "bl") == 0 || strcmp(m, "blx") == 0) {
        if (target_address(ops, &target)) {
            add_edge(f, target, false);
        } else {
            funcs[f].indirect = true;
        }
    } else if (strncmp(m, "bx", 2) == 0 && is_cond(m + 2)) {
        if (strncmp(ops, "lr", 2) != 0) {
            funcs[f].indirect = true; /* a jump through a register other than the return */
        }
    } else if (m[0] == 'b' && is_cond(m + 1)) {
        if (target_address(ops, &target)) {
            add_edge(f, target, true);
        }
    }
}

static void read_disassembly(FILE *in) {
    char line[1024];
    int cur = -1;
    while (fgets(line, sizeof line, in) != NULL) {
        unsigned long addr;
        char name[MAX_NAME];
        if (sscanf(line, "%lx <%127[^>]>:", &addr, name) == 2 && line[0] != ' ') {
            if (n_funcs >= MAX_FUNCS) {
                fprintf(stderr, "fw_stack: too many functions\n");
                exit(2);
            }
            cur = n_funcs++;
            funcs[cur] = (func){{0}, addr, 0, -1, false, false, 0, 0, 0, 0, -1};
            copy_name(funcs[cur].name, name);
            continue;
        }
        char *colon = strchr(line, ':');
        if (cur < 0 || line[0] != ' ' || colon == NULL || colon[1] != '\t') {
            continue;
        }
        char mn[32] = {0};
        char ops[512] = {0};
        if (sscanf(colon + 2, "%31s %511[^\n]", mn, ops) >= 1) {
            instruction(cur, mn, ops);
        }
    }
}

static void read_su(const char *path) {
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "fw_stack: %s: cannot open\n", path);
        exit(2);
    }
    char line[1024];
    while (fgets(line, sizeof line, f) != NULL) {
        char *tab = strchr(line, '\t');
        if (tab == NULL) {
            continue;
        }
        *tab = '\0';
        char *name = strrchr(line, ':');
        long bytes = strtol(tab + 1, NULL, 10);
        bool dynamic = strstr(tab + 1, "dynamic") != NULL && strstr(tab + 1, "bounded") == NULL;
        for (int i = 0; name != NULL && i < n_funcs; i++) {
            char key[MAX_NAME];
            su_key(funcs[i].name, key);
            if (strcmp(key, name + 1) == 0) {
                funcs[i].su_frame = funcs[i].su_frame > bytes ? funcs[i].su_frame : bytes;
                funcs[i].su_dynamic = funcs[i].su_dynamic || dynamic;
            }
        }
    }
    fclose(f);
}

/*
 * Resolves the edges to functions and groups them by caller. A branch
 * inside the caller's own code is not an edge; one that leaves it is a
 * tail call, as deep as a call.
 */
static void link_edges(void) {
    static int order[MAX_EDGES];
    int k = 0;
    for (int f = 0; f < n_funcs; f++) {
        funcs[f].first_edge = k;
        for (int e = 0; e < n_edges; e++) {
            if (edge_from[e] != f) {
                continue;
            }
            int to = func_at(edge_addr[e]);
            if (edge_tail[e] && to == f) {
                continue;
            }
            if (to < 0) {
                fprintf(stderr, "fw_stack: %s branches to 0x%lx, outside every function\n",
                        funcs[f].name, edge_addr[e]);
                unknown = true;
                continue;
            }
            /* The support library's routines share code: a jump into the middle of
             * another one counts as a call of all of it (an upper bound). */
            order[k++] = to;
        }
        funcs[f].n_edges = k - funcs[f].first_edge;
    }
    memcpy(edge_to, order, sizeof order);
}

static long frame_of(const func *f) { return f->su_frame >= 0 ? f->su_frame : f->code_frame; }

static long depth(int f) {
    func *fn = &funcs[f];
    if (fn->state == 2) {
        return fn->depth;
    }
    if (fn->state == 1) {
        fprintf(stderr, "fw_stack: recursion through %s: no bound\n", fn->name);
        unknown = true;
        return 0;
    }
    fn->state = 1;
    if (fn->su_dynamic) {
        fprintf(stderr, "fw_stack: %s has a frame of dynamic size\n", fn->name);
        unknown = true;
    }
    if (fn->indirect) {
        fprintf(stderr, "fw_stack: %s calls through a pointer: name the callees with --call\n",
                fn->name);
        unknown = true;
    }
    long best = 0;
    for (int e = fn->first_edge; e < fn->first_edge + fn->n_edges; e++) {
        long d = depth(edge_to[e]);
        if (fn->next < 0 || d > best) {
            best = d;
            fn->next = edge_to[e];
        }
    }
    fn->depth = frame_of(fn) + best;
    fn->state = 2;
    return fn->depth;
}

static void print_chain(int f) {
    for (int i = f, guard = 0; i >= 0 && guard < 64; i = funcs[i].next, guard++) {
        printf("%s%s(%ld)", i == f ? "" : " > ", funcs[i].name, frame_of(&funcs[i]));
    }
    printf("\n");
}

int main(int argc, char **argv) {
    long frame = 36;
    const char *roots[16];
    int n_roots = 0;
    const char *calls[64];
    int n_calls = 0;
    int i = 1;
    for (; i < argc && strcmp(argv[i], "--") != 0; i++) {
        if (strcmp(argv[i], "--frame") == 0 && i + 1 < argc) {
            frame = strtol(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--call") == 0 && i + 1 < argc && n_calls < 64) {
            calls[n_calls++] = argv[++i];
        } else if (argv[i][0] != '-' && n_roots < 16) {
            roots[n_roots++] = argv[i];
        } else {
            fprintf(stderr, "usage: objdump -d IMAGE | fw_stack [--frame N] [--call A=B]... "
                            "ROOT... -- FILE.su...\n");
            return 2;
        }
    }
    read_disassembly(stdin);
    for (i++; i < argc; i++) {
        read_su(argv[i]);
    }
    for (int c = 0; c < n_calls; c++) {
        char from[MAX_NAME];
        const char *eq = strchr(calls[c], '=');
        int f = -1;
        if (eq != NULL && eq - calls[c] < MAX_NAME) {
            snprintf(from, (size_t)(eq - calls[c]) + 1u, "%s", calls[c]);
            f = find_func(from);
        }
        if (f < 0) {
            fprintf(stderr, "fw_stack: --call %s: no such caller\n", calls[c]);
            return 2;
        }
        int to = find_func(eq + 1);
        if (to < 0) {
            fprintf(stderr, "fw_stack: --call %s: no such callee\n", calls[c]);
            return 2;
        }
        add_edge(f, funcs[to].addr, false);
        funcs[f].indirect = false;
    }
    link_edges();
    long total = 0;
    for (int r = 0; r < n_roots; r++) {
        int f = find_func(roots[r]);
        if (f < 0) {
            fprintf(stderr, "fw_stack: root %s is not in the image\n", roots[r]);
            return 2;
        }
        long d = depth(f);
        total += d + (r > 0 ? frame : 0);
        printf("stack %s %ld: ", roots[r], d);
        print_chain(f);
    }
    printf("stack worst %ld\n", total);
    return unknown ? 1 : 0;
}

/*
 * fmu_import: a test master for the FMU (docs/cosimulation.md). It loads
 * the FMU the way an importing tool does: from the unzipped folder it
 * reads modelDescription.xml (the value references by name, the GUID, the
 * capability flags), checks the rules of the standard a master relies on,
 * opens binaries/linux64/<modelIdentifier>.so with dlopen() and runs the
 * FMI 2.0 calling sequence. It plays a scenario's commands at the
 * communication points (the zig-zag rule closed through the heading
 * output, as a master closes a loop) and checks that the outputs are the
 * desk simulator's CSV figures of the same run, as text at 17 digits.
 *
 *   fmu_import FMU_DIR SCENARIO DESK_CSV
 *
 * Checks: the description's rules (unique names and value references,
 * legal causality/variability/initial combinations, start values where
 * required and only there, units and types declared, the model structure
 * lists the outputs); the run against the desk at a step of one slow frame
 * and at variable steps of several; two instances in one process, stepped
 * in turn with different inputs, each as if alone; fmi2Reset; saving and
 * restoring the FMU state; a step that is not a whole number of frames and
 * a wrong communication point refused with fmi2Error and a logged reason.
 * Prints "N passed, N failed" last.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2.h"
#include "csv_out.h"
#include "scenario.h"

static int passed, failed;

static void check(int ok, const char *what, ...) __attribute__((format(printf, 2, 3)));
static void check(int ok, const char *what, ...) {
    va_list ap;
    va_start(ap, what);
    printf("%s: ", ok ? "ok  " : "FAIL");
    vprintf(what, ap);
    printf("\n");
    va_end(ap);
    if (ok) {
        passed++;
    } else {
        failed++;
    }
}

static char *read_file(const char *path, size_t *n_out) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return NULL;
    }
    size_t cap = 1u << 16;
    size_t n = 0;
    char *buf = malloc(cap + 1u);
    size_t got;
    while (buf != NULL && (got = fread(buf + n, 1, cap - n, f)) > 0u) {
        n += got;
        if (n == cap) {
            cap *= 2u;
            char *b = realloc(buf, cap + 1u);
            if (b == NULL) {
                free(buf);
                buf = NULL;
            }
            buf = b;
        }
    }
    fclose(f);
    if (buf != NULL) {
        buf[n] = '\0';
    }
    if (n_out != NULL) {
        *n_out = n;
    }
    return buf;
}

/* ---- The model description ------------------------------------------------ */

#define MAX_VARS 256

typedef struct {
    char name[64];
    unsigned vr;
    char causality[24], variability[24], initial[24];
    char type[16];     /* Real, Integer, Boolean, String, Enumeration */
    char unit[16], declared[32];
    int has_start;
    double start;
} md_var;

typedef struct {
    char guid[64], identifier[64], variable_step[8], get_set_state[8];
    md_var v[MAX_VARS];
    int n;
    char *text;
} model_desc;

/* The value of attribute `name` in the tag that starts at tag (up to its '>'). */
static int attr(const char *tag, const char *name, char *out, size_t cap) {
    const char *end = strchr(tag, '>');
    size_t len = strlen(name);
    out[0] = '\0';
    for (const char *a = tag + 1; end != NULL && a < end; a++) {
        int starts = a[-1] == ' ' || a[-1] == '\n';
        if (starts && strncmp(a, name, len) == 0 && a[len] == '=' && a[len + 1] == '"') {
            const char *v = a + len + 2;
            const char *q = strchr(v, '"');
            size_t n = (size_t)(q - v) < cap - 1u ? (size_t)(q - v) : cap - 1u;
            memcpy(out, v, n);
            out[n] = '\0';
            return 1;
        }
    }
    return 0;
}

static int parse_description(const char *path, model_desc *md) {
    md->text = read_file(path, NULL);
    if (md->text == NULL) {
        return 0;
    }
    const char *root = strstr(md->text, "<fmiModelDescription");
    const char *cs = strstr(md->text, "<CoSimulation");
    if (root == NULL || cs == NULL) {
        return 0;
    }
    attr(root, "guid", md->guid, sizeof md->guid);
    attr(cs, "modelIdentifier", md->identifier, sizeof md->identifier);
    attr(cs, "canHandleVariableCommunicationStepSize", md->variable_step,
         sizeof md->variable_step);
    attr(cs, "canGetAndSetFMUstate", md->get_set_state, sizeof md->get_set_state);
    md->n = 0;
    for (const char *p = strstr(md->text, "<ScalarVariable "); p != NULL && md->n < MAX_VARS;
         p = strstr(p + 1, "<ScalarVariable ")) {
        md_var *v = &md->v[md->n++];
        char buf[64];
        attr(p, "name", v->name, sizeof v->name);
        attr(p, "valueReference", buf, sizeof buf);
        v->vr = (unsigned)strtoul(buf, NULL, 10);
        if (!attr(p, "causality", v->causality, sizeof v->causality)) {
            strcpy(v->causality, "local");
        }
        if (!attr(p, "variability", v->variability, sizeof v->variability)) {
            strcpy(v->variability, "continuous");
        }
        attr(p, "initial", v->initial, sizeof v->initial);
        const char *t = strchr(strchr(p, '>'), '<') + 1;
        size_t k = 0;
        while (t[k] != ' ' && t[k] != '/' && t[k] != '>' && k < sizeof v->type - 1u) {
            v->type[k] = t[k];
            k++;
        }
        v->type[k] = '\0';
        attr(t, "unit", v->unit, sizeof v->unit);
        attr(t, "declaredType", v->declared, sizeof v->declared);
        v->has_start = attr(t, "start", buf, sizeof buf);
        v->start = strtod(buf, NULL);
    }
    return 1;
}

static const md_var *var_named(const model_desc *md, const char *name) {
    for (int k = 0; k < md->n; k++) {
        if (strcmp(md->v[k].name, name) == 0) {
            return &md->v[k];
        }
    }
    return NULL;
}

/* The combinations of causality and variability the standard allows (FMI 2.0, 2.2.7). */
static int legal_combination(const md_var *v) {
    const char *c = v->causality;
    const char *x = v->variability;
    if (strcmp(x, "constant") == 0) {
        return strcmp(c, "output") == 0 || strcmp(c, "local") == 0;
    }
    if (strcmp(c, "parameter") == 0 || strcmp(c, "calculatedParameter") == 0) {
        return strcmp(x, "fixed") == 0 || strcmp(x, "tunable") == 0;
    }
    if (strcmp(c, "input") == 0 || strcmp(c, "output") == 0) {
        return strcmp(x, "discrete") == 0 || strcmp(x, "continuous") == 0;
    }
    if (strcmp(c, "independent") == 0) {
        return strcmp(x, "continuous") == 0;
    }
    return strcmp(c, "local") == 0;
}

/* The initial attribute, as given or as the standard's default for the combination. */
static const char *initial_of(const md_var *v) {
    if (v->initial[0] != '\0') {
        return v->initial;
    }
    if (strcmp(v->causality, "input") == 0 || strcmp(v->causality, "independent") == 0) {
        return "";
    }
    if (strcmp(v->variability, "constant") == 0 || strcmp(v->causality, "parameter") == 0) {
        return "exact";
    }
    return "calculated";
}

static void check_description(const model_desc *md) {
    int dup_names = 0, dup_vr = 0, bad_combo = 0, bad_start = 0, bad_cont = 0, bad_unit = 0;
    int bad_type = 0, bad_initial = 0;
    for (int i = 0; i < md->n; i++) {
        const md_var *v = &md->v[i];
        for (int j = 0; j < i; j++) {
            dup_names += strcmp(md->v[j].name, v->name) == 0;
            dup_vr += md->v[j].vr == v->vr;
        }
        bad_combo += !legal_combination(v);
        const char *init = initial_of(v);
        int needs_start = strcmp(v->causality, "input") == 0 || strcmp(init, "exact") == 0 ||
                          strcmp(init, "approx") == 0;
        bad_start += needs_start != v->has_start;
        bad_initial += strcmp(v->causality, "input") == 0 && v->initial[0] != '\0';
        bad_initial += strcmp(v->causality, "parameter") == 0 && strcmp(init, "exact") != 0;
        bad_cont += strcmp(v->variability, "continuous") == 0 && strcmp(v->type, "Real") != 0;
        if (v->unit[0] != '\0') {
            char pat[48];
            snprintf(pat, sizeof pat, "<Unit name=\"%s\"", v->unit);
            bad_unit += strstr(md->text, pat) == NULL;
        }
        if (strcmp(v->type, "Enumeration") == 0) {
            char pat[64];
            snprintf(pat, sizeof pat, "<SimpleType name=\"%s\"", v->declared);
            bad_type += v->declared[0] == '\0' || strstr(md->text, pat) == NULL;
        }
    }
    check(md->n > 0, "the description has %d variables", md->n);
    check(dup_names == 0, "variable names unique (%d duplicates)", dup_names);
    check(dup_vr == 0, "value references unique (%d duplicates)", dup_vr);
    check(bad_combo == 0, "causality/variability combinations legal (%d not)", bad_combo);
    check(bad_initial == 0, "initial attributes legal for their causality (%d not)",
          bad_initial);
    check(bad_start == 0, "start values on inputs and exact/approx variables only (%d wrong)",
          bad_start);
    check(bad_cont == 0, "only Real variables are continuous (%d not)", bad_cont);
    check(bad_unit == 0, "every unit used is defined (%d not)", bad_unit);
    check(bad_type == 0, "every enumeration's declared type is defined (%d not)", bad_type);
    /* ModelStructure/Outputs: exactly the outputs, by their 1-based index. */
    const char *outs = strstr(md->text, "<Outputs>");
    const char *outs_end = outs != NULL ? strstr(outs, "</Outputs>") : NULL;
    int listed = 0, missing = 0;
    for (int i = 0; i < md->n; i++) {
        if (strcmp(md->v[i].causality, "output") != 0) {
            continue;
        }
        char pat[40];
        snprintf(pat, sizeof pat, "<Unknown index=\"%d\"", i + 1);
        const char *hit = outs != NULL ? strstr(outs, pat) : NULL;
        missing += hit == NULL || hit > outs_end;
        listed++;
    }
    int unknowns = 0;
    for (const char *p = outs; p != NULL && p < outs_end; p = strstr(p + 1, "<Unknown ")) {
        unknowns += p != outs;
    }
    check(outs != NULL && missing == 0 && unknowns == listed,
          "ModelStructure lists the %d outputs (%d missing, %d listed)", listed, missing,
          unknowns);
    check(strcmp(md->variable_step, "true") == 0,
          "canHandleVariableCommunicationStepSize is declared true");
}

/* ---- The FMU's functions --------------------------------------------------- */

typedef struct {
    void *lib;
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter_init;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2DoStepTYPE *do_step;
    fmi2GetRealTYPE *get_real;
    fmi2SetRealTYPE *set_real;
    fmi2GetIntegerTYPE *get_integer;
    fmi2SetIntegerTYPE *set_integer;
    fmi2GetStringTYPE *get_string;
    fmi2ResetTYPE *reset;
    fmi2TerminateTYPE *terminate;
    fmi2GetFMUstateTYPE *get_state;
    fmi2SetFMUstateTYPE *set_state;
    fmi2FreeFMUstateTYPE *free_state;
    fmi2GetVersionTYPE *version;
    fmi2GetTypesPlatformTYPE *platform;
} fmu_api;

static int load(fmu_api *f, const char *so) {
    f->lib = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (f->lib == NULL) {
        printf("dlopen %s: %s\n", so, dlerror());
        return 0;
    }
    /* POSIX: a function pointer may be read through the object pointer dlsym returns. */
#define SYM(field, name)                                                                         \
    do {                                                                                         \
        void *p_ = dlsym(f->lib, name);                                                          \
        if (p_ == NULL) {                                                                        \
            printf("dlsym %s: missing\n", name);                                                 \
            return 0;                                                                            \
        }                                                                                        \
        memcpy(&f->field, &p_, sizeof p_);                                                       \
    } while (0)
    SYM(instantiate, "fmi2Instantiate");
    SYM(free_instance, "fmi2FreeInstance");
    SYM(setup, "fmi2SetupExperiment");
    SYM(enter_init, "fmi2EnterInitializationMode");
    SYM(exit_init, "fmi2ExitInitializationMode");
    SYM(do_step, "fmi2DoStep");
    SYM(get_real, "fmi2GetReal");
    SYM(set_real, "fmi2SetReal");
    SYM(get_integer, "fmi2GetInteger");
    SYM(set_integer, "fmi2SetInteger");
    SYM(get_string, "fmi2GetString");
    SYM(reset, "fmi2Reset");
    SYM(terminate, "fmi2Terminate");
    SYM(get_state, "fmi2GetFMUstate");
    SYM(set_state, "fmi2SetFMUstate");
    SYM(free_state, "fmi2FreeFMUstate");
    SYM(version, "fmi2GetVersion");
    SYM(platform, "fmi2GetTypesPlatform");
#undef SYM
    return 1;
}

/* The logger keeps the last error message of each instance for the checks. */
static char last_error[700];
static int log_lines;

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)env;
    char text[512];
    va_list ap;
    va_start(ap, message);
    vsnprintf(text, sizeof text, message, ap);
    va_end(ap);
    log_lines++;
    if (status >= fmi2Error) {
        snprintf(last_error, sizeof last_error, "%s [%s]: %s", instance, category, text);
    }
}

static void *alloc_memory(size_t n, size_t size) { return calloc(n, size); }

static const fmi2CallbackFunctions callbacks = {logger, alloc_memory, free, NULL, NULL};

/* ---- The master --------------------------------------------------------- */

/* The desk CSV's columns the FMU outputs (by the FMU's variable names). */
#define MAX_COLS 48
#define MAX_ROWS 4096

typedef struct {
    int n_cols;
    char names[MAX_COLS][64];
    unsigned vr[MAX_COLS];
    int is_int[MAX_COLS];
    int csv_col[MAX_COLS]; /* column in the desk CSV */
} column_map;

typedef struct {
    int n_rows;
    char *rows[MAX_ROWS]; /* the CSV rows, fields NUL-separated */
    int n_fields;
} desk_csv;

static int load_csv(const char *path, desk_csv *d, char header[][32], int *n_header) {
    char *text = read_file(path, NULL);
    if (text == NULL) {
        return 0;
    }
    char *line = strtok(text, "\n");
    int h = 0;
    for (char *f = line; f != NULL && h < MAX_COLS; h++) {
        char *comma = strchr(f, ',');
        size_t n = comma != NULL ? (size_t)(comma - f) : strlen(f);
        snprintf(header[h], 32, "%.*s", (int)n, f);
        f = comma != NULL ? comma + 1 : NULL;
    }
    *n_header = h;
    d->n_rows = 0;
    while ((line = strtok(NULL, "\n")) != NULL && d->n_rows < MAX_ROWS) {
        d->rows[d->n_rows++] = line;
    }
    return 1;
}

/* Field k of a CSV row (copied into out). */
static void field(const char *row, int k, char *out, size_t cap) {
    const char *p = row;
    for (int i = 0; i < k && p != NULL; i++) {
        p = strchr(p, ',');
        p = p != NULL ? p + 1 : NULL;
    }
    if (p == NULL) {
        out[0] = '\0';
        return;
    }
    size_t n = strcspn(p, ",");
    n = n < cap - 1u ? n : cap - 1u;
    memcpy(out, p, n);
    out[n] = '\0';
}

/* The master's view of one run: the scenario's commands played at the communication points. */
typedef struct {
    const scenario *scn;
    size_t next;          /* next event to play */
    double zz_rudder, zz_psi0;
    unsigned vr_psi;
    double bias_rpm;      /* added to every shaft speed command (0: the scenario as it is) */
    int ap;               /* the holds the master has on (the FMU's autopilot input) */
} player;

static unsigned vr_autopilot; /* the description's "autopilot" input */

static fmi2Status set1(const fmu_api *f, fmi2Component c, unsigned vr, double x) {
    return f->set_real(c, &vr, 1u, &x);
}

/*
 * The commands due at communication point t: the scenario's events up to t
 * (as the executive applies them at a slow boundary), then the zig-zag
 * rule on the heading output, which this master closes.
 */
static void play(const fmu_api *f, fmi2Component c, player *p, double t) {
    const scenario *s = p->scn;
    while (p->next < s->n_events && s->events[p->next].t_s <= t + 1e-10) {
        const scenario_event *ev = &s->events[p->next++];
        double x = ev->value + (ev->command == SCN_N_RPM ? p->bias_rpm : 0.0);
        int ap = p->ap;
        if (ev->command == SCN_AUTOPILOT) {
            /* Both holds off, their fins amidships. */
            ap = 0;
            (void)set1(f, c, 1u + SCN_RUDDER, 0.0);
            (void)set1(f, c, 1u + SCN_STERN, 0.0);
        } else {
            /* A set point turns its hold on; a manual rudder or stern command takes it off. */
            (void)set1(f, c, 1u + ev->command, x);
            ap = ev->command == SCN_HEADING ? ap | 1 : ev->command == SCN_DEPTH ? ap | 2 : ap;
            ap = ev->command == SCN_RUDDER ? ap & ~1 : ev->command == SCN_STERN ? ap & ~2 : ap;
        }
        if (ap != p->ap) {
            p->ap = ap;
            (void)f->set_integer(c, &vr_autopilot, 1u, &ap);
        }
    }
    const scenario_zigzag *z = &s->zigzag;
    int on = z->enabled && t >= z->start_s - 1e-9 && (z->stop_s < 0.0 || t < z->stop_s);
    if (!on) {
        if (p->zz_rudder != 0.0) {
            p->zz_rudder = 0.0;
            (void)set1(f, c, 1u + SCN_RUDDER, 0.0);
        }
        return;
    }
    double psi;
    (void)f->get_real(c, &p->vr_psi, 1u, &psi);
    double turned = psi - p->zz_psi0;
    if (p->zz_rudder == 0.0) {
        p->zz_psi0 = psi;
        p->zz_rudder = z->rudder_rad;
    } else if (p->zz_rudder > 0.0 ? turned <= -z->heading_rad : turned >= z->heading_rad) {
        p->zz_rudder = -p->zz_rudder;
    }
    (void)set1(f, c, 1u + SCN_RUDDER, p->zz_rudder);
}

/* The outputs as the desk writes them (csv_format_number, integers as %u), joined by commas. */
static void output_row(const fmu_api *f, fmi2Component c, const column_map *m, char *out,
                       size_t cap) {
    size_t n = 0;
    out[0] = '\0';
    for (int k = 0; k < m->n_cols; k++) {
        char v[40];
        if (m->is_int[k]) {
            fmi2Integer i = 0;
            (void)f->get_integer(c, &m->vr[k], 1u, &i);
            snprintf(v, sizeof v, "%u", (unsigned)i);
        } else {
            double x = 0.0;
            (void)f->get_real(c, &m->vr[k], 1u, &x);
            csv_format_number(v, sizeof v, x);
        }
        n += (size_t)snprintf(out + n, cap - n, "%s%s", k ? "," : "", v);
    }
}

static void desk_row(const desk_csv *d, int r, const column_map *m, char *out, size_t cap) {
    size_t n = 0;
    out[0] = '\0';
    for (int k = 0; k < m->n_cols; k++) {
        char v[40];
        field(d->rows[r], m->csv_col[k], v, sizeof v);
        n += (size_t)snprintf(out + n, cap - n, "%s%s", k ? "," : "", v);
    }
}

static fmi2Component start(const fmu_api *f, const model_desc *md, const char *name,
                           double stop) {
    fmi2Component c = f->instantiate(name, fmi2CoSimulation, md->guid, "file:///nonexistent",
                                     &callbacks, fmi2False, fmi2False);
    if (c == NULL) {
        return NULL;
    }
    if (f->setup(c, fmi2False, 0.0, 0.0, fmi2True, stop) != fmi2OK ||
        f->enter_init(c) != fmi2OK) {
        f->free_instance(c);
        return NULL;
    }
    return c;
}

/* Back to t = 0 after an error: fmi2Reset and initialisation again. */
static void restart(const fmu_api *f, fmi2Component c, double stop) {
    (void)f->reset(c);
    (void)f->setup(c, fmi2False, 0.0, 0.0, fmi2True, stop);
    (void)f->enter_init(c);
    (void)f->exit_init(c);
    last_error[0] = '\0';
}

/* Row mismatches of a run against the desk: the first is described in first[]. */
typedef struct {
    int rows, bad;
    char first[600];
} compare;

static void compare_row(compare *cmp, const fmu_api *f, fmi2Component c, const column_map *m,
                        const desk_csv *d, int row) {
    char got[2048], want[2048];
    output_row(f, c, m, got, sizeof got);
    desk_row(d, row, m, want, sizeof want);
    cmp->rows++;
    if (strcmp(got, want) != 0) {
        if (cmp->bad++ == 0) {
            snprintf(cmp->first, sizeof cmp->first, "row %d: fmu %.250s / desk %.250s", row,
                     got, want);
        }
    }
}

/*
 * Runs to `rows` records after t = 0, with the steps (in slow frames)
 * cycling through steps[], comparing every communication point's outputs
 * with the desk's row at that instant.
 */
static int run_compare(const fmu_api *f, fmi2Component c, player *p, const column_map *m,
                       const desk_csv *d, int rows, const int *steps, int n_steps,
                       compare *cmp, double frame) {
    play(f, c, p, 0.0);
    if (f->exit_init(c) != fmi2OK) {
        return 0;
    }
    compare_row(cmp, f, c, m, d, 0);
    int k = 0;
    for (int i = 0; k < rows; i++) {
        int n = steps[i % n_steps];
        n = (k + n > rows) ? rows - k : n;
        double t = (double)k * frame;
        if (f->do_step(c, t, (double)n * frame, fmi2True) != fmi2OK) {
            printf("doStep at %g s: %s\n", t, last_error);
            return 0;
        }
        k += n;
        compare_row(cmp, f, c, m, d, k);
        play(f, c, p, (double)k * frame);
    }
    return 1;
}

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: fmu_import FMU_DIR SCENARIO DESK_CSV\n");
        return 2;
    }
    const char *dir = argv[1];
    char path[4096];
    static model_desc md;
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    if (!parse_description(path, &md)) {
        printf("%s: cannot read the model description\n0 passed, 1 failed\n", path);
        return 1;
    }
    check_description(&md);

    static scenario scn;
    size_t n_text;
    char *text = read_file(argv[2], &n_text);
    scenario_error err;
    if (text == NULL || !scenario_parse(&scn, text, n_text, &err)) {
        printf("%s: cannot read the scenario\n0 passed, 1 failed\n", argv[2]);
        return 1;
    }
    static desk_csv desk;
    static char header[MAX_COLS][32];
    int n_header = 0;
    if (!load_csv(argv[3], &desk, header, &n_header)) {
        printf("%s: cannot read the desk CSV\n0 passed, 1 failed\n", argv[3]);
        return 1;
    }
    /* The desk's columns that are FMU outputs, by name (v_dc is the DC link). */
    static column_map m;
    for (int h = 0; h < n_header; h++) {
        const md_var *v = var_named(&md, header[h]);
        if (v != NULL && strcmp(v->causality, "output") == 0) {
            snprintf(m.names[m.n_cols], sizeof m.names[0], "%s", v->name);
            m.vr[m.n_cols] = v->vr;
            m.is_int[m.n_cols] = strcmp(v->type, "Real") != 0;
            m.csv_col[m.n_cols++] = h;
        }
    }
    int outputs = 0;
    for (int k = 0; k < md.n; k++) {
        outputs += strcmp(md.v[k].causality, "output") == 0;
    }
    check(m.n_cols == outputs && outputs >= 25,
          "every output of the FMU (%d) is a column of the desk CSV (%d found)", outputs,
          m.n_cols);

    fmu_api f;
    snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", dir, md.identifier);
    if (!load(&f, path)) {
        printf("%d passed, %d failed\n", passed, failed + 1);
        return 1;
    }
    check(strcmp(f.version(), "2.0") == 0 && strcmp(f.platform(), "default") == 0,
          "fmi2GetVersion %s, fmi2GetTypesPlatform %s", f.version(), f.platform());
    const md_var *frame_var = var_named(&md, "slow_frame_s");
    const md_var *psi = var_named(&md, "psi_rad");
    const md_var *ap_var = var_named(&md, "autopilot");
    if (frame_var == NULL || psi == NULL || ap_var == NULL) {
        check(0, "the description has slow_frame_s, psi_rad and autopilot");
        printf("%d passed, %d failed\n", passed, failed);
        return 1;
    }
    const double frame = frame_var->start;
    vr_autopilot = ap_var->vr;
    const int rows = desk.n_rows - 1;
    const double stop = (double)rows * frame;

    /* 1. The whole run, one slow frame per step. */
    fmi2Component a = start(&f, &md, "a", stop);
    check(a != NULL, "fmi2Instantiate with the description's GUID");
    if (a == NULL) {
        printf("%d passed, %d failed\n", passed, failed);
        return 1;
    }
    fmi2String build = NULL;
    unsigned vr_build = var_named(&md, "build")->vr;
    (void)f.get_string(a, &vr_build, 1u, &build);
    printf("build: %s, %d records of %d outputs, %.17g s\n", build, rows + 1, m.n_cols, stop);
    player pa = {&scn, 0u, 0.0, 0.0, psi->vr, 0.0, 0};
    compare c1 = {0, 0, ""};
    const int one[] = {1};
    int ok = run_compare(&f, a, &pa, &m, &desk, rows, one, 1, &c1, frame);
    check(ok && c1.bad == 0 && c1.rows == rows + 1,
          "steps of one slow frame: %d records, %d differ from the desk's CSV %s", c1.rows,
          c1.bad, c1.first);
    double t_end = 0.0;
    fmi2Status past = f.do_step(a, stop, frame, fmi2True);
    check(past == fmi2Error && strstr(last_error, "stop time") != NULL,
          "a step past the stop time: fmi2Error, logged: %s", last_error);
    (void)t_end;
    f.free_instance(a);

    /* 2. Variable steps of several frames, to the first zig-zag command. */
    int var_rows = rows;
    if (scn.zigzag.enabled) {
        var_rows = (int)(scn.zigzag.start_s / frame + 0.5);
        var_rows = var_rows < rows ? var_rows : rows;
    }
    a = start(&f, &md, "a2", stop);
    player pv = {&scn, 0u, 0.0, 0.0, psi->vr, 0.0, 0};
    compare c2 = {0, 0, ""};
    const int steps[] = {10, 5, 5, 20, 10}; /* lands on every event of the default mission */
    ok = a != NULL && run_compare(&f, a, &pv, &m, &desk, var_rows, steps, 5, &c2, frame);
    check(ok && c2.bad == 0, "variable steps of 5 to 20 frames to %g s: %d records, %d differ %s",
          (double)var_rows * frame, c2.rows, c2.bad, c2.first);
    if (a != NULL) {
        f.free_instance(a);
    }

    /* 3. Two instances in one process, stepped in turn: b with another shaft speed. */
    int short_rows = rows - 20 < 300 ? rows - 20 : 300; /* and 20 frames more (4.) */
    a = start(&f, &md, "a3", stop);
    fmi2Component b = start(&f, &md, "b3", stop);
    check(a != NULL && b != NULL && a != b, "two instances in one process");
    if (a != NULL && b != NULL) {
        player p1 = {&scn, 0u, 0.0, 0.0, psi->vr, 0.0, 0};
        player p2 = {&scn, 0u, 0.0, 0.0, psi->vr, 150.0, 0};
        compare ca = {0, 0, ""};
        compare cb = {0, 0, ""};
        play(&f, a, &p1, 0.0);
        play(&f, b, &p2, 0.0);
        int ok3 = f.exit_init(a) == fmi2OK && f.exit_init(b) == fmi2OK;
        for (int k = 0; ok3 && k < short_rows; k++) {
            double t = (double)k * frame;
            ok3 = f.do_step(a, t, frame, fmi2True) == fmi2OK &&
                  f.do_step(b, t, frame, fmi2True) == fmi2OK;
            compare_row(&ca, &f, a, &m, &desk, k + 1);
            compare_row(&cb, &f, b, &m, &desk, k + 1);
            play(&f, a, &p1, t + frame);
            play(&f, b, &p2, t + frame);
        }
        check(ok3 && ca.bad == 0, "instance a beside b: %d records, %d differ from the desk %s",
              ca.rows, ca.bad, ca.first);
        check(ok3 && cb.bad > short_rows / 2,
              "instance b (shaft command +150 rpm) differs from a: %d of %d records", cb.bad,
              cb.rows);

        /* 4. The FMU state: saved, run on, restored, run on again: the same records. */
        fmi2FMUstate saved = NULL;
        double t0 = (double)short_rows * frame;
        int ok4 = f.get_state(b, &saved) == fmi2OK;
        unsigned vr_u = var_named(&md, "u_mps")->vr;
        double u1 = 0.0, u2 = 1.0;
        ok4 = ok4 && f.do_step(b, t0, 20.0 * frame, fmi2True) == fmi2OK &&
              f.get_real(b, &vr_u, 1u, &u1) == fmi2OK;
        ok4 = ok4 && f.set_state(b, saved) == fmi2OK &&
              f.do_step(b, t0, 20.0 * frame, fmi2False) == fmi2OK &&
              f.get_real(b, &vr_u, 1u, &u2) == fmi2OK;
        check(ok4 && memcmp(&u1, &u2, sizeof u1) == 0,
              "fmi2GetFMUstate/SetFMUstate: the run repeats from the saved state (u %.17g, "
              "%.17g)", u1, u2);
        check(f.set_state(a, saved) == fmi2Error,
              "a state of instance b is refused by instance a: %s", last_error);
        (void)f.free_state(b, &saved);

        /* 5. fmi2Reset, then the start of the run again. */
        int ok5 = f.reset(a) == fmi2OK && f.setup(a, fmi2False, 0.0, 0.0, fmi2True, stop) ==
                  fmi2OK && f.enter_init(a) == fmi2OK;
        player pr = {&scn, 0u, 0.0, 0.0, psi->vr, 0.0, 0};
        compare cr = {0, 0, ""};
        ok5 = ok5 && run_compare(&f, a, &pr, &m, &desk, 20, one, 1, &cr, frame);
        check(ok5 && cr.bad == 0, "after fmi2Reset: %d records, %d differ %s", cr.rows, cr.bad,
              cr.first);

        /* 6. Steps the FMU cannot take: fmi2Error and a logged reason. */
        last_error[0] = '\0';
        double t6 = 20.0 * frame;
        fmi2Status s6 = f.do_step(a, t6, 1.5 * frame, fmi2True);
        check(s6 == fmi2Error && strstr(last_error, "whole number of slow frames") != NULL,
              "a step of 1.5 frames: fmi2Error, logged: %s", last_error);
        restart(&f, a, stop);
        s6 = f.do_step(a, 0.0, 0.5 * frame, fmi2True);
        check(s6 == fmi2Error && strstr(last_error, "whole number of slow frames") != NULL,
              "a step of half a frame: fmi2Error, logged: %s", last_error);
        restart(&f, a, stop);
        s6 = f.do_step(a, 3.0 * frame, frame, fmi2True);
        check(s6 == fmi2Error && strstr(last_error, "communication point") != NULL,
              "a step from the wrong communication point: fmi2Error, logged: %s", last_error);
        last_error[0] = '\0';
        fmi2Component bad = f.instantiate("bad", fmi2CoSimulation, "{not-this-fmu}", "",
                                          &callbacks, fmi2False, fmi2False);
        check(bad == NULL && strstr(last_error, "GUID") != NULL,
              "a wrong GUID: no instance, logged: %s", last_error);
        double nan_value = NAN;
        unsigned vr_n = 1u + SCN_N_RPM;
        check(f.set_real(b, &vr_n, 1u, &nan_value) == fmi2Error,
              "a NaN input: fmi2Error, logged: %s", last_error);
        (void)f.terminate(b);
    }
    if (a != NULL) {
        f.free_instance(a);
    }
    if (b != NULL) {
        f.free_instance(b);
    }
    printf("%d messages logged\n", log_lines);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}

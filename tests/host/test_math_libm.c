/*
 * Host test of the freestanding math library (src/math) against the C
 * library: every function is swept densely over its main ranges, at random
 * points over the whole format and at special values, and its error is
 * measured in units in the last place (ulp) of the exact result.
 *
 * References: for the double functions the long double functions of libm
 * (64-bit significand, so the measured error is exact to about 2^-11 ulp);
 * for the float functions the double functions of libm. sqrt, fmod and the
 * rounding functions must equal libm bit for bit. For each function the
 * program prints the number of points, the worst error and where it occurs,
 * the share of results identical to libm's own function, and checks the
 * worst error against the bound documented in docs/math.md. Special values
 * (zeros, infinities, NaN, extremes) must give libm's zero, infinity or NaN
 * exactly (NaN as the canonical quiet NaN) and be within the bound otherwise.
 *
 * Usage: test_math_libm [--exhaustive]
 * --exhaustive also runs every float function on all 2^32 floats (minutes).
 * The last line is "N passed, N failed"; the exit status is 1 on a failure.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "math/umath.h"

/* INFINITY and NAN are float constants; the double ones avoid implicit promotion. */
#define INF64 ((double)INFINITY)
#define NAN64 ((double)NAN)

/* ---- statistics ----------------------------------------------------------- */

typedef struct {
    const char *name;
    double bound; /* [ulp] worst error allowed */
    long points;
    long same;    /* results bit-identical to libm's function of the same type */
    double worst; /* [ulp] */
    double worst_x;
    double worst_y;
    long special_bad; /* special values with the wrong zero, infinity or NaN */
} stat_t;

static unsigned g_passed;
static unsigned g_failed;
static clock_t g_last_report;

static void stat_init(stat_t *s, const char *name, double bound) {
    memset(s, 0, sizeof *s);
    s->name = name;
    s->bound = bound;
}

static void stat_note(stat_t *s, double err, double x, double y, int same) {
    s->points++;
    s->same += same ? 1 : 0;
    if (err > s->worst || err != err) {
        s->worst = (err != err) ? INF64 : err;
        s->worst_x = x;
        s->worst_y = y;
    }
}

static void stat_report(const stat_t *s, int two_args) {
    int ok = s->worst <= s->bound && s->special_bad == 0;
    char where[96];
    if (s->worst == 0.0) {
        snprintf(where, sizeof where, "-");
    } else if (two_args) {
        snprintf(where, sizeof where, "(%a, %a)", s->worst_x, s->worst_y);
    } else {
        snprintf(where, sizeof where, "%a", s->worst_x);
    }
    clock_t now = clock();
    printf("%-12s %9ld pts  worst %6.3f ulp (bound %.2f) at %-42s same as libm %6.2f%%  "
           "%4.1fs  %s\n",
           s->name, s->points, s->worst, s->bound, where,
           100.0 * (double)s->same / (double)(s->points > 0 ? s->points : 1),
           (double)(now - g_last_report) / CLOCKS_PER_SEC, ok ? "ok" : "FAIL");
    g_last_report = now;
    if (s->special_bad != 0) {
        printf("             %ld special values with the wrong zero, infinity or NaN\n",
               s->special_bad);
    }
    if (ok) {
        g_passed++;
    } else {
        g_failed++;
    }
}

/* ---- error measures ------------------------------------------------------- */

static uint64_t bits64(double x) {
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static uint32_t bits32(float x) {
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

/* Error of a double result in ulp of the exact result ref (ulp of ref's binade). */
static double err_f64(double got, long double ref) {
    double r = (double)ref;
    if (isnan(r) || isnan(got)) {
        return (isnan(r) && isnan(got)) ? 0.0 : INF64;
    }
    if (isinf(r) || isinf(got)) {
        return (got == r) ? 0.0 : INF64;
    }
    if (ref == 0.0L) {
        return (got == 0.0) ? 0.0 : INF64;
    }
    int e;
    (void)frexpl(fabsl(ref), &e);
    long double u = ldexpl(1.0L, e - 53);
    if (u < 0x1p-1074L) {
        u = 0x1p-1074L;
    }
    return (double)(fabsl((long double)got - ref) / u);
}

static double err_f32(float got, double ref) {
    float r = (float)ref;
    if (isnan(r) || isnan(got)) {
        return (isnan(r) && isnan(got)) ? 0.0 : INF64;
    }
    if (isinf(r) || isinf(got)) {
        return (got == r) ? 0.0 : INF64;
    }
    if (ref == 0.0) {
        return (got == 0.0f) ? 0.0 : INF64;
    }
    int e;
    (void)frexp(fabs(ref), &e);
    double u = ldexp(1.0, e - 24);
    if (u < 0x1p-149) {
        u = 0x1p-149;
    }
    return fabs((double)got - ref) / u;
}

static int same64(double a, double b) { return bits64(a) == bits64(b) || (isnan(a) && isnan(b)); }

static int same32(float a, float b) { return bits32(a) == bits32(b) || (isnan(a) && isnan(b)); }

/*
 * A special value is right when a NaN, zero or infinity of libm is matched
 * exactly (NaN: the canonical quiet NaN) and any other value is in bound.
 */
static int special_ok_f64(double got, double libm_val, double err, double bound) {
    if (isnan(libm_val)) {
        return bits64(got) == 0x7ff8000000000000u;
    }
    if (libm_val == 0.0 || isinf(libm_val)) {
        return bits64(got) == bits64(libm_val);
    }
    return err <= bound;
}

static int special_ok_f32(float got, float libm_val, double err, double bound) {
    if (isnan(libm_val)) {
        return bits32(got) == 0x7fc00000u;
    }
    if (libm_val == 0.0f || isinf(libm_val)) {
        return bits32(got) == bits32(libm_val);
    }
    return err <= bound;
}

/* ---- random numbers ------------------------------------------------------- */

static uint64_t g_rng = 0x9e3779b97f4a7c15u;

static uint64_t rnd64(void) { /* xorshift64* */
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return g_rng * 2685821657736338717u;
}

static double rnd_unit(void) { return (double)(rnd64() >> 11) * 0x1p-53; }

static double rnd_range(double lo, double hi) { return lo + (hi - lo) * rnd_unit(); }

/* |x| log-uniform in [2^e0, 2^e1), random sign when signed. */
static double rnd_log(int e0, int e1, int is_signed) {
    double m = 1.0 + rnd_unit();
    int e = e0 + (int)(rnd64() % (uint64_t)(e1 - e0));
    double x = ldexp(m, e);
    return (is_signed && (rnd64() & 1u)) ? -x : x;
}

/* ---- one-argument double functions ---------------------------------------- */

typedef double (*fn64_t)(double);
typedef long double (*ref64_t)(long double);
typedef float (*fn32_t)(float);
typedef double (*ref32_t)(double);

typedef struct {
    stat_t st;
    fn64_t ours;
    fn64_t libm;
    ref64_t ref;
} unary64_t;

static void probe64(unary64_t *u, double x) {
    double got = u->ours(x);
    stat_note(&u->st, err_f64(got, u->ref((long double)x)), x, 0.0, same64(got, u->libm(x)));
}

/* n points in [lo, hi], stratified: one random point per sub-interval. */
static void sweep64(unary64_t *u, double lo, double hi, long n) {
    double step = (hi - lo) / (double)n;
    for (long i = 0; i < n; i++) {
        probe64(u, lo + step * ((double)i + rnd_unit()));
    }
}

static void sweep64_log(unary64_t *u, int e0, int e1, int is_signed, long n) {
    for (long i = 0; i < n; i++) {
        probe64(u, rnd_log(e0, e1, is_signed));
    }
}

static const double SPECIALS64[] = {
    0.0,
    -0.0,
    INF64,
    -INF64,
    NAN64,
    -NAN64,
    DBL_MIN,
    -DBL_MIN,
    0x1p-1074,
    -0x1p-1074,
    DBL_MAX,
    -DBL_MAX,
    1.0,
    -1.0,
    0.5,
    -0.5,
    2.0,
    1e-300,
    -1e-300,
    1e300,
    -1e300,
    0x1.921fb54442d18p+0,
    0x1.921fb54442d18p+1,
    0x1.921fb54442d18p+2,
    1e22,
    0x1p1023,
    709.782712893384,
    709.79,
    -745.1332191019411,
    -745.14,
    -708.4,
    1.0 - 0x1p-53,
    1.0 + 0x1p-52,
    0x1.6ac5b262ca1ffp+849,
    1e5,
    -1e5,
    0x1.8p20,
    3.0,
    0x1p-27,
    0x1p-28,
};
#define N_SPECIALS64 (sizeof SPECIALS64 / sizeof SPECIALS64[0])

static void specials64(unary64_t *u) {
    for (size_t i = 0; i < N_SPECIALS64; i++) {
        double x = SPECIALS64[i];
        double got = u->ours(x);
        double err = err_f64(got, u->ref((long double)x));
        if (!special_ok_f64(got, u->libm(x), err, u->st.bound)) {
            u->st.special_bad++;
            printf("  %s(%a) = %a, libm %a\n", u->st.name, x, got, u->libm(x));
        }
    }
}

static long double ref_wrapl(long double x) { return atan2l(sinl(x), cosl(x)); }
static double ref_wrap(double x) { return (double)ref_wrapl((long double)x); }

static void run_unary64(void) {
    unary64_t u;

    /* sin, cos, tan: main range, moderate range, every magnitude, near k*pi/2. */
    struct {
        const char *name;
        fn64_t ours;
        fn64_t libm;
        ref64_t ref;
        double bound;
    } trig[] = {
        {"sin_f64", math_sin_f64, sin, sinl, 1.0},
        {"cos_f64", math_cos_f64, cos, cosl, 1.0},
        {"tan_f64", math_tan_f64, tan, tanl, 1.5},
    };
    for (size_t k = 0; k < 3; k++) {
        stat_init(&u.st, trig[k].name, trig[k].bound);
        u.ours = trig[k].ours;
        u.libm = trig[k].libm;
        u.ref = trig[k].ref;
        sweep64(&u, -2.0 * MATH_PI_F64, 2.0 * MATH_PI_F64, 1500000);
        sweep64(&u, -1e5, 1e5, 500000);
        sweep64_log(&u, -30, 1024, 1, 300000);
        for (long i = 1; i <= 100000; i++) {
            /* The doubles next to k*pi/2 leave the smallest reduced arguments. */
            double x = (double)i * 0x1.921fb54442d18p+0;
            probe64(&u, x);
            probe64(&u, nextafter(x, 0.0));
            probe64(&u, -nextafter(x, INF64));
        }
        specials64(&u);
        stat_report(&u.st, 0);
    }

    stat_init(&u.st, "wrap_pi_f64", 1.0);
    u.ours = math_wrap_pi_f64;
    u.libm = ref_wrap;
    u.ref = ref_wrapl;
    sweep64(&u, -1e4, 1e4, 400000);
    sweep64_log(&u, 2, 20, 1, 200000);
    stat_report(&u.st, 0);

    stat_init(&u.st, "atan_f64", 1.0);
    u.ours = math_atan_f64;
    u.libm = atan;
    u.ref = atanl;
    sweep64(&u, -4.0, 4.0, 1000000);
    sweep64_log(&u, -40, 70, 1, 1000000);
    specials64(&u);
    stat_report(&u.st, 0);

    stat_init(&u.st, "asin_f64", 1.0);
    u.ours = math_asin_f64;
    u.libm = asin;
    u.ref = asinl;
    sweep64(&u, -1.0, 1.0, 1000000);
    for (long i = 0; i < 300000; i++) {
        probe64(&u, 1.0 - rnd_log(-53, -1, 0)); /* near +-1 */
        probe64(&u, -1.0 + rnd_log(-53, -1, 0));
    }
    specials64(&u);
    stat_report(&u.st, 0);

    stat_init(&u.st, "acos_f64", 1.0);
    u.ours = math_acos_f64;
    u.libm = acos;
    u.ref = acosl;
    sweep64(&u, -1.0, 1.0, 1000000);
    for (long i = 0; i < 300000; i++) {
        probe64(&u, 1.0 - rnd_log(-53, -1, 0));
        probe64(&u, -1.0 + rnd_log(-53, -1, 0));
    }
    specials64(&u);
    stat_report(&u.st, 0);

    stat_init(&u.st, "exp_f64", 1.0);
    u.ours = math_exp_f64;
    u.libm = exp;
    u.ref = expl;
    sweep64(&u, -708.0, 709.78, 1500000);
    sweep64(&u, -1.0, 1.0, 500000);
    sweep64(&u, -745.13, -708.0, 200000); /* subnormal results */
    specials64(&u);
    stat_report(&u.st, 0);

    stat_init(&u.st, "log_f64", 1.0);
    u.ours = math_log_f64;
    u.libm = log;
    u.ref = logl;
    sweep64_log(&u, -1074, 1024, 0, 1000000);
    sweep64(&u, 0.5, 2.0, 1000000);
    for (long i = 0; i < 300000; i++) {
        probe64(&u, 1.0 + rnd_log(-53, -4, 1)); /* near 1 */
    }
    specials64(&u);
    stat_report(&u.st, 0);
}

/* ---- two-argument double functions ---------------------------------------- */

static void probe_atan2(stat_t *s, double y, double x) {
    double got = math_atan2_f64(y, x);
    stat_note(s, err_f64(got, atan2l((long double)y, (long double)x)), y, x,
              same64(got, atan2(y, x)));
}

static void probe_pow(stat_t *s, double x, double y) {
    double got = math_pow_f64(x, y);
    stat_note(s, err_f64(got, powl((long double)x, (long double)y)), x, y, same64(got, pow(x, y)));
}

static void specials2(stat_t *s, double (*ours)(double, double), double (*libm)(double, double),
                      long double (*ref)(long double, long double)) {
    for (size_t i = 0; i < N_SPECIALS64; i++) {
        for (size_t j = 0; j < N_SPECIALS64; j++) {
            double a = SPECIALS64[i];
            double b = SPECIALS64[j];
            double got = ours(a, b);
            double lv = libm(a, b);
            if (!special_ok_f64(got, lv, err_f64(got, ref((long double)a, (long double)b)),
                                s->bound)) {
                s->special_bad++;
                printf("  %s(%a, %a) = %a, libm %a\n", s->name, a, b, got, lv);
            }
        }
    }
}

static void run_binary64(void) {
    stat_t s;
    stat_init(&s, "atan2_f64", 1.0);
    for (long i = 0; i < 1000000; i++) {
        double t = rnd_range(-MATH_PI_F64, MATH_PI_F64);
        double r = rnd_log(-20, 20, 0);
        probe_atan2(&s, r * sin(t), r * cos(t));
    }
    for (long i = 0; i < 500000; i++) {
        probe_atan2(&s, rnd_log(-1074, 1024, 1), rnd_log(-1074, 1024, 1));
    }
    specials2(&s, math_atan2_f64, atan2, atan2l);
    stat_report(&s, 1);

    stat_init(&s, "pow_f64", 1.0);
    for (long i = 0; i < 800000; i++) {
        probe_pow(&s, rnd_log(-30, 30, 0), rnd_range(-30.0, 30.0));
    }
    for (long i = 0; i < 300000; i++) {
        /* Battery-like: ratios near 1 with exponents near 1 (Peukert). */
        probe_pow(&s, rnd_range(0.01, 10.0), rnd_range(0.8, 1.5));
    }
    for (long i = 0; i < 300000; i++) {
        /* Near 1 with large exponents, results over the whole range. */
        double x = 1.0 + rnd_log(-40, -2, 1);
        probe_pow(&s, x, rnd_range(-700.0, 700.0) / log(x));
    }
    for (long i = 0; i < 100000; i++) {
        probe_pow(&s, -rnd_log(-8, 8, 0), (double)(int)rnd_range(-60.0, 60.0));
    }
    specials2(&s, math_pow_f64, pow, powl);
    stat_report(&s, 1);
}

/* ---- exact functions ------------------------------------------------------ */

static double rnd_any64(void) {
    uint64_t u = rnd64();
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static float rnd_any32(void) {
    uint32_t u = (uint32_t)(rnd64() >> 32);
    float x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static void run_exact(void) {
    stat_t s;
    stat_init(&s, "sqrt_f64", 0.0);
    for (long i = 0; i < 3000000; i++) {
        double x = fabs(rnd_any64());
        double got = math_sqrt_f64(x);
        stat_note(&s, same64(got, sqrt(x)) ? 0.0 : INF64, x, 0.0, same64(got, sqrt(x)));
    }
    for (long i = 0; i < 1000000; i++) {
        /* Squares and their neighbours: the rounding is hardest next to exact roots. */
        double r = rnd_range(1.0, 0x1p26);
        double x = nextafter(r * r, (i & 1) ? INF64 : 0.0);
        stat_note(&s, same64(math_sqrt_f64(x), sqrt(x)) ? 0.0 : INF64, x, 0.0, 1);
    }
    for (size_t i = 0; i < N_SPECIALS64; i++) {
        double x = SPECIALS64[i];
        double got = math_sqrt_f64(x);
        s.special_bad +=
            special_ok_f64(got, sqrt(x), same64(got, sqrt(x)) ? 0.0 : 1.0, 0.0) ? 0 : 1;
    }
    stat_report(&s, 0);

    stat_init(&s, "sqrt_f32", 0.0);
    /* Every float in [1, 4) (every significand, both exponent parities) and every subnormal. */
    for (uint32_t u = 0x3f800000u; u < 0x40800000u; u++) {
        float x;
        memcpy(&x, &u, sizeof x);
        float got = math_sqrt_f32(x);
        int same = same32(got, sqrtf(x));
        stat_note(&s, same ? 0.0 : INF64, (double)x, 0.0, same);
    }
    for (uint32_t u = 1u; u < 0x00800000u; u++) {
        float x;
        memcpy(&x, &u, sizeof x);
        int same = same32(math_sqrt_f32(x), sqrtf(x));
        stat_note(&s, same ? 0.0 : INF64, (double)x, 0.0, same);
    }
    stat_report(&s, 0);

    stat_init(&s, "fmod_f64", 0.0);
    for (long i = 0; i < 1000000; i++) {
        double x = (i % 3 == 0) ? rnd_any64() : rnd_log(-30, 60, 1);
        double y = (i % 3 == 0) ? rnd_any64() : rnd_log(-30, 30, 1);
        double got = math_fmod_f64(x, y);
        int same = same64(got, fmod(x, y)) && (!isnan(got) || bits64(got) == 0x7ff8000000000000u);
        stat_note(&s, same ? 0.0 : INF64, x, y, same);
    }
    stat_report(&s, 1);

    stat_init(&s, "fmod_f32", 0.0);
    for (long i = 0; i < 1000000; i++) {
        float x = (i % 3 == 0) ? rnd_any32() : (float)rnd_log(-20, 40, 1);
        float y = (i % 3 == 0) ? rnd_any32() : (float)rnd_log(-20, 20, 1);
        float got = math_fmod_f32(x, y);
        int same = same32(got, fmodf(x, y)) && (!isnan(got) || bits32(got) == 0x7fc00000u);
        stat_note(&s, same ? 0.0 : INF64, (double)x, (double)y, same);
    }
    stat_report(&s, 1);

    stat_init(&s, "round_f64", 0.0);
    for (long i = 0; i < 1000000; i++) {
        double x = (i & 1) ? rnd_any64() : rnd_range(-1e6, 1e6);
        int same = same64(math_floor_f64(x), floor(x)) && same64(math_ceil_f64(x), ceil(x)) &&
                   same64(math_trunc_f64(x), trunc(x)) && same64(math_round_f64(x), round(x));
        stat_note(&s, same ? 0.0 : INF64, x, 0.0, same);
    }
    stat_report(&s, 0);

    stat_init(&s, "round_f32", 0.0);
    for (long i = 0; i < 1000000; i++) {
        float x = (i & 1) ? rnd_any32() : (float)rnd_range(-1e5, 1e5);
        int same = same32(math_floor_f32(x), floorf(x)) && same32(math_ceil_f32(x), ceilf(x)) &&
                   same32(math_trunc_f32(x), truncf(x)) && same32(math_round_f32(x), roundf(x));
        stat_note(&s, same ? 0.0 : INF64, (double)x, 0.0, same);
    }
    stat_report(&s, 0);
}

/* ---- float functions ------------------------------------------------------ */

typedef struct {
    stat_t st;
    fn32_t ours;
    fn32_t libm;
    ref32_t ref;
} unary32_t;

static void probe32(unary32_t *u, float x) {
    float got = u->ours(x);
    stat_note(&u->st, err_f32(got, u->ref((double)x)), (double)x, 0.0, same32(got, u->libm(x)));
}

static void sweep32(unary32_t *u, double lo, double hi, long n) {
    double step = (hi - lo) / (double)n;
    for (long i = 0; i < n; i++) {
        probe32(u, (float)(lo + step * ((double)i + rnd_unit())));
    }
}

static void sweep32_log(unary32_t *u, int e0, int e1, int is_signed, long n) {
    for (long i = 0; i < n; i++) {
        probe32(u, (float)rnd_log(e0, e1, is_signed));
    }
}

/* Every float in [lo, hi] (both positive), then their negatives when asked. */
static void sweep32_all(unary32_t *u, float lo, float hi, int both_signs) {
    uint32_t a = bits32(lo);
    uint32_t b = bits32(hi);
    for (uint32_t v = a; v <= b; v++) {
        float x;
        memcpy(&x, &v, sizeof x);
        probe32(u, x);
        if (both_signs) {
            probe32(u, -x);
        }
    }
}

static const float SPECIALS32[] = {
    0.0f,           -0.0f,     INFINITY,       -INFINITY,       NAN,      FLT_MIN,
    -FLT_MIN,       0x1p-149f, -0x1p-149f,     FLT_MAX,         -FLT_MAX, 1.0f,
    -1.0f,          0.5f,      2.0f,           1e-30f,          1e30f,    0x1.921fb6p+0f,
    0x1.921fb6p+1f, 400.0f,    0x1.2d97c8p+2f, 0x1.f9cbe2p+7f,  88.7f,    88.73f,
    -103.9f,        -104.0f,   -87.5f,         1.0f - 0x1p-24f, 0x1p-12f, 0x1p-13f,
};
#define N_SPECIALS32 (sizeof SPECIALS32 / sizeof SPECIALS32[0])

static void specials32(unary32_t *u) {
    for (size_t i = 0; i < N_SPECIALS32; i++) {
        float x = SPECIALS32[i];
        float got = u->ours(x);
        double err = err_f32(got, u->ref((double)x));
        if (!special_ok_f32(got, u->libm(x), err, u->st.bound)) {
            u->st.special_bad++;
            printf("  %s(%a) = %a, libm %a\n", u->st.name, (double)x, (double)got,
                   (double)u->libm(x));
        }
    }
}

static double ref_wrap32(double x) { return atan2(sin(x), cos(x)); }
static float libm_wrap32(float x) { return (float)ref_wrap32((double)x); }

static int g_exhaustive;

static void run_unary32(void) {
    struct {
        const char *name;
        fn32_t ours;
        fn32_t libm;
        ref32_t ref;
        double bound;
        int kind; /* 0 trig, 1 atan, 2 asin/acos, 3 exp, 4 log, 5 wrap */
    } fns[] = {
        {"sin_f32", math_sin_f32, sinf, sin, 1.0, 0},
        {"cos_f32", math_cos_f32, cosf, cos, 1.0, 0},
        {"tan_f32", math_tan_f32, tanf, tan, 1.5, 0},
        {"wrap_pi_f32", math_wrap_pi_f32, libm_wrap32, ref_wrap32, 1.0, 5},
        {"atan_f32", math_atan_f32, atanf, atan, 1.0, 1},
        {"asin_f32", math_asin_f32, asinf, asin, 1.0, 2},
        {"acos_f32", math_acos_f32, acosf, acos, 1.0, 2},
        {"exp_f32", math_exp_f32, expf, exp, 1.0, 3},
        {"log_f32", math_log_f32, logf, log, 1.0, 4},
    };
    for (size_t k = 0; k < sizeof fns / sizeof fns[0]; k++) {
        unary32_t u;
        stat_init(&u.st, fns[k].name, fns[k].bound);
        u.ours = fns[k].ours;
        u.libm = fns[k].libm;
        u.ref = fns[k].ref;
        switch (fns[k].kind) {
        case 0: /* sin, cos: every float in [pi/4, 2 pi] (odd/even symmetry is exact) */
            if (u.ours != math_tan_f32) {
                sweep32_all(&u, 0.78f, 6.2832f, 0);
            } else {
                sweep32(&u, -6.2832, 6.2832, 2000000);
            }
            sweep32(&u, -400.0, 400.0, 1000000);
            sweep32(&u, -1e5, 1e5, 500000);
            sweep32_log(&u, -20, 128, 1, 500000);
            break;
        case 1:
            sweep32(&u, -4.0, 4.0, 1000000);
            sweep32_log(&u, -30, 128, 1, 1000000);
            break;
        case 2:
            sweep32(&u, -1.0, 1.0, 2000000);
            break;
        case 3:
            sweep32(&u, -103.9, 88.72, 2000000);
            sweep32(&u, -1.0, 1.0, 500000);
            break;
        case 4:
            sweep32_log(&u, -149, 128, 0, 1000000);
            sweep32(&u, 0.5, 2.0, 1000000);
            break;
        default:
            sweep32(&u, -1000.0, 1000.0, 1000000);
            break;
        }
        if (g_exhaustive && fns[k].kind != 5) {
            sweep32_all(&u, 0x1p-149f, FLT_MAX, 1);
        }
        if (fns[k].kind != 5) {
            specials32(&u);
        }
        stat_report(&u.st, 0);
    }
}

static void probe_atan2_32(stat_t *s, float y, float x) {
    float got = math_atan2_f32(y, x);
    stat_note(s, err_f32(got, atan2((double)y, (double)x)), (double)y, (double)x,
              same32(got, atan2f(y, x)));
}

static void run_binary32(void) {
    stat_t s;
    stat_init(&s, "atan2_f32", 1.0);
    for (long i = 0; i < 1000000; i++) {
        double t = rnd_range(-MATH_PI_F64, MATH_PI_F64);
        double r = rnd_log(-20, 20, 0);
        probe_atan2_32(&s, (float)(r * sin(t)), (float)(r * cos(t)));
    }
    for (long i = 0; i < 500000; i++) {
        probe_atan2_32(&s, (float)rnd_log(-149, 128, 1), (float)rnd_log(-149, 128, 1));
    }
    for (size_t i = 0; i < N_SPECIALS32; i++) {
        for (size_t j = 0; j < N_SPECIALS32; j++) {
            float a = SPECIALS32[i];
            float b = SPECIALS32[j];
            float got = math_atan2_f32(a, b);
            float lv = atan2f(a, b);
            if (!special_ok_f32(got, lv, err_f32(got, atan2((double)a, (double)b)), s.bound)) {
                s.special_bad++;
                printf("  atan2_f32(%a, %a) = %a, libm %a\n", (double)a, (double)b, (double)got,
                       (double)lv);
            }
        }
    }
    stat_report(&s, 1);
}

int main(int argc, char **argv) {
    g_exhaustive = argc > 1 && strcmp(argv[1], "--exhaustive") == 0;
    clock_t t0 = clock();
    g_last_report = t0;
    printf("math library vs libm: worst error in ulp of the exact result\n");
    run_exact();
    run_unary64();
    run_binary64();
    run_unary32();
    run_binary32();
    printf("(%.1f s)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
    printf("%u passed, %u failed\n", g_passed, g_failed);
    return g_failed == 0u ? 0 : 1;
}

/*
 * Writes src/fixedpoint/wavetable_data.c, the quarter-turn tables of the
 * sine lookups of src/fixedpoint/wavetable.h (the triangle is computed, not
 * tabled). It builds the whole turn, checks that the rounded entries keep
 * the sine's symmetries exactly (which the lookups' unfolding relies on),
 * and writes the first quarter. It is the only way that file is made; the
 * file is committed so that the firmware build needs no host math library.
 *
 *     gen_wavetables FILE           write the tables to FILE
 *     gen_wavetables --check FILE   exit 1 if FILE differs from what would be
 *                                   written (0 if equal, 2 on a usage or I/O error);
 *                                   ends with the line "N passed, N failed" of a test
 *
 * Host program: uses libc and libm (sinl, cosl in long double).
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixedpoint/wavetable.h"

#define TABLE_LEN (WT_TABLE_SIZE + 1u)     /* knots of a whole turn */
#define QUARTER_LEN (WT_QUARTER_SIZE + 1u) /* knots written: the first quarter */
#define TEXT_CAP (256u * 1024u)
#define TIE_MARGIN 1e-6L /* least allowed distance from a rounding tie */

static const long double two_pi_l = 6.283185307179586476925286766559005768L;

static char text[TEXT_CAP];
static size_t text_len;

/*
 * sin(2 pi phase / 2^32) in long double. The phase is reduced exactly, in
 * integers, to a quadrant and an angle of at most pi/4 from the nearer axis,
 * so sinl and cosl only ever see small arguments.
 */
static long double ref_sin_turn(uint32_t phase) {
    uint32_t quadrant = phase >> 30;
    uint32_t u = phase & 0x3FFFFFFFu;
    int use_cos = (quadrant & 1u) != 0u;
    long double x;
    long double s;

    if (u > 0x20000000u) {
        u = 0x40000000u - u;
        use_cos = !use_cos;
    }
    x = two_pi_l * (long double)u / 4294967296.0L;
    s = use_cos ? cosl(x) : sinl(x);
    return (quadrant >= 2u) ? -s : s;
}

static void emit(const char *format, ...) {
    va_list args;
    int n;

    va_start(args, format);
    n = vsnprintf(text + text_len, TEXT_CAP - text_len, format, args);
    va_end(args);
    if (n < 0 || (size_t)n >= TEXT_CAP - text_len) {
        fprintf(stderr, "gen_wavetables: output buffer too small\n");
        exit(2);
    }
    text_len += (size_t)n;
}

/* Distance of v from the nearest tie of rounding to an integer (0 to 0.5). */
static long double tie_distance_int(long double v) {
    return fabsl((v - floorl(v)) - 0.5L);
}

/*
 * Rounds s to float and returns how far s is from the tie between that
 * float and its neighbour on s's side, in units of their spacing.
 */
static long double tie_distance_float(long double s, float *rounded) {
    float f = (float)s;
    float neighbour = ((long double)f < s) ? nextafterf(f, INFINITY) : nextafterf(f, -INFINITY);
    long double spacing = fabsl((long double)neighbour - (long double)f);

    *rounded = f;
    return 0.5L - fabsl(s - (long double)f) / spacing;
}

static int build_tables(int32_t *sine_q23, float *sine_f32, long double *margin_q23,
                        long double *margin_f32) {
    uint32_t k;

    *margin_q23 = 1.0L;
    *margin_f32 = 1.0L;
    for (k = 0u; k < TABLE_LEN; k++) {
        long double s = ref_sin_turn(k << (32u - WT_INDEX_BITS));
        long double scaled = 256.0L * 32767.0L * s;
        long double d = tie_distance_int(scaled);
        long double df = tie_distance_float(s, &sine_f32[k]);

        if (d < *margin_q23) {
            *margin_q23 = d;
        }
        if (df < *margin_f32) {
            *margin_f32 = df;
        }
        sine_q23[k] = (int32_t)llroundl(scaled);
        if (sine_f32[k] == 0.0f) {
            sine_f32[k] = 0.0f; /* no negative zero in the text */
        }
    }
    /* Entries at exact values (0, +-1) have distance 0.5 and do not limit the margin. */
    return *margin_q23 >= TIE_MARGIN && *margin_f32 >= TIE_MARGIN;
}

/*
 * 1 when every entry equals its unfolding from the first quarter, as
 * wt_sine_knot_q23() and wt_sine_knot_f32() compute it.
 */
static int quarter_unfolds(const int32_t *sine_q23, const float *sine_f32) {
    uint32_t k;

    for (k = 0u; k < TABLE_LEN; k++) {
        uint32_t i = wt_quarter_index(k);
        int negate = (k & (WT_TABLE_SIZE / 2u)) != 0u;
        int32_t q = negate ? -sine_q23[i] : sine_q23[i];
        float f = negate ? -sine_f32[i] : sine_f32[i];

        if (sine_q23[k] != q || sine_f32[k] != f) {
            fprintf(stderr, "gen_wavetables: entry %u is not the unfolding of entry %u\n",
                    (unsigned)k, (unsigned)i);
            return 0;
        }
    }
    return 1;
}

static void emit_header(long double margin_q23, long double margin_f32) {
    emit("/*\n"
         " * Tables of the sine lookups of wavetable.h. This file is\n"
         " * written by tools/gen_wavetables.c and never edited by hand; to remake it:\n"
         " *\n"
         " *     make build/tools/gen_wavetables\n"
         " *     build/tools/gen_wavetables src/fixedpoint/wavetable_data.c\n"
         " *\n"
         " * and `build/tools/gen_wavetables --check src/fixedpoint/wavetable_data.c`\n"
         " * fails when this file differs from what the generator writes.\n"
         " *\n"
         " * Entry k, 0 <= k <= %u, belongs to phase k * 2^%u (angle 2 pi k / %u),\n"
         " * the first quarter turn; wt_sine_knot_q23() and wt_sine_knot_f32()\n"
         " * unfold the other %u knots of the turn by symmetry (the generator checks\n"
         " * that the rounded knots of the whole turn are exactly that unfolding).\n"
         " *   wt_sine_quarter_q23[k] = round(256 * 32767 * sin(2 pi k / %u))\n"
         " *   wt_sine_quarter_f32[k] = sin(2 pi k / %u) rounded to the nearest float\n"
         " * round() is to nearest. Each sine is evaluated in long double after an\n"
         " * exact integer reduction of the phase to an angle of at most pi/4 (by\n"
         " * quadrant and reflection), so the argument carries no reduction error.\n"
         " * The generator refuses to write a table with an entry closer than 1e-6\n"
         " * (of a step) to a rounding tie; the closest entries here are %.1Le of a\n"
         " * Q23 step and %.1Le of a float step away, so any sine accurate to far\n"
         " * less than that gives this same table.\n"
         " */\n"
         "#include \"fixedpoint/wavetable.h\"\n",
         WT_QUARTER_SIZE, 32u - WT_INDEX_BITS, WT_TABLE_SIZE, WT_TABLE_SIZE - WT_QUARTER_SIZE,
         WT_TABLE_SIZE, WT_TABLE_SIZE, margin_q23, margin_f32);
}

static void emit_int_table(const char *name, const int32_t *table) {
    uint32_t k;

    emit("\nconst int32_t %s[WT_QUARTER_SIZE + 1u] = {\n", name);
    for (k = 0u; k < QUARTER_LEN; k++) {
        emit("%s%8ld,%s", (k % 8u == 0u) ? "   " : "", (long)table[k],
             (k % 8u == 7u || k + 1u == QUARTER_LEN) ? "\n" : "");
    }
    emit("};\n");
}

static void emit_float_table(const char *name, const float *table) {
    uint32_t k;

    emit("\nconst float %s[WT_QUARTER_SIZE + 1u] = {\n", name);
    for (k = 0u; k < QUARTER_LEN; k++) {
        char digits[32];

        /* Nine significant digits identify a float uniquely. */
        snprintf(digits, sizeof digits, "%.8e", (double)table[k]);
        if (strtof(digits, NULL) != table[k]) {
            fprintf(stderr, "gen_wavetables: %s[%u] does not round-trip\n", name, (unsigned)k);
            exit(2);
        }
        emit("%s%16sf,%s", (k % 4u == 0u) ? "   " : "", digits,
             (k % 4u == 3u || k + 1u == QUARTER_LEN) ? "\n" : "");
    }
    emit("};\n");
}

static int write_file(const char *path) {
    FILE *out = fopen(path, "wb");

    if (out == NULL || fwrite(text, 1u, text_len, out) != text_len) {
        fprintf(stderr, "gen_wavetables: cannot write %s\n", path);
        if (out != NULL) {
            fclose(out);
        }
        return 2;
    }
    if (fclose(out) != 0) {
        fprintf(stderr, "gen_wavetables: cannot write %s\n", path);
        return 2;
    }
    return 0;
}

/* Compares the file with the text; reports the first differing line. */
static int check_file(const char *path) {
    static char old[TEXT_CAP + 1u];
    FILE *in = fopen(path, "rb");
    size_t n;
    size_t i;
    unsigned line = 1u;

    if (in == NULL) {
        fprintf(stderr, "gen_wavetables: cannot read %s\n", path);
        return 2;
    }
    n = fread(old, 1u, sizeof old, in);
    fclose(in);
    for (i = 0u; i < n && i < text_len && old[i] == text[i]; i++) {
        if (text[i] == '\n') {
            line++;
        }
    }
    if (n == text_len && i == n) {
        printf("%s: matches the generator\n1 passed, 0 failed\n", path);
        return 0;
    }
    printf("%s:%u: differs from what tools/gen_wavetables.c writes\n0 passed, 1 failed\n", path,
           line);
    return 1;
}

int main(int argc, char **argv) {
    static int32_t sine_q23[TABLE_LEN];
    static float sine_f32[TABLE_LEN];
    long double margin_q23;
    long double margin_f32;
    int check = argc == 3 && strcmp(argv[1], "--check") == 0;

    if (!(argc == 2 && argv[1][0] != '-') && !check) {
        fprintf(stderr, "usage: gen_wavetables [--check] FILE\n");
        return 2;
    }
    if (!build_tables(sine_q23, sine_f32, &margin_q23, &margin_f32)) {
        fprintf(stderr, "gen_wavetables: an entry lies within %Lg of a rounding tie "
                        "(Q23 margin %Lg, float margin %Lg)\n",
                TIE_MARGIN, margin_q23, margin_f32);
        return 2;
    }
    if (!quarter_unfolds(sine_q23, sine_f32)) {
        return 2;
    }
    emit_header(margin_q23, margin_f32);
    emit_int_table("wt_sine_quarter_q23", sine_q23);
    emit_float_table("wt_sine_quarter_f32", sine_f32);
    return check ? check_file(argv[2]) : write_file(argv[1]);
}

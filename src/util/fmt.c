/*
 * The freestanding formatter (see fmt.h). Output goes through a small sink
 * that counts every byte and stores what fits, so the return value is the
 * full length, as with vsnprintf.
 */
#include "util/fmt.h"

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"

typedef struct {
    char *buf;
    size_t cap;
    size_t len;
} fmt_sink;

static void sink_put(fmt_sink *s, char c) {
    if (s->len + 1u < s->cap) {
        s->buf[s->len] = c;
    }
    s->len++;
}

static void sink_pad(fmt_sink *s, char c, size_t count) {
    for (size_t i = 0; i < count; i++) {
        sink_put(s, c);
    }
}

typedef struct {
    bool left;      /* '-' flag: pad on the right */
    bool zero;      /* '0' flag: pad with zeros */
    size_t width;   /* minimum field width */
    int precision;  /* -1 when not given */
} fmt_spec;

/* Writes text of length n into the field described by spec. */
static void put_field(fmt_sink *s, const fmt_spec *spec, const char *text, size_t n) {
    size_t pad = (spec->width > n) ? spec->width - n : 0u;
    if (!spec->left) {
        /* A zero pad goes after the sign. */
        if (spec->zero && n > 0u && (text[0] == '-' || text[0] == '+')) {
            sink_put(s, text[0]);
            text++;
            n--;
            sink_pad(s, '0', pad);
        } else {
            sink_pad(s, spec->zero ? '0' : ' ', pad);
        }
    }
    for (size_t i = 0; i < n; i++) {
        sink_put(s, text[i]);
    }
    if (spec->left) {
        sink_pad(s, ' ', pad);
    }
}

/* Renders an unsigned value in base 10 or 16 at the end of tmp; returns its start. */
static char *render_unsigned(char *end, unsigned long long v, unsigned base, bool upper) {
    const char *digits = upper ? "0123456789ABCDEF" : "0123456789abcdef";
    char *p = end;
    do {
        *--p = digits[v % base];
        v /= base;
    } while (v != 0u);
    return p;
}

static void put_integer(fmt_sink *s, const fmt_spec *spec, bool negative,
                        unsigned long long magnitude, unsigned base, bool upper) {
    char tmp[24];
    char *end = tmp + sizeof tmp;
    char *p = render_unsigned(end, magnitude, base, upper);
    if (negative) {
        *--p = '-';
    }
    put_field(s, spec, p, (size_t)(end - p));
}

/* Powers of ten that are exact in double (10^0 .. 10^22). */
static double pow10_exact(int n) {
    double r = 1.0;
    for (int i = 0; i < n; i++) {
        r *= 10.0;
    }
    return r;
}

/*
 * Splits |x| (finite, non-zero) into a decimal mantissa of `digits`
 * significant digits and an exponent: |x| ~ m * 10^(e - digits + 1).
 */
static void decimal_split(double x, int digits, unsigned long long *mantissa, int *exponent) {
    int e = 0;
    /* Bring x into [1, 10) with coarse then fine steps; bounded loops. */
    for (int i = 0; i < 40 && x >= 1e16; i++) { /* LCOV_EXCL_BR_LINE: x < 2e308: <= 19 steps */
        x /= 1e16;
        e += 16;
    }
    for (int i = 0; i < 40 && x < 1e-16; i++) { /* LCOV_EXCL_BR_LINE: x >= 2^-1074: <= 20 steps */
        x *= 1e16;
        e -= 16;
    }
    for (int i = 0; i < 40 && x >= 10.0; i++) { /* LCOV_EXCL_BR_LINE: x < 1e16 here: <= 15 steps */
        x /= 10.0;
        e += 1;
    }
    for (int i = 0; i < 40 && x < 1.0; i++) { /* LCOV_EXCL_BR_LINE: x >= 1e-16 here: <= 16 steps */
        x *= 10.0;
        e -= 1;
    }
    double scaled = x * pow10_exact(digits - 1);
    unsigned long long m = (unsigned long long)(scaled + 0.5);
    unsigned long long limit = (unsigned long long)pow10_exact(digits);
    if (m >= limit) {
        m /= 10u;
        e += 1;
    }
    *mantissa = m;
    *exponent = e;
}

/* Appends the exponent part "e+XX" to p. */
static size_t put_exponent(char *p, int e) {
    size_t n = 0;
    p[n++] = 'e';
    p[n++] = (e < 0) ? '-' : '+';
    unsigned u = (unsigned)((e < 0) ? -e : e);
    if (u >= 100u) {
        p[n++] = (char)('0' + u / 100u);
    }
    p[n++] = (char)('0' + (u / 10u) % 10u);
    p[n++] = (char)('0' + u % 10u);
    return n;
}

static void put_double(fmt_sink *s, const fmt_spec *spec, double x, char conv) {
    char tmp[64];
    size_t n = 0;
    int prec = (spec->precision < 0) ? 6 : spec->precision;
    if (prec > 17) {
        prec = 17;
    }
    if (x != x) {
        put_field(s, spec, "nan", 3);
        return;
    }
    bool negative = (x < 0.0) || (x == 0.0 && 1.0 / x < 0.0);
    if (negative) {
        x = -x;
        tmp[n++] = '-';
    }
    if (x > 1.79769313486231570815e308) {
        tmp[n++] = 'i';
        tmp[n++] = 'n';
        tmp[n++] = 'f';
        put_field(s, spec, tmp, n);
        return;
    }
    if (conv == 'f' && x < 1e17) {
        /* Fixed notation: integer part and prec decimals, within 17 digits. */
        double scale = pow10_exact(prec);
        double scaled = x * scale + 0.5;
        if (scaled < 1.8e19) {
            unsigned long long v = (unsigned long long)scaled;
            unsigned long long ip = v / (unsigned long long)scale;
            unsigned long long fp = v % (unsigned long long)scale;
            char digits[24];
            char *end = digits + sizeof digits;
            char *p = render_unsigned(end, ip, 10u, false);
            while (p < end) {
                tmp[n++] = *p++;
            }
            if (prec > 0) {
                tmp[n++] = '.';
                for (int i = prec - 1; i >= 0; i--) {
                    tmp[n + (size_t)i] = (char)('0' + fp % 10u);
                    fp /= 10u;
                }
                n += (size_t)prec;
            }
            put_field(s, spec, tmp, n);
            return;
        }
        conv = 'e';
    }
    int digits = (conv == 'g') ? ((prec == 0) ? 1 : prec) : prec + 1;
    if (digits > 17) {
        digits = 17;
    }
    unsigned long long m = 0;
    int e = 0;
    if (x != 0.0) {
        decimal_split(x, digits, &m, &e);
    }
    char mant[24];
    char *end = mant + sizeof mant;
    char *p = render_unsigned(end, m, 10u, false);
    /* Left-pad the mantissa to `digits` digits (x == 0 gives "0"). */
    while ((int)(end - p) < digits) {
        *--p = '0';
    }
    bool fixed = (conv == 'g') && e >= -5 && e < digits;
    if (conv == 'g') {
        /* %g drops trailing zeros of the fraction. */
        int keep = digits;
        while (keep > 1 && p[keep - 1] == '0' && (!fixed || keep > e + 1)) {
            keep--;
        }
        digits = keep;
    }
    if (fixed) {
        if (e < 0) {
            tmp[n++] = '0';
            tmp[n++] = '.';
            for (int i = 0; i < -e - 1; i++) {
                tmp[n++] = '0';
            }
            for (int i = 0; i < digits; i++) {
                tmp[n++] = p[i];
            }
        } else {
            for (int i = 0; i < digits; i++) {
                if (i == e + 1) {
                    tmp[n++] = '.';
                }
                tmp[n++] = p[i];
            }
        }
    } else {
        tmp[n++] = p[0];
        if (digits > 1) {
            tmp[n++] = '.';
            for (int i = 1; i < digits; i++) {
                tmp[n++] = p[i];
            }
        }
        n += put_exponent(tmp + n, e);
    }
    put_field(s, spec, tmp, n);
}

size_t fmt_vformat(char *buf, size_t cap, const char *format, va_list args) {
    fmt_sink s = {buf, cap, 0u};
    for (const char *f = format; *f != '\0'; f++) {
        if (*f != '%') {
            sink_put(&s, *f);
            continue;
        }
        f++;
        fmt_spec spec = {false, false, 0u, -1};
        for (; *f == '-' || *f == '0'; f++) {
            if (*f == '-') {
                spec.left = true;
            } else {
                spec.zero = true;
            }
        }
        for (; *f >= '0' && *f <= '9'; f++) {
            spec.width = spec.width * 10u + (size_t)(*f - '0');
        }
        if (*f == '.' && f[1] == '*') {
            int prec = va_arg(args, int);
            spec.precision = (prec < 0) ? -1 : prec;
            f += 2;
        } else if (*f == '.') {
            spec.precision = 0;
            for (f++; *f >= '0' && *f <= '9'; f++) {
                spec.precision = spec.precision * 10 + (*f - '0');
            }
        }
        int longs = 0;
        for (; *f == 'l'; f++) {
            longs++;
        }
        char conv = *f;
        if (conv == '\0') {
            break;
        }
        switch (conv) {
        case 'd':
        case 'i': {
            long long v = (longs >= 2) ? va_arg(args, long long)
                          : (longs == 1) ? va_arg(args, long)
                                         : va_arg(args, int);
            unsigned long long mag = (v < 0) ? 0u - (unsigned long long)v : (unsigned long long)v;
            put_integer(&s, &spec, v < 0, mag, 10u, false);
            break;
        }
        case 'u':
        case 'x':
        case 'X': {
            unsigned long long v = (longs >= 2) ? va_arg(args, unsigned long long)
                                   : (longs == 1) ? va_arg(args, unsigned long)
                                                  : va_arg(args, unsigned);
            put_integer(&s, &spec, false, v, (conv == 'u') ? 10u : 16u, conv == 'X');
            break;
        }
        case 'c': {
            char c = (char)va_arg(args, int);
            put_field(&s, &spec, &c, 1u);
            break;
        }
        case 's': {
            const char *str = va_arg(args, const char *);
            if (str == NULL) {
                str = "(null)";
            }
            size_t n = 0;
            /* The precision is tested first: a "%.*s" argument need not be terminated. */
            while ((spec.precision < 0 || n < (size_t)spec.precision) && str[n] != '\0') {
                n++;
            }
            put_field(&s, &spec, str, n);
            break;
        }
        case 'e':
        case 'f':
        case 'g':
            put_double(&s, &spec, va_arg(args, double), conv);
            break;
        case '%':
            sink_put(&s, '%');
            break;
        default:
            sink_put(&s, '%');
            sink_put(&s, conv);
            break;
        }
    }
    if (cap > 0u) {
        buf[(s.len < cap) ? s.len : cap - 1u] = '\0';
    }
    return s.len;
}

size_t fmt_format(char *buf, size_t cap, const char *format, ...) {
    va_list args;
    va_start(args, format);
    size_t n = fmt_vformat(buf, cap, format, args);
    va_end(args);
    return n;
}

void fmt_print(const char *format, ...) {
    char line[256];
    va_list args;
    va_start(args, format);
    size_t n = fmt_vformat(line, sizeof line, format, args);
    va_end(args);
    hal_console_write(line, (n < sizeof line) ? n : sizeof line - 1u);
}

/*
 * The code point of the UTF-8 sequence at s[0..n) (n > 0) and its length,
 * or 0 when it is not well-formed (a stray continuation byte, a truncated
 * or overlong sequence, a surrogate, beyond U+10FFFF).
 */
static size_t utf8_decode(const unsigned char *s, size_t n, uint32_t *cp) {
    static const uint32_t least[4] = {0u, 0x80u, 0x800u, 0x10000u};
    const unsigned char b = s[0];
    size_t len = 0u;
    if (b < 0x80u) {
        len = 1u;
    } else if (b >= 0xC0u && b < 0xE0u) {
        len = 2u;
    } else if (b >= 0xE0u && b < 0xF0u) {
        len = 3u;
    } else if (b >= 0xF0u && b < 0xF8u) {
        len = 4u;
    } else {
        len = 0u;
    }
    if (len == 0u || len > n) {
        return 0u;
    }
    const uint32_t lead_bits = 0x7Fu >> (uint32_t)len; /* the lead byte's payload */
    uint32_t c = (uint32_t)b;
    if (len > 1u) {
        c &= lead_bits;
    }
    for (size_t i = 1u; i < len; i++) {
        if ((s[i] & 0xC0u) != 0x80u) {
            return 0u;
        }
        c = (c << 6) | (s[i] & 0x3Fu);
    }
    if (c < least[len - 1u] || c > 0x10FFFFu || (c >= 0xD800u && c <= 0xDFFFu)) {
        return 0u;
    }
    *cp = c;
    return len;
}

/* The invisible code points that move or hide text: C1, bidi controls, separators, BOM. */
static bool hides_text(uint32_t c) {
    return (c >= 0x80u && c <= 0x9Fu) || c == 0x061Cu || c == 0x200Eu || c == 0x200Fu ||
           (c >= 0x2028u && c <= 0x202Eu) || (c >= 0x2066u && c <= 0x2069u) || c == 0xFEFFu;
}

size_t fmt_text_safe(char *buf, size_t cap, const char *text, size_t n) {
    static const char hex[] = "0123456789abcdef";
    const unsigned char *s = (const unsigned char *)text;
    size_t len = 0u;
    size_t i = 0u;
    while (i < n && cap > 0u) {
        char unit[8];
        size_t u = 0u;
        uint32_t c = 0u;
        size_t k = utf8_decode(s + i, n - i, &c);
        if (k == 0u || c < 0x20u || c == 0x7Fu) {
            c = s[i];
            k = 1u;
            unit[u++] = '\\';
            unit[u++] = 'x';
            unit[u++] = hex[c >> 4];
            unit[u++] = hex[c & 15u];
        } else if (hides_text(c)) {
            unit[u++] = '\\';
            unit[u++] = 'u';
            for (int shift = 12; shift >= 0; shift -= 4) {
                unit[u++] = hex[(c >> (unsigned)shift) & 15u];
            }
        } else if (c == 0x5Cu) { /* the backslash */
            unit[u++] = '\\';
            unit[u++] = '\\';
        } else {
            for (size_t j = 0u; j < k; j++) {
                unit[u++] = (char)s[i + j];
            }
        }
        if (len + u > cap - 1u) {
            break; /* a whole character or escape, or none */
        }
        for (size_t j = 0u; j < u; j++) {
            buf[len++] = unit[j];
        }
        i += k;
    }
    if (cap > 0u) {
        buf[len] = '\0';
    }
    return len;
}

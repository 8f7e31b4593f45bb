/*
 * Text parsing helpers (see parse.h).
 */
#include "util/parse.h"

#include <stdint.h>

/* 10^k for k = 0..22, all exact in double. */
static double exact_pow10(unsigned k) {
    double r = 1.0;
    for (unsigned i = 0; i < k; i++) {
        r *= 10.0;
    }
    return r;
}

static bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool parse_number(const char *s, size_t n, double *value, size_t *used) {
    size_t i = 0;
    bool negative = false;
    if (i < n && (s[i] == '+' || s[i] == '-')) {
        negative = (s[i] == '-');
        i++;
    }
    uint64_t mantissa = 0;
    int exp10 = 0;
    unsigned digits = 0;     /* significant digits kept in mantissa */
    bool dropped = false;    /* a nonzero digit beyond those 19 */
    bool any_digit = false;
    for (; i < n && is_digit(s[i]); i++) {
        any_digit = true;
        if (digits < 19u) {
            if (mantissa != 0u || s[i] != '0') {
                digits++;
            }
            mantissa = mantissa * 10u + (uint64_t)(s[i] - '0');
        } else {
            exp10++; /* digits beyond 19 only scale */
            dropped = dropped || s[i] != '0';
        }
    }
    if (i < n && s[i] == '.') {
        i++;
        for (; i < n && is_digit(s[i]); i++) {
            any_digit = true;
            if (digits < 19u) {
                if (mantissa != 0u || s[i] != '0') {
                    digits++;
                }
                mantissa = mantissa * 10u + (uint64_t)(s[i] - '0');
                exp10--;
            } else {
                dropped = dropped || s[i] != '0';
            }
        }
    }
    if (!any_digit) {
        return false;
    }
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        size_t j = i + 1u;
        bool exp_negative = false;
        if (j < n && (s[j] == '+' || s[j] == '-')) {
            exp_negative = (s[j] == '-');
            j++;
        }
        if (j >= n || !is_digit(s[j])) {
            return false;
        }
        int e = 0;
        for (; j < n && is_digit(s[j]); j++) {
            if (e < 10000) {
                e = e * 10 + (s[j] - '0');
            }
        }
        exp10 += exp_negative ? -e : e;
        i = j;
    }
    double v = (double)mantissa;
    if (mantissa != 0u) {
        /* The range on the digits, so that 1e300 and 1e-300 themselves pass:
         * the value is in [10^lead, 10^(lead + 1)), and at lead 300 it is
         * 1e300 only when its digits are a 1 and zeros. */
        const int lead = exp10 + (int)digits - 1;
        uint64_t one = 1u;
        for (unsigned k = 1u; k < digits; k++) {
            one *= 10u;
        }
        if (lead > 300 || (lead == 300 && (mantissa != one || dropped)) || lead < -300) {
            return false;
        }
        /* Bring the magnitude in range in exact steps where possible. */
        int e = exp10;
        while (e > 22) {
            v *= 1e22;
            e -= 22;
        }
        while (e < -22) {
            v /= 1e22;
            e += 22;
        }
        v = (e >= 0) ? v * exact_pow10((unsigned)e) : v / exact_pow10((unsigned)-e);
    }
    *value = negative ? -v : v;
    *used = i;
    return true;
}

bool parse_word_is(const char *s, size_t n, const char *word) {
    size_t i = 0;
    for (; i < n && word[i] != '\0'; i++) {
        if (s[i] != word[i]) {
            return false;
        }
    }
    return i == n && word[i] == '\0';
}

size_t parse_tokens(const char *line, size_t n, parse_token *tokens, size_t max) {
    size_t count = 0;
    size_t i = 0;
    while (i < n) {
        while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) {
            i++;
        }
        if (i >= n) {
            break;
        }
        size_t start = i;
        while (i < n && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
            i++;
        }
        if (count == max) {
            return max + 1u;
        }
        tokens[count].text = line + start;
        tokens[count].len = i - start;
        count++;
    }
    return count;
}

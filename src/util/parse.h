/*
 * Text parsing helpers for scenario files and command lines: a decimal
 * number reader and whitespace tokenising, freestanding and bounded.
 */
#ifndef UUV_PARSE_H
#define UUV_PARSE_H

#include <stdbool.h>
#include <stddef.h>

/*
 * Reads a decimal number ("-12", "3.25", "1e-6", ".5") from the first n
 * characters of s. On success stores the value and the count of characters
 * used and returns true; the caller decides what may follow (a unit
 * suffix, or nothing). Infinities, NaN, hexadecimal and magnitudes beyond
 * 1e300 or below 1e-300 (as written, so 1e300 and 1e-300 pass) are
 * refused. The result is correctly rounded when the digits form
 * an integer below 2^53 and the decimal exponent is within +-22 (every
 * value a person writes in a scenario); otherwise within a few ulp.
 */
bool parse_number(const char *s, size_t n, double *value, size_t *used);

/* True when the n characters at s equal the NUL-terminated word. */
bool parse_word_is(const char *s, size_t n, const char *word);

typedef struct {
    const char *text; /* start of the token */
    size_t len;       /* its length */
} parse_token;

/*
 * Splits the n characters at line into at most max tokens separated by
 * spaces or tabs. Returns the number of tokens, or max + 1 when there are
 * more than max (the caller reports "too many fields").
 */
size_t parse_tokens(const char *line, size_t n, parse_token *tokens, size_t max);

#endif /* UUV_PARSE_H */

/*
 * The text parsing helpers (util/parse.h): decimal numbers in every form the
 * header lists, against the values a person means by them (exactly, or
 * within a few ulp where the header allows it), the refusals it documents,
 * and the tokeniser's separators.
 */
#include <stdbool.h>
#include <stddef.h>

#include "util/parse.h"
#include "ut.h"

void suite_parse(void);

/* Parses all of s; true when it is a number and how many characters were used is `used`. */
static bool number(const char *s, double *v, size_t used) {
    size_t u = 0;
    return parse_number(s, ut_text_len(s), v, &u) && u == used;
}

static bool refused(const char *s) {
    double v = 0.0;
    size_t u = 0;
    return !parse_number(s, ut_text_len(s), &v, &u);
}

static void test_numbers(void) {
    double v = 0.0;
    UT_TEST("numbers: a '+' sign, exponents with E and a sign, an exponent or a fraction "
            "followed by a unit (used stops before it), exact where the header promises it");
    UT_CHECK(number("+42", &v, 3u) && v == 42.0);
    UT_CHECK(number("1E3", &v, 3u) && v == 1000.0);
    UT_CHECK(number("25e+2", &v, 5u) && v == 2500.0);
    UT_CHECK(number("1e3m", &v, 3u) && v == 1000.0);
    UT_CHECK(number("2.5deg", &v, 3u) && v == 2.5);
    UT_CHECK(number("-0.125e-1", &v, 9u) && v == -0.0125);

    UT_TEST("numbers: more than 19 significant digits, before or after the point, are read "
            "within a few ulp (1.2345678901234567e22, 0.12345678901234567)");
    UT_CHECK(number("12345678901234567890123", &v, 23u));
    UT_NEAR(v, 1.2345678901234567e22, 4e-16 * 1.2345678901234567e22);
    UT_CHECK(number("0.12345678901234567890123", &v, 25u));
    UT_NEAR(v, 0.12345678901234567, 4e-16);

    UT_TEST("numbers: decimal exponents beyond +-22 are reached in steps, within a few ulp "
            "(1.5e250, 2.5e-100)");
    UT_CHECK(number("1.5e250", &v, 7u));
    UT_NEAR(v, 1.5e250, 1e-15 * 1.5e250);
    UT_CHECK(number("2.5e-100", &v, 8u));
    UT_NEAR(v, 2.5e-100, 1e-15 * 2.5e-100);

    UT_TEST("numbers: refused are no digits at all, an exponent without digits, magnitudes "
            "beyond 1e300 (also by a huge exponent or a 20th digit) and below 1e-300 "
            "(1e-310); the bounds themselves pass");
    UT_CHECK(refused("") && refused("-") && refused("1ex") && refused("2e+"));
    UT_CHECK(refused("2e300") && refused("1e400") && refused("-1e400"));
    UT_CHECK(refused("1e-400") && refused("1e123456") && refused("1e-310"));
    UT_CHECK(refused("1.0000000000000000001e300") && refused("1.00000000000000000001e300"));
    UT_CHECK(refused("10000000000000000000001e278") && refused("9.99e-301"));
    UT_CHECK(number("1e300", &v, 5u));
    UT_NEAR(v, 1e300, 1e-15 * 1e300);
    UT_CHECK(number("-1.000e300", &v, 10u));
    UT_NEAR(v, -1e300, 1e-15 * 1e300);
    UT_CHECK(number("100000000000000000000000e277", &v, 28u));
    UT_NEAR(v, 1e300, 1e-15 * 1e300);
    UT_CHECK(number("1e-300", &v, 6u));
    UT_NEAR(v, 1e-300, 1e-15 * 1e-300);
    UT_CHECK(number("0.001e-297", &v, 10u));
    UT_NEAR(v, 1e-300, 1e-15 * 1e-300);
    UT_CHECK(number("9.99e299", &v, 8u));
    UT_CHECK(number("0e123456", &v, 8u) && v == 0.0);
}

static void test_words_and_tokens(void) {
    UT_TEST("words: equal only when the lengths match as well as the characters");
    UT_CHECK(parse_word_is("deg", 3u, "deg"));
    UT_CHECK(!parse_word_is("degs", 4u, "deg"));
    UT_CHECK(!parse_word_is("de", 2u, "deg"));

    UT_TEST("tokens: spaces, tabs and carriage returns all separate; runs of them count once");
    static const char line[] = "at\t1  rudder=5deg\r\t n_rpm=3\r";
    parse_token tok[4];
    size_t n = parse_tokens(line, sizeof line - 1u, tok, 4u);
    UT_EQ_INT(n, 4);
    UT_CHECK(parse_word_is(tok[0].text, tok[0].len, "at"));
    UT_CHECK(parse_word_is(tok[1].text, tok[1].len, "1"));
    UT_CHECK(parse_word_is(tok[2].text, tok[2].len, "rudder=5deg"));
    UT_CHECK(parse_word_is(tok[3].text, tok[3].len, "n_rpm=3"));
    UT_EQ_INT(parse_tokens("a\tb\tc", 5u, tok, 2u), 3);
}

void suite_parse(void) {
    test_numbers();
    test_words_and_tokens();
}

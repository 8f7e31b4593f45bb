/*
 * A small, freestanding text formatter: the subset of printf that reports,
 * tests and telemetry use. Deterministic: the same arguments give the same
 * bytes on every port.
 *
 * Conversions: %d %i %u %x %X %c %s %% with the length modifiers l and ll,
 * an optional '-' or '0' flag, a field width and, for %s, a precision (also as .*); and
 * %e %f %g for double with an optional precision (default 6, at most 17).
 * Double conversion scales by powers of ten in double arithmetic, so the
 * last of 17 digits may differ from a correctly rounded libc printf; it is
 * meant for reports, not for round-tripping values.
 */
#ifndef UUV_FMT_H
#define UUV_FMT_H

#include <stdarg.h>
#include <stddef.h>

/*
 * Formats into buf (capacity cap, always NUL-terminated when cap > 0).
 * Returns the length the full output would have, like vsnprintf.
 */
size_t fmt_vformat(char *buf, size_t cap, const char *format, va_list args);
size_t fmt_format(char *buf, size_t cap, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/*
 * Copies n bytes of text into buf (capacity cap, NUL-terminated when
 * cap > 0) so that an echo of it cannot hide or reorder what a terminal
 * shows: control bytes (C0, DEL) and bytes that are not well-formed UTF-8
 * become \xHH, the C1 controls, the bidi controls (U+061C, U+200E,
 * U+200F, U+202A..U+202E, U+2066..U+2069), the line and paragraph
 * separators and U+FEFF become \uHHHH, a backslash becomes two; other
 * characters are copied. Cut to fit, at a character or escape boundary,
 * never inside one. Returns the length written.
 */
size_t fmt_text_safe(char *buf, size_t cap, const char *text, size_t n);

/* Formats and writes to the HAL console; output over 255 bytes is cut. */
void fmt_print(const char *format, ...) __attribute__((format(printf, 1, 2)));

#endif /* UUV_FMT_H */

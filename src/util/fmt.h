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

/* Formats and writes to the HAL console; output over 255 bytes is cut. */
void fmt_print(const char *format, ...) __attribute__((format(printf, 1, 2)));

#endif /* UUV_FMT_H */

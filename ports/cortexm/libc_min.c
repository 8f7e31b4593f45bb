/*
 * The four memory functions the compiler may call on its own (for struct
 * copies and initialisers) even in freestanding code. The firmware links
 * with -nostdlib, so the port provides them. Some of those calls are on
 * the fast tick's path (the executive clears and copies its frame sums at
 * each motor-frame boundary), so memcpy and memset move whole words when
 * both ends are word-aligned, and bytes otherwise.
 */
#include <stddef.h>
#include <stdint.h>

void *memcpy(void *dst, const void *src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);

/* A word that may alias any object, as these functions' accesses must. */
typedef uint32_t __attribute__((may_alias)) word_t;

static int word_aligned(const void *a, const void *b) {
    return (((uintptr_t)a | (uintptr_t)b) & 3u) == 0u;
}

void *memcpy(void *dst, const void *src, size_t n) {
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (word_aligned(d, s)) {
        for (; n >= 4u; n -= 4u, d += 4, s += 4) {
            *(word_t *)(void *)d = *(const word_t *)(const void *)s;
        }
    }
    for (size_t i = 0; i < n; i++) {
        d[i] = s[i];
    }
    return dst;
}

void *memmove(void *dst, const void *src, size_t n) {
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (d < s) {
        for (size_t i = 0; i < n; i++) {
            d[i] = s[i];
        }
    } else {
        for (size_t i = n; i > 0; i--) {
            d[i - 1] = s[i - 1];
        }
    }
    return dst;
}

void *memset(void *dst, int c, size_t n) {
    unsigned char *d = dst;
    unsigned char byte = (unsigned char)c;
    if (word_aligned(d, d)) {
        uint32_t w = 0x01010101u * byte;
        for (; n >= 4u; n -= 4u, d += 4) {
            *(word_t *)(void *)d = w;
        }
    }
    for (size_t i = 0; i < n; i++) {
        d[i] = byte;
    }
    return dst;
}

int memcmp(const void *a, const void *b, size_t n) {
    const unsigned char *x = a;
    const unsigned char *y = b;
    for (size_t i = 0; i < n; i++) {
        if (x[i] != y[i]) {
            return (x[i] < y[i]) ? -1 : 1;
        }
    }
    return 0;
}

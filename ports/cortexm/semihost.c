/*
 * Semihosting calls (see semihost.h). Each call traps to the emulator, which
 * costs far more than any instruction, so callers buffer their output.
 */
#include "semihost.h"

int32_t semihost_call(uint32_t op, const void *arg) {
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

static size_t text_length(const char *s) {
    size_t n = 0;
    while (s[n] != '\0') {
        n++;
    }
    return n;
}

int32_t semihost_open(const char *name, uint32_t mode) {
    uint32_t block[3] = {(uint32_t)(uintptr_t)name, mode, (uint32_t)text_length(name)};
    return semihost_call(SH_SYS_OPEN, block);
}

int32_t semihost_write(int32_t handle, const void *data, size_t n) {
    uint32_t block[3] = {(uint32_t)handle, (uint32_t)(uintptr_t)data, (uint32_t)n};
    return semihost_call(SH_SYS_WRITE, block);
}

size_t semihost_read(int32_t handle, void *data, size_t n) {
    uint32_t block[3] = {(uint32_t)handle, (uint32_t)(uintptr_t)data, (uint32_t)n};
    int32_t not_read = semihost_call(SH_SYS_READ, block);
    if (not_read < 0 || (size_t)not_read > n) {
        return 0;
    }
    return n - (size_t)not_read;
}

void semihost_close(int32_t handle) {
    uint32_t block[1] = {(uint32_t)handle};
    (void)semihost_call(SH_SYS_CLOSE, block);
}

int32_t semihost_cmdline(char *buf, size_t cap) {
    if (cap < 2u) {
        return -1;
    }
    /* The host writes at most block[1] bytes including the NUL and returns the length there. */
    uint32_t block[2] = {(uint32_t)(uintptr_t)buf, (uint32_t)(cap - 1u)};
    if (semihost_call(SH_SYS_GET_CMDLINE, block) != 0 || block[1] >= cap) {
        return -1;
    }
    buf[block[1]] = '\0';
    return (int32_t)block[1];
}

void semihost_exit(int status) {
    uint32_t block[2] = {SH_ADP_STOPPED_APPLICATION_EXIT, (uint32_t)status};
    for (;;) {
        (void)semihost_call(SH_SYS_EXIT_EXTENDED, block);
    }
}

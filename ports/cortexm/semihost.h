/*
 * Arm semihosting: the debugger or emulator services the firmware calls
 * with `bkpt 0xAB` (operation in r0, argument block in r1). QEMU provides
 * them when started with -semihosting-config enable=on.
 */
#ifndef UUV_SEMIHOST_H
#define UUV_SEMIHOST_H

#include <stddef.h>
#include <stdint.h>

#define SH_SYS_OPEN 0x01u
#define SH_SYS_CLOSE 0x02u
#define SH_SYS_WRITE 0x05u
#define SH_SYS_READ 0x06u
#define SH_SYS_FLEN 0x0Cu
#define SH_SYS_GET_CMDLINE 0x15u
#define SH_SYS_EXIT_EXTENDED 0x20u

#define SH_ADP_STOPPED_APPLICATION_EXIT 0x20026u

int32_t semihost_call(uint32_t op, const void *arg);

/* Opens a host file; mode as fopen's index (0 "r", 1 "rb", 4 "w", 5 "wb"). -1 on failure. */
int32_t semihost_open(const char *name, uint32_t mode);
/* Writes n bytes; returns the number NOT written (0 on success). */
int32_t semihost_write(int32_t handle, const void *data, size_t n);
/* Reads up to n bytes; returns the number read. */
size_t semihost_read(int32_t handle, void *data, size_t n);
/* Closes a handle from semihost_open. */
void semihost_close(int32_t handle);
/*
 * Copies the command line the emulator was given (QEMU: the arg= values of
 * -semihosting-config, separated by spaces) into buf, NUL-terminated.
 * Returns its length, or -1 when there is none or it does not fit.
 */
int32_t semihost_cmdline(char *buf, size_t cap);
__attribute__((noreturn)) void semihost_exit(int status);

#endif /* UUV_SEMIHOST_H */

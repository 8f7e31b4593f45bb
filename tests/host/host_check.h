/*
 * The host test programs' checks and verdict line (the C side of lib.sh):
 * one line per check, then "N passed, N failed", the line
 * tools/run-tests.sh reads. Included by one file of each program.
 */
#ifndef HOST_CHECK_H
#define HOST_CHECK_H

#include <stdbool.h>
#include <stdio.h>

static int host_passed, host_failed;

/* One check: "ok" or "FAIL" and what it checked. */
static void check(bool ok, const char *what) {
    printf("  %s  %s\n", ok ? "ok  " : "FAIL", what);
    if (ok) {
        host_passed++;
    } else {
        host_failed++;
    }
}

/* The verdict line; the program's exit status (0 when no check failed). */
static int check_finish(void) {
    printf("%d passed, %d failed\n", host_passed, host_failed);
    return (host_failed == 0) ? 0 : 1;
}

#endif

/*
 * The exact leaps' edge maps against the step they are built from (leap.c:
 * leap_edge_check(), within 1e-12 of the step's values), and the leap's
 * product and bound in their two AVX forms (product_bounded_512(), which
 * takes the leaps where the build has AVX-512, and product_bounded_256(),
 * which takes them where it has AVX2; likewise the edge maps' two forms):
 * the same bits and the same verdict on every entry of a test sequence,
 * and verdicts of both kinds among them. A build with one form only (no
 * AVX-512 in LEAP_ARCH) says so and checks the edge maps only; the fixed
 * build has no leaps. Prints each check and "N passed, N failed".
 *
 *   test_leap_forms
 */
#include <stdarg.h>
#include <stdio.h>

#include "host_check.h"
#include "leap.h"

#define N_ENTRIES 200000u
#define N_EDGES 20000u

/* check() with its text formatted. */
static void checkf(bool ok, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void checkf(bool ok, const char *fmt, ...) {
    char what[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    check(ok, what);
}

int main(void) {
    const double edge = leap_edge_check(N_EDGES);
    if (edge < 0.0) {
        printf("  this build has no leaps\n");
    } else {
        checkf(edge <= 1e-12,
               "edge maps against the step: largest difference %.2g of the step's largest value "
               "on %u cases (<= 1e-12)",
               edge, N_EDGES);
    }
    uint32_t accepted = 0u;
    const long differ = leap_forms_check(N_ENTRIES, &accepted);
    if (differ < 0) {
        printf("  this build has one form of the leap's product (no AVX-512 in LEAP_ARCH)\n");
    } else {
        checkf(differ == 0,
               "512-bit and 256-bit forms: same bits and verdict of the product and of the edge "
               "map on %u entries (%ld differ)",
               N_ENTRIES, differ);
        checkf(accepted > N_ENTRIES / 10u && accepted < N_ENTRIES - N_ENTRIES / 10u,
               "both verdicts occur (%u of %u allowed the leap)", accepted, N_ENTRIES);
    }
    return check_finish();
}

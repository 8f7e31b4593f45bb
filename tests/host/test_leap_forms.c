/*
 * The exact leaps' product and bound in their two AVX forms (leap.c:
 * product_bounded_512(), which takes the leaps where the build has
 * AVX-512, and product_bounded_256(), which takes them where it has AVX2):
 * the same bits of the product and the same verdict on every entry of a
 * test sequence, and verdicts of both kinds among them. A build with one
 * form only (no AVX-512 in LEAP_ARCH, the fixed build) says so and checks
 * nothing. Prints each check and "N passed, N failed".
 *
 *   test_leap_forms
 */
#include <stdio.h>

#include "host_check.h"
#include "leap.h"

#define N_ENTRIES 200000u

int main(void) {
    uint32_t accepted = 0u;
    const long differ = leap_forms_check(N_ENTRIES, &accepted);
    if (differ < 0) {
        printf("  this build has one form of the leap's product (no AVX-512 in LEAP_ARCH)\n");
    } else {
        char what[160];
        snprintf(what, sizeof what,
                 "512-bit and 256-bit forms: same product bits and verdict on %u entries "
                 "(%ld differ)", N_ENTRIES, differ);
        check(differ == 0, what);
        snprintf(what, sizeof what, "both verdicts occur (%u of %u allowed the leap)", accepted,
                 N_ENTRIES);
        check(accepted > N_ENTRIES / 10u && accepted < N_ENTRIES - N_ENTRIES / 10u, what);
    }
    return check_finish();
}

/*
 * uuvsim party: the host side of the multi-party run (party_host.c,
 * docs/cosimulation.md).
 */
#ifndef UUV_PARTY_HOST_H
#define UUV_PARTY_HOST_H

#include <stdbool.h>

#include "scenario.h"

/* argv[0] is the program, argv[1] "party"; the exit status. */
int party_main(int argc, char **argv);

/* Reads and parses a scenario file; prints the error (file:line: field) on failure (uuvsim.c). */
bool uuvsim_load_scenario(const char *path, scenario *scn);

#endif /* UUV_PARTY_HOST_H */

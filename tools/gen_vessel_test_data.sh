#!/bin/sh
# Writes tests/unit/test_vessel_data.h from the reference CSV files in
# tests/vectors/: the 10 random and 8 edge derivative rows, the mass matrix
# and every 10th row of the first 10 s of the 1300 rpm straight run. The
# numbers are copied as text (17 significant digits), so the compiler reads
# back exactly the doubles of the files.
#   usage: sh tools/gen_vessel_test_data.sh > tests/unit/test_vessel_data.h
set -eu
dir=${1:-tests/vectors}

# Prints the data rows of a CSV (its header lines skipped) as C initialiser rows,
# wrapped at 100 columns. Integers get ".0" so that every literal reads as a
# double.
rows() { # file first_row(1-based data row) last_row stride header_lines
    awk -F, -v first="$2" -v last="$3" -v stride="$4" -v hdr="$5" '
        NR <= hdr { next }
        {
            r = NR - hdr
            if (r < first || r > last || (r - first) % stride != 0) next
            line = "    {"
            for (i = 1; i <= NF; i++) {
                v = $i
                if (v !~ /[.eE]/) v = v ".0"
                item = v (i < NF ? "," : "},")
                if (length(line) + 1 + length(item) > 100) {
                    print line
                    line = "     " item
                } else {
                    line = line (i > 1 ? " " : "") item
                }
            }
            print line
        }' "$1"
}

cat <<'HDR'
/*
 * Reference data of the vessel tests, copied from the CSV files in
 * tests/vectors/ by tools/gen_vessel_test_data.sh (do not edit by hand).
 * The values have 17 significant digits, so each literal is the exact
 * double of the file.
 */
#ifndef UUV_TEST_VESSEL_DATA_H
#define UUV_TEST_VESSEL_DATA_H

/* Columns of a derivative row: case, 5 commands, 17 states, 17 derivatives. */
#define VEC_COL_CMD 1
#define VEC_COL_STATE 6
#define VEC_COL_DERIV 23
#define VEC_NCOLS 40

/* npsauv_derivatives.csv (10 random rows), then npsauv_derivatives_edge.csv (8 rows). */
static const double vec_derivs[18][VEC_NCOLS] = {
HDR
rows "$dir/npsauv_derivatives.csv" 1 10 1 1
rows "$dir/npsauv_derivatives_edge.csv" 1 8 1 1
cat <<'HDR'
};

/* npsauv_mass_matrix.csv: M = M_RB + M_A. */
static const double vec_mass[6][6] = {
HDR
rows "$dir/npsauv_mass_matrix.csv" 1 6 1 0
cat <<'HDR'
};

/*
 * npsauv_straight_1300rpm.csv at t = 0, 1, ..., 10 s (every 10th row):
 * t, 17 states, 5 commands applied during the following step.
 */
#define TRAJ_COL_STATE 1
#define TRAJ_COL_CMD 18
#define TRAJ_NCOLS 23
#define TRAJ_STEPS_PER_ROW 10
static const double vec_traj[11][TRAJ_NCOLS] = {
HDR
rows "$dir/npsauv_straight_1300rpm.csv" 1 101 10 1
cat <<'HDR'
};

#endif /* UUV_TEST_VESSEL_DATA_H */
HDR

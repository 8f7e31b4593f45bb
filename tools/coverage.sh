#!/bin/sh
# make coverage: branch coverage of src/ by the host unit tests (both
# numeric builds, gcc --coverage), measured with gcov through lcov.
# Prints "branch coverage src/fixedpoint: X%" and "branch coverage src: Y%",
# then one line per folder. Branches marked LCOV_EXCL_BR_LINE (defensive
# checks that cannot be reached, each with a comment saying why) are
# excluded, in the way SQLite marks its never-taken branches.
# HTML report: $BUILD/coverage/html/index.html
set -u
BUILD=${BUILD:-build}
out="$BUILD/coverage"
rc="--rc lcov_branch_coverage=1"
mkdir -p "$out"
for v in linux-cov-fixed linux-cov-float; do
    find "$BUILD/$v" -name '*.gcda' -delete
    "$BUILD/$v/unit_tests" > "$out/$v.log" 2>&1 || { echo "unit tests failed: $out/$v.log"; exit 1; }
    lcov $rc --quiet --capture --directory "$BUILD/$v/obj/src" --directory "$BUILD/$v/obj/tests" \
        --base-directory . \
        --output-file "$out/$v.info" 2>>"$out/lcov.log"
done
lcov $rc --quiet -a "$out/linux-cov-fixed.info" -a "$out/linux-cov-float.info" \
    -o "$out/all.info" 2>>"$out/lcov.log"
lcov $rc --quiet --extract "$out/all.info" "$PWD/src/*" -o "$out/src.info" 2>>"$out/lcov.log"
pct() { # info-file -> branch percentage
    lcov $rc --summary "$1" 2>&1 | sed -n 's/^ *branches\.*: \([0-9.]*%\).*/\1/p'
}
folder() { # label glob
    lcov $rc --quiet --extract "$out/src.info" "$2" -o "$out/part.info" 2>>"$out/lcov.log"
    echo "branch coverage $1: $(pct "$out/part.info")"
}
folder src/fixedpoint "$PWD/src/fixedpoint/*"
echo "branch coverage src: $(pct "$out/src.info")"
for d in math models util; do
    folder "src/$d" "$PWD/src/$d/*"
done
lcov $rc --quiet --remove "$out/src.info" "$PWD/src/*/*" -o "$out/part.info" 2>>"$out/lcov.log"
echo "branch coverage src/*.c (top level): $(pct "$out/part.info")"
if command -v genhtml >/dev/null 2>&1; then
    genhtml $rc --quiet --branch-coverage -o "$out/html" "$out/src.info" >>"$out/lcov.log" 2>&1
fi

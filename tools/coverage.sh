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
: >"$out/lcov.log"
command -v lcov >/dev/null 2>&1 || {
    echo "error: lcov is missing (make coverage installs it: sh tools/ensure-deps.sh coverage)" >&2
    exit 1
}
status=0
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
report() { # label info-file: one line, or an error when lcov gave no figure
    p=$(pct "$2")
    if [ -n "$p" ]; then
        echo "branch coverage $1: $p"
    else
        echo "error: no branch coverage figure for $1 (lcov's messages: $out/lcov.log)" >&2
        status=1
    fi
}
folder() { # label glob
    lcov $rc --quiet --extract "$out/src.info" "$2" -o "$out/part.info" 2>>"$out/lcov.log"
    report "$1" "$out/part.info"
}
folder src/fixedpoint "$PWD/src/fixedpoint/*"
report src "$out/src.info"
for d in math models util; do
    folder "src/$d" "$PWD/src/$d/*"
done
lcov $rc --quiet --remove "$out/src.info" "$PWD/src/*/*" -o "$out/part.info" 2>>"$out/lcov.log"
report "src/*.c (top level)" "$out/part.info"
if command -v genhtml >/dev/null 2>&1; then
    genhtml $rc --quiet --branch-coverage -o "$out/html" "$out/src.info" >>"$out/lcov.log" 2>&1
fi
exit $status

#!/bin/sh
# make lint: cppcheck with its MISRA C:2012 addon over src/ (both numeric
# builds), then clang-tidy with the check set below. Fails on any finding
# that tools/misra-deviations.txt does not list as a deviation, on a row of
# that file whose number of findings is not the one measured, and on any
# clang-tidy finding. Also names deviation rows that no longer match a
# finding, so the list shrinks when the code improves. Output: $BUILD/lint/.
# MISRA_DEVIATIONS names another deviation file (the default:
# tools/misra-deviations.txt; docs/misra.md gives the policy).
set -u
BUILD=${BUILD:-build}
out="$BUILD/lint"
mkdir -p "$out/cache-fixed" "$out/cache-float"
jobs=$(nproc 2>/dev/null || echo 2)

# The clang-tidy set: the static analyser, bug-prone patterns, CERT C, and a
# few readability checks that catch real mistakes. Left out, with reasons in
# docs/reliability.md: easily-swappable-parameters (style),
# readability-non-const-parameter (false positives on a pointer kept in a struct).
TIDY_CHECKS='-*,clang-analyzer-*,bugprone-*,-bugprone-easily-swappable-parameters,cert-*,misc-redundant-expression,misc-misplaced-const,readability-misleading-indentation'
TIDY_FLAGS='-std=c99 -Isrc -ffreestanding'

# 1. The deviations, as "rule glob row" lines (row: the line in the
# deviation file), and the number of findings each row states, as "row N".
devfile=${MISRA_DEVIATIONS:-tools/misra-deviations.txt}
: > "$out/deviations.txt"
: > "$out/stated.txt"
awk -v devs="$out/deviations.txt" -v stated="$out/stated.txt" -v name="$devfile" '
/^[ \t]*(#|$)/ { next }
$1 !~ /^[0-9]+\.[0-9]+$/ || $2 !~ /^[AD]$/ || $3 !~ /^[0-9]+$/ || NF < 5 {
    print name ":" FNR ": expected RULE A|D FINDINGS PLACES REASON, got: " $0; bad++; next
}
{
    n = split($4, g, /,/)
    for (i = 1; i <= n; i++) if (g[i] != "") print $1, g[i], FNR > devs
    print FNR, $3 > stated
}
END { exit bad > 0 }' "$devfile" || exit 1

# 2. cppcheck: every file in the fixed build, the drive segment again in the float build.
cpp() { # cache-dir numeric files...
    cache=$1; num=$2; shift 2
    cppcheck --addon=misra --std=c99 --platform=unix64 -Isrc -DUUV_NUMERIC="$num" \
        --enable=warning,portability --inline-suppr -q -j"$jobs" --cppcheck-build-dir="$cache" \
        --template='{file}:{line}:{id}:{message}' "$@" 2>&1
}
{
    cpp "$out/cache-fixed" 1 src/
    cpp "$out/cache-float" 2 src/drive_segment.c
} | sort -u > "$out/cppcheck.txt"

# 3. Each finding against the deviations (a glob's * also matches '/').
# The number of findings each row states must be the measured one.
awk -F: -v devs="$out/deviations.txt" -v stale="$out/stale.txt" -v stated="$out/stated.txt" \
    -v name="$devfile" '
function glob_re(g) { gsub(/\./, "\\.", g); gsub(/\*/, ".*", g); gsub(/\?/, ".", g); return "^" g "$" }
BEGIN {
    nd = 0
    while ((getline line < devs) > 0) {
        split(line, a, " "); nd++; drule[nd] = a[1]; dre[nd] = glob_re(a[2]); drow[nd] = a[3]
        dtext[nd] = a[1] " " a[2]
    }
}
{
    file = $1; id = $3; rule = id; listed = 0
    if (!(file in present)) {
        present[file] = ((getline junk < file) >= 0); close(file)
    }
    if (!present[file]) { print "  a file not in the tree (a stale cppcheck cache?): " $0; bad++; next }
    if (sub(/^misra-c2012-/, "", rule)) {
        for (i = 1; i <= nd; i++) if (drule[i] == rule && file ~ dre[i]) { listed = 1; used[i]++; break }
    }
    if (listed) { dev[rule]++; ndev++ } else { print "  not listed: " $0; bad++ }
}
END {
    for (r in dev) printf "  misra %-6s %4d (listed deviations)\n", r, dev[r] | "sort -V 1>&2"
    close("sort -V 1>&2")
    for (i = 1; i <= nd; i++) { row[drow[i]] += used[i]; rrule[drow[i]] = drule[i]; if (!used[i]) print dtext[i] > stale }
    while ((getline line < stated) > 0) {
        split(line, a, " ")
        got = row[a[1]] + 0
        if (a[2] != got) {
            print "  " name ":" a[1] ": rule " rrule[a[1]] " states " a[2] " findings, measured " got
            miscount++
        }
    }
    printf "cppcheck: %d findings, %d listed as deviations, %d not listed", ndev + bad, ndev, bad
    printf "%s\n", miscount ? ", " miscount " row(s) of " name " stating another count" : ""
    exit (bad > 0 || miscount > 0)
}' "$out/cppcheck.txt" > "$out/cppcheck-report.txt"
cpp_status=$?
cat "$out/cppcheck-report.txt"
if [ -s "$out/stale.txt" ]; then
    echo "deviations in $devfile that match no finding (remove them):"
    sed 's/^/  /' "$out/stale.txt"
fi
: > "$out/stale.txt"

# 4. clang-tidy, one file per job.
tidy_one() {
    clang-tidy --quiet -checks="$TIDY_CHECKS" "$1" -- $TIDY_FLAGS -DUUV_NUMERIC="$2" 2>/dev/null
}
export TIDY_CHECKS TIDY_FLAGS
{
    find src -name "*.c" | sort | xargs -P "$jobs" -I{} sh -c \
        'clang-tidy --quiet -checks="$TIDY_CHECKS" {} -- $TIDY_FLAGS -DUUV_NUMERIC=1 2>/dev/null'
    tidy_one src/drive_segment.c 2
} > "$out/clang-tidy.txt"
tidy_n=$(grep -cE ': (warning|error): ' "$out/clang-tidy.txt")
grep -E ': (warning|error): ' "$out/clang-tidy.txt" | sed 's/^/  /'
echo "clang-tidy: $tidy_n findings"

failed=0
[ $cpp_status -eq 0 ] || failed=$((failed + 1))
[ "$tidy_n" -eq 0 ] || failed=$((failed + 1))
echo "lint: $((2 - failed)) passed, $failed failed"
[ $failed -eq 0 ]

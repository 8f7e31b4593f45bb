#!/bin/sh
# make lint: cppcheck with its MISRA C:2012 addon over src/ (both numeric
# builds), then clang-tidy with the check set below. Fails on any finding
# that docs/misra.md does not list as a deviation (a table row
# "| rule | `glob`, ... | A, D or P | reason |"), and on any clang-tidy finding.
# Also names deviation rows that no longer match a finding, so the list
# shrinks when the code improves. Output: $BUILD/lint/.
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

# 1. The deviations, as "rule glob row" lines (row: the table row's line in
# docs/misra.md), and the counts the document states: each row's "(N
# findings)" and the totals table's "| Rr | N |" rows, as "row N" and "Rr N".
awk -F'|' '/^\| *[0-9]+\.[0-9]+ *\|/ && $4 ~ /^ *[ADP] *$/ {
    rule = $2; gsub(/ /, "", rule)
    place = $3; gsub(/`/, "", place); gsub(/,/, " ", place)
    n = split(place, g, / +/)
    for (i = 1; i <= n; i++) if (g[i] != "") print rule, g[i], NR
}' docs/misra.md > "$out/deviations.txt"
awk -F'|' '/^\| *[0-9]+\.[0-9]+ *\|/ && $4 ~ /^ *[ADP] *$/ {
    if (match($5, /\([0-9]+ findings?\)/)) print NR, substr($5, RSTART + 1, RLENGTH - 2) + 0
    else print NR, "none"
}
/^\| (R[0-9]+\.[0-9]+|all) \| [0-9]+ \|$/ { r = $2; gsub(/ /, "", r); print r, $3 + 0 }' \
    docs/misra.md > "$out/stated.txt"

# 2. cppcheck: every file in the fixed build, the float-only file in the float build.
cpp() { # cache-dir numeric files...
    cache=$1; num=$2; shift 2
    cppcheck --addon=misra --std=c99 --platform=unix64 -Isrc -DUUV_NUMERIC="$num" \
        --enable=warning,portability --inline-suppr -q -j"$jobs" --cppcheck-build-dir="$cache" \
        --template='{file}:{line}:{id}:{message}' "$@" 2>&1
}
{
    cpp "$out/cache-fixed" 1 src/
    cpp "$out/cache-float" 2 src/drive_segment_float.c
} | sort -u > "$out/cppcheck.txt"

# 3. Each finding against the deviations (a glob's * also matches '/').
# The counts the document states must be the measured ones.
awk -F: -v devs="$out/deviations.txt" -v stale="$out/stale.txt" -v stated="$out/stated.txt" '
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
    if (sub(/^misra-c2012-/, "", rule)) {
        for (i = 1; i <= nd; i++) if (drule[i] == rule && file ~ dre[i]) { listed = 1; used[i]++; break }
    }
    if (listed) { dev[rule]++; ndev++ } else { print "  not listed: " $0; bad++ }
}
END {
    for (r in dev) printf "  misra %-6s %4d (listed deviations)\n", r, dev[r] | "sort -V 1>&2"
    close("sort -V 1>&2")
    for (i = 1; i <= nd; i++) { row[drow[i]] += used[i]; if (!used[i]) print dtext[i] > stale }
    for (r in dev) total["R" r] = dev[r]
    total["all"] = ndev
    while ((getline line < stated) > 0) {
        split(line, a, " ")
        if (a[1] ~ /^[0-9]+$/) { got = row[a[1]] + 0; what = "docs/misra.md:" a[1] ": the row" }
        else { got = total[a[1]] + 0; what = "docs/misra.md: the total " a[1] }
        if (a[2] != got) { print "  " what " states " a[2] " findings, measured " got; miscount++ }
        seen[a[1]] = 1
    }
    for (r in total) if (!seen[r]) { print "  docs/misra.md: no total row | " r " | " total[r] " |"; miscount++ }
    printf "cppcheck: %d findings, %d listed as deviations, %d not listed", ndev + bad, ndev, bad
    printf "%s\n", miscount ? ", " miscount " counts in docs/misra.md to update" : ""
    exit (bad > 0 || miscount > 0)
}' "$out/cppcheck.txt" > "$out/cppcheck-report.txt"
cpp_status=$?
cat "$out/cppcheck-report.txt"
if [ -s "$out/stale.txt" ]; then
    echo "deviations in docs/misra.md that match no finding (remove them):"
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
    tidy_one src/drive_segment_float.c 2
} > "$out/clang-tidy.txt"
tidy_n=$(grep -cE ': (warning|error): ' "$out/clang-tidy.txt")
grep -E ': (warning|error): ' "$out/clang-tidy.txt" | sed 's/^/  /'
echo "clang-tidy: $tidy_n findings"

failed=0
[ $cpp_status -eq 0 ] || failed=$((failed + 1))
[ "$tidy_n" -eq 0 ] || failed=$((failed + 1))
echo "lint: $((2 - failed)) passed, $failed failed"
[ $failed -eq 0 ]

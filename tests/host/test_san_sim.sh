#!/bin/sh
# The 60 s desk simulation (scenarios/default.scn cut to 60 s: speed-up from
# rest, a turn, a dive) under AddressSanitizer and UndefinedBehaviorSanitizer,
# for each sanitized uuvsim given. A run passes when it exits 0, the
# sanitizers print nothing, the summary reports 60 s simulated and no
# overrun, and the CSV has 601 rows (t = 0 to 60 s) with no NaN or infinity.
# Usage: test_san_sim.sh UUVSIM... ; prints "N passed, N failed".
set -u
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
for sim in "$@"; do
    name=$(basename "$(dirname "$sim")")
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
        "$sim" --scenario scenarios/default.scn --duration 60 --csv "$tmp/t.csv" --json \
        >"$tmp/summary.json" 2>"$tmp/stderr"
    status=$?
    why=""
    [ $status -eq 0 ] || why="exit status $status"
    grep -qE 'Sanitizer|runtime error' "$tmp/stderr" && why="$why; sanitizer report"
    grep -qE '"sim_time_s": 60[,.]' "$tmp/summary.json" || why="$why; not 60 s simulated"
    grep -qE '"overruns": 0,' "$tmp/summary.json" || why="$why; overruns"
    rows=$(($(wc -l < "$tmp/t.csv") - 1))
    [ "$rows" -eq 601 ] || why="$why; $rows CSV rows, not 601"
    grep -qiE 'nan|inf' "$tmp/t.csv" && why="$why; NaN or infinity in the CSV"
    if [ -z "$why" ]; then
        pass=$((pass + 1)); echo "  ok    $name: 60 s under ASan + UBSan, $rows rows, clean"
    else
        fail=$((fail + 1)); echo "  FAIL  $name: ${why#; }"; head -n 30 "$tmp/stderr"
    fi
done
finish

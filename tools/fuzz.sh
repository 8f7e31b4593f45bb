#!/bin/sh
# Runs the libFuzzer harnesses of tests/fuzz/ (built by make fuzz-build).
#   fuzz.sh replay NAME...            every seed of tests/fuzz/corpus_NAME/ once
#   fuzz.sh campaign SECONDS NAME...  fuzz each harness for SECONDS
#   fuzz.sh runs COUNT NAME...        fuzz each harness for COUNT executions
# New inputs a campaign finds go to $BUILD/fuzz/work_NAME/, never into the
# seed corpus; a crash leaves its input in $BUILD/fuzz/ (crash-*, leak-*, ...).
# Prints one line per harness, then "N passed, N failed" (inputs replayed,
# or harnesses fuzzed).
set -u
BUILD=${BUILD:-build}
dir="$BUILD/fuzz"
mode=$1; shift
case $mode in
    replay) ;;
    campaign|runs) limit=$1; shift ;;
    *) echo "usage: fuzz.sh replay|campaign SECONDS|runs COUNT NAME..." >&2; exit 2 ;;
esac
pass=0
fail=0
for name in "$@"; do
    exe="$dir/fuzz_$name"
    seeds="tests/fuzz/corpus_$name"
    log="$dir/$mode-$name.log"
    if [ "$mode" = replay ]; then
        n=$(ls "$seeds" | wc -l)
        if "$exe" -runs=0 "$seeds" >"$log" 2>&1; then
            pass=$((pass + n)); echo "  ok    $name: $n seeds replayed"
        else
            fail=$((fail + 1)); echo "  FAIL  $name (see $log)"; tail -n 20 "$log"
        fi
        continue
    fi
    work="$dir/work_$name"
    mkdir -p "$work"
    if [ "$mode" = campaign ]; then
        budget="-max_total_time=$limit"
    else
        budget="-runs=$limit"
    fi
    if "$exe" $budget -timeout=10 -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
            -artifact_prefix="$dir/" "$work" "$seeds" >"$log" 2>&1; then
        pass=$((pass + 1)); verdict=ok
    else
        fail=$((fail + 1)); verdict=FAIL
    fi
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    echo "  $verdict  $name: ${execs:-?} executions, $(ls "$work" | wc -l) inputs in the work corpus"
    [ "$verdict" = FAIL ] && tail -n 30 "$log"
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]

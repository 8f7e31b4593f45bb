#!/bin/sh
# The firmware's failure paths, checked (make test):
#
#   sh tools/qemu-overrun-test.sh MACHINE TEST_IMAGE.elf DESK OUTDIR
#
# TEST_IMAGE is the firmware built with FW_OVERRUN_TEST=1, which takes
# overrun=fast|medium|slow on its command line and makes the first step of
# that rate too long. Each overrun must stop the run cleanly: exit status
# 1, the telemetry stream complete and decodable, the overrun counted at
# its own level, and no hang (every run has a time limit). Then bad input:
# a scenario with an error and a missing one exit with 2 and a message
# naming the file (and line and field); and the decoder refuses a
# truncated, a corrupted and an empty stream with a message and status 2,
# leaving no CSV behind. And one preemption case: a speed command that
# falls just after a slow boundary is taken by the motor task while the
# preempted slow step of that boundary still runs; the record must still
# show the command of the boundary, as the desk simulator (DESK, fixed
# build) does. Prints one line per check and "N passed, N failed".
set -u
machine=$1; elf=$2; desk=$3; out=$4
here=$(dirname "$0")
. "$here/fw-lib.sh"
pass=0
fail=0
check() { if [ "$1" = 0 ]; then shift; pass=$((pass + 1)); echo "  ok    $*"; else
    shift; fail=$((fail + 1)); echo "  FAIL  $*"; fi; }
rm -rf "$out"
mkdir -p "$out"
export QEMU_TIMEOUT=${QEMU_TIMEOUT:-300}

# run NAME [WORD...]: the default scenario for 0.5 s at shift 0, extra command-line words.
run() {
    name=$1; shift
    args="arg=uuvsim,arg=scenario=scenarios/default.scn,arg=duration=0.5"
    for w in "$@"; do args="$args,arg=$w"; done
    mkdir -p "$out/$name"
    timeout "$QEMU_TIMEOUT" qemu-system-arm -M "$machine" -display none -monitor none \
        -serial "file:$out/$name/telemetry.bin" \
        -semihosting-config "enable=on,target=native,$args" \
        -icount shift=0,align=off,sleep=off -kernel "$elf" >"$out/$name/console.txt" 2>&1
    status=$?
    "$FW_DECODE" "$out/$name/telemetry.bin" --csv "$out/$name/telemetry.csv" \
        --json "$out/$name/summary.json" >"$out/$name/decode.txt" 2>&1
    decoded=$?
}

for rate in fast medium slow; do
    run "$rate" "overrun=$rate"
    by_rate=$(sed -n 's/.*"overruns_by_rate": {\(.*\)}.*/\1/p' "$out/$rate/summary.json" \
        2>/dev/null)
    # The summary names the medium rate after its task, the motor.
    key=$rate; [ "$rate" = medium ] && key=motor
    n=$(echo "$by_rate" | sed -n "s/.*\"$key\": \([0-9]*\).*/\1/p")
    others=$(echo "$by_rate" | sed "s/\"$key\": [0-9]*//" | grep -c '[1-9]')
    [ $status -eq 1 ] && [ $decoded -eq 0 ] && [ "${n:-0}" -ge 1 ] && [ "$others" -eq 0 ] &&
        grep -q "stopped early: a .* overran its frame" "$out/$rate/console.txt"
    check $? "a $rate overrun stops the run: exit $status (1), stream decoded ($decoded)," \
        "counted at its level ($by_rate)"
done

printf 'duration 1\nat 0 n_rpm=1000\nat 0.5 rudder=99deg\n' >"$out/bad.scn"
timeout 60 qemu-system-arm -M "$machine" -display none -monitor none -serial null \
    -semihosting-config "enable=on,target=native,arg=uuvsim,arg=scenario=$out/bad.scn" \
    -kernel "$elf" >"$out/bad.txt" 2>&1
status=$?
[ $status -eq 2 ] && grep -q "bad.scn:3: field 'rudder'" "$out/bad.txt"
check $? "a scenario error exits with 2 naming file, line and field: $(head -n 1 "$out/bad.txt")"

timeout 60 qemu-system-arm -M "$machine" -display none -monitor none -serial null \
    -semihosting-config "enable=on,target=native,arg=uuvsim,arg=scenario=$out/none.scn" \
    -kernel "$elf" >"$out/none.txt" 2>&1
status=$?
[ $status -eq 2 ] && grep -q "none.scn: cannot open" "$out/none.txt"
check $? "a missing scenario exits with 2: $(head -n 1 "$out/none.txt")"

# The slow step of the 0.1 s boundary lasts over a millisecond at shift 1
# (software double precision), past the controller's tick at 0.1008 s.
printf 'duration 0.3\nat 0 n_rpm=1000\nat 0.1004 n_rpm=1200\n' >"$out/between.scn"
sh "$here/qemu-run.sh" "$machine" "$elf" "$out/between.scn" "" "$out/between" 1 \
    "$FW_DECODE" >"$out/between.txt" 2>&1
"$desk" --quiet --scenario "$out/between.scn" --csv "$out/between-desk.csv"
cmp -s "$out/between-desk.csv" "$out/between/telemetry.csv"
check $? "preemption: a command taken by the motor task during a slow step is reported as" \
    "on the desk (CSV byte-identical)"

# The decoder on damaged streams, cut from the medium-overrun run's.
good=$out/medium/telemetry.bin
size=$(wc -c <"$good")
refuse() { # NAME PATTERN FILE
    "$FW_DECODE" "$3" --csv "$out/damaged.csv" >"$out/decode-$1.txt" 2>&1
    status=$?
    [ $status -eq 2 ] && grep -q "$2" "$out/decode-$1.txt" && [ ! -e "$out/damaged.csv" ] &&
        [ -z "$(ls "$out" | grep "damaged.csv.partial")" ]
    check $? "decoder refuses a $1 stream (exit $status): $(head -n 1 "$out/decode-$1.txt")"
}
head -c $((size - 100)) "$good" >"$out/truncated.bin"
refuse truncated "truncated" "$out/truncated.bin"
cp "$good" "$out/corrupt.bin"
printf '\377' | dd of="$out/corrupt.bin" bs=1 seek=100 conv=notrunc 2>/dev/null
refuse corrupted "CRC mismatch" "$out/corrupt.bin"
: >"$out/empty.bin"
refuse empty "empty" "$out/empty.bin"
head -c 7 "$good" >"$out/header.bin"
refuse "header-only" "truncated" "$out/header.bin"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]

#!/bin/sh
# The firmware simulation of one machine and build, checked (make test):
#
#   sh tools/qemu-sim-test.sh MACHINE NUM IMAGE DESK OUTDIR
#
# Runs the default scenario for FW_TEST_DURATION simulated seconds under
# -icount shift=FW_TEST_SHIFT (then at smaller shifts when it overran, to
# find where it passes) and checks:
#   - the decoded telemetry CSV is byte-identical to the desk simulator's
#     (DESK, the same numeric build) for the same scenario and duration,
#     and the summary's steps, energies and final state equal the desk's;
#   - the instruction counts cover every tick (the plugin saw every entry
#     and exit);
#   - the stack: the static worst case fits in the reserved stack, and so
#     does the measured high-water mark;
#   - the footprint of the Cortex-M3 fixed images: flash <= 64 KiB,
#     RAM <= 16 KiB including the stack;
#   - real time at the shift the image claims (fw_claim below): no overrun
#     there; the run at FW_TEST_SHIFT and the shift it passes at are
#     printed beside it;
#   - the mean fast tick (the drive's work, drive_fast) within the image's
#     budget (fw_claim).
# Every criterion fails the run when it is not met.
# FW_TEST_DESK_ARGS adds options to the desk's runs: --params FILE for an
# image built with that set (uuvsim-NAME.elf, make firmware PARAMS=FILE).
# Prints one line per check and "N passed, N failed".
set -u
machine=$1; num=$2; elf=$3; desk=$4; out=$5
. "$(dirname "$0")/fw-lib.sh"
variant=$machine-$num
shift_n=${FW_TEST_SHIFT:-3}
duration=${FW_TEST_DURATION:-0.5}
scenario=${FW_TEST_SCENARIO:-scenarios/default.scn}
pass=0
fail=0
ok() { pass=$((pass + 1)); echo "  ok    $*"; }
bad() { fail=$((fail + 1)); echo "  FAIL  $*"; }
check() { if [ "$1" = 0 ]; then shift; ok "$@"; else shift; bad "$@"; fi; }
# What an image claims: the -icount shift at which it keeps real time
# (2^shift ns per instruction: shift 3 is a 125 MHz core, one instruction a
# cycle) and the budget of its drive's mean fast step (drive_fast: the
# Thumb-2 kernel in the fixed M4/M7 images, the C step elsewhere;
# instructions), "-" for none. The budgets are set above what the images
# measure with the default sub-step modulator (0.5 s of the default
# scenario, mps2-an386: drive_fast 126.2 fixed, 7 % below 135, and 194.1
# float, 14 % below 225; the same on mps2-an500); they guard against
# regressions. The fixed M4 and M7
# images keep real time at shift 3, the design's target (docs/firmware.md,
# section 9). The Cortex-M3 images have no 2 us target (50 MHz parts).
fw_claim() { # VARIANT -> "SHIFT BUDGET"
    case $1 in
        mps2-an386-fixed | mps2-an500-fixed | netduinoplus2-fixed) echo "3 135" ;;
        mps2-an386-float | mps2-an500-float | netduinoplus2-float) echo "2 225" ;;
        mps2-an385-fixed | lm3s6965evb-fixed) echo "2 -" ;;
        *) echo "- -" ;;
    esac
}
set -- $(fw_claim "$variant")
claim_shift=$1; budget=$2

rm -rf "$out"
mkdir -p "$out"

fw_run_until_pass "$machine" "$elf" "$scenario" "$duration" "$out/run" "$shift_n"
if [ -z "$fw_pass_shift" ]; then
    bad "$variant: no run completed without overrun at shift $shift_n or below (see $out/run.*.log)"
    echo "$pass passed, $fail failed"
    exit 1
fi
dir=$fw_pass_dir
sum=$dir/summary.json
echo "  run   $variant: $duration s of $scenario; at shift $shift_n: $fw_overruns_first" \
     "overrun(s) (stopped at $fw_stopped_first s); passes at shift $fw_pass_shift"

# shellcheck disable=SC2086 # the desk options are a list of words
"$desk" ${FW_TEST_DESK_ARGS:-} --quiet --scenario "$scenario" --duration "$duration" \
    --csv "$out/desk.csv"
# shellcheck disable=SC2086
"$desk" ${FW_TEST_DESK_ARGS:-} --json --scenario "$scenario" --duration "$duration" \
    >"$out/desk.json"
cmp -s "$out/desk.csv" "$dir/telemetry.csv"
check $? "$variant: decoded telemetry CSV byte-identical to the desk simulator's ($num build)"
same=0
for key in '"steps"' '"saturations"' '"battery_energy_wh"' '"mechanical_energy_wh"' '"final"'; do
    a=$(grep "^  $key" "$out/desk.json" | sed 's/,$//')
    b=$(grep "^  $key" "$sum" | sed 's/,$//')
    [ -n "$a" ] && [ "$a" = "$b" ] || { same=1; echo "        differs: $a / $b"; }
done
check $same "$variant: summary steps, saturations, energies and final state equal the desk's"

errors=$(sed -n 's/.*"errors": \([0-9]*\).*/\1/p' "$sum")
fast_n=$(fw_json "$sum" fast_tick count)
steps_fast=$(sed -n 's/.*"steps": {"fast": \([0-9]*\).*/\1/p' "$sum")
# One tick per fast step, and one more: the second half of the run's last
# boundary has a tick of its own, without a step (executive.c, boundary_end).
[ "$errors" = 0 ] && [ "$fast_n" = $((steps_fast + 1)) ]
check $? "$variant: instruction counts cover every fast tick ($fast_n ticks for $steps_fast" \
    "steps and the last boundary's), no unmatched region exit ($errors)"

fw_sizes "$elf"
fw_stack_static "$elf" "$out" "$machine"
known=$?
measured=$(fw_json "$sum" stack_used_bytes)
[ $known -eq 0 ] && [ "$fw_stack_worst" -le "$fw_stack_reserved" ] &&
    [ "$measured" -le "$fw_stack_worst" ]
check $? "$variant: stack: measured $measured <= static worst case $fw_stack_worst <=" \
    "reserved $fw_stack_reserved bytes"
if [ "$num" = fixed ] && { [ "$machine" = mps2-an385 ] || [ "$machine" = lm3s6965evb ]; }; then
    [ "$fw_flash" -le 65536 ] && [ "$fw_ram" -le 16384 ]
    check $? "$variant: Cortex-M3 footprint: flash $fw_flash <= 65536, RAM $fw_ram <= 16384" \
        "bytes (stack included)"
fi

mean=$(fw_json "$sum" fast_tick mean)
max=$(fw_json "$sum" fast_tick max)
if [ "$claim_shift" = - ]; then
    bad "$variant: the image claims no real-time shift (fw_claim)"
else
    [ -n "$fw_pass_shift" ] && [ "$fw_pass_shift" -ge "$claim_shift" ]
    check $? "$variant: real time at its claimed shift $claim_shift ($((1 << claim_shift)) ns" \
        "per instruction): passes at shift $fw_pass_shift; at shift $shift_n" \
        "$fw_overruns_first overrun(s)"
fi
# The issue's fast tick is the drive's work (PWM, inverter, DC link,
# filter, sums): drive_fast (tools/fw-regions.sh); the handler adds the
# executive's bookkeeping and is reported beside it.
drive=$(fw_json "$sum" drive_fast mean)
if [ "$budget" != - ]; then
    awk -v m="$drive" -v b="$budget" 'BEGIN { exit !(m <= b) }'
    check $? "$variant: fast tick (drive_fast) mean $drive <= $budget instructions" \
        "(handler mean $mean, max $max)"
else
    ok "$variant: fast tick reported: drive_fast mean $drive, handler mean $mean, max $max"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]

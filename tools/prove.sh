#!/bin/sh
# make prove: Frama-C Eva over src/fixedpoint, driven by
# tools/prove/fixedpoint_eva.c (every function, every allowed input).
# Fails on any alarm, on any annotation not proven valid, and on any
# statement of the driver or of src/fixedpoint that Eva did not reach (a
# statement never reached is a statement nothing was proven about).
# Needs frama-c-base (apt-get install frama-c-base).
# Prints the alarm count and "N passed, N failed". Log: $BUILD/prove/eva.log
#
# Precision: every -eva-precision level from 2 up proves it (level 1 leaves
# alarms in the float conversions); 5 keeps a margin over 2 and runs in
# about 35 s, where level 11 takes 3 to 4 minutes. A level only trades run
# time for precision: a less precise run can report more alarms, never
# fewer, so the level chosen cannot hide one.
set -u
BUILD=${BUILD:-build}
out="$BUILD/prove"
mkdir -p "$out"
if ! command -v frama-c >/dev/null 2>&1; then
    echo "frama-c is missing: apt-get install -y --no-install-recommends frama-c-base" >&2
    exit 2
fi
frama-c \
    -machdep x86_32 -cpp-extra-args="-Isrc -DUUV_NUMERIC=1 -ffreestanding" \
    -eva -eva-precision 5 -eva-subdivide-non-linear 64 -warn-special-float none -eva-warn-undefined-pointer-comparison pointer \
    -eva-report-red-statuses "$out/red.csv" -warn-signed-overflow -warn-signed-downcast \
    -warn-right-shift-negative -warn-left-shift-negative \
    -eva-msg-key=-summary \
    tools/prove/fixedpoint_eva.c src/fixedpoint/fixedpoint.c src/fixedpoint/wavetable.c \
    src/fixedpoint/wavetable_data.c \
    -then -report -report-no-proven -report-print-properties \
    -then -metrics -metrics-eva-cover > "$out/eva.log" 2>&1
status=$?
alarms=$(grep -c '\[eva:alarm\]' "$out/eva.log")
errors=$(grep -cE '\[kernel\] (User Error|Failure)|\[eva\] .*(invalid|degeneration)' "$out/eva.log")
# The report plugin lists every property not proven valid (alarms included),
# each under a status box such as "[    -    ]" or "[ Invalid ]".
unproven=$(sed -n '/^\[report\] Computing/,/^\[metrics\]/p' "$out/eva.log" |
    grep -cE '^\[[ A-Za-z-]{9}\]')
# "N stmts in analyzed functions, M stmts analyzed (P%)"
reach=$(sed -n 's/^ *\([0-9]*\) stmts in analyzed functions, \([0-9]*\) stmts analyzed.*/\2 of \1/p' \
    "$out/eva.log")
grep -E '\[eva:alarm\]|User Error|Failure' "$out/eva.log" | head -n 40
echo "frama-c eva over src/fixedpoint: $alarms alarms, $unproven properties not proven," \
    "statements reached: ${reach:-unknown} (exit $status)"
if [ $status -eq 0 ] && [ "$alarms" -eq 0 ] && [ "$errors" -eq 0 ] && [ "$unproven" -eq 0 ] &&
    [ -n "$reach" ] && [ "${reach% of *}" = "${reach#* of }" ]; then
    echo "prove: 1 passed, 0 failed"
else
    echo "prove: 0 passed, 1 failed"
    exit 1
fi

#!/bin/sh
# make prove: Frama-C Eva over src/fixedpoint, driven by
# tools/prove/fixedpoint_eva.c (every function, every allowed input).
# Fails on any alarm. Needs frama-c-base (apt-get install frama-c-base).
# Prints the alarm count and "N passed, N failed". Log: $BUILD/prove/eva.log
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
    -eva -eva-precision 11 -eva-subdivide-non-linear 64 -warn-special-float none -eva-warn-undefined-pointer-comparison pointer \
    -eva-report-red-statuses "$out/red.csv" -warn-signed-overflow -warn-signed-downcast \
    -warn-right-shift-negative -warn-left-shift-negative \
    -eva-msg-key=-summary \
    tools/prove/fixedpoint_eva.c src/fixedpoint/fixedpoint.c src/fixedpoint/wavetable.c \
    src/fixedpoint/wavetable_data.c > "$out/eva.log" 2>&1
status=$?
alarms=$(grep -c '\[eva:alarm\]' "$out/eva.log")
errors=$(grep -cE '\[kernel\] (User Error|Failure)|\[eva\] .*(invalid|degeneration)' "$out/eva.log")
grep -E '\[eva:alarm\]|User Error|Failure' "$out/eva.log" | head -n 40
echo "frama-c eva over src/fixedpoint: $alarms alarms (exit $status)"
if [ $status -eq 0 ] && [ "$alarms" -eq 0 ] && [ "$errors" -eq 0 ]; then
    echo "prove: 1 passed, 0 failed"
else
    echo "prove: 0 passed, 1 failed"
    exit 1
fi

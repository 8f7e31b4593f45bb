#!/bin/sh
# Runs every test program the build made, on the host and under QEMU, and
# prints one line per run, then the total as "N passed, N failed".
# Each run's full output is kept in $BUILD/test-logs/. A run counts as failed
# when its exit status is not 0 or its last line reports a failure; the
# must-fail programs must fail, which proves that a failing check is seen:
# their rows show the planted failure's counts and say so.
set -u
BUILD=${BUILD:-build}
logs="$BUILD/test-logs"
mkdir -p "$logs"
total_pass=0
total_fail=0
runs_bad=0
QEMU_TIMEOUT=${QEMU_TIMEOUT:-600}

qemu_cmd() { # machine image
    echo "timeout $QEMU_TIMEOUT qemu-system-arm -M $1 -display none -serial none -monitor none" \
         "-chardev stdio,id=sh0 -semihosting-config enable=on,target=native,chardev=sh0" \
         "-kernel $2"
}

# The rows run $TEST_JOBS at a time (default: the machine's cores), each in
# the background with its own log; a row's line is printed once it and every
# row before it are done, so the output keeps the order below. Rows that
# run make themselves (serial) wait for the others and run alone.
TEST_JOBS=${TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
rows="$logs/.rows"
rm -rf "$rows"
mkdir -p "$rows"
nrow=0       # rows started
nprinted=0   # rows printed

# one_row N LABEL EXPECT COMMAND...: runs a row, writes its line and counts.
one_row() {
    n=$1; label=$2; expect=$3; shift 3
    log="$logs/$(echo "$label" | tr ' /' '__').log"
    start=$(date +%s)
    "$@" >"$log" 2>&1 </dev/null
    status=$?
    secs=$(( $(date +%s) - start ))
    counts=$(grep -E '^([A-Za-z]+: )?[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
    p=$(echo "$counts" | sed -n 's/.*\b\([0-9][0-9]*\) passed.*/\1/p')
    f=$(echo "$counts" | sed -n 's/.* \([0-9][0-9]*\) failed.*/\1/p')
    p=${p:-0}; f=${f:-0}
    bad=0
    if [ "$expect" = pass ]; then
        if [ $status -eq 0 ] && [ "$f" -eq 0 ] && [ -n "$counts" ]; then
            verdict=ok
        else
            verdict=FAILED; bad=1
            [ "$f" -eq 0 ] && f=1
        fi
    else
        # A must-fail run passes when the program failed and said so.
        if [ $status -ne 0 ] && [ "$f" -gt 0 ]; then
            verdict="ok: must fail, and its planted failure was seen (proves failures count)"
            p=1; f=0
        else
            verdict="FAILED (a failing check went unseen)"
            bad=1; p=0; f=1
        fi
    fi
    [ "$expect" = fail ] && counts="${counts:+planted: }$counts"
    {
        printf '%-44s %-26s %4ss  %s\n' "$label" "${counts:-no result line}" "$secs" "$verdict"
        case $verdict in
            FAILED*) grep -E 'FAIL|fatal|error' "$log" | head -n 20 | sed 's/^/    /' ;;
        esac
    } >"$rows/$n.line"
    echo "$p $f $bad" >"$rows/$n.counts"
    : >"$rows/$n.done"
}

# Prints the finished rows that follow the last printed one.
flush_rows() {
    while [ $nprinted -lt $nrow ] && [ -e "$rows/$((nprinted + 1)).done" ]; do
        nprinted=$((nprinted + 1))
        cat "$rows/$nprinted.line"
    done
}

# Waits until fewer than $1 rows are running.
wait_rows() {
    while :; do
        flush_rows
        running=$((nrow - $(ls "$rows" | grep -c '\.done$')))
        [ $running -lt "$1" ] && break
        sleep 0.2
    done
}

# run LABEL EXPECT(pass|fail) COMMAND...
run() {
    wait_rows "$TEST_JOBS"
    nrow=$((nrow + 1))
    one_row $nrow "$@" &
}

# serial LABEL EXPECT COMMAND...: a row that runs alone.
serial() {
    wait_rows 1
    nrow=$((nrow + 1))
    one_row $nrow "$@"
    flush_rows
}

# section TITLE: a heading, printed in its place among the rows.
section() {
    nrow=$((nrow + 1))
    echo "$1" >"$rows/$nrow.line"
    : >"$rows/$nrow.done"
}

section "== host =="
for v in $HOST_VARIANTS; do
    run "host $v unit_tests" pass "$BUILD/$v/unit_tests"
done
run "host linux-fixed must-fail" fail "$BUILD/linux-fixed/unit_tests_mustfail"
for v in linux-fixed linux-float; do
    run "host $v uuvsim end-to-end" pass sh tests/host/test_uuvsim_cli.sh "$BUILD/$v/uuvsim" \
        "$BUILD/tools/csvdiff"
done
for v in linux-fixed linux-float; do
    run "host $v property, 3000 random cases" pass "$BUILD/$v/property" 3000 1
    run "host $v property through uuvsim, 100" pass sh tests/host/test_property.sh \
        "$BUILD/$v/uuvsim" 100 1
    run "host $v output safety" pass sh tests/host/test_outputs.sh "$BUILD/$v/uuvsim"
    run "host $v batch = its single runs" pass sh tests/host/test_batch.sh \
        "$BUILD/$v/uuvsim"
    run "host $v batch lanes = scalar step" pass \
        "$BUILD/$v/test_batch_lanes"
done
for v in linux-fixed linux-float; do
    run "host $v parameter sets" pass sh tests/host/test_params.sh "$BUILD/$v/uuvsim"
    run "host $v sweeps, resume, shards" pass sh tests/host/test_sweep.sh "$BUILD/$v/uuvsim"
    run "host $v fault injection" pass sh tests/host/test_faults.sh "$BUILD/$v/uuvsim"
    run "host $v leaps (--fast-path leap)" pass sh tests/host/test_leap.sh "$BUILD/$v/uuvsim"
    run "host $v soak, 600 s (make soak: 3600 s)" pass sh tests/host/test_soak.sh \
        "$BUILD/$v/uuvsim" 600
done
for n in fixed float; do
    run "host fmu-$n: FMU through a test master" pass sh tests/host/test_fmu.sh \
        "$BUILD/fmu-$n/uuvsim.fmu" "$BUILD/linux-$n/uuvsim" "$BUILD/tools/fmu_import"
done
run "host uuvsim-decode on crafted streams" pass sh tests/host/test_decode.sh \
    "$BUILD/tools/uuvsim-decode"
run "host make run's plots (gnuplot)" pass sh tests/host/test_plots.sh "$BUILD/linux-float/uuvsim"
run "host make run's dependencies, kept files" pass sh tests/host/test_make.sh
run "host uuvsim view and --view in Chromium" pass sh tests/host/test_view.sh \
    "$BUILD/linux-float/uuvsim"
run "host math vs libm" pass "$BUILD/tools/test_math_libm"
run "host CSV number text vs printf" pass "$BUILD/tools/test_csv_number"
run "host drive controller closed loop" pass "$BUILD/tools/sim_drive_control"
run "host check_tables (exhaustive)" pass "$BUILD/tools/check_tables"
run "host wavetable_data.c = generator" pass "$BUILD/tools/gen_wavetables" --check \
    src/fixedpoint/wavetable_data.c

run "host linux-float leaps: edge maps, AVX-512 and AVX2 forms" pass "$BUILD/linux-float/test_leap_forms"
run "host lint (cppcheck MISRA, clang-tidy)" pass sh tools/lint.sh
# The desk's vector code in its portable form (no AVX2 leaps, the compiler's baseline lanes):
# what a host without AVX2 and FMA, or an AArch64 one, builds.
portable="$BUILD/portable"
portable_make="make -s --no-print-directory BUILD=$portable LEAP_ARCH= BATCH_LANES_FLAGS="
serial "host linux-float leaps, portable form (LEAP_ARCH=)" pass sh -c \
    "$portable_make $portable/linux-float/uuvsim && \
     sh tests/host/test_leap.sh $portable/linux-float/uuvsim"
for v in linux-fixed linux-float; do
    serial "host $v batch lanes, portable form (BATCH_LANES_FLAGS=)" pass sh -c \
        "$portable_make $portable/$v/test_batch_lanes && $portable/$v/test_batch_lanes"
done
serial "host fuzz corpus replay (ASan+UBSan)" pass make --no-print-directory BUILD="$BUILD" fuzz-replay
serial "host 60 s desk simulation (ASan+UBSan)" pass make --no-print-directory BUILD="$BUILD" san-sim

section "== qemu =="
for v in $FW_VARIANTS; do
    machine=${v%-*}
    # A machine whose flash cannot hold every suite runs them in parts.
    for image in "$BUILD/cortexm-$v"/unit_tests.elf "$BUILD/cortexm-$v"/unit_tests_part*.elf; do
        [ -f "$image" ] || continue
        name=$(basename "$image" .elf)
        run "qemu $v $name" pass $(qemu_cmd "$machine" "$image")
    done
done
run "qemu mps2-an385-fixed must-fail" fail \
    $(qemu_cmd mps2-an385 "$BUILD/cortexm-mps2-an385-fixed/unit_tests_mustfail.elf")

# The firmware simulation: each image runs the default scenario under
# -icount and is compared with the desk simulator of its numeric build.
section "== qemu simulation (shift ${FW_TEST_SHIFT:-3}, ${FW_TEST_DURATION:-0.5} s) =="
for v in $FW_VARIANTS; do
    machine=${v%-*}
    num=${v##*-}
    run "qemu $v simulation" pass sh tools/qemu-sim-test.sh "$machine" "$num" \
        "$BUILD/cortexm-$v/uuvsim.elf" "$BUILD/linux-$num/uuvsim" "$BUILD/qemu-test/$v"
done
# A shipped non-default set compiled into the image (uuvsim-motor4kw.elf,
# as make firmware PARAMS=params/motor4kw.params builds it), against the
# desk with --params.
for num in fixed float; do
    run "qemu mps2-an386-$num simulation, set motor4kw" pass \
        env FW_TEST_SCENARIO=scenarios/from_rest_1000rpm.scn \
        FW_TEST_DESK_ARGS="--params params/motor4kw.params" sh tools/qemu-sim-test.sh \
        mps2-an386 "$num" "$BUILD/cortexm-mps2-an386-$num/uuvsim-motor4kw.elf" \
        "$BUILD/linux-$num/uuvsim" "$BUILD/qemu-test/mps2-an386-$num-motor4kw"
done
# The real-time criterion fails make test: the overrun test image with
# every fast tick some 350 instructions longer no longer keeps real time at
# the shift the image claims.
run "qemu mps2-an386-fixed simulation, slowed fast tick" fail \
    env FW_RUN_ARGS=overrun=slowed sh tools/qemu-sim-test.sh mps2-an386 fixed \
    "$BUILD/cortexm-mps2-an386-fixed/uuvsim_overrun.elf" "$BUILD/linux-fixed/uuvsim" \
    "$BUILD/qemu-test/mps2-an386-fixed-slowed"
run "qemu mps2-an386-fixed overruns, bad input" pass sh tools/qemu-overrun-test.sh \
    mps2-an386 "$BUILD/cortexm-mps2-an386-fixed/uuvsim_overrun.elf" "$BUILD/linux-fixed/uuvsim" \
    "$BUILD/qemu-test/overrun"
# The multi-party run (docs/cosimulation.md): the drive under QEMU, the slow
# segment in uuvsim party, against the desk and the all-firmware run; a
# corrupted and a lost frame stop it.
for num in fixed float; do
    run "qemu mps2-an386-$num multi-party run" pass sh tests/host/test_party.sh mps2-an386 \
        "$BUILD/cortexm-mps2-an386-$num/uuvsim_party.elf" \
        "$BUILD/cortexm-mps2-an386-$num/uuvsim.elf" "$BUILD/linux-$num/uuvsim" \
        "${FW_DECODE:-$BUILD/tools/uuvsim-decode}" "$BUILD/qemu-test/party-$num"
done

wait
flush_rows
for c in "$rows"/*.counts; do
    read -r p f bad <"$c"
    total_pass=$((total_pass + p)); total_fail=$((total_fail + f)); runs_bad=$((runs_bad + bad))
done
echo "logs in $logs/"
echo "$total_pass passed, $total_fail failed"
[ $runs_bad -eq 0 ]

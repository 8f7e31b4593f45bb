#!/bin/sh
# The real-time budgets of the firmware simulation, measured under QEMU
# with deterministic time (make qemu-bench):
#
#   sh tools/qemu-bench.sh BUILD DURATION VARIANT...
#
# For each machine and build (VARIANT = MACHINE-fixed|float): the default
# scenario for DURATION simulated seconds under -icount shift=3 (8 ns per
# instruction), and when it overruns at 2, 1, 0 until a shift passes;
# the instruction counts per fast tick, motor tick, controller tick and
# background step of the passing run (they do not depend on the shift);
# the CPU load each rate would take at shift 3; flash, RAM and the static
# worst-case stack; whether the decoded CSV equals the desk simulator's.
# Writes BUILD/qemu-bench.json (a list of records) and prints a table.
# Needs FW_DECODE, FW_PLUGIN, FW_STACK in the environment.
set -u
build=$1; duration=$2; shift 2
. "$(dirname "$0")/fw-lib.sh"
scenario=scenarios/default.scn
base=$build/qemu-bench
mkdir -p "$base"
json=$build/qemu-bench.json
rows=$base/table.txt
: >"$rows"
printf '[' >"$json.partial"
sep=""
for v in "$@"; do
    machine=${v%-*}
    num=${v##*-}
    elf=$build/cortexm-$v/uuvsim.elf
    out=$base/$v
    rm -rf "$out"
    mkdir -p "$out"
    echo "qemu-bench: $v ..." >&2
    fw_sizes "$elf"
    fw_stack_static "$elf" "$out" "$machine" || fw_stack_worst=null
    fw_run_until_pass "$machine" "$elf" "$scenario" "$duration" "$out/run" 3
    sum=${fw_pass_dir:+$fw_pass_dir/summary.json}
    if [ -z "$sum" ]; then
        # No shift passed: report what the shift-0 run measured before it stopped.
        sum=$out/run/shift0/summary.json
    fi
    j() { if [ -f "$sum" ]; then fw_json "$sum" "$@"; else echo null; fi; }
    identical=false
    if [ -n "$fw_pass_dir" ]; then
        "$build/linux-$num/uuvsim" --quiet --scenario "$scenario" --duration "$duration" \
            --csv "$out/desk.csv" && cmp -s "$out/desk.csv" "$fw_pass_dir/telemetry.csv" &&
            identical=true
    fi
    ps=${fw_pass_shift:-null}
    # CPU load at shift 3, from the passing run's load at its own shift.
    scale=$(( 1 << (3 - ${fw_pass_shift:-3}) ))
    load() { awk -v l="$(j cpu_load "$1")" -v k="$scale" 'BEGIN {
        if (l == "null") print "null"; else printf "%.4f", l * k }'; }
    cat >>"$json.partial" <<EOF
$sep
  {"machine": "$machine", "build": "$num", "shift": 3, "overruns": ${fw_overruns_first:-null},
   "stopped_at_s": ${fw_stopped_first:-null}, "pass_shift": $ps, "duration_s": $duration,
   "fast_tick_insn_min": $(j fast_tick min), "fast_tick_insn_mean": $(j fast_tick mean),
   "fast_tick_insn_max": $(j fast_tick max), "drive_fast_insn_mean": $(j drive_fast mean),
   "motor_tick_insn_mean": $(j motor_tick mean), "motor_tick_insn_max": $(j motor_tick max),
   "control_tick_insn_mean": $(j control_tick mean), "control_tick_insn_max": $(j control_tick max),
   "controller_insn_max": $(j controller max),
   "background_step_insn_mean": $(j background_step mean),
   "background_step_insn_max": $(j background_step max),
   "load_fast_at_shift3": $(load fast), "load_medium_at_shift3": $(load medium),
   "load_control_at_shift3": $(load control),
   "load_background_at_shift3": $(load background),
   "flash_bytes": $fw_flash, "ram_bytes": $fw_ram, "stack_bytes": $fw_stack_worst,
   "stack_reserved_bytes": $fw_stack_reserved, "stack_measured_bytes": $(j stack_used_bytes),
   "csv_identical": $identical}
EOF
    sep=","
    printf '%-14s %-5s %6s %6s %5s/%-5s %6s %5s %6s %6s %8s %4s %5s %s\n' "$machine" "$num" \
        "$fw_flash" "$fw_ram" "$fw_stack_worst" "$fw_stack_reserved" "$(j fast_tick mean)" \
        "$(j fast_tick max)" "$(j motor_tick max)" "$(j control_tick max)" \
        "$(j background_step max)" "${fw_overruns_first:-?}" \
        "$ps" "$identical" >>"$rows"
done
printf '\n]\n' >>"$json.partial"
mv "$json.partial" "$json"
echo "firmware simulation, $duration s of $scenario; instructions per invocation (the run"
echo "at the largest shift <= 3 without overrun); overruns at shift 3 (8 ns per instruction)"
printf '%-14s %-5s %6s %6s %11s %6s %5s %6s %6s %8s %4s %5s %s\n' machine build flash ram \
    "stack/resv" "fast" "max" "motor" "ctrl" "bg max" "ovr3" "pass" "csv=desk"
cat "$rows"
echo "written $json"

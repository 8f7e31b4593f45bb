#!/bin/sh
# Runs the firmware simulation of one machine and build under QEMU with
# deterministic time (-icount shift=SHIFT,align=off,sleep=off: 2^SHIFT ns
# per instruction) and decodes what it streamed:
#
#   sh tools/qemu-run.sh MACHINE IMAGE.elf SCENARIO DURATION OUTDIR SHIFT DECODER [PLUGIN]
#
# DURATION may be empty (the scenario's own). OUTDIR receives
#   telemetry.bin   the UART stream (src/telemetry.h frames)
#   telemetry.csv   decoded: the desk simulator's --csv format
#   summary.json    steps, overruns, instruction counts, CPU load, final state
#   console.txt     the firmware's messages (semihosting console)
#   insn.txt        the raw counts of the instruction-count plugin (with PLUGIN)
# The console is also printed. Exit status: the firmware's (0 completed,
# 1 overrun, 2 bad input, 3 fault), 124 when QEMU timed out, 2 when the
# stream could not be decoded. QEMU_TIMEOUT (seconds) overrides the limit.
set -u
if [ $# -lt 7 ]; then
    echo "usage: qemu-run.sh MACHINE IMAGE SCENARIO DURATION OUTDIR SHIFT DECODER [PLUGIN]" >&2
    exit 2
fi
machine=$1; elf=$2; scenario=$3; duration=$4; out=$5; shift_n=$6; decode=$7; plugin=${8:-}
here=$(dirname "$0")

. "$here/fw-lib.sh"
fw_run_args qemu-run "$scenario" "$duration" "$elf" "$shift_n"
limit=$fw_limit

mkdir -p "$out" || exit 2
rm -f "$out/telemetry.bin" "$out/telemetry.csv" "$out/summary.json" "$out/console.txt" \
      "$out/insn.txt"

args="arg=uuvsim,arg=scenario=$scenario"
[ -n "$duration" ] && args="$args,arg=duration=$duration"
# FW_RUN_ARGS: more words for the firmware's command line (a test image's overrun=...).
for w in ${FW_RUN_ARGS:-}; do args="$args,arg=$w"; done
plugin_opt=""
if [ -n "$plugin" ]; then
    regions=$(sh "$here/fw-regions.sh" "$elf" | tr '\n' ',' | sed 's/,$//') || exit 2
    plugin_opt="-plugin $plugin,out=$out/insn.txt,$regions"
fi

# shellcheck disable=SC2086 # plugin_opt is a list of words by design
# The firmware's console (semihosting ":tt") is QEMU's standard output.
timeout "$limit" qemu-system-arm -M "$machine" -display none -monitor none \
    -serial "file:$out/telemetry.bin" \
    -semihosting-config "enable=on,target=native,$args" \
    -icount "shift=$shift_n,align=off,sleep=off" \
    $plugin_opt -kernel "$elf" >"$out/console.txt"
status=$?
cat "$out/console.txt"
if [ $status -eq 124 ]; then
    echo "qemu-run: QEMU did not finish within $limit s (raise QEMU_TIMEOUT)" >&2
    exit 124
fi
if [ $status -gt 3 ]; then
    echo "qemu-run: QEMU failed (exit $status): see the messages above" >&2
    exit $status
fi
insn_opt=""
[ -n "$plugin" ] && insn_opt="--insn $out/insn.txt"
# shellcheck disable=SC2086
"$decode" "$out/telemetry.bin" --csv "$out/telemetry.csv" --json "$out/summary.json" \
    --shift "$shift_n" --scenario "$scenario" $insn_opt || exit 2
echo "qemu-run: $machine, shift $shift_n: $out/telemetry.csv, $out/summary.json"
exit $status

#!/bin/sh
# The multi-party run (docs/cosimulation.md): the drive as firmware under
# QEMU (the multi-party image), the slow segment in `uuvsim party` on the
# host, connected through the firmware's UART (a QEMU socket character
# device on a Unix socket that uuvsim party listens on):
#
#   sh tools/qemu-party.sh MACHINE IMAGE UUVSIM SCENARIO DURATION OUTDIR SHIFT [HOST OPTIONS...]
#
# DURATION may be empty (the scenario's own). HOST OPTIONS go to uuvsim
# party (e.g. --corrupt-down 5 for the tests). OUTDIR receives
#   telemetry.csv   the desk simulator's --csv format (written by uuvsim party)
#   console.txt     the firmware's messages (semihosting console)
#   host.txt        uuvsim party's messages
# Both are also printed. Exit status: uuvsim party's when it fails (2 a
# link failure or bad input, 1 the drive overran, 3 a state became
# non-finite), else the firmware's; 124 when QEMU did not finish in time.
set -u
if [ $# -lt 7 ]; then
    echo "usage: qemu-party.sh MACHINE IMAGE UUVSIM SCENARIO DURATION OUTDIR SHIFT [HOST OPTIONS...]" >&2
    exit 2
fi
machine=$1; elf=$2; uuvsim=$3; scenario=$4; duration=$5; out=$6; shift_n=$7
shift 7

. "$(dirname "$0")/fw-lib.sh"
fw_run_args qemu-party "$scenario" "$duration" "$elf" "$shift_n"
limit=$fw_limit
[ -x "$uuvsim" ] || { echo "qemu-party: $uuvsim: no such program" >&2; exit 2; }

mkdir -p "$out" || exit 2
rm -f "$out/telemetry.csv" "$out/console.txt" "$out/host.txt"
# A short private directory for the socket (a Unix socket's path is at most 107 bytes).
sockdir=$(mktemp -d) || exit 2
sock=$sockdir/link
qemu_pid=""
cleanup() {
    [ -n "$qemu_pid" ] && kill "$qemu_pid" 2>/dev/null
    rm -rf "$sockdir"
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP

dur_opt=""
[ -n "$duration" ] && dur_opt="--duration $duration"
# shellcheck disable=SC2086 # dur_opt is a list of words by design
"$uuvsim" party --link "$sock" --scenario "$scenario" $dur_opt --csv "$out/telemetry.csv" \
    --timeout "$limit" "$@" >"$out/host.txt" 2>&1 &
host_pid=$!

# The socket's path appears once it is listening (uuvsim party renames it into place).
tries=0
while [ ! -S "$sock" ]; do
    if ! kill -0 "$host_pid" 2>/dev/null; then
        wait "$host_pid"; status=$?
        cat "$out/host.txt"
        exit $status
    fi
    tries=$((tries + 1))
    [ $tries -gt 300 ] && { echo "qemu-party: uuvsim party did not listen" >&2; exit 2; }
    sleep 0.1
done

args="arg=uuvsim,arg=scenario=$scenario"
[ -n "$duration" ] && args="$args,arg=duration=$duration"
timeout "$limit" qemu-system-arm -M "$machine" -display none -monitor none \
    -chardev "socket,id=link,path=$sock" -serial chardev:link \
    -semihosting-config "enable=on,target=native,$args" \
    -icount "shift=$shift_n,align=off,sleep=off" \
    -kernel "$elf" >"$out/console.txt" &
qemu_pid=$!

wait "$host_pid"; host_status=$?
if [ $host_status -ne 0 ]; then
    # The drive may still wait for a frame: give it a moment to finish, then stop it.
    tries=0
    while kill -0 "$qemu_pid" 2>/dev/null && [ $tries -lt 20 ]; do
        sleep 0.1; tries=$((tries + 1))
    done
    kill "$qemu_pid" 2>/dev/null
fi
wait "$qemu_pid"; qemu_status=$?
qemu_pid=""
cat "$out/console.txt" "$out/host.txt"
if [ $host_status -ne 0 ]; then
    exit $host_status
fi
if [ $qemu_status -eq 124 ]; then
    echo "qemu-party: QEMU did not finish within $limit s (raise QEMU_TIMEOUT)" >&2
    exit 124
fi
[ $qemu_status -eq 0 ] && echo "qemu-party: $machine, shift $shift_n: $out/telemetry.csv"
exit $qemu_status

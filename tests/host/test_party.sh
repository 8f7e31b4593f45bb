#!/bin/sh
# The multi-party run (docs/cosimulation.md), one machine and build:
#   test_party.sh MACHINE PARTY_ELF FIRMWARE_ELF UUVSIM DECODER OUTDIR [DURATION] [SHIFT]
# runs the default scenario (DURATION, default 0.5 s) with the drive under
# QEMU (PARTY_ELF) and the slow segment in `UUVSIM party`, and compares its
# telemetry CSV byte for byte with the desk's (UUVSIM --csv) and with the
# all-firmware run's (FIRMWARE_ELF through tools/qemu-run.sh); the same
# with drive faults; then a corrupted frame in each direction and a lost frame, each of which must
# stop the run with exit status 2, a message naming the frame, and no CSV.
# Prints "N passed, N failed" last.
set -u
if [ $# -lt 6 ]; then
    echo "usage: test_party.sh MACHINE PARTY_ELF FIRMWARE_ELF UUVSIM DECODER OUTDIR [DURATION] [SHIFT]" >&2
    exit 2
fi
machine=$1; party=$2; fw=$3; uuvsim=$4; decode=$5; out=$6
duration=${7:-0.5}; shift_n=${8:-2}
scenario=scenarios/default.scn
here=$(dirname "$0")
tools=$here/../../tools
. "${0%/*}/lib.sh"
mkdir -p "$out" || exit 2

# The desk, the multi-party run, the all-firmware run.
"$uuvsim" --scenario "$scenario" --duration "$duration" --csv "$out/desk.csv" --quiet ||
    ko "the desk run"
sh "$tools/qemu-party.sh" "$machine" "$party" "$uuvsim" "$scenario" "$duration" "$out/party" \
    "$shift_n" > "$out/party.log" 2>&1
status=$?
if [ $status -eq 0 ]; then
    ok "the multi-party run completed: $(grep 'slow frames exchanged' "$out/party.log")"
else
    ko "the multi-party run exited $status: $(tail -n 3 "$out/party.log")"
fi
rows=$(($(wc -l < "$out/desk.csv") - 1))
if cmp -s "$out/desk.csv" "$out/party/telemetry.csv"; then
    ok "its telemetry.csv is the desk's, byte for byte ($rows records, $(wc -c < "$out/desk.csv") bytes)"
else
    ko "its telemetry.csv differs from the desk's: $(cmp "$out/desk.csv" "$out/party/telemetry.csv" 2>&1)"
fi
sh "$tools/qemu-run.sh" "$machine" "$fw" "$scenario" "$duration" "$out/firmware" "$shift_n" \
    "$decode" > "$out/firmware.log" 2>&1
status=$?
if [ $status -eq 0 ] && cmp -s "$out/firmware/telemetry.csv" "$out/party/telemetry.csv"; then
    ok "and the all-firmware run's (tools/qemu-run.sh at shift $shift_n), byte for byte"
else
    ko "the all-firmware run (exit $status) and the multi-party run differ: $(cmp "$out/firmware/telemetry.csv" "$out/party/telemetry.csv" 2>&1)"
fi

# Faults cross the link too (LINK_DOWN's fault set, the protection's trip).
printf 'duration %s\nat 0 n_rpm=1000\nat 0.2 dc_cap=0.5 current_offset=5\nat 0.3 leg_short=b\n' \
    "$duration" > "$out/faults.scn"
"$uuvsim" --scenario "$out/faults.scn" --csv "$out/faults_desk.csv" --quiet ||
    ko "the desk run with faults"
# (At shift 0: a faulted drive leaves the real-time path, and its fast tick takes longer.)
sh "$tools/qemu-party.sh" "$machine" "$party" "$uuvsim" "$out/faults.scn" "" "$out/faults" \
    0 > "$out/faults.log" 2>&1
status=$?
trip=$(awk -F, 'NR > 1 { t = $NF } END { print t + 0 }' "$out/faults_desk.csv")
if [ $status -eq 0 ] && [ "$trip" -ne 0 ] && cmp -s "$out/faults_desk.csv" "$out/faults/telemetry.csv"; then
    ok "with faults at 0.2 and 0.3 s (the leg short trips: trip $trip): byte for byte the desk's"
else
    ko "with faults: exit $status, trip $trip, $(cmp "$out/faults_desk.csv" "$out/faults/telemetry.csv" 2>&1)"
fi

# failure NAME EXPECTED_TEXT HOST_OPTIONS...: the run must stop with exit status 2, the
# expected message, and no telemetry.csv.
failure() {
    name=$1; want=$2; shift 2
    dir="$out/$(echo "$name" | tr ' ' '_')"
    sh "$tools/qemu-party.sh" "$machine" "$party" "$uuvsim" "$scenario" "$duration" "$dir" \
        "$shift_n" "$@" > "$dir.log" 2>&1
    status=$?
    msg=$(grep -F "$want" "$dir.log" | head -n 1)
    if [ $status -eq 2 ] && [ -n "$msg" ] && [ ! -e "$dir/telemetry.csv" ]; then
        ok "$name ($*): exit 2, no CSV: $msg"
    else
        ko "$name ($*): exit $status, message '$want' $( [ -n "$msg" ] || echo 'missing'):" \
            "$(tail -n 3 "$dir.log" | tr '\n' ' ')"
    fi
}
failure "a corrupted frame to the drive" "frame 3 from the host (the answer to slow frame 4): CRC mismatch" \
    --corrupt-down 3
failure "a corrupted frame from the drive" "frame 2 from the drive (LINK_UP of slow frame 2): CRC mismatch" \
    --corrupt-up 2
failure "a lost frame to the drive" "frame 1 from the host (the answer to slow frame 2): out of sequence" \
    --drop-down 1
finish

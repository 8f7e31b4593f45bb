#!/bin/sh
# Fault injection (docs/reliability.md): each fault command in a 4 s run
# (1000 rpm from rest, rudder 10 deg at 1 s, the fault at 2 s, rudder -10
# deg at 2.5 s). Each run must complete, list the fault in the summary and
# the records, produce no NaN or Inf, report the saturation count, and show
# the fault's effect and the protection's reaction. Run once per build:
#   test_faults.sh UUVSIM
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0

# run FAULT [RPM]: writes $tmp/s.json and $tmp/r.csv
run() {
    printf 'duration 4\nat 0 n_rpm=%s\nat 1 rudder=10deg\nat 2 %s\nat 2.5 rudder=-10deg\n' \
        "${2:-1000}" "$1" >"$tmp/f.scn"
    "$uuvsim" --scenario "$tmp/f.scn" --json --csv "$tmp/r.csv" >"$tmp/s.json" 2>"$tmp/err"
}

# field NAME: the summary's value of a top-level or final key (numbers, booleans, strings)
field() {
    tr -d '\n' <"$tmp/s.json" | sed -n "s/.*\"$1\": *\"\{0,1\}\([^,\"}]*\).*/\1/p"
}

# last COLUMN: the column's value in the last record
last() {
    awk -F, -v c="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i; next }
                       { v = $k } END { print v }' "$tmp/r.csv"
}

# check NAME FAULT CONDITION [RPM]: runs the fault, then the common checks and CONDITION (awk
# on the variables n, trip, reason, vdc, ibatt, dr, te, irms, lim, sat)
check() {
    name=$1; fault=$2; cond=$3
    why=""
    run "$fault" "${4:-1000}" || why="exit status $?: $(cat "$tmp/err")"
    key=${fault%%=*}
    if [ -z "$why" ]; then
        grep -q "\"faults\": \[[^]]*\"$key\"" "$tmp/s.json" || why="fault not in the summary"
        grep -qiE 'nan|inf' "$tmp/r.csv" && why="NaN or Inf in the records"
        grep -q '"saturations": [0-9]' "$tmp/s.json" || why="no saturation count"
        [ "$(last faults)" != "0" ] || why="fault not in the records"
    fi
    if [ -z "$why" ]; then
        ok=$(awk -v n="$(field n_rpm)" -v trip="$(field tripped)" -v reason="$(field reason)" \
                 -v vdc="$(last v_dc_v)" -v ibatt="$(last i_batt_a)" \
                 -v dr="$(last delta_r_rad)" -v sat="$(field saturations)" \
                 -v te="$(last te_nm)" -v irms="$(last i_rms_a)" -v lim="$(field torque_limit_s)" \
                 "BEGIN { print (($cond) ? 1 : 0) }")
        [ "$ok" = 1 ] || why="reaction not as expected: n_rpm $(field n_rpm), tripped $(field tripped) ($(field reason)), v_dc $(last v_dc_v), i_batt $(last i_batt_a), delta_r $(last delta_r_rad), te $(last te_nm), torque limit $(field torque_limit_s) s"
    fi
    if [ -z "$why" ]; then
        pass=$((pass + 1)); echo "  ok    $name"
    else
        fail=$((fail + 1)); echo "  FAIL  $name: $why"
    fi
}

check "switch a+ stuck open: the drive runs on the diodes' states, speed within 5 %, no trip" \
    "switch_open=a+" 'n > 950 && n < 1050 && trip == "false"'
check "leg b shorted: the protection trips (leg short), gates blocked, the shaft coasts down" \
    "leg_short=b" 'trip == "true" && reason == "leg short" && n < 500'
check "DC-link capacitance at 10 %: runs on, speed within 1 %, no trip" \
    "dc_cap=0.1" 'n > 990 && n < 1010 && trip == "false"'
check "battery at cut-off: contactor open, no battery current, under-voltage trip" \
    "battery_cutoff=on" 'trip == "true" && reason == "under-voltage" && ibatt == 0'
check "rudder jammed at 10 deg: the -10 deg command is ignored" \
    "fin_jam=rudder" 'dr > 0.17 && dr < 0.18 && trip == "false"'
check "phase-a current sensor offset 10 A: runs on, speed within 1 %, no trip" \
    "current_offset=10" 'n > 990 && n < 1010 && trip == "false"'
check "motor phase b open: the phase-loss protection trips, gates blocked, the shaft coasts down" \
    "phase_open=b" 'trip == "true" && reason == "phase loss" && n < 500'
check "propeller fouled (load x3) at 1000 rpm: three times the torque, speed within 2 %, no trip" \
    "prop_fouling=3" 'n > 980 && n < 1020 && te > 70 && te < 85 && trip == "false"'
check "propeller fouled (load x3) at 1400 rpm: the torque limit holds 95 N m, the speed falls to 1105" \
    "prop_fouling=3" 'n > 1080 && n < 1130 && te > 90 && te < 100 && lim > 1.5 && trip == "false"' 1400
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]

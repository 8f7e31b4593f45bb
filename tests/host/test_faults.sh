#!/bin/sh
# Fault injection (docs/reliability.md): each fault command in a 4 s run
# (1000 rpm from rest, rudder 10 deg at 1 s, the fault at 2 s, rudder -10
# deg at 2.5 s). Each run must complete, list the fault in the summary and
# the records, produce no NaN or Inf, report the saturation count, and show
# the fault's effect and the protection's reaction. Then the fault matrix:
# the 8 faults alone and in pairs (36 runs) on the switching and on the
# event inverter, which must show the same protection response (see
# matrix() below). Run once per build:
#   test_faults.sh UUVSIM
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"

# run FAULTS [RPM [INVERTER]]: writes $tmp/s.json and $tmp/r.csv (FAULTS: one or more
# fault commands, all at 2 s)
run() {
    printf 'duration 4\nat 0 n_rpm=%s\nat 1 rudder=10deg\nat 2 %s\nat 2.5 rudder=-10deg\n' \
        "${2:-1000}" "$1" >"$tmp/f.scn"
    "$uuvsim" --scenario "$tmp/f.scn" --inverter "${3:-switching}" --json --csv "$tmp/r.csv" \
        >"$tmp/s.json" 2>"$tmp/err"
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

# The fault matrix. For each fault set, one run per layer; each run's figures
# as "reason at_s n_rpm i_rms te delta_r" (the trip's time "-" when none; the
# last four from the last record).
figures() {
    run "$1" 1000 "$2" || { echo "exit status $?: $(cat "$tmp/err")"; return; }
    if grep -qiE 'nan|inf' "$tmp/r.csv"; then echo "NaN or Inf in the records"; return; fi
    at=$(field at_s)
    echo "$(field reason | tr ' ' _) ${at:--} $(field n_rpm) $(last i_rms_a) $(last te_nm)" \
         "$(last delta_r_rad)"
}

# Both layers must give: the same trip (kind, and time within one slow frame,
# 0.1 s), the same final shaft speed within 0.5 % + 1 rpm, and the same
# behaviour after a trip (gates blocked: under 1 A rms and 0.01 N m on both)
# or without one (torque within 2 % + 0.5 N m); the rudder the same within
# 1e-3 rad.
matrix() {
    sw=$(figures "$1" switching)
    ev=$(figures "$1" event)
    why=$(echo "$sw $ev" | awk 'NF != 12 { print "no figures: " $0; exit }
        { if ($1 != $7) { print "trip " $1 " against " $7; exit }
          if ($2 != "-" || $8 != "-") {
              if ($2 == "-" || $8 == "-" || $2 - $8 > 0.1 + 1e-9 || $8 - $2 > 0.1 + 1e-9) {
                  print "trip at " $2 " s against " $8 " s"; exit } }
          dn = $3 - $9; if (dn < 0) dn = -dn
          if (dn > 0.005 * $3 + 1) { print "shaft " $3 " against " $9 " rpm"; exit }
          if ($1 != "none") {
              if ($4 > 1 || $10 > 1 || $5 > 0.01 || $5 < -0.01 || $11 > 0.01 || $11 < -0.01) {
                  print "after the trip " $4 "/" $10 " A rms, " $5 "/" $11 " N m"; exit } }
          else { dt = $5 - $11; if (dt < 0) dt = -dt; m = ($5 < 0) ? -$5 : $5
              if (dt > 0.02 * m + 0.5) { print "torque " $5 " against " $11 " N m"; exit } }
          dr = $6 - $12; if (dr < 0) dr = -dr
          if (dr > 1e-3) { print "rudder " $6 " against " $12 " rad"; exit } }')
    if [ -z "$why" ]; then
        pass=$((pass + 1))
        echo "$sw $ev" | awk -v c="$1" '{ gsub("_", " ", $1); printf "  ok    matrix %s: %s%s, shaft %.1f / %.1f rpm, %.2f / %.2f A rms (switching / event)\n", c, $1, ($2 == "-") ? "" : " at " $2 " s", $3, $9, $4, $10 }'
    else
        fail=$((fail + 1)); echo "  FAIL  matrix $1: $why"
    fi
}

faults="switch_open=a+ leg_short=b dc_cap=0.1 battery_cutoff=on fin_jam=rudder current_offset=10
phase_open=b prop_fouling=3"
for a in $faults; do
    matrix "$a"
done
set -- $faults
while [ $# -gt 1 ]; do
    a=$1; shift
    for b in "$@"; do
        matrix "$a $b"
    done
done
finish

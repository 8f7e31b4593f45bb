#!/bin/sh
# Parameter sets (ports/linux/paramset.c): the printed default set reads back
# to the same run, the shipped sets run, an override of one key per
# subsystem changes the result the way its physics says, and every bad
# input is refused with its file, line and key and exit status 2.
# Usage: test_params.sh UUVSIM. Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
check() { # name, then a command that must succeed
    name=$1; shift
    if "$@" >"$tmp/out" 2>"$tmp/err"; then ok "$name"; else ko "$name"; fi
}
# expect_error NAME PATTERN ARGS...: exit 2, PATTERN on stderr, nothing on stdout, no
# $tmp/bad.csv (the runs that name it as their --csv must not leave it).
expect_error() {
    name=$1; pattern=$2; shift 2
    "$@" >"$tmp/stdout" 2>"$tmp/err"
    status=$?
    if [ $status -eq 2 ] && grep -qE -- "$pattern" "$tmp/err" && [ ! -s "$tmp/stdout" ] &&
       [ ! -e "$tmp/bad.csv" ]; then
        ok "$name"
    else
        ko "$name (exit $status)"
    fi
}
# jget KEY FILE: the first number after "KEY": in a JSON summary.
jget() { grep -o "\"$1\": [-0-9.e+]*" "$2" | head -n 1 | sed 's/.*: //'; }
# ratio_in A B LO HI: LO <= A / B <= HI.
ratio_in() { awk -v a="$1" -v b="$2" -v lo="$3" -v hi="$4" 'BEGIN { r = a / b; exit !(r >= lo && r <= hi) }'; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

build=$("$uuvsim" --version | sed 's/.*(\(.*\) build).*/\1/')
scn=scenarios/default.scn

# ---- The default set round trip ------------------------------------------
"$uuvsim" params >"$tmp/p.txt"
"$uuvsim" --scenario $scn --duration 2 --csv "$tmp/a.csv" --quiet
"$uuvsim" --params "$tmp/p.txt" --scenario $scn --duration 2 --csv "$tmp/b.csv" --quiet
check "params > p.txt; --params p.txt: the same CSV, byte for byte (full plant, 2 s)" \
    cmp "$tmp/a.csv" "$tmp/b.csv"
"$uuvsim" --plant vessel --scenario scenarios/zigzag_20_20.scn --duration 60 --csv "$tmp/a.csv" --quiet
"$uuvsim" --plant vessel --params "$tmp/p.txt" --scenario scenarios/zigzag_20_20.scn --duration 60 \
    --csv "$tmp/b.csv" --quiet
check "the same with the vessel plant (zig-zag, 60 s)" cmp "$tmp/a.csv" "$tmp/b.csv"
"$uuvsim" params --params "$tmp/p.txt" >"$tmp/p2.txt"
check "printing a loaded set gives the same file" cmp "$tmp/p.txt" "$tmp/p2.txt"
sed 1d params/default.params >"$tmp/shipped.txt"
sed 1,2d "$tmp/p.txt" >"$tmp/printed.txt"
check "params/default.params is the printed default set" cmp "$tmp/shipped.txt" "$tmp/printed.txt"
check "the summary names the set and the overrides" sh -c \
    "'$uuvsim' --params params/endurance.params --set 'stage.l=2e-3 H' --scenario $scn --duration 0.2 |
     grep -q 'parameters: params/endurance.params (endurance), overrides stage.l=2e-3 H'"

# ---- The shipped sets -----------------------------------------------------
awk '/^[a-z]/ { print $1 }' "$tmp/p.txt" >"$tmp/keys.txt"
for set in params/*.params; do
    awk '/^[a-z]/ { print $1 }' "$set" >"$tmp/set-keys.txt"
    check "$set: complete (every key of uuvsim params, in its order)" cmp "$tmp/keys.txt" "$tmp/set-keys.txt"
    check "$set: runs 1 s of the full plant" "$uuvsim" --params "$set" --scenario $scn \
        --duration 1 --quiet
done
"$uuvsim" --params params/motor4kw.params --scenario scenarios/from_rest_1000rpm.scn --duration 5 \
    --json >"$tmp/m4.json"
check "motor4kw: the 4 kW drive holds 1000 rpm (within 1 %) after 5 s" \
    ratio_in "$(jget n_rpm "$tmp/m4.json")" 1000 0.99 1.01

# ---- One override per subsystem -------------------------------------------
run_json() { # OUT ARGS...
    out=$1; shift
    "$uuvsim" --json "$@" >"$out" 2>"$tmp/err"
}
# Vessel: twice the surge drag coefficient, a lower speed at the same shaft speed.
run_json "$tmp/v0.json" --plant vessel --scenario scenarios/straight_1300rpm.scn --duration 60
run_json "$tmp/v1.json" --plant vessel --scenario scenarios/straight_1300rpm.scn --duration 60 \
    --set vessel.cd0=0.0077
check "vessel.cd0 doubled: the speed after 60 s is lower" \
    less "$(jget u_mps "$tmp/v1.json")" "$(jget u_mps "$tmp/v0.json")"
# Propeller: a larger diameter, more thrust, a higher speed.
run_json "$tmp/v2.json" --plant vessel --scenario scenarios/straight_1300rpm.scn --duration 60 \
    --set propeller.diameter=0.33
check "propeller.diameter +10 %: the speed after 60 s is higher" \
    less "$(jget u_mps "$tmp/v0.json")" "$(jget u_mps "$tmp/v2.json")"
# Battery: twice the strings, half the charge drawn.
run_json "$tmp/b0.json" --scenario $scn --duration 2
run_json "$tmp/b1.json" --scenario $scn --duration 2 --set battery.n_parallel=4
d0=$(awk -v s="$(jget soc "$tmp/b0.json")" 'BEGIN { print 1 - s }')
d1=$(awk -v s="$(jget soc "$tmp/b1.json")" 'BEGIN { print 1 - s }')
check "battery.n_parallel 2 -> 4: half the state of charge drawn (0.45..0.55)" \
    ratio_in "$d1" "$d0" 0.45 0.55
run_json "$tmp/b2.json" --scenario $scn --duration 2 --params params/endurance.params
d2=$(awk -v s="$(jget soc "$tmp/b2.json")" 'BEGIN { print 1 - s }')
check "params/endurance.params (144s4p): half the state of charge drawn of the default (0.45..0.55)" \
    ratio_in "$d2" "$d0" 0.45 0.55
# Filter: twice the inductor resistance, about twice its copper losses.
run_json "$tmp/f0.json" --scenario $scn --duration 1 --energy-audit
run_json "$tmp/f1.json" --scenario $scn --duration 1 --energy-audit --set stage.r_l=0.05
check "stage.r_l doubled: the filter losses about double (1.8..2.2)" \
    ratio_in "$(jget filter_loss_wh "$tmp/f1.json")" "$(jget filter_loss_wh "$tmp/f0.json")" 1.8 2.2
# PWM: half the carrier, twice the ripple current, higher filter losses.
run_json "$tmp/f2.json" --scenario $scn --duration 1 --energy-audit --set pwm.carrier=2500
check "pwm.carrier 5 -> 2.5 kHz: higher filter losses (more ripple)" \
    less "$(jget filter_loss_wh "$tmp/f0.json")" "$(jget filter_loss_wh "$tmp/f2.json")"
# Motor: twice the rotor inertia, a slower start at the torque limit.
run_json "$tmp/m0.json" --scenario $scn --duration 0.5
run_json "$tmp/m1.json" --scenario $scn --duration 0.5 --set motor.j_rotor=0.204 \
    --set control.kp_speed=0.04 --set control.ki_speed=0.1424 --set control.kp_current=0.3 \
    --set control.ki_current=30
check "motor.j_rotor doubled (same gains): the shaft is slower after 0.5 s" \
    less "$(jget n_rpm "$tmp/m1.json")" "$(jget n_rpm "$tmp/m0.json")"
# Controller: half the acceleration ramp, a slower start.
run_json "$tmp/c1.json" --scenario $scn --duration 0.5 --set control.accel_max=100
check "control.accel_max halved: the shaft is slower after 0.5 s (0.45..0.65 of the speed)" \
    ratio_in "$(jget n_rpm "$tmp/c1.json")" "$(jget n_rpm "$tmp/m0.json")" 0.45 0.65
# Autopilot: half the fin limit; the rudder stops at 10 deg and the turn to 90 deg is slower.
"$uuvsim" --plant vessel --scenario scenarios/autopilot_step.scn --duration 45 \
    --csv "$tmp/a0.csv" --quiet
"$uuvsim" --plant vessel --scenario scenarios/autopilot_step.scn --duration 45 \
    --set autopilot.fin_limit=10 --csv "$tmp/a1.csv" --quiet
# max_rudder CSV: the largest |delta_r| [deg]; psi_at CSV T: the heading [deg] at T s.
max_rudder() { awk -F, 'NR > 1 { d = ($14 < 0) ? -$14 : $14; if (d > m) m = d } END { print m * 57.29577951 }' "$1"; }
psi_at() { awk -F, -v t="$2" 'NR > 1 && $1 == t { print $13 * 57.29577951 }' "$1"; }
check "autopilot.fin_limit 20 -> 10 deg: the rudder reaches the limit and no more (9.99..10.001 deg)" \
    ratio_in "$(max_rudder "$tmp/a1.csv")" 10 0.999 1.0001
check "autopilot.fin_limit 20 -> 10 deg: the heading 10 s after the 90 deg step is lower" \
    less "$(psi_at "$tmp/a1.csv" 40)" "$(psi_at "$tmp/a0.csv" 40)"
# PWM dead time: each leg loses V_dc t_d f_c sign(i) of pole voltage, whose fundamental is
# (4/pi) V_dc t_d f_c, i.e. (8/pi) t_d f_c of the modulation index m (0.0127 at 1 us and
# 5 kHz) when the current is in phase with the voltage, less by the power factor otherwise.
# The current loop makes it up: at a steady 1000 rpm m rises by a part of that, in
# proportion to t_d, and the shaft keeps its speed.
for dt in 0 1000 2000; do
    "$uuvsim" --scenario scenarios/from_rest_1000rpm.scn --duration 3 --set pwm.dead_time=$dt \
        --csv "$tmp/dt$dt.csv" --quiet
done
# m_late CSV: the mean m_index over the last 0.5 s; rpm_late: the mean shaft speed there.
m_late() { awk -F, 'NR > 1 && $1 >= 2.5 { s += $29; n++ } END { print s / n }' "$1"; }
rpm_late() { awk -F, 'NR > 1 && $1 >= 2.5 { s += $18; n++ } END { print s / n }' "$1"; }
dm1=$(awk -v a="$(m_late "$tmp/dt1000.csv")" -v b="$(m_late "$tmp/dt0.csv")" 'BEGIN { print a - b }')
dm2=$(awk -v a="$(m_late "$tmp/dt2000.csv")" -v b="$(m_late "$tmp/dt0.csv")" 'BEGIN { print a - b }')
check "pwm.dead_time 1 us: m rises by 0.3..1 of (8/pi) t_d f_c = 0.01273 (measured $dm1)" \
    ratio_in "$dm1" 0.012732 0.3 1.0
check "pwm.dead_time 2 us: twice the rise of 1 us (1.8..2.2; measured $dm2)" \
    ratio_in "$dm2" "$dm1" 1.8 2.2
check "pwm.dead_time 2 us: the shaft still holds 1000 rpm (within 0.1 %)" \
    ratio_in "$(rpm_late "$tmp/dt2000.csv")" 1000 0.999 1.001
"$uuvsim" --scenario scenarios/from_rest_1000rpm.scn --duration 3 --dead-time 1us \
    --csv "$tmp/dtopt.csv" --quiet
check "--dead-time 1us is --set pwm.dead_time=1000: the same CSV, byte for byte" \
    cmp "$tmp/dt1000.csv" "$tmp/dtopt.csv"
printf 'name dt\npwm.dead_time 2000 ns\n' >"$tmp/dt.params"
check "--dead-time overrides the set's and an earlier --set (summary: 1 us, both overrides)" sh -c \
    "'$uuvsim' --params '$tmp/dt.params' --set pwm.dead_time=500 --dead-time 1us --scenario $scn \
        --duration 0.1 >'$tmp/dt.txt' && grep -q 'dead time 1 us)' '$tmp/dt.txt' &&
     grep -q 'parameters: $tmp/dt.params (dt), overrides pwm.dead_time=500 pwm.dead_time=1000 ns' '$tmp/dt.txt'"
check "a set's dead time is in the JSON summary (dead_time_s 2e-06)" sh -c \
    "'$uuvsim' --params '$tmp/dt.params' --scenario $scn --duration 0.1 --json | grep -q '\"dead_time_s\": 2e-06,'"
"$uuvsim" params --params "$tmp/dt.params" --emit-c "$tmp/dt.c"
"$uuvsim" params --emit-c "$tmp/default.c"
check "the firmware's generated set carries the dead time (.dead_time_ns = 2000u; default 0u)" sh -c \
    "grep -q '^    .dead_time_ns = 2000u,\$' '$tmp/dt.c' && grep -q '^    .dead_time_ns = 0u,\$' '$tmp/default.c'"

# Derived gains: a set that changes the motor without gains gets the motor's.
"$uuvsim" params --set motor.j_rotor=0.204 >"$tmp/pj.txt"
kp0=$(awk '$1 == "control.kp_speed" { print $2 }' "$tmp/p.txt")
kp1=$(awk '$1 == "control.kp_speed" { print $2 }' "$tmp/pj.txt")
# Kp = w_c J / K_T: J from 0.113 to 0.215 kg m^2 at w_c = 28 rad/s.
check "the speed gain follows the inertia (Kp = w_c J / K_T: 0.0758 Hz/(rad/s))" \
    ratio_in "$kp1" 0.0758 0.995 1.005
check "--set control.kp_speed=auto derives it for the default motor (0.0398)" sh -c \
    "'$uuvsim' params --set control.kp_speed=auto | awk '\$1 == \"control.kp_speed\" { exit !(\$2 > 0.0397 && \$2 < 0.0399) }'"
[ "$kp0" = 0.04 ] && ok "the default set keeps its tuned gain 0.04" || ko "default kp_speed $kp0"

# ---- Bad input ------------------------------------------------------------
bad() { printf "$1" >"$tmp/bad.params"; }
bad 'name x\nmotor.rs 0.1 ohm\nmotor.rx 1 ohm\n'
expect_error "unknown key: file:line: key" "bad.params:3: motor.rx: unknown key" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad '# c\nmotor.rs 0.1 H\n'
expect_error "wrong unit: the expected unit" "bad.params:2: motor.rs: expected the unit ohm, got 'H'" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'motor.rs 0.1\n'
expect_error "a missing unit" "bad.params:1: motor.rs: expected the value followed by its unit ohm" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'motor.rs 1000 ohm\n'
expect_error "out of range: the range and unit" \
    "bad.params:1: motor.rs: expected a value in \[0.0001, 100\] ohm, got 1000 \(out of range\)" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'battery.n_series 14.5 -\n'
expect_error "a fraction for a count" "bad.params:1: battery.n_series: .*not whole" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'motor.rs 0.1 ohm\n\nmotor.rs 0.2 ohm\n'
expect_error "duplicate key: both lines" "bad.params:3: motor.rs: duplicate key \(first given on line 1\)" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'battery.ocv 3.5 3.6 V\n'
expect_error "a table of the wrong length" "bad.params:1: battery.ocv: expected 7 values" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'battery.ocv 3.5 3.6 3.7 3.6 3.8 3.9 4.0 V\n'
expect_error "a falling OCV: the battery model refuses it" "battery: the battery model refuses" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'name a"b\n'
expect_error "a name with a quote" "bad.params:1: name: expected one word" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
expect_error "--set without '='" "--set: expected KEY=VALUE" \
    "$uuvsim" --set motor.rs --scenario $scn
expect_error "--set of an unknown key" "--set: motor.zz: unknown key" \
    "$uuvsim" --set motor.zz=1 --scenario $scn
expect_error "--set of a value that is no number" "--set: motor.rs: expected a value in" \
    "$uuvsim" --set motor.rs=abc --scenario $scn
expect_error "a missing set file" "nope.params: cannot open" \
    "$uuvsim" --params "$tmp/nope.params" --scenario $scn
bad 'name x\npwm.dead_time 1000 ns\n'
expect_error "a dead time with the averaged inverter: file:line: key, what it needs" \
    "bad.params:2: pwm.dead_time: a dead time of 1000 ns needs the switching inverter with sub-step edges" \
    "$uuvsim" --params "$tmp/bad.params" --inverter averaged --scenario $scn --csv "$tmp/bad.csv"
bad 'pwm.dead_time 1 us\n'
expect_error "a dead time in another unit" "bad.params:1: pwm.dead_time: expected the unit ns, got 'us'" \
    "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
bad 'battery.n_series 250 -\n'
if [ "$build" = fixed ]; then
    expect_error "fixed: a bus above the 1024 V base, by how much" \
        "bad.params:1: battery.n_series: the fixed build cannot hold this set: the DC link reaches 1050 V .*2.5 % above its per-unit base 1024 V" \
        "$uuvsim" --params "$tmp/bad.params" --scenario $scn --csv "$tmp/bad.csv"
    expect_error "fixed: a current limit above the 256 A base" \
        "--set: control.i_max: the fixed build cannot hold this set: the phase current reaches 257.6 A" \
        "$uuvsim" --set control.i_max=250 --scenario $scn
    expect_error "fixed: a frequency limit above the speed base" \
        "--set: control.freq_max: .*the electrical speed reaches" \
        "$uuvsim" --set control.freq_max=81 --scenario $scn
else
    check "float: a 250 A current limit is accepted (no per-unit bases)" \
        "$uuvsim" --set control.i_max=250 --scenario $scn --duration 0.2 --quiet
fi

finish

#!/bin/sh
# End-to-end checks of the uuvsim program against the reference vectors and
# its error handling. Usage: test_uuvsim_cli.sh UUVSIM CSVDIFF
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
csvdiff=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
check() { # name, then a command that must succeed
    name=$1; shift
    if "$@" >"$tmp/out" 2>&1; then
        pass=$((pass + 1)); echo "  ok    $name"
    else
        fail=$((fail + 1)); echo "  FAIL  $name"; sed 's/^/        /' "$tmp/out" | tail -n 15
    fi
}
# expect_error NAME PATTERN ARGS...: exit status 2, message matching PATTERN on stderr,
# nothing on stdout, and no output file left behind.
expect_error() {
    name=$1; pattern=$2; shift 2
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    status=$?
    if [ $status -eq 2 ] && grep -qE "$pattern" "$tmp/stderr" && [ ! -s "$tmp/stdout" ] &&
       [ -z "$(ls "$tmp" | grep -E 'bad\.csv')" ]; then
        pass=$((pass + 1)); echo "  ok    $name"
    else
        fail=$((fail + 1)); echo "  FAIL  $name (exit $status)"; sed 's/^/        /' "$tmp/stderr"
    fi
}

V=tests/vectors
derivs_match() {
    "$uuvsim" derivs "$1" >"$tmp/d.csv" && "$csvdiff" --rel 1e-9 --abs 1e-12 "$1" "$tmp/d.csv"
}
check "derivs: 10 random rows within 1e-9 relative (floor 1e-12)" derivs_match $V/npsauv_derivatives.csv
check "derivs: 8 edge rows within 1e-9 relative (floor 1e-12)" derivs_match $V/npsauv_derivatives_edge.csv

straight() {
    "$uuvsim" --quiet --plant vessel --propulsion mss --deep-water \
        --scenario scenarios/straight_1300rpm.scn \
        --csv "$tmp/s.csv" &&
        "$csvdiff" --rel 1e-6 --abs 1e-12 $V/npsauv_straight_1300rpm.csv "$tmp/s.csv"
}
check "vessel run: straight 1300 rpm, every state at every row within 1e-6" straight

twice() {
    "$uuvsim" --quiet "$@" --csv "$tmp/a.csv" && "$uuvsim" --quiet "$@" --csv "$tmp/b.csv" &&
        cmp "$tmp/a.csv" "$tmp/b.csv"
}
check "vessel run: the same scenario twice gives byte-identical CSV" \
    twice --plant vessel --scenario scenarios/zigzag_20_20.scn
check "full plant: the same scenario twice gives byte-identical CSV" \
    twice --scenario scenarios/default.scn --duration 2

summary_json() {
    "$uuvsim" --json --plant vessel --scenario scenarios/turning_circle.scn >"$tmp/t.json" &&
        grep -q '"tactical_diameter_m"' "$tmp/t.json" && grep -q '"build"' "$tmp/t.json"
}
check "summary: --json carries the build and the turning-circle metrics" summary_json

trace_window() {
    "$uuvsim" --quiet --scenario scenarios/bench_2s.scn --duration 0.2 --trace "$tmp/t.csv" \
        --trace-from 0.1 --trace-to 0.11 &&
        head -n 1 "$tmp/t.csv" | grep -q '^t_s,sa,sb,sc,m_index,f_hz,v_dc_v,v_an_v,v_bn_v,v_cn_v,vc_a_v' &&
        [ "$(wc -l <"$tmp/t.csv")" -eq 5002 ]
}
check "trace: one row per 2 us step in the window, with the documented columns" trace_window

realtime() {
    "$uuvsim" --json --realtime --scenario scenarios/bench_2s.scn --duration 0.3 >"$tmp/r.json" &&
        grep -q '"realtime_lag_max_s"' "$tmp/r.json" &&
        awk -F'[:,]' '/"wall_time_s"/ { exit !($2 >= 0.29) }' "$tmp/r.json"
}
check "realtime: the run is paced to the wall clock and reports its lag" realtime

# frames: a 200 us motor frame and a 40 ms slow frame give 10000 motor steps, 2500
# controller steps (800 us) and 50 slow steps in 2 s, one CSV row per 40 ms, and the
# shaft still at its command.
frames() {
    "$uuvsim" --json --scenario scenarios/bench_2s.scn --motor-frame 200us --slow-frame 0.04s \
        --csv "$tmp/f.csv" >"$tmp/f.json" &&
        grep -q '"frames_s": {"fast": 2e-06, "motor": 0.0002, "control": 0.0008, "slow": 0.04}' \
            "$tmp/f.json" &&
        grep -q '"steps": {"fast": 1000000, "motor": 10000, "control": 2500, "slow": 50}' \
            "$tmp/f.json" &&
        [ "$(wc -l <"$tmp/f.csv")" -eq 52 ] &&
        awk -F'[:,]' '/"n_rpm"/ { for (i = 1; i < NF; i++) if ($i ~ /"n_rpm"/) v = $(i + 1) }
                      END { exit !(v > 995 && v < 1005) }' "$tmp/f.json"
}
check "frames: --motor-frame and --slow-frame set the steps and the records" frames

# modulator: the summary names the switching inverter's modulator and dead time; the
# sampled modulator and a 1 us dead time each change the run (the CSV differs).
modulator() {
    "$uuvsim" --json --duration 0.3 --scenario scenarios/bench_2s.scn --csv "$tmp/m0.csv" \
        >"$tmp/m0.json" &&
        grep -q '"modulator": "substep",' "$tmp/m0.json" &&
        grep -q '"dead_time_s": 0,' "$tmp/m0.json" &&
        "$uuvsim" --json --duration 0.3 --modulator sampled --scenario scenarios/bench_2s.scn \
            --csv "$tmp/m1.csv" >"$tmp/m1.json" &&
        grep -q '"modulator": "sampled",' "$tmp/m1.json" &&
        "$uuvsim" --duration 0.3 --dead-time 1us --scenario scenarios/bench_2s.scn \
            --csv "$tmp/m2.csv" >"$tmp/m2.txt" &&
        grep -q 'inverter switching (modulator substep, dead time 1 us)' "$tmp/m2.txt" &&
        ! cmp -s "$tmp/m0.csv" "$tmp/m1.csv" && ! cmp -s "$tmp/m0.csv" "$tmp/m2.csv"
}
check "modulator: --modulator and --dead-time are named in the summaries and change the run" \
    modulator

# heading: the summary's compass heading is psi wrapped into [0, 360), with psi beside it.
heading() {
    printf 'duration 0.1\ninit psi_rad=-3.4\n' >"$tmp/h.scn" &&
        "$uuvsim" --plant vessel --scenario "$tmp/h.scn" >"$tmp/h.txt" &&
        grep -q 'heading 165.2 deg (psi -194.8 deg unwrapped)' "$tmp/h.txt" &&
        printf 'duration 0.1\ninit psi_rad=6.2830\n' >"$tmp/h.scn" &&
        "$uuvsim" --plant vessel --scenario "$tmp/h.scn" >"$tmp/h.txt" &&
        grep -q 'heading 0.0 deg (psi 360.0 deg unwrapped)' "$tmp/h.txt"
}
check "summary: the heading is wrapped to [0, 360) beside the unwrapped psi" heading

# The free surface: no run of the shipped scenarios (vessel plant, the soak's first 600 s),
# of a surfaced start, of the README's example scenario or the default mission (full plant) has the vehicle's centre more than
# its hull radius (0.265 m) above the surface.
# csv_top FILE: the smallest z_m.
csv_top() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "z_m") c = i; next }
             NR == 2 || $c < m { m = $c } END { print m }' "$1"
}
surface() {
    awk '/^Scenario files/ { on = 1; next } on && /^```$/ { if (in_) exit; in_ = 1; next }
         in_ { print }' README.md >"$tmp/readme.scn" &&
        [ -s "$tmp/readme.scn" ] &&
        printf 'duration 120\ninit z_m=0\nat 0 buoyancy=2000\nat 10 n_rpm=1200 heading=45deg\n' \
            >"$tmp/surfaced.scn" || return 1
    for s in scenarios/*.scn "$tmp/surfaced.scn" full:"$tmp/readme.scn" \
        full:scenarios/default.scn; do
        plant=vessel; cap="--duration 600"
        case $s in full:*) plant=full; cap=; s=${s#full:} ;; esac
        "$uuvsim" --quiet --plant $plant --scenario "$s" $cap --csv "$tmp/sf.csv" ||
            { echo "$s: run failed"; return 1; }
        top=$(csv_top "$tmp/sf.csv")
        echo "$s ($plant plant): highest centre z = $top m"
        awk -v t="$top" 'BEGIN { exit !(t > -0.265) }' || return 1
    done
}
check "free surface: no scenario, README example or surfaced start lifts the centre above -0.265 m" \
    surface

# The autopilots with the full plant, in this build: heading 0 -> 90 deg and depth 15 m at
# 30 s (1200 rpm, from the surface) settle within 60 s (1 deg, 0.1 m) and stay to 150 s.
autopilot() {
    "$uuvsim" --quiet --scenario scenarios/autopilot_step.scn --csv "$tmp/ap.csv" &&
        awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
                 $c["t_s"] >= 30 { p = $c["psi_rad"] * 57.29577951308232; z = $c["z_m"]
                     if (p < 89 || p > 91) ph = $c["t_s"] - 30
                     if (z < 14.9 || z > 15.1) dz = $c["t_s"] - 30
                     if (z > zm) zm = z; if (p > pm) pm = p }
                 END { printf "heading settled %.1f s, max %.2f deg; depth settled %.1f s, max %.3f m\n",
                       ph, pm, dz, zm; exit !(ph < 60 && dz < 60) }' "$tmp/ap.csv"
}
check "autopilots (full plant): heading 90 deg and depth 15 m settle within 60 s and stay" autopilot

# The turn of the issue's example ends (rudder 0) before a full circle: no steady diameter.
turn_ends() {
    printf 'duration 120\ninit z_m=20 u_mps=1.5\nat 0 n_rpm=1200\nat 20 rudder=-20deg\nat 60 rudder=0\n' \
        >"$tmp/tc.scn" &&
        "$uuvsim" --scenario "$tmp/tc.scn" >"$tmp/tc.txt" && cat "$tmp/tc.txt" &&
        grep -q 'rudder left its angle at 60.0 s' "$tmp/tc.txt" &&
        ! grep -q 'steady diameter [0-9]' "$tmp/tc.txt" &&
        "$uuvsim" --json --scenario "$tmp/tc.scn" | grep -q '"rudder_left_s": 60' &&
        ! "$uuvsim" --json --scenario "$tmp/tc.scn" | grep -q steady_diameter
}
check "turning circle: a turn that ends before the run reports no steady diameter" turn_ends

# Finite results (docs/vessel.md, four quadrants): astern with the paper law and the
# initial states that once diverged end finite, with exit 0 and no nan or inf in any
# output; the summary is valid JSON.
no_nonfinite() { ! grep -Eiq '(^|[^a-z_])-?(nan|inf)' "$@"; }
finite_run() { # scenario text, then options
    printf "$1" >"$tmp/fin.scn" && shift &&
        "$uuvsim" --scenario "$tmp/fin.scn" --csv "$tmp/fin.csv" --summary "$tmp/fin.json" \
            "$@" >"$tmp/fin.txt" &&
        no_nonfinite "$tmp/fin.csv" "$tmp/fin.json" "$tmp/fin.txt" &&
        python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$tmp/fin.json"
}
check "astern: the issue's 60 s at -500 rpm from the surface (paper, full plant) stays finite" \
    finite_run 'duration 60\nat 0 n_rpm=-500\n'
astern() {
    finite_run 'duration 60\ninit z_m=20\nat 0 n_rpm=-500\n' &&
        grep -Eq 'final: u -1\.2[0-9]* m/s' "$tmp/fin.txt"
}
check "astern: 60 s at -500 rpm at 20 m (paper, full plant) stays finite, u -> -1.21 m/s" astern
check "astern: 30 s at -1500 rpm (paper, vessel) stays finite" \
    finite_run 'duration 30\nat 0 n_rpm=-1500\n' --plant vessel
check "init q_radps=1 (full plant, 10 s) stays finite" finite_run 'duration 10\ninit q_radps=1\n'
check "init q_radps=0.5 (full plant, 10 s) stays finite" finite_run 'duration 10\ninit q_radps=0.5\n'
coasting_astern() {
    finite_run 'duration 10\ninit u_mps=-3 z_m=20\n' &&
        grep -Eq 'final: u -2\.[0-9]+ m/s, .*heading 0\.0 deg' "$tmp/fin.txt"
}
check "init u_mps=-3 at 20 m (full plant, 10 s): coasts astern (u -2.35 m/s), heading kept" \
    coasting_astern
check "init u_mps=-3 with a 0.5 s slow frame (vessel) stays finite" \
    finite_run 'duration 30\ninit u_mps=-3 q_radps=2\n' --plant vessel --slow-frame 500ms
printf 'duration 10\ninit w_mps=20\n' >"$tmp/w20.scn"
expect_error "error: an initial heave speed beyond the model's range" \
    "w20.scn:2: field 'w_mps': value 20 m/s out of range \\[-3, 3\\]" \
    "$uuvsim" --scenario "$tmp/w20.scn" --csv "$tmp/bad.csv"

# The guard: under mss a vehicle moving astern accelerates without bound; the run
# stops with exit 3, the time, what diverged and the last state, and no output holds
# a nan or an inf.
guard() {
    printf 'duration 60\ninit u_mps=-5 z_m=50\n' >"$tmp/g.scn"
    "$uuvsim" --plant vessel --propulsion mss --scenario "$tmp/g.scn" --csv "$tmp/g.csv" \
        --summary "$tmp/g.json" >"$tmp/g.txt" 2>"$tmp/g.err"
    [ $? -eq 3 ] &&
        grep -Eq '^uuvsim: at t = [0-9.]+ s the run stopped: non-finite or diverged .*u_mps' \
            "$tmp/g.err" &&
        grep -Eq '^uuvsim: the state at t = [0-9.]+ s: u_mps=' "$tmp/g.err" &&
        no_nonfinite "$tmp/g.csv" "$tmp/g.json" "$tmp/g.txt" "$tmp/g.err" &&
        python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$tmp/g.json"
}
check "guard: a diverging run (mss astern) stops with exit 3, time and state, no nan" guard
# The summaries' fixes, each a check that failed before.
# A paced run that falls behind says so. Falling behind is made certain,
# whatever the machine's speed: the paced run is stopped (SIGSTOP) for
# 0.6 s part way and then continued, so its later records are late.
paced_stopped() { # OUTPUT [OPTIONS...]
    o=$1; shift
    "$uuvsim" --realtime --scenario scenarios/bench_2s.scn --duration 1 "$@" >"$o" &
    p=$!
    sleep 0.4; kill -STOP $p; sleep 0.6; kill -CONT $p
    wait $p
}
behind() {
    paced_stopped "$tmp/b.txt" --energy-audit && cat "$tmp/b.txt" &&
        grep -q 'paced to the wall clock: FELL BEHIND, [1-9][0-9]* of the records late' \
            "$tmp/b.txt" &&
        grep -q '(0\.[0-9]*x real time)' "$tmp/b.txt" &&
        paced_stopped "$tmp/b.json" --json && grep -q '"realtime_behind": true' "$tmp/b.json"
}
check "realtime: a paced run that falls behind the wall clock is flagged" behind
audit_text() {
    "$uuvsim" --energy-audit --scenario scenarios/bench_2s.scn --duration 0.3 >"$tmp/a.txt" &&
        grep -q '^energy balance: battery [0-9.]* Wh = filter losses .* residual' "$tmp/a.txt"
}
check "--energy-audit: the text summary prints the energy balance" audit_text
single_frames() {
    "$uuvsim" --json --single-rate --scenario scenarios/bench_2s.scn --duration 0.1 >"$tmp/s.json" &&
        grep -q '"frames_s": {"fast": 2e-06, "motor": 2e-06, "control": 0.0008, "slow": 2e-06}' \
            "$tmp/s.json" && grep -q '"report_s": 0.1,' "$tmp/s.json"
}
check "single-rate: frames_s gives the 2 us frames the run used, report_s the records' 100 ms" \
    single_frames
printf 'duration 3\nat 0 n_rpm=1400\nat 1 leg_short=a\n' >"$tmp/trip.scn"
trip_limit() {
    "$uuvsim" --scenario "$tmp/trip.scn" >"$tmp/t.txt" && cat "$tmp/t.txt" &&
        grep -q '^faults injected: leg_short; protection: leg short' "$tmp/t.txt" &&
        "$uuvsim" --json --scenario "$tmp/trip.scn" >"$tmp/t.json" &&
        grep -q '"battery_energy_wh"' "$tmp/t.json" && grep -q '"steps": {"fast": [0-9]*, "motor"' "$tmp/t.json" &&
        tr -d '\n' <"$tmp/t.json" | sed 's/.*"at_s": \([0-9.e+-]*\), "torque_limit_s": \([0-9.e+-]*\).*/\1 \2/' |
            awk '{ print "tripped at " $1 " s, torque limit " $2 " s"; exit !($2 <= $1) }'
}
check "faults by name; torque_limit_s stops at the trip; battery_energy_wh; steps.motor" trip_limit
vessel_mode() {
    "$uuvsim" --plant vessel --scenario scenarios/turning_circle.scn --duration 1 | head -1 |
        grep -q 'vessel only: plant vessel' &&
        "$uuvsim" --json --plant vessel --scenario scenarios/turning_circle.scn --duration 1 |
            grep -q '"mode": "vessel only"'
}
check "a vessel-only run is labelled 'vessel only', not multi-rate" vessel_mode
option_equals() {
    "$uuvsim" --quiet --scenario=scenarios/bench_2s.scn --duration=0.1 --csv="$tmp/e.csv" &&
        [ "$(wc -l <"$tmp/e.csv")" -eq 3 ]
}
check "--scenario=FILE (and every --option=value) is accepted" option_equals
help_trace() { "$uuvsim" --help | grep -q 'to 0.02 s after --trace-from'; }
check "--help gives the default trace window" help_trace
csv_digits() {
    "$uuvsim" --quiet --scenario scenarios/default.scn --duration 60 --csv "$tmp/c.csv" \
        --trace "$tmp/tr.csv" --trace-from 0 --trace-to 0.002 &&
        sed -n 3p "$tmp/c.csv" | grep -q '^0\.1,' &&
        ! cut -d, -f1 "$tmp/c.csv" | grep -q '0000000000000[1-9]\|9999999999999[0-9]' &&
        ! grep -qE '(^|,)-0(,|$)' "$tmp/c.csv" "$tmp/tr.csv" &&
        ! grep -qE 'e-(1[6-9]|[2-9][0-9]|[1-9][0-9][0-9])' "$tmp/c.csv" &&
        head -1 "$tmp/c.csv" | grep -q ',v_dc_v,' &&
        head -1 "$tmp/tr.csv" | grep -q '^t_s,sa,sb,sc,m_index,f_hz,v_dc_v,v_an_v,.*,i_a_a,i_b_a,i_c_a,i_dc_a,n_rpm,te_nm$' &&
        awk -F, 'NR > 1 { for (i = 1; i <= NF; i++) if ($i + 0 != $i) bad++ } END { exit bad > 0 }' "$tmp/c.csv"
}
check "CSV: shortest round-trip digits (0.1), no -0, no tiny decays (below 1e-15: 0), units on v_dc_v and the trace" \
    csv_digits
roundtrip() {
    "$uuvsim" --quiet --plant vessel --propulsion mss --deep-water \
        --scenario scenarios/straight_1300rpm.scn --csv "$tmp/s.csv" &&
        "$csvdiff" --rel 0 --abs 1e-15 "$tmp/s.csv" "$tmp/s.csv"
}
check "CSV: the shortest digits still read back (csvdiff of a file against itself)" roundtrip

printf 'duration 10\nat 1 rudder=abc\n' >"$tmp/bad1.scn"
expect_error "error: malformed value names file, line and field" \
    "bad1.scn:2: field 'rudder'" "$uuvsim" --scenario "$tmp/bad1.scn" --csv "$tmp/bad.csv"
printf 'duration 10\nat 1 n_rpm=2000\n' >"$tmp/bad2.scn"
expect_error "error: out-of-range value" "bad2.scn:2: field 'n_rpm'.*out of range" \
    "$uuvsim" --scenario "$tmp/bad2.scn"
expect_error "error: unknown option" "unknown option '--speed'" \
    "$uuvsim" --speed 3 --scenario scenarios/turning_circle.scn
expect_error "error: missing scenario file" "nosuch.scn: cannot open" \
    "$uuvsim" --scenario "$tmp/nosuch.scn"
expect_error "error: unwritable CSV" "cannot write" \
    "$uuvsim" --scenario scenarios/turning_circle.scn --csv "$tmp/no/such/dir/bad.csv"
printf 'case,delta_r_cmd_rad\n1,2\n' >"$tmp/badd.csv"
expect_error "error: derivs file with a wrong header" "badd.csv:1: column 3" \
    "$uuvsim" derivs "$tmp/badd.csv"
# derivs reads whole lines of any length, the header's column count, plain decimal
# numbers only, finite and in range; each error names the line and column.
head -n 1 $V/npsauv_derivatives.csv | cut -d, -f1-23 >"$tmp/dh.csv"
row=$(sed -n 2p $V/npsauv_derivatives.csv | cut -d, -f1-23)
derivs_bad() { # name, pattern, the row's replacement (sed expression on the row)
    { cat "$tmp/dh.csv"; echo "$row" | sed "$3"; } >"$tmp/bad_d.csv"
    expect_error "derivs: $1" "$2" "$uuvsim" derivs "$tmp/bad_d.csv"
}
derivs_bad "a decimal comma" "bad_d.csv:2: expected 23 columns as in the header, got 24" 's/\./,/'
derivs_bad "trailing junk" "bad_d.csv:2: column 23: expected a plain decimal number, got '1300x'" \
    's/,[^,]*$/,1300x/'
derivs_bad "an extra column" "bad_d.csv:2: expected 23 columns as in the header, got 24" 's/$/,1/'
derivs_bad "inf" "bad_d.csv:2: column 7: expected a plain decimal number, got 'inf'" \
    's/^\([^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*\),[^,]*/\1,inf/'
derivs_bad "a hex float" "column 7: expected a plain decimal number, got '0x1p1'" \
    's/^\([^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*\),[^,]*/\1,0x1p1/'
derivs_bad "u_mps=1e300" "bad_d.csv:2: column 7: out of range \\[-100, 100\\]" \
    's/^\([^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*\),[^,]*/\1,1e300/'
{ cat "$tmp/dh.csv"; printf '%s\0\n' "$row"; } >"$tmp/bad_d.csv"
expect_error "derivs: a NUL byte" "bad_d.csv:2: the line holds a NUL byte" \
    "$uuvsim" derivs "$tmp/bad_d.csv"
{ cat "$tmp/dh.csv"; printf '%s' "$row"; head -c 9000 /dev/zero | tr '\0' '1'; echo; } \
    >"$tmp/bad_d.csv"
expect_error "derivs: a line longer than 8191 bytes is one line" \
    "bad_d.csv:2: column 23: expected a plain decimal number|bad_d.csv:2: column 23: out of range" \
    "$uuvsim" derivs "$tmp/bad_d.csv"
{ cat "$tmp/dh.csv"; echo "$row"; } | tr '\n' '\r' >"$tmp/cr_d.csv"
derivs_cr() { "$uuvsim" derivs "$tmp/cr_d.csv" | [ "$(wc -l)" -eq 2 ]; }
check "derivs: a file of CR line ends reads as lines" derivs_cr

# exec_init's range errors name the option or the scenario's line and field.
printf 'duration 0.04\n' >"$tmp/d1.scn"
expect_error "error: a duration shorter than half a record" \
    "d1.scn:1: field 'duration': 0.04 s is shorter than half a record period" \
    "$uuvsim" --scenario "$tmp/d1.scn" --csv "$tmp/bad.csv"
printf '# long\nduration 1e6\n' >"$tmp/d2.scn"
expect_error "error: a duration beyond the motor frames' counter" \
    "d2.scn:2: field 'duration': 1000000 s needs more than 2\\^32 - 1 motor frames" \
    "$uuvsim" --scenario "$tmp/d2.scn"
expect_error "error: --duration too short for one record" \
    "option --duration: 0.01 s is shorter than half a record period" \
    "$uuvsim" --scenario "$tmp/d2.scn" --duration 0.01
printf 'duration 2\n' >"$tmp/d3.scn"
expect_error "error: --slow-frame 10s on a 2 s run" \
    "d3.scn:1: field 'duration': 2 s is shorter than half a record period \\(10 s, the --slow-frame\\)" \
    "$uuvsim" --scenario "$tmp/d3.scn" --slow-frame 10s
expect_error "error: --slow-frame 800us with the vessel plant" \
    "option --slow-frame: 0.0008 s is out of range: .*at least 1 ms with --plant vessel" \
    "$uuvsim" --scenario "$tmp/d3.scn" --slow-frame 800us --plant vessel
printf 'duration 2\nduration 3\n' >"$tmp/d4.scn"
expect_error "error: a second duration line" \
    "d4.scn:2: field 'duration': a second duration \\(the first is on line 1\\)" \
    "$uuvsim" --scenario "$tmp/d4.scn"

printf 'duration 1\nat 0 n_rpm=800\nat 0.5 leg_short=a\n' >"$tmp/fault.scn"
expect_error "error: a fault the averaged inverter cannot model" \
    "fault.scn:3: field 'leg_short': the averaged inverter has no switches" \
    "$uuvsim" --inverter averaged --scenario "$tmp/fault.scn" --csv "$tmp/bad.csv"
expect_error "error: a drive fault with the vessel plant" \
    "fault.scn:3: field 'leg_short': .*vessel plant has no drive" \
    "$uuvsim" --plant vessel --scenario "$tmp/fault.scn" --csv "$tmp/bad.csv"
# Line numbers are 32-bit: a refusal on line 70001 says 70001 (not 65535).
awk 'BEGIN { print "duration 1"; print "at 0 n_rpm=800"; for (i = 3; i <= 70000; i++) print "#";
             print "at 0.5 leg_short=a" }' >"$tmp/long.scn"
expect_error "error: a configuration refusal on line 70001 names line 70001" \
    "long.scn:70001: field 'leg_short': the averaged inverter has no switches" \
    "$uuvsim" --inverter averaged --scenario "$tmp/long.scn" --csv "$tmp/bad.csv"
{ head -n 70000 "$tmp/long.scn"; echo "init n_rpm=100"; } >"$tmp/long_init.scn"
expect_error "error: an initial shaft speed on line 70001 names line 70001" \
    "long_init.scn:70001: field 'n_rpm': the full plant starts its motor at rest" \
    "$uuvsim" --scenario "$tmp/long_init.scn"

# Scenario text as editors write it, and text that would deceive an echo.
printf '\357\273\277duration 0.3\r\nat 0 n_rpm=500\r\n' >"$tmp/bom.scn"
check "scenario: a UTF-8 byte-order mark and CR LF line ends are read" \
    "$uuvsim" --quiet --scenario "$tmp/bom.scn"
printf 'duration 0.3\rat 0 n_rpm=500\rat 0.2 rudder=x\r' >"$tmp/mac.scn"
expect_error "error: a file of CR line ends is read as lines (the error on line 3)" \
    "mac.scn:3: field 'rudder': expected a number" "$uuvsim" --scenario "$tmp/mac.scn"
printf 'duration 1\nat 0 n_rpm=5\342\200\256007\302\233\n' >"$tmp/bidi.scn"
expect_error "error: a bidi override and a C1 control are echoed escaped" \
    "bidi.scn:2: field 'n_rpm': expected a number in rpm, got '5\\\\u202e007\\\\u009b'" \
    "$uuvsim" --scenario "$tmp/bidi.scn"
if LC_ALL=C grep -q "$(printf '\342\200\256')" "$tmp/stderr"; then
    fail=$((fail + 1)); echo "  FAIL  error: the bidi override is not in the message raw"
else
    pass=$((pass + 1)); echo "  ok    error: the bidi override is not in the message raw"
fi
printf 'duration 1\ninit u_mps=1\ninit u_mps=2\n' >"$tmp/i2.scn"
expect_error "error: an initial state given twice" \
    "i2.scn:3: field 'u_mps': a second initial u_mps \\(the first is on line 2\\)" \
    "$uuvsim" --scenario "$tmp/i2.scn"
mkfifo "$tmp/fifo.scn"
expect_error "error: --scenario FIFO is refused without waiting for a writer" \
    "fifo.scn: cannot open: not a regular file" timeout 60 "$uuvsim" --scenario "$tmp/fifo.scn"

expect_error "error: bad --plant value" "expected one of vessel|full" \
    "$uuvsim" --plant boat --scenario scenarios/turning_circle.scn

expect_error "error: a motor frame that is not whole fast steps" \
    "option --motor-frame: expected a whole number of fast steps \\(2 us\\), got 3 us" \
    "$uuvsim" --motor-frame 3us --scenario scenarios/bench_2s.scn --csv "$tmp/bad.csv"
expect_error "error: a frame without its unit" \
    "option --slow-frame: expected a time with its unit .*got '100'" \
    "$uuvsim" --slow-frame 100 --scenario scenarios/bench_2s.scn
expect_error "error: a motor frame the default controller frame is not a multiple of" \
    "option --control-frame: .*motor frames \\(150 us\\), got 800 us \\(the default: give --control-frame\\)" \
    "$uuvsim" --motor-frame 150us --scenario scenarios/bench_2s.scn

printf 'duration 10\ninit u_mps=1\ninit n_rpm=1200\n' >"$tmp/rpm.scn"
expect_error "error: an initial shaft speed with the full plant" \
    "rpm.scn:3: field 'n_rpm': the full plant starts its motor at rest" \
    "$uuvsim" --scenario "$tmp/rpm.scn" --csv "$tmp/bad.csv"
printf 'duration 10\nat 1 rudder=20\n' >"$tmp/deg.scn"
expect_error "error: an angle in the wrong unit suggests deg" \
    "deg.scn:2: field 'rudder': value 20 rad out of range .*did you mean 20deg" \
    "$uuvsim" --scenario "$tmp/deg.scn"
printf 'duration 10\nat 1 rudder=46deg\n' >"$tmp/deg.scn"
expect_error "error: an angle out of range in degrees is reported in degrees" \
    "deg.scn:2: field 'rudder': value 46 deg out of range \[-45, 45\]" \
    "$uuvsim" --scenario "$tmp/deg.scn"
expect_error "error: bad --modulator value" "option --modulator: expected one of substep|sampled" \
    "$uuvsim" --modulator held --scenario scenarios/bench_2s.scn
expect_error "error: a dead time over 10 us (--dead-time is the set's key pwm.dead_time)" \
    "set: pwm.dead_time: expected a whole number in \[0, 10000\] ns, got 12000 \(out of range\)" \
    "$uuvsim" --dead-time 12us --scenario scenarios/bench_2s.scn
expect_error "error: a dead time with the sampled modulator" \
    "set: pwm.dead_time: a dead time of 1000 ns needs the switching inverter with sub-step edges" \
    "$uuvsim" --dead-time 1us --modulator sampled --scenario scenarios/bench_2s.scn

expect_error "error: a positional argument is reported as such, with --scenario suggested" \
    "unexpected argument 'scenarios/bench_2s.scn': .* --scenario scenarios/bench_2s.scn" \
    "$uuvsim" scenarios/bench_2s.scn
expect_error "error: a trace window after the end of the run" \
    "option --trace-from: 3 s is not before the end of the run \(2 s\)" \
    "$uuvsim" --scenario scenarios/bench_2s.scn --trace "$tmp/bad.csv" --trace-from 3

finish

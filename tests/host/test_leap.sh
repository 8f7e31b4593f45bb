#!/bin/sh
# Exact leaps (uuvsim --fast-path leap, ports/linux/leap.h), one build:
#   test_leap.sh UUVSIM
# Float build: on a short run every telemetry column of the leap run is
# within 1e-5 of its RMS of the exact run, and the run did leap; near the
# clamps, where leaps are refused and steps fall back to the exact path's, within
# 2e-5; repeated
# leap runs give the same bytes; the paths that fall back to ordinary steps
# give the exact path's bytes (a trace window over the whole run, the
# energy audit, the sampled modulator, dead time, FOH, the event inverter);
# after a fault no more leaps are taken. Fixed build: the option is refused
# with a clear message. Both: a bad value is refused.
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
scn=scenarios/bench_2s.scn

result() { # NAME WHY (empty: passed)
    if [ -z "$2" ]; then
        pass=$((pass + 1)); echo "ok   $1"
    else
        fail=$((fail + 1)); echo "FAIL $1: $2"
    fi
}

# leaps FILE.json: the leaps the run took (the summary's "leaps" object)
leaps() {
    sed -n 's/.*"leaps": {"leaps": \([0-9]*\),.*/\1/p' "$1"
}

# refused NAME MESSAGE ARGS...: the run exits with 2, says MESSAGE, writes nothing
refused() {
    name=$1; msg=$2; shift 2
    "$uuvsim" --scenario "$scn" "$@" --csv "$tmp/r.csv" >"$tmp/o" 2>"$tmp/e"
    st=$?
    why=""
    [ $st -eq 2 ] || why="exit status $st, expected 2"
    grep -qF "$msg" "$tmp/e" || why="${why:+$why; }message: $(cat "$tmp/e")"
    { [ -s "$tmp/o" ] || [ -e "$tmp/r.csv" ]; } && why="${why:+$why; }an output was written"
    result "$name" "$why"
}

refused "--fast-path fast is refused" \
    "option --fast-path: expected one of exact|leap, got 'fast'" --fast-path fast

if "$uuvsim" --version | grep -q 'fixed build'; then
    refused "fixed build: --fast-path leap is refused" \
        "option --fast-path leap: not in the fixed build" --fast-path leap
    "$uuvsim" --scenario "$scn" --duration 0.2 --fast-path exact --quiet >"$tmp/o" 2>&1
    st=$?
    result "fixed build: --fast-path exact runs" "$([ $st -eq 0 ] || echo "exit status $st")"
    finish
    exit
fi

# dev EXACT.csv LEAP.csv: the column whose RMS difference relative to its RMS is largest, and it
dev() {
    awk -F, 'NR == FNR { if (FNR > 1) for (i = 1; i <= NF; i++) a[FNR, i] = $i; next }
    FNR == 1 { for (i = 1; i <= NF; i++) h[i] = $i; nc = NF; next }
    { n++; for (i = 1; i <= nc; i++) { d = $i - a[FNR, i]; sd[i] += d * d; s[i] += a[FNR, i] ^ 2 } }
    END { w = 0; wn = "none"
          if (n == 0) { print "no rows"; exit }
          for (i = 1; i <= nc; i++) {
              r = (s[i] > 0) ? sqrt(sd[i] / s[i]) : ((sd[i] > 0) ? 1 : 0)
              if (r > w) { w = r; wn = h[i] } }
          printf "%s %.3g\n", wn, w }' "$1" "$2"
}

# count FILE.json KEY: a count of the summary's "leaps" object
count() {
    sed -n "s/.*\"$2\": \([0-9]*\).*/\1/p" "$1" | head -n 1
}

# Accuracy on the 2 s bench run: RMS of the difference per column against 1e-5 of the RMS.
"$uuvsim" --scenario "$scn" --csv "$tmp/e.csv" --quiet || echo "exact run failed"
"$uuvsim" --scenario "$scn" --csv "$tmp/l.csv" --json --fast-path leap >"$tmp/l.json" ||
    echo "leap run failed"
dev=$(dev "$tmp/e.csv" "$tmp/l.csv")
why=""
echo "$dev" | awk '{ exit !($2 <= 1e-5) }' || why="largest deviation $dev"
result "2 s run: every column within 1e-5 of its RMS (largest: $dev)" "$why"
n=$(leaps "$tmp/l.json")
result "2 s run: leaps taken (${n:-none})" "$([ "${n:-0}" -gt 1000 ] || echo "leaps: ${n:-none}")"
cmp -s "$tmp/e.csv" "$tmp/l.csv" && result "2 s run: the leap run is not the exact run" "identical"

# Near the clamps: a 244-cell pack puts the DC link within 0.1 % of its 1024 V clamp, so leaps
# are refused and steps near it are the exact path's own. Within 2e-5 of the exact run: the
# battery current is the companion's small difference of two bus voltages, each rounded to its
# float ulp (61 uV at 1 kV), and on a 1 kV bus it is 1.2e-5 of its RMS apart (as with the
# 200-cell pack, far from any clamp, and before the steps in double), 7.6e-6 on the default pack.
"$uuvsim" --scenario "$scn" --set battery.n_series=244 --csv "$tmp/ce.csv" --quiet ||
    echo "exact run near the clamps failed"
"$uuvsim" --scenario "$scn" --set battery.n_series=244 --csv "$tmp/cl.csv" --json \
    --fast-path leap >"$tmp/cl.json" || echo "leap run near the clamps failed"
cdev=$(dev "$tmp/ce.csv" "$tmp/cl.csv")
why=""
echo "$cdev" | awk '{ exit !($2 <= 2e-5) }' || why="largest deviation $cdev"
[ "$(count "$tmp/cl.json" bound_refusals)" -gt 0 ] 2>/dev/null || why="${why:+$why; }no refusals"
[ "$(count "$tmp/cl.json" steps_in_runs)" -gt 0 ] 2>/dev/null ||
    why="${why:+$why; }no ordinary steps"
[ "$(count "$tmp/cl.json" steps_in_double)" -gt 0 ] 2>/dev/null ||
    why="${why:+$why; }no steps in double"
result "near the clamps: refusals ($(count "$tmp/cl.json" bound_refusals)), ordinary steps \
($(count "$tmp/cl.json" steps_in_runs)), within 2e-5 (largest: $cdev)" "$why"

# The same bytes run after run.
"$uuvsim" --scenario "$scn" --csv "$tmp/l2.csv" --quiet --fast-path leap
result "repeated leap runs give the same bytes" \
    "$(cmp -s "$tmp/l.csv" "$tmp/l2.csv" || echo "the records differ")"

# Fallbacks: the exact path's bytes.
fallback() { # NAME OPTIONS...
    name=$1; shift
    "$uuvsim" --scenario "$scn" --duration 0.3 "$@" --csv "$tmp/a.csv" --quiet
    "$uuvsim" --scenario "$scn" --duration 0.3 "$@" --csv "$tmp/b.csv" --json \
        --fast-path leap >"$tmp/b.json"
    why=""
    cmp -s "$tmp/a.csv" "$tmp/b.csv" || why="records differ from the exact run's"
    [ "$(leaps "$tmp/b.json")" = 0 ] || why="${why:+$why; }$(leaps "$tmp/b.json") leaps taken"
    result "fallback, exact bytes: $name" "$why"
}
fallback "energy audit" --energy-audit
fallback "sampled modulator" --modulator sampled
fallback "dead time 1 us" --dead-time 1us
fallback "FOH coupling" --slow-to-fast foh
fallback "event inverter" --inverter event
"$uuvsim" --scenario "$scn" --duration 0.3 --trace "$tmp/ta.csv" --trace-from 0 --trace-to 0.3 \
    --csv "$tmp/a.csv" --quiet
"$uuvsim" --scenario "$scn" --duration 0.3 --trace "$tmp/tb.csv" --trace-from 0 --trace-to 0.3 \
    --csv "$tmp/b.csv" --json --fast-path leap >"$tmp/b.json"
why=""
cmp -s "$tmp/ta.csv" "$tmp/tb.csv" || why="traces differ"
cmp -s "$tmp/a.csv" "$tmp/b.csv" || why="${why:+$why; }records differ"
[ "$(leaps "$tmp/b.json")" = 0 ] || why="${why:+$why; }$(leaps "$tmp/b.json") leaps taken"
result "fallback, exact bytes: a trace window over the whole run" "$why"

# A fault (applied at the first slow boundary, 0.1 s): no leap after it.
printf 'duration %s\nat 0 n_rpm=1000\nat 0 switch_open=a+\n' 0.2 >"$tmp/f1.scn"
printf 'duration %s\nat 0 n_rpm=1000\nat 0 switch_open=a+\n' 0.6 >"$tmp/f2.scn"
"$uuvsim" --scenario "$tmp/f1.scn" --json --fast-path leap >"$tmp/f1.json"
"$uuvsim" --scenario "$tmp/f2.scn" --json --fast-path leap >"$tmp/f2.json"
a=$(leaps "$tmp/f1.json")
b=$(leaps "$tmp/f2.json")
why=""
[ "${a:-0}" -gt 0 ] || why="no leap before the fault"
[ "$a" = "$b" ] || why="${why:+$why; }leaps $a in 0.2 s, $b in 0.6 s"
result "fault: leaps before it ($a), none after" "$why"

finish

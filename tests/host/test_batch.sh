#!/bin/sh
# uuvsim batch against the single runs (ports/linux/batch.c):
#   test_batch.sh UUVSIM
# A batch of five different short runs (switching with either modulator,
# a fault that leaves the real-time path, the averaged inverter, a trace
# window, one with a motor frame of its own), every CSV and trace cmp-equal
# to its single run's and every summary too once its two timing lines
# (wall_time_s, realtime_factor) are left out; the same runs given as files
# on the command line; bad input exits 2 with its message and writes
# nothing. Prints one line per check and "N passed, N failed".
set -u
case $1 in /*) uuvsim=$1 ;; *) uuvsim=$(pwd)/$1 ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
check() { if [ "$2" = 0 ]; then ok "$1"; else ko "$1"; fi; }

cd "$tmp" || exit 1
printf 'duration 0.4\nat 0 n_rpm=1000\n' >start.scn
printf 'duration 0.4\nat 0 n_rpm=600\nat 0.2 n_rpm=300\n' >steps.scn
printf 'duration 0.4\nat 0 n_rpm=1000\nat 0.2 switch_open=a+\n' >fault.scn
printf 'duration 0.3\nat 0 n_rpm=800 rudder=5deg\n' >turn.scn
# The list: its own options per line after the common ones (--duration 0.4).
cat >runs.txt <<'LIST'
# scenario [--name NAME] [options]
start.scn
steps.scn --modulator sampled
fault.scn
turn.scn --name turn_avg --inverter averaged
start.scn --name start_trace --trace start_trace.trace.csv --trace-from 0.1 --trace-to 0.101
turn.scn --name turn_200 --motor-frame 200us
LIST
mkdir out
"$uuvsim" batch --out out --list runs.txt -- --duration 0.4 >"$tmp/stdout" 2>"$tmp/err"
status=$?
check "a batch of six runs from a list exits 0 and prints nothing" \
    "$([ $status = 0 ] && [ ! -s "$tmp/stdout" ] && echo 0 || echo 1)"

# single NAME SCENARIO OPTIONS...: the run alone, into single/.
mkdir single
single() {
    name=$1; scn=$2; shift 2
    "$uuvsim" --scenario "$scn" --duration 0.4 --quiet --csv "single/$name.csv" \
        --summary "single/$name.json" "$@" 2>>"$tmp/err"
}
single start start.scn
single steps steps.scn --modulator sampled
single fault fault.scn
single turn_avg turn.scn --inverter averaged
single start_trace start.scn --trace single/start_trace.trace.csv --trace-from 0.1 --trace-to 0.101
single turn_200 turn.scn --motor-frame 200us
timing='"wall_time_s"\|"realtime_factor"'
for n in start steps fault turn_avg start_trace turn_200; do
    grep -v "$timing" "single/$n.json" >a.json
    grep -v "$timing" "out/$n.json" >b.json 2>/dev/null
    cmp -s "single/$n.csv" "out/$n.csv" && cmp -s a.json b.json
    check "run $n: CSV and summary equal to its single run's" $?
done
cmp -s single/start_trace.trace.csv start_trace.trace.csv && [ -s start_trace.trace.csv ]
check "run start_trace: its trace equal to its single run's" $?
grep -q '"faults": \["switch_open"\]' out/fault.json
check "the fault run's summary names the fault (it left the lane path)" $?

mkdir out2
"$uuvsim" batch --out out2 start.scn steps.scn fault.scn turn.scn -- --duration 0.4 2>"$tmp/err"
st=$?
same=0
for n in start fault; do cmp -s "single/$n.csv" "out2/$n.csv" || same=1; done
[ $st = 0 ] && [ $same = 0 ] && [ -f out2/steps.csv ] && [ -f out2/turn.json ]
check "scenario files on the command line: a run each, named after the file" $?

# refused NAME PATTERN ARGS...: exit 2, the message, nothing written in bad/.
mkdir bad
printf 'duration 0.4\nat 0 n_rpm=1000\nat 0.1 warp=9\n' >broken.scn
printf 'start.scn\n--inverter averaged\n' >optfirst.txt
printf 'start.scn\nstart.scn --modulator sampled\n' >twice.txt
refused() {
    name=$1; pattern=$2; shift 2
    "$uuvsim" batch "$@" >"$tmp/stdout" 2>"$tmp/err"
    status=$?
    if [ $status -eq 2 ] && grep -Eq -e "$pattern" "$tmp/err" && [ -z "$(ls -A bad)" ]; then
        ok "$name"
    else
        ko "$name (status $status)"
    fi
}
refused "no --out" "option --out: expected" start.scn
refused "--out not a directory" "not a directory" --out runs.txt start.scn
refused "no runs" "no runs" --out bad
refused "an unknown batch option" "unknown option '--fast'" --out bad --fast start.scn
refused "a missing scenario file" "nope.scn: cannot open" --out bad start.scn nope.scn
refused "a bad scenario line (file, line, field)" "broken.scn:3" --out bad start.scn broken.scn
refused "a bad run option" "option --inverter" --out bad start.scn -- --inverter fast
refused "--csv is not a batch option" "--csv is not a batch run's option" \
    --out bad start.scn -- --csv x.csv
refused "a missing list" "runs-none.txt: cannot open" --out bad --list runs-none.txt
refused "a list line that starts with an option (file and line)" "optfirst.txt:2: expected a scenario" \
    --out bad --list optfirst.txt
refused "two runs of one name" "both named 'start'" --out bad --list twice.txt

finish

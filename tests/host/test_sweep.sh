#!/bin/sh
# uuvsim sweep and sweep-merge (ports/linux/sweep.c): a 16-run sweep (a grid
# and seeded Monte Carlo draws, 1 s of the full plant each) with -j 2; the
# same sweep killed halfway and resumed; the same sweep in three shards
# merged: all three give the same results, one row per run. A failing run is
# a row with its error; bad sweep files are refused with file:line.
# Usage: test_sweep.sh UUVSIM. Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
check() { name=$1; shift; if "$@" >"$tmp/out" 2>"$tmp/err"; then ok "$name"; else ko "$name"; fi; }
expect_error() {
    name=$1; pattern=$2; shift 2
    "$@" >"$tmp/stdout" 2>"$tmp/err"
    status=$?
    if [ $status -eq 2 ] && grep -qE -- "$pattern" "$tmp/err"; then ok "$name"; else ko "$name (exit $status)"; fi
}

cat >"$tmp/s.sweep" <<'EOF'
# 4 x 2 grid points, 2 draws each: 16 runs of 1 s of the full plant.
scenario scenarios/default.scn
options --duration 1
grid battery.n_parallel 1 2 4 8
grid stage.l 1e-3 2e-3
draws 2
seed 7
normal motor.j_rotor 0.102 0.005
uniform stage.r_l 0.02 0.03
metric energy_wh
metric final.n_rpm
metric final.soc
metric endurance_h
metric max:i_rms_a
metric protection.tripped
EOF

check "sweep: 16 runs with -j 2" "$uuvsim" sweep "$tmp/s.sweep" --out "$tmp/full" -j 2
rows=$(($(wc -l <"$tmp/full/results.csv") - 1))
[ "$rows" -eq 16 ] && ok "results.csv: 16 rows" || ko "results.csv: $rows rows"
check "results.csv: every run's number once, in order" sh -c \
    "tail -n +2 '$tmp/full/results.csv' | cut -d, -f1 | tr '\n' ' ' | grep -qx '0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 '"
check "results.csv: every run succeeded with its metrics" sh -c \
    "tail -n +2 '$tmp/full/results.csv' | awk -F, '\$2 != 0 || \$NF == \"\" { bad = 1 } END { exit bad }'"
check "results.json: 16 runs" sh -c "[ \$(grep -c '\"run\": ' '$tmp/full/results.json') -eq 16 ]"
# The physics: the charge drawn halves with twice the strings (runs 0 and 2: 1 and 2 strings,
# the same inductance; the draws differ a little).
check "more strings, less of the charge drawn (final.soc rises with battery.n_parallel)" sh -c \
    "awk -F, 'NR > 1 && \$5 == \"1e-3\" { soc[\$4] = \$10 } END { exit !(soc[1] < soc[2] && soc[2] < soc[4] && soc[4] < soc[8]) }' '$tmp/full/results.csv'"

# Killed halfway, then resumed: SIGKILL to the sweep and the runs under way at once (its
# own process group, as a batch system cancels a job), so nothing is cleaned up and the
# runs' scratch files are left half written.
setsid "$uuvsim" sweep "$tmp/s.sweep" --out "$tmp/killed" -j 2 2>/dev/null &
pid=$!
n=0
while [ "$(ls "$tmp/killed/runs" 2>/dev/null | grep -c '\.row$')" -lt 6 ] && [ $n -lt 600 ]; do
    sleep 0.05; n=$((n + 1))
done
kill -9 -$pid 2>/dev/null
wait $pid 2>/dev/null
n=0
while kill -0 -$pid 2>/dev/null && [ $n -lt 600 ]; do # until the whole group is gone
    sleep 0.05; n=$((n + 1))
done
done_rows=$(ls "$tmp/killed/runs" | grep -c '\.row$')
[ "$done_rows" -ge 6 ] && [ "$done_rows" -lt 16 ] && [ ! -f "$tmp/killed/results.csv" ] &&
    ! kill -0 -$pid 2>/dev/null &&
    ok "killed halfway: $done_rows of 16 rows, no results yet, no run left" || ko "killed: $done_rows rows"
check "resumed: the same command completes it" "$uuvsim" sweep "$tmp/s.sweep" --out "$tmp/killed" -j 2
cp "$tmp/err" "$tmp/resume.err"
check "resumed: it ran only the runs without a row" grep -q "$((16 - done_rows)) to run ($done_rows done before)" "$tmp/resume.err"
check "resumed: results.csv equals the uninterrupted sweep's" cmp "$tmp/full/results.csv" "$tmp/killed/results.csv"
check "resumed: results.json equals the uninterrupted sweep's" cmp "$tmp/full/results.json" "$tmp/killed/results.json"

# Three shards, merged.
for k in 1 2 3; do
    check "shard $k/3" "$uuvsim" sweep "$tmp/s.sweep" --out "$tmp/shard$k" --shard $k/3
done
check "sweep-merge of the three shards" "$uuvsim" sweep-merge --out "$tmp/merged" "$tmp/shard1" \
    "$tmp/shard2" "$tmp/shard3"
check "merged results.csv equals the single-process one" cmp "$tmp/full/results.csv" "$tmp/merged/results.csv"
check "merged results.json equals the single-process one" cmp "$tmp/full/results.json" "$tmp/merged/results.json"
"$uuvsim" sweep-merge --out "$tmp/part" "$tmp/shard1" "$tmp/shard2" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "5 of 16 runs are missing" "$tmp/err" && ok "a merge without a shard says how many runs are missing" ||
    ko "merge of two shards of three"

# The Slurm job array of tools/slurm-sweep.sh, its tasks run here one after the other.
UUVSIM=$uuvsim sh tools/slurm-sweep.sh "$tmp/s.sweep" "$tmp/slurm" 2 1 >"$tmp/job.sh"
check "slurm-sweep.sh: array task 1 of 2" env SLURM_ARRAY_TASK_ID=1 sh "$tmp/job.sh"
check "slurm-sweep.sh: array task 2 of 2" env SLURM_ARRAY_TASK_ID=2 sh "$tmp/job.sh"
check "slurm-sweep.sh: the merge job" sh -c "$(UUVSIM=$uuvsim sh tools/slurm-sweep.sh --merge "$tmp/slurm" 2)"
check "the Slurm array's merged results.csv equals the single-process one" \
    cmp "$tmp/full/results.csv" "$tmp/slurm/merged/results.csv"

# A run that fails is a row with its error.
cat >"$tmp/f.sweep" <<'EOF'
scenario scenarios/default.scn
options --duration 0.2 --plant vessel
grid vessel.weight 53400 -5
metric final.u_mps
EOF
check "a failing run does not stop the sweep" "$uuvsim" sweep "$tmp/f.sweep" --out "$tmp/f"
check "the failed run's row: exit status 2 and its error" grep -q \
    '^1,2,"--set: vessel.weight: expected a value in \[100, 10000000\] N, got -5' "$tmp/f/results.csv"

# Bad sweep files and options.
printf 'scenario scenarios/default.scn\ngrid stage.l 1e-3 x\n' >"$tmp/b.sweep"
expect_error "a grid value that is no number: file:line" "b.sweep:2: grid stage.l: expected numbers, got 'x'" \
    "$uuvsim" sweep "$tmp/b.sweep" --out "$tmp/b"
printf 'scenario scenarios/default.scn\nmetric no-such\n' >"$tmp/b.sweep"
expect_error "an unknown metric form" "b.sweep:2: metric: expected" "$uuvsim" sweep "$tmp/b.sweep" --out "$tmp/b"
printf 'grid stage.l 1e-3\n' >"$tmp/b.sweep"
expect_error "no scenario" "b.sweep: no scenario" "$uuvsim" sweep "$tmp/b.sweep" --out "$tmp/b"
printf 'scenario scenarios/default.scn\nnormal stage.l 1e-3 -1\n' >"$tmp/b.sweep"
expect_error "a negative standard deviation" "b.sweep:2: normal stage.l: expected MEAN SD" \
    "$uuvsim" sweep "$tmp/b.sweep" --out "$tmp/b"
expect_error "--shard 4/3" "--shard: expected K/N" "$uuvsim" sweep "$tmp/s.sweep" --out "$tmp/b" --shard 4/3
expect_error "another sweep in the same directory" "holds another sweep" \
    "$uuvsim" sweep "$tmp/f.sweep" --out "$tmp/full"

finish

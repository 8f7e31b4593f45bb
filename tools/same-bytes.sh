#!/bin/sh
# Byte identity of the desk simulator's outputs against another commit.
#
#   tools/same-bytes.sh REV [DURATION]
#
# Builds REV's desk simulators (fixed and float) in a temporary git
# worktree under build/same-bytes/, builds this tree's, and runs both on
# the same matrix: every scenario in scenarios/ plus two fault scenarios
# written here, x both builds x the inverter modes (switching with the
# sub-step and the sampled modulator, event, averaged) x the couplings
# (each --slow-to-fast value with --fast-to-slow avg, each --fast-to-slow
# value with --slow-to-fast zoh), and a few extra paths (dead time, the
# energy audit, staggered with sampled coupling). Each run writes its CSV,
# its JSON summary and a trace window; every file is compared with cmp,
# the summary without its two wall-clock fields (wall_time_s,
# realtime_factor), and the exit codes must agree. Runs last DURATION
# simulated seconds (default 1.2; a scenario's own duration when
# shorter), so that the matrix takes a few minutes on two cores.
# Prints one line per difference and a final `N passed, N failed`;
# exits 1 when any failed.
set -eu

rev=${1:?usage: tools/same-bytes.sh REV [DURATION]}
dur=${2:-1.2}
top=$(git rev-parse --show-toplevel)
cd "$top"
work=build/same-bytes
base=$work/base
mkdir -p "$work"

# REV's tree, built in its own worktree (reused when it is already at REV).
sha=$(git rev-parse --verify "$rev^{commit}")
if [ -d "$base" ] && [ "$(git -C "$base" rev-parse HEAD 2>/dev/null)" != "$sha" ]; then
    git worktree remove --force "$base"
fi
if [ ! -d "$base" ]; then
    git worktree add --detach "$base" "$sha" >/dev/null 2>&1
fi
make -s -C "$base" -j2 build/linux-fixed/uuvsim build/linux-float/uuvsim >/dev/null
make -s -j2 build/linux-fixed/uuvsim build/linux-float/uuvsim >/dev/null

# Fault scenarios: the faults every layer takes, the switching layers'
# switch and phase faults, and a shoot-through that trips the protection.
cat > "$work/faults_drive.scn" <<'EOF'
duration 1.2
at 0 n_rpm=1000
at 0.3 current_offset=2.5 prop_fouling=2
at 0.5 dc_cap=0.5
EOF
cat > "$work/faults_switch.scn" <<'EOF'
duration 1.2
at 0 n_rpm=1000
at 0.5 switch_open=b-
at 0.8 phase_open=c
EOF
cat > "$work/faults_trip.scn" <<'EOF'
duration 1.2
at 0 n_rpm=800
at 0.4 leg_short=a
EOF

# One line per configuration: the options after --scenario.
configs() {
    for down in zoh foh deriv stagger; do
        for inv in "switching --modulator substep" "switching --modulator sampled" event averaged; do
            echo "--inverter $inv --slow-to-fast $down --fast-to-slow avg"
        done
    done
    for up in filter sample; do
        for inv in "switching --modulator substep" "switching --modulator sampled" event averaged; do
            echo "--inverter $inv --slow-to-fast zoh --fast-to-slow $up"
        done
    done
    echo "--inverter switching --modulator substep --dead-time 1us"
    echo "--inverter switching --modulator sampled --slow-to-fast stagger --fast-to-slow sample"
    echo "--inverter switching --modulator substep --energy-audit"
    echo "--inverter event --energy-audit"
    echo "--inverter averaged --energy-audit"
}

# A scenario's duration capped at DURATION.
run_s() {
    awk -v cap="$dur" '$1 == "duration" { d = $2 } END { if (d == "" || d + 0 > cap + 0) d = cap; print d }' "$1"
}

list=$work/runs.txt
: > "$list"
i=0
for scn in scenarios/*.scn "$work/faults_drive.scn" "$work/faults_switch.scn" \
        "$work/faults_trip.scn"; do
    t=$(run_s "$scn")
    from=$(awk -v t="$t" 'BEGIN { print t / 2 }')
    to=$(awk -v t="$t" 'BEGIN { print t / 2 + 0.002 }')
    configs | while IFS= read -r cfg; do
        for num in fixed float; do
            i=$((i + 1))
            echo "$i|$num|$scn|$t|$from|$to|$cfg"
        done
    done >> "$list"
done

# One run of both trees; prints PASS or FAIL lines.
cat > "$work/one.sh" <<'EOF'
#!/bin/sh
IFS='|' read -r id num scn t from to cfg <<LINE
$1
LINE
work=$2
base=$3
for side in new old; do
    if [ "$side" = new ]; then exe=build/linux-$num/uuvsim; else exe=$base/build/linux-$num/uuvsim; fi
    out=$work/out/$id.$side
    rm -rf "$out"; mkdir -p "$out"
    # shellcheck disable=SC2086
    "$exe" --scenario "$scn" --duration "$t" $cfg --quiet --csv "$out/t.csv" \
        --summary "$out/s.json" --trace "$out/tr.csv" --trace-from "$from" --trace-to "$to" \
        > "$out/stdout" 2> "$out/stderr"
    echo $? > "$out/rc"
    if [ -f "$out/s.json" ]; then
        sed -e '/"wall_time_s"/d' -e '/"realtime_factor"/d' "$out/s.json" > "$out/s.cmp"
    fi
done
what="$num $scn $cfg"
bad=
for f in rc t.csv s.cmp tr.csv stderr; do
    a=$work/out/$id.new/$f
    b=$work/out/$id.old/$f
    if [ -f "$a" ] || [ -f "$b" ]; then
        cmp -s "$a" "$b" || bad="$bad $f"
    fi
done
if [ -z "$bad" ]; then
    echo "PASS $what (exit $(cat "$work/out/$id.new/rc"))"
    rm -rf "$work/out/$id.new" "$work/out/$id.old"
else
    echo "FAIL $what:$bad differ (rc $(cat "$work/out/$id.new/rc") vs $(cat "$work/out/$id.old/rc"))"
fi
EOF
rm -rf "$work/out"
mkdir -p "$work/out"
results=$work/results.txt
xargs -P 2 -I{} sh "$work/one.sh" {} "$work" "$base" < "$list" > "$results"
grep '^FAIL' "$results" || true
pass=$(grep -c '^PASS' "$results" || true)
fail=$(grep -c '^FAIL' "$results" || true)
# A configuration both refuse (the averaged layer's switch faults) counts
# as passed when the exit codes and messages agree.
echo "$(grep -c '^PASS.*(exit [1-9]' "$results" || true) of the passed runs refused by both"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]

#!/bin/sh
# The plots of make run (tools/plots.gp): a short run of the default
# mission with a trace window, then the script. gnuplot must finish without
# a message (a missing column or an empty data set gives one), and each of
# the eight pictures must be a PNG with something drawn in it; the
# scenario's events are found and placed (tools/plot_events.awk).
#   test_plots.sh UUVSIM
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"


if "$uuvsim" --quiet --scenario scenarios/default.scn --duration 31 --csv "$tmp/telemetry.csv" \
    --trace "$tmp/trace.csv" --trace-from 30 --trace-to 30.02 2>"$tmp/err"; then
    ok "31 s of the default mission with a 20 ms trace"
else
    ko "31 s of the default mission with a 20 ms trace" "$(cat "$tmp/err")"
fi

if ! command -v gnuplot >/dev/null 2>&1; then
    ko "gnuplot" "not installed (make test installs it: tools/ensure-deps.sh)"
elif gnuplot -e "dir='$tmp'; scn='scenarios/default.scn'" tools/plots.gp >"$tmp/gp.out" 2>&1 &&
    [ ! -s "$tmp/gp.out" ]; then
    ok "tools/plots.gp runs without a message"
else
    ko "tools/plots.gp runs without a message" "$(head -5 "$tmp/gp.out")"
fi

# The PNG signature's readable bytes, and a size no blank frame reaches
# (a frame with axes and no data is about 11 kB at 900 x 600).
for p in trajectory plan depth speed shaft currents dc_link battery; do
    f="$tmp/$p.png"
    size=0
    [ -f "$f" ] && size=$(wc -c <"$f")
    if [ "$size" -gt 15000 ] && [ "$(od -An -c -j1 -N3 "$f" | tr -d ' ')" = "PNG" ]; then
        ok "$p.png ($size bytes)"
    else
        ko "$p.png" "missing, not a PNG, or $size bytes"
    fi
done

# The events of the default mission's first 31 s: the start and the turn at 40 s is not
# reached; 0 s with its three commands.
if [ -f "$tmp/events.dat" ] && [ "$(wc -l <"$tmp/events.dat")" -eq 1 ] &&
    grep -q '^0,0,0,0,"n_rpm=1000 heading=0 depth=10"$' "$tmp/events.dat"; then
    ok "events: the scenario's commands placed at the records (events.dat)"
else
    ko "events" "$(cat "$tmp/events.dat" 2>/dev/null)"
fi

finish

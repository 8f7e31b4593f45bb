#!/bin/sh
# uuvsim view: the page of a short run of the default mission, its bad
# input, and the page in a real browser (headless Chromium, software GL:
# view_browser.py): it loads without an error, draws the vehicle, and the
# time slider moves it. A deliberately broken copy of the page must fail
# the browser check, which proves that a broken page is seen. Then the
# live view (uuvsim --view) of a paced 8 s run in the same browser check.
#   test_view.sh UUVSIM
# Prints one line per check and "N passed, N failed".
set -u
uuvsim=$1
here=$(dirname "$0")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"


# expect_error WHAT MESSAGE-PART DIR: exit 2, the message, no page left behind.
expect_error() {
    "$uuvsim" view "$3" >"$tmp/out" 2>"$tmp/err"
    status=$?
    if [ $status -eq 2 ] && grep -q -- "$2" "$tmp/err" && [ ! -e "$3/mission.html" ] &&
        [ -z "$(ls "$3" | grep "mission.html.partial")" ]; then
        ok "$1 (exit 2: $(head -c 110 "$tmp/err"))"
    else
        ko "$1" "exit $status, message '$(head -c 200 "$tmp/err")'"
    fi
}

run=$tmp/run
mkdir -p "$run"
# The mission of manual commands: the camera's figures below were measured on it.
if "$uuvsim" --quiet --scenario tests/host/manual_mission.scn --duration 31 \
    --csv "$run/telemetry.csv" --summary "$run/summary.json" 2>"$tmp/err"; then
    ok "31 s of tests/host/manual_mission.scn"
else
    ko "31 s of tests/host/manual_mission.scn" "$(cat "$tmp/err")"
fi
# The summary lists the scenario's timed commands (the page marks them).
# (31 s of the mission: the one at 0 s; the next comes at 40 s.)
if grep -q '^  "events": \[{"t_s": 0, "command": "n_rpm", "value": 1000}\],$' "$run/summary.json"
then
    ok "the summary lists the scenario's commands (events)"
else
    ko "the summary lists the scenario's commands" "$(grep '"events"' "$run/summary.json")"
fi
start=$(date +%s%N)
if "$uuvsim" view "$run" >"$tmp/out" 2>"$tmp/err" && [ -s "$run/mission.html" ]; then
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    ok "uuvsim view writes mission.html ($(wc -c <"$run/mission.html") bytes, $ms ms)"
else
    ko "uuvsim view writes mission.html" "$(cat "$tmp/err")"
fi
# Self-contained: the run's rows and three.js are in it; nothing is fetched.
rows=$(($(wc -l <"$run/telemetry.csv") - 1))
if grep -q 'REVISION="1' "$run/mission.html" &&
    [ "$(grep -c '^[0-9]' "$run/mission.html")" -ge "$rows" ] &&
    ! grep -Eqi '(src|href)="(https?:|//)' "$run/mission.html"; then
    ok "the page holds three.js and the $rows rows, and loads nothing from elsewhere"
else
    ko "the page is self-contained" "three.js, rows or an outside reference"
fi

# Bad input.
expect_error "error: no such folder" "no such folder" "$tmp/missing"
mkdir -p "$tmp/empty"
expect_error "error: a folder without telemetry.csv" "telemetry.csv: No such file" "$tmp/empty"
mkdir -p "$tmp/bad1" "$tmp/bad2" "$tmp/bad3" "$tmp/bad4"
# The header's second column and the number of columns, as this build writes them.
col2=$(head -1 "$run/telemetry.csv" | cut -d, -f2)
ncols=$(head -1 "$run/telemetry.csv" | tr ',' '\n' | wc -l)
sed '3s/,[^,]*,/,x1,/' "$run/telemetry.csv" >"$tmp/bad1/telemetry.csv"
expect_error "error: a field that is not a number" \
    "telemetry.csv:3: field '$col2': expected a finite number, got 'x1'" "$tmp/bad1"
sed '5s/,[^,]*$//' "$run/telemetry.csv" >"$tmp/bad2/telemetry.csv"
expect_error "error: a short row" "telemetry.csv:5: expected $ncols fields, got $((ncols - 1))" \
    "$tmp/bad2"
sed '1s/z_m/depth/' "$run/telemetry.csv" >"$tmp/bad3/telemetry.csv"
expect_error "error: a missing column" "telemetry.csv:1: expected a column 'z_m'" "$tmp/bad3"
cp "$run/telemetry.csv" "$tmp/bad4/"
echo '[1, 2]' >"$tmp/bad4/summary.json"
expect_error "error: a summary that is no JSON object" "summary.json:1: expected a JSON object" \
    "$tmp/bad4"
mkdir -p "$tmp/bad5"
head -1 "$run/telemetry.csv" >"$tmp/bad5/telemetry.csv"
sed -n '2p' "$run/telemetry.csv" >>"$tmp/bad5/telemetry.csv"
sed -n '2p' "$run/telemetry.csv" >>"$tmp/bad5/telemetry.csv"
expect_error "error: time that does not increase" "telemetry.csv:3: field 't_s': expected a time after" \
    "$tmp/bad5"
if "$uuvsim" view >/dev/null 2>"$tmp/err"; [ $? -eq 2 ] && grep -q "expected exactly one folder" "$tmp/err"
then
    ok "error: uuvsim view without a folder"
else
    ko "error: uuvsim view without a folder" "$(cat "$tmp/err")"
fi
if UUVSIM_THREE_JS="$tmp/nothree.js" "$uuvsim" view "$tmp/bad4/../run" >/dev/null 2>"$tmp/err"; then
    ko "error: three.js missing" "exit 0"
elif grep -q "apt-get install libjs-three" "$tmp/err"; then
    ok "error: three.js missing names the package (libjs-three)"
else
    ko "error: three.js missing" "$(cat "$tmp/err")"
fi

# Extra columns (others' additions) are carried along; the page still
# draws. Subnormal values (a fin's decaying deflection) are numbers.
mkdir -p "$tmp/extra"
awk -F, 'BEGIN { OFS = "," } { print $0, (NR == 1 ? "psi_ref_rad" : "-4.9e-324") }' \
    "$run/telemetry.csv" >"$tmp/extra/telemetry.csv"
if "$uuvsim" view "$tmp/extra" >/dev/null 2>"$tmp/err"; then
    ok "a telemetry file with an extra column of subnormal values"
else
    ko "a telemetry file with an extra column of subnormal values" "$(cat "$tmp/err")"
fi

# The browser: the page as written, then a broken copy (a script error).
if python3 "$here/view_browser.py" "$run/mission.html" 5 28 >"$tmp/browser" 2>&1; then
    ok "the page in headless Chromium: $(grep -c '^ok' "$tmp/browser") checks"
else
    ko "the page in headless Chromium" "$(grep -v '^ok' "$tmp/browser" | head -5)"
fi
sed 's/^}, { passive: false });$/}, { passive: false }));/' "$run/mission.html" >"$tmp/broken.html"
if cmp -s "$run/mission.html" "$tmp/broken.html"; then
    ko "a broken page fails the browser check" "could not break the page"
elif python3 "$here/view_browser.py" "$tmp/broken.html" 5 28 >"$tmp/broken" 2>&1; then
    ko "a broken page fails the browser check" "it passed"
else
    ok "a broken page fails the browser check ($(grep -m1 '^FAIL' "$tmp/broken" | head -c 120))"
fi
sed 's/^/    /' "$tmp/browser"

# The live view: a paced 8 s run that starts when the browser opens its
# page; the frames stream in, the summary comes at the end, and the run's
# telemetry is the same bytes as without the view.
mkdir -p "$tmp/live"
"$uuvsim" --quiet --view --view-port 0 --scenario scenarios/default.scn --duration 8 \
    --csv "$tmp/live/telemetry.csv" 2>"$tmp/live/err" &
pid=$!
url=""
for k in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
    url=$(sed -n 's|.*live view on \(http://127\.0\.0\.1:[0-9]*/\).*|\1|p' "$tmp/live/err")
    [ -n "$url" ] && break
    sleep 0.25
done
if [ -n "$url" ] && python3 "$here/view_browser.py" --live "$url" >"$tmp/live/browser" 2>&1; then
    ok "the live view in headless Chromium: $(grep -c '^ok' "$tmp/live/browser") checks"
else
    ko "the live view in headless Chromium" "$(grep -v '^ok' "$tmp/live/browser" 2>/dev/null |
        head -5) $(cat "$tmp/live/err")"
fi
# The run ends by itself once watched; it is stopped if the browser never came.
for k in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
    kill -0 $pid 2>/dev/null || break
    sleep 0.5
done
kill $pid 2>/dev/null
wait $pid
status=$?
"$uuvsim" --quiet --scenario scenarios/default.scn --duration 8 --csv "$tmp/live/plain.csv"
if [ $status -eq 0 ] && cmp -s "$tmp/live/telemetry.csv" "$tmp/live/plain.csv"; then
    ok "the watched run exits 0 with the same telemetry as an unwatched one"
else
    ko "the watched run" "exit $status, or its telemetry differs"
fi
sed 's/^/    /' "$tmp/live/browser"
if "$uuvsim" --view --view-port 70000 --scenario scenarios/default.scn >/dev/null 2>"$tmp/err"; then
    ko "error: --view-port 70000" "exit 0"
elif grep -q "expected a port number in \[0, 65535\], got '70000'" "$tmp/err"; then
    ok "error: --view-port 70000 (exit 2)"
else
    ko "error: --view-port 70000" "$(cat "$tmp/err")"
fi

finish

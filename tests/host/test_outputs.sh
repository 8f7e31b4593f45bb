#!/bin/sh
# Output safety of uuvsim (ports/linux/out_file.h, docs/reliability.md):
#   test_outputs.sh UUVSIM
# Every refusal exits 2 with a message and changes nothing outside the run's
# own files: a symbolic link planted at the temporary name, a device node, a
# symbolic link or a directory as an output, two outputs with the same path
# (or the same file under two names), an output equal to the input; the
# outputs of a run are committed together or not at all; SIGINT, SIGTERM and
# SIGHUP leave no temporary file; a write error on stdout exits 2.
# Prints one line per check and "N passed, N failed".
set -u
case $1 in /*) uuvsim=$1 ;; *) uuvsim=$(pwd)/$1 ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"

d="$tmp/d"
mkdir -p "$d"
printf 'duration 2\nat 0 n_rpm=800\n' >"$d/v.scn"
printf 'keep\n' >"$d/victim.txt"
# The state of the directory (names, kinds, link targets, contents) and of /dev/null.
snapshot() {
    (cd "$d" && for f in $(ls -A | sort); do
        if [ -L "$f" ]; then echo "$f -> $(readlink "$f")"
        elif [ -f "$f" ]; then echo "$f $(cksum <"$f")"
        else echo "$f $(ls -ld "$f" | cut -c1)"; fi
    done)
}

# refused NAME PATTERN ARGS...: exit 2, the message, nothing on stdout, no change.
refused() {
    name=$1; pattern=$2; shift 2
    snapshot >"$tmp/before"
    (cd "$d" && "$uuvsim" "$@") >"$tmp/out" 2>"$tmp/err"
    status=$?
    snapshot >"$tmp/after"
    if [ $status -eq 2 ] && grep -Eq -e "$pattern" "$tmp/err" && [ ! -s "$tmp/out" ] &&
       cmp -s "$tmp/before" "$tmp/after"; then
        ok "$name"
    else
        echo "exit $status" >>"$tmp/err"; diff "$tmp/before" "$tmp/after" >>"$tmp/err"
        ko "$name"
    fi
}

# A symbolic link planted at the temporary name (the run's pid: exec keeps the shell's).
planted() {
    snapshot >"$tmp/before"
    (cd "$d" && sh -c 'ln -s victim.txt out.csv.partial.$$ && exec "$0" --plant vessel \
        --scenario v.scn --csv out.csv' "$uuvsim") >"$tmp/out" 2>"$tmp/err"
    status=$?
    rm -f "$d"/out.csv.partial.*
    snapshot >"$tmp/after"
    [ $status -eq 2 ] && grep -q 'cannot create the temporary file .*refusing' "$tmp/err" &&
        cmp -s "$tmp/before" "$tmp/after" && [ "$(cat "$d/victim.txt")" = keep ]
}
if planted; then ok "a symbolic link at the temporary name: refused, not followed"; else
    echo "exit $status" >>"$tmp/err"; ko "a symbolic link at the temporary name: refused, not followed"; fi

# The device and /dev/stdout-like cases use nodes of the test's own directory, never the
# system's: a program that failed this test would replace them (as root).
if mknod "$d/null" c 1 3 2>/dev/null; then
    refused "a device node as an output (c 1 3, as /dev/null): refused" \
        "--csv: null: a device, not a regular file" --scenario v.scn --csv null
else
    mkfifo "$d/null"
    refused "a FIFO as an output: refused" "--csv: null: a FIFO, not a regular file" \
        --scenario v.scn --csv null
fi
ln -s /proc/self/fd/1 "$d/stdout"
refused "a link to /proc/self/fd/1 (as /dev/stdout) as an output: refused" \
    "--csv: stdout: a symbolic link" --scenario v.scn --csv stdout
ln -s victim.txt "$d/link.csv"
refused "a symbolic link as an output: refused, its target kept" \
    "--trace: link.csv: a symbolic link" --scenario v.scn --trace link.csv
refused "a directory as an output: refused" "--csv: .*: a directory" --scenario v.scn --csv .
refused "two outputs with the same path: refused" \
    "--csv same.csv and --trace same.csv are the same file" \
    --scenario v.scn --csv same.csv --trace same.csv
refused "--csv X --summary ./X: refused" "--csv x.json and --summary ./x.json are the same file" \
    --scenario v.scn --csv x.json --summary ./x.json
ln "$d/victim.txt" "$d/hard.txt"
refused "two names of one file (a hard link): refused" "are the same file" \
    --scenario v.scn --csv victim.txt --summary hard.txt
refused "an output equal to the input: refused, the scenario kept" \
    "--csv v.scn and --scenario v.scn are the same file: an output must not replace an input" \
    --scenario v.scn --csv v.scn
refused "an output naming the input through ../: refused" "are the same file" \
    --scenario v.scn --summary "../d/v.scn"
refused "an unwritable summary: no output committed, none left" "cannot (write|create)" \
    --scenario v.scn --csv a.csv --trace b.csv --summary no/such/dir/s.json

# Committed together: a good run writes every output, and nothing else.
(cd "$d" && "$uuvsim" --plant vessel --quiet --scenario v.scn --csv a.csv --summary s.json) \
    2>"$tmp/err"
if [ -s "$d/a.csv" ] && [ -s "$d/s.json" ] && [ -z "$(ls "$d" | grep partial)" ]; then
    ok "a good run commits every output and leaves no temporary file"
else ko "a good run commits every output and leaves no temporary file"; fi
rm -f "$d/a.csv" "$d/s.json"

# Signals: a long run with a trace, stopped; no temporary file is left, the outputs
# are not committed, and the status is the signal's.
for sig in INT TERM HUP; do
    (cd "$d" && exec "$uuvsim" --quiet --scenario v.scn --duration 600 --csv sa.csv \
        --trace st.csv --trace-from 0 --trace-to 10) 2>"$tmp/err" &
    pid=$!
    sleep 1
    kill -"$sig" $pid
    wait $pid
    status=$?
    if [ $status -gt 128 ] && [ -z "$(ls "$d" | grep -E 'partial|sa.csv|st.csv')" ]; then
        ok "SIG$sig: no temporary file left, nothing committed (exit $status)"
    else
        ls "$d" >>"$tmp/err"; ko "SIG$sig: no temporary file left (exit $status)"
    fi
    rm -f "$d"/sa.csv* "$d"/st.csv*
done

# Standard output: a write error is exit 2, and the files of the run are not committed.
if [ -w /dev/full ]; then
    for args in "--help" "--version" "derivs tests/vectors/npsauv_derivatives.csv" \
                "--plant vessel --scenario scenarios/turning_circle.scn --json" \
                "--plant vessel --scenario scenarios/turning_circle.scn"; do
        # shellcheck disable=SC2086
        "$uuvsim" $args >/dev/full 2>"$tmp/err"
        status=$?
        if [ $status -eq 2 ] && grep -q 'standard output: write error' "$tmp/err"; then
            ok "stdout on a full device: exit 2 ($args)"
        else echo "exit $status" >>"$tmp/err"; ko "stdout on a full device: exit 2 ($args)"; fi
    done
    "$uuvsim" --plant vessel --scenario "$d/v.scn" --csv "$d/f.csv" >/dev/full 2>"$tmp/err"
    if [ $? -eq 2 ] && [ ! -e "$d/f.csv" ] && [ -z "$(ls "$d" | grep partial)" ]; then
        ok "stdout on a full device: the CSV of the run is not committed"
    else ko "stdout on a full device: the CSV of the run is not committed"; fi
fi

finish

#!/bin/sh
# The make targets' plumbing: make run installs what it needs as make test
# does, and make keeps the files it builds (no "rm ..." line after make
# test's result). Usage: test_make.sh
# Prints one line per check and "N passed, N failed".
set -u
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"

# make's database (-p) without running anything (-q: question mode).
make -pq -f Makefile run >"$tmp/db" 2>/dev/null
if [ "$(grep -cE '^\.SECONDARY:' "$tmp/db")" = 1 ] && grep -qE '^\.SECONDARY:[[:space:]]*$' "$tmp/db"; then
    ok "every built file is kept: .SECONDARY without prerequisites"
else
    ko "every built file is kept: .SECONDARY without prerequisites"
fi
if grep -qE '^run: run-deps' "$tmp/db" &&
   make -n --no-print-directory run-deps 2>/dev/null | grep -q 'ensure-deps.sh run'; then
    ok "make run first runs tools/ensure-deps.sh run"
else
    ko "make run first runs tools/ensure-deps.sh run"
fi

# ensure-deps on a machine without gnuplot, not as root: it prints the command and fails.
mkdir -p "$tmp/bin"
printf '#!/bin/sh\necho 1000\n' >"$tmp/bin/id"
chmod +x "$tmp/bin/id"
ln -s "$(command -v grep)" "$tmp/bin/grep"
if PATH="$tmp/bin" "$(command -v sh)" tools/ensure-deps.sh run >"$tmp/out" 2>&1; then
    ko "ensure-deps run, missing, not root: fails"
elif grep -q 'apt-get install -y --no-install-recommends gnuplot-nox' "$tmp/out" &&
     ! grep -q 'qemu\|clang' "$tmp/out"; then
    ok "ensure-deps run, missing, not root: prints the apt-get command for gnuplot only"
else
    ko "ensure-deps run, missing, not root: $(cat "$tmp/out")"
fi
if sh tools/ensure-deps.sh run >"$tmp/out" 2>&1 || ! command -v gnuplot >/dev/null; then
    ok "ensure-deps run with gnuplot installed: nothing to do"
else
    ko "ensure-deps run with gnuplot installed: $(cat "$tmp/out")"
fi

finish

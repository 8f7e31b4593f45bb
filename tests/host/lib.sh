# The host test scripts' counts and verdict lines, sourced by each of them
# (. "${0%/*}/lib.sh"): one line per check and, last, "N passed, N failed",
# the line tools/run-tests.sh reads.
#
#   ok NAME          a check that passed
#   ko NAME [WHY]    a check that failed: WHY on its line, or else the last
#                    lines of $tmp/err when the script has written one
#   finish           the final line; its status is 0 when no check failed,
#                    so a script that ends with it exits 1 on a failure
pass=0
fail=0
ok() { pass=$((pass + 1)); echo "  ok    $1"; }
ko() {
    fail=$((fail + 1))
    if [ $# -ge 2 ]; then
        echo "  FAIL  $1: $2"
    else
        echo "  FAIL  $1"
        if [ -n "${tmp:-}" ] && [ -s "$tmp/err" ]; then sed 's/^/        /' "$tmp/err" | tail -n 5; fi
    fi
}
finish() { echo "$pass passed, $fail failed"; [ "$fail" -eq 0 ]; }

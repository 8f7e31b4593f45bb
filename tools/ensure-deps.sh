#!/bin/sh
# Installs the tools `make test` needs when they are missing: the Arm
# cross compiler, QEMU for Arm, clang, the lint tools (cppcheck with
# its MISRA addon, which runs on python3; clang-tidy), three.js (libjs-three)
# and Chromium for uuvsim view and its browser test. As root on a Debian-like
# machine it installs them; otherwise it prints the command to run and fails.
#   ensure-deps.sh        what make test needs
#   ensure-deps.sh view   what make view needs (three.js)
#   ensure-deps.sh run    what make run needs (gnuplot, for the plots)
#   ensure-deps.sh coverage   what make coverage needs (lcov; gcov comes with gcc)
set -u

missing=""
need() { command -v "$1" >/dev/null 2>&1 || missing="$missing $2"; }
# The three.js that uuvsim view copies into its page (ports/linux/view.c).
need_three() { [ -e /usr/share/javascript/three/three.min.js ] || missing="$missing libjs-three"; }
if [ "${1:-}" = view ]; then
    need_three
elif [ "${1:-}" = run ]; then
    need gnuplot gnuplot-nox
elif [ "${1:-}" = coverage ]; then
    need gcov gcc
    need lcov lcov
else
    need_three
    need chromium chromium
    need arm-none-eabi-gcc gcc-arm-none-eabi
    need qemu-system-arm qemu-system-arm
    need clang clang
    need gnuplot gnuplot-nox
    need cppcheck cppcheck
    need clang-tidy clang-tidy
    need python3 python3
    # clang's sanitizer and libFuzzer runtimes (the fuzz replay links them).
    fuzzer_rt=$(clang -print-file-name=libclang_rt.fuzzer-x86_64.a 2>/dev/null)
    [ -e "$fuzzer_rt" ] || missing="$missing libclang-rt-14-dev"
fi

[ -z "$missing" ] && exit 0

cmd="apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing:$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null && $cmd >/dev/null || {
        echo "error: '$cmd' failed" >&2
        exit 1
    }
    exit 0
fi
echo "error: missing tools:$missing" >&2
echo "install them with:  sudo apt-get update && sudo $cmd" >&2
exit 1

#!/bin/sh
# The firmware decoder on crafted streams (ports/linux/fw_decode.c):
#   test_decode.sh UUVSIM-DECODE
# A run that stopped at the guard gives exit 3 and a message naming the
# decoder; the JSON summary stays valid JSON with a machine name and a
# scenario path full of quotes, backslashes, newlines and escape characters;
# a record holding a NaN and an instruction count file with a negative count
# are refused (exit 2), with nothing written, and so is a frame of the
# multi-party link inside a telemetry stream; overruns near 2^32 at every
# rate sum without wrapping. Prints "N passed, N failed".
set -u
decode=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"
version=$(sed -n 's/^#define TLM_VERSION \([0-9]*\)u.*/\1/p' src/telemetry.h)

# stream.py OUT STATE X0 [OVERRUNS]: START (vessel plant, machine name with specials), one
# record with u_mps = X0, END with the given state and OVERRUNS at each of the four rates.
cat >"$tmp/stream.py" <<'PY'
import struct, sys, zlib
out, state, x0, version = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
ovr = int(sys.argv[5]) if len(sys.argv) > 5 else 0
def frame(t, seq, payload):
    body = struct.pack('<BHH', t, len(payload), seq) + payload
    return b'\xa5\x5a' + body + struct.pack('<I', zlib.crc32(body) & 0xffffffff)
machine = b'a"b\\c\nd\x1be'
start = struct.pack('<BBBB5Id', version, 1, 0, 0, 100000000, 1, 1, 1, 1, 0.1) + \
    machine.ljust(24, b'\0')
rec = struct.pack('<I', 0) + struct.pack('<30d', *([0.0, x0] + [0.0] * 28)) + struct.pack('<II', 0, 0)
end = struct.pack('<BBH4Q5I2dI', state, 3 if state == 3 else 0, 0, 0, 0, 0, 1, ovr, ovr, ovr,
                  ovr, 0, 0.0, 0.0, 0)
open(out, 'wb').write(frame(1, 0, start) + frame(2, 1, rec) + frame(3, 2, end))
PY
python3 "$tmp/stream.py" "$tmp/g.bin" 3 1.0 "$version"
"$decode" "$tmp/g.bin" --json "$tmp/g.json" --scenario 'x"y\z
w' 2>"$tmp/err"
status=$?
if [ $status -eq 3 ] && grep -q '^uuvsim-decode: .*non-finite' "$tmp/err" &&
   python3 -c 'import json,sys; d = json.load(open(sys.argv[1]));
assert d["machine"] == "a\"b\\c\nd\x1be" and d["state"] == "non-finite"' "$tmp/g.json"; then
    ok "a guard stop: exit 3, the decoder's name, valid JSON with escaped strings"
else echo "exit $status" >>"$tmp/err"; ko "a guard stop: exit 3, valid JSON with escaped strings"; fi

python3 "$tmp/stream.py" "$tmp/n.bin" 1 nan "$version"
"$decode" "$tmp/n.bin" --csv "$tmp/n.csv" 2>"$tmp/err"
status=$?
if [ $status -eq 2 ] && grep -q '^uuvsim-decode: .*NaN or an infinite' "$tmp/err" &&
   [ ! -e "$tmp/n.csv" ] && [ -z "$(ls "$tmp" | grep partial)" ]; then
    ok "a record holding a NaN: refused (exit 2), nothing written"
else echo "exit $status" >>"$tmp/err"; ko "a record holding a NaN: refused"; fi

python3 "$tmp/stream.py" "$tmp/o.bin" 2 1.0 "$version" 4294967295
"$decode" "$tmp/o.bin" --json "$tmp/o.json" 2>"$tmp/err"
if python3 -c 'import json,sys; d = json.load(open(sys.argv[1]));
assert d["overruns"] == 4 * 4294967295, d["overruns"]' "$tmp/o.json" 2>>"$tmp/err"; then
    ok "overruns of 2^32 - 1 at each rate: summed to 17179869180, not wrapped"
else ko "overruns of 2^32 - 1 at each rate: summed without wrapping"; fi

printf 'stat fast count -5 min 1 max 2 sum 3\n' >"$tmp/i.txt"
"$decode" "$tmp/g.bin" --insn "$tmp/i.txt" --json "$tmp/i.json" 2>"$tmp/err"
status=$?
if [ $status -eq 2 ] && grep -q '^uuvsim-decode: .*a negative count' "$tmp/err" &&
   [ ! -e "$tmp/i.json" ]; then
    ok "a negative instruction count: refused (exit 2), not wrapped"
else echo "exit $status" >>"$tmp/err"; ko "a negative instruction count: refused"; fi

# A frame of the multi-party link (LINK_DOWN, well formed) inside a telemetry stream.
python3 - "$tmp/g.bin" "$tmp/l.bin" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], 'rb').read()
n = 7 + struct.unpack('<H', data[3:5])[0] + 4  # the START frame
body = struct.pack('<BHH', 5, 52, 1) + bytes(52)
open(sys.argv[2], 'wb').write(data[:n] + b'\xa5\x5a' + body + struct.pack('<I', zlib.crc32(body)))
PY
"$decode" "$tmp/l.bin" --csv "$tmp/l.csv" 2>"$tmp/err"
status=$?
if [ $status -eq 2 ] && grep -q '^uuvsim-decode: .*frame 1: a frame of the multi-party link' "$tmp/err" &&
   [ ! -e "$tmp/l.csv" ]; then
    ok "a multi-party link frame in a telemetry stream: refused (exit 2), nothing written"
else echo "exit $status" >>"$tmp/err"; ko "a multi-party link frame in a telemetry stream: refused"; fi

"$decode" "$tmp/g.bin" --json "$tmp/g.bin" 2>"$tmp/err"
if [ $? -eq 2 ] && grep -q '^uuvsim-decode: --json .* are the same file' "$tmp/err"; then
    ok "an output equal to the input: refused by the decoder, in its name"
else ko "an output equal to the input: refused by the decoder"; fi

finish

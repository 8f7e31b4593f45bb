#!/bin/sh
# Checks that the code of the 2 us tick was compiled with the flags its
# instruction budget depends on, from the image itself:
#
#   sh tools/fw-flags.sh IMAGE.elf IMAGE.map "FLAG..."
#
# Follows the calls from SysTick_Handler through the disassembly (direct
# calls and branches to other functions, and the two pointer calls: the
# handler's to fw_fast, the fast step's to drive_fast_tick or the port's
# kernel), finds the object file each
# function comes from in the linker map and that object's compiler flags
# in its debug information (DW_AT_producer), and fails when one of them
# lacks a FLAG. So a renamed or new file on the tick's path that misses the
# Makefile's FW_FAST_C list stops the build instead of costing its
# instructions silently. Assembly (the kernel) and libgcc carry no C
# flags and are skipped. Prints the functions checked; exit status 1 on a
# missing flag, 2 on bad input.
set -u
elf=$1; map=$2; flags=$3
OBJDUMP=${ARM_OBJDUMP:-arm-none-eabi-objdump}
READELF=${ARM_READELF:-arm-none-eabi-readelf}
[ -f "$elf" ] && [ -f "$map" ] || { echo "fw-flags: $elf or $map missing" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Functions by address (static functions of the same name in two files
# stay apart): "ADDRESS NAME" of each, and call edges "CALLER CALLEE" by
# address from bl/b/b.w to the start of another function.
"$OBJDUMP" -d --no-show-raw-insn "$elf" | awk '
    /^[0-9a-f]+ <[^>]+>:$/ { f = $1 + 0; a = $1; n = $2; gsub(/[<>:]/, "", n)
        sub(/^0+/, "", a); print "F", a, n; cur = a; next }
    /\t(bl|b|b\.w|b\.n)\t[0-9a-f]+ <[^>+]+>/ {
        t = $0; sub(/^[^\t]*\t[^\t]*\t/, "", t); sub(/ .*/, "", t); sub(/^0+/, "", t)
        if (t != cur) print "E", cur, t
    }' >"$tmp/dis"
awk '$1 == "F" { print $2, $3 }' "$tmp/dis" >"$tmp/funcs"
awk '$1 == "E" { print $2, $3 }' "$tmp/dis" >"$tmp/edges"
addr() { awk -v n="$1" '$2 == n { print $1 }' "$tmp/funcs"; }
# The pointer calls: the HAL's tick handler to the port's (fw_fast), the
# fast step (drive_fast_step, through d->fast_now) to the C or the kernel.
for a in $(addr SysTick_Handler); do for b in $(addr fw_fast); do echo "$a $b"; done; done \
    >>"$tmp/edges"
for a in $(addr fw_fast) $(addr exec_fast_tick) $(addr exec_fast_tick_event) \
    $(addr drive_fast_step); do
    for b in $(addr drive_fast_tick) $(addr drive_fast_kernel_v7m); do echo "$a $b"; done
done >>"$tmp/edges"

# Functions reachable from the SysTick handler.
addr SysTick_Handler >"$tmp/reach"
[ -s "$tmp/reach" ] || { echo "fw-flags: $elf: no SysTick_Handler" >&2; exit 2; }
while :; do
    awk 'NR == FNR { r[$1] = 1; next } ($1 in r) && !($2 in r) { print $2; r[$2] = 1 }' \
        "$tmp/reach" "$tmp/edges" | sort -u >"$tmp/new"
    [ -s "$tmp/new" ] || break
    cat "$tmp/new" >>"$tmp/reach"
done

# Object file of each input section by its address: the map's ".text.NAME"
# lines (the address and object may follow on the next line).
awk '/^ \.text\./ { if (NF >= 4) { print $2, $4; pend = 0 } else pend = 1; next }
     pend && NF >= 3 && $1 ~ /^0x/ { print $1, $3; pend = 0; next }
     { pend = 0 }' "$map" |
    awk '{ a = $1; sub(/^0x0*/, "", a); print a, $2 }' >"$tmp/objs"

# Compiler flags of each C source: DW_AT_name and DW_AT_producer of each unit.
"$READELF" --debug-dump=info "$elf" 2>/dev/null | awk '
    /DW_TAG_compile_unit/ { prod = ""; name = ""; cu = 1; next }
    cu && /DW_AT_producer/ { sub(/.*\): /, ""); prod = $0 }
    cu && /DW_AT_name/ { sub(/.*\): /, ""); name = $0 }
    cu && prod != "" && name != "" { print name "\t" prod; cu = 0 }' >"$tmp/producers"

bad=0
checked=0
while read -r at; do
    fn=$(awk -v a="$at" '$1 == a { print $2; exit }' "$tmp/funcs")
    obj=$(awk -v a="$at" '$1 == a { print $2; exit }' "$tmp/objs")
    case $obj in
        */obj/*.o) src=${obj#*/obj/}; src=${src%.o} ;;
        *) continue ;; # libgcc, or a symbol without a section of its own
    esac
    prod=$(awk -F '\t' -v s="$src.c" '$1 == s { print $2; exit }' "$tmp/producers")
    [ -n "$prod" ] || continue # assembly: no C flags
    checked=$((checked + 1))
    for flag in $flags; do
        case " $prod " in
            *" $flag "*) ;;
            *) echo "fw-flags: $fn (in $src.c) is on the fast tick's path but is compiled" \
                    "without $flag: add the file to FW_FAST_C in the Makefile" >&2
               bad=1 ;;
        esac
    done
done <"$tmp/reach"
if [ "$checked" -eq 0 ]; then
    echo "fw-flags: $elf: no C function found on the fast tick's path" >&2
    exit 2
fi
echo "fw-flags: $checked C functions on the fast tick's path, each with: $flags"
exit $bad

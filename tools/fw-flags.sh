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

# Call edges "caller callee" from the disassembly: bl/b/b.w to <name>.
"$OBJDUMP" -d --no-show-raw-insn "$elf" | awk '
    /^[0-9a-f]+ <[^>]+>:$/ { f = $2; gsub(/[<>:]/, "", f); next }
    /\t(bl|b|b\.w|b\.n)\t[0-9a-f]+ <[^>+]+>/ {
        t = $0; sub(/.*</, "", t); sub(/>.*/, "", t)
        if (t != f) print f, t
    }' >"$tmp/edges"
# The pointer calls: the HAL's tick handler to the port's (fw_fast), the
# fast step (drive_fast_step, through d->fast_now) to the C or the kernel.
echo "SysTick_Handler fw_fast" >>"$tmp/edges"
echo "exec_fast_tick drive_fast_tick" >>"$tmp/edges"
echo "exec_fast_tick drive_fast_kernel_v7m" >>"$tmp/edges"

# Functions reachable from the SysTick handler.
echo SysTick_Handler >"$tmp/reach"
while :; do
    awk 'NR == FNR { r[$1] = 1; next } ($1 in r) && !($2 in r) { print $2; r[$2] = 1 }' \
        "$tmp/reach" "$tmp/edges" | sort -u >"$tmp/new"
    [ -s "$tmp/new" ] || break
    cat "$tmp/new" >>"$tmp/reach"
done

# Object file of each function: the map's ".text.NAME" input section (the
# address and object may follow on the next line).
awk '/^ \.text\./ { name = $1; sub(/^\.text\./, "", name)
        if (NF >= 4) { print name, $4; name = "" } ; next }
     name != "" && NF >= 3 { print name, $3; name = "" }' "$map" >"$tmp/objs"

# Compiler flags of each C source: DW_AT_name and DW_AT_producer of each unit.
"$READELF" --debug-dump=info "$elf" 2>/dev/null | awk '
    /DW_TAG_compile_unit/ { prod = ""; name = ""; cu = 1; next }
    cu && /DW_AT_producer/ { sub(/.*\): /, ""); prod = $0 }
    cu && /DW_AT_name/ { sub(/.*\): /, ""); name = $0 }
    cu && prod != "" && name != "" { print name "\t" prod; cu = 0 }' >"$tmp/producers"

bad=0
checked=0
while read -r fn; do
    obj=$(awk -v f="$fn" '$1 == f { print $2; exit }' "$tmp/objs")
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

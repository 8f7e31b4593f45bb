#!/bin/sh
# Prints the arguments of tools/qemu_insn_plugin.c for a firmware image:
# where each measured piece of code begins and where it returns, from the
# image's symbols and disassembly.
#
#   sh tools/fw-regions.sh IMAGE.elf
#
# Regions: fast (SysTick_Handler), medium (PendSV_Handler: the motor
# task), control (Irq_Handler: the controller task), background
# (fw_background_step), and, inside them, drive_fast (the port's kernel
# drive_fast_kernel_v7m where the image has one, with the C's
# drive_fast_tick beside it as drive_fast_c; else drive_fast_tick) and
# controller (the controller's step), and any function named in the
# environment variable FW_PROFILE (space-separated). A region is
# usable when every return of the function is an unconditional return
# instruction and no branch leaves it (a tail call would end it without a
# return); the tick handlers and the background step are written so, and
# a model's function that is not is left out with a message on stderr.
# Exit status 1 when one of the three main regions is unusable.
set -u
elf=$1
NM=${ARM_NM:-arm-none-eabi-nm}
OBJDUMP=${ARM_OBJDUMP:-arm-none-eabi-objdump}

# "ADDRESS SIZE" (hex) of a function symbol, or nothing.
sym() {
    "$NM" -S --defined-only "$elf" | awk -v n="$1" '$4 == n && ($3 == "T" || $3 == "t") {
        print $1, $2; exit }'
}

# The return addresses of a function, "0x1a2/0x1f0"; fails when it cannot be measured.
exits() {
    s=$(sym "$1")
    [ -n "$s" ] || { echo "fw-regions: $1: not in $elf" >&2; return 1; }
    start=$(( 0x${s% *} & ~1 ))
    stop=$(( start + 0x${s#* } ))
    "$OBJDUMP" -d --no-show-raw-insn --start-address=$start --stop-address=$stop "$elf" |
    awk -v lo="$start" -v hi="$stop" -v name="$1" '
    function hex(s,   i, v, c) {
        v = 0; s = tolower(s)
        for (i = 1; i <= length(s); i++) {
            c = index("0123456789abcdef", substr(s, i, 1)) - 1
            if (c < 0) break
            v = v * 16 + c
        }
        return v
    }
    BEGIN { conds = "^(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)$"; bad = ""; out = "" }
    /^ +[0-9a-f]+:\t/ {
        split($0, part, "\t")
        a = part[1]; gsub(/[ :]/, "", a); addr = hex(a)
        mn = part[2]; ops = part[3]
        sub(/\.[nw]$/, "", mn)
        ret = (mn == "bx" && ops ~ /^lr/) || (mn == "pop" && ops ~ /pc}/) ||
              (mn == "ldmia" && ops ~ /^sp!.*pc}/) || (mn == "ldr" && ops ~ /^pc, \[sp\]/)
        if (ret) { out = out (out == "" ? "" : "/") sprintf("0x%x", addr); next }
        base = mn
        if (sub(/^(bx|pop|ldmia|ldr)/, "", base) && base ~ conds && ops ~ /(^lr|pc)/) {
            bad = bad " conditional return at " sprintf("0x%x", addr)
        } else if (mn ~ /^b/ && (substr(mn, 2) == "" || substr(mn, 2) ~ conds)) {
            t = hex(ops)
            if (t < lo || t >= hi) bad = bad " branch out at " sprintf("0x%x", addr)
        } else if (mn == "bx") {
            bad = bad " jump through a register at " sprintf("0x%x", addr)
        }
    }
    END {
        if (bad != "" || out == "") {
            printf "fw-regions: %s cannot be measured:%s%s\n", name, bad,
                   out == "" ? " no return found" : "" > "/dev/stderr"
            exit 1
        }
        print out
    }'
}

entry() { s=$(sym "$1"); printf '0x%x' $(( 0x${s% *} & ~1 )); }

region() { # NAME KIND FUNCTION [required]
    if x=$(exits "$3"); then
        printf 'region=%s:%s:%s:%s\n' "$1" "$2" "$(entry "$3")" "$x"
    elif [ "${4:-}" = required ]; then
        status=1
    fi
}

status=0
control=drive_control_step_q
[ -n "$(sym $control)" ] || control=drive_control_step_f32
region fast isr SysTick_Handler required
region medium isr PendSV_Handler required
region background call fw_background_step required
region control isr Irq_Handler required
# The drive's fast step: the port's kernel where the image has one (the
# sub-step modulator's step by its frame plan), else the C (drive_fast_tick,
# every modulator); beside the kernel, the C's own count (the steps the
# kernel hands to it) as drive_fast_c.
if [ -n "$(sym drive_fast_kernel_v7m)" ]; then
    region drive_fast call drive_fast_kernel_v7m
    region drive_fast_c call drive_fast_tick
else
    region drive_fast call drive_fast_tick
fi
region controller call "$control"
# More functions to measure, by name (a profile of a task): FW_PROFILE="f g".
for f in ${FW_PROFILE:-}; do
    region "$f" call "$f"
done
exit $status

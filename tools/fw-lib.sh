# Shell functions shared by tools/qemu-bench.sh, tools/qemu-sim-test.sh,
# tools/qemu-run.sh and tools/qemu-party.sh (sourced, not run): a run's
# argument checks, an image's footprint, its worst-case stack, values from
# a run's summary.json, and runs at decreasing -icount shifts.
# Needs: FW_DECODE, FW_PLUGIN, FW_STACK (the host tools) in the environment
# (the argument checks need none).

ARM_SIZE=${ARM_SIZE:-arm-none-eabi-size}

# fw_run_args NAME SCENARIO DURATION IMAGE SHIFT: checks a QEMU run's
# arguments (a message starting with NAME and exit 2 when one is wrong)
# and sets fw_limit, QEMU's time limit [s]: a run's wall time grows with
# its simulated time (some 10 to 25 s per simulated second here, whatever
# the shift), so it allows ample room; QEMU_TIMEOUT overrides it.
fw_run_args() {
    case "$2$3" in
        *,* | *' '* | *'	'*)
            echo "$1: the scenario path and duration may not hold commas or spaces" \
                 "(QEMU's option syntax)" >&2
            exit 2 ;;
    esac
    [ -f "$2" ] || { echo "$1: $2: no such file" >&2; exit 2; }
    [ -f "$4" ] || { echo "$1: $4: no such image (make firmware)" >&2; exit 2; }
    case "$5" in
        [0-9] | 10) ;;
        *) echo "$1: SHIFT must be 0..10, got '$5'" >&2; exit 2 ;;
    esac
    fw_sim_s=${3:-$(awk '$1 == "duration" { print $2; exit }' "$2")}
    fw_limit=${QEMU_TIMEOUT:-$(awk -v d="${fw_sim_s:-1}" 'BEGIN { printf "%d", 120 + 60 * d }')}
}
ARM_OBJDUMP=${ARM_OBJDUMP:-arm-none-eabi-objdump}

# Bytes each exception entry may push: 8 words, or 26 with the FPU's
# context, plus 4 of alignment.
fw_frame_bytes() { # MACHINE
    case "$1" in
        mps2-an385 | lm3s6965evb) echo 36 ;;
        *) echo 108 ;;
    esac
}

# fw_flash (code, constants, .data's load image), fw_ram (.data, .bss,
# stack) and fw_stack_reserved, in bytes.
fw_sizes() { # IMAGE
    eval "$("$ARM_SIZE" -A "$1" | awk '
        $1 == ".text" || $1 == ".ARM.exidx" { flash += $2 }
        $1 == ".data" { flash += $2; ram += $2 }
        $1 == ".bss" { ram += $2 }
        $1 == ".stack" { ram += $2; stack = $2 }
        END { printf "fw_flash=%d fw_ram=%d fw_stack_reserved=%d\n", flash, ram, stack }')"
}

# fw_stack_worst: the static worst case (thread, PendSV, SysTick and a
# fault report nested, with their exception frames); the chains go to
# $2/stack.txt. Returns 1 when it is unknown.
fw_stack_static() { # IMAGE OUTDIR MACHINE
    objdir=$(dirname "$1")/obj
    # The fast step's pointer call: the port's kernel where the image has one.
    kernel=drive_fast_tick
    if "$ARM_OBJDUMP" -t "$1" | grep -q ' drive_fast_kernel_v7m$'; then
        kernel=drive_fast_kernel_v7m
    fi
    # The functions that make that call: the ones of the inline chain the
    # compiler kept out of line (-Os keeps drive_fast_step(), -O2 inlines it).
    calls=""
    for f in fw_fast exec_fast_tick exec_fast_tick_event drive_fast_step; do
        if "$ARM_OBJDUMP" -t "$1" | grep -q " $f\$"; then
            calls="$calls --call $f=$kernel"
        fi
    done
    # shellcheck disable=SC2046,SC2086 # one .su file per object; calls is a list of words
    "$ARM_OBJDUMP" -d --no-show-raw-insn "$1" |
        "$FW_STACK" --frame "$(fw_frame_bytes "$3")" --call SysTick_Handler=fw_fast $calls \
            --call PendSV_Handler=fw_medium Reset_Handler PendSV_Handler SysTick_Handler \
            HardFault_Handler -- $(find "$objdir" -name '*.su' | sort) >"$2/stack.txt"
    rc=$?
    fw_stack_worst=$(awk '$2 == "worst" { print $3 }' "$2/stack.txt")
    fw_stack_worst=${fw_stack_worst:-0}
    return $rc
}

# A value from summary.json: fw_json FILE KEY gives a scalar member,
# fw_json FILE KEY FIELD a field of an object member ("null" when absent).
fw_json() {
    if [ $# -eq 2 ]; then
        sed -n "s/^ *\"$2\": \"*\([^\",]*\)\"*,*\$/\1/p" "$1" | head -n 1
    else
        v=$(sed -n "s/.*\"$2\": {[^}]*\"$3\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1)
        echo "${v:-null}"
    fi
}

# Runs at SHIFT, then at each smaller shift until a run has no overrun.
# Sets fw_overruns_first (at SHIFT), fw_stopped_first (the simulated time
# it reached), fw_pass_shift (empty when none passed), fw_pass_dir, and
# fw_last_status (of the last run). Each run goes to OUTBASE/shiftN.
fw_run_until_pass() { # MACHINE IMAGE SCENARIO DURATION OUTBASE SHIFT
    fw_pass_shift=""
    fw_pass_dir=""
    fw_overruns_first=""
    fw_stopped_first=""
    s=$6
    while [ "$s" -ge 0 ]; do
        dir=$5/shift$s
        sh "$(dirname "$0")/qemu-run.sh" "$1" "$2" "$3" "$4" "$dir" "$s" "$FW_DECODE" \
            "$FW_PLUGIN" >"$5.shift$s.log" 2>&1
        fw_last_status=$?
        if [ ! -f "$dir/summary.json" ]; then
            return 1
        fi
        o=$(fw_json "$dir/summary.json" overruns)
        if [ -z "$fw_overruns_first" ]; then
            fw_overruns_first=$o
            fw_stopped_first=$(fw_json "$dir/summary.json" sim_time_s)
        fi
        if [ "$o" = 0 ] && [ $fw_last_status -eq 0 ]; then
            fw_pass_shift=$s
            fw_pass_dir=$dir
            return 0
        fi
        s=$((s - 1))
    done
    return 0
}

# uuvsim: one GNU Makefile, no generator.
#
#   make               host programs, fixed and float builds (build/linux-*)
#   make firmware      Cortex-M images for every machine and build (build/cortexm-*)
#   make test          installs missing tools, builds everything, runs every test
#   make check-tables  exhaustive error of the sine and triangle tables
#   make host-benches  the host micro-benchmarks and the controller's closed loop (build/tools)
#   make run           the main job (see README.md)
#   make view          out/mission.html, the 3-D view of make run's mission
#
# The numeric build and the port are chosen here, by -D options and include
# paths; src/ never tests for a platform.

.SUFFIXES:
MAKEFLAGS += --no-builtin-rules
.DEFAULT_GOAL := all

BUILD ?= build
# Every build uses all the cores unless the command line gives -j (make
# alone builds both desk simulators in under half a minute on two cores).
ifeq ($(filter -j% j%,$(MAKEFLAGS)),)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 2)
endif
CC ?= gcc
ifeq ($(origin CC),default)
CC := gcc
endif
CLANG ?= clang
ARM_CC ?= arm-none-eabi-gcc
ARM_SIZE ?= arm-none-eabi-size

# ---- Flags shared by every compiler and port ------------------------------

WARN := -Wall -Wextra -Wpedantic -Wconversion -Wdouble-promotion -Wshadow -Werror
COMMON := -std=c99 $(WARN) -ffp-contract=off -MMD -MP
INC := -Isrc -Itests/harness -I$(BUILD)/gen

comma := ,
NUM_fixed := 1
NUM_float := 2

# ---- Sources --------------------------------------------------------------

SRC_C := $(sort $(shell find src -name "*.c"))
SRC_H := $(sort $(shell find src -name "*.h"))
TEST_C := tests/harness/ut.c tests/harness/runner.c $(sort $(wildcard tests/unit/test_*.c))
SUITES := $(patsubst tests/unit/test_%.c,%,$(sort $(wildcard tests/unit/test_*.c)))
LINUX_PORT_C := $(sort $(wildcard ports/linux/hal_*.c))
UUVSIM_C := ports/linux/uuvsim.c ports/linux/cli.c ports/linux/csv_out.c ports/linux/derivs.c \
            ports/linux/view.c ports/linux/live.c ports/linux/out_file.c ports/linux/paramset.c ports/linux/sweep.c \
            ports/linux/party_host.c ports/linux/leap.c ports/linux/batch.c ports/linux/batch_lanes.c
CORTEXM_PORT_C := ports/cortexm/startup.c ports/cortexm/hal_cortexm.c \
                  ports/cortexm/semihost.c ports/cortexm/libc_min.c

# The list of suites, rewritten only when it changes.
$(BUILD)/gen/suites.inc: FORCE
	@mkdir -p $(@D)
	@printf '%s\n' $(foreach s,$(SUITES),'UT_SUITE($(s))') > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@
	@rm -f $@.tmp

# The page of uuvsim view (ports/linux/mission.html) as C strings, one per
# line: backslashes, quotes and '?' (no trigraphs) escaped.
$(BUILD)/gen/mission_html.inc: ports/linux/mission.html
	@mkdir -p $(@D)
	sed -e 's/[\\"?]/\\&/g' -e 's/^/"/' -e 's/$$/\\n",/' $< > $@.tmp
	mv $@.tmp $@

.PHONY: FORCE
FORCE:

# Nothing the build makes is a throw-away intermediate: make keeps every file
# (no "rm ..." after a run, and the next make finds them in place).
.SECONDARY:

# ---- Host variants --------------------------------------------------------
# $(call host_variant,NAME,COMPILER,NUMERIC,EXTRA_CFLAGS,EXTRA_LDFLAGS)

define host_variant
$(1)_DIR := $(BUILD)/$(1)
$(1)_CFLAGS := $(COMMON) $(4) -DUUV_NUMERIC=$(NUM_$(3)) -D_POSIX_C_SOURCE=200809L $(INC) \
    -Iports/linux $(HOST_SQRT) $(HOST_DIV) $(NATIVE_INT)
$(1)_SRC_O := $$(patsubst %.c,$$($(1)_DIR)/obj/%.o,$(SRC_C) $(LINUX_PORT_C))
$(1)_TEST_O := $$(patsubst %.c,$$($(1)_DIR)/obj/%.o,$(TEST_C))
$(1)_UUVSIM_O := $$(patsubst %.c,$$($(1)_DIR)/obj/%.o,$(UUVSIM_C))
$(1)_BENCH_O := $$($(1)_DIR)/obj/ports/linux/bench.o $$($(1)_DIR)/obj/ports/linux/leap.o \
    $$($(1)_DIR)/obj/ports/linux/batch_lanes.o
$(1)_PROP_O := $$($(1)_DIR)/obj/tests/host/property.o
$(1)_FAIL_O := $$(filter-out %/test_harness.o,$$($(1)_TEST_O)) $$($(1)_DIR)/obj-mustfail/test_harness.o

# src/ is compiled freestanding on the host too, which proves it needs no libc.
$$($(1)_DIR)/obj/src/%.o: XFLAGS := -ffreestanding
$$($(1)_DIR)/obj/src/drive_fast_run.o: XFLAGS := -ffreestanding $$(if $$(findstring gcc,$(2)),$(DESK_RUN_GCC_FLAGS))
$$($(1)_DIR)/obj/ports/linux/batch_lanes.o: XFLAGS := $(BATCH_LANES_FLAGS) $$(if $$(findstring gcc,$(2)),-Wno-psabi)
$$($(1)_DIR)/obj/ports/linux/leap.o: XFLAGS := $(LEAP_ARCH)

# The variant's compiler flags (the desk's vector flags among them) and the
# lists of files that take the fast and the size flags, rewritten only when
# they change: every object depends on them, so that a changed HOST_OPT or
# LEAP_ARCH rebuilds the variant.
$$($(1)_DIR)/cflags: FORCE
	@mkdir -p $$(@D)
	@printf '%s\n' '$$(subst ','\'',$(2) $$($(1)_CFLAGS) $(DESK_RUN_GCC_FLAGS) $(BATCH_LANES_FLAGS) $(LEAP_ARCH))' > $$@.tmp
	@cmp -s $$@.tmp $$@ || mv $$@.tmp $$@
	@rm -f $$@.tmp

$$($(1)_DIR)/obj/%.o: %.c $$($(1)_DIR)/cflags | $(BUILD)/gen/suites.inc
	@mkdir -p $$(@D)
	$(2) $$($(1)_CFLAGS) $$(XFLAGS) -c $$< -o $$@

$$($(1)_DIR)/obj-mustfail/test_harness.o: tests/unit/test_harness.c $$($(1)_DIR)/cflags
	@mkdir -p $$(@D)
	$(2) $$($(1)_CFLAGS) -DUT_PROVE_FAILURE -c $$< -o $$@

$$($(1)_DIR)/obj/tests/harness/runner.o: $(BUILD)/gen/suites.inc
$$($(1)_DIR)/obj/ports/linux/view.o: $(BUILD)/gen/mission_html.inc

$$($(1)_DIR)/unit_tests: $$($(1)_SRC_O) $$($(1)_TEST_O)
	$(2) $(5) -o $$@ $$^ -lm

$$($(1)_DIR)/unit_tests_mustfail: $$($(1)_SRC_O) $$($(1)_FAIL_O)
	$(2) $(5) -o $$@ $$^ -lm

$$($(1)_DIR)/uuvsim: $$($(1)_SRC_O) $$($(1)_UUVSIM_O)
	$(2) $(5) -o $$@ $$^ -lm

$$($(1)_DIR)/bench: $$($(1)_SRC_O) $$($(1)_BENCH_O)
	$(2) $(5) -o $$@ $$^ -lm

$$($(1)_DIR)/property: $$($(1)_SRC_O) $$($(1)_PROP_O)
	$(2) $(5) -o $$@ $$^ -lm

# uuvsim batch's lane step against the desk's runs of steps (tests/host/test_batch_lanes.c).
$$($(1)_DIR)/test_batch_lanes: $$($(1)_SRC_O) $$($(1)_DIR)/obj/ports/linux/batch_lanes.o \
        $$($(1)_DIR)/obj/tests/host/test_batch_lanes.o
	$(2) $(5) -o $$@ $$^ -lm

# The leaps' two AVX forms against each other (tests/host/test_leap_forms.c).
$$($(1)_DIR)/test_leap_forms: $$($(1)_SRC_O) $$($(1)_DIR)/obj/ports/linux/leap.o \
        $$($(1)_DIR)/obj/tests/host/test_leap_forms.o
	$(2) $(5) -o $$@ $$^ -lm

-include $$(wildcard $$($(1)_DIR)/obj/*/*.d $$($(1)_DIR)/obj/*/*/*.d $$($(1)_DIR)/obj/*/*/*/*.d $$($(1)_DIR)/obj/*/*/*/*/*.d $$($(1)_DIR)/obj/*/*/*/*/*/*.d)
HOST_VARIANTS += $(1)
endef

# -O3: the desk's runs of fast steps (src/drive_fast_run.c) keep the step's
# state in registers; the results are the same bits at any level. GCC's
# partial redundancy elimination raises that loop's register pressure
# beyond x86-64's 16 registers; without it the desk runs 8 % (float) to
# 24 % (fixed) faster (docs/multirate.md, "Speed").
HOST_OPT := -O3 -g
# x86-64 and AArch64 have IEEE square-root instructions in both precisions
# (src/uuv_config.h, src/math/sqrt.c): the same bits as the integer version.
HOST_SQRT := -DUUV_HW_SQRT_F64=1 -DUUV_HW_SQRT_F32=1 -fno-math-errno
# ... and a 64-bit integer divide (src/uuv_config.h, UUV_HW_DIV_64); the
# Cortex-M images divide a 64-bit value by a frame's count in three 32-bit
# divisions instead: the same quotients.
HOST_DIV := -DUUV_HW_DIV_64=1
# GCC and Clang shift negative values arithmetically and narrow modulo 2^N
# on every target (src/uuv_config.h, UUV_NATIVE_INT_OPS): the fixed-point
# helpers then use the compiler's own shift and narrowing, the same values
# in fewer instructions (19 % fewer in the fixed build's averaged mission).
NATIVE_INT := -DUUV_NATIVE_INT_OPS=1
DESK_RUN_GCC_FLAGS := -fno-tree-pre
# uuvsim batch's lanes (ports/linux/batch_lanes.c, host only) take the
# build machine's vector width; BATCH_LANES_FLAGS= builds the portable
# 4-lane form (any x86-64 or AArch64). The results are the same bits.
# (GCC's -Wno-psabi there: its note on how wide vectors pass between the
# file's own functions.)
BATCH_LANES_FLAGS ?= -march=native
# The desk's exact leaps (ports/linux/leap.c, --fast-path leap): their maps
# in the build host's AVX2 and FMA when it has them, and in 512-bit vectors
# where it has AVX-512 too (the same bits as AVX2's: test_leap_forms); an
# x86-64 without them, AArch64: the compiler's baseline vectors. Any width
# gives correct leaps; a build's results do not vary from run to run.
# LEAP_ARCH= builds the baseline.
LEAP_ARCH ?= $(shell grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo && \
    echo -mavx2 -mfma $$(grep -qw avx512f /proc/cpuinfo && echo -mavx512f))
SAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

$(eval $(call host_variant,linux-fixed,$(CC),fixed,$(HOST_OPT),))
$(eval $(call host_variant,linux-float,$(CC),float,$(HOST_OPT),))
$(eval $(call host_variant,linux-fixed-san,$(CC),fixed,$(SAN_FLAGS),-fsanitize=address$(comma)undefined))
$(eval $(call host_variant,linux-float-san,$(CC),float,$(SAN_FLAGS),-fsanitize=address$(comma)undefined))
$(eval $(call host_variant,linux-clang-fixed,$(CLANG),fixed,$(HOST_OPT),))
$(eval $(call host_variant,linux-clang-float,$(CLANG),float,$(HOST_OPT),))

# ---- Cortex-M variants ----------------------------------------------------
# $(call fw_variant,MACHINE,NUMERIC,CPU_FLAGS,HAS_FPU,BOARD_SOURCE,TEST_PARTS,OPT)
#
# Each variant builds, from the same objects, the unit-test image
# (unit_tests.elf, or unit_tests_partN.elf, one per group of suites, on a
# machine whose flash cannot hold them all: TEST_PARTS lists the groups)
# and the firmware simulation (uuvsim.elf, ports/cortexm/fw_main.c; see
# mk/firmware.mk for running and measuring it). The firmware's scenarios
# hold at most FW_SCENARIO_EVENTS commands, and its stack is FW_STACK_BYTES
# (the static worst case, checked by make qemu-bench and make test, must fit).
# OPT, when given, replaces -O2 for the whole variant: the Cortex-M3
# images are built for size (-Os), as their 64 KiB flash budget requires.

ARM_COMMON := $(COMMON) -O2 -g -ffreestanding -fno-tree-loop-distribute-patterns \
              -ffunction-sections -fdata-sections -fstack-usage
# The files of the 2 us tick are compiled without GCC's first instruction
# scheduling pass and without partial redundancy elimination: on Thumb-2
# the one hoists loads and the other keeps loaded coefficients alive across
# the filter's two phases; both raise register pressure, and the spills
# cost the fast tick about 20 and 17 instructions (docs/firmware.md).
# Without sibling calls, each measured function returns through its own
# exit (tools/fw-regions.sh measures from entry to return).
# The real-time fast step of the fixed Cortex-M4 and M7 images: 1 the
# Thumb-2 kernel (ports/cortexm/fast_kernel_v7m.S), 0 the C (to compare
# the two). The Cortex-M3 images keep the C: the kernel would not fit
# beside it in their 64 KiB, and they have no 2 us budget to meet. For the
# same 64 KiB they are lean images (UUV_LEAN_IMAGE=1, uuv_config.h): no
# event or averaged inverter, energy audit, FOH, DERIV or filter coupling,
# or manoeuvre metrics, none of which the firmware runs.
# (Objects are rebuilt when it changes: the variant's cflags file.)
FW_FAST_KERNEL ?= 1
# FW_FAST_C: every file with code on the fast tick's path (the handlers,
# the executive's tick, the drive's step and boundary, the models it
# calls); tools/fw-flags.sh checks each image after linking and fails the
# build when a function on that path comes from a file not in this list.
FW_FAST_C := src/drive_segment.c src/executive.c \
             ports/cortexm/hal_cortexm.c ports/cortexm/fw_main.c \
             $(wildcard src/models/drive/pwm/*.c src/models/drive/inverter/*.c) \
             src/models/drive/motor/induction_motor_q.c src/models/drive/motor/induction_motor_f32.c
FW_FAST_FLAGS := -fno-schedule-insns -fno-tree-pre -fno-optimize-sibling-calls
FW_SCENARIO_EVENTS ?= 64
FW_STACK_BYTES ?= 3328
# The firmware simulation's parameter set: with PARAMS=FILE (make firmware
# PARAMS=FILE) the desk program writes FILE's set as constant data
# ($(BUILD)/gen/fw_params.c, uuvsim params --emit-c) and every image links
# it instead of the default set. The shipped sets also build as
# uuvsim-NAME.elf beside each image (params/NAME.params), for make test.
FW_PARAMS_C := $(if $(PARAMS),$(BUILD)/gen/fw_params.c,ports/cortexm/fw_params_default.c)
FW_SIM_C := ports/cortexm/fw_main.c $(FW_PARAMS_C)
# Code off the tick paths (the background's vessel and battery, start-up,
# parsing, formatting) is compiled for size: the Cortex-M3's image must
# fit in 64 KiB. The results do not change (no reassociation, no
# contraction at any level).
FW_SIZE_C := $(wildcard src/models/vessel/*.c src/models/battery/*.c src/math/*_f64.c) \
             src/math/rem_pio2.c src/scenario.c src/util/fmt.c src/util/parse.c src/manoeuvre.c \
             src/autopilot.c src/scenario_player.c src/protection.c src/telemetry.c \
             ports/cortexm/startup.c ports/cortexm/semihost.c
TEST_PART1 := battery drive_control fixedpoint hal harness induction_motor math telemetry
TEST_PART2 := autopilot drive_segment exec_paths executive fast_kernel fmt inverter_avg manoeuvre \
              math_paths parse
TEST_PART3 := $(filter-out $(TEST_PART1) $(TEST_PART2),$(SUITES))

# The suite list of one part of the unit tests.
$(BUILD)/gen/part%/suites.inc: FORCE
	@mkdir -p $(@D)
	@printf '%s\n' $(foreach s,$(TEST_PART$*),'UT_SUITE($(s))') > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@
	@rm -f $@.tmp

define fw_variant
$(1)-$(2)_DIR := $(BUILD)/cortexm-$(1)-$(2)
# The fast tick's flags: all of them for the images with a 2 us budget;
# the Cortex-M3's (built for size, OPT) keep only the one their
# measurement needs (each measured function returns through its own exit).
$(1)-$(2)_FAST_FLAGS := $(if $(7),-fno-optimize-sibling-calls,$(FW_FAST_FLAGS))
$(1)-$(2)_KERNEL := $$(if $$(filter fixed,$(2)),$$(if $$(findstring cortex-m3,$(3)),0,$(FW_FAST_KERNEL)),0)
$(1)-$(2)_CFLAGS := $(ARM_COMMON) $(3) -DUUV_NUMERIC=$(NUM_$(2)) -DUUV_TARGET_HAS_FPU=$(4) \
    -DSCENARIO_MAX_EVENTS=$(FW_SCENARIO_EVENTS)u -DBOARD_NAME='"$(1)"' $(INC) -Iports/cortexm \
    -DFW_FAST_KERNEL=$$($(1)-$(2)_KERNEL) \
    $$(if $$(findstring cortex-m3,$(3)),-DUUV_LEAN_IMAGE=1)
$(1)-$(2)_LDFLAGS := $(3) -nostdlib -Wl,--gc-sections -Lldscripts -Tldscripts/$(1).ld
$(1)-$(2)_SRC_O := $$(patsubst %.c,$$($(1)-$(2)_DIR)/obj/%.o,$(SRC_C) $(CORTEXM_PORT_C) $(5)) \
    $$(if $$(filter 1,$$($(1)-$(2)_KERNEL)),$$($(1)-$(2)_DIR)/obj/ports/cortexm/fast_kernel_v7m.o)
$(1)-$(2)_TEST_O := $$(patsubst %.c,$$($(1)-$(2)_DIR)/obj/%.o,$(TEST_C))
$(1)-$(2)_SIM_O := $$(patsubst %.c,$$($(1)-$(2)_DIR)/obj/%.o,$(FW_SIM_C))
$(1)-$(2)_FAIL_O := $$(filter-out %/test_harness.o,$$($(1)-$(2)_TEST_O)) \
    $$($(1)-$(2)_DIR)/obj-mustfail/test_harness.o

# The variant's compiler flags and the lists of files that take the fast and
# the size flags, rewritten only when they change: every
# object depends on them, so that a flag given on the command line
# (FW_FAST_KERNEL=0, FW_SCENARIO_EVENTS=...) rebuilds what it changes.
$$($(1)-$(2)_DIR)/cflags: FORCE
	@mkdir -p $$(@D)
	@printf '%s\n' '$$(subst ','\'',$(ARM_CC) $$($(1)-$(2)_CFLAGS) $(7) $$($(1)-$(2)_FAST_FLAGS))' \
	    'fast: $(FW_FAST_C)' 'size: $(FW_SIZE_C)' > $$@.tmp
	@cmp -s $$@.tmp $$@ || mv $$@.tmp $$@
	@rm -f $$@.tmp

$$($(1)-$(2)_DIR)/obj/%.o: %.c $$($(1)-$(2)_DIR)/cflags | $(BUILD)/gen/suites.inc
	@mkdir -p $$(@D)
	$(ARM_CC) $$($(1)-$(2)_CFLAGS) $$(or $(7),$$(if $$(filter $$<,$(FW_SIZE_C)),-Os)) \
	    $$(if $$(filter $$<,$(FW_FAST_C)),$$($(1)-$(2)_FAST_FLAGS)) -c $$< -o $$@

# The fast kernel's offsets, from the C declarations (fast_kernel_offsets.c).
$$($(1)-$(2)_DIR)/gen/fast_kernel_offsets.h: ports/cortexm/fast_kernel_offsets.c $(SRC_H) \
        $$($(1)-$(2)_DIR)/cflags
	@mkdir -p $$(@D)
	$(ARM_CC) $$($(1)-$(2)_CFLAGS) -S -o $$@.s $$<
	sed -n 's/^@OFFSET \([A-Z0-9_]*\) \(-\{0,1\}[0-9]*\)$$$$/#define \1 \2/p' $$@.s > $$@.tmp
	mv $$@.tmp $$@

$$($(1)-$(2)_DIR)/obj/%.o: %.S $$($(1)-$(2)_DIR)/gen/fast_kernel_offsets.h
	@mkdir -p $$(@D)
	$(ARM_CC) $$($(1)-$(2)_CFLAGS) -I$$($(1)-$(2)_DIR)/gen -c $$< -o $$@

$$($(1)-$(2)_DIR)/obj-mustfail/test_harness.o: tests/unit/test_harness.c $$($(1)-$(2)_DIR)/cflags
	@mkdir -p $$(@D)
	$(ARM_CC) $$($(1)-$(2)_CFLAGS) $(7) -DUT_PROVE_FAILURE -c $$< -o $$@

$$($(1)-$(2)_DIR)/obj/tests/harness/runner.o: $(BUILD)/gen/suites.inc

$$($(1)-$(2)_DIR)/unit_tests.elf: $$($(1)-$(2)_SRC_O) $$($(1)-$(2)_TEST_O) ldscripts/$(1).ld
	$(ARM_CC) $$($(1)-$(2)_LDFLAGS) -Wl,-Map=$$(@:.elf=.map) -o $$@ \
	    $$(filter %.o,$$^) -lgcc

$$($(1)-$(2)_DIR)/unit_tests_mustfail.elf: $$($(1)-$(2)_SRC_O) $$($(1)-$(2)_FAIL_O) ldscripts/$(1).ld
	$(ARM_CC) $$($(1)-$(2)_LDFLAGS) -o $$@ $$(filter %.o,$$^) -lgcc

# One part of the unit tests: its own runner (the part's suite list comes first
# on the include path), the harness and the part's suites.
$$($(1)-$(2)_DIR)/obj-part%/runner.o: tests/harness/runner.c $(BUILD)/gen/part%/suites.inc \
        $$($(1)-$(2)_DIR)/cflags
	@mkdir -p $$(@D)
	$(ARM_CC) -I$(BUILD)/gen/part$$* $$($(1)-$(2)_CFLAGS) $(7) -c $$< -o $$@

$$($(1)-$(2)_DIR)/unit_tests_part%.elf: $$($(1)-$(2)_SRC_O) $$($(1)-$(2)_DIR)/obj-part%/runner.o \
        $$($(1)-$(2)_DIR)/obj/tests/harness/ut.o $$($(1)-$(2)_TEST_O) ldscripts/$(1).ld
	$(ARM_CC) $$($(1)-$(2)_LDFLAGS) -Wl,-Map=$$(@:.elf=.map) -o $$@ \
	    $$(filter-out %/tests/harness/runner.o $$($(1)-$(2)_DIR)/obj/tests/unit/%, \
	        $$(filter %.o,$$^)) \
	    $$(foreach s,$$(TEST_PART$$*),$$($(1)-$(2)_DIR)/obj/tests/unit/test_$$(s).o) -lgcc

$$($(1)-$(2)_DIR)/uuvsim.elf: $$($(1)-$(2)_SRC_O) $$($(1)-$(2)_SIM_O) ldscripts/$(1).ld \
        $(BUILD)/gen/fw_params.name
	$(ARM_CC) $$($(1)-$(2)_LDFLAGS) -Wl,--defsym=STACK_SIZE=$(FW_STACK_BYTES) \
	    -Wl,-Map=$$(@:.elf=.map) -o $$@ $$(filter %.o,$$^) -lgcc
	@sh tools/fw-flags.sh $$@ $$(@:.elf=.map) '$$($(1)-$(2)_FAST_FLAGS)' >/dev/null || \
	    { rm -f $$@; exit 1; }

# The image with a shipped set: params/NAME.params as uuvsim-NAME.elf.
$$($(1)-$(2)_DIR)/uuvsim-%.elf: $$($(1)-$(2)_SRC_O) $$($(1)-$(2)_DIR)/obj/ports/cortexm/fw_main.o \
        $$($(1)-$(2)_DIR)/obj/$(BUILD)/gen/params/%.o ldscripts/$(1).ld
	$(ARM_CC) $$($(1)-$(2)_LDFLAGS) -Wl,--defsym=STACK_SIZE=$(FW_STACK_BYTES) \
	    -Wl,-Map=$$(@:.elf=.map) -o $$@ $$(filter %.o,$$^) -lgcc
	@sh tools/fw-flags.sh $$@ $$(@:.elf=.map) '$$($(1)-$(2)_FAST_FLAGS)' >/dev/null || \
	    { rm -f $$@; exit 1; }

-include $$(wildcard $$($(1)-$(2)_DIR)/obj/*/*.d $$($(1)-$(2)_DIR)/obj/*/*/*.d \
    $$($(1)-$(2)_DIR)/obj/*/*/*/*.d $$($(1)-$(2)_DIR)/obj/*/*/*/*/*.d $$($(1)-$(2)_DIR)/obj/*/*/*/*/*/*.d $$($(1)-$(2)_DIR)/obj-part*/*.d)
FW_VARIANTS += $(1)-$(2)
FW_IMAGES += $$(if $(6),$$(foreach p,$(6),$$($(1)-$(2)_DIR)/unit_tests_part$$(p).elf), \
    $$($(1)-$(2)_DIR)/unit_tests.elf)
FW_SIMS += $$($(1)-$(2)_DIR)/uuvsim.elf
endef

# The square-root instructions each core has (src/uuv_config.h): VSQRT.F32
# on the M4F, VSQRT.F32 and .F64 on the M7 (FPv5-D16), none on the M3.
CPU_M3 := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
CPU_M4F := -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard \
           -DUUV_HW_SQRT_F32=1 -fno-math-errno
CPU_M7 := -mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard \
          -DUUV_HW_SQRT_F64=1 -DUUV_HW_SQRT_F32=1 -fno-math-errno

# NATIVE_INT on every image but the LM3S6965's, which keeps the portable
# forms that make lint and make prove analyse: both forms run the unit
# tests and the host/target comparison in every make test.

$(eval $(call fw_variant,mps2-an385,fixed,$(CPU_M3) $(NATIVE_INT),0,ports/cortexm/board_mps2.c,,-Os))
$(eval $(call fw_variant,mps2-an386,fixed,$(CPU_M4F) $(NATIVE_INT),1,ports/cortexm/board_mps2.c,))
$(eval $(call fw_variant,mps2-an386,float,$(CPU_M4F) $(NATIVE_INT),1,ports/cortexm/board_mps2.c,))
$(eval $(call fw_variant,mps2-an500,fixed,$(CPU_M7) $(NATIVE_INT),1,ports/cortexm/board_mps2.c,))
$(eval $(call fw_variant,mps2-an500,float,$(CPU_M7) $(NATIVE_INT),1,ports/cortexm/board_mps2.c,))
$(eval $(call fw_variant,netduinoplus2,fixed,$(CPU_M4F) $(NATIVE_INT),1,ports/cortexm/board_stm32f405.c,))
$(eval $(call fw_variant,netduinoplus2,float,$(CPU_M4F) $(NATIVE_INT),1,ports/cortexm/board_stm32f405.c,))
$(eval $(call fw_variant,lm3s6965evb,fixed,$(CPU_M3),0,ports/cortexm/board_lm3s6965.c,1 2 3,-Os))

# The set the firmware images link (see FW_PARAMS_C): written by the fixed
# desk program, which refuses a set the fixed build's bases cannot hold;
# rewritten only when it changes. fw_params.name records which set the
# images hold, so that changing PARAMS (or dropping it) relinks them.
$(BUILD)/gen/fw_params.c: $(PARAMS) $(BUILD)/linux-fixed/uuvsim FORCE
	@mkdir -p $(@D)
	$(BUILD)/linux-fixed/uuvsim params --params $(PARAMS) --emit-c $@.new
	@cmp -s $@.new $@ || mv $@.new $@
	@rm -f $@.new

.PRECIOUS: $(BUILD)/gen/params/%.c
$(BUILD)/gen/params/%.c: params/%.params $(BUILD)/linux-fixed/uuvsim
	@mkdir -p $(@D)
	$(BUILD)/linux-fixed/uuvsim params --params $< --emit-c $@

$(BUILD)/gen/fw_params.name: FORCE
	@mkdir -p $(@D)
	@printf '%s\n' '$(or $(PARAMS),default)' > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@
	@rm -f $@.tmp

# ---- Host tools (may use libc and libm) -----------------------------------

TOOL_CFLAGS := $(COMMON) -O2 -g -Isrc

$(BUILD)/tools/check_tables: tools/check_tables.c $(wildcard src/fixedpoint/*.c)
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $^ -lm

$(BUILD)/tools/gen_wavetables: tools/gen_wavetables.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -o $@ $^ -lm

$(BUILD)/tools/test_math_libm: tests/host/test_math_libm.c $(wildcard src/math/*.c)
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -fno-builtin -o $@ $^ -lm

$(BUILD)/tools/csvdiff: tools/csvdiff.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -D_POSIX_C_SOURCE=200809L -o $@ $^ -lm

HOST_TOOLS := $(BUILD)/tools/check_tables $(BUILD)/tools/gen_wavetables \
              $(BUILD)/tools/test_math_libm $(BUILD)/tools/csvdiff $(BUILD)/tools/test_csv_number

# The host benches and the controller's closed-loop check (tests/host/*.c
# with a main of their own: libc, libm and the POSIX clock), linked with the
# fixed build's objects of src/ (each holds every model twin). make test
# builds them all, so that they keep compiling, and runs sim_drive_control.
HOST_BENCHES := $(patsubst tests/host/%.c,$(BUILD)/tools/%, \
    $(sort $(wildcard tests/host/bench_*.c)) tests/host/sim_drive_control.c)

$(HOST_BENCHES): $(BUILD)/tools/%: tests/host/%.c $(linux-fixed_SRC_O)
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -fno-builtin -D_POSIX_C_SOURCE=200809L -o $@ $< $(linux-fixed_SRC_O) -lm

# The desk's number text against its printf definition (tests/host/test_csv_number.c).
$(BUILD)/tools/test_csv_number: tests/host/test_csv_number.c $(linux-fixed_SRC_O) \
        $(BUILD)/linux-fixed/obj/ports/linux/csv_out.o
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -D_POSIX_C_SOURCE=200809L -Iports/linux -o $@ $< \
	    $(linux-fixed_SRC_O) $(BUILD)/linux-fixed/obj/ports/linux/csv_out.o -lm

# ---- Top-level targets ----------------------------------------------------

.PHONY: all firmware host-all host-benches tools test test-run check-tables run view bench clean deps

# make: the desk simulator in both numeric builds (the unit tests and the
# rest come with make test).
all: $(foreach v,linux-fixed linux-float,$(BUILD)/$(v)/uuvsim)

host-all: $(foreach v,$(HOST_VARIANTS),$(BUILD)/$(v)/unit_tests $(BUILD)/$(v)/uuvsim) \
          $(BUILD)/linux-fixed/unit_tests_mustfail \
          $(foreach v,linux-fixed linux-float,$(BUILD)/$(v)/property $(BUILD)/$(v)/test_batch_lanes) \
          $(BUILD)/linux-float/test_leap_forms

firmware: $(FW_IMAGES) $(FW_SIMS) $(BUILD)/cortexm-mps2-an385-fixed/unit_tests_mustfail.elf

tools: $(HOST_TOOLS)

host-benches: $(HOST_BENCHES)

check-tables: $(BUILD)/tools/check_tables
	@$(BUILD)/tools/check_tables

deps:
	@sh tools/ensure-deps.sh

# Tools first (they may be missing on a fresh machine), then the rest in a
# second make, so that nothing is compiled before the compilers exist.
test: deps
	@$(MAKE) --no-print-directory test-run

test-run: host-all firmware tools host-benches
	@HOST_VARIANTS="$(HOST_VARIANTS)" FW_VARIANTS="$(FW_VARIANTS)" BUILD="$(BUILD)" \
	    sh tools/run-tests.sh

# The main job: the float desk simulator on the default mission, with its
# telemetry, a 2 us trace window, the JSON summary and the plots in out/.
RUN_ARGS := --scenario scenarios/default.scn --csv out/telemetry.csv \
            --trace out/trace.csv --trace-from 30 --trace-to 30.06

# gnuplot is installed first when it is missing (tools/ensure-deps.sh run: as root
# on a Debian-like machine; otherwise it prints the command and the run stops).
run: run-deps
	@$(MAKE) --no-print-directory run-sim

run-deps:
	@sh tools/ensure-deps.sh run

run-sim: $(BUILD)/linux-float/uuvsim
	@mkdir -p out
	$(BUILD)/linux-float/uuvsim $(RUN_ARGS) --summary out/summary.json
	gnuplot -e "dir='out'; scn='scenarios/default.scn'" tools/plots.gp
	@echo "plots: out/trajectory.png plan.png depth.png speed.png shaft.png currents.png dc_link.png battery.png"


# The 3-D view of make run's mission: out/mission.html (uuvsim view), one
# page that opens from file:// (three.js from libjs-three, installed here
# when missing, as make test installs its tools).
view: $(BUILD)/linux-float/uuvsim
	@sh tools/ensure-deps.sh view
	@test -f out/telemetry.csv || { echo "make view: no out/telemetry.csv: run make run first" >&2; exit 2; }
	$(BUILD)/linux-float/uuvsim view out

# The accuracy/speed-up study of both builds, in build/bench.json.
bench: $(BUILD)/linux-fixed/bench $(BUILD)/linux-float/bench
	@$(BUILD)/linux-fixed/bench scenarios/bench_2s.scn 2 scenarios/low_speed_2s.scn > $(BUILD)/bench-fixed.json
	@$(BUILD)/linux-float/bench scenarios/bench_2s.scn 2 scenarios/low_speed_2s.scn > $(BUILD)/bench-float.json
	@printf '{"fixed": %s, "float": %s}\n' "$$(cat $(BUILD)/bench-fixed.json)" \
	    "$$(cat $(BUILD)/bench-float.json)" > $(BUILD)/bench.json
	@echo "written $(BUILD)/bench.json"

# The firmware simulation: qemu-run, qemu-bench and its part of make test.
include mk/firmware.mk
include mk/hardening.mk
include mk/fmu.mk
include mk/party.mk

clean:
	rm -rf $(BUILD)

# The firmware simulation under QEMU (docs/firmware.md): the host tools it
# needs, make qemu-run, make qemu-bench, and its part of make test.
#
#   make qemu-run [MACHINE=mps2-an386] [NUM=fixed|float] [SCENARIO=scenarios/default.scn]
#                 [DURATION=s] [OUT=out/qemu-MACHINE-NUM] [SHIFT=3]
#       one run under -icount shift=SHIFT (2^SHIFT ns per instruction):
#       OUT/telemetry.csv (the desk simulator's --csv format), OUT/summary.json
#   make qemu-bench [BENCH_DURATION=2]
#       every machine and build: instruction counts per tick, overruns per
#       shift, footprints; $(BUILD)/qemu-bench.json and a table
#   make test ... [FW_TEST_SHIFT=3] [FW_TEST_DURATION=0.5]
#       the firmware checks of tools/qemu-sim-test.sh on every machine: CSV
#       and summary equal to the desk's, stack, the M3 images' flash and RAM,
#       real time at the shift each image claims and its fast-tick budget
#       (fw_claim there); every one fails make test when it is not met

FW_DECODE := $(BUILD)/tools/uuvsim-decode
FW_PLUGIN := $(BUILD)/tools/qemu_insn_plugin.so
FW_STACK := $(BUILD)/tools/fw_stack
FW_HOST_TOOLS := $(FW_DECODE) $(FW_PLUGIN) $(FW_STACK)
FW_TEST_SHIFT ?= 3
FW_TEST_DURATION ?= 0.5
BENCH_DURATION ?= 2

# The host decoder links the desk simulator's objects (the fixed build's:
# the stream says which build the target ran; the decoder needs neither).
$(FW_DECODE): $(linux-fixed_SRC_O) $(BUILD)/linux-fixed/obj/ports/linux/csv_out.o \
              $(BUILD)/linux-fixed/obj/ports/linux/out_file.o \
              $(BUILD)/linux-fixed/obj/ports/linux/fw_decode.o
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm

$(FW_PLUGIN): tools/qemu_insn_plugin.c
	@mkdir -p $(@D)
	$(CC) -std=c99 $(WARN) -O2 -shared -fPIC -o $@ $<

$(FW_STACK): tools/fw_stack.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -D_POSIX_C_SOURCE=200809L -o $@ $<

# ---- make qemu-run ------------------------------------------------------

QEMU_RUN_VARIANT = $(or $(MACHINE),mps2-an386)-$(or $(NUM),fixed)
QEMU_RUN_ELF = $(BUILD)/cortexm-$(QEMU_RUN_VARIANT)/uuvsim.elf

.PHONY: qemu-run qemu-bench
qemu-run: $(if $(filter $(QEMU_RUN_VARIANT),$(FW_VARIANTS)),$(QEMU_RUN_ELF)) $(FW_HOST_TOOLS)
	$(if $(filter $(QEMU_RUN_VARIANT),$(FW_VARIANTS)),,$(error no firmware for MACHINE-NUM \
	    '$(QEMU_RUN_VARIANT)'; one of: $(FW_VARIANTS)))
	@FW_DECODE=$(FW_DECODE) sh tools/qemu-run.sh $(or $(MACHINE),mps2-an386) $(QEMU_RUN_ELF) \
	    $(or $(SCENARIO),scenarios/default.scn) "$(DURATION)" \
	    $(or $(OUT),out/qemu-$(QEMU_RUN_VARIANT)) $(or $(SHIFT),3) $(FW_DECODE) $(FW_PLUGIN)

# ---- make qemu-bench ----------------------------------------------------

qemu-bench: $(FW_SIMS) $(FW_HOST_TOOLS) $(BUILD)/linux-fixed/uuvsim $(BUILD)/linux-float/uuvsim
	@FW_DECODE=$(FW_DECODE) FW_PLUGIN=$(FW_PLUGIN) FW_STACK=$(FW_STACK) \
	    sh tools/qemu-bench.sh $(BUILD) $(BENCH_DURATION) $(FW_VARIANTS)

# ---- make test ------------------------------------------------------------

test-run: $(FW_SIMS) $(FW_HOST_TOOLS) $(BUILD)/cortexm-mps2-an386-fixed/uuvsim-motor4kw.elf \
    $(BUILD)/cortexm-mps2-an386-float/uuvsim-motor4kw.elf
test-run: export FW_DECODE := $(FW_DECODE)
test-run: export FW_PLUGIN := $(FW_PLUGIN)
test-run: export FW_STACK := $(FW_STACK)
test-run: export FW_TEST_SHIFT := $(FW_TEST_SHIFT)
test-run: export FW_TEST_DURATION := $(FW_TEST_DURATION)

# The failure paths: a build of the firmware that can make a step overrun
# on request (FW_OVERRUN_TEST, see ports/cortexm/fw_main.c), on one machine.
FW_OVERRUN_VARIANT := mps2-an386-fixed
FW_OVERRUN_ELF := $(BUILD)/cortexm-$(FW_OVERRUN_VARIANT)/uuvsim_overrun.elf

$(BUILD)/cortexm-$(FW_OVERRUN_VARIANT)/obj-overrun/fw_main.o: ports/cortexm/fw_main.c
	@mkdir -p $(@D)
	$(ARM_CC) $($(FW_OVERRUN_VARIANT)_CFLAGS) -DFW_OVERRUN_TEST=1 -c $< -o $@

$(FW_OVERRUN_ELF): $($(FW_OVERRUN_VARIANT)_SRC_O) \
                   $(BUILD)/cortexm-$(FW_OVERRUN_VARIANT)/obj-overrun/fw_main.o \
                   $(filter-out %/fw_main.o,$($(FW_OVERRUN_VARIANT)_SIM_O))
	$(ARM_CC) $($(FW_OVERRUN_VARIANT)_LDFLAGS) -Wl,--defsym=STACK_SIZE=$(FW_STACK_BYTES) \
	    -o $@ $^ -lgcc

test-run: $(FW_OVERRUN_ELF)
-include $(wildcard $(BUILD)/cortexm-$(FW_OVERRUN_VARIANT)/obj-overrun/*.d)

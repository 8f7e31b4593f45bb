# The multi-party run (docs/cosimulation.md): the drive as firmware under
# QEMU, the slow segment (battery, vessel, scenario, telemetry) in a host
# process (uuvsim party), connected through the firmware's UART.
#
#   make qemu-party [MACHINE=mps2-an386] [NUM=fixed|float] [SCENARIO=scenarios/default.scn]
#                   [DURATION=s] [OUT=out/party-MACHINE-NUM] [SHIFT=2]
#       OUT/telemetry.csv (the desk's --csv, byte for byte), OUT/console.txt
#
# The drive's image, uuvsim_party.elf beside each variant's uuvsim.elf, is
# ports/cortexm/fw_main.c built with FW_PARTY=1 (and the fast path's
# flags, checked as in every image: tools/fw-flags.sh): the normal images
# hold none of the link's code.

# $(call party_image,MACHINE-NUM)
define party_image
$$($(1)_DIR)/obj-party/fw_main.o: ports/cortexm/fw_main.c $$($(1)_DIR)/cflags
	@mkdir -p $$(@D)
	$(ARM_CC) $$($(1)_CFLAGS) $$($(1)_FAST_FLAGS) -DFW_PARTY=1 -c $$< -o $$@

$$($(1)_DIR)/uuvsim_party.elf: $$($(1)_SRC_O) $$($(1)_DIR)/obj-party/fw_main.o \
        $$(filter-out %/fw_main.o,$$($(1)_SIM_O))
	$(ARM_CC) $$($(1)_LDFLAGS) -Wl,--defsym=STACK_SIZE=$(FW_STACK_BYTES) \
	    -Wl,-Map=$$(@:.elf=.map) -o $$@ $$(filter %.o,$$^) -lgcc
	@sh tools/fw-flags.sh $$@ $$(@:.elf=.map) '$$($(1)_FAST_FLAGS)' >/dev/null || { rm -f $$@; exit 1; }

-include $$(wildcard $$($(1)_DIR)/obj-party/*.d)
FW_PARTY_IMAGES += $$($(1)_DIR)/uuvsim_party.elf
endef

$(foreach v,$(FW_VARIANTS),$(eval $(call party_image,$(v))))

# make test's rows (tools/run-tests.sh, tests/host/test_party.sh): both builds on the M4.
test-run: $(BUILD)/cortexm-mps2-an386-fixed/uuvsim_party.elf \
          $(BUILD)/cortexm-mps2-an386-float/uuvsim_party.elf

QEMU_PARTY_MACHINE = $(or $(MACHINE),mps2-an386)
QEMU_PARTY_NUM = $(or $(NUM),fixed)
QEMU_PARTY_VARIANT = $(QEMU_PARTY_MACHINE)-$(QEMU_PARTY_NUM)
QEMU_PARTY_ELF = $(BUILD)/cortexm-$(QEMU_PARTY_VARIANT)/uuvsim_party.elf

.PHONY: qemu-party
qemu-party: $(if $(filter $(QEMU_PARTY_VARIANT),$(FW_VARIANTS)),$(QEMU_PARTY_ELF)) \
            $(BUILD)/linux-$(QEMU_PARTY_NUM)/uuvsim
	$(if $(filter $(QEMU_PARTY_VARIANT),$(FW_VARIANTS)),,$(error no firmware for MACHINE-NUM \
	    '$(QEMU_PARTY_VARIANT)'; one of: $(FW_VARIANTS)))
	@sh tools/qemu-party.sh $(QEMU_PARTY_MACHINE) $(QEMU_PARTY_ELF) \
	    $(BUILD)/linux-$(QEMU_PARTY_NUM)/uuvsim $(or $(SCENARIO),scenarios/default.scn) \
	    "$(DURATION)" $(or $(OUT),out/party-$(QEMU_PARTY_VARIANT)) $(or $(SHIFT),2)

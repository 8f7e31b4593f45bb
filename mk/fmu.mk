# The vehicle as an FMI 2.0 co-simulation FMU (ports/fmu, docs/cosimulation.md).
#
#   make fmu [NUM=fixed|float]
#       $(BUILD)/uuvsim.fmu: the FMU of one numeric build (fixed by default;
#       each build has its own, $(BUILD)/fmu-NUM/uuvsim.fmu): the model
#       description, binaries/linux64/uuvsim.so and sources/ (the C files, a
#       build description and a Makefile, to rebuild it for another platform)

FMU_C := ports/fmu/fmu.c ports/fmu/fmu_model.c ports/fmu/fmu_hal.c
FMU_H := ports/fmu/fmi2.h ports/fmu/fmu_model.h
FMU_NUM := $(or $(NUM),fixed)

# $(call fmu_variant,NUMERIC)
define fmu_variant
fmu-$(1)_DIR := $(BUILD)/fmu-$(1)
fmu-$(1)_CFLAGS := $(COMMON) $(HOST_OPT) -fPIC -fvisibility=hidden -DUUV_NUMERIC=$(NUM_$(1)) \
    -Isrc -Iports/fmu
fmu-$(1)_O := $$(patsubst %.c,$$(fmu-$(1)_DIR)/obj/%.o,$(SRC_C) $(FMU_C))

$$(fmu-$(1)_DIR)/obj/src/%.o: XFLAGS := -ffreestanding
$$(fmu-$(1)_DIR)/obj/src/drive_fast_run.o: XFLAGS := -ffreestanding $(DESK_RUN_GCC_FLAGS)

$$(fmu-$(1)_DIR)/cflags: FORCE
	@mkdir -p $$(@D)
	@printf '%s\n' '$(CC) $$(fmu-$(1)_CFLAGS) $(DESK_RUN_GCC_FLAGS)' > $$@.tmp
	@cmp -s $$@.tmp $$@ || mv $$@.tmp $$@
	@rm -f $$@.tmp

$$(fmu-$(1)_DIR)/obj/%.o: %.c $$(fmu-$(1)_DIR)/cflags
	@mkdir -p $$(@D)
	$(CC) $$(fmu-$(1)_CFLAGS) $$(XFLAGS) -c $$< -o $$@

# No undefined symbol: a master's dlopen() must resolve everything.
$$(fmu-$(1)_DIR)/uuvsim.so: $$(fmu-$(1)_O)
	$(CC) -shared -Wl,-z,defs -o $$@ $$^ -lm

$$(fmu-$(1)_DIR)/fmu-describe: $$(filter-out %/fmu.o,$$(fmu-$(1)_O)) \
                              $$(fmu-$(1)_DIR)/obj/ports/fmu/fmu_describe_main.o
	$(CC) -o $$@ $$^ -lm

$$(fmu-$(1)_DIR)/uuvsim.fmu: $$(fmu-$(1)_DIR)/uuvsim.so $$(fmu-$(1)_DIR)/fmu-describe \
                            $(SRC_H) $(FMU_H) ports/fmu/sources.mk
	@echo "FMU $$@"
	@rm -rf $$(@D)/stage $$@
	@mkdir -p $$(@D)/stage/binaries/linux64 $$(@D)/stage/sources
	@$$(@D)/fmu-describe model $(SRC_C) $(FMU_C) > $$(@D)/stage/modelDescription.xml
	@$$(@D)/fmu-describe build $(SRC_C) $(FMU_C) > $$(@D)/stage/sources/buildDescription.xml
	@cp $$(@D)/uuvsim.so $$(@D)/stage/binaries/linux64/uuvsim.so
	@tar -cf - $(SRC_C) $(SRC_H) $(FMU_C) $(FMU_H) | tar -xf - -C $$(@D)/stage/sources
	@sed -e 's|@UUV_NUMERIC@|$(NUM_$(1))|' -e 's|@SOURCES@|$(SRC_C) $(FMU_C)|' \
	    ports/fmu/sources.mk > $$(@D)/stage/sources/Makefile
	@cd $$(@D)/stage && zip -q -X -r ../uuvsim.fmu modelDescription.xml binaries sources

-include $$(wildcard $$(fmu-$(1)_DIR)/obj/*/*.d $$(fmu-$(1)_DIR)/obj/*/*/*.d \
    $$(fmu-$(1)_DIR)/obj/*/*/*/*.d $$(fmu-$(1)_DIR)/obj/*/*/*/*/*.d \
    $$(fmu-$(1)_DIR)/obj/*/*/*/*/*/*.d)
endef

$(eval $(call fmu_variant,fixed))
$(eval $(call fmu_variant,float))

FMU_FILES := $(BUILD)/fmu-fixed/uuvsim.fmu $(BUILD)/fmu-float/uuvsim.fmu

ifneq ($(filter fmu,$(MAKECMDGOALS)),)
ifeq ($(filter fixed float,$(FMU_NUM)),)
$(error NUM must be fixed or float, not '$(FMU_NUM)')
endif
endif

.PHONY: fmu
fmu: $(BUILD)/fmu-$(FMU_NUM)/uuvsim.fmu
	cp $< $(BUILD)/uuvsim.fmu
	@echo "written $(BUILD)/uuvsim.fmu ($(FMU_NUM) build)"

# The test master (tests/host/fmu_import.c): the scenario parser and the CSV
# number format from the desk's objects; the FMU itself through dlopen().
FMU_IMPORT := $(BUILD)/tools/fmu_import
$(FMU_IMPORT): tests/host/fmu_import.c $(linux-fixed_SRC_O) $(BUILD)/linux-fixed/obj/ports/linux/csv_out.o $(FMU_H)
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) -D_POSIX_C_SOURCE=200809L -Iports/fmu -Iports/linux -o $@ $< \
	    $(linux-fixed_SRC_O) $(BUILD)/linux-fixed/obj/ports/linux/csv_out.o -ldl -lm

test-run: $(FMU_FILES) $(FMU_IMPORT)

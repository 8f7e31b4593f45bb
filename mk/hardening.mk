# Hardening: static analysis, proof, fuzzing and coverage (docs/reliability.md).
#
#   make lint       cppcheck with the MISRA C:2012 addon over src/, then
#                   clang-tidy; fails on any finding that
#                   tools/misra-deviations.txt does not list as a deviation
#                   and on a row whose count is not the one measured
#   make prove      Frama-C Eva over src/fixedpoint: fails on any alarm
#   make fuzz       a short campaign of every libFuzzer harness (FUZZ_SECONDS each)
#   make fuzz-replay  every seed in tests/fuzz/corpus_*/ through its harness
#   make coverage   gcov/lcov branch coverage of the host unit tests, per folder
#                   (installs lcov when missing; fails when it gives no figure)
#   make san-sim    the 60 s desk simulation under ASan + UBSan, both builds
#   make soak       one hour of the soak mission per build with the energy
#                   audit (SOAK_SECONDS; make test runs 600 s of it)
#   make property-campaign  the property test (no non-finite output) over
#                   PROPERTY_CASES random cases of up to PROPERTY_SECONDS per
#                   build, and PROPERTY_CLI_CASES through uuvsim (make test:
#                   3000 of up to 20 s, and 100)

.PHONY: lint prove fuzz fuzz-build fuzz-replay coverage san-sim soak property-campaign

PROPERTY_CASES ?= 100000
PROPERTY_SECONDS ?= 120
PROPERTY_CLI_CASES ?= 2000
PROPERTY_SEED ?= 2
property-campaign: $(foreach v,fixed float,$(BUILD)/linux-$(v)/property $(BUILD)/linux-$(v)/uuvsim)
	@for v in fixed float; do log=$(BUILD)/property-$$v.log; \
	    $(BUILD)/linux-$$v/property $(PROPERTY_CASES) $(PROPERTY_SEED) $(PROPERTY_SECONDS) \
	        > $$log; s=$$?; tail -n 2 $$log; [ $$s -eq 0 ] || exit 1; \
	    sh tests/host/test_property.sh $(BUILD)/linux-$$v/uuvsim $(PROPERTY_CLI_CASES) \
	        $(PROPERTY_SEED) $(PROPERTY_SECONDS) > $$log; s=$$?; tail -n 2 $$log; \
	    [ $$s -eq 0 ] || exit 1; done

SOAK_SECONDS ?= 3600
soak: $(BUILD)/linux-fixed/uuvsim $(BUILD)/linux-float/uuvsim
	@for v in fixed float; do echo "soak, $$v build, $(SOAK_SECONDS) s:"; \
	    sh tests/host/test_soak.sh $(BUILD)/linux-$$v/uuvsim $(SOAK_SECONDS) || exit 1; done

FUZZ_HARNESSES := scenario cli decode
FUZZ_SECONDS ?= 20
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_CFLAGS := -std=c99 -Wall -Wextra -Wpedantic -Wconversion -Wdouble-promotion -Wshadow \
    -Werror -ffp-contract=off -O1 -g -fno-omit-frame-pointer \
    -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all \
    -DUUV_NUMERIC=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iports/linux -MMD -MP
FUZZ_LIB_C := $(SRC_C) $(LINUX_PORT_C) ports/linux/cli.c
FUZZ_LIB_O := $(patsubst %.c,$(FUZZ_DIR)/obj/%.o,$(FUZZ_LIB_C))

$(FUZZ_DIR)/obj/%.o: %.c
	@mkdir -p $(@D)
	$(CLANG) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/fuzz_%: $(FUZZ_DIR)/obj/tests/fuzz/fuzz_%.o $(FUZZ_LIB_O)
	$(CLANG) -fsanitize=fuzzer,address,undefined -o $@ $^ -lm

# The objects are kept after the link (the Makefile's .SECONDARY keeps every
# built file), so that a second make rebuilds nothing. A .SECONDARY with a
# list here would make that one apply to the list only.

-include $(wildcard $(FUZZ_DIR)/obj/*/*.d $(FUZZ_DIR)/obj/*/*/*.d $(FUZZ_DIR)/obj/*/*/*/*.d $(FUZZ_DIR)/obj/*/*/*/*/*.d $(FUZZ_DIR)/obj/*/*/*/*/*/*.d)

fuzz-build: $(foreach h,$(FUZZ_HARNESSES),$(FUZZ_DIR)/fuzz_$(h))

fuzz-replay: fuzz-build
	@BUILD="$(BUILD)" sh tools/fuzz.sh replay $(FUZZ_HARNESSES)

fuzz: fuzz-build
	@BUILD="$(BUILD)" sh tools/fuzz.sh campaign $(FUZZ_SECONDS) $(FUZZ_HARNESSES)

lint:
	@sh tools/lint.sh

prove:
	@sh tools/prove.sh

coverage:
	@sh tools/ensure-deps.sh coverage
	@BUILD="$(BUILD)" sh tools/coverage.sh

san-sim: $(BUILD)/linux-fixed-san/uuvsim $(BUILD)/linux-float-san/uuvsim
	@sh tests/host/test_san_sim.sh $(BUILD)/linux-fixed-san/uuvsim \
	    $(BUILD)/linux-float-san/uuvsim

# Coverage builds of the unit tests (gcc --coverage, -O0), both numeric
# builds; kept out of HOST_VARIANTS so that make test does not run them.
hardening_saved_variants := $(HOST_VARIANTS)
$(eval $(call host_variant,linux-cov-fixed,$(CC),fixed,-O0 -g --coverage,--coverage))
$(eval $(call host_variant,linux-cov-float,$(CC),float,-O0 -g --coverage,--coverage))
HOST_VARIANTS := $(hardening_saved_variants)

coverage: $(BUILD)/linux-cov-fixed/unit_tests $(BUILD)/linux-cov-float/unit_tests

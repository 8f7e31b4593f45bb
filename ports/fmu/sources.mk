# Builds the FMU's binary from its sources on another platform:
#   make [CC=...] [NUM=1|2] [SO=uuvsim.so]
# NUM is the numeric build (1 fixed, 2 float); the binary checks the GUID of
# modelDescription.xml, which names the build, so keep the FMU's own.
CC ?= cc
NUM ?= @UUV_NUMERIC@
SO ?= uuvsim.so
SOURCES := @SOURCES@
CFLAGS ?= -O2
$(SO): $(SOURCES)
	$(CC) -std=c99 $(CFLAGS) -ffp-contract=off -fPIC -fvisibility=hidden -shared \
	    -DUUV_NUMERIC=$(NUM) -Isrc -Iports/fmu -o $@ $(SOURCES) -lm

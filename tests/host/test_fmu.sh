#!/bin/sh
# The FMU as a master meets it (docs/cosimulation.md):
#   test_fmu.sh FMU UUVSIM FMU_IMPORT [SCENARIO]
# unzips the FMU, validates modelDescription.xml against the FMI 2.0 schema
# (tests/host/fmi2_model_description.xsd) with xmllint, checks the archive's
# layout and that the library writes nothing to stdout or stderr, runs the
# test master (fmu_import: the standard's rules, the run against the desk
# simulator's CSV of the same scenario, two instances, reset, FMU state,
# refused steps), then rebuilds the library from the FMU's sources/ with
# their Makefile and runs the first 20 s of the scenario through it.
# Prints "N passed, N failed" last.
set -u
fmu=$1; uuvsim=$2; importer=$3; scenario=${4:-tests/host/manual_mission.scn}
here=$(dirname "$0")
. "${0%/*}/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM

if unzip -q "$fmu" -d "$tmp/fmu"; then ok "unzip $fmu"; else ko "unzip $fmu"; fi
md="$tmp/fmu/modelDescription.xml"
if xmllint --noout --schema "$here/fmi2_model_description.xsd" "$md" 2>"$tmp/xmllint.log"; then
    ok "modelDescription.xml is valid against the FMI 2.0 schema (xmllint)"
else
    ko "modelDescription.xml against the schema: $(head -n 5 "$tmp/xmllint.log")"
fi
id=$(sed -n 's/.*modelIdentifier="\([^"]*\)".*/\1/p' "$md" | head -n 1)
so="$tmp/fmu/binaries/linux64/$id.so"
if [ -n "$id" ] && [ -f "$so" ]; then ok "binaries/linux64/$id.so"; else ko "no binaries/linux64/$id.so"; fi
missing=0
for f in $(sed -n 's/.*<File name="\([^"]*\)".*/\1/p' "$md"); do
    [ -f "$tmp/fmu/sources/$f" ] || missing=$((missing + 1))
done
if [ "$missing" -eq 0 ] && [ -f "$tmp/fmu/sources/buildDescription.xml" ] &&
   xmllint --noout "$tmp/fmu/sources/buildDescription.xml" 2>/dev/null; then
    ok "sources/: every file the description lists, and buildDescription.xml"
else
    ko "sources/: $missing listed files missing, or no well-formed buildDescription.xml"
fi
# Nothing on stdout or stderr: no stdio output function among the library's imports.
out=$(nm -D --undefined-only "$so" | grep -E ' U (printf|vprintf|puts|putchar|fputs|fputc|fwrite|fprintf|vfprintf|write|perror|__printf_chk|__fprintf_chk)(@|$)')
if [ -z "$out" ]; then ok "the library imports no output function"; else ko "the library imports: $out"; fi
exports=$(nm -D --defined-only "$so" | awk '{print $3}' | grep -v '^fmi2' | grep -v '^_' | tr '\n' ' ')
if [ -z "$exports" ]; then ok "the library exports the fmi2 functions only"; else ko "it also exports: $exports"; fi

# The desk's CSV of the same scenario, then the master.
"$uuvsim" --scenario "$scenario" --csv "$tmp/desk.csv" --quiet || ko "the desk run"
"$importer" "$tmp/fmu" "$scenario" "$tmp/desk.csv" > "$tmp/import.log" 2>&1
status=$?
cat "$tmp/import.log"
counts=$(tail -n 1 "$tmp/import.log")
p=$(echo "$counts" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\1/p')
f=$(echo "$counts" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\2/p')
if [ -n "$p" ] && [ "$status" -eq 0 ]; then
    pass=$((pass + p)); fail=$((fail + f))
else
    ko "fmu_import exited $status: $counts"
fi

# The autopilots' inputs: the heading and depth steps of scenarios/autopilot_step.scn (60 s),
# the master setting heading_cmd_rad, depth_cmd_m and autopilot at the scenario's times.
ap_scn=scenarios/autopilot_step.scn
"$uuvsim" --scenario "$ap_scn" --duration 60 --csv "$tmp/desk_ap.csv" --quiet || ko "the desk run of $ap_scn"
"$importer" "$tmp/fmu" "$ap_scn" "$tmp/desk_ap.csv" > "$tmp/import_ap.log" 2>&1
status=$?
if [ "$status" -eq 0 ]; then
    ok "the autopilot inputs ($ap_scn, 60 s): $(grep 'steps of one slow frame' "$tmp/import_ap.log" | sed 's/^ok  : //')"
else
    ko "the autopilot inputs ($ap_scn): $(grep FAIL "$tmp/import_ap.log" | head -n 3)"
fi
if awk -F, 'NR > 1 && $1 + 0 >= 59.9 { found = 1; if ($10 + 0 < 5 || $13 + 0 < 0.5) exit 1 } END { exit !found }' "$tmp/desk_ap.csv"; then
    ok "the desk run of $ap_scn reaches the new depth and heading (z > 5 m, psi > 0.5 rad at 60 s)"
else
    ko "the desk run of $ap_scn: the autopilots did not act (the comparison above would prove nothing)"
fi

# Rebuilt from its sources (as on another platform): the first 20 s again.
if make -s -C "$tmp/fmu/sources" CFLAGS=-O1 SO="$tmp/rebuilt.so" > "$tmp/make.log" 2>&1; then
    ok "the library rebuilds from sources/ (make -C sources)"
    mkdir -p "$tmp/fmu2/binaries/linux64"
    cp "$md" "$tmp/fmu2/"
    cp "$tmp/rebuilt.so" "$tmp/fmu2/binaries/linux64/$id.so"
    head -n 201 "$tmp/desk.csv" > "$tmp/desk20.csv"
    if "$importer" "$tmp/fmu2" "$scenario" "$tmp/desk20.csv" > "$tmp/import2.log" 2>&1; then
        ok "the rebuilt library: $(grep 'steps of one slow frame' "$tmp/import2.log" | sed 's/^ok  : //')"
    else
        ko "the rebuilt library: $(grep FAIL "$tmp/import2.log" | head -n 3)"
    fi
else
    ko "make -C sources: $(tail -n 5 "$tmp/make.log")"
fi
finish

#!/bin/sh
# Property test (docs/reliability.md): no output of uuvsim is ever NaN or
# infinite, over random in-range inputs.
#   test_property.sh UUVSIM CASES SEED [MAX_DURATION_S]
# Each case is a random scenario: every vessel state (the full plant's motor
# starts at rest: no n_rpm there) drawn inside the range
# the scenario reader accepts (src/scenario.c), two random sets of commands
# (fins, shaft speed, buoyancy) at t = 0 and half-way, a random propulsion
# law, mostly the vessel plant (up to MAX_DURATION_S, default 20 s) and one
# case in 16 with the full plant (0.3 s). The run must exit 0; under `mss`,
# whose reference law accelerates a vehicle moving astern without bound
# (docs/vessel.md), it may instead stop at the guard with exit 3 and its
# message. Its CSV, its JSON summary and its stdout must hold no nan or inf.
# Prints the counts per law and plant, then "N passed, N failed".
set -u
uuvsim=$1
cases=$2
seed=$3
maxdur=${4:-20}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One line per case: law plant duration, then the scenario's lines joined by '|'.
awk -v n="$cases" -v seed="$seed" -v maxdur="$maxdur" 'BEGIN {
    srand(seed);
    split("u_mps v_mps w_mps p_radps q_radps r_radps x_m y_m z_m phi_rad theta_rad psi_rad " \
          "delta_r_rad delta_s_rad delta_bp_rad delta_bs_rad n_rpm", name, " ");
    split("5 3 3 5 3 3 1000 1000 100 3.14159 1.3962 6.2831 0.7853 0.7853 0.7853 0.7853 1500", lim, " ");
    for (k = 0; k < n; k++) {
        law = (rand() < 0.5) ? "paper" : "mss";
        full = (k % 16 == 15);
        dur = full ? 0.3 : 0.1 * int(1 + rand() * 10 * maxdur);
        init = "init";
        for (i = 1; i <= 17; i++) {
            v = (2 * rand() - 1) * lim[i];
            if (i == 9) v = (v < 0) ? -v : v;
            if (i < 17 || !full) init = init sprintf(" %s=%.6g", name[i], v);
        }
        s = sprintf("duration %.1f|%s", dur, init);
        for (j = 0; j < 2; j++) {
            s = s sprintf("|at %.1f rudder=%.4f stern=%.4f bow_port=%.4f bow_stbd=%.4f " \
                          "n_rpm=%.1f buoyancy=%.1f", j * int(dur * 5) / 10,
                          (2 * rand() - 1) * 0.785, (2 * rand() - 1) * 0.785,
                          (2 * rand() - 1) * 0.785, (2 * rand() - 1) * 0.785,
                          (2 * rand() - 1) * 1500, (2 * rand() - 1) * 5340);
        }
        printf "%s %s %s\n", law, full ? "full" : "vessel", s;
    }
}' >"$tmp/cases"

. "${0%/*}/lib.sh"
guard=0
k=0
while read -r law plant text; do
    k=$((k + 1))
    printf '%s\n' "$text" | tr '|' '\n' >"$tmp/c.scn"
    "$uuvsim" --scenario "$tmp/c.scn" --plant "$plant" --propulsion "$law" \
        --csv "$tmp/c.csv" --summary "$tmp/c.json" >"$tmp/out" 2>"$tmp/err"
    status=$?
    verdict=ok
    if [ $status -eq 3 ] && [ "$law" = mss ] && grep -q 'the run stopped: non-finite or diverged' "$tmp/err"; then
        guard=$((guard + 1))
    elif [ $status -ne 0 ]; then
        verdict="exit $status"
    fi
    if grep -Eiq '(^|[^a-z_])-?(nan|inf)' "$tmp/c.csv" "$tmp/c.json" "$tmp/out"; then
        verdict="a non-finite value in an output"
    fi
    if [ "$verdict" = ok ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        if [ $fail -le 5 ]; then
            echo "  FAIL  case $k ($law, $plant): $verdict"
            sed 's/^/        /' "$tmp/c.scn" "$tmp/err" | head -n 12
        fi
    fi
    rm -f "$tmp/c.csv" "$tmp/c.json"
done <"$tmp/cases"
echo "  $cases random cases (seed $seed): $pass without a non-finite output, $guard of them" \
     "stopped by the guard (mss astern)"
finish

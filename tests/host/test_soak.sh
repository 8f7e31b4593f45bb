#!/bin/sh
# Soak (docs/reliability.md): the soak mission (scenarios/soak.scn, a 300 s
# pattern repeated) for DURATION simulated seconds with the energy audit:
#   test_soak.sh UUVSIM DURATION
# Checks that the run completes with no NaN or Inf in the records, no
# saturation and no overrun; that the energy balance closes (battery energy
# at the terminals = filter losses + motor losses + shaft work within 0.6 %
# of the battery's energy: the residual is the multi-rate motor coupling's
# energy error, what the filter delivers to the motor's fast companion and
# the motor model does not absorb, 0.546 % after 600 s in both builds and
# 0.49 % to 0.55 % from 120 s to 3600 s; docs/reliability.md, "Soak"); and
# that there is no drift: the last pattern reproduces the first (means over
# the last 10 s of the 1200 rpm and the 800 rpm legs: shaft speed within
# 0.2 %, surge speed within 0.05 %, torque and current within 1 %; only the
# battery's charge may differ).
# Prints one line per check with the figures and "N passed, N failed".
set -u
uuvsim=$1
duration=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "${0%/*}/lib.sh"


# field NAME: a number from the summary
field() {
    tr -d '\n' <"$tmp/s.json" | sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p"
}

start=$(date +%s)
if ! "$uuvsim" --scenario scenarios/soak.scn --duration "$duration" --energy-audit --json \
        --quiet --csv "$tmp/r.csv" >"$tmp/s.json" 2>"$tmp/err"; then
    ko "soak run: exit status, $(cat "$tmp/err")"
    echo "$pass passed, $fail failed"
    exit 1
fi
wall=$(($(date +%s) - start))
ok "soak run of $duration s completed in $wall s of wall time"

if grep -qiE 'nan|inf' "$tmp/r.csv"; then ko "NaN or Inf in the records"; else ok "no NaN or Inf in $(($(wc -l <"$tmp/r.csv") - 1)) records"; fi
sat=$(field saturations)
ovr=$(field overruns)
if [ "$sat" = 0 ] && [ "$ovr" = 0 ]; then ok "0 saturations, 0 overruns"; else ko "saturations $sat, overruns $ovr"; fi

bal=$(tr -d '\n' <"$tmp/s.json" | sed -n 's/.*"energy_balance": {\([^}]*\)}.*/\1/p')
res=$(field residual_pct)
if awk -v r="$res" 'BEGIN { exit !(r != "" && r < 0.6 && r > -0.6) }'; then
    ok "energy balance closes: $bal"
else
    ko "energy balance residual $res % (limit 0.6 %): $bal"
fi

# Means over [t0 - 10, t0) of the columns, for the first and the last pattern.
means() { # T0 -> "n u te irms"
    awk -F, -v t0="$1" 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
        $1 + 0 >= t0 - 10.05 && $1 + 0 < t0 - 0.05 {
            n += $(h["n_rpm"]); u += $(h["u_mps"]); te += $(h["te_nm"]); ir += $(h["i_rms_a"]); k++ }
        END { if (k > 0) printf "%.9g %.9g %.9g %.9g\n", n / k, u / k, te / k, ir / k }' "$tmp/r.csv"
}
last=$(awk -v d="$duration" 'BEGIN { printf "%d", int((d + 0.5) / 300) - 1 }')
if [ "$last" -lt 1 ]; then
    ko "drift: the run is shorter than two 300 s patterns"
else
    for leg in 240 300; do
        a=$(means "$leg")
        b=$(means $((last * 300 + leg)))
        verdict=$(echo "$a $b" | awk '{
            dn = 100 * ($5 - $1) / $1; du = 100 * ($6 - $2) / $2
            dt = 100 * ($7 - $3) / $3; di = 100 * ($8 - $4) / $4
            good = (dn < 0.2 && dn > -0.2 && du < 0.05 && du > -0.05 && dt < 1 && dt > -1 &&
                    di < 1 && di > -1)
            printf "%s shaft %.4g rpm %+.3f %%, surge %.5g m/s %+.4f %%, torque %.4g N m %+.2f %%, current %.4g A %+.2f %%",
                good ? "ok" : "ko", $5, dn, $6, du, $7, dt, $8, di }')
        msg="no drift, pattern 1 to $((last + 1)), leg ending at ${leg} s:${verdict#??}"
        case $verdict in ok*) ok "$msg" ;; *) ko "$msg" ;; esac
    done
fi
finish

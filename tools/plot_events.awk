# The scenario's events for tools/plots.gp: reads the scenario (-v scn=FILE)
# and the telemetry CSV, and prints one line per timed command (and the
# zig-zag's start), comma-separated: time [s], East [m], North [m], depth [m] where the
# vehicle was at the first record at or after that time, and the command
# text in quotes.
#   awk -f tools/plot_events.awk -v scn=SCENARIO telemetry.csv
BEGIN {
    if (scn != "") {
        while ((getline line < scn) > 0) {
            sub(/#.*/, "", line)
            n = split(line, w, /[ \t]+/)
            first = (w[1] == "") ? 2 : 1
            if (w[first] == "at") {
                t[++k] = w[first + 1] + 0
                label = ""
                for (i = first + 2; i <= n; i++) {
                    if (w[i] != "") label = (label == "") ? w[i] : label " " w[i]
                }
                lab[k] = label
            } else if (w[first] == "zigzag") {
                start = 0
                for (i = first + 1; i <= n; i++) {
                    if (w[i] ~ /^start=/) start = substr(w[i], 7) + 0
                }
                t[++k] = start
                lab[k] = "zig-zag " w[first + 1] " " w[first + 2]
            }
        }
    }
}
NR == 1 {
    for (i = 1; i <= NF; i++) c[$i] = i
    next
}
{
    for (j = 1; j <= k; j++) {
        if (!(j in done) && $(c["t_s"]) >= t[j] - 1e-9) {
            done[j] = 1
            printf "%g,%s,%s,%s,\"%s\"\n", t[j], $(c["y_m"]), $(c["x_m"]), $(c["z_m"]), lab[j]
        }
    }
}

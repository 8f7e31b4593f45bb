# Plots of a desk-simulator run. Usage:
#   gnuplot -e "dir='out'; scn='scenarios/default.scn'" tools/plots.gp
# (from the repository's top; tools='DIR' when tools/plot_events.awk is elsewhere)
# reads dir/telemetry.csv (and dir/trace.csv when present) and writes PNGs
# into dir. With scn, the scenario's timed commands (and its zig-zag) are
# marked and labelled where the vehicle was when they took effect.
if (!exists("dir")) dir = 'out'
if (!exists("scn")) scn = ''
if (!exists("tools")) tools = 'tools'
set datafile separator ','
set terminal pngcairo size 1200,800 noenhanced font ',10'
set grid
set key top left
tel = dir.'/telemetry.csv'

# The events: "t east north depth label" per line, the label the command text
# (the first telemetry record at or after the command's time gives the place).
ev = dir.'/events.dat'
system(sprintf("awk -F, -f %s/plot_events.awk -v scn='%s' '%s' > '%s'", tools, scn, tel, ev))
have_ev = (system('test -s '.ev.' && echo 1') eq '1')
evn = have_ev ? int(system('wc -l < '.ev)) : 0
# The k-th event's key entry: its number, time and command.
evlab(k) = sprintf('%d: %s s  %s', k, system(sprintf("sed -n '%dp' '%s' | cut -d, -f1", k, ev)), \
                   system(sprintf("sed -n '%dp' '%s' | cut -d, -f5 | tr -d '\"'", k, ev)))

# ---- trajectory.png: the 3-D view, the plan view at equal scale, the depth profile
set output dir.'/trajectory.png'
stats tel using 'z_m' nooutput
zmax = (STATS_max > 1) ? STATS_max : 1
stats tel using 'y_m':'x_m' nooutput
east_lo = STATS_min_x; east_hi = STATS_max_x; north_lo = STATS_min_y; north_hi = STATS_max_y
# The plan's ranges: a straight run would give a sliver at equal scale, so the
# shorter side spans at least a fifth of the longer (and 10 m).
espan = east_hi - east_lo; nspan = north_hi - north_lo
big = (espan > nspan ? espan : nspan) > 10 ? (espan > nspan ? espan : nspan) : 10
plan_e = (espan < 0.2 * big) ? 0.1 * big : 0.55 * espan
plan_n = (nspan < 0.2 * big) ? 0.1 * big : 0.55 * nspan
plan_ranges = sprintf('set xrange [%g:%g]; set yrange [%g:%g]', \
    0.5 * (east_lo + east_hi) - plan_e, 0.5 * (east_lo + east_hi) + plan_e, \
    0.5 * (north_lo + north_hi) - plan_n, 0.5 * (north_lo + north_hi) + plan_n)
set multiplot layout 2,2 title 'Trajectory'
# 3-D: the floor at the deepest point with the track over ground on it.
set title '3-D path (East, North, depth)'
set xlabel 'East y [m]'
set ylabel 'North x [m]'
set zlabel 'depth z [m]' rotate
set view 60, 30
set zrange [zmax:0]
set xyplane at zmax
set ticslevel 0
# About four ticks per horizontal axis, so that their labels do not run together.
tstep(span) = (span <= 0) ? 1 : (m = 10**floor(log10(span / 4.0)), \
               (span / 4.0 / m < 2) ? 2 * m : (span / 4.0 / m < 5) ? 5 * m : 10 * m)
set xtics tstep(east_hi - east_lo)
set ytics tstep(north_hi - north_lo)
pad(span) = (span > 0) ? 0.05 * span : 1
set xrange [east_lo - pad(east_hi - east_lo):east_hi + pad(east_hi - east_lo)]
set yrange [north_lo - pad(north_hi - north_lo):north_hi + pad(north_hi - north_lo)]
set border 4095 lc rgb '#808080'
set key top right
splot tel using 'y_m':'x_m':(zmax) with lines lc rgb '#b0b0b0' lw 1 title 'track over ground', \
      tel using 'y_m':'x_m':'z_m' with lines lc rgb '#9400d3' lw 2 title 'path', \
      tel every ::0::0 using 'y_m':'x_m':'z_m' with points pt 7 ps 1.2 lc rgb '#009e73' title 'start'
set zrange [*:*]
set border 31 lc rgb 'black'
unset zlabel
set xtics autofreq
set ytics autofreq
set xrange [*:*]
set yrange [*:*]
# Plan: North up, East to the right, one metre the same length on both axes.
set title 'Plan view (equal scale)'
set xlabel 'East y [m]'
set ylabel 'North x [m]'
set size ratio -1
eval plan_ranges
set key bottom left box opaque
if (have_ev) {
    plot tel using 'y_m':'x_m' with lines lc rgb '#9400d3' lw 2 title 'track', \
         tel every ::0::0 using 'y_m':'x_m' with points pt 7 ps 1.5 lc rgb '#009e73' title 'start', \
         ev using 2:3 with points pt 9 ps 1.4 lc rgb '#d55e00' title 'commands (numbered)', \
         ev using 2:3:(sprintf('%d', $0 + 1)) with labels offset 0.8,0.8 font ',10' tc rgb '#d55e00' notitle
} else {
    plot tel using 'y_m':'x_m' with lines lc rgb '#9400d3' lw 2 title 'track', \
         tel every ::0::0 using 'y_m':'x_m' with points pt 7 ps 1.5 lc rgb '#009e73' title 'start'
}
set size noratio
set xrange [*:*]
set yrange [*:*]
# Depth profile against time, the events marked and labelled.
set title 'Depth profile'
set xlabel 't [s]'
set ylabel 'depth z [m]'
set yrange [*:*] reverse
set key top right box opaque font ',9'
if (have_ev) {
    plot tel using 't_s':'z_m' with lines lw 2 lc rgb '#0072b2' title 'depth', \
         ev using 1:4:(sprintf('%d', $0 + 1)) with labels offset 0.8,0.8 font ',10' tc rgb '#d55e00' notitle, \
         for [k=1:evn] ev every ::(k-1)::(k-1) using 1:4 with points pt 9 ps 1.4 lc rgb '#d55e00' title evlab(k)
} else {
    plot tel using 't_s':'z_m' with lines lw 2 lc rgb '#0072b2' title 'depth'
}
set yrange [*:*] noreverse
# Heading against time.
set title 'Heading'
set ylabel 'psi [deg] (unwrapped)'
set key top right box opaque font ',10'
if (have_ev) {
    plot tel using 't_s':(column('psi_rad') * 180 / pi) with lines lw 2 lc rgb '#009e73' title 'psi', \
         ev using 1:(0):(sprintf('%d', $0 + 1)) with labels font ',10' tc rgb '#d55e00' notitle, \
         ev using 1:(0) with impulses lc rgb '#d55e00' dt 3 notitle
} else {
    plot tel using 't_s':(column('psi_rad') * 180 / pi) with lines lw 2 lc rgb '#009e73' title 'psi'
}
unset multiplot
set key top left nobox

# ---- plan.png: the plan view alone, larger
set terminal pngcairo size 1100,650 noenhanced font ',10'
set output dir.'/plan.png'
set title 'Plan view, North against East (equal scale)'
set xlabel 'East y [m]'
set ylabel 'North x [m]'
set size ratio -1
eval plan_ranges
set key bottom left box opaque font ',9'
if (have_ev) {
    plot tel using 'y_m':'x_m' with lines lc rgb '#9400d3' lw 2 title 'track', \
         tel every ::0::0 using 'y_m':'x_m' with points pt 7 ps 1.5 lc rgb '#009e73' title 'start', \
         ev using 2:3:(sprintf('%d', $0 + 1)) with labels offset 0.8,0.8 font ',10' tc rgb '#d55e00' notitle, \
         for [k=1:evn] ev every ::(k-1)::(k-1) using 2:3 with points pt 9 ps 1.4 lc rgb '#d55e00' title evlab(k)
} else {
    plot tel using 'y_m':'x_m' with lines lc rgb '#9400d3' lw 2 title 'track', \
         tel every ::0::0 using 'y_m':'x_m' with points pt 7 ps 1.5 lc rgb '#009e73' title 'start'
}
set size noratio
set xrange [*:*]
set yrange [*:*]
set terminal pngcairo size 900,600 noenhanced font ',10'

set output dir.'/depth.png'
set title 'Depth'
set xlabel 't [s]'
set ylabel 'depth z [m]'
set yrange [*:*] reverse
set key top right box opaque font ',9'
if (have_ev) {
    plot tel using 't_s':'z_m' with lines lw 2 title 'z', \
         ev using 1:4:(sprintf('%d', $0 + 1)) with labels offset 0.8,0.8 font ',10' tc rgb '#d55e00' notitle, \
         for [k=1:evn] ev every ::(k-1)::(k-1) using 1:4 with points pt 9 ps 1.2 lc rgb '#d55e00' title evlab(k)
} else {
    plot tel using 't_s':'z_m' with lines lw 2 title 'z'
}
set yrange [*:*] noreverse

set output dir.'/speed.png'
set title 'Surge speed'
set xlabel 't [s]'
set ylabel 'u [m/s]'
plot tel using 't_s':'u_mps' with lines lw 2 title 'u'

# ---- shaft.png: the whole run, and the start-up zoomed, the command drawn on top
set terminal pngcairo size 1200,600 noenhanced font ',10'
set output dir.'/shaft.png'
set multiplot layout 1,2 title 'Shaft speed and its command'
set title 'Whole run'
set xlabel 't [s]'
set ylabel 'shaft speed [rpm]'
set key bottom right
plot tel using 't_s':'n_rpm' with lines lw 2 lc rgb '#0072b2' title 'shaft', \
     tel using 't_s':'n_cmd_rpm' with steps lw 2 dt 2 lc rgb '#d55e00' title 'command'
set title 'Start-up (first 3 s)'
set xrange [0:3]
plot tel using 't_s':'n_rpm' with linespoints lw 2 pt 7 ps 0.6 lc rgb '#0072b2' title 'shaft', \
     tel using 't_s':'n_cmd_rpm' with steps lw 2 dt 2 lc rgb '#d55e00' title 'command'
set xrange [*:*]
unset multiplot
set key top left
set terminal pngcairo size 900,600 noenhanced font ',10'

set output dir.'/dc_link.png'
set title 'DC-link voltage'
set xlabel 't [s]'
set ylabel 'v_dc [V]'
plot tel using 't_s':'v_dc_v' with lines lw 2 title 'v_dc'

set output dir.'/battery.png'
set title 'Battery'
set xlabel 't [s]'
set ylabel 'state of charge [-]'
set y2label 'current [A]'
set y2tics
plot tel using 't_s':'soc' with lines lw 2 title 'state of charge', \
     tel using 't_s':'i_batt_a' axes x1y2 with lines title 'current (discharge > 0)'
unset y2tics
unset y2label

# ---- currents.png: the phase currents and the phase-to-neutral voltage, one panel each
trace = dir.'/trace.csv'
if (system('test -f '.trace.' && echo 1') eq '1') {
    set terminal pngcairo size 900,800 noenhanced font ',10'
    set output dir.'/currents.png'
    set multiplot layout 2,1 title 'Motor phases (2 us trace)'
    set title 'Phase currents into the motor'
    set xlabel 't [s]'
    set ylabel 'current [A]'
    set key top right
    plot trace using 't_s':'i_a_a' with lines lw 2 title 'i_a', \
         trace using 't_s':'i_b_a' with lines lw 2 title 'i_b', \
         trace using 't_s':'i_c_a' with lines lw 2 title 'i_c'
    set title 'Inverter phase-to-neutral voltage, phase a'
    set ylabel 'v_an [V]'
    plot trace using 't_s':'v_an_v' with lines lc rgb '#555555' title 'v_an'
    unset multiplot
}

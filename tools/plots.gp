# Plots of a desk-simulator run. Usage:
#   gnuplot -e "dir='out'" tools/plots.gp
# reads dir/telemetry.csv (and dir/trace.csv when present) and writes PNGs
# into dir.
if (!exists("dir")) dir = 'out'
set datafile separator ','
set terminal pngcairo size 900,600 noenhanced font ',10'
set grid
set key top left
tel = dir.'/telemetry.csv'
col(n) = column(n)

set output dir.'/trajectory.png'
set title '3-D trajectory (East, North, depth)'
set xlabel 'East y [m]'
set ylabel 'North x [m]'
set zlabel 'depth z [m]' rotate
set view 60, 30
# The floor at the deepest point, with the path's shadow on it (the track
# over ground) and a mark where the run starts.
stats tel using 'z_m' nooutput
floor = (STATS_max > 0) ? STATS_max : 1
set zrange [floor:0]
set xyplane at floor
set border 4095 lc rgb '#808080'
splot tel using 'y_m':'x_m':(floor) with lines lc rgb '#b0b0b0' lw 1 title 'track over ground', \
      tel using 'y_m':'x_m':'z_m' with lines lc rgb '#9400d3' lw 2 title 'path', \
      tel every ::0::0 using 'y_m':'x_m':'z_m' with points pt 7 ps 1.2 lc rgb '#009e73' title 'start'
set zrange [*:*] noreverse
set border 31 lc rgb 'black'

set output dir.'/depth.png'
set title 'Depth'
set xlabel 't [s]'
set ylabel 'depth z [m]'
set yrange [*:*] reverse
plot tel using 't_s':'z_m' with lines lw 2 title 'z'
set yrange [*:*] noreverse

set output dir.'/speed.png'
set title 'Surge speed'
set ylabel 'u [m/s]'
plot tel using 't_s':'u_mps' with lines lw 2 title 'u'

set output dir.'/shaft.png'
set title 'Shaft speed and its command'
set ylabel '[rpm]'
plot tel using 't_s':'n_rpm' with lines lw 2 title 'shaft', \
     tel using 't_s':'n_cmd_rpm' with steps dt 2 title 'command'

set output dir.'/dc_link.png'
set title 'DC-link voltage'
set ylabel 'v_dc [V]'
plot tel using 't_s':'v_dc' with lines lw 2 title 'v_dc'

set output dir.'/battery.png'
set title 'Battery'
set ylabel 'state of charge [-]'
set y2label 'current [A]'
set y2tics
plot tel using 't_s':'soc' with lines lw 2 title 'state of charge', \
     tel using 't_s':'i_batt_a' axes x1y2 with lines title 'current (discharge > 0)'
unset y2tics
unset y2label

trace = dir.'/trace.csv'
if (system('test -f '.trace.' && echo 1') eq '1') {
    set output dir.'/currents.png'
    set title 'Motor phase currents and inverter voltage (2 us trace)'
    set xlabel 't [s]'
    set ylabel 'current [A]'
    set y2label 'v_an [V]'
    set y2tics
    plot trace using 't_s':'i_a' with lines lw 2 title 'i_a', \
         trace using 't_s':'i_b' with lines lw 2 title 'i_b', \
         trace using 't_s':'i_c' with lines lw 2 title 'i_c', \
         trace using 't_s':'v_an' axes x1y2 with lines lc rgb '#c0c0c0' title 'v_an'
}

# The LC filter study's figure (docs/studies.md) from a sweep's results:
#   gnuplot -e "results='out/lc/results.csv'; png='docs/img/study_lc.png'" tools/study_lc.gp
# Columns of results.csv (sweeps/lc_filter.sweep): 4 stage.l [H], 5 stage.c [F],
# 6 filter losses [Wh over the 3 s run], 9 the motor current's ripple [A rms].
if (!exists("results")) results = 'out/lc/results.csv'
if (!exists("png")) png = 'docs/img/study_lc.png'
set terminal pngcairo size 1000,420 font ",10"
set output png
set datafile separator ","
set key top right
set logscale x 2
set xlabel "filter inductance L [mH]"
set grid
cap(i) = (i == 1) ? 10e-6 : (i == 2) ? 22e-6 : 47e-6
# The runs of one capacitance, in the order of L.
rows(i) = sprintf("< awk -F, 'NR > 1 && $5 + 0 == %.3g' %s", cap(i), results)
set multiplot layout 1,2
set title "motor current ripple (rms about its mean over a carrier period)"
set ylabel "ripple [A rms]"
plot for [i = 1:3] rows(i) using ($4*1e3):9 with linespoints lw 2 \
     title sprintf("C = %g uF", cap(i) * 1e6)
set title "filter copper losses (mean over the 3 s run)"
set ylabel "losses [W]"
plot for [i = 1:3] rows(i) using ($4*1e3):($6*3600/3) with linespoints lw 2 \
     title sprintf("C = %g uF", cap(i) * 1e6)
unset multiplot

# Chapter 8: time against error for every filter, on the horizon floor and on the random
# field (data: ch08_table_horizon.dat, ch08_table_field.dat, written by fig_ch08_table).
# The error is on the minified pixels; Pareto-front filters are joined by a line.
set terminal svg size 900,420 font "sans,12" background "white"
set output "ch08_pareto.svg"
set multiplot layout 1,2
set xlabel "time per pixel / nearest"
set ylabel "RMS error (8-bit sRGB codes)"
set yrange [0:*]
set grid
set key off
do for [scene in "horizon field"] {
    set title sprintf("scene: %s", scene)
    file = sprintf("ch08_table_%s.dat", scene)
    plot file using 1:($3 == 1 ? $2 : 1/0) smooth unique with lines lw 2 lc rgb "#1f77b4", \
         file using 1:2 with points pt 7 ps 0.7 lc rgb "#444444", \
         file using 1:2:4 with labels offset 0.6,0.6 left font ",9" tc rgb "#1f77b4"
}
unset multiplot

# Chapter 8: time against error for every filter, on the horizon floor and on the random
# field (data: ch08_table_SCENE.dat and the front alone, ch08_table_SCENE_front.dat,
# written by fig_ch08_table). The error is on the minified pixels; Pareto-front filters
# are joined by a line.
set terminal svg size 900,420 font "sans,12" background "white"
set output "ch08_pareto.svg"
set multiplot layout 1,2
# The baseline, nearest, copies the 8-bit texel; the filters take 10 to 100 times as long.
set logscale x
set xlabel "time per pixel / nearest (log scale)"
set ylabel "RMS error (8-bit sRGB codes)"
set yrange [0:*]
set grid
set key off
do for [scene in "horizon field"] {
    set title sprintf("scene: %s", scene)
    file = sprintf("ch08_table_%s.dat", scene)
    plot sprintf("ch08_table_%s_front.dat", scene) using 1:2 with lines lw 2 lc rgb "#1f77b4", \
         file using 1:2 with points pt 7 ps 0.7 lc rgb "#444444", \
         file using 1:2:4 with labels offset 0.6,0.6 left font ",9" tc rgb "#1f77b4"
}
unset multiplot

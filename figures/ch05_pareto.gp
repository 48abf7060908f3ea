# Chapter 5: time against worst texel error for every mapper, on the grazing floor and
# on the random field (data: ch05_table_floor.dat, ch05_table_field.dat, written by
# fig_ch05_table). Pareto-front mappers are joined by a line; an error of 0 is drawn at
# 1e-6 texels (the bottom of the log scale).
set terminal svg size 900,420 font "sans,12" background "white"
set output "ch05_pareto.svg"
set multiplot layout 1,2
set logscale y
set yrange [1e-6:100]
set format y "10^{%L}"
set xlabel "time per pixel / affine fixed"
set ylabel "worst texel error (texels)"
set grid
set key off
do for [scene in "floor field"] {
    set title sprintf("scene: %s", scene)
    file = sprintf("ch05_table_%s.dat", scene)
    plot file using 1:($4 == 1 ? $2 : 1/0) smooth unique with lines lw 2 lc rgb "#1f77b4", \
         file using 1:2 with points pt 7 ps 0.7 lc rgb "#444444", \
         file using 1:($4 == 1 ? $2 : 1/0):5 with labels offset 0.6,0.6 left font ",9" \
              tc rgb "#1f77b4"
}
unset multiplot

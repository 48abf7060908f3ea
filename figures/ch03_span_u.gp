# u along one span of 64 pixels (depth ratio 4, 64 texels) for the exact, affine,
# quadratic and subdivided mappers, with an inset of the first pixels, where the
# parabola dips below u = 0 (@eq:pursey-overshoot). Data: ch03_span_u.dat, written by
# fig_ch03_mappers.
set terminal svg size 640,400 font "sans,12"
set output "ch03_span_u.svg"
set multiplot
set xlabel "pixel along the span"
set ylabel "u (texels)"
set key top left
set grid
set xrange [0:63]
plot "ch03_span_u.dat" using 1:2 with lines lw 2 title "exact", \
     "" using 1:3 with lines lw 1.5 dt 2 title "affine", \
     "" using 1:4 with lines lw 1.5 dt 3 title "quadratic", \
     "" using 1:5 with lines lw 1 dt 4 title "subdivided, N = 16"
# Inset: pixels 0 to 12, u from -1 to 2; the quadratic's dip below zero.
set origin 0.55, 0.14
set size 0.42, 0.42
set xrange [0:12]
set yrange [-1:2]
set xtics 4 font ",9"
set ytics 1 font ",9"
unset xlabel
unset ylabel
unset key
set title "first pixels: the parabola dips below u = 0" font ",10"
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fillcolor rgb "white" fillstyle solid 1.0
plot "ch03_span_u.dat" using 1:2 with lines lw 2, \
     "" using 1:3 with lines lw 1.5 dt 2, \
     "" using 1:4 with lines lw 1.5 dt 3, \
     "" using 1:5 with lines lw 1 dt 4, \
     0 with lines lw 0.5 lc rgb "black"
unset multiplot

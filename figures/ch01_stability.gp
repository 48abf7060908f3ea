# Chapter 1: how the two gradient methods' errors change as two vertices' y-delta
# shrinks, in double (data: ch01_stability.dat, written by fig_ch01_stability).
set terminal svg size 640,400 font "sans,12" background "white"
set output "ch01_stability.svg"
set logscale x
set logscale y
set format x "10^{%L}"
set xrange [1e-13:1]
set xlabel "y-delta between two vertices (px)"
set ylabel "error (machine epsilons of double)"
set key top left
set grid
plot "ch01_stability.dat" using 1:(strcol(2) eq "double" ? $4 : 1/0) with linespoints lw 2 pt 7 lc rgb "#b03030" title "split edge, 99th percentile", \
     "" using 1:(strcol(2) eq "double" ? $7 : 1/0) with linespoints lw 2 pt 5 lc rgb "#1f4e9a" title "closed form, 99th percentile", \
     "" using 1:(strcol(2) eq "double" ? $3 : 1/0) with linespoints lw 1 dt 2 pt 6 lc rgb "#b03030" title "split edge, median", \
     "" using 1:(strcol(2) eq "double" ? $6 : 1/0) with linespoints lw 1 dt 2 pt 4 lc rgb "#1f4e9a" title "closed form, median"

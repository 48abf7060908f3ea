# Chapter 7: the depth step over distance for three depth keys (data:
# ch07_depth_precision.dat from fig_ch07_depth_precision).
set terminal svg size 640,400 font "sans,12" background "white"
set output "ch07_depth_precision.svg"
set logscale xy
set format y "10^{%L}"
set xlabel "distance w (near plane 0.1, far plane 1000)"
set ylabel "depth step (same units)"
set grid
set key top left
plot "ch07_depth_precision.dat" using 1:3 with lines lw 2 title "z/w, 24-bit fixed point", \
     "ch07_depth_precision.dat" using 1:2 with lines lw 2 title "1/w, float (this renderer)", \
     "ch07_depth_precision.dat" using 1:4 with lines lw 2 dt 2 title "reversed z, float"

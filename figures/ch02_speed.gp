# Chapter 2: pixels per second against triangle area for every rasterizer variant and
# the plain fill (data: ch02_speed_sweep.dat, written by fig_ch02_speed from the
# benchmark's CSV).
set terminal svg size 640,420 font "sans,12" background "white"
set output "ch02_speed.svg"
set logscale x 2
set logscale y
set format x "2^{%L}"
set xrange [2:65536]
set xlabel "triangle area (px)"
set ylabel "Mpix/s (one core)"
set key top left
set grid
plot "ch02_speed_sweep.dat" using 1:7 with linespoints lw 2 pt 1 lc rgb "#707070" title "plain fill", \
     "" using 1:5 with linespoints lw 2 pt 7 lc rgb "#1f4e9a" title "fixed 8x8", \
     "" using 1:4 with linespoints lw 2 pt 5 lc rgb "#6a9ad0" title "fixed 1x1", \
     "" using 1:3 with linespoints lw 2 pt 9 lc rgb "#b05a00" title "float 8x8", \
     "" using 1:2 with linespoints lw 2 pt 11 lc rgb "#e0a060" title "float 1x1", \
     "" using 1:6 with linespoints lw 2 dt 2 pt 6 lc rgb "#b03030" title "naive"

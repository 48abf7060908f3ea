# Chapter 6: float drift along a long span (data: ch06_drift.dat from fig_ch06_drift).
set terminal svg size 640,360 font "sans,12" background "white"
set output "ch06_drift.svg"
set xlabel "pixel along the span"
set ylabel "|u - exact u| (texels)"
set grid
set key top left
plot "ch06_drift.dat" using 1:2 with lines lw 2 title "stepped: u += du", \
     "ch06_drift.dat" using 1:3 with lines lw 2 title "afresh: u0 + k du"

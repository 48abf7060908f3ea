# Chapter 10: pixels per second against triangle area, every variant and llvmpipe,
# one core, from the committed runs (data: ch10_speed_{flat,depth}.dat, written by
# fig_ch10_speed from chapters/10-fast-pixels/data/ch10_fast.csv, and
# ch10_speed_textured.dat from data/ch10_textured.csv).
set terminal svg size 640,420 font "sans,12" background "white"
set logscale x 2
set logscale y
set format x "2^{%L}"
set xrange [2:100000]
set xlabel "triangle area (px)"
set ylabel "Mpix/s (one core)"
set key bottom right
set grid
do for [mode in "flat depth"] {
    set output "ch10_speed_".mode.".svg"
    file = "ch10_speed_".mode.".dat"
    if (mode eq "flat") {
        plot file using 1:8 with linespoints lw 2 pt 1 lc rgb "#707070" title "plain fill", \
             "" using 1:5 with linespoints lw 2 pt 7 lc rgb "#1f4e9a" title "8x8 masks", \
             "" using 1:4 with linespoints lw 2 pt 5 lc rgb "#6a9ad0" title "runs", \
             "" using 1:6 with linespoints lw 2 pt 13 lc rgb "#2a8a2a" title "tiled", \
             "" using 1:3 with linespoints lw 2 pt 9 lc rgb "#b05a00" title "blocks (ch. 2)", \
             "" using 1:2 with linespoints lw 2 pt 11 lc rgb "#e0a060" title "walk (ch. 2)", \
             "" using 1:7 with linespoints lw 2 dt 2 pt 6 lc rgb "#b03030" title "llvmpipe"
    } else {
        plot file using 1:5 with linespoints lw 2 pt 7 lc rgb "#1f4e9a" title "8x8 masks", \
             "" using 1:4 with linespoints lw 2 pt 5 lc rgb "#6a9ad0" title "runs", \
             "" using 1:6 with linespoints lw 2 pt 13 lc rgb "#2a8a2a" title "tiled", \
             "" using 1:3 with linespoints lw 2 pt 9 lc rgb "#b05a00" title "blocks (ch. 2)", \
             "" using 1:2 with linespoints lw 2 pt 11 lc rgb "#e0a060" title "walk (ch. 2)", \
             "" using 1:7 with linespoints lw 2 dt 2 pt 6 lc rgb "#b03030" title "llvmpipe"
    }
}
set output "ch10_speed_textured.svg"
plot "ch10_speed_textured.dat" using 1:3 with linespoints lw 2 pt 5 lc rgb "#6a9ad0" title "textured runs", \
     "" using 1:2 with linespoints lw 2 pt 11 lc rgb "#e0a060" title "teaching path (ch. 3)", \
     "" using 1:4 with linespoints lw 2 dt 2 pt 6 lc rgb "#b03030" title "llvmpipe"

# Chapter 5: every mapper's time against its error, on the three scenes (data:
# ch05_table_SCENE.dat, written by fig_ch05_table). (a) The facing wall, where every
# mapper's worst error is 0 and the error left is the wrong texels at ties; (b) the
# grazing floor and (c) the random field, which have no ties, against the worst texel
# error (an error of 0 is drawn at 1e-6 texels, the bottom of the log scale). Each time
# carries its tie band: two mappers whose bands meet are tied within the run's noise.
# The front (the mappers no other beats on time, worst error and wrong texels at ties)
# is drawn in blue, named and joined by a line.
set terminal svg size 1200,420 font "sans,12" background "white"
set output "ch05_pareto.svg"
set multiplot layout 1,3
set xlabel "time per pixel / affine fixed"
set grid
set key off
front = "#1f77b4"
# Blocks: 0 every mapper, 1 the front by time. Columns: 1 ratio, 2 and 3 its tie band, 4 worst, 5 mean, 6 wrong at ties, 7 front, 8 name.
set title "(a) wall"
set ylabel "wrong texels at ties (pixels)"
set yrange [-2000:36000]
set format y "%.0f"
file = "ch05_table_wall.dat"
plot file index 0 using 1:6:2:3 with xerrorbars pt 7 ps 0.5 lc rgb "#444444", \
     file index 1 using 1:6 with linespoints lw 2 pt 7 ps 0.6 lc rgb front, \
     file index 1 using 1:6:8 with labels offset 0.6,0.6 left font ",9" tc rgb front
set logscale y
set yrange [1e-6:100]
set format y "10^{%L}"
set ylabel "worst texel error (texels)"
do for [panel in "b:floor c:field"] {
    scene = panel[3:]
    set title sprintf("(%s) %s", panel[1:1], scene)
    file = sprintf("ch05_table_%s.dat", scene)
    plot file index 0 using 1:4:2:3 with xerrorbars pt 7 ps 0.5 lc rgb "#444444", \
         file index 1 using 1:4 with linespoints lw 2 pt 7 ps 0.6 lc rgb front, \
         file index 1 using 1:4:8 with labels offset 0.6,0.6 left font ",9" tc rgb front
}
unset multiplot

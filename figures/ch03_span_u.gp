# u along one span of 64 pixels (depth ratio 4, 64 texels) for the exact, affine,
# quadratic and subdivided mappers. Data: ch03_span_u.dat, written by fig_ch03_mappers.
set terminal svg size 640,400 font "sans,12"
set output "ch03_span_u.svg"
set xlabel "pixel along the span"
set ylabel "u (texels)"
set key top left
set grid
plot "ch03_span_u.dat" using 1:2 with lines lw 2 title "exact", \
     "" using 1:3 with lines lw 1.5 dt 2 title "affine", \
     "" using 1:4 with lines lw 1.5 dt 3 title "quadratic", \
     "" using 1:5 with lines lw 1 dt 4 title "subdivided, N = 16"

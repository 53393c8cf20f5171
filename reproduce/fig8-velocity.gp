set terminal pngcairo size 800,560
set output 'fig8-velocity.png'
set title "Normalised v_z(y) across the depth (the paper's Fig. 8(b))"
set xlabel 'y (d)'; set ylabel 'v_z(y) / V_z'
set key bottom center; set grid; set yrange [0:*]
plot 'fig8-base.dat' u 1:2 w lp lw 2 pt 5 t 'd_w = 1', 'fig8-dw0.5.dat' u 1:2 w lp lw 2 pt 7 t 'd_w = 0.5', 'fig8-dw0.dat' u 1:2 w lp lw 2 pt 9 t 'd_w = 0', 'fig8-dw-1.5.dat' u 1:2 w lp lw 2 pt 11 t 'd_w = -1.5', 'fig8-reflect.dat' u 1:2 w lp lw 2 pt 13 t 'reflection'

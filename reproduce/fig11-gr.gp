set terminal pngcairo size 800,560
set output 'fig11-gr.png'
set title 'g(r) at small r, -15 < x < 15, 15 < z < 45, 18-34 tau (Fig. 11(b))'
set xlabel 'r (d)'; set ylabel 'g(r)'
set logscale y; set xrange [0:1.5]; set key top left; set grid
plot 'fig11-base.dat' u 1:2 w l lw 2 lc 1 dt 1 t 'Full relaxation', 'fig11-none.dat' u 1:2 w l lw 2 lc 2 dt 1 t 'No relaxation', 'fig11-random-k10.dat' u 1:2 w l lw 2 lc 3 dt 1 t 'Method 1 k = 10', 'fig11-random-k100.dat' u 1:2 w l lw 2 lc 4 dt 1 t 'Method 1 k = 100', 'fig11-random-k1000.dat' u 1:2 w l lw 2 lc 5 dt 1 t 'Method 1 k = 1000', 'fig11-counter-k10.dat' u 1:2 w l lw 2 lc 1 dt 2 t 'Method 2 k = 10', 'fig11-global-k1.dat' u 1:2 w l lw 2 lc 2 dt 2 t 'Method 3 k = 1', 'fig11-global-k10.dat' u 1:2 w l lw 2 lc 3 dt 2 t 'Method 3 k = 10', 'fig11-global-k100.dat' u 1:2 w l lw 2 lc 4 dt 2 t 'Method 3 k = 100'

set terminal pngcairo size 1100,560
set output 'fig12-badness.png'
set title 'Badness against relaxation time, both relative to full relaxation (Fig. 12)'
set xlabel 't_{relax} / t_{relax}(full)'; set ylabel 'B / B(full)'
set logscale xy; set key outside right; set grid
set format x "10^{%L}"; set format y "10^{%L}"
set xrange [1e-4:2]; set yrange [0.5:*]
plot 'fig12-ours-0.dat' u 1:2 w lp lw 2 pt 5 lc 1 t 'granflow: Full relaxation', 'fig12-paper-0.dat' u 1:2 w lp lw 1 dt 2 pt 4 lc 1 t 'paper: Full relaxation', 'fig12-ours-b1-0.dat' u 1:2 w lp lw 1 dt 3 pt 5 lc 1 t 'granflow, unsquared B1: Full relaxation', 'fig12-ours-1.dat' u 1:2 w lp lw 2 pt 7 lc 2 t 'granflow: Method 1', 'fig12-paper-1.dat' u 1:2 w lp lw 1 dt 2 pt 6 lc 2 t 'paper: Method 1', 'fig12-ours-b1-1.dat' u 1:2 w lp lw 1 dt 3 pt 7 lc 2 t 'granflow, unsquared B1: Method 1', 'fig12-ours-2.dat' u 1:2 w lp lw 2 pt 9 lc 3 t 'granflow: Method 2', 'fig12-paper-2.dat' u 1:2 w lp lw 1 dt 2 pt 8 lc 3 t 'paper: Method 2', 'fig12-ours-b1-2.dat' u 1:2 w lp lw 1 dt 3 pt 9 lc 3 t 'granflow, unsquared B1: Method 2', 'fig12-ours-3.dat' u 1:2 w lp lw 2 pt 11 lc 4 t 'granflow: Method 3', 'fig12-paper-3.dat' u 1:2 w lp lw 1 dt 2 pt 10 lc 4 t 'paper: Method 3', 'fig12-ours-b1-3.dat' u 1:2 w lp lw 1 dt 3 pt 11 lc 4 t 'granflow, unsquared B1: Method 3'

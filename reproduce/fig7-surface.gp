set terminal pngcairo size 800,560
set output 'fig7-surface.png'
set title "Free-surface angle (the paper's Fig. 7; silo filled to z = 40 d)"
set xlabel 't (tau)'; set ylabel 'surface angle (degrees)'
set key top left; set grid
plot 'fig7-surf-beta0.dat' u 1:2 w lp lw 2 pt 5 t 'beta = 0', 'fig7-surf-beta1.dat' u 1:2 w lp lw 2 pt 7 t 'beta = 1', 'fig7-surf-beta1w.dat' u 1:2 w lp lw 2 pt 9 t 'beta = 1 + weighting', 'fig7-surf-beta3w.dat' u 1:2 w lp lw 2 pt 11 t 'beta = 3 + weighting'

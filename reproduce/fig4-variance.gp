set terminal pngcairo size 800,560
set output 'fig4-variance.png'
set title 'Width of the velocity profile (window 24-34 tau)'
set xlabel 'height z (d)'; set ylabel 'Var of the Gaussian fit to v_z(x) (d^2)'
set key top left; set grid
plot 'fig4-variance-base.dat' u 1:2 w lp lw 2 pt 5 t 'event-driven', 'fig4-variance-fixed-random.dat' u 1:2 w lp lw 2 pt 7 t 'fixed, random order', 'fig4-variance-fixed-newest.dat' u 1:2 w lp lw 2 pt 9 t 'fixed, newest first', 2.28*x+1.60 w l dt 2 lc rgb 'black' t 'DEM: 2.28 z + 1.60'

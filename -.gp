# ldv allan plot; re-run with: gnuplot -.gp
set terminal pngcairo size 640,480 noenhanced
set output '-'
set logscale xy
set grid xtics ytics mxtics mytics
set format y '%.0e'
set key bottom left font ',8'
set xlabel 'tau [s]'
set title 'x'
set ylabel 'Allan deviation [1]'
plot '-.dat' index 0 using 1:2:3:4 with yerrorbars pt 7 ps 0.5 lc rgb 'black' title 'OADEV (68% CI)', '' index 1 using 1:2 with lines lw 2 lc rgb 'red' title 'fit total', '' index 1 using 1:($4>0?$4:1/0) with lines dt 2 title 'N', '' index 1 using 1:($7>0?$7:1/0) with lines dt 2 title 'R'

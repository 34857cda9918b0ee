set terminal pngcairo size 1000,760 noenhanced
set output 'accuracy.png'
set title 'python3 lengyel_perspective.py (double): error against time'
set xlabel 'time per answer, ns (log scale)'
set logscale x
set ylabel 'bits lost: worst answer (filled), 99.9th percentile (open)'
set yrange [-1:*]
set grid
set key outside below
plot 'accuracy_front.dat' using 1:2 with steps lw 2 lc rgb '#aaaaaa' title 'non-dominated front', 'accuracy_points.dat' index 0 using 1:2 with points pt 7 ps 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py (double), round trip over the pipe', '' index 0 using 1:3 with points pt 6 ps 2 lc rgb '#d62728' notitle, 'accuracy_points.dat' index 1 using 1:2 with points pt 7 ps 2 lc rgb '#1f77b4' title 'core closed_form (double)', '' index 1 using 1:3 with points pt 6 ps 2 lc rgb '#1f77b4' notitle, 'accuracy_points.dat' index 2 using 1:2 with points pt 7 ps 2 lc rgb '#2ca02c' title 'core general (double)', '' index 2 using 1:3 with points pt 6 ps 2 lc rgb '#2ca02c' notitle, 'accuracy_points.dat' index 3 using 1:2 with points pt 7 ps 2 lc rgb '#9467bd' title 'core accurate (double)', '' index 3 using 1:3 with points pt 6 ps 2 lc rgb '#9467bd' notitle

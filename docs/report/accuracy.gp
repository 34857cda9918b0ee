set terminal pngcairo size 1000,760 noenhanced
set output 'docs/report/accuracy.png'
set title 'oblique: error against run time (worst over every regime)'
set xlabel 'ns per answer, mean over regimes (log scale): a call in process, or a request over the pipe (round trip)'
set logscale x
set ylabel 'max error, bits lost = log2(ulps of the row + 1)'
set yrange [-1:*]
set grid
set key outside below maxrows 4
plot 'docs/report/accuracy_front.dat' using 1:2 with steps lw 2 lc rgb '#aaaaaa' title 'non-dominated front', 'docs/report/accuracy_points.dat' index 0 using 1:2 with points pt 7 ps 2 lc rgb '#9467bd' title 'accurate (double)', 'docs/report/accuracy_points.dat' index 1 using 1:2 with points pt 9 ps 2 lc rgb '#9467bd' title 'accurate (float)', 'docs/report/accuracy_points.dat' index 2 using 1:2 with points pt 5 ps 2 lc rgb '#9467bd' title 'accurate (long_double)', 'docs/report/accuracy_points.dat' index 3 using 1:2 with points pt 7 ps 2 lc rgb '#1f77b4' title 'closed_form (double)', 'docs/report/accuracy_points.dat' index 4 using 1:2 with points pt 9 ps 2 lc rgb '#1f77b4' title 'closed_form (float)', 'docs/report/accuracy_points.dat' index 5 using 1:2 with points pt 5 ps 2 lc rgb '#1f77b4' title 'closed_form (long_double)', 'docs/report/accuracy_points.dat' index 6 using 1:2 with points pt 9 ps 2 lc rgb '#ff7f0e' title 'example_engine_no_statuses --float (float), round trip', 'docs/report/accuracy_points.dat' index 7 using 1:2 with points pt 7 ps 2 lc rgb '#2ca02c' title 'general (double)', 'docs/report/accuracy_points.dat' index 8 using 1:2 with points pt 9 ps 2 lc rgb '#2ca02c' title 'general (float)', 'docs/report/accuracy_points.dat' index 9 using 1:2 with points pt 5 ps 2 lc rgb '#2ca02c' title 'general (long_double)', 'docs/report/accuracy_points.dat' index 10 using 1:2 with points pt 7 ps 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py (double), round trip'

set terminal pngcairo size 1200,1020 noenhanced
set output 'docs/report/stiffness.png'
set multiplot layout 3,2 title 'oblique: worst error against the stiffness of each regime (the core in double)'
set logscale x
set ylabel 'max error, bits lost'
set yrange [-1:*]
set grid
set key top left
set title 'tiny_near'
set xlabel '1/n'
plot 'docs/report/stiffness.dat' index 0 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 1 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 2 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 3 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 4 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
set title 'far_near_ratio'
set xlabel 'f/n'
plot 'docs/report/stiffness.dat' index 5 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 6 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 7 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 8 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 9 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
set title 'near_eye'
set xlabel '1/|C_w|'
plot 'docs/report/stiffness.dat' index 10 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 11 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 12 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 13 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 14 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
set title 'near_far_corner'
set xlabel '|C||Q|/(C.Q)'
plot 'docs/report/stiffness.dat' index 15 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 16 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 17 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 18 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 19 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
set title 'near_standard'
set xlabel '1/perturbation'
plot 'docs/report/stiffness.dat' index 20 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 21 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 22 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 23 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 24 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
set title 'scaled'
set xlabel 'scale'
plot 'docs/report/stiffness.dat' index 25 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'closed_form', 'docs/report/stiffness.dat' index 26 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'general', 'docs/report/stiffness.dat' index 27 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'accurate', 'docs/report/stiffness.dat' index 28 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'python3 lengyel_perspective.py', 'docs/report/stiffness.dat' index 29 using 1:2 with linespoints pt 7 lw 2 lc rgb '#8c564b' title 'example_engine_no_statuses --float'
unset multiplot

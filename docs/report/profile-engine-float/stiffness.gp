set terminal pngcairo size 900,700 noenhanced
set output 'stiffness.png'
set title 'example_engine_no_statuses --float (float): error against the stiffness of the case'
set xlabel 'kappa, the condition number of C . Q (decades)'
set logscale x
set ylabel 'bits lost, worst answer in the decade'
set yrange [-0.5:*]
set key outside below
set grid
plot 'stiffness.dat' index 0 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'example_engine_no_statuses --float (float), round trip over the pipe', 'stiffness.dat' index 1 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'core closed_form (float)', 'stiffness.dat' index 2 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'core general (float)', 'stiffness.dat' index 3 using 1:2 with linespoints pt 7 lw 2 lc rgb '#9467bd' title 'core accurate (float)'

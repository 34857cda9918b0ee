set terminal pngcairo size 1200,960 noenhanced
set output 'docs/report/stiffness.png'
set multiplot layout 3,2 title 'oblique: worst error (double) against the stiffness of each regime'
set logscale x
set ylabel 'max error, bits'
set yrange [-0.5:*]
set key top left
set title 'tiny_near'
set xlabel '1/n'
plot 'docs/report/stiffness.dat' index 0 using 1:2 with linespoints title 'closed_form', '' index 1 using 1:2 with linespoints title 'general', '' index 2 using 1:2 with linespoints title 'accurate'
set title 'far_near_ratio'
set xlabel 'f/n'
plot 'docs/report/stiffness.dat' index 3 using 1:2 with linespoints title 'closed_form', '' index 4 using 1:2 with linespoints title 'general', '' index 5 using 1:2 with linespoints title 'accurate'
set title 'near_eye'
set xlabel '1/|C_w|'
plot 'docs/report/stiffness.dat' index 6 using 1:2 with linespoints title 'closed_form', '' index 7 using 1:2 with linespoints title 'general', '' index 8 using 1:2 with linespoints title 'accurate'
set title 'near_far_corner'
set xlabel '|C||Q|/(C.Q)'
plot 'docs/report/stiffness.dat' index 9 using 1:2 with linespoints title 'closed_form', '' index 10 using 1:2 with linespoints title 'general', '' index 11 using 1:2 with linespoints title 'accurate'
set title 'near_standard'
set xlabel '1/perturbation'
plot 'docs/report/stiffness.dat' index 12 using 1:2 with linespoints title 'closed_form', '' index 13 using 1:2 with linespoints title 'general', '' index 14 using 1:2 with linespoints title 'accurate'
set title 'scaled'
set xlabel 'scale'
plot 'docs/report/stiffness.dat' index 15 using 1:2 with linespoints title 'closed_form', '' index 16 using 1:2 with linespoints title 'general', '' index 17 using 1:2 with linespoints title 'accurate'
unset multiplot

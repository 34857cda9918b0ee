set terminal pngcairo size 900,600 noenhanced
set output 'docs/report/accuracy.png'
set title 'oblique: error against run time (worst over every regime)'
set xlabel 'ns per call (mean over regimes)'
set logscale x
set ylabel 'max error, bits = log2(ulp + 1)'
set yrange [-0.5:*]
set key top right
plot 'docs/report/accuracy_front.dat' using 1:2 with lines lw 2 title 'non-dominated front', 'docs/report/accuracy_points.dat' using 1:2 with points pt 7 ps 1.5 title 'method/scalar', '' using 1:2:3 with labels offset 1,1 left notitle

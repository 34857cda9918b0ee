set terminal pngcairo size 900,650 noenhanced
set output 'docs/report/figure5.png'
set title 'Figure 5 reproduced: max NDC z along the view axis (Eq. 19, gl), clamped to 1'
set xlabel 'angle between the plane normal and -z (degrees)'
set ylabel 'distance from the camera to the plane'
set view map
set pm3d at b
set palette rgbformulae 33,13,10
set cbrange [-1:1]
set cblabel 'max NDC z'
set contour base
set cntrparam levels discrete -0.5,0,0.5,0.9,0.99
unset surface
set key off
splot 'docs/report/figure5.dat' using 1:2:3 with pm3d

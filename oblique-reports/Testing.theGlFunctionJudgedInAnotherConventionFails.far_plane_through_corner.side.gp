set terminal pngcairo size 1000,800 noenhanced
set output 'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.side.png'
set title 'far_plane_through_corner (ignores_the_convention): side view'
set xlabel 'eye z'
set ylabel 'eye y'
set size ratio -1
set key below left Left reverse maxcols 1
set grid
set xrange [-2.2:0.2]
set yrange [-1.2:1.2]
plot \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 0 using 3:2 with lines lc rgb 'black' lw 2 title 'original view volume (M)', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 1 using 3:2 with lines lc rgb '#1f77b4' lw 2 dt 3 title 'plane C (where it cuts M''s volume)', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 2 using 3:2 with lines lc rgb '#2ca02c' lw 2 title 'oblique view volume, expected (exact M'')', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 3 using 3:2 with lines lc rgb '#d62728' lw 1.5 dt 2 title 'oblique view volume, answered (the implementation''s M'')', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 4 using 3:2 with points pt 6 ps 2 lw 2 lc rgb '#9467bd' title 'far corner Q', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 5 using 3:2 with points pt 2 ps 3 lw 3 lc rgb '#e377c2' title 'marked: far corner Q'

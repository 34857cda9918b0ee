set terminal pngcairo size 1000,800 noenhanced
set output 'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.top.png'
set title 'far_plane_through_corner (ignores_the_convention): top view'
set xlabel 'eye x'
set ylabel 'eye z'
set size ratio -1
set key below left Left reverse maxcols 1
set grid
set xrange [-0.825:1.575]
set yrange [-2.2:0.2]
plot \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 0 using 1:3 with lines lc rgb 'black' lw 2 title 'original view volume (M)', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 1 using 1:3 with lines lc rgb '#1f77b4' lw 2 dt 3 title 'plane C (where it cuts M''s volume)', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 2 using 1:3 with lines lc rgb '#2ca02c' lw 2 title 'oblique view volume, expected (exact M'')', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 3 using 1:3 with lines lc rgb '#d62728' lw 1.5 dt 2 title 'oblique view volume, answered (the implementation''s M'')', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 4 using 1:3 with points pt 6 ps 2 lw 2 lc rgb '#9467bd' title 'far corner Q', \
  'Testing.theGlFunctionJudgedInAnotherConventionFails.far_plane_through_corner.views.dat' index 5 using 1:3 with points pt 2 ps 3 lw 3 lc rgb '#e377c2' title 'marked: far corner Q'

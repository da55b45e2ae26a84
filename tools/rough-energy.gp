# rough-energy.gp: chapter 17's plot, the share of light a rough conductor of reflectance 1 loses against
# its roughness (make rough-energy sets `data`, the table of build/rough-energy, and `output`, the SVG).

set terminal svg size 900,440 font "sans,13" background rgb "white"
set encoding utf8
set key inside left top vertical box
set grid ytics xtics lc rgb "#dddddd"
set border lc rgb "#444444"
set xrange [0:1]
set yrange [0:0.8]
set xlabel "roughness (alpha = roughness²)"
set ylabel "share of the light lost"

set style line 1 lw 2 pt 7 ps 0.7 lc rgb "#2471a3"
set style line 2 lw 2 pt 5 ps 0.7 lc rgb "#e67e22"
set style line 3 lw 2 pt 9 ps 0.8 lc rgb "#138d75"
set style line 4 lw 3 pt 13 ps 0.8 lc rgb "#8e44ad"

set output output
set title "GGX conductor of reflectance 1, single scattering: the light that falls between the microfacets"
plot data using 1:3 title "seen from straight above (μ = 1)" with linespoints ls 1, \
     data using 1:4 title "seen at 60° (μ = 0.5)" with linespoints ls 2, \
     data using 1:5 title "seen at 84° (μ = 0.1)" with linespoints ls 3, \
     data using 1:6 title "in a white furnace (averaged over μ)" with linespoints ls 4

# instances-plots.gp: the plot of chapter 16's walkthrough, refit against rebuild over an animation: the
# top level's SAH cost and the frame's time, frame by frame, for each way of following the instances
# (tools/instances-docs.sh sets `series`, a folder of files "FRAME SAH_COST FRAME_SECONDS" a line, one per
# mode, and `figures`, where the SVG goes).

set terminal svg size 900,420 font "sans,13" background rgb "white"
set encoding utf8
set grid ytics xtics lc rgb "#dddddd"
set border lc rgb "#444444"
set xlabel "frame"
set xrange [1:*]

set style line 1 lw 2 pt 7 ps 0.8 lc rgb "#2471a3"
set style line 2 lw 2 pt 5 ps 0.8 lc rgb "#e67e22"
set style line 3 lw 2 pt 9 ps 0.9 lc rgb "#138d75" dt 2

set output figures."/instances-refit.svg"
set multiplot layout 1,2 title "400 instances crossing the field: refit against rebuild"
set ylabel "top level's SAH cost"
set yrange [0:*]
unset key
plot series."/refit" using 1:2 title "refit" with linespoints ls 1, \
     series."/rebuild" using 1:2 title "rebuild" with linespoints ls 2, \
     series."/auto" using 1:2 title "refit, rebuild past 1.25 ×" with linespoints ls 3
set key inside left top vertical box
set ylabel "time of the frame (s, one thread)"
plot series."/refit" using 1:3 title "refit" with linespoints ls 1, \
     series."/rebuild" using 1:3 title "rebuild" with linespoints ls 2, \
     series."/auto" using 1:3 title "refit, rebuild past 1.25 ×" with linespoints ls 3
unset multiplot

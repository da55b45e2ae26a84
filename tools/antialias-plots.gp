# antialias-plots.gp: the plots of chapter 12's walkthrough, error against camera rays per pixel and
# against processor time for each sampling method (tools/antialias-docs.sh sets `series`, a folder of
# files "RAYS ERROR SECONDS" a line, one per method, and `figures`, where the SVG files go).

set terminal svg size 900,440 font "sans,13" background rgb "white"
set encoding utf8
set key outside right top vertical box
set grid ytics mytics xtics mxtics lc rgb "#dddddd"
set border lc rgb "#444444"
set logscale xy
set ylabel "mean error (8-bit levels), log scale"

set style line 1 lw 2 pt 7 ps 0.8 lc rgb "#2471a3"
set style line 2 lw 2 pt 5 ps 0.8 lc rgb "#e67e22"
set style line 3 lw 2 pt 9 ps 0.9 lc rgb "#138d75"
set style line 4 lw 2 pt 9 ps 0.9 lc rgb "#138d75" dt 2
set style line 5 lw 2 pt 13 ps 0.9 lc rgb "#8e44ad"

set output figures."/antialias-error.svg"
set title "Chapter 12's scene: error against camera rays per pixel"
set xlabel "camera rays per pixel, log scale"
plot series."/grid-0.3" using 1:2 title "grid n × n" with linespoints ls 1, \
     series."/jitter-0.3" using 1:2 title "jitter n × n" with linespoints ls 2, \
     series."/adaptive-0.3" using 1:2 title "adaptive, threshold 0.3" with linespoints ls 3, \
     series."/adaptive-0.1" using 1:2 title "adaptive, threshold 0.1" with linespoints ls 4, \
     series."/recursive-0.3" using 1:2 title "recursive, threshold 0.3" with linespoints ls 5

set output figures."/antialias-time.svg"
set title "Chapter 12's scene: error against processor time (one thread)"
set xlabel "processor time of the whole run (s), log scale"
plot series."/grid-0.3" using 3:2 title "grid n × n" with linespoints ls 1, \
     series."/jitter-0.3" using 3:2 title "jitter n × n" with linespoints ls 2, \
     series."/adaptive-0.3" using 3:2 title "adaptive, threshold 0.3" with linespoints ls 3, \
     series."/adaptive-0.1" using 3:2 title "adaptive, threshold 0.1" with linespoints ls 4, \
     series."/recursive-0.3" using 3:2 title "recursive, threshold 0.3" with linespoints ls 5

# plots.gp: the gnuplot script that draws the plots of docs/results.md (make results).
#
# Run by tools/results/publish.sh, which sets `series` (a folder of two-column files it made from the
# CSVs: X Y a line), `figures` (where the SVG files go), and `small`, `big` (scene 1's two sizes).
# Colours: one per structure, the same in every plot; the seed's figures are black.

set terminal svg size 900,440 font "sans,13" background rgb "white"
set encoding utf8
set datafile missing "?"
set key outside right top vertical box
set grid ytics mytics xtics lc rgb "#dddddd"
set border lc rgb "#444444"

c_none = "#c0392b"; c_kd = "#8e44ad"; c_median = "#e67e22"; c_sah = "#2471a3"; c_fast = "#138d75"; c_pov = "#7f8c8d"
# Line styles 1-5: brute force, kd-tree, BVH median, BVH SAH, chapter 11. The kd-tree's times lie on
# the BVHs' lines in places: it is dashed with open diamonds, and drawn after them, so it shows on top.
set style line 1 lw 2 pt 7 ps 0.8 lc rgb c_none
set style line 2 lw 2 pt 12 ps 1.1 lc rgb c_kd dt 2
set style line 3 lw 2 pt 7 ps 0.8 lc rgb c_median
set style line 4 lw 2 pt 7 ps 0.8 lc rgb c_sah
set style line 5 lw 2 pt 7 ps 0.8 lc rgb c_fast

# ---- scene 1: time against depth (brute force), two sizes, one light and two -------------------------
set output figures."/scene1-depth.svg"
set title "The seed's first scene: time against depth, brute force and a BVH"
set xlabel "recursion depth"
set ylabel "processor time (s), log scale"
set logscale y
set xrange [0.8:5.2]
set xtics 1
plot series."/s1-big-2-none" using 1:2 title "brute force, ".big.", two lights" with linespoints lw 2 pt 5 ps 0.8 lc rgb c_none dt 2, \
     series."/s1-big-1-none" using 1:2 title "brute force, ".big.", one light" with linespoints lw 2 pt 7 ps 0.8 lc rgb c_none, \
     series."/s1-small-2-none" using 1:2 title "brute force, ".small.", two lights" with linespoints lw 2 pt 5 ps 0.8 lc rgb "#e59866" dt 2, \
     series."/s1-small-1-none" using 1:2 title "brute force, ".small.", one light" with linespoints lw 2 pt 7 ps 0.8 lc rgb "#e59866", \
     series."/s1-big-1-bvh-sah" using 1:2 title "BVH (SAH), ".big.", one light" with linespoints lw 2 pt 7 ps 0.8 lc rgb c_sah

# ---- scene 1: growth against depth 1, with the seed's one number ------------------------------------
set output figures."/scene1-growth.svg"
set title "The seed's first scene: time relative to depth 1"
set ylabel "time ÷ time at depth 1"
unset logscale y
set yrange [0.9:*]
set label 1 "the seed: +60 %" at 4.9,1.6 right offset -0.5,2.2 tc rgb "black"
set key outside right top vertical box
plot series."/s1-big-1-none-growth" using 1:2 title "brute force, ".big.", one light" with linespoints lw 2 pt 7 ps 0.8 lc rgb c_none, \
     series."/s1-big-2-none-growth" using 1:2 title "brute force, ".big.", two lights" with linespoints lw 2 pt 5 ps 0.8 lc rgb c_none dt 2, \
     series."/s1-small-1-none-growth" using 1:2 title "brute force, ".small.", one light" with linespoints lw 2 pt 7 ps 0.8 lc rgb "#e59866", \
     series."/s1-small-2-none-growth" using 1:2 title "brute force, ".small.", two lights" with linespoints lw 2 pt 5 ps 0.8 lc rgb "#e59866" dt 2, \
     series."/s1-big-1-bvh-sah-growth" using 1:2 title "BVH (SAH), ".big.", one light" with linespoints ls 4, \
     series."/s1-big-1-povray-growth" using 1:2 title "POV-Ray 3.7, ".big.", one light" with linespoints lw 2 pt 4 ps 0.8 lc rgb c_pov dt 2, \
     "-" using 1:2 title "the seed (its text)" with points pt 9 ps 1.6 lc rgb "black"
5 1.6
e
unset label 1
set yrange [*:*]
set key outside right top vertical box

# ---- the bunny and the 5k teapot: time and triangle tests against depth ------------------------------
do for [model in "bunny teapot-5k"] {
    name = (model eq "bunny") ? "the bunny (3,674 triangles)" : "the teapot (5,112 triangles)"
    set output figures."/".model."-time.svg"
    set title "Time against recursion depth: ".name
    set ylabel "processor time (s), log scale"
    set logscale y
    plot series."/".model."-time-none" using 1:2 title "brute force" with linespoints ls 1, \
         series."/".model."-time-bvh-median" using 1:2 title "BVH, median split" with linespoints ls 3, \
         series."/".model."-time-bvh-sah" using 1:2 title "BVH, SAH" with linespoints ls 4, \
         series."/".model."-time-kd-sah" using 1:2 title "kd-tree (SAH)" with linespoints ls 2, \
         series."/".model."-time-povray" using 1:2 title "POV-Ray 3.7" with linespoints lw 2 pt 4 ps 0.8 lc rgb c_pov dt 2
    set output figures."/".model."-tests.svg"
    set title "Triangle tests against recursion depth: ".name
    set ylabel "triangle tests per frame, log scale"
    plot series."/".model."-tests-none" using 1:2 title "brute force" with linespoints ls 1, \
         series."/".model."-tests-kd-sah" using 1:2 title "kd-tree (SAH)" with linespoints ls 2, \
         series."/".model."-tests-bvh-median" using 1:2 title "BVH, median split" with linespoints ls 3, \
         series."/".model."-tests-bvh-sah" using 1:2 title "BVH, SAH" with linespoints ls 4
}

# ---- the large model: processor time and triangle tests per structure, and the seed's figures -------------------------
set output figures."/large.svg"
set title "The 349,872-triangle teapot at 800×600, depth 1: the whole process\n* sampled on a coarser grid and scaled up: an extrapolation, not a measurement"
set xlabel ""
set ylabel "processor time (s), log scale"
set logscale y
set yrange [0.05:30000]
set xrange [-0.6:*]
unset key
set style fill solid 0.85 border -1
set boxwidth 0.7
set xtics rotate by -30 left nomirror font ",11"
set grid noxtics
plot series."/large" using 0:2:(0.7):4:xtic(1) with boxes fc rgb variable, \
     series."/large" using 0:2:(sprintf("%s s%s", $2 >= 1000 ? gprintf("%.0f", $2) : gprintf("%.3g", $2), $3 == 1 ? "*" : "")) \
         with labels offset 0,0.8 font ",11"
set output figures."/large-tests.svg"
set title "The 349,872-triangle teapot at 800×600, depth 1: triangle tests\n* sampled on a coarser grid and scaled up: an extrapolation, not a measurement"
set ylabel "triangle tests per frame, log scale"
set yrange [1e5:1e12]
set format y "10^{%T}"
plot series."/large-tests" using 0:2:(0.7):4:xtic(1) with boxes fc rgb variable, \
     series."/large-tests" using 0:2:(sprintf("%s%s", gprintf("%.2t×10^{%T}", $2), $3 == 1 ? "*" : "")) \
         with labels offset 0,0.8 font ",11"
set format y "%g"
set xtics norotate font ",13"
set grid xtics
unset xrange
set yrange [*:*]
set style fill empty
set key outside right top vertical box

# ---- how cost grows with the model -----------------------------------------------------------------
set xlabel "triangles, log scale"
set logscale xy
set format x "10^{%T}"
set xrange [*:*]
set xtics auto
do for [measure in "build frame memory"] {
    set output figures."/scaling-".measure.".svg"
    if (measure eq "build") {
        set title "Build time against model size (teapots)"; set ylabel "build (ms), log scale"
    }
    if (measure eq "frame") {
        set title "Frame time against model size (teapots, depth 1)"; set ylabel "render (s), log scale"
    }
    if (measure eq "memory") {
        set title "Peak memory of the whole process against model size"; set ylabel "peak resident memory (MB), log scale"
    }
    guide = series."/scaling-".measure."-guides"
    each = series."/scaling-".measure."-"
    # Brute force builds nothing: the build plot has no line for it (a point far off the axes instead).
    # Its runs on the larger models are sampled on a coarser grid: open points (frame: scaled up, an
    # extrapolation; memory: the peak of the smaller frame), filled where the whole frame was measured.
    brute = (measure eq "build") ? series."/scaling-frame-none" : each."none"
    sampled = (measure eq "build") ? "" : (measure eq "frame" ? "sampled (extrapolated)" : "sampled frame")
    plot brute using 1:(measure eq "build" ? NaN : $2) title (measure eq "build" ? "" : "brute force") with lines ls 1, \
         brute using 1:(measure eq "build" || $3 > 1 ? NaN : $2) notitle with points ls 1, \
         brute using 1:(measure eq "build" || $3 == 1 ? NaN : $2) title (measure eq "build" ? "" : "brute force, ".sampled) \
             with points pt 6 ps 1.0 lw 2 lc rgb c_none, \
         each."bvh-median" using 1:2 title "BVH, median split" with linespoints ls 3, \
         each."bvh-sah" using 1:2 title "BVH, SAH" with linespoints ls 4, \
         each."fast" using 1:2 title "chapter 11's BVH" with linespoints ls 5, \
         each."kd-sah" using 1:2 title "kd-tree (SAH)" with linespoints ls 2, \
         guide using 1:2 title "guide: n log n" with lines lw 1 lc rgb "black" dt 3, \
         guide using 1:3 title "guide: n" with lines lw 1 lc rgb "black" dt 2
}

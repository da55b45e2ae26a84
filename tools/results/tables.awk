# tables.awk: turns the CSV files of make results into the Markdown tables of docs/results.md.
#
#   awk -F, -v table=NAME -f tools/results/tables.awk FILE.csv
#
# NAME is one of: seed (reads scene1.csv bunny.csv teapot-5k.csv large.csv together), machine, scene1, sweep (bunny.csv or teapot-5k.csv), large, scaling-build,
# scaling-frame, scaling-memory, threads, whole (whole.csv), accel-MODEL (accel.csv; MODEL as in its model column).
# Prints the table alone; tools/results/publish.sh puts it between the page's markers. Rows measured
# on a coarser grid and scaled up (scale > 1) are marked with an asterisk.
#
# NAME prose reads every CSV given (machine, scene1, bunny, teapot-5k, large, scaling and, when there,
# accel) and prints the numbers the page's sentences quote, one "NAME VALUE" a line; publish.sh puts
# each between its inline markers, <!--n:NAME-->VALUE<!--/n-->.

# 1234567.8 -> "1,234,568" (a whole number with thousands separators).
function thousands(x,    s, out) {
    s = sprintf("%.0f", x)
    out = ""
    while (length(s) > 3) {
        out = "," substr(s, length(s) - 2) out
        s = substr(s, 1, length(s) - 3)
    }
    return s out
}

# A time in seconds with three significant digits (at least one decimal for values >= 100).
function seconds(x) {
    if (x == "") return "–"
    if (x >= 100) return thousands(x)
    if (x >= 10) return sprintf("%.1f", x)
    if (x >= 1) return sprintf("%.2f", x)
    if (x >= 0.1) return sprintf("%.3f", x)
    return sprintf("%.4f", x)
}

function ratio(a, b) { return (b <= 0) ? "–" : (a / b >= 100) ? thousands(a / b) " ×" : sprintf("%.1f ×", a / b) }

# A number with `decimals` decimals, or a whole number with thousands separators from 10,000 on; "–"
# for an empty field.
function number(x, decimals) {
    if (x == "") return "–"
    return (x >= 10000) ? thousands(x) : sprintf("%." decimals "f", x)
}

# The label of a structure's machine name.
function structure_name(s) {
    if (s == "none") return "brute force"
    if (s == "kd-seed") return "kd-tree, seed's rule"
    if (s == "kd-sah") return "kd-tree, SAH"
    if (s == "bvh-median") return "BVH, median split (seed's rule)"
    if (s == "bvh-sah") return "BVH, SAH"
    if (s == "fast") return "chapter 11's BVH (its default rung)"
    if (s == "povray") return "POV-Ray 3.7"
    return s
}

# Fields by header name: col["cpu_best_s"] is the field number.
FNR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }

function f(name) { return $(col[name]) }

# ---- the seed's numbers beside ours: scene1.csv bunny.csv teapot-5k.csv large.csv -------------------
table == "seed" {
    s = f("structure"); name = f("scene"); depth = f("depth")
    if (name == "scene1" && s == "none") { if (f("width") > big_w) big_w = f("width"); s1[f("width"), depth] = f("cpu_best_s") }
    if ((name == "bunny" || name == "teapot-5k") && (s == "none" || s == "bvh-sah" || s == "bvh-median")) sw[name, depth, s] = f("cpu_best_s")
    if (name == "teapot-346k") { lt[s] = f("cpu_best_s"); ltests[s] = f("triangle_tests"); lpixels = f("width") * f("height") }
    next
}

# ---- the numbers the prose quotes: every CSV, told apart by file name -----------------------------------
table == "prose" {
    file = FILENAME; sub(/.*\//, "", file); sub(/\.csv$/, "", file)
    if (file == "machine") { if ($1 == "minutes") minutes = $2; next }
    if (file == "accel") {
        if (f("structure") == "bvh-sah") predicted_over_measured[f("model")] = quotient(f("sah_cost"), f("nodes_per_ray") + f("tri_per_ray"))
        next
    }
    if (file == "scaling") {
        n = f("triangles"); s = f("structure")
        if (!(s in first_n) || n + 0 < first_n[s]) { first_n[s] = n + 0; first_frame[s] = f("render_s") }
        if (!(s in last_n) || n + 0 > last_n[s]) { last_n[s] = n + 0; last_frame[s] = f("render_s"); last_memory[s] = f("peak_rss_mb") }
        build_ms[n, s] = f("build_ms"); scaling_sizes[n] = 1
        next
    }
    s = f("structure"); depth = f("depth")
    if (file == "scene1") {
        key = f("width") "x" f("height") " " f("lights")
        if (f("width") * f("height") > s1_pixels) { s1_pixels = f("width") * f("height"); s1_big = f("width") "x" f("height") }
        s1[key, depth, s] = f("cpu_best_s"); s1_keys[f("width") "x" f("height")] = 1
        next
    }
    if (file == "bunny" || file == "teapot-5k") {
        t[file, depth, s] = f("cpu_best_s"); tests[file, depth, s] = f("triangle_tests")
        if (s == "povray") { agree_max = max(agree_max, f("povray_max_diff")); over2_max = max(over2_max, f("povray_pixels_over_2")) }
        sweep_pixels = f("width") * f("height")
        next
    }
    if (file == "large") {
        lt[s] = f("cpu_best_s"); ltests[s] = f("triangle_tests"); lbuild[s] = f("build_ms")
        if (s == "none") large_rays = f("rays")
        if (s == "povray") { large_agree = f("povray_max_diff"); large_over2 = f("povray_pixels_over_2") }
        lpixels = f("width") * f("height")
        next
    }
    next
}

# ---- machine.csv ---------------------------------------------------------------------------------------
table == "machine" { kv_key[++kv_n] = $1; kv_value[kv_n] = $2; next }

# ---- scene1.csv: brute force by depth, four configurations; the structures at 800x400, one light --------
table == "scene1" {
    key = f("width") "x" f("height") " " f("lights")
    depth = f("depth")
    depths[depth] = 1
    t[key, depth, f("structure")] = f("cpu_best_s")
    if (f("structure") == "povray") agree[key, depth] = f("povray_max_diff")
    if (!(key in seen)) { seen[key] = 1; order[++n_keys] = key; w[key] = f("width"); h[key] = f("height") }
    next
}

# ---- bunny.csv, teapot-5k.csv -------------------------------------------------------------------------
table == "sweep" {
    depth = f("depth")
    depths[depth] = 1
    s = f("structure")
    t[depth, s] = f("cpu_best_s")
    tests[depth, s] = f("triangle_tests")
    if (s == "none") { rays[depth] = f("rays"); scaled[depth] = (f("scale") > 1) }
    if (s == "povray") agree[depth] = f("povray_max_diff") " / " f("povray_pixels_over_2")
    size = f("width") " × " f("height")
    next
}

# ---- large.csv ----------------------------------------------------------------------------------------
table == "large" {
    s = f("structure")
    order[++n_rows] = s
    best[s] = f("cpu_best_s"); median[s] = f("cpu_median_s"); build[s] = f("build_ms")
    tests[s] = f("triangle_tests"); peak[s] = f("peak_rss_mb"); scale[s] = f("scale")
    pixels = f("width") * f("height")
    mw[s] = f("measured_width"); mh[s] = f("measured_height")
    if (s == "povray") { large_agree = f("povray_max_diff"); large_over2 = f("povray_pixels_over_2") }
    next
}

# ---- scaling.csv ---------------------------------------------------------------------------------------
table ~ /^scaling-/ {
    n = f("triangles"); s = f("structure")
    if (!(n in seen_n)) { seen_n[n] = 1; sizes[++n_sizes] = n }
    if (!(s in seen_s)) { seen_s[s] = 1; structs[++n_structs] = s }
    v[n, s] = (table == "scaling-build") ? f("build_ms") : (table == "scaling-frame") ? f("render_s") : f("peak_rss_mb")
    scaled[n, s] = (f("scale") > 1)
    next
}

# ---- threads.csv ---------------------------------------------------------------------------------------
table == "threads" {
    p = f("program"); n = f("threads")
    rows[++n_rows] = p SUBSEP n
    rb[p, n] = f("render_best_s"); rm[p, n] = f("render_median_s"); wb[p, n] = f("wall_best_s"); wm[p, n] = f("wall_median_s")
    runs = f("runs"); cores = f("cores_online"); size = f("width") " × " f("height")
    next
}

# ---- whole.csv: the whole program against POV-Ray, paired runs (tools/results/whole.sh) --------------
table == "whole" {
    whole_lines[++n_whole] = "| " f("threads") " | " f("width") " × " f("height") " | " seconds(f("ours_wall_median_s")) " s | " \
        seconds(f("povray_wall_median_s")) " s | **" sprintf("%.1f ×", f("ratio_median")) "** | " \
        sprintf("%.1f – %.1f", f("ratio_min"), f("ratio_max")) " | " ratio(f("povray_cpu_median_s"), f("ours_cpu_median_s")) " | " \
        f("pairs") " | " f("load_before") " / " f("load_after") " |"
    next
}

# ---- accel.csv ----------------------------------------------------------------------------------------
table ~ /^accel-/ {
    if ("accel-" f("model") != table) next
    line = "| " f("structure") (f("sampled_rows") != "" ? " (sampled, " f("sampled_rows") " rows)" : "")
    line = line " | " number(f("build_ms"), 1) " | " number(f("frame_ms"), 1) " | " number(f("mrays_per_s"), 2)
    line = line " | " number(f("tri_per_ray"), 2) " | " number(f("nodes_per_ray"), 2) " | " number(f("tri_per_camera_ray"), 2)
    line = line " | " number(f("sah_cost"), 1) " | " number(f("frame_over_embree"), 2) " | " number(f("build_over_embree"), 2)
    line = line " | " number(f("pixels_differing"), 0) " |"
    accel_lines[++n_accel] = line
    next
}

function max(a, b) { return (a == "" || b + 0 > a + 0) ? b + 0 : a + 0 }

# a / b, or "" when b is not positive (a quick run's tiny build can take 0.0 ms).
function quotient(a, b) { return (b + 0 > 0) ? a / b : "" }

# widen(x) grows the span [lo, hi] (globals, "" when empty) to hold x; an empty x is left out.
function widen(x) {
    if (x == "") return
    if (lo == "" || x < lo) lo = x
    if (hi == "" || x > hi) hi = x
}

# The span [lo, hi] as "lo to hi", each with `format` (one number when both print alike; "–" when
# empty); with thousands = 1, as whole numbers with thousands separators.
function span(format, with_thousands,    a, b) {
    if (lo == "") return "–"
    a = with_thousands ? thousands(lo) : sprintf(format, lo)
    b = with_thousands ? thousands(hi) : sprintf(format, hi)
    return (a == b) ? a : a " to " b
}

# Widens the span by a / b of the bunny and teapot sweeps, every depth; a and b are structures, of
# times (what = "t") or of triangle tests.
function widen_sweeps(what, a, b,    m, d, name) {
    for (m = 1; m <= 2; m++) {
        name = (m == 1) ? "bunny" : "teapot-5k"
        for (d = 1; d <= 5; d++)
            widen(what == "t" ? quotient(t[name, d, a], t[name, d, b]) : quotient(tests[name, d, a], tests[name, d, b]))
    }
}

END {
    if (table == "prose") {
        # The large model's triangles (scenes/models/teapot-346k.ply): large.csv does not carry them.
        large_triangles = 349872
        print "minutes " minutes
        # scene 1 at its larger size, one light: time at depth 5 against depth 1; a second light
        big1 = s1_big " 1"
        print "s1-brute-growth " sprintf("%+.0f %%", 100 * (quotient(s1[big1, 5, "none"], s1[big1, 1, "none"]) - 1))
        print "s1-bvh-growth " sprintf("%+.0f %%", 100 * (quotient(s1[big1, 5, "bvh-sah"], s1[big1, 1, "bvh-sah"]) - 1))
        print "s1-povray-growth " sprintf("%+.0f %%", 100 * (quotient(s1[big1, 5, "povray"], s1[big1, 1, "povray"]) - 1))
        lo = hi = ""
        for (size in s1_keys) for (d = 1; d <= 5; d++) widen(quotient(s1[size " 2", d, "none"], s1[size " 1", d, "none"]))
        print "s1-two-lights " span("%.1f")
        # the bunny and the teapot
        lo = hi = ""; widen_sweeps("t", "none", "bvh-sah"); print "sweep-speedup " span("%.1f")
        lo = hi = ""; widen_sweeps("tests", "none", "bvh-sah"); print "sweep-tests-cut " span("", 1)
        lo = hi = ""; widen_sweeps("tests", "bvh-sah", "bvh-median")
        x = lo; lo = 1 - hi; hi = 1 - x
        print "sweep-sah-fewer " sprintf("%.0f to %.0f %%", 100 * lo, 100 * hi)
        lo = hi = ""; widen_sweeps("tests", "kd-sah", "bvh-sah"); print "sweep-kd-over-sah " span("%.1f")
        lo = hi = ""; widen_sweeps("t", "povray", "bvh-sah"); print "sweep-povray-over-bvh " span("%.1f")
        print "sweep-povray-max-diff " agree_max
        print "sweep-povray-over2 " over2_max
        print "sweep-pixels " thousands(sweep_pixels)
        print "depth-brute-bunny " sprintf("%.2f", quotient(t["bunny", 5, "none"], t["bunny", 1, "none"]))
        print "depth-brute-teapot " sprintf("%.2f", quotient(t["teapot-5k", 5, "none"], t["teapot-5k", 1, "none"]))
        lo = hi = ""
        for (m = 1; m <= 2; m++) for (k = 1; k <= 4; k++) {
            name = (m == 1) ? "bunny" : "teapot-5k"
            s = (k == 1) ? "kd-sah" : (k == 2) ? "bvh-median" : (k == 3) ? "bvh-sah" : "povray"
            widen(quotient(t[name, 5, s], t[name, 1, s]))
        }
        print "depth-others " span("%.2f")
        # the large model; the seed's numbers as in the seed table: 6,930 s, 62 s, 99,250,516 tests, 112 x
        all_pairs = large_rays * large_triangles
        print "large-seed-over-median-tests " sprintf("%.0f", quotient(99250516, ltests["bvh-median"]))
        print "large-sah-fewer " sprintf("%.0f %%", 100 * (1 - quotient(ltests["bvh-sah"], ltests["bvh-median"])))
        print "large-speedup-over-seed " sprintf("%.1f", quotient(lt["none"], lt["bvh-median"]) / 112)
        print "large-brute-over-seed " sprintf("%.1f", quotient(6930, lt["none"]))
        print "large-all-pairs " sprintf("%.1f", all_pairs / 1e9)
        print "large-brute-tests " sprintf("%.1f", ltests["none"] / 1e9)
        print "large-culled " sprintf("%.0f %%", 100 * (1 - quotient(ltests["none"], all_pairs)))
        print "large-cull-factor " sprintf("%.1f", quotient(all_pairs, ltests["none"]))
        print "large-rest-factor " sprintf("%.1f", quotient(quotient(6930, lt["none"]), quotient(all_pairs, ltests["none"])))
        print "large-ns-per-test " sprintf("%.1f", 1e9 * quotient(lt["none"], ltests["none"]))
        print "large-bvh-over-seed " sprintf("%.0f", quotient(62, lt["bvh-median"]))
        lo = hi = ""; widen(quotient(lt["none"], lt["bvh-sah"])); widen(quotient(lt["none"], lt["bvh-median"]))
        print "large-speedups " span("", 1)
        print "large-median-s " seconds(lt["bvh-median"]) " s"
        print "large-sah-s " seconds(lt["bvh-sah"]) " s"
        print "large-sah-build-over-median " sprintf("%.1f", quotient(lbuild["bvh-sah"], lbuild["bvh-median"]))
        lo = hi = ""; widen(quotient(ltests["bvh-sah"], lpixels)); widen(quotient(ltests["bvh-median"], lpixels))
        print "large-tests-per-pixel " span("%.1f")
        print "large-povray-max-diff " large_agree
        print "large-povray-over2 " large_over2
        # the scaling teapots
        print "scaling-model-growth " thousands(quotient(last_n["none"], first_n["none"]))
        print "scaling-brute-growth " thousands(quotient(last_frame["none"], first_frame["none"]))
        lo = hi = ""
        for (k = 1; k <= 4; k++) {
            s = (k == 1) ? "kd-sah" : (k == 2) ? "bvh-median" : (k == 3) ? "bvh-sah" : "fast"
            widen(quotient(last_frame[s], first_frame[s]))
        }
        print "scaling-structures-growth " span("%.1f")
        lo = hi = ""
        for (n in scaling_sizes) widen(quotient(build_ms[n, "bvh-sah"], build_ms[n, "bvh-median"]))
        print "scaling-sah-build-over-median " span("%.1f")
        for (k = 1; k <= 4; k++) { # bytes a triangle at the largest model (a megabyte here is 2^20 bytes)
            s = (k == 1) ? "none" : (k == 2) ? "kd-sah" : (k == 3) ? "bvh-sah" : "fast"
            print "scaling-bytes-" s " " sprintf("%.0f", quotient(last_memory[s] * 1048576, last_n[s]))
        }
        # the benchmark's SAH prediction against the measured cost (full runs only: accel.csv)
        lo = hi = ""
        for (model in predicted_over_measured) widen(predicted_over_measured[model])
        print "bench-sah-prediction " span("%.1f")
    } else if (table == "seed") {
        saving = 0; saving_median = 0; n_saving = 0
        for (m = 1; m <= 2; m++) {
            name = (m == 1) ? "bunny" : "teapot-5k"
            for (d = 1; d <= 5; d++) if (sw[name, d, "none"] > 0) {
                saving += 1 - sw[name, d, "bvh-sah"] / sw[name, d, "none"]
                saving_median += 1 - sw[name, d, "bvh-median"] / sw[name, d, "none"]
                n_saving++
            }
        }
        print "| | the seed (Java, its machine, 2020) | ours (C, this machine, one thread) |"
        print "|---|---:|---:|"
        print "| scene 1 without acceleration, depth 5 against depth 1 | +60 % | " sprintf("%+.0f %%", 100 * (s1[big_w, 5] / s1[big_w, 1] - 1)) " |"
        print "| time the BVH saves, average over the bunny and teapot runs | 90 % | " sprintf("%.1f %%", 100 * saving_median / n_saving) \
              " (median split, the seed's rule); " sprintf("%.1f %%", 100 * saving / n_saving) " (SAH) |"
        print "| large model, no structure | 6,930 s | " seconds(lt["none"]) " s* |"
        print "| large model, BVH (median split, the seed's rule) | 62 s | " seconds(lt["bvh-median"]) " s |"
        print "| large model, BVH (SAH) | – | " seconds(lt["bvh-sah"]) " s |"
        print "| speed-up of the BVH on the large model | 112 × | " ratio(lt["none"], lt["bvh-median"]) " (median split); " ratio(lt["none"], lt["bvh-sah"]) " (SAH) |"
        print "| triangle tests with the BVH, large model | 99,250,516 | " thousands(ltests["bvh-median"]) " (median split); " thousands(ltests["bvh-sah"]) " (SAH) |"
        print "| triangle tests per pixel with the BVH | 206.8 | " sprintf("%.2f", ltests["bvh-median"] / lpixels) " (median split); " sprintf("%.2f", ltests["bvh-sah"] / lpixels) " (SAH) |"
        print "| POV-Ray 3.7 ÷ chapter 11, large model, whole process | – | " ratio(lt["povray"], lt["fast"]) " |"
    } else if (table == "machine") {
        print "| | |"
        print "|---|---|"
        for (i = 1; i <= kv_n; i++) print "| " kv_key[i] " | " kv_value[i] " |"
    } else if (table == "scene1") {
        line = "| depth |"
        sep = "|---:|"
        for (k = 1; k <= n_keys; k++) {
            split(order[k], parts, " ")
            line = line " " w[order[k]] " × " h[order[k]] ", " parts[2] (parts[2] == 1 ? " light" : " lights") " |"
            sep = sep "---:|"
        }
        big = order[n_keys - 1]  # the largest size, one light
        split(big, parts, " ")
        sub(/x/, " × ", parts[1])
        line = line " " parts[1] ", 1 light, BVH-SAH | " parts[1] ", 1 light, POV-Ray | POV-Ray's largest difference |"
        sep = sep "---:|---:|---:|"
        print "Brute force (processor time, seconds) unless the column says otherwise:"
        print ""
        print line
        print sep
        for (d = 1; d in depths; d++) {
            line = "| " d " |"
            for (k = 1; k <= n_keys; k++) line = line " " seconds(t[order[k], d, "none"]) " |"
            line = line " " seconds(t[big, d, "bvh-sah"]) " | " seconds(t[big, d, "povray"]) " | " agree[big, d] " |"
            print line
        }
        line = "| depth 5 ÷ depth 1 |"
        for (k = 1; k <= n_keys; k++) line = line " " ratio(t[order[k], 5, "none"], t[order[k], 1, "none"]) " |"
        print line " " ratio(t[big, 5, "bvh-sah"], t[big, 1, "bvh-sah"]) " | " ratio(t[big, 5, "povray"], t[big, 1, "povray"]) " | |"
    } else if (table == "sweep") {
        print "| depth | rays | brute force | kd-tree (SAH) | BVH, median | BVH, SAH | POV-Ray | brute ÷ BVH-SAH | tests, brute force | tests, kd-tree | tests, BVH median | tests, BVH-SAH | POV-Ray's largest difference / pixels over 2 |"
        print "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        for (d = 1; d in depths; d++) {
            mark = scaled[d] ? "*" : ""
            print "| " d " | " thousands(rays[d]) " | " seconds(t[d, "none"]) mark " | " seconds(t[d, "kd-sah"]) " | " \
                seconds(t[d, "bvh-median"]) " | " seconds(t[d, "bvh-sah"]) " | " seconds(t[d, "povray"]) " | " \
                ratio(t[d, "none"], t[d, "bvh-sah"]) " | " thousands(tests[d, "none"]) mark " | " thousands(tests[d, "kd-sah"]) " | " \
                thousands(tests[d, "bvh-median"]) " | " thousands(tests[d, "bvh-sah"]) " | " agree[d] " |"
        }
    } else if (table == "large") {
        print "| structure | processor time, best | median | build | triangle tests | per pixel | peak memory | brute force ÷ this |"
        print "|---|---:|---:|---:|---:|---:|---:|---:|"
        for (i = 1; i <= n_rows; i++) {
            s = order[i]
            name = structure_name(s)
            if (scale[s] > 1) name = name " (sampled " mw[s] " × " mh[s] ", scaled up)*"
            if (s == "povray") name = name " (its picture: " large_over2 " pixels more than 2 levels from ours, the worst " large_agree ")"
            print "| " name " | " seconds(best[s]) " s | " seconds(median[s]) " s | " \
                (build[s] == "" ? "–" : sprintf("%.0f ms", build[s])) " | " (tests[s] == "" ? "–" : thousands(tests[s])) " | " \
                (tests[s] == "" ? "–" : tests[s] / pixels >= 1000 ? thousands(tests[s] / pixels) : sprintf("%.2f", tests[s] / pixels)) " | " sprintf("%.0f MB", peak[s]) " | " \
                (s == "none" ? "1 ×" : ratio(best["none"], best[s])) " |"
        }
        print "| the seed: no structure (Java, its machine) | 6,930 s | | | | | | 1 × |"
        print "| the seed: its BVH, median split | 62 s | | | 99,250,516 | 206.8 | | 112 × |"
    } else if (table ~ /^scaling-/) {
        line = "| triangles |"
        sep = "|---:|"
        for (j = 1; j <= n_structs; j++) {
            if (table == "scaling-build" && structs[j] == "none") continue
            line = line " " structure_name(structs[j]) " |"
            sep = sep "---:|"
        }
        print line
        print sep
        for (i = 1; i <= n_sizes; i++) {
            line = "| " thousands(sizes[i]) " |"
            for (j = 1; j <= n_structs; j++) {
                s = structs[j]
                if (table == "scaling-build" && s == "none") continue
                x = v[sizes[i], s]
                cell = (table == "scaling-build") ? sprintf("%.1f", x) : (table == "scaling-frame") ? seconds(x) : sprintf("%.1f", x)
                line = line " " cell (scaled[sizes[i], s] ? "*" : "") " |"
            }
            print line
        }
    } else if (table == "threads") {
        print "| program | threads | render, best | render, median | speed-up (best) | whole process (wall), best | median |"
        print "|---|---:|---:|---:|---:|---:|---:|"
        for (i = 1; i <= n_rows; i++) {
            split(rows[i], pn, SUBSEP)
            p = pn[1]; n = pn[2]
            print "| " p " | " n " | " seconds(rb[p, n]) " s | " seconds(rm[p, n]) " s | " ratio(rb[p, 1], rb[p, n]) " | " \
                seconds(wb[p, n]) " s | " seconds(wm[p, n]) " s |"
        }
    } else if (table == "whole") {
        print "| threads, each side | picture | chapter 11 (default rung), wall, median | POV-Ray 3.7, wall, median | POV-Ray ÷ chapter 11, median of the pairs | smallest – largest | processor time, POV-Ray ÷ chapter 11 (medians) | pairs | load average, before / after |"
        print "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        for (i = 1; i <= n_whole; i++) print whole_lines[i]
    } else if (table ~ /^accel-/) {
        print "| structure | build ms | frame ms | Mrays/s | tri/ray | nodes/ray | tri/cam | SAH cost | frame/E | build/E | pixels unlike BVH-SAH's |"
        print "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        for (i = 1; i <= n_accel; i++) print accel_lines[i]
    }
}

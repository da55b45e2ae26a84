# bench/bench.mk: the acceleration benchmarks of chapters 9, 10, 11 and 16. A GNU make fragment included from
# the top-level Makefile, which defines CC, BUILD, CFLAGS, LDFLAGS, LDLIBS and the rule that makes
# $(BUILD)/common/%.o from common/%.c.
#
#   make bench-accel   build $(BUILD)/bench_accel and run it on the big teapot and the bunny, with Intel
#                      Embree 3 as the yardstick (installs Debian's libembree-dev if it is missing)
#   make bench-memory  peak memory of chapters 10 and 11 (its default rung, then rungs 1 to 9) per triangle, on a teapot of about
#                      4 million triangles made by tools/models/teapot.c into out/bench/; rung 10 builds
#                      rung 8's tree and holds nothing per triangle of its own, so its peak is rung 8's
#   make bench-instances chapter 16's two-level BVH against Embree 3's instances on the forest (10,000
#                      instanced teapots and bunnies, written by tools/models/forest.c into out/bench/)
#   make bench-paths   chapter 15's path tracer against Blender's Cycles at equal noise on its Cornell box, on
#                      1 and 2 threads (tools/cycles/bench_paths.py; installs Debian's blender if it is
#                      missing): the time each needs to reach the same RMSE, and paths a second
#   make bench         every benchmark: bench-accel, then bench-memory, then bench-instances, then bench-paths
#   make bench-profile instructions, cache misses and mispredicted branches per ray for rungs 1, 5 to 9
#                      and Embree on the teapot frame (bench/profile.sh, under valgrind: ten minutes or so)
#
# $(BUILD)/bench_accel --csv FILE also writes its tables' rows as CSV (see bench_accel.c), and --size WxH
# traces a smaller frame; make test builds it too, for tests/test_bench_csv.c.
#
# bench/embree_ref.c is compiled in only when /usr/include/embree3/rtcore.h exists. So the bench-accel
# recipe installs the package first and only then makes the program, in a second make that sees the
# header. The objects of the two variants (with and without Embree) live in different directories, and
# the program depends on a file named after the variant it was linked as, $(BUILD)/bench/variant-embree
# or variant-plain, which only one of at a time exists: so after make test built the plain program on a
# machine without Embree, make bench, which installs Embree, links the Embree one (tests/test_build.c).

BENCH_MODELS := scenes/models/teapot-346k.ply scenes/models/bunny.ply
BENCH_MODULES := aabb clock big_alloc bvh bvh_check fast_bvh fast_bvh_eight fast_bvh_lean fast_bvh_build fast_bvh_packet float_triangle kdtree kdtree_check triangle triangle_syntax stats mesh mesh_read mesh_ply mesh_obj mesh_load infile camera
# Embree's header, when it is installed (`make BENCH_EMBREE= ...` builds the plain variant anyway).
BENCH_EMBREE := $(wildcard /usr/include/embree3/rtcore.h)
BENCH_VARIANT := $(if $(BENCH_EMBREE),embree,plain)
BENCH_SOURCES := bench/bench_accel.c $(if $(BENCH_EMBREE),bench/embree_ref.c)
BENCH_OBJECTS := $(patsubst bench/%.c,$(BUILD)/bench/$(BENCH_VARIANT)/%.o,$(BENCH_SOURCES))
BENCH_CFLAGS := $(if $(BENCH_EMBREE),-DWHITTED_EMBREE)
BENCH_LDLIBS := $(if $(BENCH_EMBREE),-lembree3)

.PHONY: bench bench-accel bench-memory bench-profile bench-instances bench-paths

## make bench          every benchmark: make bench-accel, then make bench-memory, then make bench-instances,
##                     then make bench-paths
bench: bench-accel bench-memory bench-instances bench-paths

## make bench-accel    the kd-tree, the BVH and chapter 11's rungs against Intel Embree 3, on the big
##                     teapot and the bunny (installs libembree-dev first)
bench-accel: $(BENCH_MODELS) | deps
	tools/build/install-deps.sh bench
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(BUILD)/bench_accel
	$(BUILD)/bench_accel $$([ -e /usr/include/embree3/rtcore.h ] && echo --embree) $(BENCH_MODELS)

$(BUILD)/bench/$(BENCH_VARIANT)/%.o: bench/%.c | $(BUILD)/bench/$(BENCH_VARIANT) deps
	$(CC) $(CFLAGS) $(BENCH_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/bench/$(BENCH_VARIANT):
	mkdir -p $@

$(BUILD)/bench/variant-$(BENCH_VARIANT): | $(BUILD)/bench/$(BENCH_VARIANT)
	rm -f $(BUILD)/bench/variant-*
	touch $@

$(BUILD)/bench_accel: $(BENCH_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(BENCH_MODULES))) \
        $(BUILD)/bench/variant-$(BENCH_VARIANT)
	$(CC) $(LDFLAGS) $(filter %.o,$^) -o $@ $(LDLIBS) $(BENCH_LDLIBS)

-include $(wildcard $(BUILD)/bench/*/*.d)

## make bench-profile  where a ray's time goes, rung by rung and in Embree: instructions, cache misses and
##                     mispredicted branches per ray on the teapot frame, counted by valgrind
##                     (bench/profile.sh; ten minutes or so)
bench-profile: scenes/models/teapot-346k.ply | deps
	tools/build/install-deps.sh profile
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(BUILD)/bench_accel
	bench/profile.sh $(BUILD)/bench_accel scenes/models/teapot-346k.ply

# ---- memory: peak RSS per triangle on a big teapot ----------------------------------------------
BENCH_MEMORY_TRIANGLES := 4000000
BENCH_MEMORY_DIR := out/bench
BENCH_MEMORY_SCENE := $(BENCH_MEMORY_DIR)/teapot-4m.scene

$(BUILD)/peak_rss: bench/peak_rss.c | $(BUILD)/bench/$(BENCH_VARIANT) deps
	$(CC) $(CFLAGS) $< -o $@

$(BENCH_MEMORY_DIR)/teapot-4m.ply: $(MODELS_TEAPOT)
	@mkdir -p $(@D)
	$(MODELS_TEAPOT) --triangles $(BENCH_MEMORY_TRIANGLES) $(@:.ply=.tmp.ply) && mv $(@:.ply=.tmp.ply) $@

# A small picture (64 x 48) on one thread: the memory is the scene's, the structure's and the build's.
$(BENCH_MEMORY_SCENE): $(BENCH_MEMORY_DIR)/teapot-4m.ply
	printf '%s\n' 'camera eye 0 2.5 9  target 0 1 0  fov 36' 'image 64 48' 'light position -5 8 6  colour 1 1 1' \
	    'material china colour 0.35 0.55 0.85 ambient 0.1 diffuse 0.7' 'mesh teapot-4m.ply material china' >$@

## make bench-memory   peak memory per triangle of chapters 10 and 11 (rungs 1 to 9; rung 10 traces rung
##                     9's tree, so its peak is rung 9's) on a teapot of about 4 million triangles
bench-memory: $(BUILD)/peak_rss $(BUILD)/chapter-10 $(BUILD)/chapter-11 $(BENCH_MEMORY_SCENE)
	@triangles=$$(awk '/^element face/ { print $$3; exit }' $(BENCH_MEMORY_DIR)/teapot-4m.ply); \
	echo "peak memory on $(BENCH_MEMORY_SCENE) ($$triangles triangles, 64x48, 1 thread):"; \
	$(BUILD)/peak_rss $$triangles "chapter 10, BVH-SAH" $(BUILD)/chapter-10 $(BENCH_MEMORY_SCENE) --threads 1 --quiet \
	    -o $(BENCH_MEMORY_DIR)/memory.png && \
	$(BUILD)/peak_rss $$triangles "chapter 11, the default rung" \
	    $(BUILD)/chapter-11 $(BENCH_MEMORY_SCENE) --threads 1 --quiet -o $(BENCH_MEMORY_DIR)/memory.png && \
	for rung in 1 2 3 4 5 6 7 8 9; do \
	    $(BUILD)/peak_rss $$triangles "chapter 11, rung $$rung" $(BUILD)/chapter-11 $(BENCH_MEMORY_SCENE) --threads 1 \
	        --quiet --rung $$rung -o $(BENCH_MEMORY_DIR)/memory.png || exit 1; \
	done; \
	$(BUILD)/peak_rss $$triangles "chapter 11, --accel none (scene and gather)" $(BUILD)/chapter-11 \
	    $(BENCH_MEMORY_SCENE) --threads 1 --quiet --accel none --width 1 --height 1 -o $(BENCH_MEMORY_DIR)/memory.png

# ---- instances: chapter 16's forest against Embree's instances ----------------------------------
BENCH_FOREST := $(BENCH_MEMORY_DIR)/forest.scene
# The same two objects placed twice: the baseline of the memory per instance.
BENCH_FOREST_BASE := $(BENCH_MEMORY_DIR)/forest-2.scene
BENCH_INSTANCES_OBJECTS := $(addprefix $(BUILD)/bench/embree/,bench_instances.o embree_instances.o embree_ref.o)

# The forests name the models as seen from out/bench/.
$(BENCH_FOREST): $(MODELS_FOREST)
	@mkdir -p $(@D)
	$(MODELS_FOREST) --models ../../scenes/models $@

$(BENCH_FOREST_BASE): $(MODELS_FOREST)
	@mkdir -p $(@D)
	$(MODELS_FOREST) --instances 2 --models ../../scenes/models $@

# Only made by bench-instances, after Embree is installed (BENCH_VARIANT is then embree).
$(BUILD)/bench_instances: $(BENCH_INSTANCES_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(MODULES_16)))
	$(CC) $(LDFLAGS) $(filter %.o,$^) -o $@ $(LDLIBS) -lembree3

## make bench-instances chapter 16's instances (a BVH per object, one over the instances) against Embree
##                     3's (rtcNewGeometry(RTC_GEOMETRY_TYPE_INSTANCE)) on the forest: 10,000 instanced
##                     teapots and bunnies, 1.77 billion triangles (installs libembree-dev first); then
##                     chapter 16 renders it, and the memory per instance of each: the peak RSS with the
##                     forest less that with a forest of two instances of the same objects, over N - 2
bench-instances: $(BENCH_MODELS) $(BENCH_FOREST) $(BENCH_FOREST_BASE) $(BUILD)/peak_rss $(BUILD)/chapter-16 | deps
	tools/build/install-deps.sh bench
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(BUILD)/bench_instances
	$(BUILD)/bench_instances $(BENCH_FOREST)
	$(BUILD)/chapter-16 $(BENCH_FOREST) --threads 1 -o $(BENCH_MEMORY_DIR)/forest.png
	@n=$$(grep -c '^instance ' $(BENCH_FOREST)); \
	echo "memory per instance: peak RSS with the forest's $$n instances less that with 2, over $$n - 2:"; \
	for run in "chapter 16, 800x600, 1 thread:$(BUILD)/chapter-16 --threads 1 --quiet -o $(BENCH_MEMORY_DIR)/memory.png" \
	           "ours, the two levels alone:$(BUILD)/bench_instances --only ours --repeats 1" \
	           "Embree 3:$(BUILD)/bench_instances --only embree --repeats 1"; do \
	    label=$${run%%:*}; command=$${run#*:}; \
	    full=$$($(BUILD)/peak_rss --kilobytes $$command $(BENCH_FOREST)) && \
	    base=$$($(BUILD)/peak_rss --kilobytes $$command $(BENCH_FOREST_BASE)) || exit 1; \
	    awk -v label="$$label" -v full=$$full -v base=$$base -v n=$$n 'BEGIN { \
	        printf "  %-30s %7.1f MB with %d, %6.1f MB with 2: %5.0f bytes per instance\n", \
	               label, full / 1024, n, base / 1024, (full - base) * 1024 / (n - 2) }'; \
	done

# ---- paths: chapter 15 against Cycles at equal noise --------------------------------------------
BENCH_PATHS_THREADS := 1 2
BENCH_PATHS_DIR := out/bench/paths

## make bench-paths    chapter 15's Cornell box drawn by chapter 15 and by Blender's Cycles at 16, 64 and 256
##                     paths a pixel, two seeds each, on 1 and then 2 threads: each one's RMSE, its cost
##                     a sample, the time each needs to reach the same RMSE and their ratio, and whether
##                     the two converge to the same picture (installs Debian's blender; a few minutes)
bench-paths: $(BUILD)/chapter-15 | deps
	tools/build/install-deps.sh cycles
	for threads in $(BENCH_PATHS_THREADS); do \
	    mkdir -p $(BENCH_PATHS_DIR)-$$threads && \
	    blender -b --factory-startup --python-exit-code 1 --python tools/cycles/bench_paths.py -- \
	        $(BUILD)/chapter-15 $$threads $(BENCH_PATHS_DIR)-$$threads >$(BENCH_PATHS_DIR)-$$threads/blender.log 2>&1 || \
	        { tail -5 $(BENCH_PATHS_DIR)-$$threads/blender.log; exit 1; }; \
	    cat $(BENCH_PATHS_DIR)-$$threads/report.txt; \
	done

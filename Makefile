# Makefile: builds the chapters of the whitted ray tracer, renders their scenes, runs the tests.
#
# `make help` lists every target: the lines starting with "## " above the rules, here and, where they
# are included, in the fragments (tools/models/models.mk, bench/bench.mk, fuzz/fuzz.mk,
# tools/results/results.mk).
#
# Every chapter links only the common/ modules introduced by chapters up to its own (MODULES_NN
# below), so a chapter that reaches for a later idea fails to link.

# ---- a student copy (make student) -------------------------------------------------------------
# The goals that need the model answers or every task done, or that would overwrite the reference files
# with the student's pictures: a student copy (tools/student.sh leaves .student-copy in it) refuses them
# with a sentence, and make help there leaves them out.
NOT_IN_HANDOUT := gallery test-long student references results figures test-accel-long rough-energy
ifneq ($(wildcard .student-copy),)
ifneq ($(filter $(NOT_IN_HANDOUT),$(MAKECMDGOALS)),)
$(error make $(filter $(NOT_IN_HANDOUT),$(MAKECMDGOALS)) is not part of the coursework copy: it needs the model \
answers or every task done, or it would overwrite the reference pictures. README.md lists your commands)
endif
endif

# ---- packages: Debian packages, installed when missing ------------------------------------------
# Every rule that compiles, and every goal that runs POV-Ray or gnuplot, has `deps` as an order-only
# prerequisite: before anything is built, tools/build/install-deps.sh installs what this run's goals
# need and is missing (nothing while the Makefile is only read, so make help and make clean install
# nothing). Building and rendering a chapter needs gcc and stb; the tests add Criterion, POV-Ray and
# gnuplot; make compare adds POV-Ray, make results POV-Ray and gnuplot. make bench and make fuzz install
# Embree and clang in their own recipes, before a second make that sees them; make web installs
# emscripten (and make test-web Chromium, its driver and Selenium) the same way. The rule is `deps`, at
# the end.
DEPS_NEEDS := build $(strip \
    $(if $(filter test test-long test-sanitize test-accel-long %run-tests %run-accel-long,$(MAKECMDGOALS)),test) \
    $(if $(filter compare,$(MAKECMDGOALS)),compare) $(if $(filter compare-cycles test-long,$(MAKECMDGOALS)),cycles) \
    $(if $(filter results,$(MAKECMDGOALS)),results) $(if $(filter test-farm test-long,$(MAKECMDGOALS)),farm))

# stb from the system, or else unpacked into .deps/ by install-deps.sh on a machine without root
# (linked statically from there, so the programs need nothing from .deps/ at run time). These are
# recursive variables, worked out when a recipe uses them, after the packages step.
STB_FROM_DEPS = $(or $(filter local,$(WHITTED_DEPS)),$(if $(shell pkg-config --exists stb 2>/dev/null && echo yes),,local))
STB_CFLAGS = $(if $(STB_FROM_DEPS),-I.deps/root/usr/include/stb,$(shell pkg-config --cflags stb))
STB_LIBS = $(if $(STB_FROM_DEPS),$(firstword $(wildcard .deps/root/usr/lib/*/libstb.a)),$(shell pkg-config --libs stb))

# ---- flags -------------------------------------------------------------------------------------
CC := gcc
SAN ?= 0
ifeq ($(SAN),1)
BUILD := build/san
OPT := -O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
TEST_OPT :=
DEBUG_INFO ?= -g
else
BUILD := build
OPT := -O2
TEST_OPT := -O1
# Line tables only (gdb's backtraces and breakpoints by line): full debug information (-g, for gdb to
# print variables: make clean, then make DEBUG_INFO=-g) makes compiling a third slower, and make test
# compiles everything. The sanitizer build keeps -g.
DEBUG_INFO ?= -g1
endif
# -ffp-contract=off: a*b - c*d is two rounded products and a rounded difference, never a fused
# multiply-add. The watertight triangle test relies on it (common/triangle.c); -std=c11 implies it in
# GCC, and saying it keeps it so under -std=gnu11 or on a machine with FMA.
# -Wno-psabi: GCC notes that 8-float vectors cross a call differently with AVX than without; ours
# (fast_bvh_packet.c) pass between static functions of one file only, so no such call crosses files.
# WERROR: warnings are errors; make check-N builds again with WERROR= to grade code that only warns.
WERROR = -Werror
CFLAGS = -std=c11 -D_DEFAULT_SOURCE $(DEBUG_INFO) $(OPT) -ffp-contract=off -Wall -Wextra $(WERROR) -Wno-psabi -fopenmp \
         -Icommon $(STB_CFLAGS)
LDFLAGS := $(OPT) -fopenmp
LDLIBS = $(STB_LIBS) -lm
CRITERION = $(shell pkg-config --cflags --libs criterion)

# ---- what each chapter introduces ----------------------------------------------------------------
MODULES_01 := clock stats camera image outfile infile png_palette text_escape name_index antialias area_light path_settings lens instance_syntax pigment_syntax sphere_syntax triangle_syntax plane_syntax box_syntax scene scene_scale scene_set povray render heatmap ray_budget cli
MODULES_02 := $(MODULES_01) sphere headlight
MODULES_03 := $(MODULES_02) big_alloc memory_budget triangle mesh mesh_read mesh_ply mesh_obj mesh_load scene_meshes
MODULES_04 := $(MODULES_03) plane
MODULES_05 := $(MODULES_04) aabb box world
MODULES_06 := $(MODULES_05) phong
MODULES_07 := $(MODULES_06) shadow
MODULES_08 := $(MODULES_07) interior whitted
MODULES_09 := $(MODULES_08) kdtree kdtree_check accel
MODULES_10 := $(MODULES_09) bvh bvh_check accel_bvh
MODULES_11 := $(MODULES_10) fast_bvh fast_bvh_eight fast_bvh_lean fast_bvh_build accel_fast_bvh fast_bvh_packet float_triangle
MODULES_12 := $(MODULES_11) sample_hash supersample
MODULES_13 := $(MODULES_12) soft_shadow thin_lens
MODULES_14 := $(MODULES_13) jpeg_decode image_map mesh_surface texture
MODULES_15 := $(MODULES_14) owen_sobol sampling emitter bsdf path_trace path_image path_program
MODULES_16 := $(MODULES_15) transform keyframes instance_bvh instances shutter
MODULES_17 := $(MODULES_16) microfacet rough_surface
CHAPTERS := 01-camera 02-sphere 03-triangle 04-plane 05-aabb 06-phong 07-shadows 08-recursion \
            09-kdtree 10-bvh 11-fast 12-antialias 13-distributed 14-textures 15-paths 16-instances 17-rough
# (with the modules of the chapters being written, so that their tests link before the chapter does)
ALL_MODULES := $(sort $(foreach c,$(CHAPTERS),$(MODULES_$(firstword $(subst -, ,$(c))))) $(MODULES_17))

chapter_number = $(firstword $(subst -, ,$(1)))
# The chapters' numbers without their leading zero (1 2 ... 17), for the chapter-N and check-N goals.
CHAPTER_NUMBERS := $(foreach c,$(CHAPTERS),$(patsubst 0%,%,$(firstword $(subst -, ,$(c)))))
chapter_dir = $(filter $(1)-%,$(CHAPTERS))

# The models the chapters' scenes name: the bunny is committed, the teapots are generated
# (tools/models/models.mk, included below).
SCENE_MODELS := scenes/models/teapot-5k.ply scenes/models/teapot-346k.ply scenes/models/teapot-5k-uv.ply
# The pictures chapter 14's scenes wrap over surfaces: drawn by tools/textures/draw_textures.c, never
# downloaded.
SCENE_TEXTURES := scenes/textures/globe.png scenes/textures/grid.png scenes/textures/grid.jpg
# What each chapter's scenes (scenes/NN-*.scene) name, meshes and pictures, as words NN:scenes/PATH (the
# paths in a scene are relative to scenes/); scene_files NN: chapter NN's. A chapter's program has them as
# order-only prerequisites, so that `make build/chapter-NN` leaves a program that can run its scene.
# (None, and no awk reading standard input, in a copy without scenes/.)
CHAPTER_SCENES := $(wildcard scenes/[0-9][0-9]-*.scene)
SCENE_FILES := $(if $(CHAPTER_SCENES),$(shell awk '$$1 == "mesh" { print substr(FILENAME, 8, 2) ":scenes/" $$2 } \
                            $$1 == "object" { print substr(FILENAME, 8, 2) ":scenes/" $$3 } \
                            $$1 == "pigment" { for (k = 3; k < NF; k++) if ($$k == "file") \
                                                   print substr(FILENAME, 8, 2) ":scenes/" $$(k + 1) }' \
                        $(CHAPTER_SCENES)))
scene_files = $(sort $(patsubst $(1):%,%,$(filter $(1):%,$(SCENE_FILES))))

.PHONY: deps all chapters exercises test test-long test-sanitize test-accel-long references compare compare-cycles gallery figures rough-energy \
        clean help check student $(foreach n,$(CHAPTER_NUMBERS),chapter-$(n) check-$(n))
.DEFAULT_GOAL := all
.SECONDEXPANSION:

## make all            build every chapter (build/chapter-NN), build/compare, build/figures and the models
##                     (what a plain `make` does)
all: $(foreach c,$(CHAPTERS),$(BUILD)/chapter-$(call chapter_number,$(c))) $(BUILD)/compare $(BUILD)/figures \
     $(BUILD)/assemble $(SCENE_MODELS) $(SCENE_TEXTURES)

# ---- compiling ---------------------------------------------------------------------------------
$(BUILD)/common/%.o: common/%.c | $(BUILD)/common deps
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/chapters/%.o: chapters/%/main.c | $(BUILD)/chapters deps
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

# The tests' own code is compiled with TEST_OPT: the work they time is in common/, compiled with OPT, and
# -O1 takes a third less time to compile them than -O2 (make test compiles all of them on a fresh clone).
$(BUILD)/tests/%.o: tests/%.c | $(BUILD)/tests deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(TEST_OPT) -Itests/support -MMD -MP -c $< -o $@

$(BUILD)/tools/%.o: tools/%.c | $(BUILD)/tools deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Itests/support -MMD -MP -c $< -o $@

$(BUILD)/common $(BUILD)/chapters $(BUILD)/tests $(BUILD)/tools out:
	mkdir -p $@

-include $(wildcard $(BUILD)/*/*.d $(BUILD)/*/*/*.d)

# One link rule per chapter, with exactly that chapter's modules (and, order-only, what its scenes name).
define chapter_rules
$(BUILD)/chapter-$(call chapter_number,$(1)): $(BUILD)/chapters/$(1).o \
        $(addprefix $(BUILD)/common/,$(addsuffix .o,$(MODULES_$(call chapter_number,$(1))))) \
        | $(call scene_files,$(call chapter_number,$(1)))
	tools/build/link-chapter.sh $(BUILD) $$(CC) $$(LDFLAGS) $$^ -o $$@ $$(LDLIBS)
endef
$(foreach c,$(CHAPTERS),$(eval $(call chapter_rules,$(c))))

# ---- running chapters --------------------------------------------------------------------------
# chapter-N for N = 1..17: explicit rules (GNU make skips pattern rules for phony targets). The program's
# rule makes the models and pictures the chapter's scenes name first.
## make chapter-N      build chapter N (1..17) and render its scene to out/chapter-NN.png
define run_chapter_rule
chapter-$(1): | out
	@n=$$$$(printf '%02d' $(1)); \
	if ! ls -d chapters/$$$$n-* >/dev/null 2>&1; then \
	    echo "chapter $(1) is not written yet (written: $(CHAPTERS))" >&2; exit 2; fi; \
	$$(MAKE) --no-print-directory $$(BUILD)/chapter-$$$$n $$(BUILD)/compare && ./$$(BUILD)/chapter-$$$$n
endef
$(foreach n,$(CHAPTER_NUMBERS),$(eval $(call run_chapter_rule,$(n))))

## make chapters       build and render every written chapter
chapters: $(foreach c,$(CHAPTERS),chapter-$(patsubst 0%,%,$(call chapter_number,$(c))))

# ---- models, benchmarks, fuzzing, make results: GNU make fragments -------------------------------
include tools/models/models.mk
include bench/bench.mk
include fuzz/fuzz.mk
include tools/results/results.mk
# The teapot generator is compiled too, so after the packages step (models.mk also works without this
# Makefile, so it cannot name `deps` itself).
$(MODELS_TEAPOT): | deps

# The textures: one run of the drawing program writes all three (into a temporary folder first, so an
# interrupted run leaves no half file under a real name).
$(BUILD)/draw-textures: tools/textures/draw_textures.c | $(BUILD)/tools deps
	$(CC) -std=c11 -D_DEFAULT_SOURCE -O2 -Wall -Wextra -Werror $(STB_CFLAGS) $< -o $@ $(STB_LIBS) -lm

$(SCENE_TEXTURES) &: $(BUILD)/draw-textures
	@mkdir -p scenes/textures/.tmp
	$(BUILD)/draw-textures scenes/textures/.tmp && mv scenes/textures/.tmp/* scenes/textures/ && rmdir scenes/textures/.tmp

# ---- tests -------------------------------------------------------------------------------------
TEST_SOURCES := $(wildcard tests/*.c tests/exercises/*.c tests/support/*.c)
TEST_OBJECTS := $(patsubst tests/%.c,$(BUILD)/tests/%.o,$(TEST_SOURCES))
# The picture comparison (and the box filter that averages a picture down, chapter 12): the tests', the grader's and build/compare's.
IMAGE_COMPARE_OBJECT := $(BUILD)/tests/support/image_compare.o $(BUILD)/tests/support/box_filter.o
# Chapter 15's statistical proofs: the tests' and the grader's (tests/support/path_proofs.c).
PATH_PROOFS_OBJECT := $(BUILD)/tests/support/path_proofs.o

# The tests and what they link: the modules, tests/support/, and the fuzzers' renderer check
# (fuzz/fuzz.mk), which tests/test_fuzz_regressions.c runs on the saved inputs.
$(BUILD)/run-tests: $(TEST_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES))) $(BUILD)/checks/check_process.o \
        $(BUILD)/fuzz/render_check.o $(BUILD)/fuzz/tiny_images.o
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS) $(CRITERION)

$(BUILD)/compare: $(BUILD)/tools/compare.o $(IMAGE_COMPARE_OBJECT) $(BUILD)/common/image.o $(BUILD)/common/outfile.o \
                  $(BUILD)/common/infile.o $(BUILD)/common/png_palette.o
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# The render farm's tile assembler (tools/farm/assemble.c, docs/farm.md).
$(BUILD)/assemble: $(BUILD)/tools/farm/assemble.o $(BUILD)/common/image.o $(BUILD)/common/infile.o $(BUILD)/common/outfile.o \
                   $(BUILD)/common/png_palette.o
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# The tests that take a minute or more run in make test-long, not make test: Criterion's "suite/test"
# patterns (`run-tests --filter`). Those that build patched copies of the tree (the gallery's faults,
# the coursework kit's student copy, the mutants), the results' quick run, the docs' commands run in a
# copy of the repository, the no-root install, the largest differential tests (thousands of
# triangles, meshes beyond float range, whole pictures by every structure and rung), and those that
# take three seconds or more of their own on one core: the damaged-mesh sweeps, the largest picture, linking every
# chapter with its own modules and with the modules before it, make bench after make test, make help
# and make clean in a copy, the soups of triangles, the sphere and the grids (make test keeps the
# bunny, the 5,000-triangle teapot and the float test's grazing rays), chapter 10's picture by 1, 2 and 4 threads
# (chapters 12 and 13 check their own in make test), the results page's staleness checks; and the
# proofs that the picture checks catch a planted fault (a wrong index of refraction, an extra trace
# level, a wrong grid or threshold, a hard shadow), while the checks themselves run in make test; rung
# 6 on meshes where a float step is the mesh's size (with the other float-range cases); chapter 12's
# grids of 2 and 4 against POV-Ray (make test compares the grid of 3 and the other methods); chapters
# 9 and 10 and POV-Ray on the watertight cube (make test keeps chapter 3's loop, the icosphere and the
# cube seen from its centre); the programs' output quoted in the walkthroughs, run again (make test keeps
# the proof that a changed counter is noticed); chapter 13's depth of field and its adaptive, circular
# and oriented lights against POV-Ray (make test compares its other lights and holds its focus to a
# reference); the glass of water against POV-Ray (make test holds it to its reference); jitter's
# unbiasedness where the grid aliases.
# Chapters 8, 10 and 11's agreement with POV-Ray is long too: make test holds each chapter's picture to
# its reference picture, which make test-long compares with POV-Ray's.
# make test and make test-long together run every test once; CI runs both (.ci/run).
LONG_TESTS := gallery/every_fault_is_caught_by_the_grader microfacet_long/* doc_outputs/quoted_output_is_what_the_program_prints \
              accel/bvh_and_kdtree_match_brute_force_on_soups_of_1_to_10_triangles \
              accel/bvh_and_kdtree_match_brute_force_on_a_sphere_from_inside_and_outside \
              accel/bvh_and_kdtree_match_brute_force_on_stacked_axis_aligned_grids \
              povray_agreement/chapter_08_recursion_agrees_with_povray povray_agreement/chapter_10_bvh_agrees_with_povray \
              povray_agreement/chapter_13_depth_of_field_within_the_noise \
              povray_agreement/chapter_13_adaptive_circular_and_oriented_lights \
              watertight/chapters_9_and_10_draw_the_cube_from_inside_without_a_leak \
              nested_glass/glass_of_water_agrees_with_povray antialias/jitter_is_unbiased_where_the_grid_aliases \
              coursework/the_grader_ends_every_run_with_a_scoreboard_of_every_task \
              coursework_proof/every_planted_fault_is_reported coursework_proof/make_exercises_* coursework_long/* \
              results/the_quick_mode_runs_every_experiment_and_draws_every_plot_and_table \
              doc_commands/every_command_runs_as_written deps/without_root_and_without_stb_* \
              povray_agreement/catches_a_highlight_multiplied_by_the_pigment \
              povray_agreement/chapter_13_depth_of_field_check_catches_a_wrong_lens \
              watertight/chapter_10_with_moller_trumbore_draws_the_leak \
              accel/*_soups_of_3000_triangles accel/*_soups_of_5000_triangles accel/*_outside_float_range \
              accel/*_corners_at_infinity_or_nan acceleration/every_structure_draws_the_brute_force_picture \
              acceleration/every_rung_of_chapter_11_draws_the_brute_force_picture \
              mesh_fuzz/* io/a_large_picture_takes_a_few_bytes_per_pixel io/a_picture_whose_pixels_are_not_numbers_is_not_written \
              layering/no_chapter_links_with_the_previous_chapters_modules \
              layering/every_chapter_links_with_its_own_modules \
              build/make_bench_after_make_test_links_bench_accel_with_embree \
              build/help_and_clean_install_nothing_while_deps_installs \
              accel/*_soups_of_30_to_300_triangles accel/*_soups_of_1000_triangles \
              acceleration/the_picture_is_the_same_for_1_2_and_4_threads \
              results/a_number_of_the_text_typed_over_or_unknown_is_caught results/a_changed_number_in_a_csv_* \
              povray_agreement/chapter_11_fast_agrees_with_povray reference_image/catches_a_wrong_ior \
              povray_agreement/catches_one_extra_trace_level povray_agreement/chapter_12_checks_catch_* \
              povray_agreement/chapter_13_check_catches_a_hard_shadow \
              reference_image/chapter_15_paths_matches_its_reference \
              accel/rung_6_matches_brute_force_where_a_float_step_is_as_large_as_the_mesh \
              povray_agreement/chapter_12_grid_of_2_and_of_4 \
              results/the_committed_plots_and_tables_are_what_their_csv_files_draw \
              watertight/povray_draws_the_cube_from_inside_without_a_leak_as_chapter_10_does \
              cycles_motion/*
LONG_TESTS += rough_plates_long/* reference_image/chapter_17_rough_matches_its_reference
# Chapters 16 and 17's slower proofs (make test stays within its minute and a half): the whole scene
# against POV-Ray (the last frame of an animation is in make test), a million instances, MIS against
# the other strategies on the plates, the tiles of every sampler but one ray a pixel and chapter 15's
# paths (and the farm's frame).
LONG_TESTS += pictures/the_twin_of_a_frame_without_blur_agrees_with_povray \
              instance_lines/a_million_instances_are_read_and_one_more_than_the_limit_refused \
              rough_plates/strategies_agree_and_mis_has_the_least_variance \
              tile/chapter_11s_packets_tiles_join_into_the_picture \
              tile/grid_jitter_and_recursive_tiles_of_any_size_join_into_the_picture \
              tile/adaptive_tiles_of_whole_blocks_join_into_the_picture \
              tile/chapter_13s_lens_and_area_lights_tiles_join_into_the_picture \
              tile/chapter_16s_moving_instances_tiles_join_into_the_picture \
              tile/a_tiles_heat_map_is_the_tile_with_its_bar \
              pictures/one_frame_of_the_farm_is_the_same_frame_of_the_whole_run
# Two brute-force loops of three to four seconds each on one core: chapter 16's two levels against every
# face of every instance on 3,000 random rays, and chapter 3's loop against Moller-Trumbore on 4,096 rays
# aimed at the cube's shared edges (make test keeps the two levels' other differential tests and the
# watertight views of the cube and the icosphere).
LONG_TESTS += two_level/nearest_hits_and_crossings_equal_brute_force_exactly \
              watertight/chapter_3s_loop_has_no_leak_where_moller_trumbore_has_some
# The deliberately wrong tracers the long tests run (built below, from tests/mutants/*.patch); defined
# here, before test-long names them, since a rule's prerequisites are expanded as make reads it.
MUTANTS := $(patsubst tests/mutants/%.patch,$(BUILD)/mutant-%,$(wildcard tests/mutants/*.patch))
LONG_TESTS_PATTERN := @($(subst $() ,|,$(strip $(LONG_TESTS))))
# make test builds what it runs (every chapter, the test runner, the grader, the benchmark program
# whose CSV its tests read) with a job per processor, unless make was already given -j: a fresh clone
# compiles a hundred files before its first test.
PARALLEL_BUILD := $(if $(filter -j%,$(MAKEFLAGS)),,-j$(shell nproc 2>/dev/null || echo 2))
# make test runs two tests per processor at once (Criterion's -j): many tests spend part of their time
# waiting on a program they run (a chapter, POV-Ray, gnuplot), and on two cores four at once finish the
# quick suite in 58 s against 68 s with two. Under the sanitizers, where each test is several times
# slower and its time limit nearer, one per processor.
TEST_JOBS := $(shell echo $$(( $(if $(filter 1,$(SAN)),1,2) * $$(nproc 2>/dev/null || echo 1) )))
# The chapters the tests run share the processors with three other tests, so their OpenMP threads sleep
# when they wait instead of spinning (OMP_WAIT_POLICY=passive): spinning threads take the processor from
# a test that has work. On two cores that is about 10 s of processor time and 5 s of make test's 60 s
# (three paired runs: 55.0/53.6/54.2 s against 60.1/58.8/59.8 s). A chapter run by hand keeps the default.
RUN_TESTS := OMP_WAIT_POLICY=passive LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan-criterion.supp \
             WHITTED_BUILD=$(BUILD) ./$(BUILD)/run-tests

## make test           the quick suite, under a minute and a half: unit tests, reference images, agreement with
##                     POV-Ray, the docs' code and outputs (installs what it needs first)
test: | deps
	$(MAKE) --no-print-directory $(PARALLEL_BUILD) all $(BUILD)/run-tests $(BUILD)/check $(BUILD)/bench_accel $(BUILD)/inset \
	    $(BUILD)/draw-textures $(MODELS_FOREST)
	$(RUN_TESTS) -j$(TEST_JOBS) --filter '$(TEST_FILTER)'

## make test-long      the tests make test leaves out (LONG_TESTS in the Makefile), ten minutes or more:
##                     the gallery's faults, the coursework kit, the mutants, make results QUICK=1, the
##                     docs' commands, the largest differential tests
test-long: all $(BUILD)/run-tests $(BUILD)/check $(MUTANTS) $(BUILD)/measure $(BUILD)/inset $(MODELS_TEAPOT) | deps
	$(RUN_TESTS) --filter '$(LONG_TESTS_PATTERN)'
	$(MAKE) --no-print-directory test-farm

## make test-farm      a Slurm cluster of one node started on this machine (munged, slurmctld and slurmd in a
##                     temporary folder, stopped afterwards): chapter 13's picture rendered as a job array of
##                     tiles and joined, byte for byte the picture of one machine, and chapter 16's frames
##                     (docs/farm.md; make test-long runs it; installs slurm-wlm and munge when missing)
.PHONY: test-farm
test-farm: $(BUILD)/chapter-13 $(BUILD)/assemble $(if $(wildcard chapters/16-*),$(BUILD)/chapter-16) | deps
	WHITTED_BUILD=$(BUILD) tools/farm/test-one-node.sh

## make test-sanitize  make test's suite built with AddressSanitizer and UndefinedBehaviorSanitizer,
##                     into build/san (make test-long SAN=1: the long one too)
test-sanitize:
	$(MAKE) --no-print-directory SAN=1 test

# The kd-tree and BVH differential tests with 20 times the rays (millions), without a time limit.
# Its own program: tests/test_accel.c built with ACCEL_TEST_TIMEOUT=0, since a test's own .timeout
# outranks --timeout 0 and 20 times the rays take longer than the 120 s the tests allow.
$(BUILD)/tests/test_accel_long.o: tests/test_accel.c | $(BUILD)/tests deps
	$(CC) $(CFLAGS) -Itests/support -DACCEL_TEST_TIMEOUT=0 -MMD -MP -c $< -o $@

$(BUILD)/run-accel-long: $(BUILD)/tests/test_accel_long.o $(filter $(BUILD)/tests/support/%,$(TEST_OBJECTS)) \
        $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS) $(CRITERION)

## make test-accel-long  the kd-tree and BVH differential tests (every rung of chapter 11 included)
##                     with 20 times the rays, millions, and no time limit
test-accel-long: $(BUILD)/run-accel-long | deps
	WHITTED_ACCEL_RAYS=20 WHITTED_BUILD=$(BUILD) ./$(BUILD)/run-accel-long --filter 'accel/*' --timeout 0

# Chapter 12's walkthrough: regions of pictures side by side, enlarged (tools/antialias-docs.sh).
$(BUILD)/inset: $(BUILD)/tools/inset.o $(BUILD)/common/image.o $(BUILD)/common/outfile.o $(BUILD)/common/infile.o \
                $(BUILD)/common/png_palette.o
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# Chapter NN's program linked with the modules of chapter MM instead of its own:
# $(BUILD)/layering-NN-with-MM. With MM = NN - 1 it must fail to link, because every chapter uses what
# it introduces; tests/test_layering.c checks that for every chapter.
layering_chapter = $(call chapter_dir,$(word 1,$(subst -with-, ,$(1))))
layering_modules = $(MODULES_$(word 2,$(subst -with-, ,$(1))))
$(BUILD)/layering-%: $$(BUILD)/chapters/$$(call layering_chapter,$$*).o \
        $$(addprefix $$(BUILD)/common/,$$(addsuffix .o,$$(call layering_modules,$$*)))
	tools/build/link-chapter.sh $(BUILD) $(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# ---- mutants: deliberately wrong tracers for the tests ---------------------------------------------
# tests/mutants/NAME.patch is a classic mistake as a patch, whose "Program: N" line names a chapter.
# $(BUILD)/mutant-NAME is that chapter built from a patched copy of common/ and chapters/ in
# $(BUILD)/mutants/NAME/ (tests/support/patched-copy.sh), by a second make that sees the copy as it
# is now; the sources themselves never carry the mistake. The tests prove that their checks catch each
# one (tests/test_images.c, tests/test_watertight.c). The copy and the second make are one recipe line:
# make -n runs a line that names $(MAKE), and the second make can only plan once the copy exists.
mutant_chapter = $(call chapter_dir,$(shell printf '%02d' $$(sed -n 's/^Program: //p' tests/mutants/$(1).patch)))

$(BUILD)/mutant-%: tests/mutants/%.patch tests/support/patched-copy.sh $(wildcard common/*.[ch] chapters/*/main.c)
	tests/support/patched-copy.sh $< $(BUILD)/mutants/$* common chapters && \
	    $(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) MUTANT=$* $(BUILD)/mutants/$*/program
	cp $(BUILD)/mutants/$*/program $@

# In the second make (MUTANT=NAME): the copy's objects, with the copy's headers first.
ifneq ($(MUTANT),)
MUTANT_DIR := $(BUILD)/mutants/$(MUTANT)
MUTANT_CHAPTER := $(call mutant_chapter,$(MUTANT))
$(MUTANT_DIR)/%.o: $(MUTANT_DIR)/%.c | deps
	$(CC) -I$(MUTANT_DIR)/common $(CFLAGS) -MMD -MP -c $< -o $@

$(MUTANT_DIR)/program: $(MUTANT_DIR)/chapters/$(MUTANT_CHAPTER)/main.o \
        $(addprefix $(MUTANT_DIR)/common/,$(addsuffix .o,$(MODULES_$(call chapter_number,$(MUTANT_CHAPTER)))))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

-include $(wildcard $(MUTANT_DIR)/common/*.d $(MUTANT_DIR)/chapters/*/*.d)
endif

# ---- the pictures: POV-Ray, references, gallery, figures -------------------------------------------
## make compare        render chapters 1 to 14 with POV-Ray too: pictures and table in out/compare/
##                     (UPDATE_DOCS=1 also writes the table into docs/povray.md; chapter 15 is
##                     checked against Cycles, make compare-cycles)
compare: all $(BUILD)/compare | deps
	UPDATE_DOCS=$(UPDATE_DOCS) tools/compare-povray.sh $(BUILD)

## make compare-cycles  chapters 15, 16 and 17 against Blender's Cycles (installs Debian's blender): chapter
##                     15's two scenes and chapter 17's two, block means within noise and means within 1 %,
##                     and chapter 16's motion blur, in out/cycles/ (UPDATE_DOCS=1 also writes the tables
##                     into docs/15-paths.md and docs/17-rough.md; CHAPTERS_COMPARED=17 only chapter 17's);
##                     several minutes
compare-cycles: $(BUILD)/chapter-15 $(BUILD)/chapter-16 $(BUILD)/chapter-17 | deps
	UPDATE_DOCS=$(UPDATE_DOCS) CHAPTERS="$(CHAPTERS_COMPARED)" tools/cycles/compare-cycles.sh $(BUILD)
CHAPTERS_COMPARED ?= 15 16 17

## make references     re-render the reference images on purpose and say what changed (a picture whose
##                     pixels are the same is left as it was, byte for byte)
references: all $(BUILD)/compare
	tools/bless-references.sh $(BUILD)

## make gallery        render the gallery of wrong pictures (the faults in tools/gallery/) beside the
##                     right ones, into docs/gallery/ and docs/gallery.md (pictures whose pixels are the
##                     same are left as they were)
gallery: all $(BUILD)/compare
	tools/gallery.sh $(BUILD)

# Chapter 17's plot of the light a rough conductor loses against its roughness: the table of
# tools/rough_energy.c (microfacet.c's numerical integral) drawn by tools/rough-energy.gp.
$(BUILD)/rough-energy: $(BUILD)/tools/rough_energy.o $(addprefix $(BUILD)/common/,microfacet.o bsdf.o owen_sobol.o sampling.o sample_hash.o)
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

## make rough-energy   redraw chapter 17's plot of energy loss against roughness (docs/images/17-energy-loss.*)
rough-energy: $(BUILD)/rough-energy
	./$(BUILD)/rough-energy > docs/images/17-energy-loss.txt
	gnuplot -e "data='docs/images/17-energy-loss.txt'; output='docs/images/17-energy-loss.svg'" tools/rough-energy.gp

# The walkthroughs' figures: tools/figures/ draws them as SVG with the chapters' own functions, into
# docs/figures/ (tests/test_figures.c checks that the committed ones are what it draws now).
FIGURE_OBJECTS := $(patsubst tools/figures/%.c,$(BUILD)/tools/figures/%.o,$(wildcard tools/figures/*.c))

$(BUILD)/figures: $(FIGURE_OBJECTS) $(PATH_PROOFS_OBJECT) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

## make figures        redraw the walkthroughs' figures, docs/figures/*.svg, from tools/figures/
figures: $(BUILD)/figures
	./$(BUILD)/figures docs/figures

# ---- the coursework kit (docs/coursework.md) -----------------------------------------------------
CHECK_OBJECTS := $(patsubst tests/checks/%.c,$(BUILD)/checks/%.o,$(wildcard tests/checks/*.c))

$(BUILD)/checks/%.o: tests/checks/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Itests/support -MMD -MP -c $< -o $@

$(BUILD)/check: $(CHECK_OBJECTS) $(IMAGE_COMPARE_OBJECT) $(PATH_PROOFS_OBJECT) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

## make check-N        grade chapter N's coursework tasks (1..17): each task, then a scoreboard (code that
##                     only has compiler warnings is graded, with the warnings shown: tests/checks/grade.sh)
define check_rule
check-$(1): | out
	@n=$$$$(printf '%02d' $(1)); \
	tests/checks/grade.sh "$$(MAKE)" $$(BUILD) $(1) $$(BUILD)/check $$(BUILD)/chapter-$$$$n
endef
$(foreach n,$(CHAPTER_NUMBERS),$(eval $(call check_rule,$(n))))

## make check          grade every chapter's coursework tasks
check: | out
	@tests/checks/grade.sh "$(MAKE)" $(BUILD) all $(BUILD)/check \
	    $(foreach c,$(CHAPTERS),$(BUILD)/chapter-$(call chapter_number,$(c))) $(SCENE_MODELS)

## make student DIR=d  a student copy with the coursework tasks blanked (TASKS="2.1 5.1": only some), a
##                     hand-out without the model answers (ANSWERS=1 keeps them: a lecturer's copy)
student:
	@test -n "$(DIR)" || { echo 'make student DIR=path [TASKS="2.1 5.1"] [ANSWERS=1]: say where the copy goes' >&2; exit 2; }
	tools/student.sh "$(DIR)" "$(TASKS)" $(if $(filter 1,$(ANSWERS)),--answers)

## make exercises      the build exercises (★★★): each one whose function common/ defines is linked into a
##                     small program of its own and checked; the others say where to start
exercises: $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES))) $(BUILD)/tests/exercises/checks.o | deps
	@CC="$(CC)" CFLAGS="$(CFLAGS)" LDFLAGS="$(LDFLAGS)" LDLIBS="$(LDLIBS)" tests/exercises/runner/run.sh $(BUILD) $^

# What make test runs: all but LONG_TESTS; in a student copy (tools/student.sh leaves .student-copy in it)
# the suites tests/student-suites names, which apply to a student: the framework around the tasks and the
# kit itself, passing whatever the tasks hold (make test ALL=1 there: all but LONG_TESTS).
ifeq ($(wildcard .student-copy)$(filter 1,$(ALL)),.student-copy)
TEST_FILTER = @($(shell grep -v '^\#' tests/student-suites | paste -sd'|'))/*
else
TEST_FILTER = !($(LONG_TESTS_PATTERN))
endif

# ---- the browser: every chapter compiled to WebAssembly (web/) ----------------------------------------
#   make web        compiles each chapter's own main.c and the common/ modules it links (MODULES_NN) to
#                   WebAssembly with Emscripten (Debian's emscripten, installed on demand) into
#                   build/web/: the page (index.html, page.js, renders.js, worker.js), one chapter-NN.js and
#                   chapter-NN.wasm per chapter (the page loads only the chapter it shows), the scenes,
#                   their meshes and textures. A static folder: any web server can serve it.
#   make serve      serves build/web on http://localhost:$(WEB_PORT)/ (python3's http.server)
#   make test-web   builds the page and the native chapters, serves the page and drives it in headless
#                   Chromium (web/test_web.py): pictures against the native ones (chapters 2, 8 and 10 at
#                   their size, every chapter small), frame rates, a parse error, the big teapot, the
#                   page's explanations, editor, size guard, layouts (375 x 667, 1280 x 800) and touch, a
#                   screenshot of the page (WEB_SCREENSHOT, and the two layouts' beside it)
#
# The same floating-point rules as the native build: -ffp-contract=off (WebAssembly has no fused
# multiply-add anyway) and no fast-math. Chapter 11's four-float boxes (common/float4.h) use GCC's
# vector extension; with -msimd128 clang compiles it to WebAssembly's 128-bit SIMD instructions (the
# x86 intrinsics are behind __SSE__, which is not defined here), and the lanes compute what SSE's
# minps/maxps compute, so the picture is the same. OpenMP is not used: each of the page's workers
# renders its band of rows on one thread (render.c's loop runs serially without _OPENMP; docs/web.md). stb's code, a library natively, is
# compiled in from its header by web/stb_code.c.

WEB := build/web
# The objects, beside the folder the page is served from (which holds only what the page loads).
WEB_OBJ := build/web-obj
WEB_PORT ?= 8642
# Where make test-web puts its screenshot of the page; README's is made with
# make test-web WEB_SCREENSHOT=docs/images/web-page.png
WEB_SCREENSHOT ?= out/web-page.png
# Where the page's links to each chapter's walkthrough and main.c (and docs/scene-format.md) point: the
# address of the repository's files, ending in a slash (e.g. https://github.com/OWNER/whitted/blob/main/).
# Empty, the default: the copies make web puts beside the page (build/web/docs/, build/web/chapters/),
# served as plain text wherever the page is served.
WEB_REPO_BASE ?=
# The page's published address, ending in a slash: the walkthroughs' "try it" links point there.
# make try-links WEB_BASE=https://... rewrites them (the default: make serve's local address).
WEB_BASE ?= http://localhost:$(WEB_PORT)/
# Debian's emcc runs JavaScript tools (acorn) that Debian installs under /usr/share/nodejs; a node from
# elsewhere does not look there by itself.
EMCC := NODE_PATH=/usr/share/nodejs emcc
WEB_CFLAGS = -std=c11 -D_DEFAULT_SOURCE -O2 -ffp-contract=off -msimd128 -Wall -Wextra -Werror -Icommon \
             $(STB_CFLAGS)
# One module per chapter, run like a process: a worker makes an instance and calls main with the
# command line (so each render of a new world starts from the program's first state, as natively). The
# instance is then held (common/cli.c's held loop): after its picture the program waits, through
# Asyncify, for the next camera, size, samples or tile of the same world and renders again without
# reading or building anything. With ASYNCIFY_IGNORE_INDIRECT, Asyncify instruments only the functions
# that call down to the wait directly (main, cli_render, the held loop), so the tracing code runs as fast
# as without it. web_join.c joins the bands of rows the workers render into the whole picture's PNG.
WEB_LDFLAGS := -O2 -msimd128 -sMODULARIZE=1 -sEXPORT_NAME=createChapter -sENVIRONMENT=worker \
               -sINVOKE_RUN=0 -sEXIT_RUNTIME=1 -sALLOW_MEMORY_GROWTH=1 -sMAXIMUM_MEMORY=2GB \
               -sFORCE_FILESYSTEM=1 -sEXPORTED_RUNTIME_METHODS=FS,callMain \
               -sASYNCIFY=1 -sASYNCIFY_IMPORTS=held_next_job -sASYNCIFY_IGNORE_INDIRECT=1
WEB_PAGE := $(addprefix $(WEB)/,index.html page.js worker.js renders.js)
WEB_CHAPTERS := $(foreach c,$(CHAPTERS),$(WEB)/chapter-$(call chapter_number,$(c)).js)

.PHONY: web serve test-web try-links

## make web            every chapter compiled to WebAssembly, with the page, scenes and meshes, into
##                     build/web/ (a static folder; installs Debian's emscripten first)
web: $(WEB_CHAPTERS) $(WEB_PAGE) $(WEB)/scenes.stamp $(WEB)/site.js $(WEB)/sources.stamp

## make serve          serves build/web on http://localhost:8642/ (WEB_PORT=N for another port)
serve: web
	@echo "the chapters in the browser: http://localhost:$(WEB_PORT)/"
	cd $(WEB) && python3 -m http.server --bind 127.0.0.1 $(WEB_PORT)

## make test-web       the page in headless Chromium against the native chapters: the same pixels,
##                     frame rates, a parse error, the big teapot, the page's explanations, editor,
##                     size guard, layouts and touch, README's screenshots
test-web: web $(foreach c,$(CHAPTERS),$(BUILD)/chapter-$(call chapter_number,$(c))) | deps
	tools/build/install-deps.sh test-web
	@mkdir -p $(dir $(WEB_SCREENSHOT))
	/usr/bin/python3 web/test_web.py --web $(WEB) --build $(BUILD) --port $(WEB_PORT) --screenshot $(WEB_SCREENSHOT)

# After the native build's packages (stb's headers, and gcc for the models and textures the page loads).
web-deps: | deps
	@tools/build/install-deps.sh web

$(WEB_OBJ)/common/%.o: common/%.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -MMD -MP -c $< -o $@

$(WEB_OBJ)/chapters/%.o: chapters/%/main.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -MMD -MP -c $< -o $@

$(WEB_OBJ)/stb_code.o: web/stb_code.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -Wno-unused-function -c $< -o $@

$(WEB_OBJ)/web_join.o: web/web_join.c | web-deps
	@mkdir -p $(@D)
	$(EMCC) $(WEB_CFLAGS) -MMD -MP -c $< -o $@

-include $(wildcard $(WEB_OBJ)/*/*.d $(WEB_OBJ)/*.d)

# One module per chapter, linked from exactly that chapter's modules (as the native link).
define web_chapter_rules
# The folder is an order-only prerequisite: the objects live elsewhere, so nothing else creates it first.
$(WEB)/chapter-$(call chapter_number,$(1)).js: $(WEB_OBJ)/chapters/$(1).o $(WEB_OBJ)/stb_code.o $(WEB_OBJ)/web_join.o \
        $(addprefix $(WEB_OBJ)/common/,$(addsuffix .o,$(MODULES_$(call chapter_number,$(1))))) Makefile | $(WEB)
	$(EMCC) $(WEB_LDFLAGS) $$(filter %.o,$$^) -o $$@
endef
$(foreach c,$(CHAPTERS),$(eval $(call web_chapter_rules,$(c))))

$(WEB):
	mkdir -p $@

$(WEB)/%: web/%
	@mkdir -p $(@D)
	cp $< $@

# FORCE: a target with no file and no recipe, so what names it is always remade (it need not be phony).
FORCE:

# The page's settings from the build (WEB_REPO_BASE), rewritten only when they change.
$(WEB)/site.js: FORCE | $(WEB)
	@printf '// site.js: where the page links to (make web WEB_REPO_BASE=...; made by the Makefile).\nwindow.WHITTED_SITE = {repoBase: "%s"};\n' \
	    '$(WEB_REPO_BASE)' > $@.new
	@cmp -s $@.new $@ && rm $@.new || mv $@.new $@

# The walkthroughs and each chapter's main.c beside the page, for its links when WEB_REPO_BASE is empty;
# the walkthroughs' "try it" links then lead back to the page beside them.
$(WEB)/sources.stamp: $(wildcard docs/*.md) $(wildcard chapters/*/main.c) | $(WEB)
	@mkdir -p $(WEB)/docs $(foreach c,$(CHAPTERS),$(WEB)/chapters/$(c))
	$(foreach c,$(CHAPTERS),cp chapters/$(c)/main.c $(WEB)/chapters/$(c)/ &&) true
	cp docs/*.md $(WEB)/docs/
	sed -E -i 's#\]\([^)]*index\.html\?chapter=([0-9]+)\)#](../index.html?chapter=\1)#' $(WEB)/docs/*.md
	touch $@

## make try-links      points the walkthroughs' "try it" links at the page published on WEB_BASE
##                     (default http://localhost:8642/, make serve's)
try-links:
	sed -E -i 's#\]\([^)]*index\.html\?chapter=([0-9]+)\)#]($(WEB_BASE)index.html?chapter=\1)#' docs/[0-9][0-9]-*.md

# The scenes and what they name (mesh and texture paths are relative to scenes/), and the list of
# scenes the page offers.
$(WEB)/scenes.stamp: $(wildcard scenes/*.scene) $(SCENE_MODELS) $(SCENE_TEXTURES) scenes/models/bunny.ply
	@mkdir -p $(WEB)/scenes/models $(WEB)/scenes/textures
	cp scenes/*.scene $(WEB)/scenes/
	cp $(SCENE_MODELS) scenes/models/bunny.ply $(WEB)/scenes/models/
	cp $(SCENE_TEXTURES) $(WEB)/scenes/textures/
	cd scenes && ls *.scene | sed 's/.*/"&"/' | paste -sd, | sed 's/.*/[&]/' > ../$(WEB)/scenes/index.json
	touch $@

# ---- housekeeping ----------------------------------------------------------------------------------
## make deps           install the Debian packages building needs, and those of the goals named with it
##                     (every goal that needs packages installs them first anyway)
deps:
	@tools/build/install-deps.sh $(DEPS_NEEDS)

## make clean          remove build/ and out/ (installs nothing)
clean:
	rm -rf build out

## make help           this list (installs nothing)
help:
	@awk -v hidden="$(if $(wildcard .student-copy),$(NOT_IN_HANDOUT))" \
	     'function show(line,    goal) { if (line ~ /^## make /) { goal = line; sub(/^## make /, "", goal); \
	                                         sub(/[ =].*$$/, "", goal); skip = index(" " hidden " ", " " goal " ") > 0 } \
	                                     if (!skip) print substr(line, 4) } \
	      /^include / { while ((getline line < $$2) > 0) if (line ~ /^## /) show(line); next } \
	      /^## / { show($$0) }' Makefile

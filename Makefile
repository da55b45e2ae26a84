# Makefile: builds the chapters of the whitted ray tracer, renders their scenes, runs the tests.
#
#   make chapter-N      build chapter N (1..11) and render its scene to out/chapter-NN.png
#   make chapters       build and render every written chapter
#   make test           unit tests, image regression, POV-Ray agreement (installs what is missing)
#   make test-sanitize  the same suite built with AddressSanitizer and UndefinedBehaviorSanitizer
#   make test-accel-long  the kd-tree and BVH differential tests with millions of rays
#   make references     re-render the reference images on purpose and say what changed
#   make gallery        render the gallery of wrong pictures into docs/gallery.md
#   make figures        redraw the walkthroughs' figures, docs/figures/*.svg, from tools/figures/
#   make compare        render every chapter with POV-Ray too: pictures and table in out/compare/
#                       (UPDATE_DOCS=1 also writes the table into docs/povray.md)
#   make results        the seed's experiments redone: CSVs, plots and tables of docs/results.md
#                       (QUICK=1: a small version in about a minute, into out/results-quick/)
#   make bench          kd-tree, BVH and chapter 11's rungs against Embree; peak memory on a 4M-triangle teapot
#   make check-N        grade chapter N's coursework tasks (make check: all), docs/coursework.md
#   make student DIR=d  a student copy with the coursework tasks blanked (TASKS="2.1 5.1": some)
#   make fuzz           the libFuzzer harnesses (scene, PLY, OBJ, renderer), FUZZ_SECONDS each
#   make clean          remove build/ and out/
#
# Every chapter links only the common/ modules introduced by chapters up to its own (MODULES_NN
# below), so a chapter that reaches for a later idea fails to link.

# ---- dependencies: Debian packages, installed when missing --------------------------------------
# Each goal asks only for what it needs (tools/install-deps.sh lists the packages): building and
# rendering a chapter needs gcc and stb; the tests add Criterion and POV-Ray; make compare adds POV-Ray.
DEPS_NEEDS := build $(if $(filter test test-sanitize test-accel-long %run-tests,$(MAKECMDGOALS)),test) \
              $(if $(filter compare,$(MAKECMDGOALS)),compare) $(if $(filter results,$(MAKECMDGOALS)),results)
ifeq ($(filter clean help,$(MAKECMDGOALS)),)
DEPS_READY := $(shell tools/install-deps.sh $(DEPS_NEEDS) >&2 && echo yes)
ifneq ($(DEPS_READY),yes)
$(error missing packages: see the message above)
endif
endif

# stb from the system, or else unpacked into .deps/ by install-deps.sh on a machine without root
# (linked statically from there, so the programs need nothing from .deps/ at run time).
LOCAL_STB_LIB := $(firstword $(wildcard .deps/root/usr/lib/*/libstb.a))
ifeq ($(if $(filter local,$(WHITTED_DEPS)),,$(shell pkg-config --exists stb 2>/dev/null && echo yes)),yes)
STB_CFLAGS := $(shell pkg-config --cflags stb)
STB_LIBS := $(shell pkg-config --libs stb)
else
STB_CFLAGS := -I.deps/root/usr/include/stb
STB_LIBS := $(LOCAL_STB_LIB)
endif

# ---- flags -------------------------------------------------------------------------------------
CC := gcc
SAN ?= 0
ifeq ($(SAN),1)
BUILD := build/san
OPT := -O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
else
BUILD := build
OPT := -O2
endif
# -ffp-contract=off: a*b - c*d is two rounded products and a rounded difference, never a fused
# multiply-add. The watertight triangle test relies on it (common/triangle.c); -std=c11 implies it in
# GCC, and saying it keeps it so under -std=gnu11 or on a machine with FMA.
CFLAGS := -std=c11 -D_DEFAULT_SOURCE -g $(OPT) -ffp-contract=off -Wall -Wextra -Werror -fopenmp -Icommon $(STB_CFLAGS)
LDFLAGS := $(OPT) -fopenmp
LDLIBS := $(STB_LIBS) -lm
CRITERION = $(shell pkg-config --cflags --libs criterion)

# ---- what each chapter introduces ----------------------------------------------------------------
MODULES_01 := stats camera image outfile infile text_escape name_index scene scene_scale scene_set povray render heatmap cli
MODULES_02 := $(MODULES_01) sphere headlight
MODULES_03 := $(MODULES_02) triangle mesh mesh_ply mesh_obj scene_meshes
MODULES_04 := $(MODULES_03) plane
MODULES_05 := $(MODULES_04) aabb box world
MODULES_06 := $(MODULES_05) phong
MODULES_07 := $(MODULES_06) shadow
MODULES_08 := $(MODULES_07) interior whitted
MODULES_09 := $(MODULES_08) kdtree kdtree_events kdtree_check accel
MODULES_10 := $(MODULES_09) bvh accel_bvh
MODULES_11 := $(MODULES_10) fast_bvh accel_fast_bvh
CHAPTERS := 01-camera 02-sphere 03-triangle 04-plane 05-aabb 06-phong 07-shadows 08-recursion \
            09-kdtree 10-bvh 11-fast
ALL_MODULES := $(sort $(foreach c,$(CHAPTERS),$(MODULES_$(firstword $(subst -, ,$(c))))))

chapter_number = $(firstword $(subst -, ,$(1)))
chapter_dir = $(filter $(1)-%,$(CHAPTERS))

# ---- models: the bunny is committed, the teapots are generated (tools/models.mk) -----------------
include tools/models.mk
SCENE_MODELS := scenes/models/teapot-5k.ply scenes/models/teapot-346k.ply

.PHONY: all chapters test test-sanitize test-accel-long references compare gallery figures clean help models \
        $(foreach n,1 2 3 4 5 6 7 8 9 10 11,chapter-$(n))
.DEFAULT_GOAL := all
.SECONDARY:
.SECONDEXPANSION:

all: $(foreach c,$(CHAPTERS),$(BUILD)/chapter-$(call chapter_number,$(c))) $(BUILD)/compare $(BUILD)/figures \
     $(SCENE_MODELS)

# ---- compiling ---------------------------------------------------------------------------------
$(BUILD)/common/%.o: common/%.c | $(BUILD)/common
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/chapters/%.o: chapters/%/main.c | $(BUILD)/chapters
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/tests/%.o: tests/%.c | $(BUILD)/tests
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Itools -MMD -MP -c $< -o $@

$(BUILD)/tools/%.o: tools/%.c | $(BUILD)/tools
	$(CC) $(CFLAGS) -Itools -MMD -MP -c $< -o $@

$(BUILD)/common $(BUILD)/chapters $(BUILD)/tests $(BUILD)/tools $(BUILD)/mutants out:
	mkdir -p $@

-include $(wildcard $(BUILD)/*/*.d $(BUILD)/*/*/*.d)

# One link rule per chapter, with exactly that chapter's modules.
define chapter_rules
$(BUILD)/chapter-$(call chapter_number,$(1)): $(BUILD)/chapters/$(1).o \
        $(addprefix $(BUILD)/common/,$(addsuffix .o,$(MODULES_$(call chapter_number,$(1)))))
	tools/link-chapter.sh $(BUILD) $$(CC) $$(LDFLAGS) $$^ -o $$@ $$(LDLIBS)
endef
$(foreach c,$(CHAPTERS),$(eval $(call chapter_rules,$(c))))

# ---- running chapters --------------------------------------------------------------------------
# chapter-N for N = 1..11: explicit rules (GNU make skips pattern rules for phony targets). Only the
# models that the chapter's scene names are made first (mesh paths are relative to scenes/).
define run_chapter_rule
chapter-$(1): | out
	@n=$$$$(printf '%02d' $(1)); \
	if ! ls -d chapters/$$$$n-* >/dev/null 2>&1; then \
	    echo "chapter $(1) is not written yet (written: $(CHAPTERS))" >&2; exit 2; fi; \
	models=$$$$(awk '$$$$1 == "mesh" { print "scenes/" $$$$2 }' scenes/$$$$n-*.scene); \
	$$(MAKE) --no-print-directory $$(BUILD)/chapter-$$$$n $$(BUILD)/compare $$$$models && ./$$(BUILD)/chapter-$$$$n
endef
$(foreach n,1 2 3 4 5 6 7 8 9 10 11,$(eval $(call run_chapter_rule,$(n))))

chapters: $(foreach c,$(CHAPTERS),chapter-$(patsubst 0%,%,$(call chapter_number,$(c))))

# ---- benchmarks (bench/bench.mk): make bench, make bench-accel ----------------------------------
include bench/bench.mk

# ---- fuzzing (fuzz/fuzz.mk): make fuzz, make fuzz-smoke -----------------------------------------
include fuzz/fuzz.mk
include tools/results/results.mk

# ---- tests -------------------------------------------------------------------------------------
TEST_SOURCES := $(wildcard tests/*.c tests/exercises/*.c)
TEST_OBJECTS := $(patsubst tests/%.c,$(BUILD)/tests/%.o,$(TEST_SOURCES))
TOOL_OBJECTS := $(BUILD)/tools/image_compare.o
TEST_TOOL_OBJECTS := $(TOOL_OBJECTS) $(BUILD)/tools/closed_mesh.o

$(BUILD)/run-tests: $(TEST_OBJECTS) $(TEST_TOOL_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS) $(CRITERION)

$(BUILD)/compare: $(BUILD)/tools/compare.o $(TOOL_OBJECTS) $(BUILD)/common/image.o $(BUILD)/common/outfile.o
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# Chapter NN's program linked with the modules of chapter MM instead of its own:
# $(BUILD)/layering-NN-with-MM. With MM = NN - 1 it must fail to link, because every chapter uses what
# it introduces; tests/test_layering.c checks that for every chapter.
layering_chapter = $(call chapter_dir,$(word 1,$(subst -with-, ,$(1))))
layering_modules = $(MODULES_$(word 2,$(subst -with-, ,$(1))))
$(BUILD)/layering-%: $$(BUILD)/chapters/$$(call layering_chapter,$$*).o \
        $$(addprefix $$(BUILD)/common/,$$(addsuffix .o,$$(call layering_modules,$$*)))
	tools/link-chapter.sh $(BUILD) $(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# Deliberately wrong tracers, for the tests that prove the POV-Ray agreement check catches real
# mistakes: chapter 6 with its highlight multiplied by the pigment colour (see common/phong.c).
MUTANTS := $(BUILD)/mutant-highlight-times-pigment $(BUILD)/mutant-moller-trumbore
$(BUILD)/mutants/phong-highlight-times-pigment.o: common/phong.c | $(BUILD)/mutants
	$(CC) $(CFLAGS) -DWHITTED_MUTANT_HIGHLIGHT_TIMES_PIGMENT -MMD -MP -c $< -o $@

$(BUILD)/mutant-highlight-times-pigment: $(BUILD)/chapters/06-phong.o $(BUILD)/mutants/phong-highlight-times-pigment.o \
        $(addprefix $(BUILD)/common/,$(addsuffix .o,$(filter-out phong,$(MODULES_06))))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# Chapter 10 with Moller-Trumbore in place of the watertight triangle test (common/triangle.h), in the
# brute-force loop, the kd-tree and the BVH alike: the tests show it letting rays through closed meshes.
$(BUILD)/mutants/mt/%.o: common/%.c | $(BUILD)/mutants
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -DWHITTED_MUTANT_MOLLER_TRUMBORE -MMD -MP -c $< -o $@

$(BUILD)/mutant-moller-trumbore: $(BUILD)/chapters/10-bvh.o $(addprefix $(BUILD)/mutants/mt/,$(addsuffix .o,$(MODULES_10)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

# $(BUILD)/bench_accel: tests/test_bench_csv.c runs the benchmark on the bunny (without Embree).
test: all $(BUILD)/run-tests $(MUTANTS) $(BUILD)/bench_accel
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan-criterion.supp WHITTED_BUILD=$(BUILD) ./$(BUILD)/run-tests $(TEST_FILTER)

compare: all $(BUILD)/compare
	UPDATE_DOCS=$(UPDATE_DOCS) tools/compare-povray.sh $(BUILD)

test-sanitize:
	$(MAKE) --no-print-directory SAN=1 test

# The kd-tree and BVH differential tests with 20 times the rays (millions), without a time limit.
# Its own program: tests/test_accel.c built with ACCEL_TEST_TIMEOUT=0, since a test's own .timeout
# outranks --timeout 0 and 20 times the rays take longer than the 120 s make test allows.
$(BUILD)/tests/test_accel_long.o: tests/test_accel.c | $(BUILD)/tests
	$(CC) $(CFLAGS) -Itools -DACCEL_TEST_TIMEOUT=0 -MMD -MP -c $< -o $@

$(BUILD)/run-accel-long: $(BUILD)/tests/test_accel_long.o $(BUILD)/tests/test_support.o $(BUILD)/tests/image_test_support.o \
        $(TEST_TOOL_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS) $(CRITERION)

test-accel-long: $(BUILD)/run-accel-long
	WHITTED_ACCEL_RAYS=20 WHITTED_BUILD=$(BUILD) ./$(BUILD)/run-accel-long --filter 'accel/*' --timeout 0

references: all $(BUILD)/compare
	tools/bless-references.sh $(BUILD)

# The gallery of wrong pictures: every fault in tools/gallery/ rendered beside the right picture, into
# docs/gallery/ and docs/gallery.md.
gallery: all $(BUILD)/compare
	tools/gallery.sh $(BUILD)

# The walkthroughs' figures: tools/figures/ draws them as SVG with the chapters' own functions, into
# docs/figures/ (tests/test_figures.c checks that the committed ones are what it draws now).
FIGURE_OBJECTS := $(patsubst tools/figures/%.c,$(BUILD)/tools/figures/%.o,$(wildcard tools/figures/*.c))
$(BUILD)/tools/figures/%.o: tools/figures/%.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/figures: $(FIGURE_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

figures: $(BUILD)/figures
	./$(BUILD)/figures docs/figures

clean:
	rm -rf build out

help:
	@sed -n '2,18p' Makefile | sed 's/^# \{0,1\}//'

# ---- the coursework kit (docs/coursework.md) -----------------------------------------------------
#   make student DIR=path [TASKS="2.1 5.1"] [ANSWERS=1]  a student copy with the marked tasks' bodies
#                                              blanked; ANSWERS=1 keeps the model answers (a lecturer's)
#   make check-N (N = 1..11), make check       grade chapter N (or all): each task, then a scoreboard
#   make exercises                             the build exercises (★★★) the student has started
CHECK_OBJECTS := $(patsubst tests/checks/%.c,$(BUILD)/checks/%.o,$(wildcard tests/checks/*.c))

$(BUILD)/checks/%.o: tests/checks/%.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Itools -MMD -MP -c $< -o $@

$(BUILD)/check: $(CHECK_OBJECTS) $(TOOL_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS)

define check_rule
check-$(1): $(BUILD)/check | out
	@n=$$$$(printf '%02d' $(1)); \
	models=$$$$(awk '$$$$1 == "mesh" { print "scenes/" $$$$2 }' scenes/$$$$n-*.scene); \
	$$(MAKE) --no-print-directory $$(BUILD)/chapter-$$$$n $$$$models >/dev/null && WHITTED_BUILD=$$(BUILD) ./$$(BUILD)/check $(1)
endef
$(foreach n,1 2 3 4 5 6 7 8 9 10 11,$(eval $(call check_rule,$(n))))

check: $(BUILD)/check $(foreach c,$(CHAPTERS),$(BUILD)/chapter-$(call chapter_number,$(c))) $(SCENE_MODELS) | out
	WHITTED_BUILD=$(BUILD) ./$(BUILD)/check all

student:
	@test -n "$(DIR)" || { echo 'make student DIR=path [TASKS="2.1 5.1"] [ANSWERS=1]: say where the copy goes' >&2; exit 2; }
	tools/student.sh "$(DIR)" "$(TASKS)" $(if $(filter 1,$(ANSWERS)),--answers)

# The build exercises (★★★): each one whose function common/ defines is linked into a small program of
# its own and checked; the others say where to start. Needs only the compiler.
exercises: $(addprefix $(BUILD)/common/,$(addsuffix .o,$(ALL_MODULES))) $(BUILD)/tests/exercises/checks.o
	@CC="$(CC)" CFLAGS="$(CFLAGS)" LDFLAGS="$(LDFLAGS)" LDLIBS="$(LDLIBS)" tests/exercises/runner/run.sh $(BUILD) $^

# make test leaves out the kit's long proofs on student copies (make test-coursework-long runs them). In
# a student copy (tools/student.sh leaves .student-copy in it), it runs the suites that apply to a student,
# tests/student-suites: the framework around the tasks and the kit itself, which pass whatever the tasks
# hold; make test ALL=1 there runs the authors' whole suite, which needs every task done.
ifeq ($(wildcard .student-copy),)
TEST_FILTER := --filter '!(coursework_long)/*'
else ifneq ($(ALL),1)
TEST_FILTER := --filter '@($(shell grep -v '^\#' tests/student-suites | paste -sd'|'))/*'
endif

test-coursework-long: all $(BUILD)/run-tests $(BUILD)/check
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan-criterion.supp WHITTED_BUILD=$(BUILD) ./$(BUILD)/run-tests \
	    --filter 'coursework_long/*'


.PHONY: check student exercises test-coursework-long $(foreach n,1 2 3 4 5 6 7 8 9 10 11,check-$(n))
test: $(BUILD)/check

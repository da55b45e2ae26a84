# fuzz/fuzz.mk: the libFuzzer harnesses (make fuzz). A GNU make fragment included from the top-level
# Makefile, which defines BUILD, LDLIBS and ALL_MODULES.
#
#   make fuzz         build the five harnesses with clang and run each for FUZZ_SECONDS (default 120);
#                     crashes are saved under out/fuzz/HARNESS/, the growing corpus under out/fuzz/corpus/
#   make fuzz-smoke   the same harnesses for a fixed number of runs with a fixed seed (CI, when clang
#                     is there: well under a minute)
#
# The harnesses and the common/ modules they test are compiled by clang with libFuzzer, AddressSanitizer
# and UndefinedBehaviorSanitizer, into build/libfuzzer/ (whatever BUILD is: the objects are clang's, not
# gcc's). fuzz/run.sh runs them; docs/fuzzing.md explains the whole. clang comes from Debian's `clang`
# package, installed by tools/build/install-deps.sh fuzz (make test does not need it).

FUZZ_SECONDS ?= 120
FUZZ_BUILD := build/libfuzzer
FUZZ_HARNESSES := scene ply obj render image
FUZZ_CC := clang
FUZZ_SANITIZERS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# -ffp-contract=off as in the Makefile's CFLAGS (clang would fuse a*b + c into one rounding otherwise,
# and the structures' exact agreement with brute force relies on the same roundings everywhere).
# Recursive (=), as the Makefile's CFLAGS: STB_CFLAGS is worked out after the packages step.
FUZZ_CFLAGS = -std=c11 -D_DEFAULT_SOURCE -g -O1 -ffp-contract=off -Wall -Wextra -Werror -Wno-unknown-pragmas -Icommon \
               $(STB_CFLAGS) $(FUZZ_SANITIZERS) -fsanitize=fuzzer-no-link
FUZZ_LDFLAGS := $(FUZZ_SANITIZERS) -fsanitize=fuzzer
# What each harness links besides its own file and fuzz_support: the modules of the chapter that
# introduces what it tests (the Makefile's MODULES_NN), without those for the picture, the output
# files and the command line (render.c also needs OpenMP, which this clang build leaves out).
FUZZ_NOT_LINKED := image png_palette outfile povray render heatmap cli scene_set headlight
FUZZ_MODULES_scene := $(filter-out $(FUZZ_NOT_LINKED),$(MODULES_01))
FUZZ_MODULES_ply := $(filter-out $(FUZZ_NOT_LINKED),$(MODULES_03))
FUZZ_MODULES_obj := $(FUZZ_MODULES_ply)
# The renderer harness takes chapter 10's modules and what chapters 12 to 17 add to the tracing, with the
# picture, its heat-map and its file, which chapter 12's sampling links to. Chapter 11's fast BVH comes
# in as chapter 16's bottom level (its instances' objects); the worlds it checks against brute force
# are chapter 10's structures.
FUZZ_MODULES_render := $(filter-out $(FUZZ_NOT_LINKED),$(MODULES_10)) image png_palette outfile heatmap sample_hash supersample \
                       soft_shadow thin_lens jpeg_decode image_map mesh_surface texture owen_sobol sampling emitter bsdf path_trace \
                       fast_bvh fast_bvh_eight fast_bvh_lean fast_bvh_build float_triangle transform keyframes \
                       instance_bvh instances microfacet rough_surface
FUZZ_MODULES_image := infile png_palette jpeg_decode image_map pigment_syntax
FUZZ_EXTRA_ply := fuzz_mesh
FUZZ_EXTRA_obj := fuzz_mesh
# stb_image's decoder is compiled by clang into the harnesses that read pictures (fuzz/stb_image_impl.c).
FUZZ_EXTRA_render := render_check tiny_images stb_image_impl
FUZZ_EXTRA_image := stb_image_impl

.PHONY: fuzz fuzz-build fuzz-smoke

## make fuzz           the libFuzzer harnesses (scene, PLY, OBJ, renderer, image), FUZZ_SECONDS each (default
##                     120); installs clang first (docs/fuzzing.md)
fuzz: fuzz-build
	fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

## make fuzz-smoke     the same harnesses for a fixed number of runs with a fixed seed (CI)
fuzz-smoke: fuzz-build
	fuzz/run.sh --smoke $(FUZZ_BUILD)

# clang is installed first, in its own step, so that a machine without it still runs make test.
## make fuzz-build     build the harnesses into build/libfuzzer/ without running them
fuzz-build: | deps
	tools/build/install-deps.sh fuzz
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(addprefix $(FUZZ_BUILD)/fuzz_,$(FUZZ_HARNESSES)) \
	    $(FUZZ_BUILD)/seeds/image.made

$(FUZZ_BUILD)/common/%.o: common/%.c | $(FUZZ_BUILD)/common
	$(FUZZ_CC) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@

$(FUZZ_BUILD)/%.o: fuzz/%.c | $(FUZZ_BUILD)/common
	$(FUZZ_CC) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@

# stb's own code, not ours: compiled without the warnings our code is held to.
$(FUZZ_BUILD)/stb_image_impl.o: fuzz/stb_image_impl.c | $(FUZZ_BUILD)/common
	$(FUZZ_CC) $(FUZZ_CFLAGS) -w -c $< -o $@

$(FUZZ_BUILD)/common:
	mkdir -p $@

# The image harness's seed corpus: the tiny images (fuzz/tiny_images.h), drawn at build time by a small
# program of their own, never committed.
$(FUZZ_BUILD)/image-seeds: fuzz/image_seeds.c fuzz/tiny_images.c fuzz/tiny_images.h | $(FUZZ_BUILD)/common
	$(FUZZ_CC) -std=c11 -D_DEFAULT_SOURCE -O1 -Wall -Wextra -Werror $(STB_CFLAGS) fuzz/image_seeds.c fuzz/tiny_images.c \
	    -o $@ $(STB_LIBS) -lm
$(FUZZ_BUILD)/seeds/image.made: $(FUZZ_BUILD)/image-seeds
	rm -rf $(FUZZ_BUILD)/seeds/image && mkdir -p $(FUZZ_BUILD)/seeds/image
	$(FUZZ_BUILD)/image-seeds $(FUZZ_BUILD)/seeds/image && touch $@

fuzz_objects = $(FUZZ_BUILD)/fuzz_$(1).o $(FUZZ_BUILD)/fuzz_support.o \
               $(addprefix $(FUZZ_BUILD)/,$(addsuffix .o,$(FUZZ_EXTRA_$(1)))) \
               $(addprefix $(FUZZ_BUILD)/common/,$(addsuffix .o,$(FUZZ_MODULES_$(1))))
$(foreach h,$(FUZZ_HARNESSES),$(eval $(FUZZ_BUILD)/fuzz_$(h): $(call fuzz_objects,$(h))))
$(addprefix $(FUZZ_BUILD)/fuzz_,$(FUZZ_HARNESSES)):
	$(FUZZ_CC) $(FUZZ_LDFLAGS) $^ -o $@ $(STB_LIBS) -lm

-include $(wildcard $(FUZZ_BUILD)/*.d $(FUZZ_BUILD)/common/*.d)

# The renderer's check also runs in the tests, on the saved inputs (tests/test_fuzz_regressions.c),
# compiled there by gcc like every test (the Makefile links it and its tiny images into $(BUILD)/run-tests).
$(BUILD)/fuzz/%.o: fuzz/%.c | $(BUILD)/common deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@
-include $(wildcard $(BUILD)/fuzz/*.d)

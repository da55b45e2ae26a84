# tools/models/models.mk: the generated models in scenes/models/. A GNU make fragment, included from
# the top-level Makefile (it also works alone: make -f tools/models/models.mk models). Paths are
# relative to the top of the tree. Nothing here needs the network: scenes/models/bunny.ply is
# committed, and is remade only by hand with tools/models/fetch-bunny.sh.
#
#   make models          the small and the large teapot, the small one with (u, v) (and checks that
#                        bunny.ply is there)
#   make clean-models    removes the generated teapots
#
# teapot-5k:   the smallest tessellation with at least 5,000 triangles (N = 9: 5,112 triangles)
# teapot-346k: the smallest with at least 345,994 triangles, the Stanford Armadillo's count, for which
#              it stands in (N = 74: 349,872 triangles)
# teapot-5k-uv: teapot-5k's triangles with each patch's (u, v) and averaged normals at the corners,
#              seam vertices one per patch (chapter 14's textured teapot)
#
# $(MODELS_FOREST) (tools/models/forest.c) writes chapter 16's forest scene of instanced teapots and
# bunnies; make bench makes it into out/bench/ (bench/bench.mk), it is not kept in scenes/.

MODELS_DIR := scenes/models
MODELS_TEAPOT := build/teapot
MODELS_FOREST := build/forest
MODELS_TEAPOT_CFLAGS := -std=c11 -D_DEFAULT_SOURCE -O2 -Wall -Wextra -Werror
MODELS_GENERATED := $(MODELS_DIR)/teapot-5k.ply $(MODELS_DIR)/teapot-346k.ply $(MODELS_DIR)/teapot-5k-uv.ply

.PHONY: models clean-models

## make models         the teapots in scenes/models/ (make clean-models removes them)
models: $(MODELS_GENERATED) $(MODELS_DIR)/bunny.ply

$(MODELS_TEAPOT): tools/models/teapot.c
	@mkdir -p $(@D)
	$(CC) $(MODELS_TEAPOT_CFLAGS) $< -o $@ -lm

$(MODELS_FOREST): tools/models/forest.c
	@mkdir -p $(@D)
	$(CC) $(MODELS_TEAPOT_CFLAGS) $< -o $@ -lm

# Written to a temporary name first (X.tmp.ply for X.ply), so an interrupted run leaves no half
# file under the real name.
$(MODELS_DIR)/teapot-5k.ply: $(MODELS_TEAPOT)
	@mkdir -p $(@D)
	$(MODELS_TEAPOT) --triangles 5000 $(@:.ply=.tmp.ply) && mv $(@:.ply=.tmp.ply) $@

$(MODELS_DIR)/teapot-346k.ply: $(MODELS_TEAPOT)
	@mkdir -p $(@D)
	$(MODELS_TEAPOT) --triangles 345994 $(@:.ply=.tmp.ply) && mv $(@:.ply=.tmp.ply) $@

$(MODELS_DIR)/teapot-5k-uv.ply: $(MODELS_TEAPOT)
	@mkdir -p $(@D)
	$(MODELS_TEAPOT) --uv --triangles 5000 $(@:.ply=.tmp.ply) && mv $(@:.ply=.tmp.ply) $@

# Committed; this rule only runs when it is missing, and says how to remake it (needs npm).
$(MODELS_DIR)/bunny.ply:
	@echo "$@ is missing: it is committed; remake it with tools/models/fetch-bunny.sh (needs npm)" >&2
	@false

## make clean-models   remove the generated teapots
clean-models:
	rm -f $(MODELS_GENERATED) $(MODELS_GENERATED:.ply=.tmp.ply)

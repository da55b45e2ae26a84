# bench/bench.mk: the acceleration benchmark of chapters 9 and 10. A GNU make fragment included from
# the top-level Makefile, which defines CC, BUILD, CFLAGS, LDFLAGS, LDLIBS and the rule that makes
# $(BUILD)/common/%.o from common/%.c.
#
#   make bench-accel   build $(BUILD)/bench_accel and run it on the big teapot and the bunny, with Intel
#                      Embree 3 as the yardstick (installs Debian's libembree-dev if it is missing)
#   make bench         every benchmark (for now bench-accel)
#
# bench/embree_ref.c is compiled in only when /usr/include/embree3/rtcore.h exists. So the bench-accel
# recipe installs the package first and only then makes the program, in a second make that sees the
# header. The objects of the two builds (with and without Embree) live in different directories, so
# installing Embree later rebuilds what must change.

BENCH_MODELS := scenes/models/teapot-346k.ply scenes/models/bunny.ply
BENCH_MODULES := bvh kdtree kdtree_events kdtree_check triangle stats mesh mesh_ply mesh_obj camera
BENCH_EMBREE := $(wildcard /usr/include/embree3/rtcore.h)
BENCH_VARIANT := $(if $(BENCH_EMBREE),embree,plain)
BENCH_SOURCES := bench/bench_accel.c $(if $(BENCH_EMBREE),bench/embree_ref.c)
BENCH_OBJECTS := $(patsubst bench/%.c,$(BUILD)/bench/$(BENCH_VARIANT)/%.o,$(BENCH_SOURCES))
BENCH_CFLAGS := $(if $(BENCH_EMBREE),-DWHITTED_EMBREE)
BENCH_LDLIBS := $(if $(BENCH_EMBREE),-lembree3)

.PHONY: bench bench-accel

bench: bench-accel

bench-accel: $(BENCH_MODELS)
	tools/install-deps.sh bench
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(BUILD)/bench_accel
	$(BUILD)/bench_accel $$([ -e /usr/include/embree3/rtcore.h ] && echo --embree) $(BENCH_MODELS)

$(BUILD)/bench/$(BENCH_VARIANT)/%.o: bench/%.c | $(BUILD)/bench/$(BENCH_VARIANT)
	$(CC) $(CFLAGS) $(BENCH_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/bench/$(BENCH_VARIANT):
	mkdir -p $@

$(BUILD)/bench_accel: $(BENCH_OBJECTS) $(addprefix $(BUILD)/common/,$(addsuffix .o,$(BENCH_MODULES)))
	$(CC) $(LDFLAGS) $^ -o $@ $(LDLIBS) $(BENCH_LDLIBS)

-include $(wildcard $(BUILD)/bench/*/*.d)

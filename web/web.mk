# web/web.mk: every chapter in the browser. A GNU make fragment included from the top-level Makefile,
# which defines CHAPTERS, MODULES_NN, SCENE_MODELS and SCENE_TEXTURES.
#
#   make web        compiles each chapter's own main.c and the common/ modules it links (MODULES_NN) to
#                   WebAssembly with Emscripten (Debian's emscripten, installed on demand) into
#                   build/web/: the page (index.html, page.js, worker.js), one chapter-NN.js and
#                   chapter-NN.wasm per chapter (the page loads only the chapter it shows), the scenes,
#                   their meshes and textures. A static folder: any web server can serve it.
#   make serve      serves build/web on http://localhost:$(WEB_PORT)/ (python3's http.server)
#   make test-web   builds the page and the native chapters 2, 8 and 10, serves the page and drives it in
#                   headless Chromium (web/test_web.py): pictures against the native ones, frame rates,
#                   a parse error, the big teapot, the screenshot docs/figures/web-page.png
#
# The same floating-point rules as the native build: -ffp-contract=off (WebAssembly has no fused
# multiply-add anyway) and no fast-math. Chapter 11's four-float boxes (common/float4.h) use GCC's
# vector extension; with -msimd128 clang compiles it to WebAssembly's 128-bit SIMD instructions (the
# x86 intrinsics are behind __SSE__, which is not defined here), and the lanes compute what SSE's
# minps/maxps compute, so the picture is the same. OpenMP is not used: the page renders in one worker,
# one thread (render.c's loop runs serially without _OPENMP). stb's code, a library natively, is
# compiled in from its header by web/stb_code.c.

WEB := build/web
# The objects, beside the folder the page is served from (which holds only what the page loads).
WEB_OBJ := build/web-obj
WEB_PORT ?= 8642
# Debian's emcc runs JavaScript tools (acorn) that Debian installs under /usr/share/nodejs; a node from
# elsewhere does not look there by itself.
EMCC := NODE_PATH=/usr/share/nodejs emcc
WEB_CFLAGS := -std=c11 -D_DEFAULT_SOURCE -O2 -ffp-contract=off -msimd128 -Wall -Wextra -Werror -Icommon \
              -I/usr/include/stb
# One module per chapter, run like a process: the worker makes a fresh instance for every render and
# calls main with the command line (so each render starts from the program's first state, as natively).
WEB_LDFLAGS := -O2 -msimd128 -sMODULARIZE=1 -sEXPORT_NAME=createChapter -sENVIRONMENT=worker \
               -sINVOKE_RUN=0 -sEXIT_RUNTIME=1 -sALLOW_MEMORY_GROWTH=1 -sMAXIMUM_MEMORY=2GB \
               -sFORCE_FILESYSTEM=1 -sEXPORTED_RUNTIME_METHODS=FS,callMain
WEB_PAGE := $(addprefix $(WEB)/,index.html page.js worker.js)
WEB_CHAPTERS := $(foreach c,$(CHAPTERS),$(WEB)/chapter-$(call chapter_number,$(c)).js)

.PHONY: web serve test-web web-deps

## make web            every chapter compiled to WebAssembly, with the page, scenes and meshes, into
##                     build/web/ (a static folder; installs Debian's emscripten first)
web: $(WEB_CHAPTERS) $(WEB_PAGE) $(WEB)/scenes.stamp

## make serve          serves build/web on http://localhost:8642/ (WEB_PORT=N for another port)
serve: web
	@echo "the chapters in the browser: http://localhost:$(WEB_PORT)/"
	cd $(WEB) && python3 -m http.server --bind 127.0.0.1 $(WEB_PORT)

## make test-web       the page in headless Chromium against the native chapters 2, 8 and 10: same
##                     pixels, frame rates, a parse error, the big teapot, README's screenshot
test-web: web $(BUILD)/chapter-02 $(BUILD)/chapter-08 $(BUILD)/chapter-10 | deps
	tools/build/install-deps.sh test-web
	/usr/bin/python3 web/test_web.py --web $(WEB) --build $(BUILD) --port $(WEB_PORT) \
	    --screenshot docs/figures/web-page.png

web-deps:
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

-include $(wildcard $(WEB_OBJ)/*/*.d)

# One module per chapter, linked from exactly that chapter's modules (as the native link).
define web_chapter_rules
$(WEB)/chapter-$(call chapter_number,$(1)).js: $(WEB_OBJ)/chapters/$(1).o $(WEB_OBJ)/stb_code.o \
        $(addprefix $(WEB_OBJ)/common/,$(addsuffix .o,$(MODULES_$(call chapter_number,$(1)))))
	$(EMCC) $(WEB_LDFLAGS) $$^ -o $$@
endef
$(foreach c,$(CHAPTERS),$(eval $(call web_chapter_rules,$(c))))

$(WEB)/%: web/%
	@mkdir -p $(@D)
	cp $< $@

# The scenes and what they name (mesh and texture paths are relative to scenes/), and the list of
# scenes the page offers.
$(WEB)/scenes.stamp: $(wildcard scenes/*.scene) $(SCENE_MODELS) $(SCENE_TEXTURES) scenes/models/bunny.ply
	@mkdir -p $(WEB)/scenes/models $(WEB)/scenes/textures
	cp scenes/*.scene $(WEB)/scenes/
	cp $(SCENE_MODELS) scenes/models/bunny.ply $(WEB)/scenes/models/
	cp $(SCENE_TEXTURES) $(WEB)/scenes/textures/
	cd scenes && ls *.scene | sed 's/.*/"&"/' | paste -sd, | sed 's/.*/[&]/' > ../$(WEB)/scenes/index.json
	touch $@

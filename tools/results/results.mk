# tools/results/results.mk: make results, the seed's experiments redone (docs/results.md). A GNU make
# fragment included from the top-level Makefile, which defines CC, BUILD, CFLAGS and the chapters' rules.
#
#   make results          run every experiment (about a quarter of an hour: 13.8 minutes in the run
#                         docs/results.md shows), write the CSVs to out/results/, copy them to
#                         docs/results/, and redraw docs/results/*.svg and
#                         the tables of docs/results.md from them (installs gnuplot-nox, POV-Ray and
#                         Embree when missing)
#   make results QUICK=1  the same experiments on small pictures and models, about a minute: the
#                         CSVs, plots, pictures and a copy of the page with its tables go to
#                         out/results-quick/, and docs/ is left alone (make test-long runs this)
#
# tools/results/run.sh runs the experiments, tools/results/publish.sh draws and writes the tables
# (tools/results/plots.gp, tools/results/tables.awk); publish.sh --check is what the tests use to
# find a committed plot or table that is stale against its CSV.

RESULTS_QUICK_DIR := out/results-quick

$(BUILD)/measure: tools/results/measure.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $< -o $@

.PHONY: results
## make results        the seed's experiments redone: CSVs, plots and tables of docs/results.md, about a
##                     quarter of an hour (QUICK=1: a small version in about a minute, into out/results-quick/)
ifeq ($(QUICK),1)
results: all $(BUILD)/measure $(MODELS_TEAPOT) | deps
	BUILD=$(BUILD) TEAPOT=$(MODELS_TEAPOT) tools/results/run.sh --quick $(RESULTS_QUICK_DIR)
	sed 's#](results/#](#g' docs/results.md >$(RESULTS_QUICK_DIR)/results.md
	tools/results/publish.sh $(RESULTS_QUICK_DIR) $(RESULTS_QUICK_DIR) $(RESULTS_QUICK_DIR)/results.md
	@echo "quick results: $(RESULTS_QUICK_DIR)/results.md, with its CSV files, plots and pictures beside it"
else
results: all $(BUILD)/measure $(MODELS_TEAPOT) | deps
	tools/build/install-deps.sh bench
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) $(BUILD)/bench_accel
	BUILD=$(BUILD) TEAPOT=$(MODELS_TEAPOT) tools/results/run.sh out/results
	mkdir -p docs/results
	cp out/results/*.csv out/results/*.png docs/results/
	tools/results/publish.sh docs/results docs/results docs/results.md
	@echo "results: docs/results.md, docs/results/ (CSV files and plots)"
endif

# inertest: the two commands of the quick start are `make demo` and `make test`.
# Each installs the Debian packages it needs (scripts/install-deps.sh), then builds in build/.

BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PYTHON ?= /usr/bin/python3
CMAKE_FLAGS ?=
# make bench BENCH_FLAGS=--huge adds the 1e9-sample f32 record (4 GB written to the temp dir, deleted after).
BENCH_FLAGS ?=
# The sanitizer suite and the fuzz targets share one clang build with ASan + UBSan (+ libFuzzer).
SANITIZE_DIR ?= build-sanitize
FUZZ_SECONDS ?= 600
FUZZ_SHORT_SECONDS ?= 20
FUZZ_MAX_LEN ?= 4096
FUZZ_TIMEOUT ?= 10
FUZZ_TARGETS := text_table binary_record plan mat_record hdf5_record tdms_record
export ASAN_OPTIONS ?= detect_leaks=1:strict_string_checks=1
export UBSAN_OPTIONS ?= halt_on_error=1:print_stacktrace=1

.PHONY: all deps configure build test test-normal demo bench clean sanitize-build test-sanitize fuzz test-fuzz-short

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DINERTEST_BUILD_TESTS=ON \
		-DINERTEST_BUILD_PYTHON=ON -DPYTHON_EXECUTABLE=$(PYTHON) $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The normal suite, then the same suite under ASan + UBSan, then a short pass of each fuzz target.
test: test-normal test-sanitize test-fuzz-short

test-normal: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

sanitize-build: deps
	@cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ \
	  -DINERTEST_SANITIZE=ON -DINERTEST_BUILD_FUZZERS=ON -DINERTEST_BUILD_TESTS=ON > /dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS)

# Left out: find_package_downstream (it links an uninstrumented program against the library) and
# report_in_chromium and serve_in_chromium (they test the browser's rendering, not our memory safety;
# the server's own code runs under the sanitizers in server_test).
test-sanitize: sanitize-build
	@cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS) -E '^(find_package_downstream|report_in_chromium|serve_in_chromium)$$'

# Each target runs FUZZ_SECONDS on its seed corpus (fuzz/corpus/<target>/, read only); new inputs
# go to $(SANITIZE_DIR)/fuzz/<target>/, and a crash, hang (FUZZ_TIMEOUT s) or leak fails the run
# and leaves its input as $(SANITIZE_DIR)/fuzz/<target>-crash-* (or -timeout-*, -leak-*).
# The targets run JOBS at a time (one core each), so each gets its whole FUZZ_SECONDS of a core.
fuzz: sanitize-build
	@$(MAKE) --no-print-directory -j $(JOBS) $(addprefix fuzz-,$(FUZZ_TARGETS))

fuzz-%:
	@mkdir -p $(SANITIZE_DIR)/fuzz/$* && \
	  echo "fuzz: $* for $(FUZZ_SECONDS) s" && \
	  $(SANITIZE_DIR)/bin/$*_fuzzer -max_total_time=$(FUZZ_SECONDS) -max_len=$(FUZZ_MAX_LEN) \
	    -timeout=$(FUZZ_TIMEOUT) -rss_limit_mb=2048 -detect_leaks=1 -print_final_stats=1 \
	    -artifact_prefix=$(SANITIZE_DIR)/fuzz/$*- \
	    $(SANITIZE_DIR)/fuzz/$* fuzz/corpus/$* 2> $(SANITIZE_DIR)/fuzz/$*.log || \
	  { tail -n 60 $(SANITIZE_DIR)/fuzz/$*.log; echo "fuzz: $* FAILED"; exit 1; }; \
	  echo "fuzz: $* $$(grep -E '^stat::number_of_executed_units' $(SANITIZE_DIR)/fuzz/$*.log)"

test-fuzz-short:
	@$(MAKE) --no-print-directory fuzz FUZZ_SECONDS=$(FUZZ_SHORT_SECONDS)

demo: build
	@$(BUILD_DIR)/bin/inertest demo --out demo > /dev/null; status=$$?; \
	  echo "demo: report in demo/report.html (text: demo/report.txt), results with truth_check in demo/results.json"; \
	  [ $$status -eq 0 ] || exit $$status; \
	  $(BUILD_DIR)/bin/inertest demo --fleet --out demo/fleet > /dev/null && \
	  echo "demo: fleet archive in demo/fleet/archive.sqlite, pages demo/fleet/fleet.html and demo/fleet/history-*.html" && \
	  rm -f demo/archive.sqlite demo/archive.sqlite-wal demo/archive.sqlite-shm && \
	  cp demo/fleet/archive.sqlite demo/archive.sqlite && \
	  $(BUILD_DIR)/bin/inertest archive add demo/results.json --db demo/archive.sqlite > /dev/null && \
	  echo "demo: the fleet and the demo campaign in demo/archive.sqlite (inertest serve --db demo/archive.sqlite)"

bench: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DINERTEST_BUILD_BENCHMARKS=ON > /dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)
	@$(PYTHON) bench/bench.py --build-dir $(BUILD_DIR) $(BENCH_FLAGS)

clean:
	@rm -rf $(BUILD_DIR) $(SANITIZE_DIR) demo

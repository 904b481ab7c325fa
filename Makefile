# inertest: the two commands of the quick start are `make demo` and `make test`.
# Each installs the Debian packages it needs (scripts/install-deps.sh), then builds in build/.

BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PYTHON ?= /usr/bin/python3
CMAKE_FLAGS ?=

.PHONY: all deps configure build test demo bench clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DINERTEST_BUILD_TESTS=ON \
		-DINERTEST_BUILD_PYTHON=ON -DPYTHON_EXECUTABLE=$(PYTHON) $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD_DIR)/bin/inertest demo --out demo > /dev/null; status=$$?; \
	  echo "demo: report in demo/report.txt, results (with truth_check) in demo/results.json"; exit $$status

bench: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DINERTEST_BUILD_BENCHMARKS=ON > /dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)
	@for script in bench/*_compare.py; do $(PYTHON) $$script --build-dir $(BUILD_DIR) || exit 1; done

clean:
	@rm -rf $(BUILD_DIR) demo

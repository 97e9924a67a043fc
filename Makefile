# Entry points for users: `make demo` and `make test` work on a fresh
# Debian 12 machine (they install missing packages first, as root).
BUILD ?= build
ASAN  ?= build-asan
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
CLI    = $(BUILD)/unstack
OUT   ?= demo-out

.PHONY: all deps build asan demo test test-release test-asan bench clean

all: build

deps:
	@bash scripts/deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

asan: deps
	@cmake -S . -B $(ASAN) -DCMAKE_BUILD_TYPE=Debug -DUS_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN) -j$(JOBS)

# The main job on a built-in default: the source's 91-block pyramid.
demo: build
	@mkdir -p $(OUT)
	$(CLI) generate pyramid --rows 13 -o $(OUT)/pyramid.json
	$(CLI) check $(OUT)/pyramid.json
	$(CLI) plan $(OUT)/pyramid.json -o $(OUT)/pyramid-plan.json
	$(CLI) verify $(OUT)/pyramid.json $(OUT)/pyramid-plan.json
	$(CLI) render $(OUT)/pyramid.json --plan $(OUT)/pyramid-plan.json -o $(OUT)/pyramid.svg
	@echo "wrote $(OUT)/pyramid-plan.json and $(OUT)/pyramid.svg"

test-release: build
	cd $(BUILD) && ctest -j$(JOBS) --output-on-failure

test-asan: asan
	cd $(ASAN) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest -j$(JOBS) --output-on-failure -E '^bench'

test: test-release test-asan

bench: build
	bash bench/run.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN) $(OUT)

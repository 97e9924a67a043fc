# Entry points for users: `make demo` and `make test` work on a fresh
# Debian 12 machine (they install missing packages first, as root).
BUILD ?= build
ASAN  ?= build-asan
TSAN  ?= build-tsan
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
CLI    = $(BUILD)/unstack
OUT   ?= demo-out
QUICK ?= 0

.PHONY: all deps build cli asan demo test test-release test-asan test-tsan bench clean fuzz fuzz-build

all: build

deps:
	@bash scripts/deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

asan: deps
	@cmake -S . -B $(ASAN) -DCMAKE_BUILD_TYPE=Debug -DUS_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN) -j$(JOBS)

# What the demo runs: the tool and its modules (docs/modules.md), none of
# the test programs; `make build` and `make test` build everything.
cli:
	@bash scripts/deps.sh demo
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS) --target unstack_cli

# `make install PREFIX=P` (docs/install.md): builds only what is installed
# (the tool, libunstack.so, its modules; no tests) and installs it under P
# in Debian's layout; DESTDIR=D stages it under D for a package.
PREFIX ?= /usr/local
.PHONY: install
install:
	@bash scripts/deps.sh demo
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS) --target us_installed
	DESTDIR="$(DESTDIR)" cmake --install $(BUILD) --prefix "$(abspath $(PREFIX))"

# The main job on a built-in default: the source's 91-block pyramid.
demo: cli
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

# ThreadSanitizer on what runs threads: unstack batch (tests/cli/batch.sh,
# --jobs 2) and test_threads; only those two targets are built (no MPI:
# mpirun runs in the release suite)
test-tsan: deps
	@cmake -S . -B $(TSAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUS_TSAN=ON -DUS_MPI=OFF >/dev/null
	@cmake --build $(TSAN) -j$(JOBS) --target unstack_cli test_threads
	cd $(TSAN) && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
	  ctest -j$(JOBS) --output-on-failure -R '^(threads\.|cli\.batch$$)'

test: test-release test-asan test-tsan

# QUICK=1: a subset in under a minute (bench/results/*-quick.*)
bench: build
	QUICK=$(QUICK) bash bench/run.sh $(BUILD)

# libFuzzer (docs/fuzzing.md): clang builds the targets of tests/fuzz/ into
# $(FUZZ_BUILD); each runs FUZZ_TIME seconds from its seed corpus. New
# inputs and findings go to $(FUZZ_OUT), never into the repository.
FUZZ_BUILD   ?= build-fuzz
FUZZ_OUT     ?= $(FUZZ_BUILD)/out
FUZZ_TIME    ?= 60
FUZZ_TARGETS ?= structure pipeline oom svg html mesh
FUZZ_FLAGS   ?= -max_len=8192 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1

fuzz-build:
	@bash scripts/deps.sh fuzz
	@CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUS_FUZZ=ON >/dev/null
	@cmake --build $(FUZZ_BUILD) -j$(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS)) -- --no-print-directory

fuzz: fuzz-build
	@found=0; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_OUT)/$$t/corpus $(FUZZ_OUT)/$$t/findings; \
	  echo "fuzz_$$t: $(FUZZ_TIME) s, new inputs in $(FUZZ_OUT)/$$t/corpus"; \
	  OPENBLAS_NUM_THREADS=1 $(FUZZ_BUILD)/fuzz_$$t $(FUZZ_FLAGS) -max_total_time=$(FUZZ_TIME) \
	    -dict=tests/fuzz/$$( [ -f tests/fuzz/$$t.dict ] && echo $$t || echo json).dict -artifact_prefix=$(FUZZ_OUT)/$$t/findings/ \
	    $(FUZZ_OUT)/$$t/corpus tests/fuzz/corpus/$$t 2>$(FUZZ_OUT)/$$t/log \
	    || { found=1; echo "fuzz_$$t: FINDING in $(FUZZ_OUT)/$$t/findings/ (log: $(FUZZ_OUT)/$$t/log)"; }; \
	  tail -n 3 $(FUZZ_OUT)/$$t/log; \
	done; exit $$found

clean:
	rm -rf $(BUILD) $(ASAN) $(TSAN) $(OUT) $(FUZZ_BUILD)

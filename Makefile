# The two entry commands (README): `make run` renders the default scene, `make test` runs the whole suite.
# Both install what they need first (scripts/setup.sh, Debian packages only).
BUILD ?= build
CONFIG ?= Release
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
SIZE ?= 256x256
CTEST_ARGS ?=
FUZZ_SECONDS ?= 120

.PHONY: setup configure build run test test-asan bench fuzz clean

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(CONFIG) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	@mkdir -p out
	@$(BUILD)/bin/idk render --size $(SIZE) --out out/default.png
	@echo "out/default.png"

# The fuzz harnesses (ctest label fuzz) run from build-fuzz/, a clang build shared by both test passes.
test: build
	@bash scripts/fuzz.sh build
	@ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 900 $(CTEST_ARGS)

# AddressSanitizer + UndefinedBehaviorSanitizer build of the whole suite, in its own build folder. The fuzz
# harnesses (label fuzz) are the same build-fuzz/ binaries in both passes, already built with ASan by clang, so
# this pass does not run them a second time.
test-asan:
	@$(MAKE) --no-print-directory test BUILD=build-asan CONFIG=RelWithDebInfo CMAKE_FLAGS="-DIDK_SANITIZE=ON $(CMAKE_FLAGS)" \
		CTEST_ARGS="-LE fuzz"

bench: build
	@bash scripts/bench.sh $(BUILD)

# Every libFuzzer harness for FUZZ_SECONDS each, its corpus kept in build-fuzz/corpus/ (scripts/fuzz.sh).
fuzz: setup
	@bash scripts/fuzz.sh all $(FUZZ_SECONDS)

clean:
	@rm -rf $(BUILD) build-asan build-fuzz out

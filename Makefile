# liftmap: the two commands of the README's quick start are `make demo` and `make test`.
# Both install the Debian packages they need (scripts/install-deps.sh) and build first.

BUILD      ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
FUZZ_SECONDS ?= 600
FUZZ_JOBS  ?= 1
JOBS       ?= 2
LIFTMAP    := $(BUILD)/app/liftmap
SOURCES    := $(shell find src app python tests bench fuzz -name '*.cpp' -o -name '*.h' 2>/dev/null)

.PHONY: all deps meshes build build-asan test test-slow test-blas-kernels demo bench fuzz lint format clean

all: build

deps:
	@./scripts/install-deps.sh

meshes: deps
	@./scripts/get-meshes.sh

$(BUILD)/build.ninja: CMakeLists.txt
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

$(BUILD_ASAN)/build.ninja: CMakeLists.txt
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLIFTMAP_SANITIZE=ON

build-asan: deps $(BUILD_ASAN)/build.ninja
	cmake --build $(BUILD_ASAN) -j $(JOBS)

# The suite in Release, then again under AddressSanitizer + UndefinedBehaviorSanitizer. Tests labelled `slow`
# (the 300-configuration cut sweep) run with `make test-slow`; the CVXOPT differential test is in the suite.
test: meshes build build-asan
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -LE slow
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(BUILD_ASAN) --output-on-failure -j $(JOBS) -LE slow

test-slow: meshes build
	cmake --build $(BUILD) --target bench_scaling
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -L slow

# The solver, flattening and whole-map tests (ctest label `solver`) once per OpenBLAS kernel the CPU supports.
test-blas-kernels: meshes build
	./scripts/test-blas-kernels.sh $(BUILD) $(JOBS)

demo: meshes build
	./scripts/demo.sh $(LIFTMAP)

# Builds only what it runs (the tests are not needed), then works to a 42-minute budget (bench/run.py's PLAN).
bench: meshes $(BUILD)/build.ninja
	cmake --build $(BUILD) --target liftmap benchmarks -j $(JOBS)
	./bench/run.py $(BUILD)

# libFuzzer targets of the file readers (clang, ASan + UBSan), each run FUZZ_SECONDS (FUZZ_JOBS at a time).
$(BUILD_FUZZ)/build.ninja: CMakeLists.txt
	CXX=clang++-14 CC=clang-14 cmake -S . -B $(BUILD_FUZZ) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DLIFTMAP_FUZZ=ON -DLIFTMAP_BUILD_TESTS=OFF

fuzz: deps $(BUILD_FUZZ)/build.ninja
	cmake --build $(BUILD_FUZZ) --target fuzzers -j $(JOBS)
	FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_JOBS=$(FUZZ_JOBS) ./scripts/fuzz.sh $(BUILD_FUZZ)

# Formatting and static analysis, as checked by CI.
lint: build
	clang-format --dry-run --Werror $(SOURCES)
	printf '%s\n' $(filter %.cpp,$(filter src/% app/%,$(SOURCES))) | xargs -P $(JOBS) -n 8 clang-tidy -p $(BUILD) --quiet

format:
	clang-format -i $(SOURCES)

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ)

# The Makefile only drives CMake (STYLE.md convention 13).
BUILD ?= build
TYPE  ?= RelWithDebInfo
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=

# `make fuzz`: the libFuzzer targets of tests/fuzz, FUZZ_SECONDS each (clang).
# `make test-sanitize`: the whole suite built with ASan + UBSan.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?=
SAN_BUILD    ?= build-asan
CTEST_FLAGS  ?=

.PHONY: all deps configure build test demo bench clean docs format fuzz test-sanitize validate

all: build

deps:
	@bash scripts/deps.sh

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(TYPE) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# `make validate`: the long tier (docs/validation/README.md), hours on 2
# cores; CASES="packing_six hopper_dead_zone" picks cases, QUICK=1 runs
# their short forms (minutes), which write nothing into docs/.
CASES ?=
QUICK ?=
validate: configure
	cmake --build $(BUILD) -j $(JOBS) --target shapedem
	bash validate/run $(BUILD) $(if $(QUICK),--quick) $(CASES)

fuzz: deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DSHAPEDEM_FUZZ=ON -DSHAPEDEM_OPENMP=OFF $(CMAKE_FLAGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_programs
	bash tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# Halts at the first report (-fno-sanitize-recover); leaks are reports too.
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHAPEDEM_SANITIZE=ON $(CMAKE_FLAGS)
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ASAN_OPTIONS=$${ASAN_OPTIONS:-detect_leaks=1} \
	  UBSAN_OPTIONS=$${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
	  ctest --output-on-failure -j $(JOBS) $(CTEST_FLAGS)

# The demo builds only the program it runs (and shapedem-mpi with it, in an
# MPI build: the README's mpirun line), not the test suite.
demo: configure
	cmake --build $(BUILD) -j $(JOBS) --target shapedem
	$(BUILD)/shapedem run examples/settle-spheres.yaml -o out/settle-spheres

bench:
	@bash bench/run

# docs/scene-format.md from the key table, and the README's package list
# (the line after its marker) from scripts/deps.sh --list
docs: build
	$(BUILD)/shapedem help scene --markdown > docs/scene-format.md
	list=$$(SHAPEDEM_WITH_BENCH= bash scripts/deps.sh --list | paste -sd ' '); \
	sed -i "/^<!-- scripts\/deps.sh --list -->$$/{n;s/.*/\`$$list\`/;}" README.md

format:
	clang-format -i $$(git ls-files '*.c' '*.h' '*.cu')

clean:
	rm -rf $(BUILD)

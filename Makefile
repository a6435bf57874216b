# seam: `make run` builds and runs the flagship example; `make test` builds and runs the tests.
BUILD ?= build
JOBS ?= $(shell nproc)
EXAMPLE ?= examples/cattaneo_mindlin/cattaneo.yaml

SANITIZE_BUILD ?= build-sanitize
# What `make sanitize` runs: the unit tests and the verification cases that are small enough
# to run instrumented (a finding fails the test: the sanitizers stop the program with exit 86).
SANITIZE_TESTS ?= unit_|verify_(patch|bad_input|fuzz|progress)$$
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=0:exitcode=86:strict_string_checks=1:detect_stack_use_after_return=1 \
  UBSAN_OPTIONS=halt_on_error=1:exitcode=86:print_stacktrace=1

.PHONY: all deps configure build run test bench format clean sanitize

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then \
	  cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release; fi

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The flagship: a cylinder pressed on a block of the same material (non-matching meshes) and
# pulled sideways with Coulomb friction; the comparison with Hertz and Cattaneo-Mindlin is
# printed and drawn into $(BUILD)/run/cattaneo.png.
run: build
	cd examples && ../$(BUILD)/bin/seam run $(abspath $(EXAMPLE)) -o $(abspath $(BUILD)/run)
	@if [ "$(EXAMPLE)" = "examples/cattaneo_mindlin/cattaneo.yaml" ]; then \
	  /usr/bin/python3 scripts/plot_contact.py cattaneo $(BUILD)/run --mu 0.3 \
	    -o $(BUILD)/run/cattaneo.png && \
	  echo "seam: the tractions against Cattaneo-Mindlin are drawn in $(BUILD)/run/cattaneo.png"; fi
	@echo "seam: results written to $(BUILD)/run (open results.pvd in ParaView)"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# AddressSanitizer + UndefinedBehaviorSanitizer in its own build folder (ccache keys on the
# flags, so the two builds share its cache without conflicts). Leak detection is off: MPI and
# PETSc keep their allocations to the end of the process. The instrumented build is compiled at
# -O1 with line tables only (-g1): the sanitizers check the same code as at -O2 (-O1 is what
# their documentation recommends; it inlines less, so fewer accesses are folded away), and a
# finding's stack trace still names file, line and function, but the cold build costs
# about half of RelWithDebInfo's -O2 -g (README "Sanitizers"). Without the benchmarks the
# default target is exactly what SANITIZE_TESTS run: bin/seam and the unit test executables.
SANITIZE_FLAGS ?= -O1 -g1 -DNDEBUG
sanitize: deps
	@if [ ! -f $(SANITIZE_BUILD)/build.ninja ]; then \
	  cmake -S . -B $(SANITIZE_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(SANITIZE_FLAGS)" \
	    -DCMAKE_C_FLAGS_RELWITHDEBINFO="$(SANITIZE_FLAGS)" \
	    -DSEAM_SANITIZE=ON -DSEAM_BUILD_BENCH=OFF; fi
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -R '$(SANITIZE_TESTS)'

bench: build
	$(BUILD)/bin/seam-bench --help

format:
	find apps src tests bench -name '*.[ch]pp' | xargs clang-format -i

clean:
	rm -rf $(BUILD)

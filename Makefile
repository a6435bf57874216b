# seam: `make run` builds and runs the flagship example; `make test` builds and runs the tests.
BUILD ?= build
JOBS ?= $(shell nproc)
EXAMPLE ?= examples/neo_hooke_block/block.yaml

.PHONY: all deps configure build run test bench format clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then \
	  cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release; fi

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	cd examples && ../$(BUILD)/bin/seam run $(abspath $(EXAMPLE)) -o $(abspath $(BUILD)/run)
	@echo "seam: results written to $(BUILD)/run (open results.pvd in ParaView)"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/bin/seam-bench --help

format:
	find apps src tests bench -name '*.[ch]pp' | xargs clang-format -i

clean:
	rm -rf $(BUILD)

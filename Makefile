# The two commands of the README:
#   make demo   - set up, build, then translate, flatten, draw and explore a
#                 bundled example
#   make test   - set up, build, and run the whole test suite (lit + GoogleTest)
# Also: make build, make sanitize-test (ASan+UBSan build running the suite),
#       make bench, make format.

BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
CMAKE_GEN := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

.PHONY: all setup build demo test sanitize-test bench format clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release

build: setup $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@echo "== netlift translate examples/cylinder/closed.net (verified, canonical form)"
	$(BUILD)/bin/netlift translate examples/cylinder/closed.net
	@echo "== netlift opt -p flatten: one flat module"
	$(BUILD)/bin/netlift opt examples/cylinder/closed.net -p flatten --stats -o $(BUILD)/closed.flat.net
	cat $(BUILD)/closed.flat.net
	$(BUILD)/bin/netlift emit $(BUILD)/closed.flat.net --to dot -o $(BUILD)/closed.flat.dot
	dot -Tsvg $(BUILD)/closed.flat.dot -o $(BUILD)/closed.flat.svg
	@echo "== drawing written to $(BUILD)/closed.flat.svg"
	@echo "== netlift reach: the closed loop's state space"
	$(BUILD)/bin/netlift reach examples/cylinder/closed.net --summary json -q
	@echo "== a shortest run to the cylinder at its end, controller in step 2"
	$(BUILD)/bin/netlift reach examples/cylinder/closed.net -q --find 'p.end and c.step == 2'

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/CMakeCache.txt:
	cmake -S . -B $(ASAN_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Debug \
	  -DNETLIFT_SANITIZE=address,undefined

sanitize-test: setup $(ASAN_BUILD)/CMakeCache.txt
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	bash bench/run.sh $(BUILD)
	bash bench/reach-bench.sh $(BUILD)
	bash bench/enforce-bench.sh $(BUILD)
	bash bench/st-bench.sh $(BUILD)

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)

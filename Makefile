# The two commands of the README:
#   make demo   - set up, build, then run the lifter example end to end
#                 (examples/lifter/run.sh) and print where its reports are
#   make test   - set up, build, and run the whole test suite (lit + GoogleTest)
# Also: make build, make sanitize-test (ASan+UBSan build running the suite),
#       make bench, make format, make install PREFIX=/opt/netlift (the
#       binary, the plant library and the docs: CMakeLists.txt says where),
#       make package (a Debian package of the same tree, build/netlift_*.deb).

BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
PREFIX ?= /usr/local
CMAKE_GEN := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

.PHONY: all setup build demo test install package sanitize-test bench format clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release

build: setup $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@echo "== the lifter of the structural-reasoning paper: Ladder Diagram controller"
	@echo "== (PLCopen XML) + plant library -> closed loop -> reduced -> explored -> report"
	bash examples/lifter/run.sh $(BUILD)/bin/netlift $(BUILD)/lifter

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

package: build
	cd $(BUILD) && cpack -G DEB

$(ASAN_BUILD)/CMakeCache.txt:
	cmake -S . -B $(ASAN_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DNETLIFT_SANITIZE=address,undefined

sanitize-test: setup $(ASAN_BUILD)/CMakeCache.txt
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	bash bench/run.sh $(BUILD)
	bash bench/reach-bench.sh $(BUILD)
	bash bench/enforce-bench.sh $(BUILD)
	bash bench/st-bench.sh $(BUILD)
	bash bench/inputs-bench.sh $(BUILD)

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)

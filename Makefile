# The package's two everyday commands, for a fresh Debian 12 machine:
#   make demo   installs what is needed, builds, and runs the demo
#   make test   installs what is needed, builds, and runs every test
# Debian's python3 first: ROS's scripts (`#!/usr/bin/env python3`) need its rospkg,
# which a python3 earlier in PATH (pyenv, venv) lacks.
export PATH := /usr/bin:$(PATH)
SHELL := /bin/bash

# Not `build/`: rosrun ignores executables under <package>/build/.
BUILD ?= .build
BUILD_ABS := $(abspath $(BUILD))
JOBS ?= 2
DURATION ?= 10

.PHONY: deps build test sanitize fuzz demo bench peers clean

deps:
	bash scripts/install_deps

build: deps
	cmake -S . -B $(BUILD) -DPYTHON_EXECUTABLE=/usr/bin/python3 \
	  -DCATKIN_DEVEL_PREFIX=$(BUILD_ABS)/devel -DCMAKE_BUILD_TYPE=RelWithDebInfo
	cmake --build $(BUILD) -j$(JOBS)

test: build
	cmake --build $(BUILD) -j$(JOBS) --target tests
	bash scripts/run_tests $(BUILD)

# Every test again, built with AddressSanitizer and UndefinedBehaviorSanitizer; fails on
# any report. Their code runs several times slower: BCS_SLOWDOWN tells the tests that time
# the node's answers to allow that much more. (a leak is reported after the test's result file is written, so the log is
# searched too). std::regex in pluginlib's headers trips a false maybe-uninitialized
# warning under the sanitizers, hence that one warning is not an error here.
SANITIZE_BUILD ?= .build-sanitize
SANITIZE_FLAGS := -O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DPYTHON_EXECUTABLE=/usr/bin/python3 \
	  -DCATKIN_DEVEL_PREFIX=$(abspath $(SANITIZE_BUILD))/devel -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS="$(SANITIZE_FLAGS) -Wno-error=maybe-uninitialized" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined"
	cmake --build $(SANITIZE_BUILD) -j$(JOBS) --target tests
	BCS_SLOWDOWN=4 bash scripts/run_tests $(SANITIZE_BUILD) 2>&1 | tee $(SANITIZE_BUILD)/tests.log; test $${PIPESTATUS[0]} -eq 0
	! grep -E "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" -r $(SANITIZE_BUILD)/tests.log $(SANITIZE_BUILD)/test_results

# The libFuzzer targets (test/fuzz/), built with clang apart from the package, then each
# run for FUZZ_SECONDS in turn, one process; findings land in $(FUZZ_BUILD)/artifacts/.
FUZZ_BUILD ?= .build-fuzz
FUZZ_SECONDS ?= 60
fuzz:
	bash scripts/install_deps --fuzz
	cmake -S test/fuzz -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug
	cmake --build $(FUZZ_BUILD) -j$(JOBS)
	bash scripts/run_fuzz $(FUZZ_BUILD) $(FUZZ_SECONDS)

demo: build
	bash scripts/demo $(BUILD) $(DURATION)

bench: build
	cmake --build $(BUILD) -j$(JOBS) --target benchmarks
	bash bench/run_bench $(BUILD)

# The same scenes in ODE, Bullet and Box2D beside this package, in one run.
peers: build
	bash scripts/install_deps --peers
	cmake -S . -B $(BUILD) > /dev/null
	cmake --build $(BUILD) -j$(JOBS) --target compare_peers
	$(BUILD)/devel/lib/ball_collision_sim/compare_peers --out bench/results/$$(hostname -s)-peers.csv
	/usr/bin/python3 bench/peers_table bench/results/$$(hostname -s)-peers.csv

clean:
	rm -rf $(BUILD)

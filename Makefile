# ECO — two commands: `make demo` and `make test`.

BUILD      ?= build
ASAN_BUILD ?= build-sanitize
TSAN_BUILD ?= build-tsan
JOBS       ?= $(shell nproc)
DEBIAN_PACKAGES := cmake make g++ clang libclang-rt-14-dev lld libeigen3-dev libgtest-dev liblzf-dev zlib1g-dev libisal-dev \
                   liblz4-dev libzstd-dev libsqlite3-dev \
                   librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev pluginlib-dev \
                   librcpputils-dev librcutils-dev libament-index-cpp-dev \
                   python3-rosbag python3-sensor-msgs python3-nav-msgs python3-geometry-msgs python3-std-msgs python3-tf2-msgs \
                   ros-core libroscpp-dev libtf2-ros-dev libvisualization-msgs-dev libstd-srvs-dev python3-rospy python3-std-srvs \
                   libnanoflann-dev libcli11-dev nlohmann-json3-dev libpcl-dev \
                   pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest \
                   python3-matplotlib python3-pip python3-venv python3-setuptools python3-wheel \
                   pkg-config libcpp-httplib-dev libjs-three chromium chromium-driver python3-selenium
## Debian's own interpreter, whatever else is first on PATH (pyenv, conda).
PYTHON     ?= /usr/bin/python3

.PHONY: all deps build demo test test-release test-sanitize test-threads test-fuzz install python clean

all: build

deps:
	@scripts/install-deps.sh $(DEBIAN_PACKAGES)

## The release build leaves the C++ unit tests to the sanitizer phase (UNIT_TESTS=ON builds them
## here too): compiled twice, they were a third of `make test`'s time.
UNIT_TESTS ?= OFF
RELEASE_CONFIG = -DCMAKE_BUILD_TYPE=Release -DECO_BUILD_PYTHON=ON -DECO_UNIT_TESTS=$(UNIT_TESTS) -DPython_EXECUTABLE=$(PYTHON)
build: deps
	cmake -S . -B $(BUILD) $(RELEASE_CONFIG)
	cmake --build $(BUILD) -j $(JOBS)

## demo: the question a newcomer brings (should I use this instead of PCL's octree, a k-d tree, a
## voxel map?) on the simulator's default drive, written once to DEMO_DATA: the robot's case (raw
## scans, 2 points kept per 0.1 m) against PCL's octree, nanoflann and the scan pass; a LiDAR
## odometry on each map; then the paper's Table II settings. Builds the eco command alone; the
## results go under DEMO_OUT.
DEMO_DATA   ?= $(BUILD)/sim-default
DEMO_FRAMES ?= 120
DEMO_OUT    ?= $(BUILD)/demo
demo: deps
	cmake -S . -B $(BUILD) $(RELEASE_CONFIG)
	cmake --build $(BUILD) -j $(JOBS) --target eco_cli
	@test -f $(DEMO_DATA)/poses.txt || $(BUILD)/bin/eco simulate --out $(DEMO_DATA) --frames $(DEMO_FRAMES) --seed 1
	@rm -rf $(DEMO_OUT)  # each run's results in folders of their own: eco bench refuses an earlier run's
	@printf '\n== 1. The robot: raw scans, 2 points kept per 0.1 m cell; update, voxel map, KNN ==\n'
	$(BUILD)/bin/eco bench --data $(DEMO_DATA) --preset robot-cap-0.1 --methods eco,pcl_octree,nanoflann,scan_pass \
	  --brief --out $(DEMO_OUT)/robot
	@printf '\n== 2. A LiDAR odometry on each map: the same frames, the same registration ==\n'
	$(BUILD)/bin/eco odometry --data $(DEMO_DATA) --map all --out $(DEMO_OUT)/odometry
	@printf "\n== 3. The paper's Table II settings: ShiftInOnly, N_max = 8 ==\n"
	$(BUILD)/bin/eco bench --data $(DEMO_DATA) --preset paper --workload static --frames 30 --brief \
	  --out $(DEMO_OUT)/paper-static
	$(BUILD)/bin/eco bench --data $(DEMO_DATA) --preset paper --workload dynamic --brief --out $(DEMO_OUT)/paper-dynamic
	@printf '\nTo watch a drive in a web browser as ECO takes it in: $(BUILD)/bin/eco run --frames 60 --view\n'

## test: the command-line, Python, viewer and install tests and the vector loops' in a release
## build; every C++ unit test under AddressSanitizer + UBSan, built by clang (its UBSan also
## checks float-to-int conversions, which GCC's leaves out, and it compiles the tests in two
## thirds of GCC's time), and beside them each parser's libFuzzer target for a fixed time
## (FUZZ_SECONDS); then the concurrency tests under ThreadSanitizer.
FUZZ_SECONDS ?= 6
## The sanitized builds keep line tables only: all a sanitizer's report needs, and about 30 % less
## time to compile than full debug information; they link with LLVM's lld, a fifth of the time GNU
## ld takes for each of their hundred test executables.
SANITIZED_DEBUG := -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld \
                   -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld
## A report's allocation stack 4 frames deep, not 30: every allocation unwinds it, and the tests
## run 10-15 % faster (rerun a failing test with ASAN_OPTIONS unset for the whole stack).
SANITIZED_TEST_ASAN := malloc_context_size=4
test: test-release test-sanitize test-threads

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

## The sanitized build leaves out the eco command (a third of its compile time): its tests, and the
## viewer's server behind it, run in the release build; its code's libraries are tested here. The
## parsers' fuzzers are built and run beside the unit tests, on the same libraries.
SANITIZED_CONFIG = -DCMAKE_CXX_COMPILER=clang++ $(SANITIZED_DEBUG) -DECO_SANITIZE=ON -DECO_FUZZ=ON \
                   -DECO_FUZZ_SECONDS=$(FUZZ_SECONDS) -DECO_BUILD_EXAMPLES=OFF -DECO_BUILD_TOOLS=OFF \
                   -DPython_EXECUTABLE=$(PYTHON)
test-sanitize: deps
	cmake -S . -B $(ASAN_BUILD) $(SANITIZED_CONFIG)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=$(SANITIZED_TEST_ASAN) ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

## The concurrency tests under ThreadSanitizer, built by clang too (in two thirds of GCC's time).
test-threads: deps
	cmake -S . -B $(TSAN_BUILD) -DCMAKE_CXX_COMPILER=clang++ $(SANITIZED_DEBUG) -DECO_THREAD_SANITIZE=ON -DECO_BUILD_TOOLS=OFF -DECO_BUILD_EXAMPLES=OFF
	cmake --build $(TSAN_BUILD) -j $(JOBS) --target snapshot_threads_test batch_knn_test
	ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(JOBS)

## test-fuzz: the fuzzers alone (make test runs them in test-sanitize), e.g. longer: FUZZ_SECONDS=600.
test-fuzz: deps
	cmake -S . -B $(ASAN_BUILD) $(SANITIZED_CONFIG)
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target fuzzers
	ASAN_OPTIONS=$(SANITIZED_TEST_ASAN) ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) -R '^fuzz_'

## python: the Python package eco, built by pip through setuptools and our CMake, offline, for
## PYTHON. Debian's interpreter refuses pip outside a virtual environment (PEP 668) unless told;
## the package goes to /usr/local, which Debian leaves to the administrator.
PIP_FLAGS = --no-build-isolation --no-index --disable-pip-version-check \
  $(shell $(PYTHON) -c 'import os, sys, sysconfig; print("--break-system-packages" if sys.prefix == sys.base_prefix and os.path.exists(os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED")) else "")')
python: deps
	$(PYTHON) -m pip install $(PIP_FLAGS) ./python

## install: the C++ library into PREFIX (default /usr/local).
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(TSAN_BUILD)

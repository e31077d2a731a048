# palprig: the two set-up commands of the README.
#   make demo   install missing Debian packages (the build's only), configure, build the palprig program only, run the demo
#   make test   same set-up plus the test tools' packages, then build the suites and the fuzz targets and run the whole test suite
#   make build  configure and build everything, the benchmarks included (make bench runs them)
#   make package       the Debian package palprig_VERSION_ARCH.deb in build/ (CPack; docs/rig-pc.md)
#   make test-package  build it, run it from a scratch root, then (root) apt install it on this machine, run it as a lab user, apt purge it
#   make test-package-vm  the apt/lab-user part inside a fresh Debian 12 VM (QEMU), where real-time limits can be shown
#   make test-package-scratch  only the scratch-root part (no root needed, nothing installed; make test runs it)
#   make fuzz   run every fuzz target for a minute (make test runs each for a second)
#   make test-tsan  the threaded suites under ThreadSanitizer
#   make test-analyst  the analyst-only build (-DPALPRIG_RIG=OFF: stats, export, store) and its suites
#   make format the style of .clang-format applied to every C++ file (make test fails on one that differs)
# Both are idempotent: packages already present are not touched and the build is incremental.

BUILD      ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
BUILD_TSAN ?= build-tsan
BUILD_ANALYST ?= build-analyst
FUZZ_SECONDS ?= 60
JOBS       ?= 2
# Tests at a time: twice the compile jobs. Most of the suites' time is waiting, not computing (a
# throwaway PostgreSQL server starting, a rig served over Modbus in real time, sessions paced in
# real time, processes killed and restarted): measured one test at a time, the longest tests used
# 2-25 % of a core over their wall time (docs/benchmarks.md, "Build time"). The tests that do
# compute hard say so with ctest's PROCESSORS, so two of them never share the two cores with more.
TEST_JOBS  ?= $(shell echo $$(( $(JOBS) * 2 )))
CMAKE_ARGS ?=
# ccache (tools/debian-packages.txt; CMakeLists.txt makes it the compiler launcher) keyed by paths
# relative to the clone and not by the build folder: the analyst-only build (make test-analyst)
# then takes the objects it shares with the release build (the study-data floor's libraries and
# suites, compiled with the same flags) from the cache instead of compiling them again.
# Depend mode: on a miss the compiler runs once and its dependency file (-MD) makes the manifest,
# where ccache would otherwise run the preprocessor first (a cold build, as on CI, is all misses).
export CCACHE_BASEDIR := $(CURDIR)
# New build folders are Ninja's (tools/debian-packages.txt): Ninja compiles a target's sources
# while the libraries it links are still compiling, where Make's generator waits for them, so the
# two cores stay busy (a cold release build 279 s against 317 s; docs/benchmarks.md "Build
# time"). CMake reads this only when it creates a build folder: one made before keeps its own.
export CMAKE_GENERATOR := Ninja
export CCACHE_NOHASHDIR := 1
export CCACHE_DEPEND := 1

# Debian 12 packages, one per line: tools/debian-packages.txt what the program's build needs (make
# demo installs only these), tools/debian-packages-test.txt what the suites, the style gate, the
# fuzz targets and the package checks add (make test and the other test targets).
PACKAGES := $(shell grep -v '^\s*\#' tools/debian-packages.txt | tr '\n' ' ')
TEST_PACKAGES := $(shell grep -v '^\s*\#' tools/debian-packages-test.txt | tr '\n' ' ')
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps deps-test configure build build-suites test-tools demo package test-package test-package-scratch test-package-system test-package-vm test test-asan test-tsan test-analyst fuzz fuzz-build fuzz-smoke bench clean bids-validator format

all: build

# install_missing PACKAGES: apt-get install those not installed yet (nothing when all are).
define install_missing
	@missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "palprig: installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi
endef

deps:
	$(call install_missing,$(PACKAGES))

deps-test:
	$(call install_missing,$(PACKAGES) $(TEST_PACKAGES))

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_ARGS)

configure: deps $(BUILD)/CMakeCache.txt

# Everything: the default target (the program, its libraries, the suites) and the benchmarks.
build: configure
	cmake --build $(BUILD) -j$(JOBS) --target all palprig_benches

# What make test runs: the default target, without the benchmark programs (no test runs one; the
# style gate still checks their sources). About 110 s of a cold build's compiling.
build-suites: configure
	cmake --build $(BUILD) -j$(JOBS)

# Only the program the demo runs (the window is part of it): the 140 objects of the suites, the
# benchmarks and the fuzz targets' libraries are for make test.
demo: configure
	cmake --build $(BUILD) -j$(JOBS) --target palprig
	$(BUILD)/bin/palprig demo

# The Debian package: the installed targets only (not the suites), then CPack (packaging/packaging.cmake).
package: configure
	cmake --build $(BUILD) -j$(JOBS) --target palprig palprig_cli_docs palprig_changelog
	cd $(BUILD) && cpack -G DEB

# The package installed into a scratch root (dpkg -x) and run from a folder far from the clone
# (also package.InstallAndRun in make test).
test-package-scratch: deps-test package
	tests/package/install_and_run.sh $(BUILD) "$$(ls -t $(BUILD)/palprig_*.deb | head -n 1)"

# The package as a rig PC gets it (docs/rig-pc.md): the scratch-root run, then for real on this machine
# (root; it installs with apt, adds a lab user to the palprig group, runs as that user, purges).
# Not part of make test, since it changes the system. test-package-system: the same (its old name).
# Where no process may raise RLIMIT_RTPRIO (a container whose root lacks CAP_SYS_RESOURCE), the
# machine cannot show the real-time limits at work, so the same test then runs again inside a VM.
test-package: test-package-scratch
	$(SUDO) tests/package/apt_install_as_lab_user.sh "$$(ls -t $(BUILD)/palprig_*.deb | head -n 1)"
	@if $(SUDO) bash -c 'ulimit -Hr 90' 2>/dev/null; then echo "real-time limits checked on this machine"; \
	else $(MAKE) --no-print-directory test-package-vm; fi
test-package-system: test-package

# The apt install, lab-user and purge test inside a fresh Debian 12 virtual machine with its own
# kernel (tests/package/in_vm.sh; QEMU, KVM where present): the real-time limits shown for real.
VM_PACKAGES = qemu-system-x86 debootstrap e2fsprogs
test-package-vm: package
	$(call install_missing,$(VM_PACKAGES))
	$(SUDO) tests/package/in_vm.sh "$$(ls -t $(BUILD)/palprig_*.deb | head -n 1)"

# The compile needs only the build's packages (make demo's); the test tools' packages
# (tools/debian-packages-test.txt: clang, clang-tidy, PostgreSQL, Xvfb, SciPy, ... on a fresh
# machine mostly waiting on the network and dpkg) and then the BIDS validator's npm download
# are fetched beside it: make's -j2 starts both. No test runs before both have ended.
test: deps configure
	$(MAKE) --no-print-directory -j2 build-suites test-tools
	cd $(BUILD) && ctest --output-on-failure -j$(TEST_JOBS) --timeout 600
	$(MAKE) --no-print-directory fuzz-smoke

# What the suites need beyond the build: the test packages, then the BIDS validator (one after
# the other: both may run apt-get, which takes a lock).
test-tools: deps-test
	$(MAKE) --no-print-directory bids-validator

# The official BIDS validator (npm package, pinned), for the export test that checks a BIDS
# tree; into the build folder, never system-wide. npm itself is Debian's (with nodejs, 356
# packages, about 20 s): installed here, beside the compile, rather than with the test packages
# before it. Without npm (no apt, no network) the test says why it skips.
BIDS_VALIDATOR_VERSION := 1.15.0
bids-validator: configure
	@[ -x $(BUILD)/tools/node_modules/.bin/bids-validator ] || command -v npm >/dev/null 2>&1 || { \
	  echo "palprig: installing Debian's npm for the BIDS validator"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends npm >/dev/null \
	    || echo "palprig: apt could not install npm"; }
	@[ -x $(BUILD)/tools/node_modules/.bin/bids-validator ] || { \
	  if command -v npm >/dev/null 2>&1; then \
	    echo "palprig: installing bids-validator $(BIDS_VALIDATOR_VERSION) with npm into $(BUILD)/tools"; \
	    npm install --silent --no-audit --no-fund --prefix $(BUILD)/tools bids-validator@$(BIDS_VALIDATOR_VERSION) \
	      || echo "palprig: npm could not install bids-validator; the BIDS validation test will skip"; \
	  else echo "palprig: npm not found; the BIDS validation test will skip"; fi; }

# The fuzz targets of fuzz/ (libFuzzer, clang): only the reader libraries, in their own build dir.
fuzz-build: deps-test
	@[ -f $(BUILD_FUZZ)/CMakeCache.txt ] || CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DPALPRIG_FUZZ=ON
	cmake --build $(BUILD_FUZZ) -j$(JOBS)

# make test: each target for 1 s from its seeds (the shipped files), a crash fails the run.
fuzz-smoke: fuzz-build
	fuzz/run_fuzz.sh $(BUILD_FUZZ) 1

# Longer: FUZZ_SECONDS (60) per target; prints executions, time and crashes per target.
fuzz: fuzz-build
	fuzz/run_fuzz.sh $(BUILD_FUZZ) $(FUZZ_SECONDS)

# The threaded suites (loop, Modbus bus thread, tablet reader, telemetry writer) under
# ThreadSanitizer; a reported race fails the run.
TSAN_TESTS := \.(LoopRunner|ModbusLoopback|ModbusEndToEnd|TabletInput|RealtimeSafety|TelemetryHardening)\.
test-tsan: deps-test
	@[ -f $(BUILD_TSAN)/CMakeCache.txt ] || cmake -S . -B $(BUILD_TSAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DPALPRIG_TSAN=ON -DPALPRIG_BENCH=OFF -DPALPRIG_GUI=OFF
	cmake --build $(BUILD_TSAN) -j$(JOBS) --target palprig palprig_tests_controller
	cd $(BUILD_TSAN) && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
	  ctest --output-on-failure -j$(JOBS) --timeout 900 -R '$(TSAN_TESTS)'

# One run of every suite, the window's included, under AddressSanitizer + UndefinedBehaviorSanitizer (CI runs it).
# The window's code too: the Qt suites (offscreen, and the Xvfb cases) run under the sanitizers.
# Leaks are checked (LeakSanitizer): a process that leaks fails its test; only system libraries'
# allocations kept for the life of a process are suppressed (tools/lsan-suppressions.txt).
# The libraries at -O1 -g1, as the sanitizers' own documentation advises (the suites' own sources at
# -O0, tests/CMakeLists.txt): at -O0 Eigen's code ran the simulated
# sessions over ten times slower than the release build (14 sessions took over 300 s), and line
# tables are all a sanitizer report needs.
test-asan: deps-test
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DPALPRIG_SANITIZE=ON \
	  -DPALPRIG_BENCH=OFF -DPALPRIG_GUI=ON
	cmake --build $(BUILD_ASAN) -j$(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan-suppressions.txt:print_suppressions=0 \
	  ctest --output-on-failure -j$(TEST_JOBS) --timeout 900

# The analyst-only build: the study-data floor and the palprig command without any rig library
# (no libmodbus, comedilib or libevdev linked); its suites, the layout check and the refusal of
# the rig's commands. CI builds it once.
test-analyst: deps-test
	@[ -f $(BUILD_ANALYST)/CMakeCache.txt ] || cmake -S . -B $(BUILD_ANALYST) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DPALPRIG_RIG=OFF -DPALPRIG_GUI=OFF -DPALPRIG_BENCH=OFF
	cmake --build $(BUILD_ANALYST) -j$(JOBS)
	cd $(BUILD_ANALYST) && ctest --output-on-failure -j$(TEST_JOBS) --timeout 600

# Every C++ file formatted as .clang-format says (style.ClangFormat in make test checks it).
format: deps-test
	python3 tools/check_style.py format --fix

bench: build
	bench/run_all.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ) $(BUILD_TSAN) $(BUILD_ANALYST)

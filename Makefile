# palprig: the two set-up commands of the README.
#   make demo   install missing Debian packages, configure, build, run the demo
#   make test   same set-up, then the whole test suite
# Both are idempotent: packages already present are not touched and the build is incremental.

BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= 2
CMAKE_ARGS ?=

# Debian 12 packages the build needs (one per line in tools/debian-packages.txt).
PACKAGES := $(shell grep -v '^\s*\#' tools/debian-packages.txt | tr '\n' ' ')
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps configure build demo test test-asan bench clean

all: build

deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "palprig: installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_ARGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j$(JOBS)

demo: build
	$(BUILD)/bin/palprig demo

test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS) --timeout 600

# One run of the core suites under AddressSanitizer + UndefinedBehaviorSanitizer (CI runs it).
test-asan: deps
	@[ -f $(BUILD_ASAN)/CMakeCache.txt ] || cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug \
	  -DPALPRIG_SANITIZE=ON -DPALPRIG_BENCH=OFF -DPALPRIG_GUI=OFF
	cmake --build $(BUILD_ASAN) -j$(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure -j$(JOBS) --timeout 900

bench: build
	bench/run_all.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)

# The two commands of the README, and a few more for developers.
#   make run       install what is missing, build, render the default scene
#   make test      install what is missing, build with -Werror, run the tests
#   make addon     build only the Blender add-on, $(BUILD)/shafts_blender.zip
#   make test-asan the test suite under AddressSanitizer + UBSan
#   make fuzz      the libFuzzer harnesses (clang), FUZZ_SECONDS each
#                  (docs/fuzzing.md; CI runs FUZZ_SECONDS=20)
#   make validate REPORT=DIR       cross-renderer report, quick (minutes)
#   make validate-full REPORT=DIR  the same, thorough (docs/validation.md)
BUILD ?= build
JOBS ?= $(shell nproc)
SCENE ?= scenes/teapot_spot.json
OUT ?= out
REPORT ?= $(BUILD)/validation-report
FUZZ_SECONDS ?= 600
VALIDATE_ARGS ?=

.PHONY: all bootstrap build addon run test test-asan fuzz validate validate-full clean

all: build

bootstrap:
	@tools/bootstrap.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DSHAFTS_WERROR=ON

build: bootstrap $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

addon: bootstrap $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target addon

run: build
	@tools/run_default.sh $(BUILD) $(SCENE) $(OUT)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-asan: bootstrap
	cmake -S . -B $(BUILD)-asan -DSHAFTS_WERROR=ON -DSHAFTS_SANITIZE=ON
	cmake --build $(BUILD)-asan -j $(JOBS)
	cd $(BUILD)-asan && LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp \
	  ctest --output-on-failure -j $(JOBS)

fuzz: bootstrap
	CC=clang CXX=clang++ cmake -S . -B $(BUILD)-fuzz -DSHAFTS_FUZZ=ON
	cmake --build $(BUILD)-fuzz -j $(JOBS) --target scene_fuzz mesh_fuzz
	fuzz/run.sh $(BUILD)-fuzz $(FUZZ_SECONDS)

validate: build
	python3 -m validation.validate --quick --report $(REPORT) --build-dir $(BUILD) $(VALIDATE_ARGS)

validate-full: build
	python3 -m validation.validate --full --report $(REPORT) --build-dir $(BUILD) $(VALIDATE_ARGS)

clean:
	rm -rf $(BUILD) $(BUILD)-asan $(BUILD)-fuzz

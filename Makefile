# plumage: the two-command setup.
#   make demo   install missing packages, build, render the default scene (build/demo/demo.png)
#   make test   install missing packages, build, run the default test suite (ctest)
# Also: make materials (every species variant characterised into build/materials), make build, make validate (slow validations, ctest label `validation`), make bench,
# make fuzz (each libFuzzer harness for 10 minutes), make test-sanitize (unit tests under ASan+UBSan).

BUILD ?= build
JOBS  ?= $(shell nproc)
PLUMAGE = $(BUILD)/bin/plumage
DEMO_OUT = $(BUILD)/demo

.PHONY: all deps configure build demo materials test validate bench fuzz test-sanitize clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log 2>&1 || \
	  (cat $(BUILD).configure.log; exit 1)
	@rm -f $(BUILD).configure.log

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The main job: render the default scene (configs/scenes/demo.yaml, a rock-dove neck of 1200
# barb-level feathers, paper Fig. 14). Its feather material (rock dove, forest) is taken from
# $(MATERIALS) when cached there, else characterised at preview fidelity first (~30 s CPU, once).
DEMO_SCENE ?= configs/scenes/demo.yaml
MATERIALS ?= $(BUILD)/materials
demo: build
	$(PLUMAGE) render $(DEMO_SCENE) --out $(DEMO_OUT) --materials $(MATERIALS)
	@echo "demo: wrote $(DEMO_OUT)/demo.exr (linear radiance) and $(DEMO_OUT)/demo.png (preview)"

# Every variant of every species of configs/species/ (SPECIES=rockdove starling... for some)
# characterised at FIDELITY into $(MATERIALS), under the names scenes and `render --materials`
# look up (`plumage materials`, material_batch.hpp): a current material is skipped, an interrupted
# one resumes from its journal, so the target can be stopped and rerun. CHARACTERIZE_FLAGS passes
# overrides through (e.g. --grid 4 --lambda-nm 400,500 for a quick look).
FIDELITY ?= production
SPECIES ?= all
CHARACTERIZE_FLAGS ?=
SPECIES_FILES = $(if $(filter all,$(SPECIES)),$(sort $(wildcard configs/species/*.yaml)),$(SPECIES:%=configs/species/%.yaml))
materials: build
	$(PLUMAGE) materials $(SPECIES_FILES) --fidelity $(FIDELITY) --into $(MATERIALS) $(CHARACTERIZE_FLAGS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE validation

validate: build
	cd $(BUILD) && ctest --output-on-failure -L validation

bench: build
	$(PLUMAGE) bench multilayer --record docs/benchmarks.md
	$(PLUMAGE) bench simulate --record docs/benchmarks.md
	$(PLUMAGE) bench ladder --record docs/benchmarks.md --chart-copy docs/img/ladder.png

# Each harness of fuzz/ for FUZZ_SECONDS (default 10 minutes), one at a time; new corpus entries
# and findings go to $(BUILD)/fuzz/campaign/ (fuzz/README.md). Needs clang + libclang-rt-14-dev.
FUZZ_SECONDS ?= 600
fuzz: build
	scripts/fuzz_campaign.sh $(BUILD) $(FUZZ_SECONDS)

# The default unit tests once under AddressSanitizer + UndefinedBehaviorSanitizer (g++, the
# compiler of the main build), in their own build folder. Not run there: the fuzz smoke tests
# (already sanitized, with clang) and the MPI launch (OpenMPI's runtime is not instrumented and
# reports its own allocations as leaks); see docs/validation.md. ASan's quarantine is 16 MiB, not
# 256: the memory budgets subtract the resident set, and freed blocks held in a large quarantine
# count as resident (cli_hardening_budgets' lowered-parallelism run was refused with 263 MiB).
SANITIZE_BUILD ?= build-sanitize
test-sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Release -DPLUMAGE_SANITIZE=ON -DPLUMAGE_FUZZ=OFF -DPLUMAGE_PYTHON=OFF \
	  > $(SANITIZE_BUILD).configure.log 2>&1 || (cat $(SANITIZE_BUILD).configure.log; exit 1)
	@rm -f $(SANITIZE_BUILD).configure.log
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && ASAN_OPTIONS=detect_leaks=1:quarantine_size_mb=16 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -LE validation -E '^cli_characterize_mpi$$'

clean:
	rm -rf $(BUILD)

# plumage: the two-command setup.
#   make demo   install missing packages, build, render the default scene (build/demo/demo.png)
#   make test   install missing packages, build, run the default test suite (ctest)
# Also: make build, make validate (slow validations, ctest label `validation`), make bench.

BUILD ?= build
JOBS  ?= $(shell nproc)
PLUMAGE = $(BUILD)/bin/plumage
DEMO_OUT = $(BUILD)/demo

.PHONY: all deps configure build demo test validate bench clean

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

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE validation

validate: build
	cd $(BUILD) && ctest --output-on-failure -L validation

bench: build
	$(PLUMAGE) bench multilayer --record docs/benchmarks.md
	$(PLUMAGE) bench simulate --record docs/benchmarks.md
	$(PLUMAGE) bench ladder --record docs/benchmarks.md --chart-copy docs/img/ladder.png

clean:
	rm -rf $(BUILD)

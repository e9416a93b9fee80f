# plumage: the two-command setup.
#   make demo   install missing packages, build, run the main job on the default scene
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

# The main job on the embedded default: reflectance spectra of every species' local layer stack.
demo: build
	$(PLUMAGE) spectra configs/species/*.yaml --lambda-nm 400:700:5 --theta-deg 0,30,60 \
	  --csv $(DEMO_OUT)/spectra.csv --plot $(DEMO_OUT)/spectra.png
	@echo "demo: wrote $(DEMO_OUT)/spectra.png and $(DEMO_OUT)/spectra.csv"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE validation

validate: build
	cd $(BUILD) && ctest --output-on-failure -L validation

bench: build
	$(PLUMAGE) bench multilayer --record docs/benchmarks.md

clean:
	rm -rf $(BUILD)

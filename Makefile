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

# The main job on the embedded default: the far-field reflection pattern of rock-dove barbules
# (geometry -> local multilayer reflection -> Eq. 2 currents -> far field, 10 instances, 21
# wavelengths, paper Fig. 7 style), and the reflectance spectra of every species' mean stack.
demo: build
	$(PLUMAGE) simulate configs/species/rockdove.yaml --lambda-nm 400:700:15 --instances 10 \
	  --theta-deg 0 --phi-deg 0 --out $(DEMO_OUT)/rockdove.ffs --csv $(DEMO_OUT)/rockdove-pattern.csv \
	  --pattern $(DEMO_OUT)/rockdove-pattern.png
	$(PLUMAGE) spectra configs/species/*.yaml --lambda-nm 400:700:5 --theta-deg 0,30,60 \
	  --csv $(DEMO_OUT)/spectra.csv --plot $(DEMO_OUT)/spectra.png
	@echo "demo: wrote $(DEMO_OUT)/rockdove-pattern.png, $(DEMO_OUT)/spectra.png (and .csv, .ffs beside them)"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE validation

validate: build
	cd $(BUILD) && ctest --output-on-failure -L validation

bench: build
	$(PLUMAGE) bench multilayer --record docs/benchmarks.md
	$(PLUMAGE) bench simulate --record docs/benchmarks.md

clean:
	rm -rf $(BUILD)

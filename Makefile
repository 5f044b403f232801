# povray-fc: build POV-Ray 3.7.0.10 from Debian's source package with our patch
# series and our frame-coherence library, the way Debian builds it.
#
#   make deps   install every Debian package we need (root, idempotent)
#   make        build build/bin/povray-fc (and later the coordinator)
#   make test   build, then run the unit tests and patch checks, then the integration tests
#   make demo   render a short animation into out/
#   make clean  remove build/ and out/ (keeps the downloaded source cache)

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := all
MAKEFLAGS += --no-builtin-rules

TOP       := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
BUILD     := $(TOP)/build
STAMPS    := $(BUILD)/stamps
BIN       := $(BUILD)/bin
JOBS      ?= $(shell nproc)

# Debian's source package, fetched once into a cache outside the tracked tree.
POV_DEB_VERSION := 1:3.7.0.10-2
POV_UPSTREAM    := 3.7.0.10
SRC_CACHE ?= $(HOME)/.cache/povray-fc/debian-source
POV_DSC   := $(SRC_CACHE)/povray_3.7.0.10-2.dsc
POV_TREE  := $(BUILD)/povray

# Our own libraries (CMakeLists.txt): the fc engine (povray-fc/) and the speed-ups that are
# not frame coherence (speedups/), built with CMake before POV-Ray, unit-tested with ctest.
LIB_BUILD := $(BUILD)/libs
FC_LIB    := $(LIB_BUILD)/povray-fc/libpovrayfc.a
FC_MASK_PLUGIN := $(LIB_BUILD)/povray-fc/povrayfc-mask.so
SPEEDUPS_LIB := $(LIB_BUILD)/speedups/libspeedups.a
# SDL loaded on demand (speedups/sdl_on_demand.c): linked whole and before POV-Ray's -lSDL,
# so the linker's --as-needed (gcc's default here) drops libSDL from the binary.
SPEEDUPS_SDL_LIB := $(LIB_BUILD)/speedups/libspeedups-sdl.a
LIB_SOURCES := $(TOP)/CMakeLists.txt $(shell find $(TOP)/povray-fc $(TOP)/speedups $(TOP)/frame-channel -type f \( -name '*.cpp' -o -name '*.c' -o -name '*.h' -o -name 'CMakeLists.txt' \) 2>/dev/null)

PATCHES   := $(TOP)/patches/series $(wildcard $(TOP)/patches/*.patch)
# Files our patches add to POV-Ray: unix/prebuild.sh lists the sources in the
# Makefiles, so a new file must re-run it (and configure) once.
PATCH_NEW_FILES := $(shell awk '/^--- \/dev\/null/ { getline; print $$2 }' $(TOP)/patches/*.patch 2>/dev/null)

# ccache: one cache for every clone. base_dir makes paths relative and nohashdir
# drops the working directory from -g builds, so a fresh clone (CI) hits the cache.
export CCACHE_DIR      ?= $(HOME)/.ccache
export CCACHE_BASEDIR  := $(TOP)
export CCACHE_NOHASHDIR := 1
export CCACHE_MAXSIZE  ?= 5G
# ccache's compiler wrappers: configure then records the plain compiler name
# (POV-Ray prints it in its banner) while every compile still goes through ccache.
CCACHE_PATH := /usr/lib/ccache

# Debian's flags (debian/rules: hardening=+all, then -O3, no -ffast-math).
# -ffile-prefix-map is dropped: it only names this checkout's path in debug info,
# and keeping it would defeat ccache across clones.
DEB_FLAGS  = DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get
strip_map  = $(filter-out -ffile-prefix-map=%,$(1))
POV_CXXFLAGS  := $(call strip_map,$(shell $(DEB_FLAGS) CXXFLAGS 2>/dev/null)) -O3
# Our headers: the engine's as "povrayfc/NAME.h", the other folders' as "FOLDER/NAME.h".
POV_CPPFLAGS  := $(shell $(DEB_FLAGS) CPPFLAGS 2>/dev/null) -I$(TOP)/povray-fc/include -I$(TOP)
POV_LDFLAGS   := $(shell $(DEB_FLAGS) LDFLAGS 2>/dev/null)
COMPILED_BY   := povray-fc (frame-coherent POV-Ray, built from Debian povray $(POV_DEB_VERSION))

PYTHON := /usr/bin/python3

.PHONY: all deps test fast-test unit-test patch-check results-check integration-test demo clean distclean
.DELETE_ON_ERROR:

all: $(BIN)/povray-fc $(BIN)/povrayfc-mask.so coordinator

# The PVM master and slave (coordinator/): fc-master and fc-slave in $(BIN).
include $(TOP)/coordinator/coordinator.mk
coordinator: | deps

# Our code that includes POV-Ray's headers is compiled as POV-Ray compiles its vfe/ front end:
# with that directory's configured compile command (automake's CXXCOMPILE: its defines,
# include paths and flags, config.h), run there. $(call pov_compile,SOURCE,OBJECT)
pov_compile = PATH=$(CCACHE_PATH):$$PATH $(MAKE) -s --no-print-directory -C $(POV_TREE)/vfe \
  --eval='our-object: ; $$(CXXCOMPILE) -c -o $(2) $(1)' our-object

# The renderer's frame channel and frame control (frame-channel/): libframechannel.a.
include $(TOP)/frame-channel/frame-channel.mk

# Frame coherence's code that reads POV-Ray's objects (fc-scene/): libfcscene.a.
include $(TOP)/fc-scene/fc-scene.mk

# fc-image-writer (image-writer/), fc-master's helper that links POV-Ray.
include $(TOP)/image-writer/image-writer.mk

# Checks in a fraction of a second when everything is installed, so the build
# targets run it first: on a fresh machine `make demo` or `make test` is all it takes.
deps:
	@$(TOP)/scripts/install-deps.sh

# --- Debian source -----------------------------------------------------------

$(POV_DSC): | deps
	@command -v dpkg-source >/dev/null || { echo "make: dpkg-source missing: run 'make deps' first" >&2; exit 1; }
	mkdir -p $(SRC_CACHE)
	cd $(SRC_CACHE) && apt-get source --download-only povray=$(POV_DEB_VERSION) \
	  || { echo "make: 'apt-get source povray' failed: run 'make deps' (adds the deb-src entry)" >&2; exit 1; }

# Unpack with Debian's own patches applied, then prepare it as debian/rules does.
$(STAMPS)/unpacked: $(POV_DSC)
	rm -rf $(POV_TREE) $(STAMPS)/patched $(STAMPS)/configured
	mkdir -p $(STAMPS)
	dpkg-source --no-check -x $(POV_DSC) $(POV_TREE) >/dev/null
	cd $(POV_TREE)/unix/config && for ax in *.m4; do \
	  if [ ! -h "$$ax" ] && [ -f "/usr/share/aclocal/$$ax" ]; then mv "$$ax" "$$ax.dist"; ln -s "/usr/share/aclocal/$$ax"; fi; done
	mv $(POV_TREE)/libraries $(POV_TREE)/libraries.donotuse
	touch $@

# Our series goes on top of Debian's with quilt. Re-applying after a patch change
# pops everything first; ccache turns the resulting recompiles into cache hits.
$(STAMPS)/patched: $(STAMPS)/unpacked $(PATCHES)
	cd $(POV_TREE) && export QUILT_PATCHES=$(TOP)/patches QUILT_PC=.pc-povray-fc && \
	  { [ ! -d .pc-povray-fc ] || quilt pop -a -q -f >/dev/null || [ $$? = 2 ]; } && \
	  { quilt push -a -q >/dev/null || [ $$? = 2 ]; }
	touch $@

# Flags (and added files) that, when changed, must re-run prebuild and configure.
$(STAMPS)/configure-args: FORCE | deps
	@mkdir -p $(STAMPS)
	@echo 'g++ via $(CCACHE_PATH) | $(POV_CXXFLAGS) | $(POV_CPPFLAGS) | $(POV_LDFLAGS) | $(FC_LIB) $(SPEEDUPS_LIB) | $(SPEEDUPS_SDL_LIB) | $(COMPILED_BY) | $(PATCH_NEW_FILES)' > $@.new
	@if cmp -s $@.new $@; then rm $@.new; else mv $@.new $@; fi

# Configure once per set of flags. Our patches never touch the build system (our
# code is a separate library), so a patch change does not re-run configure.
# configure links its test programs with LIBS, so our library must exist first.
$(STAMPS)/configured: $(STAMPS)/unpacked $(STAMPS)/configure-args | $(STAMPS)/patched $(FC_LIB) $(SPEEDUPS_LIB) $(SPEEDUPS_SDL_LIB)
	cd $(POV_TREE)/unix && ./prebuild.sh >$(BUILD)/prebuild.log 2>&1 \
	  || { echo "make: unix/prebuild.sh failed, see $(BUILD)/prebuild.log" >&2; exit 1; }
	cd $(POV_TREE) && PATH=$(CCACHE_PATH):$$PATH ./configure --prefix=/usr --sysconfdir=/etc \
	  --disable-optimiz --disable-strip \
	  --with-boost-thread=boost_thread \
	  CC=gcc CXX=g++ \
	  COMPILED_BY="$(COMPILED_BY)" \
	  CXXFLAGS="$(POV_CXXFLAGS)" CPPFLAGS="$(POV_CPPFLAGS)" LDFLAGS="$(POV_LDFLAGS) -Wl,--whole-archive $(SPEEDUPS_SDL_LIB) -Wl,--no-whole-archive" \
	  LIBS="$(FC_LIB) $(SPEEDUPS_LIB)" >$(BUILD)/configure.log 2>&1 \
	  || { echo "make: configure failed, see $(BUILD)/configure.log" >&2; exit 1; }
	touch $@

# --- our libraries -----------------------------------------------------------

$(LIB_BUILD)/CMakeCache.txt: $(TOP)/CMakeLists.txt | deps
	cmake -S $(TOP) -B $(LIB_BUILD) -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
	  -DCMAKE_CXX_FLAGS="$(POV_CXXFLAGS) $(filter-out -I%,$(POV_CPPFLAGS))" >/dev/null

# One CMake build: its targets share the build directory, so they are built in turn.
$(FC_LIB): $(LIB_BUILD)/CMakeCache.txt $(LIB_SOURCES)
	cmake --build $(LIB_BUILD) -j$(JOBS) --target povrayfc
	touch $@

$(SPEEDUPS_LIB): $(LIB_BUILD)/CMakeCache.txt $(LIB_SOURCES) | $(FC_LIB)
	cmake --build $(LIB_BUILD) -j$(JOBS) --target speedups
	touch $@

$(SPEEDUPS_SDL_LIB): $(LIB_BUILD)/CMakeCache.txt $(LIB_SOURCES) | $(SPEEDUPS_LIB)
	cmake --build $(LIB_BUILD) -j$(JOBS) --target speedups-sdl
	touch $@

# Frame_Coherence_Mask's writer, loaded from beside the binary.
$(BIN)/povrayfc-mask.so: $(LIB_BUILD)/CMakeCache.txt $(LIB_SOURCES) | $(SPEEDUPS_SDL_LIB)
	cmake --build $(LIB_BUILD) -j$(JOBS) --target povrayfc-mask
	mkdir -p $(BIN) && cp $(FC_MASK_PLUGIN) $@

# --- the binary --------------------------------------------------------------

# POV-Ray's Makefiles do not know our libraries: relink when one is newer. The frame
# channel's and fc-scene's libraries need the configured tree, so configure cannot link its
# test programs with them: they join the configured LIBS here (fc-scene before the engine
# it calls, which the configured LIBS name).
$(BIN)/povray-fc: $(STAMPS)/patched $(STAMPS)/configured $(FC_LIB) $(SPEEDUPS_LIB) $(SPEEDUPS_SDL_LIB) \
  $(FRAME_CHANNEL_LIB) $(FC_SCENE_LIB) FORCE
	@for lib in $(FC_LIB) $(SPEEDUPS_LIB) $(SPEEDUPS_SDL_LIB) $(FRAME_CHANNEL_LIB) $(FC_SCENE_LIB); do \
	  if [ -e $(POV_TREE)/unix/povray ] && [ $$lib -nt $(POV_TREE)/unix/povray ]; then rm $(POV_TREE)/unix/povray; fi; done
	PATH=$(CCACHE_PATH):$$PATH $(MAKE) -C $(POV_TREE) -j$(JOBS) \
	  LIBS="$(FRAME_CHANNEL_LIB) $(FC_SCENE_LIB) $$(sed -n 's/^LIBS = //p' $(POV_TREE)/unix/Makefile)" >$(BUILD)/povray-make.log 2>&1 \
	  || { tail -30 $(BUILD)/povray-make.log >&2; echo "make: POV-Ray build failed, see $(BUILD)/povray-make.log" >&2; exit 1; }
	mkdir -p $(BIN)
	if ! cmp -s $(POV_TREE)/unix/povray $@; then cp $(POV_TREE)/unix/povray $@.tmp && mv $@.tmp $@; fi

FORCE:

# --- tests and demo ----------------------------------------------------------

# The fast tier first (unit tests, the patch series' checks and the README's results table:
# seconds), then the integration tests (minutes).
test: fast-test
	$(MAKE) --no-print-directory integration-test

fast-test: unit-test patch-check results-check

# The README's results table says what the measurement scripts wrote into docs/
# (scripts/results-table), and its check fails on a table that does not.
results-check:
	$(PYTHON) $(TOP)/scripts/results-table --check
	cd $(TOP) && $(PYTHON) -m pytest -q -p no:cacheprovider tests/test_results_table.py

# Every patch a DEP-3 header and under 150 lines (scripts/check-patches).
patch-check:
	$(PYTHON) $(TOP)/scripts/check-patches

# Every GoogleTest unit, by ctest: our libraries' (the engine, the speed-ups, the frame record
# and control lines) in $(LIB_BUILD), then the coordinator's in its own CMake build.
unit-test: $(LIB_BUILD)/CMakeCache.txt | deps
	cmake --build $(LIB_BUILD) -j$(JOBS)
	cd $(LIB_BUILD) && ctest --output-on-failure
	$(MAKE) --no-print-directory coordinator-unit-test

integration-test: all
	cd $(TOP) && $(PYTHON) -m pytest -q -p no:cacheprovider tests

demo: all
	$(TOP)/scripts/demo.sh

clean:
	rm -rf $(BUILD) $(TOP)/out

distclean: clean
	rm -rf $(SRC_CACHE)
